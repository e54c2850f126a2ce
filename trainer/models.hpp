// The dynamics and running cost of every mode (docs/models.md sections 1-5),
// written once and templated on the scalar so that plain doubles and Eigen's
// forward-mode AutoDiff and the Hessian's second-order type share the same code.
//
// Each model has, for state x (NX), input u (NU):
//   eval(x, u, f, L, path): f = x' (NX), L = running cost [W], path (NP)
//   bounds on x, u, path and the final time T; the boundary state built from
//   sampled coordinates with the virtual constraints of docs/models.md section 7;
//   param_keys(), the keys its robot-file block must have (trainer/params.cpp);
//   floor_power() and top_speed(), from which every edge's least cost follows
//   (cost_floor, trainer/model_table.hpp); solver_hints(), how the solver
//   driver treats it (trainer/mode_config.hpp); kDefaultSamples, a full
//   dataset's pairs. Which model a mode has: trainer/model_table.hpp; the
//   rest of a mode's description: its record in onboard/include/hylo/modes.h.
#ifndef HYLO_TRAINER_MODELS_HPP
#define HYLO_TRAINER_MODELS_HPP

#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "hylo/modes.h"
#include "trainer/robot_params.hpp"

namespace hylo::trainer {

namespace ad {
using std::cos;
using std::sin;
using std::sqrt;
using std::tan;
using std::tanh;
}  // namespace ad

// Smoothing: docs/models.md fixes the constants (relax = 1). The solver also
// solves with them multiplied by relax > 1 first (a continuation: a smoother
// problem whose solution starts the exact one); only relax = 1 results count.

// Positive part of a power, smoothed (docs/models.md section 1): (P + sqrt(P^2 + d^2)) / 2.
template <class S>
S positive_power(const S &P, double relax)
{
	using ad::sqrt;
	const double delta = 0.1 * relax;
	return (P + sqrt(P * P + delta * delta)) * 0.5;
}

// x*|x| smoothed as x*sqrt(x^2 + eps^2), eps = 1e-3.
template <class S>
S signed_square(const S &x, double relax)
{
	using ad::sqrt;
	const double eps = 1e-3 * relax;
	return x * sqrt(x * x + eps * eps);
}

struct Bounds {
	std::vector<double> x_lo, x_hi, u_lo, u_hi, path_lo, path_hi;
	double T_min = 0, T_max = 0;
};

// How the solver driver treats a model (trainer/mode_config.hpp, ModeInfo:
// what each field does); the defaults are those of a plain model.
struct SolverHints {
	int position_dims = 0;        // position components a corridor box bounds (0: none)
	std::vector<double> continuation = {100.0, 10.0, 3.0, 1.0};  // smoothing multipliers, to 1
	int min_segments = 0;         // a start's mesh has at least these segments
	double max_step_s = 0;        // > 0: and segments of at most this guessed duration [s]
	bool first_accepted = false;  // keep the first start that passes, try no more
	int step_max_iter = 0;        // > 0: a continuation step's iteration limit
	bool mumps_no_permuting_scaling = false;  // MUMPS without MC64 (else its own choice)
	int path_guess_points = 0;    // > 0: straight-line starts from path_guess(a, b, T, this)
	// > 0: a BVP's solution (a training label, trainer --solve) is accepted
	// on at least this many segments: one that passes its replay on a
	// coarser mesh is solved again on doubled meshes from it.
	int accept_segments = 0;
};

// ---- double integrator (docs/models.md section 2) ------------------------------
struct DiModel {
	double relax = 1.0;   // smoothing multiplier (see positive_power)
	static constexpr int NX = 2, NU = 1, NP = 0, NS = 2;
	static constexpr bool kSmoothed = false;   // nothing to relax: no continuation
	static constexpr bool kReplayFromKnots = false;
	double rho = 0.1;
	bool positive = false;   // the mode record's side: p >= 0 (di_pos), else p <= 0
	bool damped = false;     // the mode record's damped: v' = u - v (di_pos), else v' = u

	DiModel(const ModeParams &p, const hylo_mode_desc &d)
		: rho(p.at("rho")), positive(d.side > 0), damped(d.damped != 0) {}

	static std::vector<std::string> param_keys() { return {"rho"}; }
	static SolverHints solver_hints() { return {}; }
	static constexpr uint64_t kDefaultSamples = 2000;
	// L >= rho and |v| <= 1: T >= the distance in p.
	double floor_power() const { return rho; }
	double top_speed() const { return 1.0; }

	template <class S>
	void eval(const S *x, const S *u, S *f, S &L, S *) const
	{
		f[0] = x[1];
		f[1] = damped ? S(u[0] - x[1]) : S(u[0]);
		L = u[0] * u[0] + rho;
	}
	Bounds bounds() const
	{
		Bounds b;
		b.x_lo = {positive ? 0.0 : -1.0, -1.0};
		b.x_hi = {positive ? 1.0 : 0.0, 1.0};
		b.u_lo = {-1.0};
		b.u_hi = {1.0};
		b.T_min = 0.05;
		b.T_max = 20;
		return b;
	}
	std::array<double, NX> full_state(const double *xs) const { return {xs[0], xs[1]}; }
	std::array<double, NX> scale() const { return {1.0, 1.0}; }
	std::array<double, NU> input_guess() const { return {0.0}; }
	double position_distance(const double *a, const double *b) const
	{
		return std::hypot(b[0] - a[0], b[1] - a[1]);
	}
	double typical_speed() const { return 0.5; }
};

// ---- what the ground and marine modes share -----------------------------------
// Two inputs (left, right) in [-1, 1], four sampled coordinates (px, py, vx,
// theta), a planar position that corridor boxes bound, no path constraint;
// stable open loop; standing still as the input guess.
struct PlanarModel {
	double relax = 1.0;   // smoothing multiplier (see positive_power)
	static constexpr int NU = 2, NP = 0, NS = 4;
	static constexpr bool kSmoothed = true;
	static constexpr bool kReplayFromKnots = false;
	static constexpr uint64_t kDefaultSamples = 11520;

	static SolverHints solver_hints()
	{
		SolverHints h;
		h.position_dims = 2;
		// 20 segments of a few tenths of a second cannot place a brief
		// turn: labels 0.5-7% above the optimum (docs/decisions.md, "Labels
		// against an independent optimum: the 20-segment mesh"). Marine's
		// are within 0.1% of it on 40; ground's want 80 (GroundModel).
		h.accept_segments = 40;
		return h;
	}
	std::array<double, NU> input_guess() const { return {0.0, 0.0}; }
	double position_distance(const double *a, const double *b) const
	{
		return std::hypot(b[0] - a[0], b[1] - a[1]);
	}
	// f[0..5], the rates of the planar rigid body x = (px, py, vx, vy, theta,
	// omega) (body-frame velocities) under the body-frame forces Fx, Fy and
	// the moment Mz; mass m, inertia Iz.
	template <class S>
	static void body_rates(const S *x, const S &Fx, const S &Fy, const S &Mz, double m, double Iz, S *f)
	{
		using ad::cos;
		using ad::sin;
		const S &vx = x[2], &vy = x[3], &th = x[4], &om = x[5];
		f[0] = vx * cos(th) - vy * sin(th);
		f[1] = vx * sin(th) + vy * cos(th);
		f[2] = Fx / m + om * vy;
		f[3] = Fy / m - om * vx;
		f[4] = om;
		f[5] = Mz / Iz;
	}
	// The mode's state bounds and longest duration, with the inputs in
	// [-1, 1] and T >= 0.1 s.
	static Bounds bounds_with(std::vector<double> x_lo, std::vector<double> x_hi, double T_max)
	{
		Bounds b;
		b.x_lo = std::move(x_lo);
		b.x_hi = std::move(x_hi);
		b.u_lo = {-1, -1};
		b.u_hi = {1, 1};
		b.T_min = 0.1;
		b.T_max = T_max;
		return b;
	}
};

// ---- skid-steer ground mode (docs/models.md section 3) ------------------------
struct GroundModel : PlanarModel {
	static constexpr int NX = 6;
	double m, Iz, B, Lc, r, G, kt, R, Vcc, crr, mut, Cy, Pd, vmax, g;

	GroundModel(const ModeParams &p, double grav)
		: m(p.at("m")), Iz(p.at("Iz")), B(p.at("B")), Lc(p.at("Lc")), r(p.at("r")),
		  G(p.at("G")), kt(p.at("kt")), R(p.at("R")), Vcc(p.at("Vcc")), crr(p.at("crr")),
		  mut(p.at("mut")), Cy(p.at("Cy")), Pd(p.at("Pd")), vmax(p.at("vmax")), g(grav)
	{
	}

	static std::vector<std::string> param_keys()
	{
		return {"m", "Iz", "B", "Lc", "r", "G", "kt", "R", "Vcc", "crr", "mut", "Cy", "Pd", "vmax"};
	}
	double floor_power() const { return Pd; }   // every second drains Pd
	double top_speed() const { return vmax; }
	// Skid-steer turns are brief and sharp (track friction): on 40 segments
	// 3 of 20 labels stayed 0.6-1.2% above the independent optimum, on 80
	// none was above 0.35% (docs/decisions.md, the same section).
	static SolverHints solver_hints()
	{
		SolverHints h = PlanarModel::solver_hints();
		h.accept_segments = 80;
		return h;
	}

	// x = (px, py, vx, vy, theta, omega), u = (uL, uR)
	template <class S>
	void eval(const S *x, const S *u, S *f, S &L, S *) const
	{
		using ad::tanh;
		const S &vx = x[2], &vy = x[3], &om = x[5];
		S phiL = G * (vx - om * (B / 2)) / r, phiR = G * (vx + om * (B / 2)) / r;
		S VL = Vcc * u[0], VR = Vcc * u[1];
		S iL = (VL - kt * phiL) / R, iR = (VR - kt * phiR) / R;
		S FL = G * kt * iL / r, FR = G * kt * iR / r;
		S Fx = FL + FR - crr * m * g * tanh(vx / (0.05 * relax));
		S Fy = -Cy * vy;
		S Mz = (FR - FL) * (B / 2) - mut * m * g * Lc / 4 * tanh(om / (0.1 * relax));
		body_rates(x, Fx, Fy, Mz, m, Iz, f);
		L = positive_power(S(VL * iL), relax) + positive_power(S(VR * iR), relax) + Pd;
	}
	Bounds bounds() const
	{
		const double inf = 1e20;
		return bounds_with({-inf, -inf, -vmax, -1, -inf, -3}, {inf, inf, vmax, 1, inf, 3}, 60);
	}
	// Sampled (px, py, vx, theta) -> full state with vy = 0, omega = 0.
	std::array<double, NX> full_state(const double *xs) const
	{
		return {xs[0], xs[1], xs[2], 0.0, xs[3], 0.0};
	}
	std::array<double, NX> scale() const { return {1, 1, 1, 1, 1, 1}; }
	double typical_speed() const { return 0.5 * vmax; }
};

// ---- marine mode (docs/models.md section 4) ----------------------------------
struct MarineModel : PlanarModel {
	static constexpr int NX = 8;
	double m, Iz, B, Jm, kt, R, Vcc, kT, kq, dx, dy, Cy_w, dw, Pd, vmax_w;

	MarineModel(const ModeParams &p, double)
		: m(p.at("m")), Iz(p.at("Iz")), B(p.at("B")), Jm(p.at("Jm")), kt(p.at("kt")),
		  R(p.at("R")), Vcc(p.at("Vcc")), kT(p.at("kT")), kq(p.at("kq")), dx(p.at("dx")),
		  dy(p.at("dy")), Cy_w(p.at("Cy_w")), dw(p.at("dw")), Pd(p.at("Pd")),
		  vmax_w(p.at("vmax_w"))
	{
	}

	static std::vector<std::string> param_keys()
	{
		return {"m", "Iz", "B", "Jm", "kt", "R", "Vcc", "kT", "kq", "dx", "dy", "Cy_w", "dw", "Pd", "vmax_w"};
	}
	double floor_power() const { return Pd; }
	double top_speed() const { return vmax_w; }

	double phi_n(double vx) const { return vx * std::sqrt(dx / (2 * kT)); }

	// x = (px, py, vx, vy, theta, omega, phiL, phiR), u = (uL, uR)
	template <class S>
	void eval(const S *x, const S *u, S *f, S &L, S *) const
	{
		const S &vx = x[2], &vy = x[3], &om = x[5], &pL = x[6], &pR = x[7];
		S VL = Vcc * u[0], VR = Vcc * u[1];
		S iL = (VL - kt * pL) / R, iR = (VR - kt * pR) / R;
		S TL = kT * signed_square(pL, relax), TR = kT * signed_square(pR, relax);
		S Fx = TL + TR - dx * signed_square(vx, relax);
		S Fy = -dy * signed_square(vy, relax) - Cy_w * vy;
		S Mz = (TR - TL) * (B / 2) - dw * signed_square(om, relax);
		body_rates(x, Fx, Fy, Mz, m, Iz, f);
		f[6] = (kt * iL - kq * signed_square(pL, relax)) / Jm;
		f[7] = (kt * iR - kq * signed_square(pR, relax)) / Jm;
		L = positive_power(S(VL * iL), relax) + positive_power(S(VR * iR), relax) + Pd;
	}
	Bounds bounds() const
	{
		const double inf = 1e20;
		return bounds_with({-inf, -inf, -vmax_w, -1, -inf, -2, -inf, -inf}, {inf, inf, vmax_w, 1, inf, 2, inf, inf},
				   90);
	}
	std::array<double, NX> full_state(const double *xs) const
	{
		double pn = phi_n(xs[2]);
		return {xs[0], xs[1], xs[2], 0.0, xs[3], 0.0, pn, pn};
	}
	std::array<double, NX> scale() const
	{
		double ps = std::max(1.0, phi_n(vmax_w));
		return {1, 1, 1, 1, 1, 1, ps, ps};
	}
	double typical_speed() const { return 0.5 * vmax_w; }
};

// ---- quadrotor flight mode (docs/models.md section 5) -------------------------
struct FlightModel {
	double relax = 1.0;   // smoothing multiplier (see positive_power)
	static constexpr int NX = 16, NU = 4, NP = 1, NS = 6;
	static constexpr bool kSmoothed = true;
	// Open loop a quadrotor is unstable (rotor speed, body rate, attitude,
	// velocity and position integrate one another), so an end state
	// replayed over seconds measures that instability, not the
	// transcription: the replay restarts at every knot (see replay.cpp).
	static constexpr bool kReplayFromKnots = true;
	double m, l, Jx, Jy, Jz, kf, km, Jr, Vcc, kt, R, cd, Pd, vmax_f, phi_max, g;

	FlightModel(const ModeParams &p, double grav)
		: m(p.at("m")), l(p.at("l")), Jx(p.at("Jx")), Jy(p.at("Jy")), Jz(p.at("Jz")),
		  kf(p.at("kf")), km(p.at("km")), Jr(p.at("Jr")), Vcc(p.at("Vcc")), kt(p.at("kt")),
		  R(p.at("R")), cd(p.at("cd")), Pd(p.at("Pd")), vmax_f(p.at("vmax_f")),
		  phi_max(p.at("phi_max")), g(grav)
	{
	}

	static std::vector<std::string> param_keys()
	{
		return {"m", "l", "Jx", "Jy", "Jz", "kf", "km", "Jr", "Vcc", "kt", "R", "cd", "Pd", "vmax_f",
			"phi_max"};
	}
	// Segments of at most 20 ms (the rotors' time constant is 13 ms), the
	// Hermite guess with fine continuation steps, the first start that
	// passes, and no MC64 in MUMPS (2.2x less CPU, same labels); each
	// measured in docs/decisions.md, "Flight training: five changes".
	static SolverHints solver_hints()
	{
		SolverHints h;
		h.position_dims = 3;
		h.mumps_no_permuting_scaling = true;
		h.continuation = {100.0, 50.0, 30.0, 20.0, 10.0, 5.0, 3.0, 2.0, 1.5, 1.0};
		h.min_segments = 80;
		h.max_step_s = 0.02;
		h.first_accepted = true;
		h.step_max_iter = 400;
		h.path_guess_points = 16;
		return h;
	}
	static constexpr uint64_t kDefaultSamples = 17016;
	double floor_power() const { return Pd; }
	double top_speed() const { return vmax_f; }

	double phi_n() const { return std::sqrt(m * g / (4 * kf)); }
	// Input holding a rotor at phi_n: kt*i = km*phi^2, i = (Vcc*u - kt*phi)/R.
	double u_hover() const
	{
		double ph = phi_n();
		return (km * ph * ph * R / kt + kt * ph) / Vcc;
	}

	// x = (p 3, v 3 body, Theta 3 (roll, pitch, yaw), omega 3, phi 4), u in [0,1]^4
	template <class S>
	void eval(const S *x, const S *u, S *f, S &L, S *path) const
	{
		using ad::cos;
		using ad::sin;
		using ad::tan;
		const S *v = x + 3, *th = x + 6, *w = x + 9, *ph = x + 12;
		S cr = cos(th[0]), sr = sin(th[0]), cp = cos(th[1]), sp = sin(th[1]);
		S cy = cos(th[2]), sy = sin(th[2]);
		// Rwb = Rz(yaw) Ry(pitch) Rx(roll)
		S R00 = cy * cp, R01 = cy * sp * sr - sy * cr, R02 = cy * sp * cr + sy * sr;
		S R10 = sy * cp, R11 = sy * sp * sr + cy * cr, R12 = sy * sp * cr - cy * sr;
		S R20 = -sp, R21 = cp * sr, R22 = cp * cr;
		f[0] = R00 * v[0] + R01 * v[1] + R02 * v[2];
		f[1] = R10 * v[0] + R11 * v[1] + R12 * v[2];
		f[2] = R20 * v[0] + R21 * v[1] + R22 * v[2];
		S fr[4], q[4], P = S(0.0);
		S thrust = S(0.0);
		for (int i = 0; i < 4; i++) {
			fr[i] = kf * ph[i] * ph[i];
			q[i] = km * ph[i] * ph[i];
			S V = Vcc * u[i];
			S cur = (V - kt * ph[i]) / R;
			f[12 + i] = (kt * cur - q[i]) / Jr;
			P = P + positive_power(S(V * cur), relax);
			thrust = thrust + fr[i];
		}
		const double a = l / std::sqrt(2.0);
		// rotors: 1 (+a,-a,+1) 2 (-a,+a,+1) 3 (+a,+a,-1) 4 (-a,-a,-1)
		S tx = (-a) * fr[0] + a * fr[1] + a * fr[2] + (-a) * fr[3];
		S ty = -(a * fr[0] + (-a) * fr[1] + a * fr[2] + (-a) * fr[3]);
		S tz = -(q[0] + q[1] - q[2] - q[3]);
		// v' = -omega x v + Rwb^T (0,0,-g) + (0,0,thrust)/m - (cd/m) v
		S gx = R20 * (-g), gy = R21 * (-g), gz = R22 * (-g);
		f[3] = -(w[1] * v[2] - w[2] * v[1]) + gx - (cd / m) * v[0];
		f[4] = -(w[2] * v[0] - w[0] * v[2]) + gy - (cd / m) * v[1];
		f[5] = -(w[0] * v[1] - w[1] * v[0]) + gz + thrust / m - (cd / m) * v[2];
		S k = w[1] * sr + w[2] * cr;
		f[6] = w[0] + k * tan(th[1]);
		f[7] = w[1] * cr - w[2] * sr;
		f[8] = k / cp;
		// omega' = J^-1 (tau - omega x J omega)
		f[9] = (tx - (w[1] * Jz * w[2] - w[2] * Jy * w[1])) / Jx;
		f[10] = (ty - (w[2] * Jx * w[0] - w[0] * Jz * w[2])) / Jy;
		f[11] = (tz - (w[0] * Jy * w[1] - w[1] * Jx * w[0])) / Jz;
		L = P + Pd;
		path[0] = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
	}
	Bounds bounds() const
	{
		const double inf = 1e20;
		Bounds b;
		b.x_lo = {-inf, -inf, -inf, -inf, -inf, -inf, -1, -1, -inf, -6, -6, -6, 0, 0, 0, 0};
		b.x_hi = {inf, inf, inf, inf, inf, inf, 1, 1, inf, 6, 6, 6,
			  phi_max, phi_max, phi_max, phi_max};
		b.u_lo = {0, 0, 0, 0};
		b.u_hi = {1, 1, 1, 1};
		b.path_lo = {-inf};
		b.path_hi = {vmax_f * vmax_f};
		b.T_min = 0.1;
		b.T_max = 60;
		return b;
	}
	// Sampled (p, v) -> hover attitude, zero rates, rotors at phi_n.
	std::array<double, NX> full_state(const double *xs) const
	{
		double pn = phi_n();
		return {xs[0], xs[1], xs[2], xs[3], xs[4], xs[5], 0, 0, 0, 0, 0, 0, pn, pn, pn, pn};
	}
	std::array<double, NX> scale() const
	{
		double pn = phi_n();
		return {1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, pn, pn, pn, pn};
	}
	std::array<double, NU> input_guess() const
	{
		double uh = u_hover();
		return {uh, uh, uh, uh};
	}
	double position_distance(const double *a, const double *b) const
	{
		return std::sqrt((b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]) +
				 (b[2] - a[2]) * (b[2] - a[2]));
	}
	double typical_speed() const { return 3.0; }
	// An initial guess from a to b over T that the dynamics can nearly fly:
	// positions on the cubic Hermite curve through both ends' velocities
	// (hover attitude, so body = world there), at every point the attitude
	// and rotor speed whose thrust gives that curve's acceleration against
	// gravity and drag (yaw 0). K + 1 states, uniform in time.
	std::vector<std::vector<double>> path_guess(const std::vector<double> &a,
						    const std::vector<double> &b, double T, int K) const
	{
		std::vector<std::vector<double>> out;
		for (int s = 0; s <= K; s++) {
			double t = static_cast<double>(s) / K, t2 = t * t, t3 = t2 * t;
			double hp[4] = {2 * t3 - 3 * t2 + 1, t3 - 2 * t2 + t, -2 * t3 + 3 * t2, t3 - t2};
			double hv[4] = {6 * t2 - 6 * t, 3 * t2 - 4 * t + 1, -6 * t2 + 6 * t, 3 * t2 - 2 * t};
			double ha[4] = {12 * t - 6, 6 * t - 4, -12 * t + 6, 6 * t - 2};
			std::vector<double> x(NX, 0.0);
			double vw[3], F[3];
			for (int k = 0; k < 3; k++) {
				double c[4] = {a[k], T * a[3 + k], b[k], T * b[3 + k]};
				x[k] = hp[0] * c[0] + hp[1] * c[1] + hp[2] * c[2] + hp[3] * c[3];
				vw[k] = (hv[0] * c[0] + hv[1] * c[1] + hv[2] * c[2] + hv[3] * c[3]) / T;
				F[k] = (ha[0] * c[0] + ha[1] * c[1] + ha[2] * c[2] + ha[3] * c[3]) / (T * T) +
				       (cd / m) * vw[k];
			}
			F[2] += g;
			double n = std::sqrt(F[0] * F[0] + F[1] * F[1] + F[2] * F[2]);
			double roll = std::min(0.9, std::max(-0.9, -std::asin(F[1] / n)));
			double pitch = std::min(0.9, std::max(-0.9, std::atan2(F[0], F[2])));
			double cr = std::cos(roll), sr = std::sin(roll), cp = std::cos(pitch), sp = std::sin(pitch);
			// v_body = Rwb^T v_world with Rwb = Ry(pitch) Rx(roll)
			x[3] = cp * vw[0] - sp * vw[2];
			x[4] = sr * sp * vw[0] + cr * vw[1] + sr * cp * vw[2];
			x[5] = cr * sp * vw[0] - sr * vw[1] + cr * cp * vw[2];
			x[6] = roll;
			x[7] = pitch;
			double ph = std::min(phi_max, std::sqrt(m * n / (4 * kf)));
			for (int k = 12; k < 16; k++)
				x[static_cast<size_t>(k)] = ph;
			out.push_back(s == 0 ? a : s == K ? b : x);
		}
		return out;
	}
};

}  // namespace hylo::trainer

#endif
