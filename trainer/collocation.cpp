#include "trainer/collocation.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "trainer/hand_overs.hpp"
#include "trainer/hs_phase.hpp"
#include "trainer/mode_config.hpp"
#include "trainer/models.hpp"
#include "trainer/solve_strategy.hpp"
#include "trainer/starts.hpp"

namespace hylo::trainer {
namespace {

using internal::ModeInfo;
using internal::PhaseSetup;
using internal::Stacked;
using internal::Start;

// Throws std::invalid_argument unless v has n finite components inside [lo, hi].
void check_state(const std::vector<double> &v, const Bounds &bd, hylo_mode mode)
{
	for (size_t k = 0; k < v.size(); k++)
		if (!std::isfinite(v[k]) || v[k] < bd.x_lo[k] - 1e-12 || v[k] > bd.x_hi[k] + 1e-12)
			throw std::invalid_argument("boundary state component " + std::to_string(k) + " = " +
						    std::to_string(v[k]) + " is outside [" +
						    std::to_string(bd.x_lo[k]) + ", " + std::to_string(bd.x_hi[k]) +
						    "] of mode " + hylo_mode_str(mode));
}

// ---- single-mode BVPs ---------------------------------------------------

// The BVP x1s -> x2s of mode as a one-phase stacked problem.
struct Bvp {
	ModeInfo info;
	Stacked p;
	std::vector<double> a, b;
};

Bvp bvp(hylo_mode mode, const RobotParams &robot, const double *x1s, const double *x2s,
	const SolveOptions &opt)
{
	Bvp v{internal::mode_info(mode, robot), {}, {}, {}};
	v.a = v.info.full_state(x1s);
	v.b = v.info.full_state(x2s);
	check_state(v.a, v.info.bounds, mode);
	check_state(v.b, v.info.bounds, mode);
	PhaseSetup s;
	s.segments = opt.segments;
	s.accept_segments = v.info.accept_segments;
	s.T_fixed = opt.T_fixed;
	s.guess = {v.a, v.b};
	s.first_lo = s.first_hi = v.a;
	s.last_lo = s.last_hi = v.b;
	v.p = Stacked{{mode}, {v.info}, {s}, {}, {}};
	return v;
}

Solution phase_solution(const MultiPhaseSolution &m)
{
	Solution out;
	if (!m.phases.empty())
		out = m.phases[0];
	out.converged = m.converged;
	out.status = m.status;
	out.status_text = m.status_text;
	out.iterations = m.iterations;
	out.starts = m.starts;
	out.converged_starts = m.converged_starts;
	out.refined_starts = m.refined_starts;
	out.solve_seconds = m.solve_seconds;
	if (!m.converged)
		out.cost = 0;
	return out;
}

// The guesses' best, if cheaper than line (see solve_bvp_guesses).
Solution solve_from_guesses(const RobotParams &robot, const Bvp &v, const SolveOptions &opt,
			    const std::vector<Guess> &guesses, const Solution &line)
{
	if (guesses.empty())
		return line;
	double incumbent = line.converged ? line.cost : std::numeric_limits<double>::infinity();
	Solution s = phase_solution(
		internal::solve_stacked(robot, v.p, internal::guess_starts(v.info.bounds, guesses), 0, opt, incumbent));
	Solution out = s.converged && (!line.converged || s.cost < line.cost) ? s : line;
	out.starts = line.starts + s.starts;
	out.converged_starts = line.converged_starts + s.converged_starts;
	out.refined_starts = line.refined_starts + s.refined_starts;
	out.solve_seconds = line.solve_seconds + s.solve_seconds;
	return out;
}

// solve_bvp_strategies on a built problem.
Solution add_strategies(const RobotParams &robot, const Bvp &v, const SolveOptions &opt, const Solution &line)
{
	if (!v.info.strategy_guesses)
		return line;
	return solve_from_guesses(robot, v, opt, v.info.strategy_guesses(v.a, v.b), line);
}

// ---- multi-phase problems -------------------------------------------------

// Throws std::invalid_argument unless ps's corridor boxes have the mode's
// position dimensions, intervals inside [0, 1] and non-empty boxes, and
// boxes whose intervals overlap intersect (their knots would have no room).
void check_corridor(const PhaseSpec &ps, size_t dims, const std::string &where)
{
	for (size_t i = 0; i < ps.corridor.size(); i++) {
		const CorridorBox &b = ps.corridor[i];
		std::string box = where + ": corridor box " + std::to_string(i);
		if (dims == 0)
			throw std::invalid_argument(box + ": mode " + hylo_mode_str(ps.mode) + " has no corridor");
		if (b.lo.size() != dims || b.hi.size() != dims)
			throw std::invalid_argument(box + " has " + std::to_string(b.lo.size()) + " and " +
						    std::to_string(b.hi.size()) + " bounds, the mode's position " +
						    std::to_string(dims));
		if (!(b.tau0 >= 0 && b.tau0 <= b.tau1 && b.tau1 <= 1))
			throw std::invalid_argument(box + ": interval [" + std::to_string(b.tau0) + ", " +
						    std::to_string(b.tau1) + "] is not inside [0, 1]");
		for (size_t k = 0; k < dims; k++)
			if (!(b.lo[k] <= b.hi[k]))
				throw std::invalid_argument(box + " is empty along component " + std::to_string(k));
		for (size_t j = 0; j < i; j++) {
			const CorridorBox &a = ps.corridor[j];
			if (a.tau1 < b.tau0 || b.tau1 < a.tau0)
				continue;
			for (size_t k = 0; k < dims; k++)
				if (std::max(a.lo[k], b.lo[k]) > std::min(a.hi[k], b.hi[k]))
					throw std::invalid_argument(box + " and box " + std::to_string(j) +
								    " overlap in time but not in space");
		}
	}
}

// Throws std::invalid_argument unless the guess has at least two states of nx components.
void check_guess(const PhaseSpec &ps, size_t nx, const std::string &where)
{
	if (ps.guess.size() < 2)
		throw std::invalid_argument(where + ": the initial guess needs at least two states");
	for (const auto &g : ps.guess)
		if (g.size() != nx)
			throw std::invalid_argument(where + ": a guess state has " + std::to_string(g.size()) +
						    " components, the mode has " + std::to_string(nx));
}

// The normalized times of ps's guess states: as given (checked), else with a
// corridor proportional to their positions' arc length (its boxes are timed
// so), else none (uniform).
std::vector<double> guess_times(const PhaseSpec &ps, const std::string &where)
{
	const size_t n = ps.guess.size();
	if (!ps.guess_at.empty()) {
		bool ok = ps.guess_at.size() == n && ps.guess_at.front() == 0 && ps.guess_at.back() == 1;
		for (size_t i = 1; ok && i < n; i++)
			ok = ps.guess_at[i] >= ps.guess_at[i - 1];
		if (!ok)
			throw std::invalid_argument(where + ": the guess's times must be one per state, increasing from 0 to 1");
		return ps.guess_at;
	}
	if (ps.corridor.empty())
		return {};
	std::vector<double> at(n, 0.0);
	const size_t dims = ps.corridor[0].lo.size();
	for (size_t w = 1; w < n; w++) {
		double d = 0;
		for (size_t k = 0; k < dims; k++)
			d += std::pow(ps.guess[w][k] - ps.guess[w - 1][k], 2);
		at[w] = at[w - 1] + std::sqrt(d);
	}
	for (size_t w = 0; w < n; w++)
		at[w] = at.back() > 0 ? at[w] / at.back() : static_cast<double>(w) / static_cast<double>(n - 1);
	return at;
}

// A knot's bounds as given (nx components) or, empty, the mode's.
std::vector<double> knot_bounds(const std::vector<double> &v, const std::vector<double> &mode_bounds, size_t nx,
				const char *what, const std::string &where)
{
	if (v.empty())
		return mode_bounds;
	if (v.size() != nx)
		throw std::invalid_argument(where + ": " + what + " has " + std::to_string(v.size()) +
					    " components, the mode has " + std::to_string(nx));
	return v;
}

// Phase k of a problem as the transcription's setup, checked.
PhaseSetup phase_setup(const PhaseSpec &ps, const ModeInfo &info, const std::string &where)
{
	const size_t nx = static_cast<size_t>(info.nx);
	check_guess(ps, nx, where);
	PhaseSetup s;
	s.segments = ps.segments;
	s.guess = ps.guess;
	s.first_lo = knot_bounds(ps.first_lo, info.bounds.x_lo, nx, "first_lo", where);
	s.first_hi = knot_bounds(ps.first_hi, info.bounds.x_hi, nx, "first_hi", where);
	s.last_lo = knot_bounds(ps.last_lo, info.bounds.x_lo, nx, "last_lo", where);
	s.last_hi = knot_bounds(ps.last_hi, info.bounds.x_hi, nx, "last_hi", where);
	double length = 0;
	for (size_t i = 1; i < ps.guess.size(); i++)
		length += info.distance(ps.guess[i - 1].data(), ps.guess[i].data());
	s.T_guess = ps.T_guess > 0 ? ps.T_guess : internal::duration_guess(info.bounds, info.typical_speed, length);
	check_corridor(ps, static_cast<size_t>(info.position_dims), where);
	s.corridor = ps.corridor;
	s.corridor_inset_m = ps.corridor_inset_m;
	s.guess_at = guess_times(ps, where);
	return s;
}

// Throws std::invalid_argument for a row naming a phase or component p does not have.
void check_rows(const std::vector<LinearRow> &rows, const Stacked &p)
{
	for (const LinearRow &r : rows)
		for (const auto &t : r.terms)
			if (t.first.phase < 0 || static_cast<size_t>(t.first.phase) >= p.setups.size() ||
			    t.first.component < 0 || t.first.component >= p.info[static_cast<size_t>(t.first.phase)].nx)
				throw std::invalid_argument("a linear row names phase " + std::to_string(t.first.phase) +
							    " component " + std::to_string(t.first.component) +
							    ", which does not exist");
}

// The problem as the strategy sees it, checked: each phase as its pieces
// between hand-overs (hand_overs.hpp), joined by full-state continuity.
Stacked stacked(const RobotParams &robot, const MultiPhaseProblem &prob)
{
	if (prob.phases.empty())
		throw std::invalid_argument("a multi-phase problem needs at least one phase");
	Stacked given, p;
	std::vector<int> first(prob.phases.size()), last(prob.phases.size());
	for (size_t k = 0; k < prob.phases.size(); k++) {
		const PhaseSpec &ps = prob.phases[k];
		ModeInfo info = internal::mode_info(ps.mode, robot);
		const PhaseSetup s = phase_setup(ps, info, "phase " + std::to_string(k) + " (" + hylo_mode_str(ps.mode) + ")");
		first[k] = static_cast<int>(p.setups.size());
		for (PhaseSetup &piece : internal::hand_over_pieces(s, info)) {
			if (p.setups.size() > static_cast<size_t>(first[k]))
				for (int c = 0; c < info.nx; c++) {
					const int b = static_cast<int>(p.setups.size());
					p.rows.push_back({{{KnotRef{b, false, c}, 1.0}, {KnotRef{b - 1, true, c}, -1.0}}, 0, 0});
				}
			p.setups.push_back(std::move(piece));
			p.modes.push_back(ps.mode);
			p.info.push_back(info);
			p.owner.push_back(k);
		}
		last[k] = static_cast<int>(p.setups.size()) - 1;
		given.setups.push_back(s);
		given.info.push_back(std::move(info));
	}
	check_rows(prob.rows, given);
	for (LinearRow r : prob.rows) {
		for (auto &t : r.terms)
			t.first.phase = t.first.last ? last[static_cast<size_t>(t.first.phase)]
						     : first[static_cast<size_t>(t.first.phase)];
		p.rows.push_back(std::move(r));
	}
	return p;
}

}  // namespace

std::vector<double> full_state(hylo_mode mode, const RobotParams &robot, const double *xs)
{
	return internal::mode_info(mode, robot).full_state(xs);
}

std::pair<std::vector<double>, std::vector<double>> state_bounds(hylo_mode mode,
								 const RobotParams &robot)
{
	Bounds b = internal::mode_info(mode, robot).bounds;
	return {b.x_lo, b.x_hi};
}

Solution solve_bvp(hylo_mode mode, const RobotParams &robot, const double *x1s,
		   const double *x2s, const SolveOptions &opt)
{
	Bvp v = bvp(mode, robot, x1s, x2s, opt);
	const double duration = internal::duration_guess(v.info.bounds, v.info.typical_speed,
							 v.info.distance(v.a.data(), v.b.data()));
	std::vector<Start> starts = internal::line_starts(v.info.bounds, opt.T_guesses, duration);
	Solution line = phase_solution(internal::solve_stacked(robot, v.p, starts, 0, opt));
	return opt.strategy_starts ? add_strategies(robot, v, opt, line) : line;
}

Solution solve_bvp_strategies(hylo_mode mode, const RobotParams &robot, const double *x1s,
			      const double *x2s, const SolveOptions &opt, const Solution &line)
{
	return add_strategies(robot, bvp(mode, robot, x1s, x2s, opt), opt, line);
}

SolveOptions guess_solve_options(const SolveOptions &opt)
{
	SolveOptions o = opt;
	o.refine_repeats = false;
	return o;
}

Solution solve_bvp_guesses(hylo_mode mode, const RobotParams &robot, const double *x1s,
			   const double *x2s, const SolveOptions &opt, const std::vector<Guess> &guesses,
			   const Solution &incumbent)
{
	const SolveOptions o = guess_solve_options(opt);
	Bvp v = bvp(mode, robot, x1s, x2s, o);
	internal::check_guesses(mode, guesses, v.a, v.b);
	return solve_from_guesses(robot, v, o, guesses, incumbent);
}

std::string solve_options_text(const SolveOptions &opt)
{
	auto num = [](double v) {
		char buf[64];
		auto r = std::to_chars(buf, buf + sizeof buf, v);   // shortest round trip
		return std::string(buf, r.ptr);
	};
	std::string T_guesses, ipopt;
	for (double T : opt.T_guesses)
		T_guesses += (T_guesses.empty() ? "" : " ") + num(T);
	for (const IpoptOption &o : opt.ipopt_options)
		ipopt += (ipopt.empty() ? "" : " ") + o.name + "=" + o.value;
	return "segments: " + std::to_string(opt.segments) + "\ntol: " + num(opt.tol) +
	       "\nmax_iter: " + std::to_string(opt.max_iter) + "\nT_fixed: " + num(opt.T_fixed) +
	       "\nT_guesses: " + (T_guesses.empty() ? "from distance and speed" : T_guesses) +
	       "\nrefinements: " + std::to_string(opt.refinements) +
	       "\nreplay_state_tol: " + num(opt.replay_state_tol) + "\nmax_step_s: " + num(opt.max_step_s) +
	       "\nstep_max_iter: " + std::to_string(opt.step_max_iter) +
	       // Only where set (the smoother's rebuild rounds): metas made before it stay valid.
	       (opt.iteration_budget > 0 ? "\niteration_budget: " + std::to_string(opt.iteration_budget) : "") +
	       "\nobjective_scale: " + num(opt.objective_scale) + "\nrefine_within: " + num(opt.refine_within) +
	       "\nreplay: " + (opt.replay ? "on" : "off") + "\ncontinuation: " + (opt.continuation ? "on" : "off") +
	       "\nrefine_retry: " + (opt.refine_retry ? "on" : "off") +
	       // Only where off (warm starts): the metas made before it stay valid.
	       (opt.refine_repeats ? "" : "\nrefine_repeats: off") +
	       "\nipopt_options: " + (ipopt.empty() ? "none" : ipopt) + "\n";
}

MultiPhaseSolution solve_multiphase(const RobotParams &robot, const MultiPhaseProblem &prob,
				    const SolveOptions &opt)
{
	Stacked p = stacked(robot, prob);
	std::vector<Bounds> bounds;
	std::vector<double> T_guesses;
	for (size_t k = 0; k < p.setups.size(); k++) {
		bounds.push_back(p.info[k].bounds);
		T_guesses.push_back(p.setups[k].T_guess);
	}
	MultiPhaseSolution out = internal::joined_pieces(
		internal::solve_stacked(robot, p, internal::scaled_starts(bounds, T_guesses, prob.T_scales),
					prob.switch_cost, opt),
		p.owner);
	out.notes = prob.notes;
	return out;
}

}  // namespace hylo::trainer
