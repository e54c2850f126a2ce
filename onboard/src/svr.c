#include <math.h>
#include <stddef.h>
#include <string.h>
#include "hylo/features.h"
#include "hylo/svr.h"

/*
 * Two doubles per operation (GCC/Clang vector extension): SSE2 on x86-64,
 * NEON on aarch64, plain scalar code where neither exists. The batch path
 * spends most of its time in the kernel's exponentials and the running
 * products; this halves both (bench_plan). Same bits on every target: no
 * fused multiply-add (-std=c99 keeps contraction off), one rounding per op.
 */
typedef double hylo_v2 __attribute__((vector_size(16)));
typedef int64_t hylo_v2i __attribute__((vector_size(16)));

static hylo_v2 load2(const double *p)
{
	hylo_v2 v;

	memcpy(&v, p, sizeof v);
	return v;
}

static void store2(double *p, hylo_v2 v)
{
	memcpy(p, &v, sizeof v);
}

/*
 * exp(x) for x <= 0, to about 4e-16 relative (within two ulp of libm's): x =
 * k ln2 + r with |r| <= ln2/2, exp(r) by its degree-13 Taylor polynomial in
 * Estrin's form (short dependency chains), times 2^k put into the exponent
 * bits. Below -700 the result is 0 (libm's is < 1e-304, and it only ever
 * multiplies a support vector's coefficient).
 */
static hylo_v2 exp_nonpositive2(hylo_v2 x)
{
	const hylo_v2 shift = { 0x1.8p52, 0x1.8p52 }, lowest = { -700.0, -700.0 };
	const double ln2_hi = 0x1.62e42feep-1, ln2_lo = 0x1.a39ef35793c76p-33;
	hylo_v2i keep = x >= lowest, xb, lb, tb, pb;
	hylo_v2 t, k, r, r2, r4, r8, p;

	memcpy(&xb, &x, sizeof xb);
	memcpy(&lb, &lowest, sizeof lb);
	xb = (xb & keep) | (lb & ~keep);
	memcpy(&x, &xb, sizeof x);
	t = x * 0x1.71547652b82fep0 + shift;  /* k, rounded, in the low mantissa bits */
	k = t - shift;
	r = (x - k * ln2_hi) - k * ln2_lo;
	r2 = r * r;
	r4 = r2 * r2;
	r8 = r4 * r4;
	p = ((1.0 + r) + (0.5 + r * (1.0 / 6)) * r2) +
	    ((1.0 / 24 + r * (1.0 / 120)) + (1.0 / 720 + r * (1.0 / 5040)) * r2) * r4 +
	    (((1.0 / 40320 + r * (1.0 / 362880)) + (1.0 / 3628800 + r * (1.0 / 39916800)) * r2) +
	     (1.0 / 479001600 + r * (1.0 / 6227020800.0)) * r4) * r8;
	memcpy(&tb, &t, sizeof tb);
	memcpy(&pb, &p, sizeof pb);
	pb = (pb + (tb << 52)) & keep;
	memcpy(&p, &pb, sizeof p);
	return p;
}

static int finite_array(const double *a, uint32_t n)
{
	uint32_t i;

	for (i = 0; i < n; i++)
		if (!isfinite(a[i]))
			return 0;
	return 1;
}

static hylo_status check_envelope(const hylo_svr_model *m, const char *name, hylo_reason *r)
{
	const hylo_svr_envelope *e = m->envelope;
	uint64_t n;
	uint32_t i;

	if (m->n_features != HYLO_FEATURES_PLANAR && m->n_features != HYLO_FEATURES_FLIGHT)
		return hylo_fail(r, HYLO_E_BAD_VALUE,
				 "svr model %s: an envelope needs planar (%d) or flight (%d) features, "
				 "not %u", name, HYLO_FEATURES_PLANAR, HYLO_FEATURES_FLIGHT,
				 (unsigned)m->n_features);
	if (e->n_d == 0 || e->n_z == 0 || e->n_v == 0 ||
	    (m->n_features == HYLO_FEATURES_PLANAR && e->n_z != 1))
		return hylo_fail(r, HYLO_E_BAD_VALUE,
				 "svr model %s: envelope of %u x %u x %u cells (each >= 1, "
				 "planar climb cells 1)", name, (unsigned)e->n_d, (unsigned)e->n_z,
				 (unsigned)e->n_v);
	n = (uint64_t)e->n_d * e->n_z;
	if (n >= ((uint64_t)1 << 32) || e->n_v >= ((uint32_t)1 << 16) ||
	    n * e->n_v * e->n_v >= ((uint64_t)1 << 32))
		return hylo_fail(r, HYLO_E_BAD_VALUE,
				 "svr model %s: envelope of %u x %u x %u cells has 2^32 values or more",
				 name, (unsigned)e->n_d, (unsigned)e->n_z, (unsigned)e->n_v);
	if (!(e->d_step > 0) || !isfinite(e->d_step) || !(e->v_step > 0) || !isfinite(e->v_step) ||
	    !isfinite(e->v_min) || !isfinite(e->z_min) || !isfinite(e->z_step) ||
	    (e->n_z > 1 && !(e->z_step > 0)))
		return hylo_fail(r, HYLO_E_BAD_VALUE,
				 "svr model %s: envelope steps d %g, z %g, v %g m/s (finite, > 0) or "
				 "origins z %g, v %g not finite", name, e->d_step, e->z_step, e->v_step,
				 e->z_min, e->v_min);
	if (!e->value)
		return hylo_fail(r, HYLO_E_NULL, "svr model %s: the envelope's values are NULL", name);
	n *= (uint64_t)e->n_v * e->n_v;
	for (i = 0; i < (uint32_t)n; i++)
		if (!isfinite(e->value[i]) || !(e->value[i] >= 0))
			return hylo_fail(r, HYLO_E_BAD_VALUE,
					 "svr model %s: envelope value %u is %g (finite, >= 0)", name,
					 (unsigned)i, (double)e->value[i]);
	return HYLO_OK;
}

hylo_status hylo_svr_check(const hylo_svr_model *m, hylo_reason *r)
{
	hylo_status st;
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
	if (!isfinite(m->speed_min_mps) || !isfinite(m->speed_max_mps) ||
	    !(m->speed_min_mps <= m->speed_max_mps))
		return hylo_fail(r, HYLO_E_BAD_VALUE,
				 "svr model %s: speed range [%g, %g] m/s is not an interval",
				 name, m->speed_min_mps, m->speed_max_mps);
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
	if (m->envelope && (st = check_envelope(m, name, r)) != HYLO_OK)
		return st;
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

int hylo_svr_speed_trained(const hylo_svr_model *m, double speed)
{
	/* Rounding slack: a flight speed at the bound, given by its components,
	 * comes back from sqrt a few ulps off. */
	double slack = 1e-9 * (fabs(m->speed_min_mps) + fabs(m->speed_max_mps));

	if (m->speed_min_mps == 0 && m->speed_max_mps == 0)
		return !isnan(speed);
	return speed >= m->speed_min_mps - slack && speed <= m->speed_max_mps + slack;
}

/* The speed nodes of v: i[0] = i[1] = the node within 1e-9 m/s of v, else
 * the two bracketing it; 0 when v is outside the nodes or NaN. */
static int envelope_nodes(const hylo_svr_envelope *e, double v, uint32_t *i)
{
	double x = (v - e->v_min) / e->v_step, top = (double)(e->n_v - 1), dv;
	uint32_t n;

	if (!(x > -1 && x < top + 1))  /* also NaN; the casts below stay in range */
		return 0;
	n = x < 0 ? 0 : (uint32_t)(x + 0.5);
	if (n > e->n_v - 1)
		n = e->n_v - 1;
	dv = v - (e->v_min + n * e->v_step);
	if (dv >= -1e-9 && dv <= 1e-9) {
		i[0] = i[1] = n;
		return 1;
	}
	if (!(x > 0 && x < top))
		return 0;
	i[0] = (uint32_t)x;
	i[1] = i[0] + 1;
	return 1;
}

double hylo_svr_envelope_bound(const hylo_svr_model *m, double d, double dz, double v1, double v2)
{
	const hylo_svr_envelope *e;
	uint32_t k, j = 0, a[2], b[2], p, q;
	double x, best = 0;
	size_t row;

	if (!m || !(e = m->envelope) || !e->value)
		return 0;
	x = d / e->d_step;
	if (!(x >= 0 && x < (double)e->n_d))
		return 0;
	k = (uint32_t)x;
	if (e->n_z > 1) {
		x = (dz - e->z_min) / e->z_step;
		if (!(x >= 0 && x < (double)e->n_z))
			return 0;
		j = (uint32_t)x;
	}
	if (!envelope_nodes(e, v1, a) || !envelope_nodes(e, v2, b))
		return 0;
	row = ((size_t)k * e->n_z + j) * e->n_v;
	for (p = 0; p < 2; p++)
		for (q = 0; q < 2; q++) {
			double v = e->value[(row + a[p]) * e->n_v + b[q]];

			if ((p == 0 && q == 0) || v < best)
				best = v;
		}
	return best;
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
	c->n_groups = 0;
	c->clock = 0;
	c->hits = c->misses = 0;
	c->n_prefix = 0;
	for (k = 0; k < HYLO_MAX_FEATURES; k++)
		c->n_used[k] = 0;
}

/* The groups of svr.h for nf features (planar (dx', |dy'|, s*dtheta, vx1, vx2,
 * d, turn, arc), flight (dp, v1, v2), the double integrator's (p1, v1, p2,
 * v2)); any other count: one group per feature. */
static void feature_groups(hylo_svr_cache *c, uint32_t nf)
{
	static const uint32_t planar[8] = { 3, 0, 1, 2, 5, 6, 7, 4 }, planar_begin[4] = { 0, 1, 7, 8 };
	static const uint32_t flight[9] = { 3, 4, 5, 0, 1, 2, 6, 7, 8 }, flight_begin[4] = { 0, 3, 6, 9 };
	static const uint32_t di_begin[3] = { 0, 2, 4 };
	uint32_t k;

	for (k = 0; k < nf; k++)
		c->order[k] = nf == HYLO_FEATURES_PLANAR ? planar[k] : nf == HYLO_FEATURES_FLIGHT ? flight[k] : k;
	c->n_groups = nf == HYLO_FEATURES_PLANAR ? 3 : nf == HYLO_FEATURES_FLIGHT ? 3 :
		      nf == HYLO_FEATURES_DI ? 2 : nf;
	for (k = 0; k <= c->n_groups; k++)
		c->group_begin[k] = nf == HYLO_FEATURES_PLANAR ? planar_begin[k] :
				    nf == HYLO_FEATURES_FLIGHT ? flight_begin[k] :
				    nf == HYLO_FEATURES_DI ? di_begin[k] : k;
}

/* The factor row exp(-gamma |z_G - s_G|^2) of group g at the standardized
 * values v[] (its features in order), computing it into the least recently
 * used slot when v is not cached. */
static const double *factor_row(const hylo_svr_model *m, hylo_svr_cache *c, uint32_t g,
				const double *v)
{
	uint32_t b = c->group_begin[g], w = c->group_begin[g + 1] - b, j, k, slot = 0, i;
	double *row;

	for (j = 0; j < c->n_used[g]; j++) {
		for (k = 0; k < w && c->value[g][j][k] == v[k]; k++)
			;
		if (k == w) {
			c->last_use[g][j] = ++c->clock;
			c->hits++;
			return c->factor[g][j];
		}
	}
	if (c->n_used[g] < HYLO_SVR_CACHE_VALUES) {
		slot = c->n_used[g]++;
	} else {
		for (j = 1; j < HYLO_SVR_CACHE_VALUES; j++)
			if (c->last_use[g][j] < c->last_use[g][slot])
				slot = j;
	}
	c->misses++;
	for (k = 0; k < w; k++)
		c->value[g][slot][k] = v[k];
	c->last_use[g][slot] = ++c->clock;
	row = c->factor[g][slot];
	for (i = 0; i < m->n_sv; i += 2) {  /* an odd last one is paired with itself */
		uint32_t i1 = i + 1 < m->n_sv ? i + 1 : i;
		hylo_v2 d2 = { 0, 0 }, e;

		for (k = 0; k < w; k++) {
			const double *col = c->sv_col[c->order[b + k]];
			hylo_v2 d = { v[k] - col[i], v[k] - col[i1] };

			d2 += d * d;
		}
		e = exp_nonpositive2(-m->gamma * d2);
		row[i] = e[0];
		row[i1] = e[1];
	}
	return row;
}

/* sum_i a[i] * b[i] with four partial sums in a fixed pattern: a quarter of
 * the dependent-add latency of one running sum, and the same bits every time. */
static double dot(const double *a, const double *b, uint32_t n)
{
	hylo_v2 s01 = { 0, 0 }, s23 = { 0, 0 };
	double s[4];
	uint32_t i;

	for (i = 0; i + 4 <= n; i += 4) {
		s01 += load2(&a[i]) * load2(&b[i]);
		s23 += load2(&a[i + 2]) * load2(&b[i + 2]);
	}
	store2(&s[0], s01);
	store2(&s[2], s23);
	for (; i < n; i++)
		s[0] += a[i] * b[i];
	return (s[0] + s[1]) + (s[2] + s[3]);
}

/* out[i] = a[i] * b[i], i < n. */
static void multiply(double *out, const double *a, const double *b, uint32_t n)
{
	uint32_t i;

	for (i = 0; i + 2 <= n; i += 2)
		store2(&out[i], load2(&a[i]) * load2(&b[i]));
	if (i < n)
		out[i] = a[i] * b[i];
}

/* Decision value of standardized z, reusing the running products of the
 * previous prediction up to the first group (in order) that changed. */
static double cached_decision(const hylo_svr_model *m, hylo_svr_cache *c, const double *z)
{
	uint32_t ng = c->n_groups, n = m->n_sv, level, k;
	double v[HYLO_MAX_FEATURES];  /* z in group order */
	const double *row;

	for (k = 0; k < m->n_features; k++)
		v[k] = z[c->order[k]];
	for (level = 0; level < c->n_prefix && level + 1 < ng; level++) {
		for (k = c->group_begin[level];
		     k < c->group_begin[level + 1] && c->prefix_value[k] == v[k]; k++)
			;
		if (k < c->group_begin[level + 1])
			break;
	}
	for (; level + 1 < ng; level++) {
		row = factor_row(m, c, level, &v[c->group_begin[level]]);
		multiply(c->prefix[level], level == 0 ? m->coef : c->prefix[level - 1], row, n);
		for (k = c->group_begin[level]; k < c->group_begin[level + 1]; k++)
			c->prefix_value[k] = v[k];
	}
	c->n_prefix = ng - 1;
	row = factor_row(m, c, ng - 1, &v[c->group_begin[ng - 1]]);
	return dot(ng == 1 ? m->coef : c->prefix[ng - 2], row, n) - m->rho;
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
		feature_groups(c, m->n_features);
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
