#include <math.h>
#include <stddef.h>
#include "hylo/svr.h"

static int finite_array(const double *a, uint32_t n)
{
	uint32_t i;

	for (i = 0; i < n; i++)
		if (!isfinite(a[i]))
			return 0;
	return 1;
}

hylo_status hylo_svr_check(const hylo_svr_model *m, hylo_reason *r)
{
	const char *name;
	uint32_t k;

	if (!m)
		return hylo_fail(r, HYLO_E_NULL, "svr: model is NULL");
	name = m->name ? m->name : "(unnamed)";
	if (m->n_sv > HYLO_MAX_SV || m->n_features > HYLO_MAX_FEATURES)
		return hylo_fail(r, HYLO_E_CAP_SV,
				 "svr model %s: %u support vectors x %u features exceeds "
				 "HYLO_MAX_SV=%u / HYLO_MAX_FEATURES=%u",
				 name, (unsigned)m->n_sv, (unsigned)m->n_features,
				 (unsigned)HYLO_MAX_SV, (unsigned)HYLO_MAX_FEATURES);
	if (m->n_features == 0)
		return hylo_fail(r, HYLO_E_BAD_VALUE, "svr model %s: no features", name);
	if ((m->n_sv > 0 && (!m->sv || !m->coef)) || !m->feature_offset || !m->feature_scale)
		return hylo_fail(r, HYLO_E_NULL, "svr model %s: a data array is NULL", name);
	if (!(m->gamma > 0) || !isfinite(m->gamma))
		return hylo_fail(r, HYLO_E_BAD_VALUE, "svr model %s: gamma %g is not > 0",
				 name, m->gamma);
	if (!isfinite(m->rho) || !isfinite(m->label_offset))
		return hylo_fail(r, HYLO_E_BAD_VALUE, "svr model %s: rho or label_offset not finite",
				 name);
	if (!(m->label_scale > 0) || !isfinite(m->label_scale))
		return hylo_fail(r, HYLO_E_BAD_VALUE, "svr model %s: label_scale %g is not > 0",
				 name, m->label_scale);
	if (m->label_log != 0 && m->label_log != 1)
		return hylo_fail(r, HYLO_E_BAD_VALUE, "svr model %s: label_log is %d, not 0 or 1",
				 name, m->label_log);
	if (!(m->cost_floor_per_m >= 0) || !isfinite(m->cost_floor_per_m))
		return hylo_fail(r, HYLO_E_BAD_VALUE, "svr model %s: cost_floor_per_m %g is not >= 0",
				 name, m->cost_floor_per_m);
	if (!(m->cost_floor_j >= 0) || !isfinite(m->cost_floor_j))
		return hylo_fail(r, HYLO_E_BAD_VALUE, "svr model %s: cost_floor_j %g is not >= 0",
				 name, m->cost_floor_j);
	if (!(m->max_distance_m >= 0) || !isfinite(m->max_distance_m))
		return hylo_fail(r, HYLO_E_BAD_VALUE, "svr model %s: max_distance_m %g is not >= 0",
				 name, m->max_distance_m);
	for (k = 0; k < m->n_features; k++)
		if (!isfinite(m->feature_offset[k]) || !(m->feature_scale[k] > 0) ||
		    !isfinite(m->feature_scale[k]))
			return hylo_fail(r, HYLO_E_BAD_VALUE,
					 "svr model %s: feature %u has offset %g, scale %g "
					 "(scale must be finite and > 0)",
					 name, (unsigned)k, m->feature_offset[k], m->feature_scale[k]);
	if (!finite_array(m->coef, m->n_sv) ||
	    !finite_array(m->sv, m->n_sv * m->n_features))
		return hylo_fail(r, HYLO_E_BAD_VALUE,
				 "svr model %s: a support vector or coefficient is not finite", name);
	hylo_reason_clear(r);
	return HYLO_OK;
}

double hylo_svr_decision(const hylo_svr_model *m, const double *z)
{
	double sum = 0;
	uint32_t i, k, nf = m->n_features;

	for (i = 0; i < m->n_sv; i++) {
		const double *s = &m->sv[(size_t)i * nf];
		double d2 = 0;

		for (k = 0; k < nf; k++) {
			double d = z[k] - s[k];

			d2 += d * d;
		}
		sum += m->coef[i] * exp(-m->gamma * d2);
	}
	return sum - m->rho;
}

static double label_of(const hylo_svr_model *m, double d)
{
	double y = d * m->label_scale + m->label_offset;

	return m->label_log ? exp(y) : y;
}

static void standardize(const hylo_svr_model *m, const double *x, double *z)
{
	uint32_t k;

	for (k = 0; k < m->n_features; k++)
		z[k] = (x[k] - m->feature_offset[k]) / m->feature_scale[k];
}

double hylo_svr_cost_floor(const hylo_svr_model *m, double distance_m)
{
	return m->cost_floor_j + m->cost_floor_per_m * distance_m;
}

double hylo_svr_predict(const hylo_svr_model *m, const double *x)
{
	double z[HYLO_MAX_FEATURES];

	standardize(m, x, z);
	return label_of(m, hylo_svr_decision(m, z));
}

void hylo_svr_cache_reset(hylo_svr_cache *c)
{
	uint32_t k;

	if (!c)
		return;
	c->model = NULL;
	c->clock = 0;
	c->hits = c->misses = 0;
	c->n_prefix = 0;
	for (k = 0; k < HYLO_MAX_FEATURES; k++)
		c->n_used[k] = 0;
}

/* The factor row of feature k at standardized value v, computing it into the
 * least recently used slot when v is not cached. */
static const double *factor_row(const hylo_svr_model *m, hylo_svr_cache *c, uint32_t k,
				double v)
{
	uint32_t j, slot = 0, i;
	const double *col;
	double *row;

	for (j = 0; j < c->n_used[k]; j++)
		if (c->value[k][j] == v) {
			c->last_use[k][j] = ++c->clock;
			c->hits++;
			return c->factor[k][j];
		}
	if (c->n_used[k] < HYLO_SVR_CACHE_VALUES) {
		slot = c->n_used[k]++;
	} else {
		for (j = 1; j < HYLO_SVR_CACHE_VALUES; j++)
			if (c->last_use[k][j] < c->last_use[k][slot])
				slot = j;
	}
	c->misses++;
	c->value[k][slot] = v;
	c->last_use[k][slot] = ++c->clock;
	row = c->factor[k][slot];
	col = c->sv_col[k];
	for (i = 0; i < m->n_sv; i++) {
		double d = v - col[i];

		row[i] = exp(-m->gamma * d * d);
	}
	return row;
}

/* The running-product order (see svr.h): planar (dx', dy', dtheta, vx1, vx2)
 * as vx1, dx', dy', vx2, dtheta; flight (dp, v1, v2) as v1, dp, v2; the
 * double integrator's (p1, v1, p2, v2) as is. */
static void feature_order(uint32_t nf, uint32_t *order)
{
	static const uint32_t planar[5] = { 3, 0, 1, 4, 2 };
	static const uint32_t flight[9] = { 3, 4, 5, 0, 1, 2, 6, 7, 8 };
	uint32_t k;

	for (k = 0; k < nf; k++)
		order[k] = nf == 5 ? planar[k] : nf == 9 ? flight[k] : k;
}

/* sum_i a[i] * b[i] with four partial sums in a fixed pattern: a quarter of
 * the dependent-add latency of one running sum, and the same bits every time. */
static double dot(const double *a, const double *b, uint32_t n)
{
	double s0 = 0, s1 = 0, s2 = 0, s3 = 0;
	uint32_t i;

	for (i = 0; i + 4 <= n; i += 4) {
		s0 += a[i] * b[i];
		s1 += a[i + 1] * b[i + 1];
		s2 += a[i + 2] * b[i + 2];
		s3 += a[i + 3] * b[i + 3];
	}
	for (; i < n; i++)
		s0 += a[i] * b[i];
	return (s0 + s1) + (s2 + s3);
}

/* Decision value of standardized z, reusing the running products of the
 * previous prediction up to the first feature (in order) that changed. */
static double cached_decision(const hylo_svr_model *m, hylo_svr_cache *c, const double *z)
{
	uint32_t order[HYLO_MAX_FEATURES], nf = m->n_features, n = m->n_sv, level, i;
	const double *row;

	feature_order(nf, order);
	for (level = 0; level < c->n_prefix && level + 1 < nf; level++)
		if (c->prefix_value[level] != z[order[level]])
			break;
	for (; level + 1 < nf; level++) {
		double *out = c->prefix[level];

		row = factor_row(m, c, order[level], z[order[level]]);
		if (level == 0)
			for (i = 0; i < n; i++)
				out[i] = m->coef[i] * row[i];
		else
			for (i = 0; i < n; i++)
				out[i] = c->prefix[level - 1][i] * row[i];
		c->prefix_value[level] = z[order[level]];
	}
	c->n_prefix = nf - 1;
	row = factor_row(m, c, order[nf - 1], z[order[nf - 1]]);
	return dot(nf == 1 ? m->coef : c->prefix[nf - 2], row, n) - m->rho;
}

hylo_status hylo_svr_predict_batch(const hylo_svr_model *m, hylo_svr_cache *c,
				   const double *x, uint32_t n, double *cost)
{
	uint32_t e, k;

	if (!m || !c || (n > 0 && (!x || !cost)))
		return HYLO_E_NULL;
	if (m->n_sv > HYLO_MAX_SV || m->n_features > HYLO_MAX_FEATURES || m->n_features == 0)
		return HYLO_E_CAP_SV;
	if (c->model != m) {
		uint32_t i;

		hylo_svr_cache_reset(c);
		c->model = m;
		for (k = 0; k < m->n_features; k++)
			for (i = 0; i < m->n_sv; i++)
				c->sv_col[k][i] = m->sv[(size_t)i * m->n_features + k];
	}
	for (e = 0; e < n; e++) {
		double z[HYLO_MAX_FEATURES];
		int finite = 1;

		standardize(m, &x[(size_t)e * m->n_features], z);
		for (k = 0; k < m->n_features; k++)
			finite &= isfinite(z[k]) != 0;
		if (!finite) {  /* never cache NaN: it would never match again */
			cost[e] = NAN;
			continue;
		}
		cost[e] = label_of(m, cached_decision(m, c, z));
	}
	return HYLO_OK;
}
