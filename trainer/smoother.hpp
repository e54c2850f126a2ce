// Final path smoothing (paper section III.A.3): a plan's waypoints are split
// into phases at its guard points, and one multi-phase collocation problem
// with that mode sequence is solved, the switch points free to slide along
// their guards (a straight piece of the shoreline fitted to the map, or the
// drivable stretch of the takeoff or landing platform), switching costs
// included. The smoothed trajectory is the optimum from the plan's guess.
//
// The map's domain is enforced at the switch points only: inside a phase the
// trajectory is bounded by the mode's state bounds, not by obstacles.
#ifndef HYLO_TRAINER_SMOOTHER_HPP
#define HYLO_TRAINER_SMOOTHER_HPP

#include <cstdint>
#include <string>
#include <vector>

#include "trainer/collocation.hpp"
#include "trainer/params.hpp"
#include "trainer/switching.hpp"

namespace hylo::trainer {

// Modes as numbered in goal_t (MODE_*); "" for an unknown number.
std::string mode_name(int goal_mode);
int mode_number(const std::string &mode);

// The parts of a map_t the smoother reads.
struct TerrainGrid {
	int nx = 0, ny = 0;
	double resolution_m = 1, origin_x_m = 0, origin_y_m = 0;
	std::vector<int8_t> terrain;   // map_t TERRAIN_*: 0 obstacle, 1 ground, 2 water
	std::vector<float> height_m;
};

struct Waypoint {
	int mode = 0;                  // goal_t MODE_*
	double state[6] = {};          // sampled coordinates (models.md section 7)
	bool guard = false;
};

struct SmoothOptions {
	int segments_per_edge = 6;     // collocation segments per plan edge of a phase
	int min_segments = 10, max_segments = 48;
	double guard_half_length_m = 6; // how far a switch point may slide each way
};

// The multi-phase problem of a plan. Throws std::invalid_argument for a plan
// that cannot be smoothed (fewer than two waypoints, a switch without a guard
// pair, a mode of another robot, a switch point off the map).
MultiPhaseProblem smoothing_problem(const RobotParams &robot, const std::vector<Waypoint> &plan,
				    const TerrainGrid &map, const TakeoffLanding &costs,
				    const SmoothOptions &opt = {});

// Solver options of the smoother: an open-loop replay of a whole phase (tens
// of metres) drifts with its length, so a phase's replayed end state may be
// 0.05 off (scaled: metres, m/s, rad) where a training edge may be 0.02 off.
SolveOptions smoothing_solve_options();

// Exact cost of the plan's own path: every edge solved on its own as a
// single-phase problem, plus the switching costs. Infinity if an edge fails.
double graph_path_cost(const RobotParams &robot, const std::vector<Waypoint> &plan,
		       const TakeoffLanding &costs, const SolveOptions &opt);

}  // namespace hylo::trainer

#endif
