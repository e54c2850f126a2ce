// The gather step of a sharded dataset (`trainer --stage gather --shards N`):
// checks the N files `--shard K/N` wrote and merges them, in order, into the
// unsharded dataset with its .meta, byte for byte what one unsharded run
// writes. A shard that is missing, short or ends in a torn row is named for
// resubmission (its task resumes it); one made for another stream or under
// other settings, or with rows that are not its own, must be moved away first.
#ifndef HYLO_TRAINER_GATHER_HPP
#define HYLO_TRAINER_GATHER_HPP

#include <cstdint>
#include <string>
#include <vector>

#include "trainer/dataset.hpp"
#include "trainer/params.hpp"

namespace hylo::trainer {

struct ShardCheck {
	enum State { ok, missing, incomplete, torn, foreign };
	int shard = 0;
	State state = ok;
	uint64_t rows = 0, want = 0;   // complete rows found, rows the shard has
	std::string path, detail;      // detail: why it is not ok
};

struct GatherReport {
	std::vector<ShardCheck> shards;
	std::vector<int> resubmit;     // missing, incomplete or torn: their tasks resume them
	std::vector<int> foreign;      // to move away (and then resubmit)
	std::string path;              // the merged dataset
	uint64_t rows = 0;             // complete rows found (all of them when merged)
	bool merged = false;           // path holds every row
	bool unchanged = false;        // path held them already; shards not read
};

// opt is the generation's options with shards = N (shard is ignored). When
// the unsharded dataset already holds opt.samples rows of this stream (under
// these settings or, as generation accepts, others) it is left as it is and
// no shard is read. Otherwise every shard is checked against the .meta this
// trainer would write for it; when all are complete the unsharded .meta and
// then the dataset are written (each atomically: a temporary file, fsync'd,
// renamed). An existing unsharded dataset is replaced only if it is of these
// settings and a prefix of the merged one, else std::invalid_argument (before
// any shard is read when its settings differ).
GatherReport gather(const RobotParams &robot, const GenOptions &opt);

// One line per shard and what to do, as `trainer --stage gather` prints it.
std::string gather_text(const GatherReport &r);

}  // namespace hylo::trainer

#endif
