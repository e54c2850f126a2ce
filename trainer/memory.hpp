// A memory of motion: the solutions a dataset's rows reached, kept beside it
// in its sidecar <mode>.solutions.csv (one line per row: the row's result
// columns and its path, path_points full states uniformly in time; after a
// repair, a row whose label a neighbour's path lowered has that solution's),
// used as warm starts for other pairs of the mode. The repair stage warms each row
// with its nearest rows' paths (repair.hpp); trainer --solve warms a new
// pair with the paths of the dataset's rows nearest to it (Memory), so that
// a solve reaches the basins its labels reached.
#ifndef HYLO_TRAINER_MEMORY_HPP
#define HYLO_TRAINER_MEMORY_HPP

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "trainer/params.hpp"
#include "trainer/problem.hpp"
#include "trainer/solution.hpp"

namespace hylo::trainer {

// One sidecar line: a result and, converged, its path.
struct StoredSolution {
	Solution s;
	std::vector<std::vector<double>> path;   // path_points full states
};

// Whether b is converged and a better result than a: a has none, or b is
// cheaper by more than 1e-6 relative. Starts that reach the same optimum
// agree to about 1e-8 (Ipopt's tol); such a tie keeps a, so a label or a
// --solve result changes only for another basin, not in its last bits.
bool improves_on(const Solution &b, const Solution &a);

// The sidecar's header fields for paths of `points` states.
std::vector<std::string> sidecar_columns(hylo_mode mode, int points);

// Sample i's sidecar line: the result columns of its dataset row, then its
// path from a to b (sampled coordinates) at `points` uniform times (zeros
// when it did not converge).
std::string solution_line(const RobotParams &robot, hylo_mode mode, int points, uint64_t i, const double *a,
			  const double *b, const Solution &s);

// A sidecar line of sample i back. Throws std::runtime_error naming `where`
// unless it is one, with `points` states.
StoredSolution parse_solution_line(hylo_mode mode, const std::string &line, uint64_t i, int points,
				   const std::string &where);

// A dataset row's result columns (csv_columns' cost_j ... replay_cost_j,
// from column `first`) as a Solution. Throws std::invalid_argument naming
// `where`.
Solution row_result(const std::vector<std::string> &fields, size_t first, const std::string &where);

// A stored path (converged) as a guess for the BVP a -> b (full states),
// moved to run between them (transplanted_guess).
Guess stored_guess(hylo_mode mode, const StoredSolution &stored, const std::vector<double> &a,
		   const std::vector<double> &b, int points);

// For each row, the k nearest other rows with a converged solution, in the
// sampled coordinates (x1 then x2), each scaled by its range over the rows
// (a coordinate with none left out); ties by index.
std::vector<std::vector<uint64_t>> nearest_rows(const std::vector<std::vector<double>> &coords,
						const std::vector<StoredSolution> &sol, int k);

// A dataset directory's memory of one mode: <dir>/<mode>.csv and its
// sidecar, with their .meta files, of the same stream and of this robot
// file. The sidecar's lines follow the dataset's rows, each naming the same
// sample (any of the stream's rows, in any order). Rows the sidecar has not
// reached yet (a regeneration in progress) and rows that did not converge
// are left out.
class Memory {
public:
	// Throws std::invalid_argument naming the file and what is wrong: a
	// missing file, another robot's, mode's or robot file's, a dataset and
	// sidecar of different streams, a malformed line.
	Memory(const RobotParams &robot, hylo_mode mode, const std::string &dir);

	size_t rows() const { return coords_.size(); }
	const std::string &sidecar() const { return sidecar_; }

	// Guesses for the BVP x1s -> x2s (sampled coordinates, in any frame the
	// mode is invariant to: planar pairs are turned and moved into the start's
	// frame, spatial ones moved, as the dataset draws them): the paths of the
	// k rows nearest to it, scaled as nearest_rows scales, moved back into its
	// frame and between its states.
	std::vector<Guess> guesses(const RobotParams &robot, const double *x1s, const double *x2s, int k) const;

private:
	hylo_mode mode_;
	int points_ = 0;
	std::string sidecar_;
	std::vector<std::vector<double>> coords_;   // x1s then x2s, in the dataset's frame
	std::vector<StoredSolution> sol_;
	std::vector<double> scale_;
};

// The memory --memory DIR names for robot_name's mode: "" the committed
// dataset trainer/datasets/<robot_name> where it holds the mode's sidecar
// (else none), "none" none, else DIR's (throws as Memory does). Null: none.
std::unique_ptr<Memory> open_memory(const std::string &dir, const std::string &robot_name, const RobotParams &robot,
				    hylo_mode mode);

// The pair x1s -> x2s solved from its own starts and, with a memory, from
// the paths of its k nearest rows too: the cheaper (improves_on: a tie
// keeps the pair's own), with the starts and seconds of both. What
// trainer --solve and bench_accuracy call the exact cost. memory_starts,
// when given, is set to the number of memory starts.
Solution solve_remembered(hylo_mode mode, const RobotParams &robot, const double *x1s, const double *x2s,
			  const SolveOptions &opt, const Memory *memory, int k, size_t *memory_starts = nullptr);

}  // namespace hylo::trainer

#endif
