/*
 * A toy mode, added in this one place: a double integrator on the whole
 * phase plane (p, v in [-1, 1], v' = u, running cost u^2 + rho, the
 * dynamics of di_neg's model). A build
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

// The double integrator's dynamics and cost (v' = u, u^2 + rho: di_neg's),
// on the whole plane.
struct ToyModel : DiModel {
	ToyModel(const ModeParams &p, double) : DiModel(p, *hylo_mode_describe(p.id)) {}

	static constexpr uint64_t kDefaultSamples = 200;
	Bounds bounds() const
	{
		Bounds b = DiModel::bounds();
		b.x_lo[0] = -1.0;
		b.x_hi[0] = 1.0;
		return b;
	}
};

}  // namespace hylo::trainer

#define HYLO_EXTRA_MODEL_TYPE_CASES \
	case HYLO_MODE_TOY:         \
		return f(ModelType<ToyModel>{});
#define HYLO_EXTRA_MODEL_CASES \
	case HYLO_MODE_TOY:    \
		return f(ToyModel(p, g));

#endif
