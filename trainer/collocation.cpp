#include "trainer/collocation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <memory>
#include <stdexcept>

#include <Eigen/Dense>
#include <unsupported/Eigen/AutoDiff>

#include <IpIpoptApplication.hpp>
#include <IpSolveStatistics.hpp>
#include <IpTNLP.hpp>

#include "trainer/models.hpp"
#include "trainer/replay.hpp"

namespace hylo::trainer {
namespace {

using Ipopt::Index;
using Ipopt::Number;

// One mode's transcription. M provides NX, NU, NP, eval<S>() and bounds().
template <class M>
class HsNlp : public Ipopt::TNLP {
public:
	static constexpr int NX = M::NX, NU = M::NU, NP = M::NP, NZ = NX + NU;
	static constexpr int NPO = NP > 0 ? NP : 1;   // array size for path outputs
	using AD1 = Eigen::AutoDiffScalar<Eigen::Matrix<double, NZ, 1>>;
	using AD2 = Eigen::AutoDiffScalar<Eigen::Matrix<AD1, NZ, 1>>;

	HsNlp(const M &model, int segments, const std::array<double, NX> &x0,
	      const std::array<double, NX> &x1, double T_guess, double T_fixed)
		: m_(model), N_(segments), x0_(x0), x1_(x1), T_guess_(T_guess), T_fixed_(T_fixed),
		  b_(model.bounds())
	{
		npts_ = 2 * N_ + 1;
		nvar_ = npts_ * NZ + 1;
		ncon_ = 2 * N_ * NX + npts_ * NP + N_ * NU;
		f_.resize(static_cast<size_t>(npts_) * NX);
		L_.resize(static_cast<size_t>(npts_));
		path_.resize(static_cast<size_t>(npts_) * NPO);
		jf_.resize(static_cast<size_t>(npts_) * NX * NZ);
		jl_.resize(static_cast<size_t>(npts_) * NZ);
		jp_.resize(static_cast<size_t>(npts_) * NPO * NZ);
	}

	// Point p: knots 0..N are points 0..N, midpoint k is point N+1+k.
	int knot(int i) const { return i; }
	int mid(int k) const { return N_ + 1 + k; }
	int zi(int p) const { return p * NZ; }
	int Ti() const { return npts_ * NZ; }

	bool get_nlp_info(Index &n, Index &m, Index &nnz_jac, Index &nnz_h,
			  IndexStyleEnum &style) override
	{
		n = nvar_;
		m = ncon_;
		// C1: NX x (2 NZ + NX + 1), C2: NX x (3 NZ + 1), path: NP x NZ per point.
		nnz_jac = N_ * NX * (2 * NZ + NX + 1) + N_ * NX * (3 * NZ + 1) + npts_ * NP * NZ +
			  3 * N_ * NU;
		nnz_h = npts_ * (NZ * (NZ + 1) / 2 + NZ) + 1;
		style = TNLP::C_STYLE;
		return true;
	}

	bool get_bounds_info(Index, Number *xl, Number *xu, Index, Number *gl, Number *gu) override
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
		for (int k = 0; k < NX; k++) {
			xl[zi(knot(0)) + k] = xu[zi(knot(0)) + k] = x0_[static_cast<size_t>(k)];
			xl[zi(knot(N_)) + k] = xu[zi(knot(N_)) + k] = x1_[static_cast<size_t>(k)];
		}
		xl[Ti()] = T_fixed_ > 0 ? T_fixed_ : b_.T_min;
		xu[Ti()] = T_fixed_ > 0 ? T_fixed_ : b_.T_max;
		for (int r = 0; r < 2 * N_ * NX; r++)
			gl[r] = gu[r] = 0;
		for (int p = 0; p < npts_; p++)
			for (int j = 0; j < NP; j++) {
				gl[2 * N_ * NX + p * NP + j] = b_.path_lo[static_cast<size_t>(j)];
				gu[2 * N_ * NX + p * NP + j] = b_.path_hi[static_cast<size_t>(j)];
			}
		for (int r = c3(0); r < ncon_; r++)
			gl[r] = gu[r] = 0;
		return true;
	}

	// Start from z (a solution of the same size) instead of the straight-line guess.
	void warm_start(const std::vector<double> &z) { warm_ = z; }
	const std::vector<double> &solution() const { return z_; }

	bool get_starting_point(Index n, bool, Number *z, bool, Number *, Number *, Index, bool,
				Number *) override
	{
		if (warm_.size() == static_cast<size_t>(n)) {
			std::copy(warm_.begin(), warm_.end(), z);
			return true;
		}
		auto ug = m_.input_guess();
		for (int p = 0; p < npts_; p++) {
			double s = p <= N_ ? static_cast<double>(p) / N_
					   : (static_cast<double>(p - N_ - 1) + 0.5) / N_;
			for (int k = 0; k < NX; k++) {
				double a = x0_[static_cast<size_t>(k)], b = x1_[static_cast<size_t>(k)];
				z[zi(p) + k] = clamp(a + s * (b - a), b_.x_lo[static_cast<size_t>(k)],
						     b_.x_hi[static_cast<size_t>(k)]);
			}
			for (int k = 0; k < NU; k++)
				z[zi(p) + NX + k] = ug[static_cast<size_t>(k)];
		}
		z[Ti()] = T_fixed_ > 0 ? T_fixed_ : T_guess_;
		return true;
	}

	// Variables and constraints in units of each state's typical magnitude
	// (rotor and paddle speeds are hundreds of rad/s, positions metres).
	bool get_scaling_parameters(Number &obj_scaling, bool &use_x_scaling, Index n, Number *x_scaling,
				    bool &use_g_scaling, Index m, Number *g_scaling) override
	{
		auto sc = m_.scale();
		obj_scaling = 1.0 / std::max(1.0, T_guess_ * 10.0);
		use_x_scaling = true;
		use_g_scaling = true;
		for (int p = 0; p < npts_; p++) {
			for (int k = 0; k < NX; k++)
				x_scaling[zi(p) + k] = 1.0 / sc[static_cast<size_t>(k)];
			for (int k = 0; k < NU; k++)
				x_scaling[zi(p) + NX + k] = 1.0;
		}
		x_scaling[n - 1] = 1.0 / std::max(1.0, T_guess_);
		for (int r = 0; r < m; r++)
			g_scaling[r] = 1.0;
		for (int k = 0; k < N_; k++)
			for (int r = 0; r < NX; r++) {
				g_scaling[c1(k) + r] = 1.0 / sc[static_cast<size_t>(r)];
				g_scaling[c2(k) + r] = 1.0 / sc[static_cast<size_t>(r)];
			}
		return true;
	}

	bool eval_f(Index, const Number *z, bool new_x, Number &obj) override
	{
		update(z, new_x);
		double sum = 0;
		for (int p = 0; p < npts_; p++)
			sum += weight(p) * L_[static_cast<size_t>(p)];
		obj = z[Ti()] / (6.0 * N_) * sum;
		return true;
	}

	bool eval_grad_f(Index n, const Number *z, bool new_x, Number *g) override
	{
		update(z, new_x);
		std::fill(g, g + n, 0.0);
		double h6 = z[Ti()] / (6.0 * N_), sum = 0;
		for (int p = 0; p < npts_; p++) {
			for (int j = 0; j < NZ; j++)
				g[zi(p) + j] = h6 * weight(p) * jl_[static_cast<size_t>(p * NZ + j)];
			sum += weight(p) * L_[static_cast<size_t>(p)];
		}
		g[Ti()] = sum / (6.0 * N_);
		return true;
	}

	bool eval_g(Index, const Number *z, bool new_x, Index, Number *g) override
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
		return true;
	}

	bool eval_jac_g(Index, const Number *z, bool new_x, Index, Index, Index *iRow,
			Index *jCol, Number *v) override
	{
		int e = 0;
		if (!v) {
			for (int k = 0; k < N_; k++) {
				int a = knot(k), b = knot(k + 1), c = mid(k);
				for (int r = 0; r < NX; r++) {
					for (int j = 0; j < NZ; j++) put(iRow, jCol, e, c1(k) + r, zi(a) + j);
					for (int j = 0; j < NZ; j++) put(iRow, jCol, e, c1(k) + r, zi(b) + j);
					for (int j = 0; j < NX; j++) put(iRow, jCol, e, c1(k) + r, zi(c) + j);
					put(iRow, jCol, e, c1(k) + r, Ti());
				}
				for (int r = 0; r < NX; r++) {
					for (int j = 0; j < NZ; j++) put(iRow, jCol, e, c2(k) + r, zi(a) + j);
					for (int j = 0; j < NZ; j++) put(iRow, jCol, e, c2(k) + r, zi(b) + j);
					for (int j = 0; j < NZ; j++) put(iRow, jCol, e, c2(k) + r, zi(c) + j);
					put(iRow, jCol, e, c2(k) + r, Ti());
				}
			}
			for (int p = 0; p < npts_; p++)
				for (int r = 0; r < NP; r++)
					for (int j = 0; j < NZ; j++)
						put(iRow, jCol, e, 2 * N_ * NX + p * NP + r, zi(p) + j);
			for (int k = 0; k < N_; k++)
				for (int j = 0; j < NU; j++) {
					put(iRow, jCol, e, c3(k) + j, zi(mid(k)) + NX + j);
					put(iRow, jCol, e, c3(k) + j, zi(knot(k)) + NX + j);
					put(iRow, jCol, e, c3(k) + j, zi(knot(k + 1)) + NX + j);
				}
			return true;
		}
		update(z, new_x);
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
		return true;
	}

	bool eval_h(Index, const Number *z, bool, Number sigma, Index, const Number *lambda, bool,
		    Index, Index *iRow, Index *jCol, Number *v) override
	{
		int e = 0;
		if (!v) {
			for (int p = 0; p < npts_; p++) {
				for (int i = 0; i < NZ; i++)
					for (int j = 0; j <= i; j++)
						put(iRow, jCol, e, zi(p) + i, zi(p) + j);
				for (int j = 0; j < NZ; j++)
					put(iRow, jCol, e, Ti(), zi(p) + j);
			}
			put(iRow, jCol, e, Ti(), Ti());
			return true;
		}
		double T = z[Ti()];
		for (int p = 0; p < npts_; p++) {
			// The point's share of the Lagrangian: T * (Lambda . f + beta L) + mu . path.
			double w[NX + 1 + NPO] = {};
			for (int r = 0; r < NX; r++)
				w[r] = dyn_weight(p, r, lambda);
			w[NX] = sigma * weight(p) / (6.0 * N_);
			double grad[NZ], hess[NZ * NZ];
			hessian(z + zi(p), w, false, grad, hess);
			double hp[NZ * NZ] = {};
			if (NP > 0) {
				double wp[NX + 1 + NPO] = {};
				for (int r = 0; r < NP; r++)
					wp[NX + 1 + r] = lambda[2 * N_ * NX + p * NP + r];
				double gp[NZ];
				hessian(z + zi(p), wp, true, gp, hp);
			}
			for (int i = 0; i < NZ; i++)
				for (int j = 0; j <= i; j++)
					v[e++] = T * hess[i * NZ + j] + hp[i * NZ + j];
			for (int j = 0; j < NZ; j++)
				v[e++] = grad[j];
		}
		v[e++] = 0;
		return true;
	}

	void finalize_solution(Ipopt::SolverReturn, Index n, const Number *z, const Number *,
			       const Number *, Index, const Number *, const Number *, Number obj,
			       const Ipopt::IpoptData *, Ipopt::IpoptCalculatedQuantities *) override
	{
		z_.assign(z, z + n);
		obj_ = obj;
	}

	// Variables of the 2N-segment mesh from those of the N-segment one: the old
	// knots and midpoints, in time order, become the new knots; new midpoints
	// are the means of their knots.
	static std::vector<double> refine(const std::vector<double> &z, int N)
	{
		int M2 = 2 * N, npts2 = 2 * M2 + 1;
		std::vector<double> out(static_cast<size_t>(npts2) * NZ + 1);
		auto old_point = [&](int i) { return i % 2 == 0 ? i / 2 : N + 1 + i / 2; };
		for (int i = 0; i <= M2; i++)
			for (int j = 0; j < NZ; j++)
				out[static_cast<size_t>(i * NZ + j)] = z[static_cast<size_t>(old_point(i) * NZ + j)];
		for (int k = 0; k < M2; k++)
			for (int j = 0; j < NZ; j++)
				out[static_cast<size_t>((M2 + 1 + k) * NZ + j)] =
					0.5 * (out[static_cast<size_t>(k * NZ + j)] + out[static_cast<size_t>((k + 1) * NZ + j)]);
		out.back() = z.back();
		return out;
	}

	// The solution as a time-ordered trajectory.
	void fill(Solution &s) const
	{
		s.T = z_[static_cast<size_t>(Ti())];
		s.cost = obj_;
		s.traj.nx = NX;
		s.traj.nu = NU;
		s.traj.t.clear();
		s.traj.x.clear();
		s.traj.u.clear();
		for (int i = 0; i <= 2 * N_; i++) {
			int p = i % 2 == 0 ? knot(i / 2) : mid(i / 2);
			s.traj.t.push_back(s.T * i / (2.0 * N_));
			for (int k = 0; k < NX; k++)
				s.traj.x.push_back(z_[static_cast<size_t>(zi(p) + k)]);
			for (int k = 0; k < NU; k++)
				s.traj.u.push_back(z_[static_cast<size_t>(zi(p) + NX + k)]);
		}
	}

private:
	static double clamp(double v, double lo, double hi) { return std::min(std::max(v, lo), hi); }
	static void put(Index *iRow, Index *jCol, int &e, int r, int c)
	{
		iRow[e] = r;
		jCol[e] = c;
		e++;
	}
	int c1(int k) const { return k * 2 * NX; }
	int c2(int k) const { return k * 2 * NX + NX; }
	// Piecewise-linear control: the midpoint input is the mean of its knots'
	// (the optimizer cannot exploit Simpson's rule with chattering inputs).
	int c3(int k) const { return 2 * N_ * NX + npts_ * NP + k * NU; }
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

	// Gradient and Hessian of w . (f, L, path) at point variables zp (second-order AutoDiff).
	void hessian(const Number *zp, const double *w, bool path_only, double *grad, double *hess) const
	{
		AD2 in[NZ], out[NX], L, path[NPO];
		for (int j = 0; j < NZ; j++) {
			in[j].value() = AD1(zp[j], NZ, j);
			in[j].derivatives() = Eigen::Matrix<AD1, NZ, 1>::Constant(AD1(0.0, Eigen::Matrix<double, NZ, 1>::Zero()));
			in[j].derivatives()(j) = AD1(1.0, Eigen::Matrix<double, NZ, 1>::Zero());
		}
		m_.template eval<AD2>(in, in + NX, out, L, path);
		AD2 s = AD2(0.0);
		if (!path_only) {
			for (int r = 0; r < NX; r++)
				s = s + w[r] * out[r];
			s = s + w[NX] * L;
		}
		for (int r = 0; r < NP; r++)
			s = s + w[NX + 1 + r] * path[r];
		for (int i = 0; i < NZ; i++) {
			const AD1 &d = s.derivatives().size() ? s.derivatives()(i) : AD1(0.0);
			grad[i] = d.value();
			for (int j = 0; j < NZ; j++)
				hess[i * NZ + j] = d.derivatives().size() ? d.derivatives()(j) : 0.0;
		}
	}

	const M &m_;
	int N_, npts_, nvar_, ncon_;
	std::array<double, NX> x0_, x1_;
	double T_guess_, T_fixed_;
	Bounds b_;
	bool have_ = false;
	std::vector<double> f_, L_, path_, jf_, jl_, jp_;
	std::vector<double> z_, warm_;
	double obj_ = 0;
};

Ipopt::SmartPtr<Ipopt::IpoptApplication> make_app(const SolveOptions &opt, bool warm = false)
{
	Ipopt::SmartPtr<Ipopt::IpoptApplication> app = IpoptApplicationFactory();
	bool ok = app->Options()->SetIntegerValue("print_level", 0);
	ok = ok && app->Options()->SetStringValue("sb", "yes");
	ok = ok && app->Options()->SetNumericValue("tol", opt.tol);
	ok = ok && app->Options()->SetIntegerValue("max_iter", opt.max_iter);
	ok = ok && app->Options()->SetStringValue("linear_solver", "mumps");
	ok = ok && app->Options()->SetStringValue("nlp_scaling_method", "user-scaling");
	// Monotone barrier from a small start converged on every robot mode tried,
	// where the adaptive strategy hit the iteration limit (stiff friction terms).
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
	if (const char *extra = std::getenv("HYLO_IPOPT_OPTS")) {   // name=value,... for experiments
		std::string all = extra;
		size_t pos = 0;
		while (pos < all.size()) {
			size_t end = all.find(',', pos);
			std::string kv = all.substr(pos, end == std::string::npos ? std::string::npos : end - pos);
			size_t eq = kv.find('=');
			std::string k = kv.substr(0, eq), v = kv.substr(eq + 1);
			char *e = nullptr;
			double num = std::strtod(v.c_str(), &e);
			if (e && *e == '\0' && !v.empty())
				ok = ok && (v.find('.') == std::string::npos && v.find('e') == std::string::npos
						    ? app->Options()->SetIntegerValue(k, static_cast<int>(num))
						    : app->Options()->SetNumericValue(k, num));
			else
				ok = ok && app->Options()->SetStringValue(k, v);
			if (end == std::string::npos)
				break;
			pos = end + 1;
		}
	}
	if (!ok)
		throw std::logic_error("an Ipopt option was refused");
	// An empty options file name: never read ./ipopt.opt (deps.md).
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

template <class M>
Solution solve_model(const std::string &mode, const RobotParams &robot, const M &model,
		     const double *x1s, const double *x2s, const SolveOptions &opt)
{
	auto t0 = std::chrono::steady_clock::now();
	auto a = model.full_state(x1s), b = model.full_state(x2s);
	Bounds bd = model.bounds();
	for (int k = 0; k < M::NX; k++)
		for (double v : {a[static_cast<size_t>(k)], b[static_cast<size_t>(k)]})
			if (!std::isfinite(v) || v < bd.x_lo[static_cast<size_t>(k)] - 1e-12 ||
			    v > bd.x_hi[static_cast<size_t>(k)] + 1e-12)
				throw std::invalid_argument("boundary state component " + std::to_string(k) +
							    " = " + std::to_string(v) + " is outside [" +
							    std::to_string(bd.x_lo[static_cast<size_t>(k)]) + ", " +
							    std::to_string(bd.x_hi[static_cast<size_t>(k)]) +
							    "] of mode " + mode);
	std::vector<double> guesses = opt.T_guesses;
	if (guesses.empty()) {
		double d = model.position_distance(a.data(), b.data());
		double base = std::max(bd.T_min * 2, d / model.typical_speed());
		guesses = {base, 2 * base, 0.5 * base + bd.T_min};
	}
	Solution best;
	best.cost = std::numeric_limits<double>::infinity();
	const bool debug = std::getenv("HYLO_TRAINER_DEBUG") != nullptr;
	auto run = [&](const M &m, int segments, double T, const std::vector<double> &start,
		       Ipopt::SmartPtr<HsNlp<M>> &nlp, bool warm) {
		nlp = new HsNlp<M>(m, segments, a, b, T, opt.T_fixed);
		if (!start.empty())
			nlp->warm_start(start);
		auto app = make_app(opt, warm);
		Ipopt::ApplicationReturnStatus st = app->OptimizeTNLP(nlp);
		int it = Ipopt::IsValid(app->Statistics()) ? app->Statistics()->IterationCount() : 0;
		if (debug)
			std::fprintf(stderr, "start T=%g N=%d relax %g: %s, %d iterations\n", T, segments,
				     m.relax, status_text(st), it);
		return std::make_pair(st, it);
	};
	for (double T : guesses) {
		T = std::min(std::max(T, bd.T_min), bd.T_max);
		best.starts++;
		// Continuation on the coarse mesh: smoother problems first, each
		// starting the next; the last has models.md's exact constants.
		std::vector<double> start;
		Ipopt::SmartPtr<HsNlp<M>> nlp;
		std::pair<Ipopt::ApplicationReturnStatus, int> res{Ipopt::Solve_Succeeded, 0};
		M relaxed = model;
		const double levels[] = {100.0, 10.0, 3.0, 1.0};
		for (double relax : levels) {
			if ((!M::kSmoothed || !opt.derivative_test_file.empty()) && relax != 1.0)
				continue;
			relaxed.relax = relax;
			res = run(relaxed, opt.segments, T, start, nlp, !start.empty());
			if (succeeded(res.first))
				start = nlp->solution();
		}
		if (!opt.derivative_test_file.empty())
			return best;
		if (!succeeded(res.first))
			continue;
		best.converged_starts++;
		// Mesh refinement until the replay agrees: each finer mesh starts
		// from the coarser solution (its knots and midpoints become knots).
		int segments = opt.segments, iterations = res.second;
		for (int refine = 0;; refine++) {
			Solution s;
			nlp->fill(s);
			s.status = static_cast<int>(res.first);
			s.status_text = status_text(res.first);
			s.iterations = iterations;
			s.segments = segments;
			if (opt.replay) {
				replay(mode, robot, s);
				if (debug)
					std::fprintf(stderr, "  replay: error %.3g, cost %.6g vs %.6g (%.2f%%)\n",
						     s.replay_error, s.replay_cost, s.cost,
						     100 * (s.replay_cost - s.cost) / s.cost);
			}
			if (!opt.replay || s.replay_ok) {
				s.converged = true;
				if (s.cost < best.cost) {
					int starts = best.starts, conv = best.converged_starts;
					best = s;
					best.starts = starts;
					best.converged_starts = conv;
				}
				break;
			}
			if (refine >= opt.refinements)
				break;
			std::vector<double> fine = HsNlp<M>::refine(nlp->solution(), segments);
			segments *= 2;
			res = run(model, segments, T, fine, nlp, true);
			iterations += res.second;
			if (!succeeded(res.first))
				break;
		}
	}
	if (!best.converged) {
		best.cost = 0;
		best.status_text = best.converged_starts ? "replay rejected every solution" : "no start converged";
	}
	best.solve_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
	return best;
}

}  // namespace

bool known_mode(const std::string &m)
{
	return m == "ground" || m == "marine" || m == "flight" || m == "di_neg" || m == "di_pos";
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

Solution solve_bvp(const std::string &mode, const RobotParams &robot, const double *x1s,
		   const double *x2s, const SolveOptions &opt)
{
	if (!known_mode(mode))
		throw std::invalid_argument("unknown mode '" + mode + "' (ground, marine, flight, di_neg, di_pos)");
	const ModeParams &p = robot.mode(mode);
	if (mode == "ground")
		return solve_model(mode, robot, GroundModel(p, robot.g), x1s, x2s, opt);
	if (mode == "marine")
		return solve_model(mode, robot, MarineModel(p, robot.g), x1s, x2s, opt);
	if (mode == "flight")
		return solve_model(mode, robot, FlightModel(p, robot.g), x1s, x2s, opt);
	return solve_model(mode, robot, DiModel(p, mode == "di_pos"), x1s, x2s, opt);
}

}  // namespace hylo::trainer
