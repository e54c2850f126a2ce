// The model pipeline of one robot mode: generate (or resume) the dataset,
// fit the cost model and feasibility classifier, export the header.
#ifndef HYLO_TRAINER_PIPELINE_HPP
#define HYLO_TRAINER_PIPELINE_HPP

#include <string>

#include "hylo/version.h"
#include "trainer/dataset.hpp"
#include "trainer/params.hpp"

namespace hylo::trainer {

// hylo/version.h: --version and every exported model's provenance.
constexpr const char *kHyloVersion = HYLO_VERSION;

struct PipelineOptions {
	GenOptions gen;
	std::string models_dir = "onboard/models";
	int neighbours = 8;   // --stage repair, --solve: warm starts (RepairOptions, Memory)
	bool solutions = false;   // gen: also keep each row's solution for the repair (--solutions)
	std::string compare;      // fit: another header of this robot and mode, scored on the same held-out rows
};

// A draw's sample count, its supplement's end (dataset.hpp): ground and
// marine 8,640 (draw 4), 14,400 (draw 3), 11,520 (draws 1 and 2, the
// paper's); flight 17,016; di 4,000 (draw 2), 2,000 (draw 1).
uint64_t default_samples(hylo_mode mode, int draws);

// --samples when none is given: the draw's count, or the rows of the
// dataset in opt.out_dir when it holds more (a dataset extended past its
// draw's count, like Ambot marine's, is repaired and fitted whole).
uint64_t default_samples(const GenOptions &opt);

// Runs stage "gen", "repair", "fit", "export", "all" (gen, fit, export) or
// "gather"; returns the exit code. "repair" repairs the dataset's first
// samples rows (trainer/repair.hpp). "gather" (gen.shards = N) checks and
// merges the N shards (trainer/gather.hpp): exit 1 when some are to be
// resubmitted, 2 when some are not this stream's. A sharded run (N > 1)
// only generates: other stages throw std::invalid_argument.
// "fit" writes <out>/<robot>_<mode>.h (the fitted model) and
// <out>/<mode>.fit.json, and with compare set also prints the held-out
// errors of that header's model on the same rows; "export" reads that header, adds the envelope
// (ground, marine, flight; trainer/envelope.hpp) and writes the result into
// models_dir. "region" writes the trained region (trained_region,
// trainer/dataset.hpp), checked against the dataset rows the model was
// fitted on, into the header in models_dir, changing nothing else.
// Nothing is written on bad data.
int run_pipeline(const RobotParams &robot, const PipelineOptions &opt, const std::string &stage);

}  // namespace hylo::trainer

#endif
