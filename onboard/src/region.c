#include "hylo/region.h"

#include "hylo/modes.h"

#include <math.h>
#include <stdio.h>

const char *hylo_coord_name(hylo_mode mode, unsigned k)
{
	const hylo_mode_desc *d = hylo_mode_describe(mode);

	return d && k < d->xs_dim ? d->coord[k].name : "?";
}

const char *hylo_coord_unit(hylo_mode mode, unsigned k)
{
	const hylo_mode_desc *d = hylo_mode_describe(mode);

	return d && k < d->xs_dim ? d->coord[k].unit : "?";
}

/* Rounding slack: a speed at its bound, given by its components, comes back
 * from sqrt a few ulps off; a bound at 0 gets an absolute 1e-9. */
static int within(hylo_real v, hylo_real lo, hylo_real hi)
{
	hylo_real slack = 1e-9 * (fabs(lo) > fabs(hi) ? fabs(lo) : fabs(hi));

	if (slack < 1e-9)
		slack = 1e-9;
	return v >= lo - slack && v <= hi + slack;
}

static int miss_at(hylo_region_miss *miss, hylo_region_part part, unsigned coord, hylo_real v,
		   hylo_real lo, hylo_real hi)
{
	if (miss) {
		miss->part = part;
		miss->end = 0;
		miss->coord = coord;
		miss->value = v;
		miss->lo = lo;
		miss->hi = hi;
	}
	return 0;
}

int hylo_region_state(const hylo_svr_model *m, hylo_mode mode, const hylo_real *xs,
		      hylo_region_miss *miss)
{
	unsigned k, dim = hylo_mode_dim(mode);
	hylo_real speed = hylo_state_speed(mode, xs);

	if (!hylo_svr_speed_trained(m, speed))
		return miss_at(miss, HYLO_REGION_SPEED, 0, speed, m->speed_min_mps, m->speed_max_mps);
	for (k = 0; k < dim; k++)
		if ((m->state_bounded >> k & 1u) && !within(xs[k], m->state_min[k], m->state_max[k]))
			return miss_at(miss, HYLO_REGION_COORD, k, xs[k], m->state_min[k],
				       m->state_max[k]);
	if (miss)
		miss->part = HYLO_REGION_INSIDE;
	return 1;
}

hylo_real hylo_edge_distance(hylo_mode mode, const hylo_real *a, const hylo_real *b)
{
	const hylo_mode_desc *d = hylo_mode_describe(mode);
	hylo_real s2 = 0, dk;
	unsigned k;

	if (!d)
		return 0;
	for (k = 0; k < d->distance_dims; k++) {
		dk = b[k] - a[k];
		s2 += dk * dk;
	}
	return sqrt(s2);
}

int hylo_region_edge(const hylo_svr_model *m, hylo_mode mode, const hylo_real *tail,
		     const hylo_real *head, hylo_region_miss *miss)
{
	hylo_real d = hylo_edge_distance(mode, tail, head);

	if (m->max_distance_m > 0 && !within(d, 0, m->max_distance_m))
		return miss_at(miss, HYLO_REGION_DISTANCE, 0, d, 0, m->max_distance_m);
	if (!hylo_region_state(m, mode, tail, miss))
		return 0;
	if (!hylo_region_state(m, mode, head, miss)) {
		if (miss)
			miss->end = 1;
		return 0;
	}
	return 1;
}

void hylo_region_describe(hylo_mode mode, const hylo_region_miss *miss, char *buf, size_t n)
{
	if (!buf || n == 0)
		return;
	switch (miss->part) {
	case HYLO_REGION_SPEED:
		snprintf(buf, n, "speed %g m/s is outside the training range [%g, %g] m/s", miss->value,
			 miss->lo, miss->hi);
		break;
	case HYLO_REGION_COORD:
		snprintf(buf, n, "%s = %g %s is outside the training range [%g, %g] %s",
			 hylo_coord_name(mode, miss->coord), miss->value,
			 hylo_coord_unit(mode, miss->coord), miss->lo, miss->hi,
			 hylo_coord_unit(mode, miss->coord));
		break;
	case HYLO_REGION_DISTANCE:
		snprintf(buf, n, "displacement %g m is beyond the training range %g m", miss->value,
			 miss->hi);
		break;
	default:
		snprintf(buf, n, "inside the training region");
		break;
	}
}
