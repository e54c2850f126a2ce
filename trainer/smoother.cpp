#include "trainer/smoother.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>

#include "trainer/clearance.hpp"
#include "trainer/corridor.hpp"

namespace hylo::trainer {

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

SolveOptions smoothing_solve_options(const SmoothOptions &opt, bool full)
{
	SolveOptions so = smoothing_solve_options();
	so.ipopt_options = opt.ipopt_options;
	if (full)
		so.ipopt_options.insert(so.ipopt_options.end(), opt.full_ipopt_options.begin(),
					opt.full_ipopt_options.end());
	so.debug = opt.debug;
	return so;
}

namespace {

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

// Every phase of q starts at solution s's (its knots and midpoints, its
// duration and mesh). False when s has a phase without a trajectory.
bool start_from(MultiPhaseProblem &q, const MultiPhaseSolution &s)
{
	for (size_t k = 0; k < q.phases.size() && k < s.phases.size(); k++) {
		PhaseSpec &ps = q.phases[k];
		const Trajectory &tr = s.phases[k].traj;
		const size_t nx = static_cast<size_t>(tr.nx), n = tr.t.size();
		if (n < 2 || s.phases[k].T <= 0)
			return false;
		ps.guess.clear();
		ps.guess_at.clear();
		for (size_t i = 0; i < n; i++) {
			ps.guess.emplace_back(&tr.x[i * nx], &tr.x[i * nx] + nx);
			ps.guess_at.push_back(i + 1 < n ? std::min(1.0, tr.t[i] / tr.t.back()) : 1.0);
		}
		ps.T_guess = s.phases[k].T;
		ps.segments = s.phases[k].segments;
	}
	q.T_scales = {1.0};
	return true;
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
	if (!start_from(q, s))
		return false;
	for (size_t k = 0; k < q.phases.size() && k < s.phases.size(); k++) {
		PhaseSpec &ps = q.phases[k];
		const Trajectory &tr = s.phases[k].traj;
		const size_t nx = static_cast<size_t>(tr.nx), n = tr.t.size();
		if (!mode_desc(ps.mode).air || ps.corridor.empty())
			continue;
		std::vector<std::array<double, 3>> path;
		std::vector<double> times;
		for (size_t i = 0; i < n; i++) {
			const double *x = &tr.x[i * nx];
			path.push_back({x[0], x[1], x[2]});
			times.push_back(std::min(1.0, std::max(0.0, tr.t[i] / s.phases[k].T)));
		}
		Corridor c = build_corridor(ps.mode, path, maps);
		if (!c.notes.empty() || !c.first_box || !c.last_box)
			continue;   // keep the old boxes rather than get less clearance
		for (CorridorBox &b : c.boxes) {
			b.tau0 = b.tau0 <= 0 ? 0 : time_at_fraction(path, times, b.tau0);
			b.tau1 = b.tau1 >= 1 ? 1 : std::max(b.tau0, time_at_fraction(path, times, b.tau1));
		}
		ps.corridor = std::move(c.boxes);
		changed = true;
	}
	return changed;
}

// A rebuild round starts from a converged solution; one that has not
// converged in this many Ipopt iterations is given up (the test's chasm
// gate ran to 1,927 and failed: 5 of its 7 minutes).
constexpr int kRebuildIterations = 400;

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
			SolveOptions so = smoothing_solve_options(opt, true);
			so.iteration_budget = kRebuildIterations;
			r = solve_multiphase(robot, q, so);
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

// How far inside its boxes keep_inside keeps a trajectory's points: more
// than a cubic bulges between two knots on a face (the river's six-change
// alternative: less than this), too little to matter to a controller
// (that one: 1,119.4 -> 1,122.0 J; 1 cm cost it 1,149.7 J).
constexpr double kInsetM = 1e-3;

// The exact check (trainer/clearance.hpp) also samples the cubic between
// knots: where a solution's knots ride a corridor's face, it can cross the
// face by a hair and leave the domain or the margin. Then the problem is
// solved again from s with every point but the phase ends kInsetM inside
// its boxes, and that solution is taken when it passes the check.
void keep_inside(const RobotParams &robot, const TerrainGrid &map, const SmoothOptions &opt,
		 MultiPhaseProblem &prob, MultiPhaseSolution &s)
{
	const double body = robot.body_radius_m;
	const ClearanceCheck before = check_clearance(s, map, body, opt.margin_m);
	if (before.safe || !opt.corridors)
		return;
	MultiPhaseProblem q = prob;
	for (PhaseSpec &ps : q.phases)
		ps.corridor_inset_m = kInsetM;
	MultiPhaseSolution r;
	try {
		if (!start_from(q, s))
			return;
		r = solve_multiphase(robot, q, smoothing_solve_options(opt, true));
	} catch (const std::invalid_argument &) {   // s stands
		return;
	}
	s.solve_seconds += r.solve_seconds;
	if (!r.converged || !check_clearance(r, map, body, opt.margin_m).safe)
		return;
	char buf[200];
	std::snprintf(buf, sizeof buf, "kept %.3g m inside its corridors (the check found it %s): %.1f J -> %.1f J",
		      kInsetM, before.outside_phase >= 0 ? "leaving its domain" : "short of the margin", s.cost, r.cost);
	r.solve_seconds = s.solve_seconds;
	r.notes = s.notes;
	r.notes.push_back(buf);
	s = std::move(r);
	prob = std::move(q);
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
		s = solve_multiphase(robot, prob, smoothing_solve_options(opt, true));
		seconds += s.solve_seconds;
		s.solve_seconds = seconds;
		rejected = std::min(rejected, s.rejected_cost);
		if (from_straightened)
			*from_straightened = attempt == 1;
		if (s.converged) {
			refine_corridors(robot, map, opt, prob, s);
			keep_inside(robot, map, opt, prob, s);
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

}  // namespace hylo::trainer
