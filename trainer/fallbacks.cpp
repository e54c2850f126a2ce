#include "trainer/fallbacks.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "trainer/domain_check.hpp"
#include "trainer/smoother.hpp"

namespace hylo::trainer {

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
void append_phase(MultiPhaseSolution &out, hylo_mode m, Solution ph)
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

// Phase k of the pinned problem p on its own: what the joins leave free of
// its switch knots fixed to the plan's state there (its guess's ends), so
// consecutive phases still meet.
PhaseSpec phase_alone(const MultiPhaseProblem &p, size_t k, const RobotParams &robot)
{
	PhaseSpec s = p.phases[k];
	auto b = state_bounds(s.mode, robot);
	if (s.first_lo.empty()) s.first_lo = b.first, s.first_hi = b.second;
	if (s.last_lo.empty()) s.last_lo = b.first, s.last_hi = b.second;
	if (k > 0)
		fix_free(s.first_lo, s.first_hi, s.guess.front());
	if (k + 1 < p.phases.size())
		fix_free(s.last_lo, s.last_hi, s.guess.back());
	return s;
}

// The phase-by-phase step: the plan's problem with its switch points pinned
// to the plan's guard points, every phase then solved alone from the switch
// states the plan has there.
MultiPhaseSolution phase_by_phase(const RobotParams &robot, const std::vector<Waypoint> &plan,
				  const TerrainGrid &map, const TakeoffLanding &costs, const SmoothOptions &opt)
{
	SmoothOptions pinned = opt;
	pinned.guard_half_length_m = 0;
	MultiPhaseProblem p = smoothing_problem(robot, plan, map, costs, pinned);
	SolveOptions so = smoothing_solve_options(opt, false);
	MultiPhaseSolution out;
	out.converged = true;
	for (size_t k = 0; k < p.phases.size(); k++) {
		MultiPhaseProblem q;
		q.phases = {phase_alone(p, k, robot)};
		q.T_scales = p.T_scales;
		const hylo_mode mode = q.phases[0].mode;
		MultiPhaseSolution r = solve_multiphase(robot, q, so);
		out.solve_seconds += r.solve_seconds;
		if (!r.converged) {
			out.converged = false;
			out.status_text = "phase " + std::to_string(k) + " (" + hylo_mode_str(mode) + ") alone: " + r.status_text;
			out.rejection = r.rejection;
			return out;
		}
		append_phase(out, mode, std::move(r.phases[0]));
	}
	out.cost += p.switch_cost;
	out.replay_cost += p.switch_cost;
	return out;
}

// The inner waypoint of a run of the mode where d left the domain nearest to
// where it did, not a via point yet (0: none).
size_t nearest_inner_waypoint(const std::vector<Waypoint> &p, const DomainCheck &d)
{
	size_t best = 0;
	double best_d = std::numeric_limits<double>::infinity();
	for (size_t i = 1; i + 1 < p.size(); i++) {
		if (p[i].via || p[i].guard || p[i].mode != p[i - 1].mode || p[i].mode != p[i + 1].mode ||
		    p[i].mode != d.mode)
			continue;
		double di = std::hypot(p[i].state[0] - d.x_m, p[i].state[1] - d.y_m);
		if (di < best_d) {
			best_d = di;
			best = i;
		}
	}
	return best;
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
	const SolveOptions so = smoothing_solve_options(opt, false);
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
		const size_t best = nearest_inner_waypoint(p, d);
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

// The finer mesh step: the plan's problem with twice the segments per edge
// (mesh refinement as in the full optimization).
MultiPhaseSolution finer_mesh(const RobotParams &robot, const std::vector<Waypoint> &plan, const TerrainGrid &map,
			      const TakeoffLanding &costs, const SmoothOptions &opt)
{
	SmoothOptions fine = opt;
	fine.segments_per_edge *= 2;
	fine.min_segments *= 2;
	fine.max_segments *= 2;
	MultiPhaseProblem prob = smoothing_problem(robot, plan, map, costs, fine);
	return solve_multiphase(robot, prob, smoothing_solve_options(opt, true));
}

// Every edge of the plan solved on its own (strategy starts), joined in
// time; a guard pair adds its switching cost. Not converged at the first
// edge that fails, which status_text names.
MultiPhaseSolution edges_joined(const RobotParams &robot, const std::vector<Waypoint> &given,
				const TakeoffLanding &costs, const SolveOptions &opt)
{
	SolveOptions edge_opt = opt;
	edge_opt.strategy_starts = true;
	MultiPhaseSolution out;
	out.converged = true;
	const std::vector<Waypoint> plan = unwound_headings(given);
	for (size_t i = 1; i < plan.size(); i++) {
		const Waypoint &a = plan[i - 1], &b = plan[i];
		const hylo_mode ma = a.mode, mb = b.mode;
		if (ma != mb) {   // a guard pair: the switch itself
			double c = ma == HYLO_MODE_GROUND && mb == HYLO_MODE_FLIGHT ? costs.takeoff_j
				 : ma == HYLO_MODE_FLIGHT && mb == HYLO_MODE_GROUND ? costs.landing_j : 0;
			out.cost += c;
			out.replay_cost += c;
			continue;
		}
		std::vector<double> xa = sampled(a), xb = sampled(b);
		Solution s = solve_bvp(ma, robot, xa.data(), xb.data(), edge_opt);
		out.solve_seconds += s.solve_seconds;
		if (!s.converged) {
			out.converged = false;
			out.status_text = "edge " + std::to_string(i - 1) + " -> " + std::to_string(i) + " (" + hylo_mode_str(ma) +
					  "): " + s.status_text;
			if (s.replayed && !s.replay_ok)
				out.rejection = replay_verdict(s);
			return out;
		}
		append_phase(out, ma, std::move(s));
	}
	return out;
}

// The chain's record as its steps run: each step's trajectory is taken, or
// rejected with why.
class Chain {
public:
	explicit Chain(const TerrainGrid &map) : map_(map) {}

	// Runs a step's solve; true when its trajectory is taken. A step that
	// cannot pose its problem (std::invalid_argument) is rejected.
	template <class Solve>
	bool step(SmoothMethod m, Solve &&solve)
	{
		try {
			return take(m, solve());
		} catch (const std::invalid_argument &e) {
			result.rejections.push_back(std::string(method_name(m)) + ": " + e.what());
			return false;
		}
	}

	// A solution of the full problem replayed but left the domain (left says where).
	bool left_domain() const { return left.phase >= 0; }

	SmoothResult result;
	DomainCheck left;   // where the last full-problem solution left the domain (phase -1: none did)

private:
	bool take(SmoothMethod m, MultiPhaseSolution s)
	{
		SmoothResult &r = result;
		r.seconds += s.solve_seconds;
		const bool full_problem = m == SmoothMethod::Full || m == SmoothMethod::FinerMesh;
		if (full_problem)
			r.lowest_cost = std::min(r.lowest_cost, s.rejected_cost);
		if (!s.converged) {
			r.rejections.push_back(std::string(method_name(m)) + ": " + why_not(s));
			return false;
		}
		DomainCheck d = domain_check(s, map_);
		if (d.worst_m > domain_tolerance_m(map_)) {
			char tol[64];
			std::snprintf(tol, sizeof tol, " > tolerance %.3g m", domain_tolerance_m(map_));
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
	}

	const TerrainGrid &map_;
};

}  // namespace

MultiPhaseSolution graph_path_trajectory(const RobotParams &robot, const std::vector<Waypoint> &plan,
					 const TerrainGrid &map, const TakeoffLanding &costs, const SmoothOptions &opt)
{
	if (opt.corridors && plan.size() > 2) {
		std::vector<Waypoint> edges = plan;
		for (Waypoint &w : edges)
			w.via = true;   // every inner waypoint ends a phase: a phase per edge
		MultiPhaseSolution s;
		try {
			s = phase_by_phase(robot, edges, map, costs, opt);
		} catch (const std::invalid_argument &) {   // the edges alone, below
		}
		if (s.converged)
			return s;
	}
	MultiPhaseSolution out = edges_joined(robot, plan, costs, smoothing_solve_options(opt, false));
	if (out.converged && out.phases.empty()) {
		out.converged = false;
		out.status_text = "the plan has no edge to follow";
	}
	return out;
}

double graph_path_cost(const RobotParams &robot, const std::vector<Waypoint> &plan, const TakeoffLanding &costs,
		       const SolveOptions &opt)
{
	MultiPhaseSolution s = edges_joined(robot, plan, costs, opt);
	return s.converged ? s.cost : std::numeric_limits<double>::infinity();
}

SmoothResult smooth_with_fallbacks(const RobotParams &robot, const std::vector<Waypoint> &plan,
				   const TerrainGrid &map, const TakeoffLanding &costs, const SmoothOptions &opt)
{
	Chain chain(map);
	SmoothResult &r = chain.result;
	bool straight = false;
	if (chain.step(SmoothMethod::Full, [&] { return smooth_plan(robot, plan, map, costs, opt, {}, &straight); })) {
		if (straight)
			r.method = SmoothMethod::Straightened;
		return r;
	}
	// A full solution that replayed but left the domain gains nothing from a
	// finer mesh: straight to the via points.
	if (!chain.left_domain() &&
	    chain.step(SmoothMethod::FinerMesh, [&] { return finer_mesh(robot, plan, map, costs, opt); }))
		return r;
	// Via points start where a full solution left the domain; without one
	// they would only repeat the full optimization.
	if (chain.left_domain() &&
	    chain.step(SmoothMethod::ViaPoints, [&] { return via_points(robot, plan, map, costs, opt, chain.left); }))
		return r;
	if (chain.step(SmoothMethod::PhaseByPhase, [&] { return phase_by_phase(robot, plan, map, costs, opt); }))
		return r;
	if (chain.step(SmoothMethod::GraphPath,
		       [&] { return graph_path_trajectory(robot, plan, map, costs, opt); }))
		return r;
	r.failure = r.rejections.back().substr(std::string(method_name(SmoothMethod::GraphPath)).size() + 2);
	return r;
}

}  // namespace hylo::trainer
