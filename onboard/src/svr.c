#include <math.h>
#include <stddef.h>
#include <string.h>
#include "hylo/features.h"
#include "hylo/modes.h"
#include "hylo/svr.h"

#define TWO_PI 6.283185307179586476925286766559

/*
 * Four doubles per operation (GCC/Clang vector extension): two SSE2
 * operations on x86-64, or one AVX2 operation where the CPU has it (the hot
 * loops are compiled for both and chosen at run time, HYLO_CLONES), NEON on
 * aarch64. The batch path spends most of its time in the kernel's
 * exponentials and the running products. Same bits on every target and
 * path: every lane does the same operations in the same order, no fused
 * multiply-add (-ffp-contract=off, mk/config.mk), one rounding per op.
 */
typedef double hylo_v4 __attribute__((vector_size(32)));
/* The helpers below are static and inlined, so the AVX calling convention
 * GCC and Clang warn about for 32-byte vectors never applies: the pragma
 * silences the warning on returned vectors, and vector arguments go by
 * pointer, because GCC's note on those ignores the pragma. */
#if defined(__clang__)
#pragma clang diagnostic ignored "-Wpsabi"
#elif defined(__GNUC__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif
typedef uint64_t hylo_v4u __attribute__((vector_size(32)));

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(HYLO_NO_CLONES)
#define HYLO_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define HYLO_CLONES
#endif

static inline hylo_v4 load4(const double *p)
{
	hylo_v4 v;

	memcpy(&v, p, sizeof v);
	return v;
}

static inline void store4(double *p, const hylo_v4 *v)
{
	memcpy(p, v, sizeof *v);
}

static inline hylo_v4 splat4(double x)
{
	hylo_v4 v = { x, x, x, x };

	return v;
}

/* 2^(j/64), j = 0 .. 63, correctly rounded. */
static const double exp2_64[64] = {
	0x1.0000000000000p+0, 0x1.02c9a3e778061p+0, 0x1.059b0d3158574p+0, 0x1.0874518759bc8p+0,
	0x1.0b5586cf9890fp+0, 0x1.0e3ec32d3d1a2p+0, 0x1.11301d0125b51p+0, 0x1.1429aaea92de0p+0,
	0x1.172b83c7d517bp+0, 0x1.1a35beb6fcb75p+0, 0x1.1d4873168b9aap+0, 0x1.2063b88628cd6p+0,
	0x1.2387a6e756238p+0, 0x1.26b4565e27cddp+0, 0x1.29e9df51fdee1p+0, 0x1.2d285a6e4030bp+0,
	0x1.306fe0a31b715p+0, 0x1.33c08b26416ffp+0, 0x1.371a7373aa9cbp+0, 0x1.3a7db34e59ff7p+0,
	0x1.3dea64c123422p+0, 0x1.4160a21f72e2ap+0, 0x1.44e086061892dp+0, 0x1.486a2b5c13cd0p+0,
	0x1.4bfdad5362a27p+0, 0x1.4f9b2769d2ca7p+0, 0x1.5342b569d4f82p+0, 0x1.56f4736b527dap+0,
	0x1.5ab07dd485429p+0, 0x1.5e76f15ad2148p+0, 0x1.6247eb03a5585p+0, 0x1.6623882552225p+0,
	0x1.6a09e667f3bcdp+0, 0x1.6dfb23c651a2fp+0, 0x1.71f75e8ec5f74p+0, 0x1.75feb564267c9p+0,
	0x1.7a11473eb0187p+0, 0x1.7e2f336cf4e62p+0, 0x1.82589994cce13p+0, 0x1.868d99b4492edp+0,
	0x1.8ace5422aa0dbp+0, 0x1.8f1ae99157736p+0, 0x1.93737b0cdc5e5p+0, 0x1.97d829fde4e50p+0,
	0x1.9c49182a3f090p+0, 0x1.a0c667b5de565p+0, 0x1.a5503b23e255dp+0, 0x1.a9e6b5579fdbfp+0,
	0x1.ae89f995ad3adp+0, 0x1.b33a2b84f15fbp+0, 0x1.b7f76f2fb5e47p+0, 0x1.bcc1e904bc1d2p+0,
	0x1.c199bdd85529cp+0, 0x1.c67f12e57d14bp+0, 0x1.cb720dcef9069p+0, 0x1.d072d4a07897cp+0,
	0x1.d5818dcfba487p+0, 0x1.da9e603db3285p+0, 0x1.dfc97337b9b5fp+0, 0x1.e502ee78b3ff6p+0,
	0x1.ea4afa2a490dap+0, 0x1.efa1bee615a27p+0, 0x1.f50765b6e4540p+0, 0x1.fa7c1819e90d8p+0
};

/*
 * exp(x) for x <= 0, to about 3e-16 relative (within two ulp of libm's):
 * x = (64 k + j) ln2/64 + r with |r| <= ln2/128, exp(r) by its degree-5
 * Taylor polynomial (truncation below 4e-17), times 2^(j/64) from a table,
 * times 2^k put into the exponent bits. Below -700 the result is 0 (libm's
 * is < 1e-304, and it only ever multiplies a support vector's coefficient).
 */
static inline hylo_v4 exp_nonpositive4(const hylo_v4 *arg)
{
	const double ln2_64_hi = 0x1.62e42fef00000p-7, ln2_64_lo = 0x1.473de6af278edp-40;
	const hylo_v4 shift = splat4(0x1.8p52), lowest = splat4(-700.0);
	hylo_v4u keep, xb, lb, tb, jb, pb;
	hylo_v4 x = *arg, t, n, r, r2, p, tab;

	keep = (hylo_v4u)(x >= lowest);
	memcpy(&xb, &x, sizeof xb);
	memcpy(&lb, &lowest, sizeof lb);
	xb = (xb & keep) | (lb & ~keep);
	memcpy(&x, &xb, sizeof x);
	t = x * 0x1.71547652b82fep+6 + shift;  /* round(64 x / ln2) in the low mantissa bits */
	n = t - shift;
	r = (x - n * ln2_64_hi) - n * ln2_64_lo;
	r2 = r * r;
	p = (1.0 + r) + r2 * ((0.5 + r * (1.0 / 6)) + r2 * (1.0 / 24 + r * (1.0 / 120)));
	memcpy(&tb, &t, sizeof tb);
	jb = tb & 63;
	tab[0] = exp2_64[jb[0]];
	tab[1] = exp2_64[jb[1]];
	tab[2] = exp2_64[jb[2]];
	tab[3] = exp2_64[jb[3]];
	p = p * tab;
	memcpy(&pb, &p, sizeof pb);
	/* (tb >> 6) << 52: floor(n / 64) in the exponent field (mod 2^12). */
	pb = (pb + ((tb >> 6) << 52)) & keep;
	memcpy(&p, &pb, sizeof p);
	return p;
}

static int turn_cells(const hylo_svr_model *m);

static int finite_array(const double *a, uint32_t n)
{
	uint32_t i;

	for (i = 0; i < n; i++)
		if (!isfinite(a[i]))
			return 0;
	return 1;
}

/* e is m's envelope, or its turn table (turn: its cells are turns). */
static hylo_status check_envelope(const hylo_svr_model *m, const hylo_svr_envelope *e, int turn,
				  const char *name, hylo_reason *r)
{
	const hylo_feature_layout *l = hylo_feature_layout_of_count(m->n_features);
	uint64_t n;
	uint32_t i;

	if (!l || !l->envelope)
		return hylo_fail(r, HYLO_E_BAD_VALUE,
				 "svr model %s: an envelope needs planar (%d) or flight (%d) features, "
				 "not %u", name,
				 hylo_feature_layout_of(HYLO_LAYOUT_PLANAR)->n_features,
				 hylo_feature_layout_of(HYLO_LAYOUT_SPATIAL)->n_features,
				 (unsigned)m->n_features);
	if (e->n_d == 0 || e->n_z == 0 || e->n_v == 0)
		return hylo_fail(r, HYLO_E_BAD_VALUE,
				 "svr model %s: envelope of %u x %u x %u cells (each >= 1)", name,
				 (unsigned)e->n_d, (unsigned)e->n_z, (unsigned)e->n_v);
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
	if (turn && e->n_z > 1 &&
	    !(e->z_min == 0 && fabs(e->n_z * e->z_step - TWO_PI) <= 1e-12 * TWO_PI))
		return hylo_fail(r, HYLO_E_BAD_VALUE,
				 "svr model %s: an envelope's %u turn cells of %g rad from %g "
				 "must cover [0, 2 pi] (or one cell, the turn ignored)", name,
				 (unsigned)e->n_z, e->z_step, e->z_min);
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

/* A turn table: a flight model's, with an envelope of the same distance
 * cells and speed nodes, turn cells over [0, 2 pi]. */
static hylo_status check_turn_envelope(const hylo_svr_model *m, const char *name, hylo_reason *r)
{
	const hylo_svr_envelope *e = m->turn_envelope, *c = m->envelope;
	const hylo_feature_layout *l = hylo_feature_layout_of_count(m->n_features);
	hylo_status st;

	if (!l || l->kind != HYLO_LAYOUT_SPATIAL || !c)
		return hylo_fail(r, HYLO_E_BAD_VALUE,
				 "svr model %s: a turn table needs flight features (%d) and an envelope",
				 name, hylo_feature_layout_of(HYLO_LAYOUT_SPATIAL)->n_features);
	if ((st = check_envelope(m, e, 1, name, r)) != HYLO_OK)
		return st;
	if (e->n_d != c->n_d || e->d_step != c->d_step || e->n_v != c->n_v ||
	    e->v_min != c->v_min || e->v_step != c->v_step)
		return hylo_fail(r, HYLO_E_BAD_VALUE,
				 "svr model %s: the turn table's distance cells and speed nodes must "
				 "be the envelope's", name);
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
	if (m->state_bounded >> HYLO_XS_DIM)
		return hylo_fail(r, HYLO_E_BAD_VALUE,
				 "svr model %s: state_bounded 0x%x names a coordinate beyond %d", name,
				 (unsigned)m->state_bounded, HYLO_XS_DIM);
	for (k = 0; k < HYLO_XS_DIM; k++)
		if ((m->state_bounded >> k & 1u) &&
		    !(isfinite(m->state_min[k]) && isfinite(m->state_max[k]) &&
		      m->state_min[k] <= m->state_max[k]))
			return hylo_fail(r, HYLO_E_BAD_VALUE,
					 "svr model %s: trained range [%g, %g] of coordinate %u is not an interval",
					 name, m->state_min[k], m->state_max[k], (unsigned)k);
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
	if (m->envelope && (st = check_envelope(m, m->envelope, turn_cells(m), name, r)) != HYLO_OK)
		return st;
	if (m->turn_envelope && (st = check_turn_envelope(m, name, r)) != HYLO_OK)
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

int hylo_svr_envelope_speed(const hylo_svr_model *m, double v, uint32_t nodes[2])
{
	return m && m->envelope && m->envelope->value && envelope_nodes(m->envelope, v, nodes);
}

/* 1 when m's envelope's z cells are turns (its features' layout says). */
static int turn_cells(const hylo_svr_model *m)
{
	const hylo_feature_layout *l = hylo_feature_layout_of_count(m->n_features);

	return l && l->envelope_turn;
}

/* The cell of table e (turn: its z cells are turns, the last closed). */
static int table_cell(const hylo_svr_envelope *e, int turn, double d, double dz, size_t *cell)
{
	uint32_t k, j = 0;
	double x;

	if (!e || !e->value)
		return 0;
	x = d / e->d_step;
	if (!(x >= 0 && x < (double)e->n_d))
		return 0;
	k = (uint32_t)x;
	if (e->n_z > 1) {
		x = (dz - e->z_min) / e->z_step;
		/* A planar turn of 2 pi (the goal straight behind with the same
		 * heading) lies in the last turn cell. */
		if (x == (double)e->n_z && turn)
			x = e->n_z - 1;
		if (!(x >= 0 && x < (double)e->n_z))
			return 0;
		j = (uint32_t)x;
	}
	*cell = ((size_t)k * e->n_z + j) * e->n_v * e->n_v;
	return 1;
}

int hylo_svr_envelope_cell(const hylo_svr_model *m, double d, double dz, size_t *cell)
{
	return m && table_cell(m->envelope, turn_cells(m), d, dz, cell);
}

static double table_value(const hylo_svr_envelope *e, size_t cell, const uint32_t tail[2],
			  const uint32_t head[2])
{
	const float *v = &e->value[cell];
	uint32_t n = e->n_v;
	double best = v[tail[0] * n + head[0]], x;

	if ((x = v[tail[0] * n + head[1]]) < best)
		best = x;
	if ((x = v[tail[1] * n + head[0]]) < best)
		best = x;
	if ((x = v[tail[1] * n + head[1]]) < best)
		best = x;
	return best;
}

double hylo_svr_envelope_value(const hylo_svr_model *m, size_t cell, const uint32_t tail[2],
			       const uint32_t head[2])
{
	return table_value(m->envelope, cell, tail, head);
}

int hylo_svr_turn_envelope_cell(const hylo_svr_model *m, double d, double dz, double turn,
				size_t *cell)
{
	double r = m ? m->max_distance_m : 0;

	if (!m || !m->turn_envelope || !(d * d + dz * dz <= r * r))
		return 0;
	return table_cell(m->turn_envelope, 1, d, turn, cell);
}

double hylo_svr_turn_envelope_value(const hylo_svr_model *m, size_t cell, const uint32_t tail[2],
				    const uint32_t head[2])
{
	return table_value(m->turn_envelope, cell, tail, head);
}

double hylo_svr_turn_envelope_bound(const hylo_svr_model *m, double d, double dz, double turn,
				    double v1, double v2)
{
	uint32_t a[2], b[2];
	size_t cell;

	if (!hylo_svr_turn_envelope_cell(m, d, dz, turn, &cell) ||
	    !envelope_nodes(m->turn_envelope, v1, a) || !envelope_nodes(m->turn_envelope, v2, b))
		return 0;
	return hylo_svr_turn_envelope_value(m, cell, a, b);
}

double hylo_svr_envelope_bound(const hylo_svr_model *m, double d, double dz, double v1, double v2)
{
	uint32_t a[2], b[2];
	size_t cell;

	if (!hylo_svr_envelope_cell(m, d, dz, &cell) || !hylo_svr_envelope_speed(m, v1, a) ||
	    !hylo_svr_envelope_speed(m, v2, b))
		return 0;
	return hylo_svr_envelope_value(m, cell, a, b);
}

double hylo_svr_predict(const hylo_svr_model *m, const double *x)
{
	double z[HYLO_MAX_FEATURES];

	standardize(m, x, z);
	return label_of(m, hylo_svr_decision(m, z));
}

/* Feature groups of a model with nf features: its layout's (hylo/modes.h),
 * or one group per feature when no layout has nf features. */
static uint32_t group_count(uint32_t nf)
{
	const hylo_feature_layout *l = hylo_feature_layout_of_count(nf);

	return l ? l->n_groups : nf;
}

/* Doubles per support vector: factor rows, the SV's features, running products. */
static size_t doubles_per_sv(uint32_t nf)
{
	return (size_t)group_count(nf) * HYLO_SVR_CACHE_VALUES + nf + group_count(nf);
}

size_t hylo_svr_cache_size(const hylo_svr_model *m)
{
	if (!m || m->n_features == 0 || m->n_features > HYLO_MAX_FEATURES)
		return 0;
	return doubles_per_sv(m->n_features) * m->n_sv * sizeof(double);
}

void hylo_svr_cache_attach(hylo_svr_cache *c, double *mem, size_t bytes)
{
	if (!c)
		return;
	c->mem = mem;
	c->mem_doubles = mem ? bytes / sizeof(double) : 0;
	hylo_svr_cache_reset(c);
}

void hylo_svr_cache_reset(hylo_svr_cache *c)
{
	uint32_t k;

	if (!c)
		return;
	c->model = NULL;
	c->factor = c->sv_col = c->prefix = NULL;
	c->n_groups = 0;
	c->clock = 0;
	c->hits = c->misses = 0;
	c->n_prefix = 0;
	for (k = 0; k < HYLO_MAX_FEATURES; k++)
		c->n_used[k] = 0;
}

/* The groups of svr.h for nf features: those of the feature layout with nf
 * features (hylo/modes.h); any other count: one group per feature. */
static void feature_groups(hylo_svr_cache *c, uint32_t nf)
{
	const hylo_feature_layout *l = hylo_feature_layout_of_count(nf);
	uint32_t k;

	for (k = 0; k < nf; k++)
		c->order[k] = l ? l->order[k] : k;
	c->n_groups = group_count(nf);
	for (k = 0; k <= c->n_groups; k++)
		c->group_begin[k] = l ? l->begin[k] : k;
}

/* row[i] = exp(-gamma |v - s_i|^2) over the w features order[b .. b + w) of
 * every support vector i < n, four at a time (a short last block repeats
 * the last SV). */
HYLO_CLONES
static void kernel_row(double *row, const hylo_svr_cache *c, uint32_t b, uint32_t w,
		       const double *v, double gamma, uint32_t n)
{
	uint32_t i, k, l;

	for (i = 0; i + 4 <= n; i += 4) {
		hylo_v4 d2 = splat4(0), e;

		for (k = 0; k < w; k++) {
			hylo_v4 d = splat4(v[k]) - load4(&c->sv_col[(size_t)c->order[b + k] * n + i]);

			d2 += d * d;
		}
		e = -gamma * d2;
		e = exp_nonpositive4(&e);
		store4(&row[i], &e);
	}
	if (i < n) {
		hylo_v4 d2 = splat4(0), e;

		for (k = 0; k < w; k++) {
			const double *col = &c->sv_col[(size_t)c->order[b + k] * n];
			hylo_v4 d;

			for (l = 0; l < 4; l++)
				d[l] = v[k] - col[i + l < n ? i + l : n - 1];
			d2 += d * d;
		}
		e = -gamma * d2;
		e = exp_nonpositive4(&e);
		for (l = 0; i + l < n; l++)
			row[i + l] = e[l];
	}
}

/* The factor row exp(-gamma |z_G - s_G|^2) of group g at the standardized
 * values v[] (its features in order), computing it into the least recently
 * used slot when v is not cached. */
static const double *factor_row(const hylo_svr_model *m, hylo_svr_cache *c, uint32_t g,
				const double *v)
{
	uint32_t b = c->group_begin[g], w = c->group_begin[g + 1] - b, j, k, slot = 0;
	double *row;

	for (j = 0; j < c->n_used[g]; j++) {
		for (k = 0; k < w && c->value[g][j][k] == v[k]; k++)
			;
		if (k == w) {
			c->last_use[g][j] = ++c->clock;
			c->hits++;
			return &c->factor[((size_t)g * HYLO_SVR_CACHE_VALUES + j) * m->n_sv];
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
	row = &c->factor[((size_t)g * HYLO_SVR_CACHE_VALUES + slot) * m->n_sv];
	kernel_row(row, c, b, w, v, m->gamma, m->n_sv);
	return row;
}

/* sum_i a[i] * b[i] with four partial sums in a fixed pattern (lane l
 * takes the i = l mod 4): a quarter of the dependent-add latency of one
 * running sum, and the same bits every time. */
HYLO_CLONES
static double dot(const double *a, const double *b, uint32_t n)
{
	hylo_v4 acc = splat4(0);
	double s[4];
	uint32_t i;

	for (i = 0; i + 4 <= n; i += 4)
		acc += load4(&a[i]) * load4(&b[i]);
	store4(s, &acc);
	for (; i < n; i++)
		s[0] += a[i] * b[i];
	return (s[0] + s[1]) + (s[2] + s[3]);
}

/* out[i] = a[i] * b[i], i < n. */
HYLO_CLONES
static void multiply(double *out, const double *a, const double *b, uint32_t n)
{
	uint32_t i;

	for (i = 0; i + 4 <= n; i += 4) {
		hylo_v4 p = load4(&a[i]) * load4(&b[i]);

		store4(&out[i], &p);
	}
	for (; i < n; i++)
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
		multiply(&c->prefix[(size_t)level * n], level == 0 ? m->coef : &c->prefix[(size_t)(level - 1) * n],
			 row, n);
		for (k = c->group_begin[level]; k < c->group_begin[level + 1]; k++)
			c->prefix_value[k] = v[k];
	}
	c->n_prefix = ng - 1;
	row = factor_row(m, c, ng - 1, &v[c->group_begin[ng - 1]]);
	return dot(ng == 1 ? m->coef : &c->prefix[(size_t)(ng - 2) * n], row, n) - m->rho;
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
		size_t ng = group_count(m->n_features);

		if (hylo_svr_cache_size(m) > c->mem_doubles * sizeof(double))
			return HYLO_E_CAP_SV;
		hylo_svr_cache_reset(c);
		c->model = m;
		c->factor = c->mem;
		c->sv_col = c->factor + ng * HYLO_SVR_CACHE_VALUES * m->n_sv;
		c->prefix = c->sv_col + (size_t)m->n_features * m->n_sv;
		feature_groups(c, m->n_features);
		for (k = 0; k < m->n_features; k++)
			for (i = 0; i < m->n_sv; i++)
				c->sv_col[(size_t)k * m->n_sv + i] = m->sv[(size_t)i * m->n_features + k];
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
