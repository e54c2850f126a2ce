// Training datasets: BVP pairs drawn from the robot file's sampling ranges,
// solved (collocation + CVODE replay) by worker processes, written as CSV.
//
// Sample i of a stream depends only on (seed, i), so the rows are the same
// for any number of workers, and `--shard K/N` (the K-th contiguous slice of
// the indices) files concatenate in order to the unsharded file byte for
// byte. Rows are appended in index order a whole chunk at a time (fsync'd);
// a re-run resumes after the last complete row, dropping a torn tail.
#ifndef HYLO_TRAINER_DATASET_HPP
#define HYLO_TRAINER_DATASET_HPP

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "trainer/collocation.hpp"
#include "trainer/files.hpp"
#include "trainer/params.hpp"

namespace hylo::trainer {

// The solver's options for training pairs (and `trainer --solve`, so that it
// reproduces a row): every start is refined (refine_within infinite: pruning
// by the coarse cost lost basins, docs/decisions.md, "Labels that are the
// best optimum found"). Ground and marine pairs also get the strategy guesses
// (solve_bvp_strategies: backing up, facing the goal, and issue #35's three).
inline SolveOptions training_solve_options()
{
	SolveOptions o;
	o.strategy_starts = true;
	return o;
}

struct GenOptions {
	hylo_mode mode = HYLO_MODE_NONE;
	std::string out_dir;
	uint64_t samples = 0, seed = 1;
	int jobs = 1;
	int shard = 1, shards = 1;         // K of N
	int chunk = 32;                    // rows per atomic append
	SolveOptions solve = training_solve_options();
	// Non-empty: a dataset of the same stream labelled from straight-line
	// starts alone; its rows are taken as those starts' results and only the
	// other starts are solved (solve_bvp_strategies). Rows past its end are
	// solved in full.
	std::string relabel;
	bool progress = true;
	// How pairs are drawn (draw_pair); 0: the newest for the mode
	// (draws_for). Ground and marine 1 is the committed datasets' draw.
	int draws = 0;
};

// A sample whose solve threw (a bug, an exhausted resource, Ipopt failing to
// start) has no outcome: its row keeps the draw and a status beginning with
// this, so that a run goes on past it, and fit leaves it out (it is neither a
// cost nor an infeasible pair for the classifier).
inline constexpr const char *kErrorStatus = "error: ";
inline bool is_error_status(const std::string &status)
{
	return status.compare(0, 7, kErrorStatus) == 0;
}

struct GenSummary {
	uint64_t done = 0, resumed_from = 0, converged = 0, rejected = 0;
	uint64_t errors = 0;   // rows whose solve threw (is_error_status)
	double seconds = 0;
	std::string path;
};

// What generation also writes per row beside the dataset (the repair
// stage's solutions, repair.hpp): line() in the row's worker process, from
// its pair and solution; append() with the chunk's lines, first index
// first, before the chunk's rows go to the dataset (so it never has fewer
// rows than the dataset).
struct RowSink {
	virtual ~RowSink() = default;
	virtual std::string line(uint64_t i, const double *x1s, const double *x2s, const Solution &s) const = 0;
	virtual void append(uint64_t first, const std::vector<std::string> &lines) = 0;
};

// Relative coordinates of docs/models.md section 7 for a pair of sampled states,
// the columns f0, f1, ... of a dataset (hylo_relative, onboard/features.h).
std::vector<double> relative_coords(hylo_mode mode, const double *x1s, const double *x2s);

// The model's features of relative coordinates r (hylo_features_of_relative):
// what the fit and the onboard planner see.
std::vector<double> features_of_relative(hylo_mode mode, const std::vector<double> &r);

// Number of features of mode (throws std::invalid_argument for no mode).
int feature_count(hylo_mode mode);

// Sign flips of the features that leave a mode's optimal cost unchanged, one
// vector of +-1 per flip (the fit trains on each sample's mirror images too).
// Flight: the reflection across the displacement's heading (in world axes
// the reflections x -> -x and y -> -y are exact to 1e-15 in the solver; turns
// about z are not, by up to 0.1%: ZYX Euler angles).
std::vector<std::vector<double>> feature_symmetries(hylo_mode mode);

// The cost model's feature weights for mode (FitOptions::feature_weights;
// empty: none). Marine: 2 on arc, the distance from the one circular arc
// that joins the poses (hylo/features.h): paddling at speed, the cost is a
// narrow valley along it (docs/decisions.md, "The arc feature's weight").
std::vector<double> feature_weights(hylo_mode mode);

// The draw a run uses: requested (1 to 4; 0: the newest, 4) for ground and
// marine, 2 for flight, 1 or 2 (newest 2) for the double integrator.
// Throws std::invalid_argument for a draw the mode does not have.
int draws_for(hylo_mode mode, int requested);

// A draw's supplement: the pairs from index `from` on are drawn where the
// planner asks and the first draw is thin, so a dataset of the draw before,
// up to `from` rows, is a prefix of this one, pair for pair. Ground and
// marine, draw 3: cruise pairs from the paper's sample count on; draw 4:
// the same number of cruise pairs from half of it, then draw 2's pairs
// again (closed); the double integrator, draw 2: short pairs. pairs = 0:
// the draw has none. A draw's default sample count is from + pairs.
struct Supplement {
	uint64_t from = 0, pairs = 0;
	bool closed = false;   // pairs past from + pairs are the first draw's again
	bool holds(uint64_t i) const { return pairs > 0 && i >= from && (!closed || i < from + pairs); }
};
Supplement supplement(hylo_mode mode, int draws);

// Sample i's pair under draw `draws` (draws_for): x1s, x2s (the record's
// xs_dim each).
// - Ground and marine, draw 2: each speed is 0 with probability
//   kRestFraction, else uniform as in draw 1 (every start, goal and switch
//   point is at rest, and draw 1's uniform speeds never are).
// - Ground and marine, draw 3: draw 2's pairs, then (supplement) cruise
//   pairs: the goal on an arc from the start (bearing within pi/4, the
//   turn twice the bearing, half exactly, half within 0.3 rad), each speed
//   at rest with probability kRestFraction, at the top speed with
//   kTopFraction, else uniform.
// - Ground and marine, draw 4: draw 2's pairs but for the indices 5,760 to
//   8,639, cruise pairs drawn as draw 3's: the default 8,640 rows hold as
//   many cruise pairs as draw 3's 14,400, and a longer run adds draw 2's
//   pairs (14,400 rows: draw 3's mix).
// - Double integrator, draw 2: draw 1's pairs, then (supplement) short
//   pairs: the goal at a distance uniform on [0, kShortPairMax] in the phase
//   plane from a start drawn as draw 1's (the planner's edges are its
//   connection radius long, 0.3 on scenes/di.yaml; draw 1's are 0.7 on
//   average).
void draw_pair(const ModeParams &p, uint64_t seed, uint64_t i, double *x1s, double *x2s, int draws = 0);
inline constexpr double kRestFraction = 0.2, kTopFraction = 0.3, kShortPairMax = 0.5;

// The draw of the dataset already in opt.out_dir (its .meta's "draws:"
// line; none: 1), or 0 (the newest) when there is none.
int existing_draws(const GenOptions &opt);

// The whole rows of the dataset already in opt.out_dir (0 when there is
// none; a torn last row does not count).
uint64_t existing_rows(const GenOptions &opt);

// The sampled coordinates draw_pair bounds, beyond the displacement
// (max_distance_m) and the speed range: bit k of bounded set means
// coordinate k of both states of every pair lies in [min[k], max[k]]
// (hylo_svr_model's state_bounded, state_min, state_max). Ground and
// marine: vx; flight: vx, vy within the top speed, vz = 0 (level
// velocities); double integrator: p in the mode's half of [-1, 1], v.
// Positions and headings are not bounded (the features do not see where a
// pair is, and every heading and turn is drawn).
struct TrainedRegion {
	uint32_t bounded = 0;
	std::array<double, 6> min{}, max{};
};
TrainedRegion trained_region(const ModeParams &p);

// The CSV column names, in order.
std::vector<std::string> csv_columns(hylo_mode mode);

// Index of the column called name in csv_columns(mode); throws
// std::invalid_argument if there is none.
size_t csv_column(hylo_mode mode, const std::string &name);

// The comma-separated fields of one CSV row.
std::vector<std::string> csv_fields(const std::string &row);

// One CSV row (without the newline) of fields that hold no comma; the
// header line is csv_join(csv_columns(mode)).
std::string csv_join(const std::vector<std::string> &fields);

// One CSV row (without the newline) for sample i.
std::string csv_row(hylo_mode mode, uint64_t i, const double *x1s, const double *x2s,
		    const Solution &s);

// Generates (or resumes) the dataset file of opt; throws std::runtime_error
// with a clear message on I/O errors or a mismatching existing file. With
// `also`, each row's line goes to it too (RowSink).
GenSummary generate(const RobotParams &robot, const GenOptions &opt, RowSink *also = nullptr);

// The dataset file a run with these options writes.
std::string dataset_path(const GenOptions &opt);

// Shared by generation, the repair stage (repair.hpp) and gather.
namespace internal {

// The .meta of a dataset generated with opt: the stream (robot, mode, seed,
// robot file, draws, shard) and what its labels depend on.
std::string meta_text(const RobotParams &robot, const GenOptions &opt);
// The value of a meta's "key: value" line ("" if it has none).
std::string meta_value(const std::string &meta, const std::string &key);
// The lines in which two metas differ, "old vs new; ...".
std::string meta_differences(const std::string &old_meta, const std::string &new_meta);
// Whether two metas describe the same stream of pairs, whatever labelled them.
bool same_stream(const std::string &a, const std::string &b);
// A pass over a dataset's rows after generation (trainer/repair.hpp): its
// word, the prefix of its .meta lines, their row count's key, and its
// in-progress files' suffix.
struct MetaPass {
	std::string name, prefix, rows_key, suffix;
};
inline const MetaPass kRepairPass{"repair", "repair_", "repaired_rows", ".repair"};
inline const MetaPass kRemeshPass{"remesh", "remesh_", "remeshed_rows", ".remesh"};
// A dataset's .meta without the passes' lines: the lines generation wrote.
std::string generated_lines(const std::string &meta);
// Where a file of rows after header resumes: the bytes to keep (the header
// and complete rows; a torn last row dropped) and how many rows they hold.
struct ResumePoint {
	size_t keep = 0;
	uint64_t rows = 0;
};
ResumePoint resume_point(const std::string &existing, const std::string &header);
// f(lo) ... f(hi - 1), the rows of samples lo to hi - 1, each solved in its
// own process (fork_chunks, jobs at a time); done(c, e, rows) gets the rows
// of samples [c, e), chunk at a time in index order, while the workers go on.
// Throws "the process <doing> sample I failed" for one that died.
void fork_sample_chunks(uint64_t lo, uint64_t hi, int jobs, int chunk,
			const std::function<std::string(uint64_t)> &f, const std::string &doing,
			const std::function<void(uint64_t, uint64_t, std::vector<std::string> &)> &done);

}  // namespace internal

}  // namespace hylo::trainer

#endif
