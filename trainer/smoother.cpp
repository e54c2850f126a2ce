#include "trainer/smoother.hpp"

#include <array>
#include <memory>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <stdexcept>

#include "trainer/corridor.hpp"

namespace hylo::trainer {
namespace {

constexpr int8_t kGround = 1, kWater = 2;

double norm3(double x, double y, double z)
{
	return std::sqrt(x * x + y * y + z * z);
}

struct Cell {
	bool inside = false;
	int index = 0;
};

Cell cell_at(const TerrainGrid &m, double x, double y)
{
	double fx = (x - m.origin_x_m) / m.resolution_m, fy = (y - m.origin_y_m) / m.resolution_m;
	if (!(fx >= 0 && fy >= 0 && fx < m.nx && fy < m.ny))
		return {};
	return {true, static_cast<int>(fy) * m.nx + static_cast<int>(fx)};
}

struct Point {
	double x, y;
};

// Midpoints of the edges between ground and water cells within r of (x, y).
std::vector<Point> shore_points(const TerrainGrid &m, double x, double y, double r)
{
	std::vector<Point> pts;
	int cx = static_cast<int>((x - m.origin_x_m) / m.resolution_m);
	int cy = static_cast<int>((y - m.origin_y_m) / m.resolution_m);
	int span = static_cast<int>(std::ceil(r / m.resolution_m)) + 1;
	for (int iy = std::max(0, cy - span); iy <= std::min(m.ny - 1, cy + span); iy++)
		for (int ix = std::max(0, cx - span); ix <= std::min(m.nx - 1, cx + span); ix++) {
			int8_t t = m.terrain[static_cast<size_t>(iy * m.nx + ix)];
			const int nb[2][2] = {{1, 0}, {0, 1}};
			for (const auto &d : nb) {
				int jx = ix + d[0], jy = iy + d[1];
				if (jx >= m.nx || jy >= m.ny)
					continue;
				int8_t u = m.terrain[static_cast<size_t>(jy * m.nx + jx)];
				if (!((t == kGround && u == kWater) || (t == kWater && u == kGround)))
					continue;
				Point p{m.origin_x_m + (ix + 0.5 + 0.5 * d[0]) * m.resolution_m,
					m.origin_y_m + (iy + 0.5 + 0.5 * d[1]) * m.resolution_m};
				if (std::hypot(p.x - x, p.y - y) <= r)
					pts.push_back(p);
			}
		}
	return pts;
}

// A straight piece of shoreline through the switch point: its direction
// fitted (principal axis) to the shore near it, extended each way while the
// shore stays within a cell of the line.
SwitchGuard shoreline_guard(const TerrainGrid &m, double x, double y, double half_length)
{
	double fit_r = std::max(1.5, 3 * m.resolution_m);
	std::vector<Point> near = shore_points(m, x, y, fit_r);
	if (near.size() < 2)
		throw std::invalid_argument("no shoreline near the switch point (" + std::to_string(x) + ", " +
					    std::to_string(y) + ")");
	double mx = 0, my = 0;
	for (const Point &p : near) {
		mx += p.x;
		my += p.y;
	}
	mx /= static_cast<double>(near.size());
	my /= static_cast<double>(near.size());
	double sxx = 0, sxy = 0, syy = 0;
	for (const Point &p : near) {
		sxx += (p.x - mx) * (p.x - mx);
		sxy += (p.x - mx) * (p.y - my);
		syy += (p.y - my) * (p.y - my);
	}
	double angle = 0.5 * std::atan2(2 * sxy, sxx - syy);
	double tx = std::cos(angle), ty = std::sin(angle);
	std::vector<Point> shore = shore_points(m, x, y, half_length + m.resolution_m);
	auto on_shore = [&](double px, double py) {
		for (const Point &p : shore)
			if (std::hypot(p.x - px, p.y - py) <= m.resolution_m)
				return true;
		return false;
	};
	double step = 0.5 * m.resolution_m, ends[2] = {0, 0};
	for (int side = 0; side < 2; side++) {
		double sgn = side ? 1.0 : -1.0;
		for (double s = step; s <= half_length + 1e-9 && on_shore(x + sgn * s * tx, y + sgn * s * ty); s += step)
			ends[side] = s;
	}
	return {x - ends[0] * tx, y - ends[0] * ty, x + ends[1] * tx, y + ends[1] * ty, 0};
}

// The rectangle of level, drivable ground around (x, y) where the robot may
// take off or land: grown a row or column of cells at a time while the new
// cells are level with (x, y)'s and within half_length of it. Its bounds are
// the centres of its outer cells (the robot keeps half a cell from the edge),
// widened to hold (x, y) itself. An area, not a line: a plan that reaches the
// platform's edge at a corner may take off straight ahead instead. With
// clear, only its clear ground cells count (the takeoff cell's too).
SwitchGuard platform_area(const TerrainGrid &m, double x, double y, double half_length,
			  const ClearanceMap *clear = nullptr)
{
	Cell c = cell_at(m, x, y);
	if (!c.inside || m.terrain[static_cast<size_t>(c.index)] != kGround)
		throw std::invalid_argument("the takeoff or landing point (" + std::to_string(x) + ", " +
					    std::to_string(y) + ") is not on drivable ground");
	const double h = m.height_m[static_cast<size_t>(c.index)];
	const int cx = c.index % m.nx, cy = c.index / m.nx;
	const int reach = static_cast<int>(std::floor(half_length / m.resolution_m + 1e-9));
	auto level = [&](int ix, int iy) {
		size_t k = static_cast<size_t>(iy * m.nx + ix);
		return m.terrain[k] == kGround && std::fabs(m.height_m[k] - h) < 1e-3 &&
		       (!clear || clear->clear("ground", ix, iy));
	};
	int lo[2] = {cx, cy}, hi[2] = {cx, cy};
	const int size[2] = {m.nx, m.ny}, centre[2] = {cx, cy};
	for (bool grew = true; grew;) {
		grew = false;
		for (int axis = 0; axis < 2; axis++)
			for (int dir = -1; dir <= 1; dir += 2) {
				int at = (dir < 0 ? lo[axis] : hi[axis]) + dir;
				if (at < 0 || at >= size[axis] || std::abs(at - centre[axis]) > reach)
					continue;
				bool ok = true;
				int other = 1 - axis;
				for (int j = lo[other]; j <= hi[other] && ok; j++)
					ok = axis == 0 ? level(at, j) : level(j, at);
				if (ok) {
					(dir < 0 ? lo[axis] : hi[axis]) = at;
					grew = true;
				}
			}
	}
	SwitchGuard g;
	g.area = true;
	g.height_m = h;
	g.ax = std::min(x, m.origin_x_m + (lo[0] + 0.5) * m.resolution_m);
	g.bx = std::max(x, m.origin_x_m + (hi[0] + 0.5) * m.resolution_m);
	g.ay = std::min(y, m.origin_y_m + (lo[1] + 0.5) * m.resolution_m);
	g.by = std::max(y, m.origin_y_m + (hi[1] + 0.5) * m.resolution_m);
	return g;
}

std::vector<double> sampled(const Waypoint &w)
{
	int n = sampled_dim(mode_name(w.mode));
	return std::vector<double>(w.state, w.state + n);
}

bool same_place(const Waypoint &a, const Waypoint &b)
{
	return std::hypot(a.state[0] - b.state[0], a.state[1] - b.state[1]) < 1e-6;
}

double height_at(const TerrainGrid &m, double x, double y)
{
	Cell c = cell_at(m, x, y);
	if (!c.inside)
		throw std::invalid_argument("the point (" + std::to_string(x) + ", " + std::to_string(y) +
					    ") is off the map");
	return m.height_m[static_cast<size_t>(c.index)];
}

struct Crossing {
	double t;        // along the segment, 0..1
	WallGate gate;
};

// Where the straight flight a -> b (sampled flight states) crosses a wall:
// a cell boundary across which the terrain height steps by more than the
// map's max_step. The gate lies on that boundary, kAirClearanceM above the
// higher side (the planner's flight clearance).
std::vector<Crossing> wall_crossings(const TerrainGrid &m, const double *a, const double *b)
{
	std::vector<Crossing> out;
	double len = std::hypot(b[0] - a[0], b[1] - a[1]);
	int steps = std::max(1, static_cast<int>(std::ceil(4 * len / m.resolution_m)));
	Cell prev = cell_at(m, a[0], a[1]);
	for (int i = 1; i <= steps && prev.inside; i++) {
		double t = static_cast<double>(i) / steps;
		Cell c = cell_at(m, a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]));
		if (!c.inside || c.index == prev.index) {
			prev = c;
			continue;
		}
		double h0 = m.height_m[static_cast<size_t>(prev.index)], h1 = m.height_m[static_cast<size_t>(c.index)];
		if (std::fabs(h1 - h0) > m.max_step_m) {
			int ix0 = prev.index % m.nx, ix1 = c.index % m.nx, iy0 = prev.index / m.nx, iy1 = c.index / m.nx;
			WallGate g;
			g.axis = ix0 != ix1 ? 0 : 1;
			g.c = g.axis == 0 ? m.origin_x_m + std::max(ix0, ix1) * m.resolution_m
					  : m.origin_y_m + std::max(iy0, iy1) * m.resolution_m;
			g.z_min = std::max(h0, h1) + kAirClearanceM;
			double d = b[g.axis] - a[g.axis];
			out.push_back({std::fabs(d) > 1e-12 ? (g.c - a[g.axis]) / d : t, g});
		}
		prev = c;
	}
	return out;
}

// A duration guess for a phase through sampled states: ground and marine
// leave it to the solver (path length / typical speed); flight edges take
// their length over their mean speed, at least 1 m/s (flights of tens of
// metres at 8 m/s would otherwise be guessed at 3 m/s, with a mesh twice as
// fine as they need).
double flight_time_guess(const std::vector<std::vector<double>> &xs)
{
	double T = 0;
	for (size_t i = 1; i < xs.size(); i++) {
		const double *a = xs[i - 1].data(), *b = xs[i].data();
		double d = norm3(b[0] - a[0], b[1] - a[1], b[2] - a[2]);
		T += d / std::max(1.0, 0.5 * (norm3(a[3], a[4], a[5]) + norm3(b[3], b[4], b[5])));
	}
	return std::max(0.2, T);
}

// The clearance maps of a plan's corridors, or none (opt.corridors off, no
// map; a map the onboard code refuses: a note says so).
std::unique_ptr<CorridorMaps> corridor_maps(const RobotParams &robot, const TerrainGrid &map,
					    const SmoothOptions &opt, std::vector<std::string> &notes)
{
	if (!(std::isfinite(opt.margin_m) && opt.margin_m >= 0))
		throw std::invalid_argument("the margin " + std::to_string(opt.margin_m) + " m must be finite and >= 0");
	if (!(std::isfinite(opt.corridor_pad_m) && opt.corridor_pad_m >= 0))
		throw std::invalid_argument("the corridor pad " + std::to_string(opt.corridor_pad_m) +
					    " m must be finite and >= 0");
	if (!opt.corridors || map.nx <= 0 || map.ny <= 0)
		return nullptr;
	const double body = opt.body_radius_m >= 0 ? opt.body_radius_m : robot.body_radius_m;
	try {
		return std::make_unique<CorridorMaps>(map, body + opt.margin_m, opt.corridor_pad_m);
	} catch (const std::invalid_argument &e) {
		notes.push_back(std::string("no corridors: ") + e.what());
		return nullptr;
	}
}

bool has_corridor(const std::string &mode)
{
	return mode == "ground" || mode == "marine" || mode == "flight";
}

// Each phase's corridor along its guess path (notes in p.notes); per phase
// whether the corridor's first and last pieces have boxes.
std::vector<std::array<bool, 2>> add_corridors(MultiPhaseProblem &p, const CorridorMaps &maps)
{
	std::vector<std::array<bool, 2>> ends(p.phases.size(), {false, false});
	for (size_t k = 0; k < p.phases.size(); k++) {
		PhaseSpec &s = p.phases[k];
		if (!has_corridor(s.mode))
			continue;
		std::vector<std::array<double, 3>> path;
		for (const auto &x : s.guess)
			path.push_back({x[0], x[1], s.mode == "flight" ? x[2] : 0.0});
		Corridor c = build_corridor(s.mode, path, maps);
		s.corridor = std::move(c.boxes);
		ends[k] = {c.first_box, c.last_box};
		for (const std::string &n : c.notes)
			p.notes.push_back("phase " + std::to_string(k) + " (" + s.mode + ") corridor: " + n);
	}
	return ends;
}

// The shoreline piece where phase k's corridor ends (ground or water) and
// phase k + 1's begins (the other): the intersection of the two boxes, a
// piece of the shared edge of adjacent clear ground and water cells, within
// half_length of the plan's switch point (x, y) per axis (0: the point).
// False when the boxes do not meet.
bool shore_from_boxes(const CorridorBox &a, const CorridorBox &b, double x, double y, double half_length,
		      SwitchGuard &g)
{
	double lo[2], hi[2], at[2] = {x, y};
	for (int i = 0; i < 2; i++) {
		lo[i] = std::max({a.lo[static_cast<size_t>(i)], b.lo[static_cast<size_t>(i)], at[i] - half_length});
		hi[i] = std::min({a.hi[static_cast<size_t>(i)], b.hi[static_cast<size_t>(i)], at[i] + half_length});
		if (lo[i] > hi[i])
			return false;
	}
	g = SwitchGuard{lo[0], lo[1], hi[0], hi[1], 0};
	g.area = true;
	return true;
}

// The takeoff or landing area (platform_area) over the cells clear at the
// first corridor level whose cell under (x, y) is; the plain area with a
// note if none is (or without corridors).
SwitchGuard clear_platform(const TerrainGrid &map, double x, double y, double half_length, const CorridorMaps *maps,
			   std::vector<std::string> &notes)
{
	if (!maps)
		return platform_area(map, x, y, half_length);
	Cell c = cell_at(map, x, y);
	for (const auto &level : maps->levels())
		if (c.inside && level->clear("ground", c.index % map.nx, c.index / map.nx)) {
			if (level->clearance() < maps->levels().front()->clearance()) {
				char buf[160];
				std::snprintf(buf, sizeof buf, "switch at (%.3g, %.3g): its cell is clear by %.3g m, not %.3g m",
					      x, y, level->clearance(), maps->levels().front()->clearance());
				notes.push_back(buf);
			}
			return platform_area(map, x, y, half_length, level.get());
		}
	return platform_area(map, x, y, half_length);
}

}  // namespace

MultiPhaseProblem smoothing_problem(const RobotParams &robot, const std::vector<Waypoint> &plan,
				    const TerrainGrid &map, const TakeoffLanding &costs, const SmoothOptions &opt)
{
	if (plan.size() < 2)
		throw std::invalid_argument("a plan needs at least two waypoints to smooth");
	for (size_t i = 0; i < plan.size(); i++) {
		std::string m = mode_name(plan[i].mode);
		if (m.empty() || !robot.modes.count(m))
			throw std::invalid_argument("waypoint " + std::to_string(i) + " has mode " +
						    std::to_string(plan[i].mode) + ", which robot " + robot.robot +
						    " does not have");
		for (int k = 0; k < sampled_dim(m); k++)
			if (!std::isfinite(plan[i].state[k]))
				throw std::invalid_argument("waypoint " + std::to_string(i) + " has a non-finite state");
	}
	// Runs of one mode; a switch is a guard pair at one place.
	std::vector<std::pair<size_t, size_t>> runs{{0, 0}};
	for (size_t i = 1; i < plan.size(); i++) {
		if (plan[i].mode == plan[i - 1].mode) {
			runs.back().second = i;
			continue;
		}
		if (!plan[i - 1].guard || !plan[i].guard || !same_place(plan[i - 1], plan[i]))
			throw std::invalid_argument("waypoints " + std::to_string(i - 1) + " and " + std::to_string(i) +
						    " switch mode without a guard pair at one place");
		runs.push_back({i, i});
	}
	auto run_mode = [&](size_t k) { return mode_name(plan[runs[k].first].mode); };
	auto single = [&](size_t k) { return runs[k].first == runs[k].second; };
	// A plan that takes off at its first waypoint (lands at its last) has no
	// ground phase there: its flight starts (ends) hovering above that point.
	const size_t R = runs.size();
	const bool takeoff_first = R > 1 && single(0) && run_mode(0) == "ground" && run_mode(1) == "flight";
	const bool landing_last = R > 1 && single(R - 1) && run_mode(R - 1) == "ground" && run_mode(R - 2) == "flight";
	MultiPhaseProblem p;
	std::vector<size_t> first_phase(R), last_phase(R);
	std::vector<std::pair<size_t, WallGate>> gates;   // phase k and k + 1 meet at a wall
	std::vector<std::pair<size_t, size_t>> vias;      // phase k and k + 1 meet at waypoint i
	for (size_t k = 0; k < R; k++) {
		if ((k == 0 && takeoff_first) || (k + 1 == R && landing_last))
			continue;
		const std::string mode = run_mode(k);
		// The run's sampled states, a flight cut at every wall it crosses.
		std::vector<std::vector<std::vector<double>>> pieces{{sampled(plan[runs[k].first])}};
		for (size_t i = runs[k].first + 1; i <= runs[k].second; i++) {
			std::vector<double> a = sampled(plan[i - 1]), b = sampled(plan[i]);
			if (mode == "flight")
				for (const Crossing &c : wall_crossings(map, a.data(), b.data())) {
					std::vector<double> x(6);
					for (int j = 0; j < 6; j++)
						x[static_cast<size_t>(j)] = a[static_cast<size_t>(j)] + c.t * (b[static_cast<size_t>(j)] - a[static_cast<size_t>(j)]);
					x[2] = std::max(x[2], c.gate.z_min + 0.5);
					pieces.back().push_back(x);
					pieces.push_back({x});
					gates.push_back({p.phases.size() + pieces.size() - 2, c.gate});
				}
			pieces.back().push_back(b);
			if (plan[i].via && i < runs[k].second) {
				pieces.push_back({b});
				vias.push_back({p.phases.size() + pieces.size() - 2, i});
			}
		}
		first_phase[k] = p.phases.size();
		for (const auto &xs : pieces) {
			PhaseSpec s;
			s.mode = mode;
			for (const auto &x : xs)
				s.guess.push_back(full_state(mode, robot, x.data()));
			if (s.guess.size() == 1)
				s.guess.push_back(s.guess[0]);
			int edges = static_cast<int>(xs.size()) - 1;
			s.segments = std::min(opt.max_segments, std::max(opt.min_segments, opt.segments_per_edge * edges));
			if (mode == "flight")
				s.T_guess = flight_time_guess(xs);
			auto b = state_bounds(mode, robot);
			s.first_lo = s.last_lo = b.first;
			s.first_hi = s.last_hi = b.second;
			p.phases.push_back(std::move(s));
		}
		last_phase[k] = p.phases.size() - 1;
	}
	// The plan's ends: fixed, or the hover above a takeoff (landing) point.
	auto hover_above = [&](const Waypoint &w) {
		double xs[6] = {w.state[0], w.state[1], height_at(map, w.state[0], w.state[1]) + 1, 0, 0, 0};
		return full_state("flight", robot, xs);
	};
	const std::unique_ptr<CorridorMaps> maps = corridor_maps(robot, map, opt, p.notes);
	std::vector<std::array<bool, 2>> boxed(p.phases.size(), {false, false});
	if (maps)
		boxed = add_corridors(p, *maps);
	PhaseSpec &head = p.phases.front(), &tail = p.phases.back();
	head.first_lo = head.first_hi = takeoff_first ? hover_above(plan.front()) : head.guess.front();
	tail.last_lo = tail.last_hi = landing_last ? hover_above(plan.back()) : tail.guess.back();
	p.switch_cost += (takeoff_first ? costs.takeoff_j : 0) + (landing_last ? costs.landing_j : 0);
	for (const auto &g : gates)
		join_gate(p, g.first, robot, g.second);
	for (const auto &v : vias)
		join_via(p, v.first, robot, plan[v.second].state);
	for (size_t k = 0; k + 1 < R; k++) {
		if ((k == 0 && takeoff_first) || (k + 2 == R && landing_last))
			continue;
		const Waypoint &g = plan[runs[k].second];
		const std::string a = run_mode(k), b = run_mode(k + 1);
		SwitchGuard guard;
		// Phases joined at this switch: the last of run k, the first of run k + 1.
		if (first_phase[k + 1] != last_phase[k] + 1)
			throw std::logic_error("smoothing_problem: phases out of order");
		const size_t ka = last_phase[k], kb = first_phase[k + 1];
		if ((a == "ground" && b == "marine") || (a == "marine" && b == "ground")) {
			bool boxes = boxed[ka][1] && boxed[kb][0] &&
				     shore_from_boxes(p.phases[ka].corridor.back(), p.phases[kb].corridor.front(), g.state[0],
						      g.state[1], opt.guard_half_length_m, guard);
			if (!boxes) {
				guard = shoreline_guard(map, g.state[0], g.state[1], opt.guard_half_length_m);
				if (maps)
					p.notes.push_back("switch " + std::to_string(ka) + " -> " + std::to_string(kb) +
							  ": the corridors do not meet at the shore; the fitted shoreline instead");
			}
		} else {   // takeoff or landing: where the robot is on the ground
			const Waypoint &ground = a == "ground" ? g : plan[runs[k + 1].first];
			guard = clear_platform(map, ground.state[0], ground.state[1], opt.guard_half_length_m, maps.get(),
					       p.notes);
		}
		join_phases(p, last_phase[k], robot, guard, costs);
	}
	return p;
}

std::vector<Waypoint> straightened(const std::vector<Waypoint> &plan)
{
	std::vector<Waypoint> out = plan;
	size_t i0 = 0;
	while (i0 < plan.size()) {
		size_t i1 = i0;
		while (i1 + 1 < plan.size() && plan[i1 + 1].mode == plan[i0].mode)
			i1++;
		const Waypoint &a = plan[i0], &b = plan[i1];
		bool flight = mode_name(a.mode) == "flight";
		int np = flight ? 3 : 2;
		for (size_t i = i0 + 1; i < i1; i++) {
			double f = static_cast<double>(i - i0) / static_cast<double>(i1 - i0);
			for (int k = 0; k < np; k++)
				out[i].state[k] = a.state[k] + f * (b.state[k] - a.state[k]);
			if (!flight && std::hypot(b.state[0] - a.state[0], b.state[1] - a.state[1]) > 1e-9)
				out[i].state[3] = std::atan2(b.state[1] - a.state[1], b.state[0] - a.state[0]);
		}
		i0 = i1 + 1;
	}
	return out;
}

namespace {

// The smoother's solver options: smoothing_solve_options() with opt's Ipopt
// options, and with the full optimization's own ones if full.
SolveOptions solver_options(const SmoothOptions &opt, bool full)
{
	SolveOptions so = smoothing_solve_options();
	so.ipopt_options = opt.ipopt_options;
	if (full)
		so.ipopt_options.insert(so.ipopt_options.end(), opt.full_ipopt_options.begin(),
					opt.full_ipopt_options.end());
	so.debug = std::getenv("HYLO_TRAINER_DEBUG") != nullptr;
	return so;
}

// The straightened copy's problem with the plan's own corridors: the
// straight line between a run's ends may cross water or rock, the plan's
// path does not (when both have the same phases: a flight's wall cuts may
// differ).
void keep_corridors(MultiPhaseProblem &straight, const MultiPhaseProblem &own)
{
	if (straight.phases.size() != own.phases.size())
		return;
	for (size_t k = 0; k < own.phases.size(); k++)
		if (straight.phases[k].mode != own.phases[k].mode)
			return;
	for (size_t k = 0; k < own.phases.size(); k++)
		straight.phases[k].corridor = own.phases[k].corridor;
	straight.notes = own.notes;
}

}  // namespace

namespace {

// The fraction of the time of samples `times` (normalized, increasing) at
// which the polyline through `path` has covered fraction f of its length.
double time_at_fraction(const std::vector<std::array<double, 3>> &path, const std::vector<double> &times, double f)
{
	std::vector<double> at(path.size(), 0.0);
	for (size_t i = 1; i < path.size(); i++)
		at[i] = at[i - 1] + std::sqrt(std::pow(path[i][0] - path[i - 1][0], 2) +
					      std::pow(path[i][1] - path[i - 1][1], 2) + std::pow(path[i][2] - path[i - 1][2], 2));
	const double s = f * at.back();
	for (size_t i = 1; i < path.size(); i++)
		if (at[i] >= s) {
			const double d = at[i] - at[i - 1];
			return d > 0 ? times[i - 1] + (times[i] - times[i - 1]) * (s - at[i - 1]) / d : times[i - 1];
		}
	return times.back();
}

// The problem again from its solution s: every phase starts at s (its
// knots and midpoints), and each flight's corridor is rebuilt along s's
// path and timed by s's own times, so s lies in it. The first corridor
// followed the plan's path and its timing, which may hold a flight back
// from a cheaper way over an edge (a new box holds what the old one cut
// off). False when no flight's corridor changed.
bool around_solution(MultiPhaseProblem &q, const MultiPhaseSolution &s, const CorridorMaps &maps)
{
	bool changed = false;
	for (size_t k = 0; k < q.phases.size() && k < s.phases.size(); k++) {
		PhaseSpec &ps = q.phases[k];
		const Trajectory &tr = s.phases[k].traj;
		const size_t nx = static_cast<size_t>(tr.nx), n = tr.t.size();
		if (n < 2 || s.phases[k].T <= 0)
			return false;
		ps.guess.clear();
		std::vector<std::array<double, 3>> path;
		std::vector<double> times;
		for (size_t i = 0; i < n; i++) {
			const double *x = &tr.x[i * nx];
			ps.guess.emplace_back(x, x + nx);
			path.push_back({x[0], x[1], ps.mode == "flight" ? x[2] : 0.0});
			times.push_back(std::min(1.0, std::max(0.0, tr.t[i] / s.phases[k].T)));
		}
		ps.guess_timed = true;
		ps.T_guess = s.phases[k].T;
		ps.segments = s.phases[k].segments;
		if (ps.mode != "flight" || ps.corridor.empty())
			continue;
		Corridor c = build_corridor("flight", path, maps);
		if (!c.notes.empty() || !c.first_box || !c.last_box)
			continue;   // keep the old boxes rather than get less clearance
		for (CorridorBox &b : c.boxes) {
			b.tau0 = b.tau0 <= 0 ? 0 : time_at_fraction(path, times, b.tau0);
			b.tau1 = b.tau1 >= 1 ? 1 : std::max(b.tau0, time_at_fraction(path, times, b.tau1));
		}
		ps.corridor = std::move(c.boxes);
		changed = true;
	}
	q.T_scales = {1.0};
	return changed;
}

// Rounds of around_solution while each converges and saves more than 0.1%
// (at most 8; on chasm_070 each saved about 20 J, 0.45%, for 20-30 s):
// prob and s become the better ones.
void refine_corridors(const RobotParams &robot, const TerrainGrid &map, const SmoothOptions &opt,
		      MultiPhaseProblem &prob, MultiPhaseSolution &s)
{
	std::vector<std::string> notes;
	const std::unique_ptr<CorridorMaps> maps = corridor_maps(robot, map, opt, notes);
	if (!maps)
		return;
	for (int round = 0; round < 8; round++) {
		MultiPhaseProblem q = prob;
		MultiPhaseSolution r;
		try {
			if (!around_solution(q, s, *maps))
				return;
			r = solve_multiphase(robot, q, solver_options(opt, true));
		} catch (const std::invalid_argument &) {   // s stands
			return;
		}
		s.solve_seconds += r.solve_seconds;
		if (!r.converged || !(r.cost < s.cost))
			return;
		const bool more = r.cost < s.cost * (1 - 1e-3);
		r.solve_seconds = s.solve_seconds;
		char buf[120];
		std::snprintf(buf, sizeof buf, "flight corridors rebuilt along the solution: %.1f J -> %.1f J", s.cost, r.cost);
		r.notes = s.notes;
		r.notes.push_back(buf);
		s = std::move(r);
		prob = std::move(q);
		if (!more)
			return;
	}
}

}  // namespace

MultiPhaseSolution smooth_plan(const RobotParams &robot, const std::vector<Waypoint> &plan,
			       const TerrainGrid &map, const TakeoffLanding &costs, const SmoothOptions &opt,
			       const std::vector<double> &T_scales, bool *from_straightened)
{
	MultiPhaseSolution s;
	double seconds = 0, rejected = std::numeric_limits<double>::infinity();
	std::string why;
	const MultiPhaseProblem own = smoothing_problem(robot, plan, map, costs, opt);
	for (int attempt = 0; attempt < 2; attempt++) {
		MultiPhaseProblem prob = attempt ? smoothing_problem(robot, straightened(plan), map, costs, opt) : own;
		if (attempt)
			keep_corridors(prob, own);
		if (!T_scales.empty())
			prob.T_scales = T_scales;
		s = solve_multiphase(robot, prob, solver_options(opt, true));
		seconds += s.solve_seconds;
		s.solve_seconds = seconds;
		rejected = std::min(rejected, s.rejected_cost);
		if (from_straightened)
			*from_straightened = attempt == 1;
		if (s.converged) {
			refine_corridors(robot, map, opt, prob, s);
			break;
		}
		why += attempt ? "; straightened: " + s.status_text + (s.rejection.empty() ? "" : " (" + s.rejection + ")")
			       : s.rejection;
	}
	if (!s.converged) {
		s.rejection = why;
		s.rejected_cost = rejected;
	}
	return s;
}

const char *method_name(SmoothMethod m)
{
	switch (m) {
	case SmoothMethod::Full: return "full";
	case SmoothMethod::Straightened: return "straightened";
	case SmoothMethod::FinerMesh: return "finer mesh";
	case SmoothMethod::PhaseByPhase: return "phase by phase";
	case SmoothMethod::GraphPath: return "graph path";
	case SmoothMethod::ViaPoints: return "via points";
	}
	return "?";
}

namespace {

// Appends phase solution ph (mode m) to a joined trajectory.
void append_phase(MultiPhaseSolution &out, const std::string &m, Solution ph)
{
	out.modes.push_back(m);
	out.cost += ph.cost;
	out.T += ph.T;
	out.replay_cost += ph.replay_cost;
	out.replay_error = std::max(out.replay_error, ph.replay_error);
	out.phases.push_back(std::move(ph));
}

std::string why_not(const MultiPhaseSolution &s)
{
	return s.status_text + (s.rejection.empty() ? "" : " (" + s.rejection + ")");
}

// Every component of a knot's bounds [lo, hi] not fixed yet, fixed to x.
void fix_free(std::vector<double> &lo, std::vector<double> &hi, const std::vector<double> &x)
{
	for (size_t c = 0; c < lo.size() && c < x.size(); c++)
		if (lo[c] != hi[c])
			lo[c] = hi[c] = std::min(std::max(x[c], lo[c]), hi[c]);
}

// The phase-by-phase step: the plan's problem with its switch points pinned
// to the plan's guard points, every phase then solved alone from the switch
// states the plan has there (what the joins leave free of a switch knot is
// fixed to the plan's state, so consecutive phases still meet).
MultiPhaseSolution phase_by_phase(const RobotParams &robot, const std::vector<Waypoint> &plan,
				  const TerrainGrid &map, const TakeoffLanding &costs, const SmoothOptions &opt)
{
	SmoothOptions pinned = opt;
	pinned.guard_half_length_m = 0;
	MultiPhaseProblem p = smoothing_problem(robot, plan, map, costs, pinned);
	SolveOptions so = solver_options(opt, false);
	MultiPhaseSolution out;
	out.converged = true;
	for (size_t k = 0; k < p.phases.size(); k++) {
		PhaseSpec s = p.phases[k];
		auto b = state_bounds(s.mode, robot);
		if (s.first_lo.empty()) s.first_lo = b.first, s.first_hi = b.second;
		if (s.last_lo.empty()) s.last_lo = b.first, s.last_hi = b.second;
		if (k > 0)
			fix_free(s.first_lo, s.first_hi, s.guess.front());
		if (k + 1 < p.phases.size())
			fix_free(s.last_lo, s.last_hi, s.guess.back());
		MultiPhaseProblem q;
		q.phases = {s};
		q.T_scales = p.T_scales;
		MultiPhaseSolution r = solve_multiphase(robot, q, so);
		out.solve_seconds += r.solve_seconds;
		if (!r.converged) {
			out.converged = false;
			out.status_text = "phase " + std::to_string(k) + " (" + s.mode + ") alone: " + r.status_text;
			out.rejection = r.rejection;
			return out;
		}
		append_phase(out, s.mode, std::move(r.phases[0]));
	}
	out.cost += p.switch_cost;
	out.replay_cost += p.switch_cost;
	return out;
}

// The via points step: the full problem, made to pass through the plan's
// inner waypoint nearest to where its trajectory leaves the domain, one more
// per solve while it still does (up to kMaxVia). Not converged when a solve
// fails or the waypoints run out.
MultiPhaseSolution via_points(const RobotParams &robot, const std::vector<Waypoint> &plan, const TerrainGrid &map,
			      const TakeoffLanding &costs, const SmoothOptions &opt, DomainCheck d)
{
	constexpr int kMaxVia = 8;
	std::vector<Waypoint> p = plan;
	const SolveOptions so = solver_options(opt, false);
	double seconds = 0;
	std::string added;
	MultiPhaseSolution s;
	for (int n = 0;; n++) {
		if (n > 0) {
			s = solve_multiphase(robot, smoothing_problem(robot, p, map, costs, opt), so);
			seconds += s.solve_seconds;
			s.solve_seconds = seconds;
			if (!s.converged) {
				s.status_text = "through" + added + ": " + s.status_text;
				return s;
			}
			d = domain_check(s, map);
			if (d.worst_m <= domain_tolerance_m(map))
				return s;
		}
		// The inner waypoint of a run of the offending mode nearest to the violation.
		size_t best = 0;
		double best_d = std::numeric_limits<double>::infinity();
		for (size_t i = 1; i + 1 < p.size(); i++) {
			if (p[i].via || p[i].guard || p[i].mode != p[i - 1].mode || p[i].mode != p[i + 1].mode ||
			    mode_name(p[i].mode) != d.mode)
				continue;
			double di = std::hypot(p[i].state[0] - d.x_m, p[i].state[1] - d.y_m);
			if (di < best_d) {
				best_d = di;
				best = i;
			}
		}
		if (best == 0 || n == kMaxVia) {
			s.converged = false;
			s.status_text = added.empty() ? "no waypoint near where it leaves the domain"
						      : "through" + added + " still leaves the domain";
			s.rejection = "domain: " + d.text();
			s.rejected_cost = std::numeric_limits<double>::infinity();
			return s;
		}
		p[best].via = true;
		added += " " + std::to_string(best);
	}
}

}  // namespace

MultiPhaseSolution graph_path_trajectory(const RobotParams &robot, const std::vector<Waypoint> &plan,
					 const TakeoffLanding &costs, const SolveOptions &opt)
{
	SolveOptions edge_opt = opt;
	edge_opt.strategy_starts = true;
	MultiPhaseSolution out;
	out.converged = true;
	for (size_t i = 1; i < plan.size(); i++) {
		const Waypoint &a = plan[i - 1], &b = plan[i];
		std::string ma = mode_name(a.mode), mb = mode_name(b.mode);
		if (ma != mb) {   // a guard pair: the switch itself
			double c = ma == "ground" && mb == "flight" ? costs.takeoff_j
				 : ma == "flight" && mb == "ground" ? costs.landing_j : 0;
			out.cost += c;
			out.replay_cost += c;
			continue;
		}
		std::vector<double> xa = sampled(a), xb = sampled(b);
		Solution s = solve_bvp(ma, robot, xa.data(), xb.data(), edge_opt);
		out.solve_seconds += s.solve_seconds;
		if (!s.converged) {
			out.converged = false;
			out.status_text = "edge " + std::to_string(i - 1) + " -> " + std::to_string(i) + " (" + ma +
					  "): " + s.status_text;
			if (s.replayed && !s.replay_ok)
				out.rejection = replay_verdict(s);
			return out;
		}
		append_phase(out, ma, std::move(s));
	}
	if (out.phases.empty()) {
		out.converged = false;
		out.status_text = "the plan has no edge to follow";
	}
	return out;
}

namespace {

// Distance from (x, y) to the nearest cell of terrain class cls within
// reach (infinity if none): 0 on such a cell.
double distance_to_class(const TerrainGrid &m, double x, double y, int8_t cls, double reach)
{
	Cell c = cell_at(m, x, y);
	if (!c.inside)
		return std::numeric_limits<double>::infinity();
	if (m.terrain[static_cast<size_t>(c.index)] == cls)
		return 0;
	const int cx = c.index % m.nx, cy = c.index / m.nx;
	const int span = static_cast<int>(std::ceil(reach / m.resolution_m)) + 1;
	double best = std::numeric_limits<double>::infinity();
	for (int iy = std::max(0, cy - span); iy <= std::min(m.ny - 1, cy + span); iy++)
		for (int ix = std::max(0, cx - span); ix <= std::min(m.nx - 1, cx + span); ix++) {
			if (m.terrain[static_cast<size_t>(iy * m.nx + ix)] != cls)
				continue;
			double x0 = m.origin_x_m + ix * m.resolution_m, y0 = m.origin_y_m + iy * m.resolution_m;
			double dx = std::max({x0 - x, 0.0, x - (x0 + m.resolution_m)});
			double dy = std::max({y0 - y, 0.0, y - (y0 + m.resolution_m)});
			best = std::min(best, std::hypot(dx, dy));
		}
	return best;
}

}  // namespace

double domain_tolerance_m(const TerrainGrid &map)
{
	return map.resolution_m;
}

DomainCheck domain_check(const MultiPhaseSolution &s, const TerrainGrid &map)
{
	DomainCheck d;
	if (map.nx <= 0 || map.ny <= 0)
		return d;
	const double reach = 4 * domain_tolerance_m(map);
	double t0 = 0;
	for (size_t k = 0; k < s.phases.size(); k++) {
		const Trajectory &tr = s.phases[k].traj;
		const std::string &mode = s.modes[k];
		const bool planar = mode == "ground" || mode == "marine";
		if (planar || mode == "flight")
			for (size_t i = 0; i < tr.t.size(); i++) {
				const double *x = &tr.x[i * static_cast<size_t>(tr.nx)];
				double out;
				if (planar) {
					out = distance_to_class(map, x[0], x[1], mode == "ground" ? kGround : kWater, reach);
				} else {
					Cell c = cell_at(map, x[0], x[1]);
					out = c.inside ? std::max(0.0, map.height_m[static_cast<size_t>(c.index)] - x[2])
						       : std::numeric_limits<double>::infinity();
				}
				if (out > d.worst_m) {
					d = {out, static_cast<int>(k), mode, t0 + tr.t[i], x[0], x[1], reach};
				}
			}
		t0 += s.phases[k].T;
	}
	return d;
}

std::string DomainCheck::text() const
{
	if (phase < 0)
		return "inside its domain";
	char buf[200];
	const char *what = mode == "ground" ? "m from ground" : mode == "marine" ? "m from water" : "m below the terrain";
	if (std::isfinite(worst_m))
		std::snprintf(buf, sizeof buf, "phase %d (%s) at t = %.3g s, (%.3g, %.3g) m: %.3g %s", phase, mode.c_str(),
			      t_s, x_m, y_m, worst_m, what);
	else   // off the map, or farther than domain_check looks
		std::snprintf(buf, sizeof buf, "phase %d (%s) at t = %.3g s, (%.3g, %.3g) m: off the map or over %.3g %s",
			      phase, mode.c_str(), t_s, x_m, y_m, reach_m, what);
	return buf;
}

SmoothResult smooth_with_fallbacks(const RobotParams &robot, const std::vector<Waypoint> &plan,
				   const TerrainGrid &map, const TakeoffLanding &costs, const SmoothOptions &opt)
{
	SmoothResult r;
	DomainCheck left;   // where the last full-problem solution left the domain (phase -1: none did)
	auto take = [&](SmoothMethod m, MultiPhaseSolution s) {
		r.seconds += s.solve_seconds;
		const bool full_problem = m == SmoothMethod::Full || m == SmoothMethod::FinerMesh;
		if (full_problem)
			r.lowest_cost = std::min(r.lowest_cost, s.rejected_cost);
		if (!s.converged) {
			r.rejections.push_back(std::string(method_name(m)) + ": " + why_not(s));
			return false;
		}
		DomainCheck d = domain_check(s, map);
		if (d.worst_m > domain_tolerance_m(map)) {
			char tol[64];
			std::snprintf(tol, sizeof tol, " > tolerance %.3g m", domain_tolerance_m(map));
			r.rejections.push_back(std::string(method_name(m)) + ": domain: " + d.text() + tol);
			if (full_problem) {
				r.lowest_cost = std::min(r.lowest_cost, s.cost);
				left = d;
			}
			return false;
		}
		r.ok = true;
		r.method = m;
		r.solution = std::move(s);
		return true;
	};
	auto step = [&](SmoothMethod m, auto &&solve) {
		try {
			return take(m, solve());
		} catch (const std::invalid_argument &e) {   // the step cannot pose its problem
			r.rejections.push_back(std::string(method_name(m)) + ": " + e.what());
			return false;
		}
	};
	bool straight = false;
	if (step(SmoothMethod::Full, [&] { return smooth_plan(robot, plan, map, costs, opt, {}, &straight); })) {
		if (straight)
			r.method = SmoothMethod::Straightened;
		return r;
	}
	// A full solution that replayed but left the domain gains nothing from a
	// finer mesh: straight to the via points.
	if (left.phase < 0 && step(SmoothMethod::FinerMesh, [&] {
		    SmoothOptions fine = opt;
		    fine.segments_per_edge *= 2;
		    fine.min_segments *= 2;
		    fine.max_segments *= 2;
		    MultiPhaseProblem prob = smoothing_problem(robot, plan, map, costs, fine);
		    return solve_multiphase(robot, prob, solver_options(opt, true));
	    }))
		return r;
	// Via points start where a full solution left the domain; without one
	// they would only repeat the full optimization.
	if (left.phase >= 0 && step(SmoothMethod::ViaPoints, [&] { return via_points(robot, plan, map, costs, opt, left); }))
		return r;
	if (step(SmoothMethod::PhaseByPhase, [&] { return phase_by_phase(robot, plan, map, costs, opt); }))
		return r;
	if (step(SmoothMethod::GraphPath,
		 [&] { return graph_path_trajectory(robot, plan, costs, solver_options(opt, false)); }))
		return r;
	r.failure = r.rejections.back().substr(std::string(method_name(SmoothMethod::GraphPath)).size() + 2);
	return r;
}

AlternativesChoice smooth_alternatives(const RobotParams &robot, const std::vector<PlanAlternative> &alternatives,
				       const TerrainGrid &map, const TakeoffLanding &costs, const SmoothOptions &opt,
				       const AlternativesBudget &budget)
{
	AlternativesChoice c;
	const auto t0 = std::chrono::steady_clock::now();
	int smoothed = 0;
	for (const PlanAlternative &a : alternatives) {
		AlternativeOutcome o;
		const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
		char why[128] = "";
		if (smoothed >= std::max(1, budget.max_count))
			std::snprintf(why, sizeof why, "not smoothed: %d alternative%s smoothed already (the count budget)",
				      smoothed, smoothed == 1 ? "" : "s");
		else if (smoothed > 0 && budget.seconds > 0 && elapsed >= budget.seconds)
			std::snprintf(why, sizeof why, "not smoothed: %.1f s spent already, budget %.4g s", elapsed,
				      budget.seconds);
		if (why[0]) {
			o.skipped = why;
		} else {
			o.smoothed = true;
			o.result = smooth_with_fallbacks(robot, a.plan, map, costs, opt);
			smoothed++;
			const int k = static_cast<int>(c.outcomes.size());
			if (o.result.ok && (c.chosen < 0 ||
					    o.result.solution.cost < c.outcomes[static_cast<size_t>(c.chosen)].result.solution.cost))
				c.chosen = k;
		}
		c.outcomes.push_back(std::move(o));
	}
	return c;
}

SolveOptions smoothing_solve_options()
{
	SolveOptions o;
	o.replay_state_tol = 0.05;
	// Up to four mesh doublings where a phase's replay disagrees: long ground
	// phases drift open loop and need 384 segments or more (with two, 2 of 20
	// generated Ambot scenes fell back to a finer mesh, slower).
	o.refinements = 4;
	o.max_step_s = 0.04;
	o.step_max_iter = 1000;
	o.objective_scale = 100;
	return o;
}

double graph_path_cost(const RobotParams &robot, const std::vector<Waypoint> &plan, const TakeoffLanding &costs,
		       const SolveOptions &opt)
{
	SolveOptions edge_opt = opt;
	edge_opt.strategy_starts = true;
	double sum = 0;
	for (size_t i = 1; i < plan.size(); i++) {
		const Waypoint &a = plan[i - 1], &b = plan[i];
		std::string ma = mode_name(a.mode), mb = mode_name(b.mode);
		if (ma != mb) {
			if (ma == "ground" && mb == "flight")
				sum += costs.takeoff_j;
			else if (ma == "flight" && mb == "ground")
				sum += costs.landing_j;
			continue;
		}
		std::vector<double> xa = sampled(a), xb = sampled(b);
		Solution s = solve_bvp(ma, robot, xa.data(), xb.data(), edge_opt);
		if (!s.converged)
			return std::numeric_limits<double>::infinity();
		sum += s.cost;
	}
	return sum;
}

}  // namespace hylo::trainer
