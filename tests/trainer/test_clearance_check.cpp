// The smoother's exact clearance check (trainer/clearance.hpp) on
// trajectories built by hand: a straight drive past an obstacle is measured
// to the millimetre, the same drive pushed into the obstacle is caught and
// named (phase, time, place), the check looks between knots (a curve whose
// knots are clear but whose cubic cuts a corner), and a flight past a wall
// reports the 3-D distance to the wall's top edge. Prints TAP.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "tests/tap.hpp"
#include "tests/trainer/grids.hpp"
#include "trainer/clearance.hpp"

using namespace hylo::trainer;

namespace {

// 20 x 20 cells of 0.5 m, flat ground; an obstacle at cells (10..11, 10..11),
// i.e. [5, 6] x [5, 6] m.
TerrainGrid grid()
{
	TerrainGrid g = flat_ground(20, 20, 0.5);
	g.ceiling_m = 8;
	for (int iy = 10; iy <= 11; iy++)
		for (int ix = 10; ix <= 11; ix++)
			g.terrain[static_cast<size_t>(iy * 20 + ix)] = 0;
	return g;
}

// A ground phase through the given positions, heading along x at speed v,
// knots and midpoints 0.5 s apart.
MultiPhaseSolution drive(const std::vector<std::pair<double, double>> &xy, double v, double theta = 0)
{
	MultiPhaseSolution s;
	Solution ph;
	ph.traj.nx = 6;
	ph.traj.nu = 2;
	for (size_t i = 0; i < xy.size(); i++) {
		ph.traj.t.push_back(0.5 * static_cast<double>(i));
		for (double x : {xy[i].first, xy[i].second, v, 0.0, theta, 0.0})
			ph.traj.x.push_back(x);
		ph.traj.u.push_back(0);
		ph.traj.u.push_back(0);
	}
	ph.T = ph.traj.t.back();
	s.phases.push_back(ph);
	s.modes.push_back(HYLO_MODE_GROUND);
	return s;
}

bool near(double a, double b, double tol = 1e-9) { return std::fabs(a - b) <= tol; }

}  // namespace

int main()
{
	const TerrainGrid g = grid();
	const double body = 0.35, margin = 0.1;

	// Along y = 4.0 at 1 m/s, from x = 2 to 6: the obstacle's lower side is
	// 1.0 m away, minus the body: 0.65 m.
	std::vector<std::pair<double, double>> line;
	for (int i = 0; i <= 8; i++)
		line.push_back({2 + 0.5 * i, 4.0});
	ClearanceCheck c = check_clearance(drive(line, 1.0), g, body, margin);
	check(c.safe && near(c.min_clearance_m, 0.65) && c.phase == 0 && c.mode == HYLO_MODE_GROUND,
	      "a drive 1 m beside an obstacle: safe, clearance 0.65 m beyond a 0.35 m body", c.text());

	// The same drive at y = 4.6: 0.05 m beyond the body, under the margin.
	for (auto &p : line)
		p.second = 4.6;
	c = check_clearance(drive(line, 1.0), g, body, margin);
	check(!c.safe && near(c.min_clearance_m, 0.05) && c.x_m >= 5 - 1e-9 && c.x_m <= 6 + 1e-9 &&
		      c.text().find("not safe") == 0 && c.text().find("phase 0") != std::string::npos,
	      "pushed 0.6 m towards the obstacle: not safe, clearance 0.05 m, where it is named", c.text());

	// Pushed into it: outside the domain, and the place is said.
	for (auto &p : line)
		p.second = 5.5;
	c = check_clearance(drive(line, 1.0), g, body, margin);
	check(!c.safe && c.outside_phase == 0 && c.outside_x_m >= 5 - 1e-9 && c.min_clearance_m < 0 &&
		      c.text().find("leaves its domain") != std::string::npos,
	      "pushed into the obstacle: not safe, outside its domain at the obstacle", c.text());

	// Between knots: two knots 2 m apart left and right of the obstacle's
	// corner, with velocities that bow the cubic into it. The knots alone
	// are clear; the check must find the bow.
	MultiPhaseSolution bow = drive({{4.0, 4.3}, {7.0, 4.3}}, 6.0, 0.9);
	bow.phases[0].traj.t = {0, 1.0};
	bow.phases[0].traj.x[4] = 0.9;    // leaving up and right,
	bow.phases[0].traj.x[10] = -0.9;  // arriving down and right
	c = check_clearance(bow, g, body, margin, 0);
	const ClearanceCheck dense = check_clearance(bow, g, body, margin);
	check(c.safe && !dense.safe && dense.min_clearance_m < c.min_clearance_m,
	      "the check looks between knots: clear knots, a cubic that bows into the obstacle",
	      c.text() + " | " + dense.text());

	// A flight at z = 1.2 m passing 0.3 m beside a 1 m wall (its top edge at
	// x = 5, z = 1): the sphere's distance is hypot(0.3, 0.2) - 0.32.
	TerrainGrid w = grid();
	for (int iy = 0; iy < 20; iy++)
		for (int ix = 10; ix < 20; ix++) {
			w.terrain[static_cast<size_t>(iy * 20 + ix)] = 1;
			w.height_m[static_cast<size_t>(iy * 20 + ix)] = ix >= 10 ? 1.0f : 0.0f;
		}
	MultiPhaseSolution f;
	Solution ph;
	ph.traj.nx = 16;
	ph.traj.nu = 4;
	for (int i = 0; i <= 4; i++) {
		ph.traj.t.push_back(0.5 * i);
		std::vector<double> x(16, 0.0);
		x[0] = 4.7;
		x[1] = 2.0 + 0.5 * i;
		x[2] = 1.2;
		x[8] = 1.5707963267948966;   // yaw 90 degrees: body-x along world y
		x[3] = 1.0;
		ph.traj.x.insert(ph.traj.x.end(), x.begin(), x.end());
		ph.traj.u.insert(ph.traj.u.end(), 4, 0.0);
	}
	ph.T = 2;
	f.phases.push_back(ph);
	f.modes.push_back(HYLO_MODE_FLIGHT);
	c = check_clearance(f, w, 0.32, margin);
	check(!c.safe && near(c.min_clearance_m, std::hypot(0.3, 0.2) - 0.32, 1e-6) && c.mode == HYLO_MODE_FLIGHT &&
		      near(c.z_m, 1.2, 1e-6),
	      "a flight 0.3 m beside and 0.2 m above a wall's top edge: 3-D clearance, not safe", c.text());
	return tap_finish();
}
