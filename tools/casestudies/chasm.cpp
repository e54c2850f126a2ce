// Case study 3's chasms (chasm.hpp).
#include "tools/casestudies/chasm.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace hylo::casestudies {

using scene::Scene;
using trainer::Waypoint;

size_t Profile::segment_at(double x) const
{
	return static_cast<size_t>(std::upper_bound(walls.begin(), walls.end(), x) - walls.begin());
}

std::string Profile::segment_name(size_t s) const
{
	if (s == 0)
		return "start";
	if (s == last())
		return "goal";
	return (s % 2 ? "floor" : "mid") + std::to_string((s + 1) / 2);
}

Profile profile_of(const Scene &sc, double clearance_m)
{
	Profile c;
	c.y = sc.goal.start.x[1];
	c.x_start = sc.goal.start.x[0];
	c.x_goal = sc.goal.goal.x[0];
	c.margin = sc.resolution_m * (1 + std::ceil(clearance_m / sc.resolution_m - 1e-9));
	int iy = static_cast<int>((c.y - sc.origin_y_m) / sc.resolution_m);
	auto column = [&](double x) { return static_cast<int>((x - sc.origin_x_m) / sc.resolution_m); };
	auto h = [&](int ix) { return sc.height_m[static_cast<size_t>(iy * sc.nx + ix)]; };
	for (int ix = column(c.x_start); ix < column(c.x_goal); ix++)
		if (std::fabs(h(ix + 1) - h(ix)) > sc.max_step_m)
			c.walls.push_back(sc.origin_x_m + (ix + 1) * sc.resolution_m);
	if (c.walls.empty() || c.walls.size() % 2 || c.x_goal <= c.x_start)
		throw std::runtime_error(sc.path + ": not a chasm scene (an even number of walls between start and goal along x)");
	for (size_t s = 0; s <= c.last(); s++)   // the height at the segment's middle
		c.heights.push_back(h(column(s == 0 ? c.x_start : 0.5 * (c.lo(s) + c.hi(s)))));
	return c;
}

Scene chasms(const Scene &sc, const Profile &c, const std::vector<double> &lengths)
{
	if (c.walls.size() != 2)
		throw std::invalid_argument(sc.path + ": more than one chasm to make chasms from");
	if (lengths.size() % 2 == 0)
		throw std::invalid_argument("chasms: an odd number of lengths (floor, platform, floor, ...) is needed");
	auto column = [&](double x) { return static_cast<int>(std::lround((x - sc.origin_x_m) / sc.resolution_m)); };
	// Each new column is a copy of one of sc's: its start platform up to the
	// first wall, each floor from sc's floor (f0 .. f1), each platform sc's
	// last column before the first wall, then sc's goal platform onwards.
	const int f0 = column(c.walls[0]), f1 = column(c.walls[1]);
	const int mid = static_cast<int>((0.5 * (c.walls[0] + c.walls[1]) - sc.origin_x_m) / sc.resolution_m);
	std::vector<int> from;
	for (int ix = 0; ix < f0; ix++)
		from.push_back(ix);
	std::string name = "chasm";
	for (size_t k = 0; k < lengths.size(); k++) {
		const long n = std::lround(lengths[k] / sc.resolution_m);
		if (!(n >= 1 && n <= 100000))
			throw std::invalid_argument("chasms: segment " + std::to_string(k + 1) + " is not between a cell and 100,000 cells long");
		char part[32];
		std::snprintf(part, sizeof part, "_%03ld", std::lround(n * sc.resolution_m));
		name += part;
		for (int j = 0; j < n; j++) {
			if (k % 2)   // a platform
				from.push_back(f0 - 1);
			else if (n >= f1 - f0)   // a floor as wide or wider: the middle column repeated
				from.push_back(j < mid - f0 ? f0 + j : j < mid - f0 + (n - (f1 - f0)) ? mid : j - static_cast<int>(n) + f1);
			else   // narrower: middle columns left out
				from.push_back(j < n / 2 ? f0 + j : f1 - static_cast<int>(n) + j);
		}
	}
	for (int ix = f1; ix < sc.nx; ix++)
		from.push_back(ix);
	Scene w = sc;
	w.nx = static_cast<int32_t>(from.size());
	w.terrain.clear();
	w.height_m.clear();
	for (int iy = 0; iy < sc.ny; iy++)
		for (int ix : from) {
			w.terrain.push_back(sc.terrain[static_cast<size_t>(iy * sc.nx + ix)]);
			w.height_m.push_back(sc.height_m[static_cast<size_t>(iy * sc.nx + ix)]);
		}
	w.goal.goal.x[0] += (w.nx - sc.nx) * sc.resolution_m;
	w.name = name;
	w.path = sc.path + (lengths.size() == 1 ? " widened to " : " made into ") + name;
	return w;
}

Scene widened(const Scene &sc, const Profile &c, double extra_m)
{
	if (c.walls.size() != 2)
		throw std::invalid_argument(sc.path + ": more than one chasm to widen");
	return chasms(sc, c, {c.walls[1] - c.walls[0] + extra_m});
}

std::string route_name(const Profile &c, const Route &r)
{
	const bool label = c.last() > 2;   // more than one intermediate segment
	std::string s = r.drive_start ? "DF" : "F";
	for (size_t seg : r.landings)
		s += "D" + (label ? "(" + c.segment_name(seg) + ")" : "") + "F";
	return r.drive_goal ? s + "D" : s;
}

Route route_of(const Profile &c, const std::string &name)
{
	auto bad = [&](const std::string &why) {
		return std::invalid_argument("route '" + name + "': " + why);
	};
	// Legs: 'D' (with its segment's name, "" if none given) or 'F'.
	std::vector<std::pair<char, std::string>> legs;
	for (size_t i = 0; i < name.size(); i++) {
		if (name[i] != 'D' && name[i] != 'F')
			throw bad("'" + name.substr(i, 1) + "' is not D (drive) or F (fly)");
		legs.push_back({name[i], ""});
		if (name[i] == 'D' && i + 1 < name.size() && name[i + 1] == '(') {
			size_t close = name.find(')', i);
			if (close == std::string::npos)
				throw bad("a '(' without ')'");
			legs.back().second = name.substr(i + 2, close - i - 2);
			i = close;
		}
	}
	for (size_t i = 1; i < legs.size(); i++)
		if (legs[i].first == legs[i - 1].first)
			throw bad("drives and flights must alternate");
	if (legs.empty() || (legs.size() == 1 && legs[0].first == 'D'))
		throw bad("no flight: the walls cannot be driven over");
	Route r;
	r.drive_start = legs.front().first == 'D';
	r.drive_goal = legs.back().first == 'D';
	for (size_t i = r.drive_start ? 1 : 0; i + (r.drive_goal ? 1 : 0) < legs.size(); i++) {
		if (legs[i].first == 'F')
			continue;
		size_t seg = 0;
		if (legs[i].second.empty()) {
			if (c.last() != 2)
				throw bad("a drive between flights names its segment when there are several: D(floor1)");
			seg = 1;
		} else {
			for (size_t s = 1; s < c.last(); s++)
				if (c.segment_name(s) == legs[i].second)
					seg = s;
			if (seg == 0)
				throw bad("no segment '" + legs[i].second + "' between the start and goal platforms");
		}
		if (!r.landings.empty() && seg <= r.landings.back())
			throw bad("the segments landed on must follow one another from start to goal");
		r.landings.push_back(seg);
	}
	for (size_t i = 0; i < legs.size(); i++)
		if (!legs[i].second.empty() && ((i == 0 && r.drive_start) || (i + 1 == legs.size() && r.drive_goal)))
			throw bad("the first and last drives are on the start and goal platforms, unnamed");
	return r;
}

std::vector<Route> routes(const Profile &c)
{
	const size_t k = c.last() - 1;   // intermediate segments
	std::vector<std::vector<size_t>> subsets;
	for (size_t m = 0; m < (size_t{1} << k); m++) {
		std::vector<size_t> s;
		for (size_t i = 0; i < k; i++)
			if (m >> i & 1)
				s.push_back(i + 1);
		subsets.push_back(s);
	}
	std::stable_sort(subsets.begin(), subsets.end(), [](const auto &a, const auto &b) {
		return a.size() != b.size() ? a.size() < b.size() : a < b;
	});
	std::vector<Route> out;
	for (const auto &s : subsets) {
		Route r;
		r.landings = s;
		out.push_back(r);
	}
	return out;
}

Route route_of_plan(const Profile &c, const std::vector<Waypoint> &plan)
{
	const hylo_mode G = HYLO_MODE_GROUND;
	std::vector<std::pair<size_t, size_t>> runs;   // [first, last] waypoint of each mode's run
	for (size_t i = 0; i < plan.size(); i++)
		if (i == 0 || plan[i].mode != plan[i - 1].mode)
			runs.push_back({i, i});
		else
			runs.back().second = i;
	Route r;
	if (runs.empty())
		return r;
	auto drives = [&](size_t k) { return plan[runs[k].first].mode == G && runs[k].second > runs[k].first; };
	r.drive_start = drives(0);
	r.drive_goal = runs.size() > 1 && drives(runs.size() - 1);
	for (size_t k = 1; k + 1 < runs.size(); k++)
		if (plan[runs[k].first].mode == G)
			r.landings.push_back(c.segment_at(plan[runs[k].first].state[0]));
	return r;
}

std::vector<Waypoint> sequence_plan(const Profile &c, const Route &r, double lambda)
{
	const hylo_mode G = HYLO_MODE_GROUND, F = HYLO_MODE_FLIGHT;
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
	auto surface_h = [&](double x) { return c.heights[c.segment_at(x)]; };
	// A flight 1 m above every wall top it passes (the highest segment
	// from its start to its end); from or to a lower surface it climbs
	// (descends) straight over its end, so the guess keeps clear of the
	// walls it crosses (a straight descent would cut through a wall's top
	// edge, and the corridors are built along the guess).
	auto fly = [&](double x0, double x1) {
		double top = -INFINITY;
		for (size_t s = c.segment_at(x0); s <= c.segment_at(x1); s++)
			top = std::max(top, c.heights[s]);
		const double cruise = top + 1, z0 = surface_h(x0) + 1, z1 = surface_h(x1) + 1;
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
	// The legs in order: D on a segment, or F (segment unused).
	struct Leg {
		bool drive;
		size_t seg;
	};
	std::vector<Leg> legs;
	if (r.drive_start)
		legs.push_back({true, 0});
	for (size_t s : r.landings) {
		if (s == 0 || s >= c.last())
			throw std::invalid_argument("sequence_plan: a landing on segment " + std::to_string(s) +
						    ", not between the start and goal platforms");
		legs.push_back({false, 0});
		legs.push_back({true, s});
	}
	legs.push_back({false, 0});
	if (r.drive_goal)
		legs.push_back({true, c.last()});
	// Where a ground leg on segment s takes off, coming from x: `lambda` of
	// the way from a margin before its far wall back to x or the segment's
	// middle, whichever is nearer the wall (x: the start platform's start).
	auto takeoff = [&](size_t s, double x) {
		const double b = c.walls[s], back = s == 0 ? c.x_start : 0.5 * (c.lo(s) + c.hi(s));
		return (b - c.margin) - lambda * (b - c.margin - std::max(x, back));
	};
	// Where a flight lands on segment s: `lambda` of the way from a margin
	// past its near wall to its middle (the goal on the goal platform).
	auto landing = [&](size_t s) {
		const double a = c.walls[s - 1], far = s == c.last() ? c.x_goal : 0.5 * (c.lo(s) + c.hi(s));
		return (a + c.margin) + lambda * (far - a - c.margin);
	};
	const size_t last = legs.size() - 1;
	double x = c.x_start;
	for (size_t i = 0; i < legs.size(); i++) {
		if (legs[i].drive) {
			double to = i == last ? c.x_goal : takeoff(legs[i].seg, x);
			drive(x, to, i > 0, i < last);
			x = to;
		} else {
			double to = i == last ? c.x_goal : landing(legs[i + 1].seg);
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

std::vector<Waypoint> sequence_plan(const Profile &c, const std::string &route, double lambda)
{
	return sequence_plan(c, route_of(c, route), lambda);
}

std::string letters(const std::vector<Waypoint> &plan)
{
	std::string s;
	for (size_t i = 0; i < plan.size(); i++)
		if (i == 0 || plan[i].mode != plan[i - 1].mode)
			s += plan[i].mode == HYLO_MODE_FLIGHT ? 'F' : 'D';
	return s;
}

}  // namespace hylo::casestudies
