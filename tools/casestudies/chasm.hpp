// Case study 3's chasm scenes (scenes/chasm_*.yaml, the paper's Table I):
// where the walls are, the fixed mode sequences across them as plans for the
// smoother, and chasms of any width made from a committed one.
#ifndef HYLO_TOOLS_CASESTUDIES_CHASM_HPP
#define HYLO_TOOLS_CASESTUDIES_CHASM_HPP

#include <string>
#include <vector>

#include "tools/scene/scene.hpp"
#include "trainer/smoother.hpp"

namespace hylo::casestudies {

// A chasm scene along the line from start to goal: platform 1 up to the
// first wall at e1, the floor up to the second wall at e2, platform 2 after.
struct Chasm {
	double y = 0, x_start = 0, x_goal = 0, e1 = 0, e2 = 0, h_platform = 0, h_floor = 0, margin = 0;
};

// Throws std::runtime_error naming the file unless there are exactly two
// walls between start and goal along x. Switch points keep clearance_m (the
// robot's body and margin) from the walls' edges and a cell more: they lie
// in cells the corridors keep clear (margin).
Chasm chasm_of(const scene::Scene &sc, double clearance_m);

// The chasm scene sc made extra_m wider: floor columns inserted at the
// chasm's middle, the far platform and the goal moved along. For widths
// between the committed scenes (the crossover).
scene::Scene widened(const scene::Scene &sc, const Chasm &c, double extra_m);

// A fixed mode sequence (D drive, F fly) across the chasm as a plan for the
// smoother: D legs on platform 1 (first letter), platform 2 (last) or the
// floor (between flights); switch points placed `lambda` of the way from the
// wall they lead over (0: at the wall) to the leg's far end, every ground leg
// through waypoints at most 4 m apart at 2 m/s, every flight through
// waypoints at most 8 m apart at up to 8 m/s (3 m/s^2 from and to hover),
// high enough above the platforms. These are only the initial guess: the
// smoother lets every switch point slide along its whole platform or floor.
std::vector<trainer::Waypoint> sequence_plan(const Chasm &c, const std::string &seq, double lambda);

// "DFD": a plan's modes in order (D ground, F flight).
std::string letters(const std::vector<trainer::Waypoint> &plan);

}  // namespace hylo::casestudies

#endif
