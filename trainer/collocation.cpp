#include "trainer/collocation.hpp"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <limits>
#include <memory>
#include <stdexcept>

#include "trainer/hs_phase.hpp"
#include "trainer/ipopt_nlp.hpp"
#include "trainer/mode_config.hpp"
#include "trainer/models.hpp"
#include "trainer/starts.hpp"
#include "trainer/replay.hpp"

namespace hylo::trainer {
namespace {

using internal::Index;
using internal::Number;
using internal::PhaseBlock;
using internal::PhaseSetup;
using internal::kMumpsChoosesPermutingScaling;
using internal::NlpSettings;
using internal::NlpStatus;
using internal::Row;
using internal::StackedNlp;
using internal::ModeInfo;
using internal::Start;

// One stacked problem as the engine sees it: modes, their setups and the
// rows by knot reference (resolved per mesh, since offsets change).
struct Stacked {
	std::vector<std::string> modes;
	std::vector<ModeInfo> info;
	std::vector<PhaseSetup> setups;
	std::vector<LinearRow> rows;
};

std::unique_ptr<StackedNlp> build(const Stacked &p, double relax)
{
	std::vector<std::unique_ptr<PhaseBlock>> blocks;
	std::vector<int> offset;
	int n = 0;
	for (size_t k = 0; k < p.setups.size(); k++) {
		blocks.push_back(p.info[k].make(relax, p.setups[k]));
		offset.push_back(n);
		n += blocks.back()->nvar();
	}
	std::vector<Row> rows;
	for (const LinearRow &lr : p.rows) {
		Row r;
		r.lo = lr.lo;
		r.hi = lr.hi;
		for (const auto &t : lr.terms) {
			size_t k = static_cast<size_t>(t.first.phase);
			r.terms.emplace_back(offset[k] + blocks[k]->state_var(t.first.last, t.first.component), t.second);
		}
		rows.push_back(std::move(r));
	}
	return std::make_unique<StackedNlp>(std::move(blocks), std::move(rows));
}

// Solves from each start: continuation over the smoothing on the coarse
// mesh, then mesh refinement until every phase's replay passes. Keeps the
// cheapest. With opt.refine_within finite, a start is not refined whose
// coarse cost is that fraction above the cheaper of the best refined result
// and incumbent (a cost already known for the problem).
MultiPhaseSolution solve_stacked(const RobotParams &robot, Stacked base, const std::vector<Start> &starts,
				 double switch_cost, const SolveOptions &opt,
				 double incumbent = std::numeric_limits<double>::infinity())
{
	auto t0 = std::chrono::steady_clock::now();
	MultiPhaseSolution best;
	best.modes = base.modes;
	best.cost = std::numeric_limits<double>::infinity();
	const bool debug = opt.debug;
	bool smoothed = false, first_accepted = true;
	for (const ModeInfo &i : base.info) {
		smoothed = smoothed || i.smoothed;
		first_accepted = first_accepted && i.first_accepted;
	}
	// Per-mode solver settings: the most mesh doublings any phase's mode asks
	// for, and the union of their continuation steps.
	int refinements = opt.refinements;
	std::vector<double> levels;
	for (const ModeInfo &i : base.info) {
		refinements = std::max(refinements, i.refinements);
		levels.insert(levels.end(), i.continuation.begin(), i.continuation.end());
	}
	std::sort(levels.begin(), levels.end(), std::greater<double>());
	levels.erase(std::unique(levels.begin(), levels.end()), levels.end());
	// MUMPS's permutation and scaling as the mode sets it in single-mode
	// BVPs; multi-phase problems keep it (without it a chasm crossing failed;
	// docs/decisions.md, "Flight training: five changes").
	const int permuting_scaling = base.info.size() == 1 ? base.info[0].mumps_permuting_scaling
								 : kMumpsChoosesPermutingScaling;
	// A continuation or refinement step's options: the tightest iteration
	// limit a phase's mode sets.
	SolveOptions step_opt = opt;
	for (const ModeInfo &i : base.info)
		if (i.step_max_iter > 0)
			step_opt.max_iter = std::min(step_opt.max_iter, i.step_max_iter);
	// Smoothing: a long plan's steps can need more than flight's 400
	// (docs/decisions.md, "Smoothing long plans").
	if (opt.step_max_iter > 0)
		step_opt.max_iter = opt.step_max_iter;
	// A step that runs out of its own limit gives its start up.
	const bool give_up = step_opt.max_iter < opt.max_iter || opt.step_max_iter > 0;
	auto run = [&](const Stacked &p, double relax, const std::vector<double> &start,
		       std::unique_ptr<StackedNlp> &nlp, bool warm, const SolveOptions &o) {
		nlp = build(p, relax);
		NlpStatus st = nlp->solve(o, start, NlpSettings{warm, permuting_scaling});
		if (debug)
			std::fprintf(stderr, "start T=%g N=%d relax %g: %s, %d iterations\n",
				     p.setups[0].T_guess, p.setups[0].segments, relax, st.text(), st.iterations);
		return st;
	};
	// A start after its continuation on the coarse mesh: the cost (with the
	// switches') and duration it reached there.
	struct Coarse {
		Stacked p;
		std::unique_ptr<StackedNlp> nlp;
		NlpStatus res;   // a success of no iterations until a solve
		double cost = 0, T = 0;
	};
	std::string last_status = "no start";   // Ipopt's status of the last start that failed
	auto coarse = [&](const Start &st, Coarse &c) {
		const std::vector<double> &Ts = st.T;
		Stacked &p = c.p;
		p = base;
		if (!st.path.empty())
			p.setups[0].guess = st.path;
		for (size_t k = 0; k < p.setups.size(); k++) {
			p.setups[k].T_guess = Ts[k];
			const ModeInfo &i = p.info[k];
			double step = i.max_step_s > 0 && opt.max_step_s > 0 ? opt.max_step_s : i.max_step_s;
			int by_step = step > 0 ? static_cast<int>(std::ceil(Ts[k] / step)) : 0;
			if (opt.derivative_test_file.empty())   // the checker needs no fine mesh, only exact derivatives
				p.setups[k].segments = std::max({p.setups[k].segments, i.min_segments, by_step});
			if (i.path_guess && p.setups[k].guess.size() == 2) {
				p.setups[k].guess = i.path_guess(p.setups[k].guess[0], p.setups[k].guess[1], Ts[k]);
				p.setups[k].guess_by_arc_length = false;
			}
		}
		best.starts++;
		// Continuation: smoother problems first, each starting the next; the
		// last (1) has docs/models.md's exact constants.
		std::vector<double> start;
		for (double relax : levels) {
			if ((!smoothed || !opt.continuation || !opt.derivative_test_file.empty()) && relax != 1.0)
				continue;
			c.res = run(p, relax, start, c.nlp, !start.empty(), step_opt);
			if (c.res.succeeded())
				start = c.nlp->solution();
			else if (give_up)
				break;
		}
		if (!c.res.succeeded()) {
			last_status = c.res.text();
			return false;
		}
		best.converged_starts++;
		c.cost = switch_cost;
		for (size_t k = 0; k < p.setups.size(); k++) {
			Solution ph;
			c.nlp->fill(k, ph);
			c.cost += ph.cost;
			c.T += ph.T;
		}
		return true;
	};
	// Mesh refinement until the replays agree: each finer mesh starts from
	// the coarser solution (its knots and midpoints become knots). Keeps the
	// result if it is the cheapest so far.
	std::string rejection;   // why the last rejected solution was rejected
	double rejected_cost = std::numeric_limits<double>::infinity();
	auto refine = [&](Coarse &c) {
		best.refined_starts++;
		Stacked &p = c.p;
		std::unique_ptr<StackedNlp> &nlp = c.nlp;
		NlpStatus res = c.res;
		int iterations = res.iterations;
		for (int refinement = 0;; refinement++) {
			MultiPhaseSolution s;
			s.modes = p.modes;
			s.status = res.status;
			s.status_text = res.text();
			s.iterations = iterations;
			bool all_ok = true;
			std::vector<bool> failed(p.setups.size(), false);
			for (size_t k = 0; k < p.setups.size(); k++) {
				Solution ph;
				nlp->fill(k, ph);
				ph.status = s.status;
				ph.status_text = s.status_text;
				ph.iterations = iterations;
				if (opt.replay) {
					replay(p.modes[k], robot, ph, opt.replay_state_tol);
					if (debug)
						std::fprintf(stderr, "  replay %s: error %.3g, cost %.6g vs %.6g: %s\n",
							     p.modes[k].c_str(), ph.replay_error, ph.replay_cost, ph.cost,
							     replay_verdict(ph).c_str());
					if (!ph.replay_ok && all_ok)
						rejection = "phase " + std::to_string(k) + " (" + p.modes[k] + ", " +
							    std::to_string(p.setups[k].segments) + " segments): " +
							    replay_verdict(ph);
					all_ok = all_ok && ph.replay_ok;
					failed[k] = !ph.replay_ok;
				}
				ph.converged = !opt.replay || ph.replay_ok;
				s.cost += ph.cost;
				s.T += ph.T;
				s.replay_cost += ph.replay_cost;
				s.replay_error = std::max(s.replay_error, ph.replay_error);
				s.phases.push_back(std::move(ph));
			}
			if (all_ok) {
				s.converged = true;
				s.cost += switch_cost;
				s.replay_cost += switch_cost;
				if (s.cost < best.cost) {
					s.starts = best.starts;
					s.converged_starts = best.converged_starts;
					s.refined_starts = best.refined_starts;
					best = std::move(s);
				}
				return;
			}
			rejected_cost = std::min(rejected_cost, s.cost + switch_cost);
			if (refinement >= refinements)
				return;
			// Only the phases whose replay failed get the finer mesh.
			std::vector<double> fine = nlp->refined(failed);
			for (size_t k = 0; k < p.setups.size(); k++)
				if (failed[k])
					p.setups[k].segments *= 2;
			res = run(p, 1.0, fine, nlp, true, step_opt);
			iterations += res.iterations;
			if (!res.succeeded()) {
				rejection += "; then the finer mesh failed (" + std::string(res.text()) + ")";
				return;
			}
		}
	};
	if (first_accepted || !std::isfinite(opt.refine_within)) {
		// Each start in turn, refined as soon as it converges.
		for (const Start &st : starts) {
			if (best.converged && first_accepted)
				break;
			Coarse c;
			bool ok = coarse(st, c);
			if (!opt.derivative_test_file.empty())
				return best;
			if (ok)
				refine(c);
		}
	} else {
		// Every start on the coarse mesh first. A start that reached an
		// earlier one's solution (cost and duration to 1e-6) is not refined
		// again, nor one whose coarse cost is more than refine_within above
		// the best refined result: refinement lowers costs by a few percent.
		std::vector<Coarse> reached;
		for (const Start &st : starts) {
			Coarse c;
			bool ok = coarse(st, c);
			if (!opt.derivative_test_file.empty())
				return best;
			auto same = [&](const Coarse &o) {
				return std::fabs(o.cost - c.cost) <= 1e-6 * std::fabs(o.cost) &&
				       std::fabs(o.T - c.T) <= 1e-6 * o.T;
			};
			if (ok && std::none_of(reached.begin(), reached.end(), same))
				reached.push_back(std::move(c));
		}
		std::stable_sort(reached.begin(), reached.end(),
				 [](const Coarse &a, const Coarse &b) { return a.cost < b.cost; });
		for (Coarse &c : reached)
			if (c.cost <= std::min(best.converged ? best.cost : incumbent, incumbent) * (1 + opt.refine_within))
				refine(c);
	}
	if (!best.converged) {
		best.cost = 0;
		best.status_text = best.converged_starts ? "replay rejected every solution" : "no start converged";
		best.rejection = rejection;
		best.rejected_cost = rejected_cost;
		if (!best.converged_starts)
			best.rejection = "Ipopt: " + last_status;
	}
	best.solve_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
	return best;
}

// Throws std::invalid_argument unless v has n finite components inside [lo, hi].
void check_state(const std::vector<double> &v, const Bounds &bd, const std::string &mode)
{
	for (size_t k = 0; k < v.size(); k++)
		if (!std::isfinite(v[k]) || v[k] < bd.x_lo[k] - 1e-12 || v[k] > bd.x_hi[k] + 1e-12)
			throw std::invalid_argument("boundary state component " + std::to_string(k) + " = " +
						    std::to_string(v[k]) + " is outside [" +
						    std::to_string(bd.x_lo[k]) + ", " + std::to_string(bd.x_hi[k]) +
						    "] of mode " + mode);
}

// Throws std::invalid_argument unless ps's corridor boxes have the mode's
// position dimensions, intervals inside [0, 1] and non-empty boxes, and
// boxes whose intervals overlap intersect (their knots would have no room).
void check_corridor(const PhaseSpec &ps, size_t dims, const std::string &where)
{
	for (size_t i = 0; i < ps.corridor.size(); i++) {
		const CorridorBox &b = ps.corridor[i];
		std::string box = where + ": corridor box " + std::to_string(i);
		if (dims == 0)
			throw std::invalid_argument(box + ": mode " + ps.mode + " has no corridor");
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

}  // namespace

std::vector<double> full_state(const std::string &mode, const RobotParams &robot, const double *xs)
{
	return internal::mode_info(mode, robot).full_state(xs);
}

std::pair<std::vector<double>, std::vector<double>> state_bounds(const std::string &mode,
								 const RobotParams &robot)
{
	Bounds b = internal::mode_info(mode, robot).bounds;
	return {b.x_lo, b.x_hi};
}

namespace {

// The BVP x1s -> x2s of mode as a one-phase stacked problem.
struct Bvp {
	ModeInfo info;
	Stacked p;
	std::vector<double> a, b;
};

Bvp bvp(const std::string &mode, const RobotParams &robot, const double *x1s, const double *x2s,
	const SolveOptions &opt)
{
	Bvp v{internal::mode_info(mode, robot), {}, {}, {}};
	v.a = v.info.full_state(x1s);
	v.b = v.info.full_state(x2s);
	check_state(v.a, v.info.bounds, mode);
	check_state(v.b, v.info.bounds, mode);
	PhaseSetup s;
	s.segments = opt.segments;
	s.T_fixed = opt.T_fixed;
	s.guess = {v.a, v.b};
	s.first_lo = s.first_hi = v.a;
	s.last_lo = s.last_hi = v.b;
	v.p = Stacked{{mode}, {v.info}, {s}, {}};
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
	std::vector<Start> starts = internal::guess_starts(v.info.bounds, guesses);
	double incumbent = line.converged ? line.cost : std::numeric_limits<double>::infinity();
	Solution s = phase_solution(solve_stacked(robot, v.p, starts, 0, opt, incumbent));
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

}  // namespace

Solution solve_bvp(const std::string &mode, const RobotParams &robot, const double *x1s,
		   const double *x2s, const SolveOptions &opt)
{
	Bvp v = bvp(mode, robot, x1s, x2s, opt);
	const double duration = internal::duration_guess(v.info.bounds, v.info.typical_speed,
							 v.info.distance(v.a.data(), v.b.data()));
	std::vector<Start> starts = internal::line_starts(v.info.bounds, opt.T_guesses, duration);
	Solution line = phase_solution(solve_stacked(robot, v.p, starts, 0, opt));
	return opt.strategy_starts ? add_strategies(robot, v, opt, line) : line;
}

Solution solve_bvp_strategies(const std::string &mode, const RobotParams &robot, const double *x1s,
			      const double *x2s, const SolveOptions &opt, const Solution &line)
{
	return add_strategies(robot, bvp(mode, robot, x1s, x2s, opt), opt, line);
}

Solution solve_bvp_guesses(const std::string &mode, const RobotParams &robot, const double *x1s,
			   const double *x2s, const SolveOptions &opt, const std::vector<Guess> &guesses,
			   const Solution &incumbent)
{
	Bvp v = bvp(mode, robot, x1s, x2s, opt);
	internal::check_guesses(mode, guesses, v.a, v.b);
	return solve_from_guesses(robot, v, opt, guesses, incumbent);
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
	       "\nobjective_scale: " + num(opt.objective_scale) + "\nrefine_within: " + num(opt.refine_within) +
	       "\nreplay: " + (opt.replay ? "on" : "off") + "\ncontinuation: " + (opt.continuation ? "on" : "off") +
	       "\nipopt_options: " + (ipopt.empty() ? "none" : ipopt) + "\n";
}

MultiPhaseSolution solve_multiphase(const RobotParams &robot, const MultiPhaseProblem &prob,
				    const SolveOptions &opt)
{
	if (prob.phases.empty())
		throw std::invalid_argument("a multi-phase problem needs at least one phase");
	Stacked p;
	for (size_t k = 0; k < prob.phases.size(); k++) {
		const PhaseSpec &ps = prob.phases[k];
		ModeInfo info = internal::mode_info(ps.mode, robot);
		const size_t nx = static_cast<size_t>(info.nx);
		std::string where = "phase " + std::to_string(k) + " (" + ps.mode + ")";
		if (ps.guess.size() < 2)
			throw std::invalid_argument(where + ": the initial guess needs at least two states");
		for (const auto &g : ps.guess)
			if (g.size() != nx)
				throw std::invalid_argument(where + ": a guess state has " + std::to_string(g.size()) +
							    " components, the mode has " + std::to_string(nx));
		PhaseSetup s;
		s.segments = ps.segments;
		s.guess = ps.guess;
		auto bound = [&](const std::vector<double> &v, const std::vector<double> &dflt, const char *what) {
			if (v.empty())
				return dflt;
			if (v.size() != nx)
				throw std::invalid_argument(where + ": " + what + " has " + std::to_string(v.size()) +
							    " components, the mode has " + std::to_string(nx));
			return v;
		};
		s.first_lo = bound(ps.first_lo, info.bounds.x_lo, "first_lo");
		s.first_hi = bound(ps.first_hi, info.bounds.x_hi, "first_hi");
		s.last_lo = bound(ps.last_lo, info.bounds.x_lo, "last_lo");
		s.last_hi = bound(ps.last_hi, info.bounds.x_hi, "last_hi");
		double length = 0;
		for (size_t i = 1; i < ps.guess.size(); i++)
			length += info.distance(ps.guess[i - 1].data(), ps.guess[i].data());
		s.T_guess = ps.T_guess > 0 ? ps.T_guess : internal::duration_guess(info.bounds, info.typical_speed, length);
		check_corridor(ps, static_cast<size_t>(info.position_dims), where);
		s.corridor = ps.corridor;
		s.guess_by_arc_length = !ps.corridor.empty() && !ps.guess_timed;
		p.modes.push_back(ps.mode);
		p.info.push_back(std::move(info));
		p.setups.push_back(std::move(s));
	}
	for (const LinearRow &r : prob.rows)
		for (const auto &t : r.terms)
			if (t.first.phase < 0 || static_cast<size_t>(t.first.phase) >= p.setups.size() ||
			    t.first.component < 0 || t.first.component >= p.info[static_cast<size_t>(t.first.phase)].nx)
				throw std::invalid_argument("a linear row names phase " + std::to_string(t.first.phase) +
							    " component " + std::to_string(t.first.component) +
							    ", which does not exist");
	p.rows = prob.rows;
	std::vector<Bounds> bounds;
	std::vector<double> T_guesses;
	for (size_t k = 0; k < p.setups.size(); k++) {
		bounds.push_back(p.info[k].bounds);
		T_guesses.push_back(p.setups[k].T_guess);
	}
	std::vector<Start> starts = internal::scaled_starts(bounds, T_guesses, prob.T_scales);
	MultiPhaseSolution out = solve_stacked(robot, p, starts, prob.switch_cost, opt);
	out.notes = prob.notes;
	return out;
}

}  // namespace hylo::trainer
