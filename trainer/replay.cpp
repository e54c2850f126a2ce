#include "trainer/replay.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <vector>

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "trainer/model_table.hpp"

namespace hylo::trainer {
namespace {

// Move-only owners of the SUNDIALS handles; constructors fail loudly.
struct Context {
	SUNContext ctx = nullptr;
	Context()
	{
		if (SUNContext_Create(nullptr, &ctx) != 0)
			throw std::runtime_error("SUNContext_Create failed");
	}
	~Context() { SUNContext_Free(&ctx); }
	Context(const Context &) = delete;
	Context &operator=(const Context &) = delete;
};

template <class M>
struct Replay {
	const M &m;
	const Trajectory &tr;
	int N;             // segments
	double h;

	// HS-consistent input at time t.
	void input(double t, double *u) const
	{
		int k = std::min(N - 1, std::max(0, static_cast<int>(std::floor(t / h))));
		double s = (t - k * h) / h;   // in [0, 1]
		const double *ua = &tr.u[static_cast<size_t>(2 * k) * M::NU];
		const double *um = &tr.u[static_cast<size_t>(2 * k + 1) * M::NU];
		const double *ub = &tr.u[static_cast<size_t>(2 * k + 2) * M::NU];
		double la = 2 * (s - 0.5) * (s - 1), lm = -4 * s * (s - 1), lb = 2 * s * (s - 0.5);
		for (int j = 0; j < M::NU; j++)
			u[j] = la * ua[j] + lm * um[j] + lb * ub[j];
	}

	static int rhs(sunrealtype t, N_Vector y, N_Vector ydot, void *user)
	{
		auto *self = static_cast<Replay *>(user);
		double u[M::NU], f[M::NX], L, path[M::NP > 0 ? M::NP : 1];
		self->input(t, u);
		self->m.template eval<double>(N_VGetArrayPointer(y), u, f, L, path);
		double *d = N_VGetArrayPointer(ydot);
		for (int k = 0; k < M::NX; k++)
			d[k] = f[k];
		d[M::NX] = L;
		return 0;
	}
};

template <class M>
void replay_model(const M &model, Solution &s, double state_tol)
{
	const Trajectory &tr = s.traj;
	int N = (static_cast<int>(tr.t.size()) - 1) / 2;
	if (N < 1 || tr.nx != M::NX || tr.nu != M::NU)
		throw std::invalid_argument("replay: malformed trajectory");
	Replay<M> r{model, tr, N, s.T / N};
	Context c;
	N_Vector y = N_VNew_Serial(M::NX + 1, c.ctx);
	double *yv = N_VGetArrayPointer(y);
	for (int k = 0; k < M::NX; k++)
		yv[k] = tr.x[static_cast<size_t>(k)];
	yv[M::NX] = 0;
	void *mem = CVodeCreate(CV_BDF, c.ctx);
	SUNMatrix A = SUNDenseMatrix(M::NX + 1, M::NX + 1, c.ctx);
	SUNLinearSolver LS = SUNLinSol_Dense(y, A, c.ctx);
	bool ok = mem && A && LS && CVodeInit(mem, Replay<M>::rhs, 0.0, y) == CV_SUCCESS &&
		  CVodeSStolerances(mem, 1e-9, 1e-9) == CV_SUCCESS &&
		  CVodeSetUserData(mem, &r) == CV_SUCCESS &&
		  CVodeSetLinearSolver(mem, LS, A) == CV_SUCCESS &&
		  CVodeSetMaxNumSteps(mem, 200000) == CV_SUCCESS;
	// Integrate segment by segment: the input's derivative jumps at knots.
	// A model unstable open loop (M::kReplayFromKnots) restarts every
	// segment from its own knot and is judged by the worst segment's end.
	double t = 0, err = 0;
	auto sc = model.scale();
	Bounds bd = model.bounds();
	double worst_bound = 0, worst_bound_t = 0;
	int worst_bound_j = -1;
	auto error_at = [&](int k) {   // scaled distance of y from knot k
		const double *xk = &tr.x[static_cast<size_t>(2 * k) * M::NX];
		for (int j = 0; j < M::NX; j++)
			err = std::max(err, std::fabs(yv[j] - xk[j]) / sc[static_cast<size_t>(j)]);
	};
	for (int k = 1; ok && k <= N; k++) {
		double tk = s.T * k / N;
		ok = CVodeSetStopTime(mem, tk) == CV_SUCCESS && CVode(mem, tk, y, &t, CV_NORMAL) >= 0;
		for (int j = 0; ok && j < M::NX; j++) {
			double lo = bd.x_lo[static_cast<size_t>(j)], hi = bd.x_hi[static_cast<size_t>(j)];
			double over = std::max(lo - yv[j], yv[j] - hi) / sc[static_cast<size_t>(j)];
			if (over > worst_bound) {
				worst_bound = over;
				worst_bound_j = j;
				worst_bound_t = tk;
			}
		}
		if (ok && M::kReplayFromKnots && k < N) {
			error_at(k);
			for (int j = 0; j < M::NX; j++)
				yv[j] = tr.x[static_cast<size_t>(2 * k) * M::NX + static_cast<size_t>(j)];
			ok = CVodeReInit(mem, tk, y) == CV_SUCCESS;
		}
	}
	s.replayed = true;
	s.replay_check = ReplayCheck{};
	if (ok) {
		error_at(N);
		s.replay_error = err;
		s.replay_cost = yv[M::NX];
		const double cost_dev = std::fabs(s.replay_cost - s.cost) / std::max(std::fabs(s.cost), 1e-300);
		// The first check that fails, in this order: end state, state bounds, cost.
		if (err > state_tol)
			s.replay_check = {"end state", err, state_tol};
		else if (worst_bound > state_tol)
			s.replay_check = {"state bounds", worst_bound, state_tol, worst_bound_j, worst_bound_t};
		else if (!(cost_dev <= kReplayCostTol))
			s.replay_check = {"cost", cost_dev, kReplayCostTol};
		s.replay_ok = s.replay_check.check.empty();
	} else {
		s.replay_error = INFINITY;
		s.replay_cost = NAN;
		s.replay_ok = false;
		s.replay_check = {"integration", INFINITY, state_tol};
	}
	SUNLinSolFree(LS);
	SUNMatDestroy(A);
	CVodeFree(&mem);
	N_VDestroy(y);
}

}  // namespace

std::string replay_verdict(const Solution &s)
{
	const ReplayCheck &c = s.replay_check;
	if (!s.replayed)
		return "not replayed";
	if (c.check.empty())
		return "replay passed";
	char buf[160];
	if (c.check == "end state")
		std::snprintf(buf, sizeof buf, "replayed end state off by %.3g (scaled) > tolerance %.3g", c.value, c.tol);
	else if (c.check == "state bounds")
		std::snprintf(buf, sizeof buf,
			      "replayed state %d leaves the mode's bounds by %.3g (scaled) at t = %.3g s > tolerance %.3g",
			      c.component, c.value, c.t_s, c.tol);
	else if (c.check == "cost")
		std::snprintf(buf, sizeof buf, "replayed cost %.6g J differs from %.6g J by %.3g%% > tolerance %.3g%%",
			      s.replay_cost, s.cost, 100 * c.value, 100 * c.tol);
	else
		std::snprintf(buf, sizeof buf, "CVODE could not integrate the control");
	return c.check + ": " + buf;
}

void replay(hylo_mode mode, const RobotParams &robot, Solution &s, double state_tol)
{
	const ModeParams &p = robot.mode(mode);
	with_model(p, robot.g, [&](const auto &model) { replay_model(model, s, state_tol); });
}

}  // namespace hylo::trainer
