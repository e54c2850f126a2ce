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

#include <IpIpoptApplication.hpp>
#include <IpSolveStatistics.hpp>
#include <IpTNLP.hpp>

#include "trainer/hs_phase.hpp"
#include "trainer/models.hpp"
#include "trainer/replay.hpp"

namespace hylo::trainer {
namespace {

using internal::Index;
using internal::Number;
using internal::PhaseBlock;
using internal::PhaseSetup;

// A linear row resolved to variable indices of the stacked problem.
struct Row {
	std::vector<std::pair<int, double>> terms;
	double lo = 0, hi = 0;
};

// The Ipopt problem: phases stacked (variables and constraints in phase
// order), then the linear rows joining them. Held by SmartPtr, one per solve.
class CollocationNlp : public Ipopt::TNLP {
public:
	CollocationNlp(std::vector<std::unique_ptr<PhaseBlock>> phases, std::vector<Row> rows)
		: ph_(std::move(phases)), rows_(std::move(rows))
	{
		for (const auto &p : ph_) {
			vo_.push_back(nvar_);
			co_.push_back(ncon_);
			nvar_ += p->nvar();
			ncon_ += p->ncon();
		}
	}

	int var_offset(size_t phase) const { return vo_[phase]; }
	const PhaseBlock &phase(size_t k) const { return *ph_[k]; }
	size_t n_phases() const { return ph_.size(); }
	// Start from z (a solution of the same size) instead of the guess.
	void warm_start(const std::vector<double> &z) { warm_ = z; }
	const std::vector<double> &solution() const { return z_; }

	bool get_nlp_info(Index &n, Index &m, Index &nnz_jac, Index &nnz_h, IndexStyleEnum &style) override
	{
		n = nvar_;
		m = ncon_ + static_cast<int>(rows_.size());
		nnz_jac = 0;
		nnz_h = 0;
		for (const auto &p : ph_) {
			nnz_jac += p->nnz_jac();
			nnz_h += p->nnz_h();
		}
		for (const Row &r : rows_)
			nnz_jac += static_cast<int>(r.terms.size());
		style = TNLP::C_STYLE;
		return true;
	}

	bool get_bounds_info(Index, Number *xl, Number *xu, Index, Number *gl, Number *gu) override
	{
		for (size_t k = 0; k < ph_.size(); k++)
			ph_[k]->bounds(xl + vo_[k], xu + vo_[k], gl + co_[k], gu + co_[k]);
		for (size_t i = 0; i < rows_.size(); i++) {
			gl[ncon_ + static_cast<int>(i)] = rows_[i].lo;
			gu[ncon_ + static_cast<int>(i)] = rows_[i].hi;
		}
		return true;
	}

	bool get_starting_point(Index n, bool, Number *z, bool, Number *, Number *, Index, bool,
				Number *) override
	{
		if (warm_.size() == static_cast<size_t>(n)) {
			std::copy(warm_.begin(), warm_.end(), z);
			return true;
		}
		for (size_t k = 0; k < ph_.size(); k++)
			ph_[k]->start(z + vo_[k]);
		return true;
	}

	bool get_scaling_parameters(Number &obj_scaling, bool &use_x_scaling, Index, Number *x_scaling,
				    bool &use_g_scaling, Index, Number *g_scaling) override
	{
		double T = 0;
		for (const auto &p : ph_)
			T += p->T_guess();
		obj_scaling = 1.0 / std::max(1.0, T * 10.0);
		use_x_scaling = true;
		use_g_scaling = true;
		for (size_t k = 0; k < ph_.size(); k++)
			ph_[k]->scaling(x_scaling + vo_[k], g_scaling + co_[k]);
		for (size_t i = 0; i < rows_.size(); i++)
			g_scaling[ncon_ + static_cast<int>(i)] = 1.0;
		return true;
	}

	bool eval_f(Index, const Number *z, bool new_x, Number &obj) override
	{
		obj = 0;
		for (size_t k = 0; k < ph_.size(); k++)
			obj += ph_[k]->objective(z + vo_[k], new_x);
		return true;
	}

	bool eval_grad_f(Index, const Number *z, bool new_x, Number *g) override
	{
		for (size_t k = 0; k < ph_.size(); k++)
			ph_[k]->gradient(z + vo_[k], new_x, g + vo_[k]);
		return true;
	}

	bool eval_g(Index, const Number *z, bool new_x, Index, Number *g) override
	{
		for (size_t k = 0; k < ph_.size(); k++)
			ph_[k]->constraints(z + vo_[k], new_x, g + co_[k]);
		for (size_t i = 0; i < rows_.size(); i++) {
			double s = 0;
			for (const auto &t : rows_[i].terms)
				s += t.second * z[t.first];
			g[ncon_ + static_cast<int>(i)] = s;
		}
		return true;
	}

	bool eval_jac_g(Index, const Number *z, bool new_x, Index, Index, Index *iRow, Index *jCol,
			Number *v) override
	{
		int e = 0;
		for (size_t k = 0; k < ph_.size(); k++) {
			if (v)
				ph_[k]->jac_values(z + vo_[k], new_x, v + e);
			else
				ph_[k]->jac_structure(iRow + e, jCol + e, vo_[k], co_[k]);
			e += ph_[k]->nnz_jac();
		}
		for (size_t i = 0; i < rows_.size(); i++)
			for (const auto &t : rows_[i].terms) {
				if (v) {
					v[e] = t.second;
				} else {
					iRow[e] = ncon_ + static_cast<int>(i);
					jCol[e] = t.first;
				}
				e++;
			}
		return true;
	}

	// The rows are linear: only the phases contribute to the Hessian.
	bool eval_h(Index, const Number *z, bool, Number sigma, Index, const Number *lambda, bool, Index,
		    Index *iRow, Index *jCol, Number *v) override
	{
		int e = 0;
		for (size_t k = 0; k < ph_.size(); k++) {
			if (v)
				ph_[k]->hess_values(z + vo_[k], sigma, lambda + co_[k], v + e);
			else
				ph_[k]->hess_structure(iRow + e, jCol + e, vo_[k]);
			e += ph_[k]->nnz_h();
		}
		return true;
	}

	void finalize_solution(Ipopt::SolverReturn, Index n, const Number *z, const Number *,
			       const Number *, Index, const Number *, const Number *, Number,
			       const Ipopt::IpoptData *, Ipopt::IpoptCalculatedQuantities *) override
	{
		z_.assign(z, z + n);
	}

	// Phase k of the solution.
	void fill(size_t k, Solution &s) { ph_[k]->fill(z_.data() + vo_[k], s); }
	// The solution with the phases marked in `which` on meshes of twice the
	// segments, the others as they are.
	std::vector<double> refined(const std::vector<bool> &which) const
	{
		std::vector<double> out;
		for (size_t k = 0; k < ph_.size(); k++) {
			const Number *z = z_.data() + vo_[k];
			std::vector<double> r = which[k] ? ph_[k]->refine(z) : std::vector<double>(z, z + ph_[k]->nvar());
			out.insert(out.end(), r.begin(), r.end());
		}
		return out;
	}

private:
	std::vector<std::unique_ptr<PhaseBlock>> ph_;
	std::vector<Row> rows_;
	std::vector<int> vo_, co_;
	int nvar_ = 0, ncon_ = 0;
	std::vector<double> z_, warm_;
};

// Sets o by the type Ipopt registered for its name; false if there is none,
// the value does not parse as that type, or Ipopt refuses it (silently).
bool set_ipopt_option(Ipopt::IpoptApplication &app, const IpoptOption &o)
{
	Ipopt::SmartPtr<const Ipopt::RegisteredOption> reg = app.RegOptions()->GetOption(o.name);
	if (!Ipopt::IsValid(reg))
		return false;
	Ipopt::SmartPtr<Ipopt::OptionsList> list = app.Options();
	const char *begin = o.value.c_str(), *end = begin + o.value.size();
	switch (reg->Type()) {
	case Ipopt::OT_Number: {
		double v = 0;
		auto r = std::from_chars(begin, end, v);
		return r.ec == std::errc() && r.ptr == end && list->SetNumericValue(o.name, v, true, true);
	}
	case Ipopt::OT_Integer: {
		int v = 0;
		auto r = std::from_chars(begin, end, v);
		return r.ec == std::errc() && r.ptr == end && list->SetIntegerValue(o.name, v, true, true);
	}
	case Ipopt::OT_String:
		return list->SetStringValue(o.name, o.value, true, true);
	default:
		return false;
	}
}

// Ipopt's mumps_permuting_scaling (MUMPS ICNTL(6)): Ipopt's default lets
// MUMPS choose; 0 skips the column permutation and scaling (MC64).
constexpr int kMumpsChoosesPermutingScaling = 7;

Ipopt::SmartPtr<Ipopt::IpoptApplication> make_app(const SolveOptions &opt, bool warm, int permuting_scaling)
{
	Ipopt::SmartPtr<Ipopt::IpoptApplication> app = IpoptApplicationFactory();
	bool ok = app->Options()->SetIntegerValue("print_level", 0);
	ok = ok && app->Options()->SetStringValue("sb", "yes");
	ok = ok && app->Options()->SetNumericValue("tol", opt.tol);
	ok = ok && app->Options()->SetIntegerValue("max_iter", opt.max_iter);
	ok = ok && app->Options()->SetStringValue("linear_solver", "mumps");
	ok = ok && app->Options()->SetIntegerValue("mumps_permuting_scaling", permuting_scaling);
	ok = ok && app->Options()->SetStringValue("nlp_scaling_method", "user-scaling");
	if (opt.objective_scale != 1)
		ok = ok && app->Options()->SetNumericValue("obj_scaling_factor", opt.objective_scale);
	// Monotone barrier from a small start: the adaptive strategy hit the
	// iteration limit on stiff friction terms (docs/decisions.md).
	ok = ok && app->Options()->SetStringValue("mu_strategy", "monotone");
	// A warm start is already near the optimum: a small barrier keeps it there.
	ok = ok && app->Options()->SetNumericValue("mu_init", warm ? 1e-5 : 1e-2);
	if (warm) {
		ok = ok && app->Options()->SetNumericValue("bound_push", 1e-6);
		ok = ok && app->Options()->SetNumericValue("bound_frac", 1e-6);
	}
	if (!opt.derivative_test_file.empty()) {
		ok = ok && app->Options()->SetStringValue("derivative_test", "second-order");
		ok = ok && app->Options()->SetNumericValue("derivative_test_perturbation", opt.derivative_test_perturbation);
		ok = ok && app->Options()->SetNumericValue("derivative_test_tol", 1e-4);
		ok = ok && app->Options()->SetStringValue("output_file", opt.derivative_test_file);
		ok = ok && app->Options()->SetIntegerValue("file_print_level", 5);
		ok = ok && app->Options()->SetIntegerValue("print_level", 0);
		ok = ok && app->Options()->SetIntegerValue("max_iter", 0);
	}
	for (const IpoptOption &o : opt.ipopt_options)
		ok = ok && set_ipopt_option(*app, o);
	if (!ok)
		throw std::logic_error("an Ipopt option was refused");
	// An empty options file name: never read ./ipopt.opt (docs/deps.md).
	if (app->Initialize("") != Ipopt::Solve_Succeeded)
		throw std::runtime_error("Ipopt failed to initialize");
	return app;
}

bool succeeded(Ipopt::ApplicationReturnStatus st)
{
	return st == Ipopt::Solve_Succeeded || st == Ipopt::Solved_To_Acceptable_Level;
}

const char *status_text(Ipopt::ApplicationReturnStatus st)
{
	switch (st) {
	case Ipopt::Solve_Succeeded: return "solved";
	case Ipopt::Solved_To_Acceptable_Level: return "solved to acceptable level";
	case Ipopt::Infeasible_Problem_Detected: return "infeasible";
	case Ipopt::Maximum_Iterations_Exceeded: return "maximum iterations";
	case Ipopt::Restoration_Failed: return "restoration failed";
	case Ipopt::Error_In_Step_Computation: return "error in step computation";
	case Ipopt::Maximum_CpuTime_Exceeded: return "maximum cpu time";
	case Ipopt::Diverging_Iterates: return "diverging iterates";
	case Ipopt::Invalid_Number_Detected: return "invalid number";
	default: return "failed";
	}
}

// What the solver needs of a mode outside the model templates.
struct ModeInfo {
	int nx = 0, nu = 0;
	bool smoothed = false;
	Bounds bounds;
	std::function<std::unique_ptr<PhaseBlock>(double relax, const PhaseSetup &)> make;
	std::function<std::vector<double>(const double *xs)> full_state;
	std::function<double(const double *a, const double *b)> distance;   // between full states
	double typical_speed = 1;
	std::vector<double> continuation = {100.0, 10.0, 3.0, 1.0};  // smoothing multipliers, to 1
	int refinements = 0;          // the parameter file's solver: {refinements: N}
	int min_segments = 0;         // a start's mesh has at least these segments
	double max_step_s = 0;        // > 0: and segments of at most this guessed duration [s]
	bool first_accepted = false;  // keep the first start that passes, try no more
	int step_max_iter = 0;        // > 0: a continuation step's iteration limit; a start
				      // whose step fails is given up
	int mumps_permuting_scaling = kMumpsChoosesPermutingScaling;
	// Set: the initial guess of a phase guessed as a straight line a -> b,
	// given its duration T (the start's).
	std::function<std::vector<std::vector<double>>(const std::vector<double> &a,
						       const std::vector<double> &b, double T)> path_guess;
	// Set: the initial guesses of a BVP a -> b besides the straight line
	// (solve_bvp_strategies).
	std::function<std::vector<Guess>(const std::vector<double> &a, const std::vector<double> &b)> strategy_guesses;
};

constexpr double kPi = 3.14159265358979323846;

// Planar modes, x = (px, py, vx, vy, theta, omega, ...). Paths that differ in
// strategy, not only in duration; from each start Ipopt stays in the basin
// it starts in, so a basin no start leads into is never found:
// - backing up with the start's heading, through the midpoint, and driving
//   forward facing the goal (from the straight line alone, goals behind the
//   robot often ended in a worse local optimum; docs/decisions.md, "Training
//   labels"); durations from the path length;
// - (issue #35) backing up with the start's heading at twice that duration;
//   reversing towards the goal, the rear facing it, through the midpoint;
//   and turning on the spot to that heading, reversing, turning on the spot
//   to the goal's heading. Their headings are wound to the nearest the mean
//   of the start's and the goal's (theta is not wrapped: the goal's is
//   reached as given). Durations add the turns at 2 rad/s (through the
//   midpoint) or 1 rad/s (on the spot). On the first 12 Ambot ground
//   samples these three found basins 25% (sample 0, 131 -> 98 J) and 23%
//   (sample 10, 144 -> 111 J) below every other start's (docs/decisions.md).
// point(px, py, v, theta) is the mode's full state there (vy = omega = 0;
// marine's paddle speeds at their steady value for v).
std::vector<Guess> planar_strategy_guesses(
	const std::vector<double> &a, const std::vector<double> &b, const Bounds &bd, double speed,
	const std::function<std::vector<double>(double, double, double, double)> &point)
{
	std::vector<double> mid = a;
	mid[0] = 0.5 * (a[0] + b[0]);
	mid[1] = 0.5 * (a[1] + b[1]);
	mid[3] = mid[5] = 0;
	std::vector<double> back = mid, face = mid;
	back[2] = std::max(-speed, bd.x_lo[2]);
	face[2] = std::min(speed, bd.x_hi[2]);
	double bearing = std::atan2(b[1] - a[1], b[0] - a[0]);
	face[4] = a[4] + std::remainder(bearing - a[4], 2 * kPi);
	const double d = std::hypot(b[0] - a[0], b[1] - a[1]);
	// duration_guess of a path through the midpoint (its length is d).
	const double T = std::max(bd.T_min * 2, d / speed);
	std::vector<Guess> out = {{T, {a, back, b}}, {T, {a, face, b}}};
	out.push_back({2 * T, {a, back, b}});
	const double mean = 0.5 * (a[4] + b[4]);
	const double h = mean + std::remainder(bearing + kPi - mean, 2 * kPi);
	const double turn = std::fabs(h - a[4]) + std::fabs(b[4] - h);
	const double rev = std::max(-speed, bd.x_lo[2]);
	out.push_back({T + 0.5 * turn, {a, point(mid[0], mid[1], rev, h), b}});
	out.push_back({T + turn,
		       {a, point(a[0], a[1], 0, h), point(mid[0], mid[1], rev, h), point(b[0], b[1], 0, h), b}});
	for (Guess &g : out)
		g.T = std::min(g.T, bd.T_max);
	return out;
}

template <class M>
ModeInfo info_of(const M &model)
{
	ModeInfo i;
	i.nx = M::NX;
	i.nu = M::NU;
	i.smoothed = M::kSmoothed;
	i.bounds = model.bounds();
	i.make = [model](double relax, const PhaseSetup &s) -> std::unique_ptr<PhaseBlock> {
		M m = model;
		m.relax = relax;
		return std::make_unique<internal::HsPhase<M>>(m, s);
	};
	i.full_state = [model](const double *xs) {
		auto a = model.full_state(xs);
		return std::vector<double>(a.begin(), a.end());
	};
	i.distance = [model](const double *a, const double *b) { return model.position_distance(a, b); };
	i.typical_speed = model.typical_speed();
	return i;
}

ModeInfo mode_info(const std::string &mode, const RobotParams &robot)
{
	if (!known_mode(mode))
		throw std::invalid_argument("unknown mode '" + mode + "' (ground, marine, flight, di_neg, di_pos)");
	const ModeParams &p = robot.mode(mode);
	ModeInfo i = mode == "ground"   ? info_of(GroundModel(p, robot.g))
		     : mode == "marine" ? info_of(MarineModel(p, robot.g))
		     : mode == "flight" ? info_of(FlightModel(p, robot.g))
					: info_of(DiModel(p, mode == "di_pos"));
	i.refinements = p.refinements;
	// Flight: segments of at most 20 ms (the rotors' time constant is 13 ms),
	// the Hermite guess with fine continuation steps, the first start that
	// passes, and no MC64 in MUMPS (2.2x less CPU, same labels); each
	// measured in docs/decisions.md, "Flight training: five changes".
	if (mode == "flight") {
		i.mumps_permuting_scaling = 0;
		i.continuation = {100.0, 50.0, 30.0, 20.0, 10.0, 5.0, 3.0, 2.0, 1.5, 1.0};
		i.min_segments = 80;
		i.max_step_s = 0.02;
		i.first_accepted = true;
		i.step_max_iter = 400;
		FlightModel fm(p, robot.g);
		i.path_guess = [fm](const std::vector<double> &a, const std::vector<double> &b, double T) {
			return fm.path_guess(a, b, T, 16);
		};
	}
	if (mode == "ground" || mode == "marine") {
		Bounds bd = i.bounds;
		double speed = i.typical_speed;
		auto full = i.full_state;
		i.strategy_guesses = [bd, speed, full](const std::vector<double> &a, const std::vector<double> &b) {
			auto point = [&full](double px, double py, double v, double th) {
				const double xs[4] = {px, py, v, th};
				return full(xs);
			};
			return planar_strategy_guesses(a, b, bd, speed, point);
		};
	}
	return i;
}

// One stacked problem as the engine sees it: modes, their setups and the
// rows by knot reference (resolved per mesh, since offsets change).
struct Stacked {
	std::vector<std::string> modes;
	std::vector<ModeInfo> info;
	std::vector<PhaseSetup> setups;
	std::vector<LinearRow> rows;
};

Ipopt::SmartPtr<CollocationNlp> build(const Stacked &p, double relax)
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
	return new CollocationNlp(std::move(blocks), std::move(rows));
}

// A start: every phase's duration guess, and the states phase 0's guess runs
// through (empty: the base's).
struct Start {
	std::vector<double> T;
	std::vector<std::vector<double>> path;
};

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
		       Ipopt::SmartPtr<CollocationNlp> &nlp, bool warm, const SolveOptions &o) {
		nlp = build(p, relax);
		if (!start.empty())
			nlp->warm_start(start);
		auto app = make_app(o, warm, permuting_scaling);
		Ipopt::ApplicationReturnStatus st = app->OptimizeTNLP(nlp);
		int it = Ipopt::IsValid(app->Statistics()) ? app->Statistics()->IterationCount() : 0;
		if (debug)
			std::fprintf(stderr, "start T=%g N=%d relax %g: %s, %d iterations\n",
				     p.setups[0].T_guess, p.setups[0].segments, relax, status_text(st), it);
		return std::make_pair(st, it);
	};
	// A start after its continuation on the coarse mesh: the cost (with the
	// switches') and duration it reached there.
	struct Coarse {
		Stacked p;
		Ipopt::SmartPtr<CollocationNlp> nlp;
		std::pair<Ipopt::ApplicationReturnStatus, int> res{Ipopt::Solve_Succeeded, 0};
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
			if (succeeded(c.res.first))
				start = c.nlp->solution();
			else if (give_up)
				break;
		}
		if (!succeeded(c.res.first)) {
			last_status = status_text(c.res.first);
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
		Ipopt::SmartPtr<CollocationNlp> &nlp = c.nlp;
		std::pair<Ipopt::ApplicationReturnStatus, int> res = c.res;
		int iterations = res.second;
		for (int refinement = 0;; refinement++) {
			MultiPhaseSolution s;
			s.modes = p.modes;
			s.status = static_cast<int>(res.first);
			s.status_text = status_text(res.first);
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
			iterations += res.second;
			if (!succeeded(res.first)) {
				rejection += "; then the finer mesh failed (" + std::string(status_text(res.first)) + ")";
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
void check_corridor(const PhaseSpec &ps, const std::string &where)
{
	const size_t dims = ps.mode == "flight" ? 3 : ps.mode == "ground" || ps.mode == "marine" ? 2 : 0;
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

bool known_mode(const std::string &m)
{
	return m == "ground" || m == "marine" || m == "flight" || m == "di_neg" || m == "di_pos";
}

namespace {
const char *const kModeNames[] = {"", "ground", "marine", "flight", "di_neg", "di_pos"};
}  // namespace

std::string mode_name(int m)
{
	return m >= 1 && m <= 5 ? kModeNames[m] : "";
}

int mode_number(const std::string &mode)
{
	for (int m = 1; m <= 5; m++)
		if (mode == kModeNames[m])
			return m;
	return 0;
}

int sampled_dim(const std::string &m)
{
	if (m == "ground" || m == "marine")
		return 4;
	if (m == "flight")
		return 6;
	if (m == "di_neg" || m == "di_pos")
		return 2;
	return 0;
}

int state_dim(const std::string &m)
{
	if (m == "ground")
		return GroundModel::NX;
	if (m == "marine")
		return MarineModel::NX;
	if (m == "flight")
		return FlightModel::NX;
	return known_mode(m) ? DiModel::NX : 0;
}

int input_dim(const std::string &m)
{
	if (m == "ground")
		return GroundModel::NU;
	if (m == "marine")
		return MarineModel::NU;
	if (m == "flight")
		return FlightModel::NU;
	return known_mode(m) ? DiModel::NU : 0;
}

std::vector<double> full_state(const std::string &mode, const RobotParams &robot, const double *xs)
{
	return mode_info(mode, robot).full_state(xs);
}

std::pair<std::vector<double>, std::vector<double>> state_bounds(const std::string &mode,
								 const RobotParams &robot)
{
	Bounds b = mode_info(mode, robot).bounds;
	return {b.x_lo, b.x_hi};
}

namespace {

// The duration guess of a phase whose guess path has the given length (not
// clamped to T_max).
double duration_guess(const ModeInfo &info, double length)
{
	return std::max(info.bounds.T_min * 2, length / info.typical_speed);
}

// The BVP x1s -> x2s of mode as a one-phase stacked problem.
struct Bvp {
	ModeInfo info;
	Stacked p;
	std::vector<double> a, b;
};

Bvp bvp(const std::string &mode, const RobotParams &robot, const double *x1s, const double *x2s,
	const SolveOptions &opt)
{
	Bvp v{mode_info(mode, robot), {}, {}, {}};
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
	std::vector<Start> starts;
	for (const Guess &g : guesses)
		starts.push_back({{std::min(std::max(g.T, v.info.bounds.T_min), v.info.bounds.T_max)}, g.path});
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
	const Bounds &bd = v.info.bounds;
	std::vector<double> guesses = opt.T_guesses;
	if (guesses.empty()) {
		double base = duration_guess(v.info, v.info.distance(v.a.data(), v.b.data()));
		guesses = {base, 2 * base, 0.5 * base + bd.T_min};
	}
	std::vector<Start> starts;
	for (double T : guesses)
		starts.push_back({{std::min(std::max(T, bd.T_min), bd.T_max)}, {}});
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
	const size_t nx = static_cast<size_t>(v.info.nx);
	auto same = [](const std::vector<double> &x, const std::vector<double> &y) {
		for (size_t k = 0; k < x.size(); k++)
			if (std::fabs(x[k] - y[k]) > 1e-9 * std::max(1.0, std::fabs(y[k])))
				return false;
		return true;
	};
	for (size_t g = 0; g < guesses.size(); g++) {
		const auto &path = guesses[g].path;
		std::string where = "guess " + std::to_string(g) + " of a " + mode + " BVP: ";
		if (path.size() < 2)
			throw std::invalid_argument(where + "its path needs at least two states");
		for (const auto &x : path)
			if (x.size() != nx)
				throw std::invalid_argument(where + "a state has " + std::to_string(x.size()) +
							    " components, the mode has " + std::to_string(nx));
		if (!same(path.front(), v.a) || !same(path.back(), v.b))
			throw std::invalid_argument(where + "its path does not run from the BVP's start to its goal");
		if (!(guesses[g].T > 0) || !std::isfinite(guesses[g].T))
			throw std::invalid_argument(where + "its duration is not positive");
	}
	return solve_from_guesses(robot, v, opt, guesses, incumbent);
}

Guess transplanted_guess(const Trajectory &traj, double T, const std::vector<double> &a,
			 const std::vector<double> &b, int points)
{
	const size_t nx = static_cast<size_t>(traj.nx), n = traj.t.size();
	if (points < 2 || n < 2 || a.size() != nx || b.size() != nx || traj.x.size() != n * nx)
		throw std::invalid_argument("transplanted_guess: a trajectory of " + std::to_string(n) +
					    " times and states of " + std::to_string(traj.nx) + " for boundary states of " +
					    std::to_string(a.size()) + " and " + std::to_string(b.size()) + ", " +
					    std::to_string(points) + " points");
	const double t0 = traj.t.front(), t1 = traj.t.back();
	auto state_at = [&](double t, size_t k) {
		size_t i = static_cast<size_t>(std::upper_bound(traj.t.begin(), traj.t.end(), t) - traj.t.begin());
		i = std::min(std::max<size_t>(i, 1), n - 1);
		double ta = traj.t[i - 1], tb = traj.t[i], w = tb > ta ? (t - ta) / (tb - ta) : 0;
		w = std::min(std::max(w, 0.0), 1.0);
		return traj.x[(i - 1) * nx + k] + w * (traj.x[i * nx + k] - traj.x[(i - 1) * nx + k]);
	};
	Guess g;
	g.T = T;
	for (int p = 0; p < points; p++) {
		double s = static_cast<double>(p) / (points - 1);
		std::vector<double> x(nx);
		for (size_t k = 0; k < nx; k++)
			x[k] = state_at(t0 + s * (t1 - t0), k) + (1 - s) * (a[k] - traj.x[k]) +
			       s * (b[k] - traj.x[(n - 1) * nx + k]);
		g.path.push_back(std::move(x));
	}
	g.path.front() = a;   // exactly, not to rounding
	g.path.back() = b;
	return g;
}

IpoptOption parse_ipopt_option(const std::string &text)
{
	size_t eq = text.find('=');
	if (eq == std::string::npos || eq == 0)
		throw std::invalid_argument("'" + text + "' is not NAME=VALUE");
	IpoptOption o{text.substr(0, eq), text.substr(eq + 1)};
	// No console journal: Ipopt would print the option's documentation.
	Ipopt::SmartPtr<Ipopt::IpoptApplication> app = new Ipopt::IpoptApplication(false);
	if (!Ipopt::IsValid(app->RegOptions()->GetOption(o.name)))
		throw std::invalid_argument("Ipopt has no option '" + o.name + "'");
	if (!set_ipopt_option(*app, o))
		throw std::invalid_argument("Ipopt refuses '" + o.value + "' for " + o.name +
					    " (its type, range or list of values)");
	return o;
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
		ModeInfo info = mode_info(ps.mode, robot);
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
		s.T_guess = ps.T_guess > 0 ? ps.T_guess : duration_guess(info, length);
		check_corridor(ps, where);
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
	std::vector<Start> starts;
	for (double f : prob.T_scales) {
		Start st;
		for (size_t k = 0; k < p.setups.size(); k++) {
			const Bounds &bd = p.info[k].bounds;
			st.T.push_back(std::min(std::max(f * p.setups[k].T_guess, bd.T_min), bd.T_max));
		}
		starts.push_back(st);
	}
	MultiPhaseSolution out = solve_stacked(robot, p, starts, prob.switch_cost, opt);
	out.notes = prob.notes;
	return out;
}

}  // namespace hylo::trainer
