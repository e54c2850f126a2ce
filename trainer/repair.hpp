// The repair stage (trainer --stage repair, issue #35): labels that are the
// best optimum found, not the first. Each of a dataset's first N rows is
// solved again from the solutions of its K nearest rows (the "memory of
// motion" warm start of learned trajectory optimization: a neighbour's path,
// moved to run between this row's states, transplanted_guess), and its label
// becomes the cheapest accepted solution of the stored one, the current
// solver's and those warm starts'. A label is only ever lowered, and only by
// more than 1e-6 relative (less is a tie, Ipopt's tolerance), or a row that
// did not converge gets one; the rows are otherwise the input's bytes.
//
// The neighbours' solutions come from the dataset's sidecar,
// <out>/<mode>.solutions.csv (memory.hpp): each row's result and path
// (path_points states uniformly in time), written by gen --solutions as it
// labels, or here, for rows it lacks, by solving them again with the current
// solver (solve_bvp, training options). The repair reads only the sidecar as
// it was when it started (Jacobi: row i's warm starts do not depend on
// whether row j < i was repaired already), so the result does not depend on
// --jobs, on chunking or on an interruption. When it is done, the sidecar
// line of each row whose label a neighbour's path lowered becomes that
// solution, so the sidecar holds the paths of the labels (the memory
// trainer --solve starts from).
//
// Files in <out>: <mode>.csv (the dataset, at least N rows, its .meta of
// this stream), <mode>.solutions.csv(.meta) (the sidecar), <mode>.csv.repair
// (.meta) (the repaired rows while in progress, appended a chunk at a time,
// fsync'd; a re-run resumes) and <mode>.solutions.csv.repair (the new
// sidecar lines, each chunk's synced before its rows). When every row is
// done the sidecar, then the dataset, are replaced atomically (a temporary
// file renamed over each): the sidecar with the new lines in place; the
// dataset as the repaired rows, then the input's rows past N unchanged, and
// its .meta gets the repair's lines
// (repaired_rows, repair_neighbours, repair_path_points and the repairing
// solver's settings and numerics as repair_<line>), so a second repair
// with the same settings does nothing.
//
// The remesh pass (trainer --stage remesh; RepairOptions::remesh) is the
// same pass over the rows for another reason: a mode whose solver now
// accepts labels only on a finer mesh than a dataset's rows were accepted
// on (SolverHints::accept_segments; issue #35: 20 segments left labels up
// to 7% above the optimum). Each converged row on a coarser mesh is solved
// again from its own stored path (the sidecar as it stands: paths of
// another solver's settings are still warm starts), and the finer
// solution, where it converges, becomes its label and its sidecar line,
// cheaper or dearer (the finer mesh's cost is the better estimate); the
// other rows keep their bytes. Its files and lines: <mode>.csv.remesh,
// <mode>.solutions.csv.remesh, remeshed_rows and remesh_<line>, beside an
// earlier repair's, which stay.
//
// Generation extends a repaired dataset (its .meta keeps the repair's
// lines: they describe its first repaired_rows rows). A repair of more
// rows under the same settings then repairs only the rows past them, their
// neighbours among all N (the earlier rows keep their labels, their
// sidecar lines the earlier repair's paths), and the .meta lists the
// passes (repair_passes: 8640 17280). Under other settings every row is
// repaired again.
#ifndef HYLO_TRAINER_REPAIR_HPP
#define HYLO_TRAINER_REPAIR_HPP

#include <cstdint>
#include <string>

#include "trainer/dataset.hpp"
#include "trainer/params.hpp"

namespace hylo::trainer {

struct RepairOptions {
	// mode, out_dir, samples (N: the rows repaired, the first N), seed, jobs,
	// chunk, solve (the solver's options), progress.
	GenOptions gen;
	int neighbours = 8;      // K: warm starts per row
	int path_points = 21;    // states per stored path (a 20-segment coarse mesh's knots)
	bool remesh = false;     // the remesh pass (above) instead: no neighbours
};

struct RepairSummary {
	uint64_t rows = 0;             // N
	uint64_t kept = 0;             // the first rows, an earlier pass's (repaired_before)
	uint64_t solved_again = 0;     // sidecar rows solved by this run
	uint64_t repaired_now = 0;     // rows repaired by this run (the rest resumed)
	uint64_t lowered = 0;          // converged before and after, label lower by more than 0.5%
	uint64_t raised = 0;           // the same, higher by more than 0.5% (remesh only)
	uint64_t relabelled = 0;       // rows whose bytes changed
	uint64_t lowered_by_solver = 0;     // of those, by the current solver alone
	uint64_t lowered_by_neighbours = 0; // of those, by a neighbour's warm start
	uint64_t newly_converged = 0;  // rows without a label before that have one now
	uint64_t solutions_replaced = 0;   // sidecar lines now a neighbour's warm start's solution
					   // (remesh: the finer mesh's)
	double median_drop = 0, max_drop = 0;   // relative drops of the lowered rows
	bool already = false;          // the dataset's meta records this repair already: nothing done
	double solve_cpu_s = 0;        // CPU time of this run's sidecar solves (its worker processes)
	double warm_cpu_s = 0;         // and of its warm-started solves
	double seconds = 0;
	std::string path;
};

// Repairs (or remeshes) the first opt.gen.samples rows of <out>/<mode>.csv
// (see above).
// Throws std::invalid_argument for a missing or short dataset, another
// stream's, or a row that is not this stream's sample; std::runtime_error
// for I/O errors and for a sidecar or an in-progress repair made under other
// settings (naming the differing lines).
RepairSummary repair(const RobotParams &robot, const RepairOptions &opt);

// The sidecar's file for a run with these options.
std::string solutions_path(const GenOptions &opt);

// generate(), also writing each row's solution into the sidecar as it is
// solved (trainer --stage gen --solutions), so that a repair of the dataset
// solves only the warm starts: half the work of a repair that must solve
// every row again for its path. The sidecar is first brought up to the
// dataset's rows (solved again, as the repair would), then kept in step;
// an interrupted run resumes both. Throws as generate() does, and for a
// sharded run (std::invalid_argument).
GenSummary generate_with_solutions(const RobotParams &robot, const RepairOptions &opt);

}  // namespace hylo::trainer

#endif
