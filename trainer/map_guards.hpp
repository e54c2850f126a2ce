// Where a plan's switch points may slide, read off its map (docs/smoothing.md,
// "The problem"): the piece of shore where a ground and a water corridor
// meet, or a straight piece of shoreline fitted to the map; the rectangle of
// level, clear ground a takeoff or landing may use; the walls a flight
// crosses. trainer/switching.hpp joins the phases on them.
#ifndef HYLO_TRAINER_MAP_GUARDS_HPP
#define HYLO_TRAINER_MAP_GUARDS_HPP

#include <string>
#include <vector>

#include "trainer/corridor.hpp"
#include "trainer/problem.hpp"
#include "trainer/switching.hpp"
#include "trainer/terrain_grid.hpp"

namespace hylo::trainer {

// A straight piece of shoreline through the switch point (x, y): its
// direction fitted (principal axis) to the shore near it, extended each way
// (up to half_length) while the shore stays within a cell of the line.
// Throws std::invalid_argument when there is no shoreline near the point.
SwitchGuard shoreline_guard(const TerrainGrid &m, double x, double y, double half_length);

// The shoreline piece where one phase's corridor ends (ground or water, its
// last box a) and the next one's begins (the other, its first box b): the
// intersection of the two boxes, a piece of the shared edge of adjacent
// clear ground and water cells, within half_length of the plan's switch
// point (x, y) per axis (0: the point). False when the boxes do not meet.
bool shore_from_boxes(const CorridorBox &a, const CorridorBox &b, double x, double y, double half_length,
		      SwitchGuard &g);

// The rectangle of level, drivable ground around the takeoff or landing
// point (x, y), within half_length of it per axis, over the cells clear at
// the first corridor level whose cell under (x, y) is (a note says when
// that is not the first level); without maps, or when no level's is, over
// every level ground cell. Its bounds are the centres of its outer cells
// (the robot keeps half a cell from the edge), widened to hold (x, y). An
// area, not a line: a plan that reaches the platform's edge at a corner may
// take off straight ahead instead. Throws std::invalid_argument when
// (x, y) is not on drivable ground.
SwitchGuard clear_platform(const TerrainGrid &map, double x, double y, double half_length, const CorridorMaps *maps,
			   std::vector<std::string> &notes);

// Where the straight flight a -> b (sampled flight states) crosses a wall,
// walking the cells it passes through exactly (hylo_cell_walk, the onboard
// domain check's walk): a point where it passes from cell to cell and the
// terrain under it (the highest cell the point touches: on a vertex, all
// four) and the terrain on one side differ by more than the map's max_step.
// An end on a grid line counts as in the cell cell_at gives it, so that a
// flight through a waypoint on a wall's line is cut once, by one of its two
// edges (at t 0 or 1). The gate lies on the grid line crossed (through a
// vertex, the x one), kAirClearanceM above that terrain (the planner's
// flight clearance); t is where along a -> b (0..1). The walk ends where
// the flight leaves the map.
struct WallCrossing {
	double t;
	WallGate gate;
};
std::vector<WallCrossing> wall_crossings(const TerrainGrid &m, const double *a, const double *b);

}  // namespace hylo::trainer

#endif
