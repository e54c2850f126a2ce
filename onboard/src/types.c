#include "hylo/types.h"

#include <math.h>

static const unsigned mode_dims[HYLO_MODE_COUNT] = {
	[HYLO_MODE_GROUND] = 4,
	[HYLO_MODE_MARINE] = 4,
	[HYLO_MODE_FLIGHT] = 6,
	[HYLO_MODE_DI_NEG] = 2,
	[HYLO_MODE_DI_POS] = 2,
};

static const char *const mode_names[HYLO_MODE_COUNT] = {
	[HYLO_MODE_NONE] = "none",
	[HYLO_MODE_GROUND] = "ground",
	[HYLO_MODE_MARINE] = "marine",
	[HYLO_MODE_FLIGHT] = "flight",
	[HYLO_MODE_DI_NEG] = "di_neg",
	[HYLO_MODE_DI_POS] = "di_pos",
};

int hylo_mode_valid(int mode)
{
	return mode > HYLO_MODE_NONE && mode < HYLO_MODE_COUNT;
}

unsigned hylo_mode_dim(hylo_mode mode)
{
	return hylo_mode_valid((int)mode) ? mode_dims[mode] : 0;
}

const char *hylo_mode_str(hylo_mode mode)
{
	return hylo_mode_valid((int)mode) ? mode_names[mode] : "invalid";
}

hylo_real hylo_state_speed(hylo_mode mode, const hylo_real *xs)
{
	switch (mode) {
	case HYLO_MODE_GROUND:
	case HYLO_MODE_MARINE:
		return xs[2];
	case HYLO_MODE_FLIGHT:
		return sqrt(xs[3] * xs[3] + xs[4] * xs[4] + xs[5] * xs[5]);
	case HYLO_MODE_DI_NEG:
	case HYLO_MODE_DI_POS:
		return xs[1];
	default:
		return 0;
	}
}
