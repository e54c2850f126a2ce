#include "hylo/types.h"

#include <math.h>
#include "hylo/modes.h"

int hylo_mode_valid(int mode)
{
	return mode > HYLO_MODE_NONE && mode < HYLO_MODE_COUNT;
}

unsigned hylo_mode_dim(hylo_mode mode)
{
	const hylo_mode_desc *d = hylo_mode_describe(mode);

	return d ? d->xs_dim : 0;
}

const char *hylo_mode_str(hylo_mode mode)
{
	const hylo_mode_desc *d = hylo_mode_describe(mode);

	return d ? d->name : "invalid";
}

hylo_real hylo_state_speed(hylo_mode mode, const hylo_real *xs)
{
	const hylo_mode_desc *d = hylo_mode_describe(mode);
	hylo_real s2 = 0;
	unsigned k;

	if (!d)
		return 0;
	if (d->speed_width == 1)
		return xs[d->speed_index];
	for (k = 0; k < d->speed_width; k++)
		s2 += xs[d->speed_index + k] * xs[d->speed_index + k];
	return sqrt(s2);
}
