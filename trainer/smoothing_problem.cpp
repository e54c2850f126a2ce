#include "trainer/smoothing_problem.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "hylo/features.h"
#include "trainer/map_guards.hpp"

namespace hylo::trainer {

std::vector<double> sampled(const Waypoint &w)
{
	const hylo_mode_desc *d = hylo_mode_describe(w.mode);
	return std::vector<double>(w.state, w.state + (d ? d->xs_dim : 0));
}

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
	try {
		return std::make_unique<CorridorMaps>(map, robot.body_radius_m + opt.margin_m, opt.corridor_pad_m);
	} catch (const std::invalid_argument &e) {
		notes.push_back(std::string("no corridors: ") + e.what());
		return nullptr;
	}
}

namespace {

double norm3(double x, double y, double z)
{
	return std::sqrt(x * x + y * y + z * z);
}

bool same_place(const Waypoint &a, const Waypoint &b)
{
	return std::hypot(a.state[0] - b.state[0], a.state[1] - b.state[1]) < 1e-6;
}

double height_at(const TerrainGrid &m, double x, double y)
{
	GridCell c = cell_at(m, x, y);
	if (!c.inside)
		throw std::invalid_argument("the point (" + std::to_string(x) + ", " + std::to_string(y) +
					    ") is off the map");
	return m.height_m[static_cast<size_t>(c.index)];
}

// Every waypoint in a mode of the robot, with finite sampled coordinates.
void check_waypoints(const RobotParams &robot, const std::vector<Waypoint> &plan)
{
	if (plan.size() < 2)
		throw std::invalid_argument("a plan needs at least two waypoints to smooth");
	for (size_t i = 0; i < plan.size(); i++) {
		const hylo_mode_desc *d = hylo_mode_describe(plan[i].mode);
		if (!d || !robot.has(plan[i].mode))
			throw std::invalid_argument("waypoint " + std::to_string(i) + " has mode " +
						    std::to_string(static_cast<int>(plan[i].mode)) + ", which robot " +
						    robot.robot + " does not have");
		for (int k = 0; k < d->xs_dim; k++)
			if (!std::isfinite(plan[i].state[k]))
				throw std::invalid_argument("waypoint " + std::to_string(i) + " has a non-finite state");
	}
}

// Waypoints first..last of a plan, all in one mode.
struct Run {
	size_t first = 0, last = 0;
	hylo_mode mode;
	bool single() const { return first == last; }
};

// The plan's runs of one mode; a switch is a guard pair at one place.
std::vector<Run> mode_runs(const std::vector<Waypoint> &plan)
{
	std::vector<Run> runs{{0, 0, plan[0].mode}};
	for (size_t i = 1; i < plan.size(); i++) {
		if (plan[i].mode == plan[i - 1].mode) {
			runs.back().last = i;
			continue;
		}
		if (!plan[i - 1].guard || !plan[i].guard || !same_place(plan[i - 1], plan[i]))
			throw std::invalid_argument("waypoints " + std::to_string(i - 1) + " and " + std::to_string(i) +
						    " switch mode without a guard pair at one place");
		runs.push_back({i, i, plan[i].mode});
	}
	return runs;
}

// The problem under construction: the plan's runs, the phases made of them
// and where they are to be joined.
struct Layout {
	std::vector<Run> runs;
	// A plan that takes off at its first waypoint (lands at its last) has no
	// ground phase there: its flight starts (ends) hovering above that point.
	bool takeoff_first = false, landing_last = false;
	MultiPhaseProblem p;
	std::vector<size_t> first_phase, last_phase;      // of each run
	std::vector<std::pair<size_t, WallGate>> gates;   // phase k and k + 1 meet at a wall
	std::vector<std::pair<size_t, size_t>> vias;      // phase k and k + 1 meet at waypoint i
	std::vector<std::array<bool, 2>> boxed;           // per phase: its corridor's first and last pieces have boxes

	// Run k is a hover end, with no phase of its own.
	bool hovered(size_t k) const
	{
		return (k == 0 && takeoff_first) || (k + 1 == runs.size() && landing_last);
	}
};

// A phase's sampled states.
using Piece = std::vector<std::vector<double>>;

// Run r's sampled states, cut into pieces (a phase each) at every wall a
// flight crosses and at its via points; the cuts go to l.gates and l.vias
// (phases numbered on from l.p's).
std::vector<Piece> cut_run(const std::vector<Waypoint> &plan, const Run &r, const TerrainGrid &map, Layout &l)
{
	std::vector<Piece> pieces{{sampled(plan[r.first])}};
	for (size_t i = r.first + 1; i <= r.last; i++) {
		std::vector<double> a = sampled(plan[i - 1]), b = sampled(plan[i]);
		if (mode_desc(r.mode).air)   // flights are cut at the walls they cross
			for (const WallCrossing &c : wall_crossings(map, a.data(), b.data())) {
				std::vector<double> x(6);
				for (int j = 0; j < 6; j++)
					x[static_cast<size_t>(j)] = a[static_cast<size_t>(j)] + c.t * (b[static_cast<size_t>(j)] - a[static_cast<size_t>(j)]);
				x[2] = std::max(x[2], c.gate.z_min + 0.5);
				pieces.back().push_back(x);
				pieces.push_back({x});
				l.gates.push_back({l.p.phases.size() + pieces.size() - 2, c.gate});
			}
		pieces.back().push_back(b);
		if (plan[i].via && i < r.last) {
			pieces.push_back({b});
			l.vias.push_back({l.p.phases.size() + pieces.size() - 2, i});
		}
	}
	return pieces;
}

// A duration guess for a phase through sampled states: ground and marine
// leave it to the solver (path length / typical speed); flight edges take
// their length over their mean speed, at least 1 m/s (flights of tens of
// metres at 8 m/s would otherwise be guessed at 3 m/s, with a mesh twice as
// fine as they need).
double flight_time_guess(const Piece &xs)
{
	double T = 0;
	for (size_t i = 1; i < xs.size(); i++) {
		const double *a = xs[i - 1].data(), *b = xs[i].data();
		double d = norm3(b[0] - a[0], b[1] - a[1], b[2] - a[2]);
		T += d / std::max(1.0, 0.5 * (norm3(a[3], a[4], a[5]) + norm3(b[3], b[4], b[5])));
	}
	return std::max(0.2, T);
}

// The phase of mode through the states xs: its guess runs through them, its
// segments per edge of the plan, its end knots within the mode's bounds.
PhaseSpec phase_through(hylo_mode mode, const RobotParams &robot, const Piece &xs, const SmoothOptions &opt)
{
	PhaseSpec s;
	s.mode = mode;
	for (const auto &x : xs)
		s.guess.push_back(full_state(mode, robot, x.data()));
	if (s.guess.size() == 1)
		s.guess.push_back(s.guess[0]);
	int edges = static_cast<int>(xs.size()) - 1;
	s.segments = std::min(opt.max_segments, std::max(opt.min_segments, opt.segments_per_edge * edges));
	if (mode_desc(mode).air)
		s.T_guess = flight_time_guess(xs);
	auto b = state_bounds(mode, robot);
	s.first_lo = s.last_lo = b.first;
	s.first_hi = s.last_hi = b.second;
	return s;
}

// The plan's runs and their phases, in order (none for a hover end).
Layout lay_out_phases(const RobotParams &robot, const std::vector<Waypoint> &plan, const TerrainGrid &map,
		      const SmoothOptions &opt)
{
	Layout l;
	l.runs = mode_runs(plan);
	const std::vector<Run> &runs = l.runs;
	const size_t R = runs.size();
	l.takeoff_first = R > 1 && runs[0].single() && runs[0].mode == HYLO_MODE_GROUND && runs[1].mode == HYLO_MODE_FLIGHT;
	l.landing_last = R > 1 && runs[R - 1].single() && runs[R - 1].mode == HYLO_MODE_GROUND && runs[R - 2].mode == HYLO_MODE_FLIGHT;
	l.first_phase.resize(R);
	l.last_phase.resize(R);
	for (size_t k = 0; k < R; k++) {
		if (l.hovered(k))
			continue;
		const std::vector<Piece> pieces = cut_run(plan, runs[k], map, l);
		l.first_phase[k] = l.p.phases.size();
		for (const Piece &xs : pieces)
			l.p.phases.push_back(phase_through(runs[k].mode, robot, xs, opt));
		l.last_phase[k] = l.p.phases.size() - 1;
	}
	l.boxed.assign(l.p.phases.size(), {false, false});
	return l;
}

// Modes that move in the map's work space (not a phase plane) have corridors.
bool has_corridor(hylo_mode mode)
{
	const hylo_mode_desc &d = mode_desc(mode);
	return d.planar || d.air;
}

// Each phase's corridor along its guess path (notes in the problem's notes),
// and whether its first and last pieces have boxes.
void add_corridors(Layout &l, const CorridorMaps &maps)
{
	MultiPhaseProblem &p = l.p;
	for (size_t k = 0; k < p.phases.size(); k++) {
		PhaseSpec &s = p.phases[k];
		if (!has_corridor(s.mode))
			continue;
		std::vector<std::array<double, 3>> path;
		for (const auto &x : s.guess)
			path.push_back({x[0], x[1], mode_desc(s.mode).air ? x[2] : 0.0});
		Corridor c = build_corridor(s.mode, path, maps);
		s.corridor = std::move(c.boxes);
		l.boxed[k] = {c.first_box, c.last_box};
		for (const std::string &n : c.notes)
			p.notes.push_back("phase " + std::to_string(k) + " (" + hylo_mode_str(s.mode) + ") corridor: " + n);
	}
}

// The plan's ends: fixed at its first and last states, or the hover above a
// takeoff (landing) point, whose switching cost is added.
void hold_ends(Layout &l, const RobotParams &robot, const std::vector<Waypoint> &plan, const TerrainGrid &map,
	       const TakeoffLanding &costs)
{
	auto hover_above = [&](const Waypoint &w) {
		double xs[6] = {w.state[0], w.state[1], height_at(map, w.state[0], w.state[1]) + 1, 0, 0, 0};
		return full_state(HYLO_MODE_FLIGHT, robot, xs);
	};
	PhaseSpec &head = l.p.phases.front(), &tail = l.p.phases.back();
	head.first_lo = head.first_hi = l.takeoff_first ? hover_above(plan.front()) : head.guess.front();
	tail.last_lo = tail.last_hi = l.landing_last ? hover_above(plan.back()) : tail.guess.back();
	l.p.switch_cost += (l.takeoff_first ? costs.takeoff_j : 0) + (l.landing_last ? costs.landing_j : 0);
}

// Joins the phases where a wall or a via point cut a run in two.
void join_cuts(Layout &l, const RobotParams &robot, const std::vector<Waypoint> &plan)
{
	for (const auto &g : l.gates)
		join_gate(l.p, g.first, robot, g.second);
	for (const auto &v : l.vias)
		join_via(l.p, v.first, robot, plan[v.second].state);
}

// The guard of the switch from run k to run k + 1: for a shore, the piece
// where their corridors meet, else the fitted shoreline; for a takeoff or
// landing, the clear level ground around the robot's place on the ground.
SwitchGuard switch_guard(Layout &l, size_t k, const std::vector<Waypoint> &plan, const TerrainGrid &map,
			 const SmoothOptions &opt, const CorridorMaps *maps)
{
	const Waypoint &g = plan[l.runs[k].last];
	const hylo_mode a = l.runs[k].mode, b = l.runs[k + 1].mode;
	const size_t ka = l.last_phase[k], kb = l.first_phase[k + 1];
	SwitchGuard guard;
	if ((a == HYLO_MODE_GROUND && b == HYLO_MODE_MARINE) || (a == HYLO_MODE_MARINE && b == HYLO_MODE_GROUND)) {
		bool boxes = l.boxed[ka][1] && l.boxed[kb][0] &&
			     shore_from_boxes(l.p.phases[ka].corridor.back(), l.p.phases[kb].corridor.front(), g.state[0],
					      g.state[1], opt.guard_half_length_m, guard);
		if (!boxes) {
			guard = shoreline_guard(map, g.state[0], g.state[1], opt.guard_half_length_m);
			if (maps)
				l.p.notes.push_back("switch " + std::to_string(ka) + " -> " + std::to_string(kb) +
						    ": the corridors do not meet at the shore; the fitted shoreline instead");
		}
	} else {   // takeoff or landing: where the robot is on the ground
		const Waypoint &ground = a == HYLO_MODE_GROUND ? g : plan[l.runs[k + 1].first];
		guard = clear_platform(map, ground.state[0], ground.state[1], opt.guard_half_length_m, maps, l.p.notes);
	}
	return guard;
}

// Joins the last phase of each run to the first of the next on its switch's
// guard (a hover end has none: its switch is the fixed end).
void join_switches(Layout &l, const RobotParams &robot, const std::vector<Waypoint> &plan, const TerrainGrid &map,
		   const TakeoffLanding &costs, const SmoothOptions &opt, const CorridorMaps *maps)
{
	for (size_t k = 0; k + 1 < l.runs.size(); k++) {
		if (l.hovered(k) || l.hovered(k + 1))
			continue;
		if (l.first_phase[k + 1] != l.last_phase[k] + 1)
			throw std::logic_error("smoothing_problem: phases out of order");
		const SwitchGuard guard = switch_guard(l, k, plan, map, opt, maps);
		join_phases(l.p, l.last_phase[k], robot, guard, costs);
	}
}

}  // namespace

MultiPhaseProblem smoothing_problem(const RobotParams &robot, const std::vector<Waypoint> &given,
				    const TerrainGrid &map, const TakeoffLanding &costs, const SmoothOptions &opt)
{
	check_waypoints(robot, given);
	const std::vector<Waypoint> plan = unwound_headings(given);
	Layout l = lay_out_phases(robot, plan, map, opt);
	const std::unique_ptr<CorridorMaps> maps = corridor_maps(robot, map, opt, l.p.notes);
	if (maps)
		add_corridors(l, *maps);
	hold_ends(l, robot, plan, map, costs);
	join_cuts(l, robot, plan);
	join_switches(l, robot, plan, map, costs, opt, maps.get());
	return std::move(l.p);
}

double priced_turn(hylo_mode mode, const double *tail, const double *head)
{
	double r[HYLO_RELATIVE_PLANAR];
	hylo_relative(mode, tail, head, r);
	return r[2];
}

std::vector<Waypoint> unwound_headings(const std::vector<Waypoint> &plan)
{
	std::vector<Waypoint> out = plan;
	for (size_t i = 1; i < plan.size(); i++)
		if (mode_desc(plan[i - 1].mode).planar && mode_desc(plan[i].mode).planar)
			out[i].state[3] = out[i - 1].state[3] + priced_turn(plan[i].mode, plan[i - 1].state, plan[i].state);
	return out;
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
		const hylo_mode_desc *d = hylo_mode_describe(a.mode);   // unchecked plans too
		const bool flight = d && d->air;
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

}  // namespace hylo::trainer
