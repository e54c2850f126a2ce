#include "trainer/switching.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "trainer/modes.hpp"

namespace hylo::trainer {
namespace {

// x_{k+1}(0)[to] - coef * x_k(T)[from] = 0
LinearRow carry(size_t k, int from, int to, double coef = 1.0)
{
	LinearRow r;
	r.terms = {{KnotRef{static_cast<int>(k) + 1, false, to}, 1.0},
		   {KnotRef{static_cast<int>(k), true, from}, -coef}};
	return r;
}

void fix(std::vector<double> &lo, std::vector<double> &hi, int component, double value)
{
	lo[static_cast<size_t>(component)] = hi[static_cast<size_t>(component)] = value;
}

// The switch point (components 0, 1 of phase k's last knot) on the guard.
void on_guard(MultiPhaseProblem &p, size_t k, const SwitchGuard &g)
{
	const int ph = static_cast<int>(k);
	PhaseSpec &a = p.phases[k];
	if (g.area) {
		a.last_lo[0] = std::max(a.last_lo[0], std::min(g.ax, g.bx));
		a.last_hi[0] = std::min(a.last_hi[0], std::max(g.ax, g.bx));
		a.last_lo[1] = std::max(a.last_lo[1], std::min(g.ay, g.by));
		a.last_hi[1] = std::min(a.last_hi[1], std::max(g.ay, g.by));
		return;
	}
	double tx = g.bx - g.ax, ty = g.by - g.ay, len2 = tx * tx + ty * ty;
	if (len2 < 1e-18) {
		fix(a.last_lo, a.last_hi, 0, g.ax);
		fix(a.last_lo, a.last_hi, 1, g.ay);
		return;
	}
	LinearRow normal, along;
	normal.terms = {{KnotRef{ph, true, 0}, -ty}, {KnotRef{ph, true, 1}, tx}};
	normal.lo = normal.hi = -ty * g.ax + tx * g.ay;
	along.terms = {{KnotRef{ph, true, 0}, tx}, {KnotRef{ph, true, 1}, ty}};
	along.lo = tx * g.ax + ty * g.ay;
	along.hi = along.lo + len2;
	p.rows.push_back(normal);
	p.rows.push_back(along);
}

void default_bounds(PhaseSpec &s, const RobotParams &robot)
{
	auto b = state_bounds(s.mode, robot);
	if (s.first_lo.empty()) s.first_lo = b.first;
	if (s.first_hi.empty()) s.first_hi = b.second;
	if (s.last_lo.empty()) s.last_lo = b.first;
	if (s.last_hi.empty()) s.last_hi = b.second;
}

}  // namespace

TakeoffLanding takeoff_landing(const RobotParams &robot, const SolveOptions &opt)
{
	double lo[6] = {0, 0, 0, 0, 0, 0}, hi[6] = {0, 0, 1, 0, 0, 0};
	Solution up = solve_bvp(HYLO_MODE_FLIGHT, robot, lo, hi, opt);
	Solution down = solve_bvp(HYLO_MODE_FLIGHT, robot, hi, lo, opt);
	if (!up.converged || !down.converged)
		throw std::runtime_error("the takeoff or landing optimization did not converge");
	return {up.cost, down.cost};
}

void join_phases(MultiPhaseProblem &p, size_t k, const RobotParams &robot, const SwitchGuard &g,
		 const TakeoffLanding &costs)
{
	if (k + 1 >= p.phases.size())
		throw std::invalid_argument("join_phases: phase " + std::to_string(k) + " has no successor");
	PhaseSpec &a = p.phases[k], &b = p.phases[k + 1];
	default_bounds(a, robot);
	default_bounds(b, robot);
	const std::string pair = std::string(hylo_mode_str(a.mode)) + " -> " + hylo_mode_str(b.mode);
	if ((a.mode == HYLO_MODE_DI_POS && b.mode == HYLO_MODE_DI_NEG) || (a.mode == HYLO_MODE_DI_NEG && b.mode == HYLO_MODE_DI_POS)) {
		fix(a.last_lo, a.last_hi, 0, 0.0);
		p.rows.push_back(carry(k, 0, 0));
		p.rows.push_back(carry(k, 1, 1));
	} else if ((a.mode == HYLO_MODE_GROUND && b.mode == HYLO_MODE_MARINE) || (a.mode == HYLO_MODE_MARINE && b.mode == HYLO_MODE_GROUND)) {
		for (int i = 0; i < 6; i++)
			p.rows.push_back(carry(k, i, i));
		if (b.mode == HYLO_MODE_MARINE) {
			double xs[4] = {0, 0, 1, 0};   // phi_n is linear in vx: its slope
			double slope = full_state(HYLO_MODE_MARINE, robot, xs)[6];
			p.rows.push_back(carry(k, 2, 6, slope));
			p.rows.push_back(carry(k, 2, 7, slope));
		}
		on_guard(p, k, g);
	} else if (a.mode == HYLO_MODE_GROUND && b.mode == HYLO_MODE_FLIGHT) {
		for (int i : {2, 3, 5})
			fix(a.last_lo, a.last_hi, i, 0.0);
		double xs[6] = {0, 0, g.height_m + 1, 0, 0, 0};
		std::vector<double> hover = full_state(HYLO_MODE_FLIGHT, robot, xs);
		for (int i = 2; i < 16; i++)
			fix(b.first_lo, b.first_hi, i, hover[static_cast<size_t>(i)]);
		p.rows.push_back(carry(k, 0, 0));
		p.rows.push_back(carry(k, 1, 1));
		on_guard(p, k, g);
		p.switch_cost += costs.takeoff_j;
	} else if (a.mode == HYLO_MODE_FLIGHT && b.mode == HYLO_MODE_GROUND) {
		double xs[6] = {0, 0, g.height_m + 1, 0, 0, 0};
		std::vector<double> hover = full_state(HYLO_MODE_FLIGHT, robot, xs);
		for (int i = 2; i < 16; i++)
			fix(a.last_lo, a.last_hi, i, hover[static_cast<size_t>(i)]);
		for (int i : {2, 3, 4, 5})
			fix(b.first_lo, b.first_hi, i, 0.0);
		p.rows.push_back(carry(k, 0, 0));
		p.rows.push_back(carry(k, 1, 1));
		on_guard(p, k, g);
		p.switch_cost += costs.landing_j;
	} else {
		throw std::invalid_argument("no mode switch " + pair + " (docs/models.md section 6)");
	}
}

void join_gate(MultiPhaseProblem &p, size_t k, const RobotParams &robot, const WallGate &g)
{
	if (k + 1 >= p.phases.size() || p.phases[k].mode != HYLO_MODE_FLIGHT || p.phases[k + 1].mode != HYLO_MODE_FLIGHT)
		throw std::invalid_argument("join_gate: phases " + std::to_string(k) + " and " + std::to_string(k + 1) +
					    " are not two flight phases");
	PhaseSpec &a = p.phases[k];
	default_bounds(a, robot);
	default_bounds(p.phases[k + 1], robot);
	for (int i = 0; i < mode_desc(HYLO_MODE_FLIGHT).nx; i++)
		p.rows.push_back(carry(k, i, i));
	fix(a.last_lo, a.last_hi, g.axis == 0 ? 0 : 1, g.c);
	a.last_lo[2] = std::max(a.last_lo[2], g.z_min);
}

void join_via(MultiPhaseProblem &p, size_t k, const RobotParams &robot, const double *position)
{
	if (k + 1 >= p.phases.size() || p.phases[k].mode != p.phases[k + 1].mode)
		throw std::invalid_argument("join_via: phases " + std::to_string(k) + " and " + std::to_string(k + 1) +
					    " are not two phases of one mode");
	PhaseSpec &a = p.phases[k];
	default_bounds(a, robot);
	default_bounds(p.phases[k + 1], robot);
	for (int i = 0; i < mode_desc(a.mode).nx; i++)
		p.rows.push_back(carry(k, i, i));
	const hylo_mode_desc &d = mode_desc(a.mode);   // position coordinates: 3 air, 2 planar, else 1
	const int n = d.air ? 3 : d.planar ? 2 : 1;
	for (int i = 0; i < n; i++)
		fix(a.last_lo, a.last_hi, i, position[i]);
}

PhaseSpec phase_between(hylo_mode mode, const RobotParams &robot, const double *xs0,
			const double *xs1, const double *guess0, const double *guess1, int segments)
{
	PhaseSpec p;
	p.mode = mode;
	p.segments = segments;
	p.guess = {full_state(mode, robot, guess0), full_state(mode, robot, guess1)};
	auto b = state_bounds(mode, robot);
	p.first_lo = p.last_lo = b.first;
	p.first_hi = p.last_hi = b.second;
	if (xs0)
		p.first_lo = p.first_hi = full_state(mode, robot, xs0);
	if (xs1)
		p.last_lo = p.last_hi = full_state(mode, robot, xs1);
	return p;
}

namespace {
hylo_mode di_side(const double *x) { return x[0] > 0 ? HYLO_MODE_DI_POS : HYLO_MODE_DI_NEG; }
}  // namespace

MultiPhaseSolution di_two_phase(const RobotParams &di, const double *a, const double *b, double v_guess)
{
	double s[2] = {0, v_guess};
	MultiPhaseProblem p;
	p.phases = {phase_between(di_side(a), di, a, nullptr, a, s, 20),
		    phase_between(di_side(b), di, nullptr, b, s, b, 20)};
	join_phases(p, 0, di, SwitchGuard{});
	return solve_multiphase(di, p, SolveOptions());
}

std::pair<double, double> di_swept_optimum(const RobotParams &di, const double *a, const double *b)
{
	auto through = [&](double v) {
		double s[2] = {0, v};
		Solution x = solve_bvp(di_side(a), di, a, s, SolveOptions());
		Solution y = solve_bvp(di_side(b), di, s, b, SolveOptions());
		return x.converged && y.converged ? x.cost + y.cost : INFINITY;
	};
	double best_v = 0, best = INFINITY;
	for (int i = 0; i <= 40; i++) {
		double v = -1 + 2.0 * i / 40, c = through(v);
		if (c < best) {
			best = c;
			best_v = v;
		}
	}
	double lo = std::max(-1.0, best_v - 0.05), hi = std::min(1.0, best_v + 0.05);
	// Golden-section search: each step keeps one interior point and its cost.
	const double gr = (std::sqrt(5.0) - 1) / 2;
	double x1 = hi - gr * (hi - lo), x2 = lo + gr * (hi - lo), f1 = through(x1), f2 = through(x2);
	for (int it = 0; it < 24; it++) {
		if (f1 < f2) {
			hi = x2;
			x2 = x1;
			f2 = f1;
			x1 = hi - gr * (hi - lo);
			f1 = through(x1);
		} else {
			lo = x1;
			x1 = x2;
			f1 = f2;
			x2 = lo + gr * (hi - lo);
			f2 = through(x2);
		}
	}
	double v = 0.5 * (lo + hi), c = through(v);
	return c < best ? std::make_pair(c, v) : std::make_pair(best, best_v);
}

}  // namespace hylo::trainer
