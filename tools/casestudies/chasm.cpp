// Case study 3's chasms (chasm.hpp).
#include "tools/casestudies/chasm.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace hylo::casestudies {

using scene::Scene;
using trainer::mode_number;
using trainer::Waypoint;

Chasm chasm_of(const Scene &sc, double clearance_m)
{
	Chasm c;
	c.y = sc.goal.start.x[1];
	c.x_start = sc.goal.start.x[0];
	c.x_goal = sc.goal.goal.x[0];
	c.margin = sc.resolution_m * (1 + std::ceil(clearance_m / sc.resolution_m - 1e-9));
	int iy = static_cast<int>((c.y - sc.origin_y_m) / sc.resolution_m);
	int i0 = static_cast<int>((c.x_start - sc.origin_x_m) / sc.resolution_m);
	int i1 = static_cast<int>((c.x_goal - sc.origin_x_m) / sc.resolution_m);
	auto h = [&](int ix) { return sc.height_m[static_cast<size_t>(iy * sc.nx + ix)]; };
	std::vector<double> walls;
	for (int ix = i0; ix < i1; ix++)
		if (std::fabs(h(ix + 1) - h(ix)) > sc.max_step_m)
			walls.push_back(sc.origin_x_m + (ix + 1) * sc.resolution_m);
	if (walls.size() != 2 || c.x_goal <= c.x_start)
		throw std::runtime_error(sc.path + ": not a chasm scene (two walls between start and goal along x)");
	c.e1 = walls[0];
	c.e2 = walls[1];
	c.h_platform = h(i0);
	c.h_floor = h(i0 + static_cast<int>((c.e1 - c.x_start) / sc.resolution_m) + 1);
	return c;
}

Scene widened(const Scene &sc, const Chasm &c, double extra_m)
{
	const int n = static_cast<int>(std::lround(extra_m / sc.resolution_m));
	const int mid = static_cast<int>((0.5 * (c.e1 + c.e2) - sc.origin_x_m) / sc.resolution_m);
	Scene w = sc;
	w.nx = sc.nx + n;
	w.terrain.clear();
	w.height_m.clear();
	for (int iy = 0; iy < sc.ny; iy++)
		for (int ix = 0; ix < w.nx; ix++) {
			int from = ix < mid ? ix : ix < mid + n ? mid : ix - n;
			w.terrain.push_back(sc.terrain[static_cast<size_t>(iy * sc.nx + from)]);
			w.height_m.push_back(sc.height_m[static_cast<size_t>(iy * sc.nx + from)]);
		}
	w.goal.goal.x[0] += n * sc.resolution_m;
	char name[64];
	std::snprintf(name, sizeof name, "chasm_%03d", static_cast<int>(std::lround(c.e2 - c.e1 + n * sc.resolution_m)));
	w.name = name;
	w.path = sc.path + " widened to " + std::string(name);
	return w;
}

std::vector<Waypoint> sequence_plan(const Chasm &c, const std::string &seq, double lambda)
{
	const int G = mode_number("ground"), F = mode_number("flight");
	std::vector<Waypoint> w;
	auto ground = [&](double x, double v, double heading, bool guard) {
		Waypoint p;
		p.mode = G;
		p.guard = guard;
		p.state[0] = x;
		p.state[1] = c.y;
		p.state[2] = v;
		p.state[3] = heading;
		w.push_back(p);
	};
	auto drive = [&](double x0, double x1, bool guard0, bool guard1) {
		int n = std::max(1, static_cast<int>(std::ceil(std::fabs(x1 - x0) / 4)));
		for (int i = 0; i <= n; i++)
			ground(x0 + (x1 - x0) * i / n, i == 0 || i == n ? 0 : 2, 0, (i == 0 && guard0) || (i == n && guard1));
	};
	auto surface_h = [&](double x) { return x < c.e1 || x >= c.e2 ? c.h_platform : c.h_floor; };
	// A flight 1 m above the platforms; from or to the floor it climbs
	// (descends) straight over its floor end, so the guess keeps clear of
	// the wall it crosses (a straight descent would cut through the wall's
	// top edge, and the corridors are built along the guess).
	auto fly = [&](double x0, double x1) {
		const double cruise = c.h_platform + 1, z0 = surface_h(x0) + 1, z1 = surface_h(x1) + 1;
		std::vector<std::array<double, 2>> corner{{x0, z0}};
		if (z0 < cruise)
			corner.push_back({x0, cruise});
		if (z1 < cruise)
			corner.push_back({x1, cruise});
		corner.push_back({x1, z1});
		double L = 0;
		for (size_t k = 1; k < corner.size(); k++)
			L += std::hypot(corner[k][0] - corner[k - 1][0], corner[k][1] - corner[k - 1][1]);
		double s0 = 0;
		for (size_t k = 1; k < corner.size(); k++) {
			const double dx = corner[k][0] - corner[k - 1][0], dz = corner[k][1] - corner[k - 1][1];
			const double len = std::hypot(dx, dz);
			const int n = std::max(1, static_cast<int>(std::ceil(len / 8)));
			for (int i = k == 1 ? 0 : 1; i <= n; i++) {
				const double s = s0 + len * i / n;
				const bool end = (k == 1 && i == 0) || (k + 1 == corner.size() && i == n);
				const double v = end ? 0 : std::min(8.0, std::sqrt(6 * std::min(s, L - s)));
				Waypoint p;
				p.mode = F;
				p.guard = end;
				double st[6] = {corner[k - 1][0] + dx * i / n, c.y, corner[k - 1][1] + dz * i / n,
						v * dx / len, 0, v * dz / len};
				std::copy(st, st + 6, p.state);
				w.push_back(p);
			}
			s0 += len;
		}
	};
	const double mid = 0.5 * (c.e1 + c.e2);
	const size_t last = seq.size() - 1;
	double x = c.x_start;
	for (size_t i = 0; i < seq.size(); i++) {
		if (seq[i] == 'D') {
			double to = i == last	? c.x_goal
				    : i == 0	? (c.e1 - c.margin) - lambda * (c.e1 - c.margin - c.x_start)
						: (c.e2 - c.margin) - lambda * (c.e2 - c.margin - std::max(x, mid));
			drive(x, to, i > 0, i < last);
			x = to;
		} else {
			double to = i == last	    ? c.x_goal
				    : i + 1 == last ? (c.e2 + c.margin) + lambda * (c.x_goal - c.e2 - c.margin)
						    : (c.e1 + c.margin) + lambda * (mid - c.e1 - c.margin);
			if (i == 0)
				ground(x, 0, 0, true);
			fly(x, to);
			if (i == last)   // else the next (D) leg's first waypoint is the landing point
				ground(to, 0, 0, true);
			x = to;
		}
	}
	return w;
}

std::string letters(const std::vector<Waypoint> &plan)
{
	std::string s;
	for (size_t i = 0; i < plan.size(); i++)
		if (i == 0 || plan[i].mode != plan[i - 1].mode)
			s += plan[i].mode == mode_number("flight") ? 'F' : 'D';
	return s;
}

}  // namespace hylo::casestudies
