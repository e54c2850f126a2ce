#include <math.h>
#include "hylo/features.h"

unsigned hylo_feature_count(hylo_mode mode)
{
	switch (mode) {
	case HYLO_MODE_GROUND:
	case HYLO_MODE_MARINE:
		return HYLO_FEATURES_PLANAR;
	case HYLO_MODE_FLIGHT:
		return HYLO_FEATURES_FLIGHT;
	case HYLO_MODE_DI_NEG:
	case HYLO_MODE_DI_POS:
		return HYLO_FEATURES_DI;
	default:
		return 0;
	}
}

hylo_real hylo_wrap_angle(hylo_real a)
{
	const hylo_real two_pi = 6.283185307179586476925286766559;
	hylo_real w;

	if (!isfinite(a))
		return a;
	w = fmod(a, two_pi);              /* (-2pi, 2pi), sign of a */
	if (w > two_pi / 2)
		w -= two_pi;
	else if (w <= -two_pi / 2)
		w += two_pi;
	return w;
}

unsigned hylo_features(hylo_mode mode, const hylo_real *tail, const hylo_real *head,
		       hylo_real *f)
{
	unsigned k;

	switch (mode) {
	case HYLO_MODE_GROUND:
	case HYLO_MODE_MARINE: {
		hylo_real dx = head[0] - tail[0], dy = head[1] - tail[1];
		hylo_real c = cos(tail[3]), s = sin(tail[3]);

		f[0] = c * dx + s * dy;
		f[1] = -s * dx + c * dy;
		f[2] = hylo_wrap_angle(head[3] - tail[3]);
		f[3] = tail[2];
		f[4] = head[2];
		return HYLO_FEATURES_PLANAR;
	}
	case HYLO_MODE_FLIGHT:
		for (k = 0; k < 3; k++) {
			f[k] = head[k] - tail[k];
			f[3 + k] = tail[3 + k];
			f[6 + k] = head[3 + k];
		}
		return HYLO_FEATURES_FLIGHT;
	case HYLO_MODE_DI_NEG:
	case HYLO_MODE_DI_POS:
		f[0] = tail[0];
		f[1] = tail[1];
		f[2] = head[0];
		f[3] = head[1];
		return HYLO_FEATURES_DI;
	default:
		return 0;
	}
}
