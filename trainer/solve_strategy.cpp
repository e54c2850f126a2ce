#include "trainer/solve_strategy.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>

#include "trainer/ipopt_nlp.hpp"
#include "trainer/replay.hpp"

namespace hylo::trainer::internal {
namespace {

// The settings of a problem's steps, from its phases' modes and the options.
struct StepSettings {
	bool smoothed = false;        // a phase's mode is smoothed: continuation applies
	bool first_accepted = true;   // every phase's mode keeps its first accepted start
	int refinements = 0;          // mesh doublings at most
	std::vector<double> levels;   // continuation's smoothing multipliers, descending, to 1
	int permuting_scaling = kMumpsChoosesPermutingScaling;
	SolveOptions step_opt;        // the options of a continuation or refinement step
	bool give_up = false;         // a step that fails gives its start up
	double retry_relax = 0;       // > 0: a failed finer mesh is solved again from this level
};

StepSettings step_settings(const Stacked &base, const SolveOptions &opt)
{
	StepSettings s;
	// Per-mode solver settings: the most mesh doublings any phase's mode asks
	// for, and the union of their continuation steps.
	s.refinements = opt.refinements;
	for (const ModeInfo &i : base.info) {
		s.smoothed = s.smoothed || i.smoothed;
		s.first_accepted = s.first_accepted && i.first_accepted;
		s.refinements = std::max(s.refinements, i.refinements);
		s.levels.insert(s.levels.end(), i.continuation.begin(), i.continuation.end());
	}
	std::sort(s.levels.begin(), s.levels.end(), std::greater<double>());
	s.levels.erase(std::unique(s.levels.begin(), s.levels.end()), s.levels.end());
	// MUMPS's permutation and scaling as the mode sets it in single-mode
	// BVPs; multi-phase problems keep it (without it a chasm crossing failed;
	// docs/decisions.md, "Flight training: five changes").
	if (base.info.size() == 1)
		s.permuting_scaling = base.info[0].mumps_permuting_scaling;
	// A continuation or refinement step's options: the tightest iteration
	// limit a phase's mode sets.
	s.step_opt = opt;
	for (const ModeInfo &i : base.info)
		if (i.step_max_iter > 0)
			s.step_opt.max_iter = std::min(s.step_opt.max_iter, i.step_max_iter);
	// Smoothing: a long plan's steps can need more than flight's 400
	// (docs/decisions.md, "Smoothing long plans").
	if (opt.step_max_iter > 0)
		s.step_opt.max_iter = opt.step_max_iter;
	// A step that runs out of its own limit gives its start up.
	s.give_up = s.step_opt.max_iter < opt.max_iter || opt.step_max_iter > 0;
	// The refinement's retry: single-mode BVPs of modes that try every start
	// (ground, marine), from the continuation's last smoothed level.
	if (opt.refine_retry && opt.continuation && s.smoothed && !s.first_accepted && base.info.size() == 1)
		for (double relax : s.levels)
			if (relax > 1.0)
				s.retry_relax = relax;   // descending: the smallest above 1
	return s;
}

// The NLP of a stacked problem at a smoothing multiplier, its rows resolved
// to the phases' variables.
std::unique_ptr<StackedNlp> stacked_nlp(const Stacked &p, double relax)
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

// "phase N (mode" of stacked phase k, with its piece's number when the
// phase is solved as pieces ("phase 1 (flight, piece 2 of 3").
std::string phase_name(const Stacked &p, size_t k)
{
	std::string name = "phase " + std::to_string(k < p.owner.size() ? p.owner[k] : k) + " (" + hylo_mode_str(p.modes[k]);
	if (k >= p.owner.size())
		return name;
	const auto [first, last] = std::equal_range(p.owner.begin(), p.owner.end(), p.owner[k]);
	if (last - first > 1)
		name += ", piece " + std::to_string(k - static_cast<size_t>(first - p.owner.begin()) + 1) + " of " +
			std::to_string(last - first);
	return name;
}

// A phase's coarse mesh: its own segments, at least its mode's, and with a
// step length, segments of at most that (opt.max_step_s replacing the
// mode's); a piece of a phase, its share of the mode's least segments.
// The derivative checker needs no fine mesh, only exact derivatives.
int coarse_segments(const PhaseSetup &s, const ModeInfo &i, double T, const SolveOptions &opt)
{
	if (!opt.derivative_test_file.empty())
		return s.segments;
	double step = i.max_step_s > 0 && opt.max_step_s > 0 ? opt.max_step_s : i.max_step_s;
	int by_step = step > 0 ? static_cast<int>(std::ceil(T / step)) : 0;
	const int least = static_cast<int>(std::ceil(i.min_segments * s.mesh_share));
	return std::max({s.segments, least, by_step});
}

// A start after its continuation on the coarse mesh: its problem and last
// solve, and the cost (with the switches') and duration it reached there.
struct Coarse {
	Stacked p;
	std::unique_ptr<StackedNlp> nlp;
	NlpStatus res;   // a success of no iterations until a solve
	double cost = 0, T = 0;
	int iterations = 0;   // Ipopt's, over every step of the start
};

// A coarse optimum's cost and duration.
struct CoarseResult {
	double cost = 0, T = 0;
};

// A start reached an earlier one's solution: cost and duration to 1e-6.
bool same_result(const CoarseResult &earlier, const CoarseResult &c)
{
	return std::fabs(earlier.cost - c.cost) <= 1e-6 * std::fabs(earlier.cost) &&
	       std::fabs(earlier.T - c.T) <= 1e-6 * earlier.T;
}
bool same_result(const Coarse &earlier, const Coarse &c)
{
	return same_result(CoarseResult{earlier.cost, earlier.T}, CoarseResult{c.cost, c.T});
}

// The strategy's state over one problem's starts: the best result so far,
// counts, and why the last start failed or was rejected.
class Strategy {
public:
	Strategy(const RobotParams &robot, const Stacked &base, double switch_cost, const SolveOptions &opt,
		 double incumbent)
		: robot_(robot), base_(base), switch_cost_(switch_cost), opt_(opt), incumbent_(incumbent),
		  set_(step_settings(base, opt))
	{
		best_.modes = base.modes;
		best_.cost = std::numeric_limits<double>::infinity();
	}

	MultiPhaseSolution run(const std::vector<Start> &starts)
	{
		const bool complete = set_.first_accepted || !std::isfinite(opt_.refine_within)
					      ? each_refined_in_turn(starts)
					      : coarse_first_then_pruned(starts);
		if (complete)
			finish();
		return best_;
	}

private:
	bool checking_derivatives() const { return !opt_.derivative_test_file.empty(); }
	bool continuation_skips(double relax) const
	{
		return (!set_.smoothed || !opt_.continuation || checking_derivatives()) && relax != 1.0;
	}

	// One Ipopt solve of c's problem at the smoothing multiplier, from start
	// (empty: the phases' guesses), into a new c.nlp; its iterations count
	// against the start's budget.
	NlpStatus step(Coarse &c, double relax, const std::vector<double> &start, bool warm)
	{
		const Stacked &p = c.p;
		c.nlp = stacked_nlp(p, relax);
		SolveOptions so = set_.step_opt;
		if (opt_.iteration_budget > 0)
			so.max_iter = std::max(0, std::min(so.max_iter, opt_.iteration_budget - c.iterations));
		NlpStatus st = c.nlp->solve(so, start, NlpSettings{warm, set_.permuting_scaling});
		c.iterations += st.iterations;
		if (opt_.debug)
			std::fprintf(stderr, "start T=%g N=%d relax %g: %s, %d iterations\n",
				     p.setups[0].T_guess, p.setups[0].segments, relax, st.text(), st.iterations);
		return st;
	}

	// The problem of a start: its durations and guess path, coarse meshes,
	// and the modes' own path guesses for straight-line phases.
	Stacked start_problem(const Start &st) const
	{
		Stacked p = base_;
		if (!st.path.empty())
			p.setups[0].guess = st.path;
		for (size_t k = 0; k < p.setups.size(); k++) {
			PhaseSetup &s = p.setups[k];
			const ModeInfo &i = p.info[k];
			s.T_guess = st.T[k];
			s.segments = coarse_segments(s, i, st.T[k], opt_);
			if (i.path_guess && s.guess.size() == 2) {
				s.guess = i.path_guess(s.guess[0], s.guess[1], st.T[k]);
				s.guess_at.clear();
			}
		}
		return p;
	}

	// Continuation: smoother problems first, each starting the next; the
	// last (1) has docs/models.md's exact constants. False if a start's last
	// step failed.
	bool continuation(const Start &st, Coarse &c)
	{
		c.p = start_problem(st);
		best_.starts++;
		std::vector<double> start;
		for (double relax : set_.levels) {
			if (continuation_skips(relax))
				continue;
			c.res = step(c, relax, start, !start.empty());
			if (c.res.succeeded())
				start = c.nlp->solution();
			else if (set_.give_up)
				break;
		}
		if (!c.res.succeeded()) {
			last_status_ = c.res.text();
			return false;
		}
		best_.converged_starts++;
		c.cost = switch_cost_;
		for (size_t k = 0; k < c.p.setups.size(); k++) {
			Solution ph;
			c.nlp->fill(k, ph);
			c.cost += ph.cost;
			c.T += ph.T;
		}
		return true;
	}

	// c's solution phase by phase, each replayed (opt.replay); failed[k]
	// says phase k's replay failed. Notes why the first failing phase failed.
	MultiPhaseSolution replayed(Coarse &c, const NlpStatus &res, int iterations, std::vector<bool> &failed)
	{
		MultiPhaseSolution s;
		s.modes = c.p.modes;
		s.status = res.status;
		s.status_text = res.text();
		s.iterations = iterations;
		failed.assign(c.p.setups.size(), false);
		for (size_t k = 0; k < c.p.setups.size(); k++) {
			Solution ph;
			c.nlp->fill(k, ph);
			ph.status = s.status;
			ph.status_text = s.status_text;
			ph.iterations = iterations;
			if (opt_.replay)
				failed[k] = !replay_phase(c, k, ph, std::find(failed.begin(), failed.end(), true) == failed.end());
			ph.converged = !opt_.replay || ph.replay_ok;
			s.cost += ph.cost;
			s.T += ph.T;
			s.replay_cost += ph.replay_cost;
			s.replay_error = std::max(s.replay_error, ph.replay_error);
			s.phases.push_back(std::move(ph));
		}
		return s;
	}

	// Replays phase k's solution ph; if it fails and note_rejection, says why.
	bool replay_phase(const Coarse &c, size_t k, Solution &ph, bool note_rejection)
	{
		const hylo_mode mode = c.p.modes[k];
		replay(mode, robot_, ph, opt_.replay_state_tol);
		if (opt_.debug)
			std::fprintf(stderr, "  replay %s: error %.3g, cost %.6g vs %.6g: %s\n", hylo_mode_str(mode),
				     ph.replay_error, ph.replay_cost, ph.cost, replay_verdict(ph).c_str());
		if (!ph.replay_ok && note_rejection)
			rejection_ = phase_name(c.p, k) + ", " + std::to_string(c.p.setups[k].segments) +
				     " segments): " + replay_verdict(ph);
		return ph.replay_ok;
	}

	// A solution whose replays all passed: kept if the cheapest so far.
	void accept(MultiPhaseSolution s)
	{
		s.converged = true;
		s.cost += switch_cost_;
		s.replay_cost += switch_cost_;
		if (s.cost < best_.cost) {
			s.starts = best_.starts;
			s.converged_starts = best_.converged_starts;
			s.refined_starts = best_.refined_starts;
			best_ = std::move(s);
		}
	}

	// The phases whose replay failed on meshes of twice the segments, solved
	// from the coarser solution (its knots and midpoints become knots). That
	// start is infeasible where knots were interpolated, and at the exact
	// constants Ipopt can wander to its iteration limit from it; where the
	// settings say so, a failure is solved again through the last smoothed
	// level first (on 60 marine rows it found cheaper basins for 3 labels).
	NlpStatus refine_mesh(Coarse &c, const std::vector<bool> &failed)
	{
		std::vector<double> fine = c.nlp->refined(failed);
		for (size_t k = 0; k < c.p.setups.size(); k++)
			if (failed[k])
				c.p.setups[k].segments *= 2;
		const int before = c.iterations;
		NlpStatus st = step(c, 1.0, fine, true);
		if (st.succeeded() || set_.retry_relax <= 0)
			return st;
		st = step(c, set_.retry_relax, fine, true);
		if (st.succeeded()) {
			std::vector<double> smoothed = c.nlp->solution();
			st = step(c, 1.0, smoothed, true);
		}
		st.iterations = c.iterations - before;   // every step of this refinement
		return st;
	}

	// A solution s whose replays passed, on the meshes its phases are
	// accepted on (PhaseSetup::accept_segments): phases on coarser meshes are
	// solved again on doubled meshes from it until they reach theirs, those
	// whose replay fails there refined as refine() does. The finest solution
	// whose replays pass is returned: s where no finer one does (it passed
	// its own replays).
	MultiPhaseSolution on_accepted_mesh(Coarse &c, MultiPhaseSolution s)
	{
		const std::string rejection = rejection_;   // s is accepted: no rejection to report
		std::vector<bool> failed(c.p.setups.size(), false);
		int iterations = s.iterations, replay_refinements = 0;
		for (;;) {
			std::vector<bool> finer;
			for (size_t k = 0; k < c.p.setups.size(); k++)
				finer.push_back(failed[k] || c.p.setups[k].segments < c.p.setups[k].accept_segments);
			if (std::find(finer.begin(), finer.end(), true) == finer.end())
				break;
			if (std::find(failed.begin(), failed.end(), true) != failed.end() &&
			    replay_refinements++ >= set_.refinements)
				break;
			NlpStatus res = refine_mesh(c, finer);
			iterations += res.iterations;
			if (!res.succeeded())
				break;
			MultiPhaseSolution fine = replayed(c, res, iterations, failed);
			if (std::find(failed.begin(), failed.end(), true) == failed.end())
				s = std::move(fine);
		}
		rejection_ = rejection;
		return s;
	}

	// Mesh refinement until the replays agree, at most set_.refinements
	// times; the result is kept if it is the cheapest so far. True if the
	// replays agreed.
	bool refine(Coarse &c)
	{
		best_.refined_starts++;
		NlpStatus res = c.res;
		int iterations = res.iterations;
		for (int refinement = 0;; refinement++) {
			std::vector<bool> failed;
			MultiPhaseSolution s = replayed(c, res, iterations, failed);
			if (std::find(failed.begin(), failed.end(), true) == failed.end()) {
				accept(on_accepted_mesh(c, std::move(s)));
				return true;
			}
			rejected_cost_ = std::min(rejected_cost_, s.cost + switch_cost_);
			if (refinement >= set_.refinements)
				return false;
			res = refine_mesh(c, failed);
			iterations += res.iterations;
			if (!res.succeeded()) {
				rejection_ += "; then the finer mesh failed (" + std::string(res.text()) + ")";
				return false;
			}
		}
	}

	// Each start in turn, refined as soon as it converges; modes that keep
	// their first accepted start stop there. Without opt.refine_repeats, a
	// start whose coarse optimum repeats one that an earlier start was
	// refined from into an accepted solution is not refined again. False:
	// the derivative checker ran on the first start, nothing more to do.
	bool each_refined_in_turn(const std::vector<Start> &starts)
	{
		std::vector<CoarseResult> accepted;
		for (const Start &st : starts) {
			if (best_.converged && set_.first_accepted)
				break;
			Coarse c;
			bool ok = continuation(st, c);
			if (checking_derivatives())
				return false;
			if (!ok)
				continue;
			const CoarseResult r{c.cost, c.T};
			if (!opt_.refine_repeats && std::any_of(accepted.begin(), accepted.end(), [&r](const CoarseResult &e) {
				    return same_result(e, r);
			    }))
				continue;
			if (refine(c))
				accepted.push_back(r);
		}
		return true;
	}

	// Every start on the coarse mesh first. A start that reached an earlier
	// one's solution is not refined again, nor one whose coarse cost is more
	// than refine_within above the best refined result: refinement lowers
	// costs by a few percent. False as each_refined_in_turn.
	bool coarse_first_then_pruned(const std::vector<Start> &starts)
	{
		std::vector<Coarse> reached;
		for (const Start &st : starts) {
			Coarse c;
			bool ok = continuation(st, c);
			if (checking_derivatives())
				return false;
			if (ok && std::none_of(reached.begin(), reached.end(),
					       [&c](const Coarse &earlier) { return same_result(earlier, c); }))
				reached.push_back(std::move(c));
		}
		std::stable_sort(reached.begin(), reached.end(),
				 [](const Coarse &a, const Coarse &b) { return a.cost < b.cost; });
		for (Coarse &c : reached)
			if (worth_refining(c))
				refine(c);
		return true;
	}

	bool worth_refining(const Coarse &c) const
	{
		const double known = std::min(best_.converged ? best_.cost : incumbent_, incumbent_);
		return c.cost <= known * (1 + opt_.refine_within);
	}

	// The counts' and failures' summary; the time taken.
	void finish()
	{
		if (!best_.converged) {
			best_.cost = 0;
			best_.status_text = best_.converged_starts ? "replay rejected every solution" : "no start converged";
			best_.rejection = rejection_;
			best_.rejected_cost = rejected_cost_;
			if (!best_.converged_starts)
				best_.rejection = "Ipopt: " + last_status_;
		}
		best_.solve_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
	}

	const RobotParams &robot_;
	const Stacked &base_;
	const double switch_cost_;
	const SolveOptions &opt_;
	const double incumbent_;
	const StepSettings set_;
	const std::chrono::steady_clock::time_point t0_ = std::chrono::steady_clock::now();
	MultiPhaseSolution best_;
	std::string last_status_ = "no start";   // Ipopt's status of the last start that failed
	std::string rejection_;                  // why the last rejected solution was rejected
	double rejected_cost_ = std::numeric_limits<double>::infinity();
};

}  // namespace

MultiPhaseSolution solve_stacked(const RobotParams &robot, const Stacked &base, const std::vector<Start> &starts,
				 double switch_cost, const SolveOptions &opt, double incumbent)
{
	return Strategy(robot, base, switch_cost, opt, incumbent).run(starts);
}

}  // namespace hylo::trainer::internal
