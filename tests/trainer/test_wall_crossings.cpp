// The walls a flight crosses (trainer/map_guards.hpp wall_crossings): the
// exact cell walk cuts a diagonal flight clipping a wall's corner, which 4
// samples per cell miss; the gates of a straight crossing sit on the wall's
// grid lines at the right t and height, once where a waypoint lies on one;
// a flight through a vertex between two blocks, and one along a grid line
// beside a wall, are cut above them; a point and a flight leaving the map
// cut only on the map. Prints TAP.
#include <cmath>
#include <string>
#include <vector>

#include "tests/tap.hpp"
#include "tests/trainer/grids.hpp"
#include "trainer/map_guards.hpp"

namespace {

using namespace hylo::trainer;

void raise(TerrainGrid &g, int ix, int iy, float h)
{
	g.height_m[static_cast<size_t>(iy * g.nx + ix)] = h;
}

std::vector<WallCrossing> cross(const TerrainGrid &g, double ax, double ay, double bx, double by)
{
	const double a[6] = {ax, ay, 3, 0, 0, 0}, b[6] = {bx, by, 3, 0, 0, 0};
	return wall_crossings(g, a, b);
}

bool gate_is(const WallCrossing &c, double t, int axis, double at, double z_min)
{
	return std::fabs(c.t - t) < 1e-12 && c.gate.axis == axis && std::fabs(c.gate.c - at) < 1e-12 &&
	       std::fabs(c.gate.z_min - z_min) < 1e-12;
}

std::string show(const std::vector<WallCrossing> &cs)
{
	std::string s = std::to_string(cs.size()) + " crossings:";
	for (const WallCrossing &c : cs)
		s += " (t " + tap_num(c.t, 6) + ", axis " + std::to_string(c.gate.axis) + ", c " + tap_num(c.gate.c, 6) +
		     ", z_min " + tap_num(c.gate.z_min, 6) + ")";
	return s;
}

}  // namespace

int main()
{
	const double air = kAirClearanceM;
	{
		// Cell (2, 1) is 2 m high; the flight's slope 0.208 takes it through
		// the cell's corner at (3, 1) for t in [0.801, 0.833], between two of
		// its 13 samples.
		TerrainGrid g = flat_ground(6, 4);
		raise(g, 2, 1, 2);
		auto cs = cross(g, 0.5, 0.5, 3.5, 0.5 + 3 * 0.208);
		check(cs.size() == 2 && gate_is(cs[0], 0.5 / 0.208 / 3, 1, 1, 2 + air) &&
			      gate_is(cs[1], 2.5 / 3, 0, 3, 2 + air),
		      "a diagonal flight clipping a wall's corner is cut on both of its edges", show(cs));
	}
	{
		// A wall of columns 4 and 5 (x in [1, 2] m), 1.2 m high; the map's
		// origin (-1, 2) m, cells of 0.5 m.
		TerrainGrid g = flat_ground(10, 6, 0.5);
		g.origin_x_m = -1;
		g.origin_y_m = 2;
		for (int iy = 0; iy < 6; iy++) {
			raise(g, 4, iy, 1.2f);
			raise(g, 5, iy, 1.2f);
		}
		auto cs = cross(g, -0.5, 3.25, 3.5, 3.25);
		const double z = static_cast<double>(1.2f) + air;
		check(cs.size() == 2 && gate_is(cs[0], 1.5 / 4, 0, 1, z) && gate_is(cs[1], 2.5 / 4, 0, 2, z),
		      "a straight crossing: gates at x = 1 and 2 m, t 0.375 and 0.625, 0.5 m above the wall", show(cs));
		cs = cross(g, 1.2, 4.9, 1.2, 2.1);
		check(cs.empty(), "a flight along the wall's top crosses no wall", show(cs));
		// A waypoint on the wall's line x = 1: one cut, by either edge.
		auto e1 = cross(g, -0.5, 3.25, 1, 3.25), e2 = cross(g, 1, 3.25, 1.2, 3.25);
		check(e1.size() == 1 && gate_is(e1[0], 1, 0, 1, z) && e2.empty(),
		      "reaching a waypoint on a wall's line: cut at the first edge's end", show(e1) + "; " + show(e2));
		e1 = cross(g, 1.2, 3.25, 1, 3.25);
		e2 = cross(g, 1, 3.25, -0.5, 3.25);
		check(e1.empty() && e2.size() == 1 && gate_is(e2[0], 0, 0, 1, z),
		      "leaving a waypoint on a wall's line: cut at the second edge's start", show(e1) + "; " + show(e2));
		cs = cross(g, 0, 3, 0, 3);
		check(cs.empty(), "a point crosses no wall", show(cs));
		cs = cross(g, 0.2, 3.1, 8, 3.1);
		check(cs.size() == 2 && gate_is(cs[1], 1.8 / 7.8, 0, 2, z),
		      "a flight leaving the map is cut at the walls on the map", show(cs));
	}
	{
		// Blocks (2, 1) and (1, 2), 1 m and 1.5 m high, meet at the vertex
		// (2, 2) the flight passes through: one gate, over the higher.
		TerrainGrid g = flat_ground(5, 5);
		raise(g, 2, 1, 1);
		raise(g, 1, 2, 1.5f);
		auto cs = cross(g, 0.5, 0.5, 3.5, 3.5);
		check(cs.size() == 1 && gate_is(cs[0], 0.5, 0, 2, 1.5 + air),
		      "a flight through the vertex between two blocks is cut above the higher", show(cs));
		// Along the grid line y = 2: the cells on both sides count (0, 1.5,
		// 1, 0, 0 m high columns).
		cs = cross(g, 0.5, 2, 4.5, 2);
		check(cs.size() == 3 && gate_is(cs[0], 0.125, 0, 1, 1.5 + air) && gate_is(cs[1], 0.375, 0, 2, 1.5 + air) &&
			      gate_is(cs[2], 0.625, 0, 3, 1 + air),
		      "a flight along a grid line is cut at the walls of the cells on both sides", show(cs));
	}
	return tap_finish();
}
