// Case study 3's chasm scenes (scenes/chasm_*.yaml, the paper's Table I):
// where the walls are, the fixed mode sequences across them as plans for the
// smoother, and scenes nobody tuned on made from a committed one: a chasm of
// any width, or several chasms in a row.
#ifndef HYLO_TOOLS_CASESTUDIES_CHASM_HPP
#define HYLO_TOOLS_CASESTUDIES_CHASM_HPP

#include <cstddef>
#include <string>
#include <vector>

#include "tools/scene/scene.hpp"
#include "trainer/smoothing_problem.hpp"

namespace hylo::casestudies {

// A chasm scene along the line from start to goal (y constant): segments
// between walls (height steps over max_step_m). Segment 0 is the start
// platform (from x_start), then a floor, a platform, a floor, ..., the last
// the goal platform (up to x_goal): one chasm has segments platform, floor,
// platform; two chasms platform, floor1, mid1, floor2, platform.
struct Profile {
	double y = 0, x_start = 0, x_goal = 0;
	double margin = 0;             // switch points keep this from the walls [m]
	std::vector<double> walls;     // x of each wall, ascending; an even number
	std::vector<double> heights;   // each segment's surface height: walls.size() + 1

	size_t last() const { return walls.size(); }   // the goal platform's segment
	double lo(size_t s) const { return s == 0 ? x_start : walls[s - 1]; }
	double hi(size_t s) const { return s == last() ? x_goal : walls[s]; }
	// The segment x lies on: a wall's own x belongs to the segment after it.
	size_t segment_at(double x) const;
	// "floor1", "mid1", "floor2", ... for the intermediate segments (1 ..
	// last() - 1), "start" and "goal" for the platforms at the ends.
	std::string segment_name(size_t s) const;
};

// Throws std::runtime_error naming the file unless there is an even number
// (at least two) of walls between start and goal along x. Switch points keep
// clearance_m (the robot's body and margin) from the walls' edges and a
// cell more: they lie in cells the corridors keep clear (margin).
Profile profile_of(const scene::Scene &sc, double clearance_m);

// The one-chasm scene sc with its floor replaced by intermediate segments
// `lengths` [m] (an odd number: floor, platform, floor, ...): each floor
// sc's floor with columns inserted at its middle (copies of the middle
// column) or left out there, each platform copies of sc's start platform's
// column at the first wall; sc's goal platform and the goal moved along.
// Lengths are rounded to cells. Named chasm_030_020_030 (lengths in m),
// chasm_050 for one length. Throws std::invalid_argument unless sc has one
// chasm and lengths are an odd number of at least a cell each.
scene::Scene chasms(const scene::Scene &sc, const Profile &c, const std::vector<double> &lengths);

// The one-chasm scene sc made extra_m wider (chasms() with the floor's
// width plus extra_m): floor columns inserted at the chasm's middle, the far
// platform and the goal moved along. For widths between the committed
// scenes (the crossover).
scene::Scene widened(const scene::Scene &sc, const Profile &c, double extra_m);

// A route across the chasms: where the robot drives. Always on the start
// platform first unless !drive_start (it takes off at the start), always on
// the goal platform last unless !drive_goal (it lands on the goal), and on
// each intermediate segment in `landings` (floors or middle platforms,
// ascending), one flight between consecutive ground legs, crossing one or
// more walls.
struct Route {
	bool drive_start = true, drive_goal = true;
	std::vector<size_t> landings;

	bool operator==(const Route &o) const
	{
		return drive_start == o.drive_start && drive_goal == o.drive_goal && landings == o.landings;
	}
};

// A route's name: its modes in order (D drive, F fly), each ground leg on an
// intermediate segment followed by the segment's name, "DFD(floor1)FD";
// with one intermediate segment (one chasm) the letters alone: "DFDFD".
std::string route_name(const Profile &c, const Route &r);

// The route named `name` (route_name's form; an intermediate leg's segment
// may be left out when there is one intermediate segment: "FDF"). Throws
// std::invalid_argument saying what is wrong.
Route route_of(const Profile &c, const std::string &name);

// Every route that drives on the start and goal platforms: one per subset of
// the intermediate segments landed on (2^(walls - 1)), by number of landings,
// then in the order of the segments.
std::vector<Route> routes(const Profile &c);

// The route a plan takes (a planner path): its ground legs, each on the
// segment of its first waypoint; a ground leg of one waypoint at either end
// (a takeoff at the start, a landing on the goal) is no drive. Landings in
// the plan's order (a plan landing twice on one segment lists it twice).
Route route_of_plan(const Profile &c, const std::vector<trainer::Waypoint> &plan);

// A route as a plan for the smoother: ground legs from the start at rest,
// to the goal at rest; switch points placed `lambda` of the way from the
// wall they lead over (0: a margin from the wall) to the leg's far end (its
// middle for a leg between flights), every ground leg through waypoints at
// most 4 m apart at 2 m/s, every flight through waypoints at most 8 m apart
// at up to 8 m/s (3 m/s^2 from and to hover), 1 m above the surface under
// it, and 1 m above every wall top between the first and the last wall it
// crosses. These are only the initial guess: the smoother lets every switch
// point slide along its whole platform or floor.
std::vector<trainer::Waypoint> sequence_plan(const Profile &c, const Route &r, double lambda);
// The same for the route named `route` (route_of): "DFD", "DFD(mid1)FD".
std::vector<trainer::Waypoint> sequence_plan(const Profile &c, const std::string &route, double lambda);

// "DFD": a plan's modes in order (D ground, F flight).
std::string letters(const std::vector<trainer::Waypoint> &plan);

}  // namespace hylo::casestudies

#endif
