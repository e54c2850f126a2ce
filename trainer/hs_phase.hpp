// One phase of a Hermite-Simpson transcription (internal to the trainer).
// A phase owns its variable layout (states and inputs at N+1 knots and N
// midpoints, then its duration T) and its constraints; StackedNlp
// (ipopt_nlp.hpp) stacks phases and the linear rows that join them into
// one Ipopt problem. Derivatives are exact, in forward mode: Eigen's AutoDiff
// for the Jacobian, a second-order type (hyperdual.hpp) for the Hessian.
//
// Transcription (separated form), per segment k, h = T/N, f_j = f(x_j, u_j):
//   x_m - (x_k + x_k+1)/2 - h/8 (f_k - f_k+1) = 0
//   x_k+1 - x_k - h/6 (f_k + 4 f_m + f_k+1)   = 0
// cost J = h/6 sum_k (L_k + 4 L_m + L_k+1) (Simpson), path constraints at
// every knot and midpoint, bounds on states and inputs everywhere. The input
// is piecewise linear (u_m = (u_k + u_k+1)/2): with free midpoint inputs the
// optimizer chattered and Simpson's rule undercounted the energy by 5-25%
// against the CVODE replay.
#ifndef HYLO_TRAINER_HS_PHASE_HPP
#define HYLO_TRAINER_HS_PHASE_HPP

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <vector>

#include <Eigen/Dense>
#include <unsupported/Eigen/AutoDiff>

#include <IpTNLP.hpp>

#include "trainer/hyperdual.hpp"
#include "trainer/models.hpp"
#include "trainer/problem.hpp"
#include "trainer/solution.hpp"

namespace hylo::trainer::internal {

using Ipopt::Index;
using Ipopt::Number;

// What a phase is asked to be: its mesh, duration and end conditions.
struct PhaseSetup {
	int segments = 20;
	double T_guess = 1;
	double T_fixed = 0;                        // > 0: T fixed to this value
	std::vector<std::vector<double>> guess;    // full states the initial guess runs through (>= 2)
	std::vector<double> first_lo, first_hi;    // bounds of the first knot's state (NX each)
	std::vector<double> last_lo, last_hi;      // bounds of the last knot's state
	std::vector<CorridorBox> corridor;         // PhaseSpec::corridor (checked by solve_multiphase)
	double corridor_inset_m = 0;               // PhaseSpec::corridor_inset_m
	// The first (last) knot is kept inside its boxes by the inset too: it is
	// a hand-over inside a phase (hand_overs.hpp), not an end of the phase.
	bool inset_first = false, inset_last = false;
	// The normalized times of the guess states (increasing, 0 to 1); empty:
	// uniform.
	std::vector<double> guess_at;
	double T_min = 0;                          // > 0: replaces the mode's least duration
	// The phase's share of a longer phase's time (hand_overs.hpp): its mode's
	// least number of segments is scaled by it.
	double mesh_share = 1;
	// > 0: a solution is accepted on at least this many segments (a BVP's,
	// its mode's ModeInfo::accept_segments; solve_strategy.cpp).
	int accept_segments = 0;
};

// A sparsity structure written entry by entry, as Ipopt's triplet arrays
// take it: put(r, c) makes the next entry (row0 + r, col0 + c).
struct Triplets {
	Index *iRow, *jCol;
	int row0, col0;
	int e = 0;
	void operator()(int r, int c)
	{
		iRow[e] = row0 + r;
		jCol[e] = col0 + c;
		e++;
	}
};

// The interface StackedNlp sees. Pointers passed in are already offset to
// the phase's own variables, constraints and multipliers; structure calls get
// the offsets to add to indices.
class PhaseBlock {
public:
	virtual ~PhaseBlock() = default;
	virtual int nvar() const = 0;
	virtual int ncon() const = 0;
	virtual int nnz_jac() const = 0;
	virtual int nnz_h() const = 0;
	virtual int segments() const = 0;
	virtual double T_guess() const = 0;
	// Index, within the phase, of a component of its first or last knot's state.
	virtual int state_var(bool last, int component) const = 0;
	virtual void bounds(Number *xl, Number *xu, Number *gl, Number *gu) const = 0;
	virtual void start(Number *z) const = 0;
	virtual void scaling(Number *xs, Number *gs) const = 0;
	virtual double objective(const Number *z, bool new_x) = 0;
	virtual void gradient(const Number *z, bool new_x, Number *g) = 0;
	virtual void constraints(const Number *z, bool new_x, Number *g) = 0;
	virtual void jac_structure(Index *iRow, Index *jCol, int vo, int co) const = 0;
	virtual void jac_values(const Number *z, bool new_x, Number *v) = 0;
	virtual void hess_structure(Index *iRow, Index *jCol, int vo) const = 0;
	virtual void hess_values(const Number *z, Number sigma, const Number *lambda, Number *v) const = 0;
	// The phase's T, cost and time-ordered trajectory (t from 0).
	virtual void fill(const Number *z, Solution &s) = 0;
	// Variables of the same phase on a mesh of twice the segments: the old
	// knots and midpoints become knots, new midpoints are their means.
	virtual std::vector<double> refine(const Number *z) const = 0;
};

template <class M>
class HsPhase : public PhaseBlock {
public:
	static constexpr int NX = M::NX, NU = M::NU, NP = M::NP, NZ = NX + NU;
	static constexpr int NPO = NP > 0 ? NP : 1;   // array size for path outputs
	using AD1 = Eigen::AutoDiffScalar<Eigen::Matrix<double, NZ, 1>>;

	HsPhase(const M &model, const PhaseSetup &setup)
		: m_(model), s_(setup), N_(setup.segments), b_(model.bounds())
	{
		npts_ = 2 * N_ + 1;
		f_.resize(static_cast<size_t>(npts_) * NX);
		L_.resize(static_cast<size_t>(npts_));
		path_.resize(static_cast<size_t>(npts_) * NPO);
		jf_.resize(static_cast<size_t>(npts_) * NX * NZ);
		jl_.resize(static_cast<size_t>(npts_) * NZ);
		jp_.resize(static_cast<size_t>(npts_) * NPO * NZ);
	}

	int nvar() const override { return npts_ * NZ + 1; }
	int ncon() const override { return 2 * N_ * NX + npts_ * NP + N_ * NU; }
	// C1: NX x (2 NZ + NX + 1), C2: NX x (3 NZ + 1), path: NP x NZ per point.
	int nnz_jac() const override
	{
		return N_ * NX * (2 * NZ + NX + 1) + N_ * NX * (3 * NZ + 1) + npts_ * NP * NZ + 3 * N_ * NU;
	}
	int nnz_h() const override { return npts_ * (NZ * (NZ + 1) / 2 + NZ) + 1; }
	int segments() const override { return N_; }
	double T_guess() const override { return s_.T_guess; }
	int state_var(bool last, int component) const override
	{
		return zi(last ? knot(N_) : knot(0)) + component;
	}

	void bounds(Number *xl, Number *xu, Number *gl, Number *gu) const override
	{
		for (int p = 0; p < npts_; p++) {
			for (int k = 0; k < NX; k++) {
				xl[zi(p) + k] = b_.x_lo[static_cast<size_t>(k)];
				xu[zi(p) + k] = b_.x_hi[static_cast<size_t>(k)];
			}
			for (int k = 0; k < NU; k++) {
				xl[zi(p) + NX + k] = b_.u_lo[static_cast<size_t>(k)];
				xu[zi(p) + NX + k] = b_.u_hi[static_cast<size_t>(k)];
			}
		}
		for (int p = 0; p < npts_ && !s_.corridor.empty(); p++) {
			const bool end = (p == knot(0) && !s_.inset_first) || (p == knot(N_) && !s_.inset_last);
			in_corridor(time_of(p), end ? 0 : s_.corridor_inset_m, xl + zi(p), xu + zi(p));
		}
		end_bounds(knot(0), s_.first_lo, s_.first_hi, xl, xu);
		end_bounds(knot(N_), s_.last_lo, s_.last_hi, xl, xu);
		xl[Ti()] = s_.T_fixed > 0 ? s_.T_fixed : s_.T_min > 0 ? s_.T_min : b_.T_min;
		xu[Ti()] = s_.T_fixed > 0 ? s_.T_fixed : b_.T_max;
		for (int r = 0; r < 2 * N_ * NX; r++)
			gl[r] = gu[r] = 0;
		for (int p = 0; p < npts_; p++)
			for (int j = 0; j < NP; j++) {
				gl[2 * N_ * NX + p * NP + j] = b_.path_lo[static_cast<size_t>(j)];
				gu[2 * N_ * NX + p * NP + j] = b_.path_hi[static_cast<size_t>(j)];
			}
		for (int r = c3(0); r < ncon(); r++)
			gl[r] = gu[r] = 0;
	}

	// Piecewise linear through the guess states, at their times (guess_at)
	// or uniformly in time, clamped to the bounds; inputs at the model's guess.
	void start(Number *z) const override
	{
		auto ug = m_.input_guess();
		const int nw = static_cast<int>(s_.guess.size()) - 1;
		const std::vector<double> &at = s_.guess_at;
		for (int p = 0; p < npts_; p++) {
			double s = time_of(p);
			int w = std::min(nw - 1, static_cast<int>(s * nw));
			double local = s * nw - w;
			if (!at.empty()) {
				for (w = 0; w + 1 < nw && at[static_cast<size_t>(w + 1)] <= s;)
					w++;
				double span = at[static_cast<size_t>(w + 1)] - at[static_cast<size_t>(w)];
				local = span > 0 ? clamp((s - at[static_cast<size_t>(w)]) / span, 0, 1) : 0;
			}
			const std::vector<double> &a = s_.guess[static_cast<size_t>(w)];
			const std::vector<double> &b = s_.guess[static_cast<size_t>(w + 1)];
			for (int k = 0; k < NX; k++) {
				double va = a[static_cast<size_t>(k)], vb = b[static_cast<size_t>(k)];
				z[zi(p) + k] = clamp(va + local * (vb - va), b_.x_lo[static_cast<size_t>(k)],
						     b_.x_hi[static_cast<size_t>(k)]);
			}
			for (int k = 0; k < NU; k++)
				z[zi(p) + NX + k] = ug[static_cast<size_t>(k)];
		}
		z[Ti()] = s_.T_fixed > 0 ? s_.T_fixed : s_.T_guess;
	}

	// Variables and constraints in units of each state's typical magnitude
	// (rotor and paddle speeds are hundreds of rad/s, positions metres).
	void scaling(Number *xs, Number *gs) const override
	{
		auto sc = m_.scale();
		for (int p = 0; p < npts_; p++) {
			for (int k = 0; k < NX; k++)
				xs[zi(p) + k] = 1.0 / sc[static_cast<size_t>(k)];
			for (int k = 0; k < NU; k++)
				xs[zi(p) + NX + k] = 1.0;
		}
		xs[Ti()] = 1.0 / std::max(1.0, s_.T_guess);
		for (int r = 0; r < ncon(); r++)
			gs[r] = 1.0;
		for (int k = 0; k < N_; k++)
			for (int r = 0; r < NX; r++) {
				gs[c1(k) + r] = 1.0 / sc[static_cast<size_t>(r)];
				gs[c2(k) + r] = 1.0 / sc[static_cast<size_t>(r)];
			}
	}

	double objective(const Number *z, bool new_x) override
	{
		update(z, new_x);
		double sum = 0;
		for (int p = 0; p < npts_; p++)
			sum += weight(p) * L_[static_cast<size_t>(p)];
		return z[Ti()] / (6.0 * N_) * sum;
	}

	void gradient(const Number *z, bool new_x, Number *g) override
	{
		update(z, new_x);
		double h6 = z[Ti()] / (6.0 * N_), sum = 0;
		for (int p = 0; p < npts_; p++) {
			for (int j = 0; j < NZ; j++)
				g[zi(p) + j] = h6 * weight(p) * jl_[static_cast<size_t>(p * NZ + j)];
			sum += weight(p) * L_[static_cast<size_t>(p)];
		}
		g[Ti()] = sum / (6.0 * N_);
	}

	void constraints(const Number *z, bool new_x, Number *g) override
	{
		update(z, new_x);
		double T = z[Ti()], h8 = T / (8.0 * N_), h6 = T / (6.0 * N_);
		for (int k = 0; k < N_; k++) {
			int a = knot(k), b = knot(k + 1), c = mid(k);
			for (int r = 0; r < NX; r++) {
				g[c1(k) + r] = z[zi(c) + r] - 0.5 * (z[zi(a) + r] + z[zi(b) + r]) -
					       h8 * (F(a, r) - F(b, r));
				g[c2(k) + r] = z[zi(b) + r] - z[zi(a) + r] -
					       h6 * (F(a, r) + 4 * F(c, r) + F(b, r));
			}
		}
		for (int p = 0; p < npts_; p++)
			for (int j = 0; j < NP; j++)
				g[2 * N_ * NX + p * NP + j] = path_[static_cast<size_t>(p * NPO + j)];
		for (int k = 0; k < N_; k++)
			for (int j = 0; j < NU; j++)
				g[c3(k) + j] = z[zi(mid(k)) + NX + j] -
					       0.5 * (z[zi(knot(k)) + NX + j] + z[zi(knot(k + 1)) + NX + j]);
	}

	void jac_structure(Index *iRow, Index *jCol, int vo, int co) const override
	{
		Triplets put{iRow, jCol, co, vo};
		for (int k = 0; k < N_; k++) {
			int a = knot(k), b = knot(k + 1), c = mid(k);
			for (int r = 0; r < NX; r++) {
				for (int j = 0; j < NZ; j++) put(c1(k) + r, zi(a) + j);
				for (int j = 0; j < NZ; j++) put(c1(k) + r, zi(b) + j);
				for (int j = 0; j < NX; j++) put(c1(k) + r, zi(c) + j);
				put(c1(k) + r, Ti());
			}
			for (int r = 0; r < NX; r++) {
				for (int j = 0; j < NZ; j++) put(c2(k) + r, zi(a) + j);
				for (int j = 0; j < NZ; j++) put(c2(k) + r, zi(b) + j);
				for (int j = 0; j < NZ; j++) put(c2(k) + r, zi(c) + j);
				put(c2(k) + r, Ti());
			}
		}
		for (int p = 0; p < npts_; p++)
			for (int r = 0; r < NP; r++)
				for (int j = 0; j < NZ; j++)
					put(2 * N_ * NX + p * NP + r, zi(p) + j);
		for (int k = 0; k < N_; k++)
			for (int j = 0; j < NU; j++) {
				put(c3(k) + j, zi(mid(k)) + NX + j);
				put(c3(k) + j, zi(knot(k)) + NX + j);
				put(c3(k) + j, zi(knot(k + 1)) + NX + j);
			}
	}

	void jac_values(const Number *z, bool new_x, Number *v) override
	{
		update(z, new_x);
		int e = 0;
		double T = z[Ti()], h8 = T / (8.0 * N_), h6 = T / (6.0 * N_);
		for (int k = 0; k < N_; k++) {
			int a = knot(k), b = knot(k + 1), c = mid(k);
			for (int r = 0; r < NX; r++) {
				for (int j = 0; j < NZ; j++)
					v[e++] = -(j == r ? 0.5 : 0.0) - h8 * JF(a, r, j);
				for (int j = 0; j < NZ; j++)
					v[e++] = -(j == r ? 0.5 : 0.0) + h8 * JF(b, r, j);
				for (int j = 0; j < NX; j++)
					v[e++] = j == r ? 1.0 : 0.0;
				v[e++] = -(F(a, r) - F(b, r)) / (8.0 * N_);
			}
			for (int r = 0; r < NX; r++) {
				for (int j = 0; j < NZ; j++)
					v[e++] = -(j == r ? 1.0 : 0.0) - h6 * JF(a, r, j);
				for (int j = 0; j < NZ; j++)
					v[e++] = (j == r ? 1.0 : 0.0) - h6 * JF(b, r, j);
				for (int j = 0; j < NZ; j++)
					v[e++] = -4 * h6 * JF(c, r, j);
				v[e++] = -(F(a, r) + 4 * F(c, r) + F(b, r)) / (6.0 * N_);
			}
		}
		for (int p = 0; p < npts_; p++)
			for (int r = 0; r < NP; r++)
				for (int j = 0; j < NZ; j++)
					v[e++] = jp_[static_cast<size_t>((p * NPO + r) * NZ + j)];
		for (int k = 0; k < N_; k++)
			for (int j = 0; j < NU; j++) {
				v[e++] = 1.0;
				v[e++] = -0.5;
				v[e++] = -0.5;
			}
	}

	void hess_structure(Index *iRow, Index *jCol, int vo) const override
	{
		Triplets put{iRow, jCol, vo, vo};
		for (int p = 0; p < npts_; p++) {
			for (int i = 0; i < NZ; i++)
				for (int j = 0; j <= i; j++)
					put(zi(p) + i, zi(p) + j);
			for (int j = 0; j < NZ; j++)
				put(Ti(), zi(p) + j);
		}
		put(Ti(), Ti());
	}

	void hess_values(const Number *z, Number sigma, const Number *lambda, Number *v) const override
	{
		int e = 0;
		double T = z[Ti()];
		for (int p = 0; p < npts_; p++) {
			// The point's share of the Lagrangian: T * (Lambda . f + beta L) + mu . path.
			double w[NX + 1] = {}, wp[NPO] = {};
			for (int r = 0; r < NX; r++)
				w[r] = dyn_weight(p, r, lambda);
			w[NX] = sigma * weight(p) / (6.0 * N_);
			for (int r = 0; r < NP; r++)
				wp[r] = lambda[2 * N_ * NX + p * NP + r];
			double grad[NZ];
			Hyper<NZ> h = hessian(z + zi(p), w, wp, T, grad);
			for (int k = 0; k < Hyper<NZ>::NH; k++)
				v[e++] = h.h[k];
			for (int j = 0; j < NZ; j++)
				v[e++] = grad[j];
		}
		v[e++] = 0;
	}

	void fill(const Number *z, Solution &s) override
	{
		s.T = z[Ti()];
		s.cost = objective(z, true);
		s.segments = N_;
		s.traj.nx = NX;
		s.traj.nu = NU;
		s.traj.t.clear();
		s.traj.x.clear();
		s.traj.u.clear();
		for (int i = 0; i <= 2 * N_; i++) {
			int p = i % 2 == 0 ? knot(i / 2) : mid(i / 2);
			s.traj.t.push_back(s.T * i / (2.0 * N_));
			for (int k = 0; k < NX; k++)
				s.traj.x.push_back(z[zi(p) + k]);
			for (int k = 0; k < NU; k++)
				s.traj.u.push_back(z[zi(p) + NX + k]);
		}
	}

	std::vector<double> refine(const Number *z) const override
	{
		const int N = N_, M2 = 2 * N, npts2 = 2 * M2 + 1;
		std::vector<double> out(static_cast<size_t>(npts2) * NZ + 1);
		auto old_point = [&](int i) { return i % 2 == 0 ? i / 2 : N + 1 + i / 2; };
		for (int i = 0; i <= M2; i++)
			for (int j = 0; j < NZ; j++)
				out[static_cast<size_t>(i * NZ + j)] = z[old_point(i) * NZ + j];
		for (int k = 0; k < M2; k++)
			for (int j = 0; j < NZ; j++)
				out[static_cast<size_t>((M2 + 1 + k) * NZ + j)] =
					0.5 * (out[static_cast<size_t>(k * NZ + j)] + out[static_cast<size_t>((k + 1) * NZ + j)]);
		out.back() = z[Ti()];
		return out;
	}

private:
	// Point p: knots 0..N are points 0..N, midpoint k is point N+1+k.
	int knot(int i) const { return i; }
	int mid(int k) const { return N_ + 1 + k; }
	int zi(int p) const { return p * NZ; }
	int Ti() const { return npts_ * NZ; }
	int c1(int k) const { return k * 2 * NX; }
	int c2(int k) const { return k * 2 * NX + NX; }
	// Piecewise-linear control: the midpoint input is the mean of its knots'
	// (the optimizer cannot exploit Simpson's rule with chattering inputs).
	int c3(int k) const { return 2 * N_ * NX + npts_ * NP + k * NU; }
	static double clamp(double v, double lo, double hi) { return std::min(std::max(v, lo), hi); }
	// Normalized time of point p (0 the first knot, 1 the last).
	double time_of(int p) const
	{
		return p <= N_ ? static_cast<double>(p) / N_ : (static_cast<double>(p - N_ - 1) + 0.5) / N_;
	}

	// Position bounds of a point at normalized time s, lo and hi narrowed to
	// every corridor box whose interval holds s, inset inside them where
	// their intersection is wider than twice that.
	void in_corridor(double s, double inset, Number *lo, Number *hi) const
	{
		constexpr double eps = 1e-12;
		for (size_t k = 0; k < (s_.corridor.empty() ? 0 : s_.corridor[0].lo.size()); k++) {
			double l = lo[k], h = hi[k];
			bool boxed = false;
			for (const CorridorBox &b : s_.corridor)
				if (s >= b.tau0 - eps && s <= b.tau1 + eps) {
					l = std::max(l, b.lo[k]);
					h = std::min(h, b.hi[k]);
					boxed = true;
				}
			const bool room = boxed && h - l > 2 * inset;
			lo[k] = room ? l + inset : l;
			hi[k] = room ? h - inset : h;
		}
	}

	// The first or last knot's bounds: its own, intersected with the
	// corridor's where that leaves something (a pinned end outside it keeps
	// its own).
	void end_bounds(int p, const std::vector<double> &lo, const std::vector<double> &hi, Number *xl,
			Number *xu) const
	{
		for (int k = 0; k < NX; k++) {
			double l = std::max(lo[static_cast<size_t>(k)], xl[zi(p) + k]);
			double h = std::min(hi[static_cast<size_t>(k)], xu[zi(p) + k]);
			bool keep = !s_.corridor.empty() && l <= h;
			xl[zi(p) + k] = keep ? l : lo[static_cast<size_t>(k)];
			xu[zi(p) + k] = keep ? h : hi[static_cast<size_t>(k)];
		}
	}

	double F(int p, int r) const { return f_[static_cast<size_t>(p * NX + r)]; }
	double JF(int p, int r, int j) const { return jf_[static_cast<size_t>((p * NX + r) * NZ + j)]; }
	// Simpson weight of point p in the cost.
	double weight(int p) const
	{
		if (p > N_)
			return 4;
		return (p == 0 || p == N_) ? 1 : 2;
	}

	// Coefficient (per T) of f_p's row r in the constraints, times the multipliers.
	double dyn_weight(int p, int r, const Number *lambda) const
	{
		double s = 0, a8 = 1.0 / (8.0 * N_), a6 = 1.0 / (6.0 * N_);
		if (p > N_) {
			int k = p - N_ - 1;
			return -4 * a6 * lambda[c2(k) + r];
		}
		if (p < N_)   // as the segment's left knot
			s += -a8 * lambda[c1(p) + r] - a6 * lambda[c2(p) + r];
		if (p > 0)    // as the previous segment's right knot
			s += a8 * lambda[c1(p - 1) + r] - a6 * lambda[c2(p - 1) + r];
		return s;
	}

	// Values and first derivatives at every point, once per new iterate.
	void update(const Number *z, bool new_x)
	{
		if (!new_x && have_)
			return;
		have_ = true;
		for (int p = 0; p < npts_; p++) {
			AD1 in[NZ], out[NX], L, path[NPO];
			for (int j = 0; j < NZ; j++)
				in[j] = AD1(z[zi(p) + j], NZ, j);
			m_.template eval<AD1>(in, in + NX, out, L, path);
			for (int r = 0; r < NX; r++) {
				f_[static_cast<size_t>(p * NX + r)] = out[r].value();
				for (int j = 0; j < NZ; j++)
					jf_[static_cast<size_t>((p * NX + r) * NZ + j)] = out[r].derivatives()(j);
			}
			L_[static_cast<size_t>(p)] = L.value();
			for (int j = 0; j < NZ; j++)
				jl_[static_cast<size_t>(p * NZ + j)] = L.derivatives()(j);
			for (int r = 0; r < NP; r++) {
				path_[static_cast<size_t>(p * NPO + r)] = path[r].value();
				for (int j = 0; j < NZ; j++)
					jp_[static_cast<size_t>((p * NPO + r) * NZ + j)] = path[r].derivatives()(j);
			}
		}
	}

	// At point variables zp, with s = w . (f, L): the gradient of s (the
	// T column of the Hessian) and T s + wp . path with its Hessian.
	Hyper<NZ> hessian(const Number *zp, const double *w, const double *wp, double T, double *grad) const
	{
		using H = Hyper<NZ>;
		H in[NZ], out[NX], L, path[NPO];
		for (int j = 0; j < NZ; j++)
			in[j] = H::variable(zp[j], j);
		m_.template eval<H>(in, in + NX, out, L, path);
		H s = w[NX] * L;
		for (int r = 0; r < NX; r++)
			s = s + w[r] * out[r];
		for (int j = 0; j < NZ; j++)
			grad[j] = s.g[j];
		s = T * s;
		for (int r = 0; r < NP; r++)
			s = s + wp[r] * path[r];
		return s;
	}

	M m_;
	PhaseSetup s_;
	int N_, npts_;
	Bounds b_;
	bool have_ = false;
	std::vector<double> f_, L_, path_, jf_, jl_, jp_;
};

}  // namespace hylo::trainer::internal

#endif
