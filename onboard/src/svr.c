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
	for (k = 0; k < HYLO_MAX_FEATURES; k++)
		c->n_used[k] = 0;
}

/* The factor row of feature k at standardized value v, computing it into the
 * least recently used slot when v is not cached. */
static const double *factor_row(const hylo_svr_model *m, hylo_svr_cache *c, uint32_t k,
				double v)
{
	uint32_t j, slot = 0, i, nf = m->n_features;
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
	for (i = 0; i < m->n_sv; i++) {
		double d = v - m->sv[(size_t)i * nf + k];

		row[i] = exp(-m->gamma * d * d);
	}
	return row;
}

hylo_status hylo_svr_predict_batch(const hylo_svr_model *m, hylo_svr_cache *c,
				   const double *x, uint32_t n, double *cost)
{
	uint32_t e, i, k;

	if (!m || !c || (n > 0 && (!x || !cost)))
		return HYLO_E_NULL;
	if (m->n_sv > HYLO_MAX_SV || m->n_features > HYLO_MAX_FEATURES || m->n_features == 0)
		return HYLO_E_CAP_SV;
	if (c->model != m) {
		hylo_svr_cache_reset(c);
		c->model = m;
	}
	for (e = 0; e < n; e++) {
		const double *xe = &x[(size_t)e * m->n_features];
		const double *row[HYLO_MAX_FEATURES];
		double z[HYLO_MAX_FEATURES], sum = 0;
		int finite = 1;

		standardize(m, xe, z);
		for (k = 0; k < m->n_features; k++)
			finite &= isfinite(z[k]) != 0;
		if (!finite) {  /* never cache NaN: it would never match again */
			cost[e] = NAN;
			continue;
		}
		for (k = 0; k < m->n_features; k++)
			row[k] = factor_row(m, c, k, z[k]);
		for (i = 0; i < m->n_sv; i++) {
			double p = m->coef[i];

			for (k = 0; k < m->n_features; k++)
				p *= row[k][i];
			sum += p;
		}
		cost[e] = label_of(m, sum - m->rho);
	}
	return HYLO_OK;
}
