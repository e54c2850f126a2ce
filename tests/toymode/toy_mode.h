/*
 * A toy mode, added in this one place: a double integrator on the whole
 * phase plane (p, v in [-1, 1], v' = u, running cost u^2 + rho). A build
 * with -DHYLO_EXTRA_MODES_H='"toymode/toy_mode.h"' -Itests (mk/toymode.mk)
 * has mode 6, "toy": its value (hylo/types.h), its record (hylo/modes.h,
 * onboard/src/modes.c) and its trainer model (trainer/model_table.hpp).
 * tests/toymode/test_toy_mode.sh trains it, exports its header, registers
 * it for a robot "toy" and plans with it.
 */

/* The mode's value and record (C: the onboard library, the trainer). */
#ifndef HYLO_TOY_MODE_H
#define HYLO_TOY_MODE_H

#define HYLO_EXTRA_MODE_ENUM HYLO_MODE_TOY = 6,

#define HYLO_EXTRA_MODE_RECORDS                                                          \
	[HYLO_MODE_TOY] = {                                                              \
		.mode = HYLO_MODE_TOY, .name = "toy", .c_name = "HYLO_MODE_TOY",         \
		.xs_dim = 2, .coord = { { "p", "m" }, { "v", "m/s" } },                  \
		.speed_index = 1, .speed_width = 1, .distance_dims = 2,                  \
		.domain = HYLO_DOMAIN_PHASE, .side = 0, .layout = HYLO_LAYOUT_PHASE,     \
		.nx = 2, .nu = 1,                                                        \
	},

#endif

/* Its model (C++: the trainer, from trainer/model_table.hpp). */
#if defined(__cplusplus) && defined(HYLO_EXTRA_MODELS_WANTED) && !defined(HYLO_TOY_MODEL)
#define HYLO_TOY_MODEL

namespace hylo::trainer {

struct ToyModel {
	double relax = 1.0;
	static constexpr int NX = 2, NU = 1, NP = 0, NS = 2;
	static constexpr bool kSmoothed = false;
	static constexpr bool kReplayFromKnots = false;
	double rho;

	ToyModel(const ModeParams &p, double) : rho(p.at("rho")) {}

	static std::vector<std::string> param_keys() { return {"rho"}; }
	static SolverHints solver_hints() { return {}; }
	static constexpr uint64_t kDefaultSamples = 200;
	double floor_power() const { return rho; }
	double top_speed() const { return 1.0; }

	template <class S>
	void eval(const S *x, const S *u, S *f, S &L, S *) const
	{
		f[0] = x[1];
		f[1] = u[0];
		L = u[0] * u[0] + rho;
	}
	Bounds bounds() const
	{
		Bounds b;
		b.x_lo = {-1.0, -1.0};
		b.x_hi = {1.0, 1.0};
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

}  // namespace hylo::trainer

#define HYLO_EXTRA_MODEL_TYPE_CASES \
	case HYLO_MODE_TOY:         \
		return f(ModelType<ToyModel>{});
#define HYLO_EXTRA_MODEL_CASES \
	case HYLO_MODE_TOY:    \
		return f(ToyModel(p, g));

#endif
