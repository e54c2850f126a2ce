/*
 * The batch evaluator (feature groups, cached factor rows and running
 * products, two-lane exponential) against the plain one-at-a-time sum
 * hylo_svr_decision, which follows svm_predict term by term (test_export
 * checks that one against libsvm itself). Random models of every feature
 * count the groups treat differently (planar 8, flight 9, double integrator
 * 4, and others), odd and even support-vector counts, batches whose features
 * repeat the way a planner expansion's do, and kernels wide enough and narrow
 * enough to reach the exponential's underflow.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <string.h>

#include "hylo/svr.h"

#define MAX_SV_TEST 101
#define BATCH 96

static uint64_t rng_state;

static double uniform(double lo, double hi)
{
	rng_state = rng_state * 6364136223846793005ULL + 1442695040888963407ULL;
	return lo + (hi - lo) * (double)(rng_state >> 11) * 0x1.0p-53;
}

static double sv[MAX_SV_TEST * HYLO_MAX_FEATURES], coef[MAX_SV_TEST];
static double offset[HYLO_MAX_FEATURES], scale[HYLO_MAX_FEATURES];
static double x[BATCH][HYLO_MAX_FEATURES], flat[BATCH * HYLO_MAX_FEATURES], got[BATCH];
static hylo_svr_cache cache;
static double cache_mem[MAX_SV_TEST * HYLO_MAX_FEATURES * (HYLO_SVR_CACHE_VALUES + 2)];

static hylo_svr_model random_model(uint32_t n_sv, uint32_t nf, double gamma)
{
	hylo_svr_model m;
	uint32_t i, k;

	memset(&m, 0, sizeof m);
	for (i = 0; i < n_sv * nf; i++)
		sv[i] = uniform(-2, 2);
	for (i = 0; i < n_sv; i++)
		coef[i] = uniform(-3, 3);
	for (k = 0; k < nf; k++) {
		offset[k] = uniform(-1, 1);
		scale[k] = uniform(0.5, 2);
	}
	m.name = "random";
	m.n_sv = n_sv;
	m.n_features = nf;
	m.gamma = gamma;
	m.rho = uniform(-1, 1);
	m.sv = sv;
	m.coef = coef;
	m.feature_offset = offset;
	m.feature_scale = scale;
	m.label_scale = 1;
	return m;
}

/* A batch like a planner expansion: one tail, heads in runs that share all
 * but their last features, some values repeating across runs. */
static void planner_like_batch(uint32_t nf)
{
	uint32_t e, k;

	for (k = 0; k < nf; k++)
		x[0][k] = uniform(-4, 4);
	for (e = 1; e < BATCH; e++)
		for (k = 0; k < nf; k++) {
			int keep = (int)(e % 4) > (int)k % 3;  /* earlier features change less */

			x[e][k] = keep ? x[e - 1][k] : (e % 7 == 0 ? x[0][k] : uniform(-4, 4));
		}
}

/* The batch API reads rows of n_features: x's rows packed into flat. */
static void pack(uint32_t nf)
{
	uint32_t e, k;

	for (e = 0; e < BATCH; e++)
		for (k = 0; k < nf; k++)
			flat[e * nf + k] = x[e][k];
}

static void check_batch(const hylo_svr_model *m)
{
	uint32_t e;

	assert_int_equal(hylo_svr_check(m, NULL), HYLO_OK);
	assert_int_equal(hylo_svr_predict_batch(m, &cache, flat, BATCH, got), HYLO_OK);
	for (e = 0; e < BATCH; e++) {
		double want = hylo_svr_predict(m, &flat[e * m->n_features]), mag = fabs(m->rho);
		uint32_t i;

		for (i = 0; i < m->n_sv; i++)
			mag += fabs(m->coef[i]);
		if (!(fabs(got[e] - want) <= 1e-13 * mag))
			fail_msg("n_sv %u, %u features, gamma %g, edge %u: batch %.17g, one %.17g",
				 (unsigned)m->n_sv, (unsigned)m->n_features, m->gamma, (unsigned)e,
				 got[e], want);
	}
}

static void test_batch_matches_one_at_a_time(void **state)
{
	static const uint32_t counts[] = { 1, 2, 3, 4, 5, 7, 8, 9 };
	static const uint32_t svs[] = { 1, 2, 37, 100, 101 };
	static const double gammas[] = { 0.05, 0.7, 40.0 };
	uint32_t a, b, c;

	(void)state;
	rng_state = 20261123;
	for (a = 0; a < sizeof counts / sizeof counts[0]; a++)
		for (b = 0; b < sizeof svs / sizeof svs[0]; b++)
			for (c = 0; c < sizeof gammas / sizeof gammas[0]; c++) {
				hylo_svr_model m = random_model(svs[b], counts[a], gammas[c]);

				hylo_svr_cache_reset(&cache);
				planner_like_batch(counts[a]);
				pack(counts[a]);
				check_batch(&m);
				check_batch(&m);  /* again, now from a warm cache */
			}
}

/* One feature, one SV: the batch result is coef * exp(-gamma d^2) - rho, so
 * this checks the exponential itself against libm over its whole range,
 * down to the underflow cut-off. */
static void test_exponential_against_libm(void **state)
{
	static double one_sv[1] = { 0 }, one_coef[1] = { 1 }, zero[1] = { 0 }, unit[1] = { 1 };
	hylo_svr_model m;
	double xs[BATCH], y[BATCH];
	uint32_t e;

	(void)state;
	memset(&m, 0, sizeof m);
	m.name = "exp";
	m.n_sv = 1;
	m.n_features = 1;
	m.gamma = 1;
	m.sv = one_sv;
	m.coef = one_coef;
	m.feature_offset = zero;
	m.feature_scale = unit;
	m.label_scale = 1;
	for (e = 0; e < BATCH; e++)
		xs[e] = e == 0 ? 0 : sqrt(800.0 * e / (BATCH - 1)) * (e % 2 ? 1 : -1);
	hylo_svr_cache_reset(&cache);
	assert_int_equal(hylo_svr_predict_batch(&m, &cache, xs, BATCH, y), HYLO_OK);
	assert_true(y[0] == 1.0);
	for (e = 0; e < BATCH; e++) {
		double want = exp(-xs[e] * xs[e]);

		if (!(fabs(y[e] - want) <= 1e-15 * want || (want < 1e-300 && y[e] < 1e-300)))
			fail_msg("exp(%.17g): %.17g, libm %.17g", -xs[e] * xs[e], y[e], want);
	}
}

/* The training speed range: its bounds with rounding slack, NaN never
 * inside, "any" when both bounds are 0, and a bad range refused by check. */
static void test_speed_range(void **state)
{
	hylo_svr_model m = random_model(3, 9, 0.5);
	const hylo_real at_bound[6] = { 0, 0, 0, 8 * cos(0.3), 8 * sin(0.3), 0 };
	const hylo_real climbing[6] = { 0, 0, 0, 3, 0, 4 };
	const hylo_real backing[4] = { 0, 0, -0.5, 1 };
	const hylo_real di[2] = { 0.3, -0.7 };

	(void)state;
	assert_true(hylo_state_speed(HYLO_MODE_FLIGHT, climbing) == 5);
	assert_true(hylo_state_speed(HYLO_MODE_GROUND, backing) == -0.5);
	assert_true(hylo_state_speed(HYLO_MODE_MARINE, backing) == -0.5);
	assert_true(hylo_state_speed(HYLO_MODE_DI_NEG, di) == -0.7);
	m.speed_min_mps = 0;
	m.speed_max_mps = 8;
	assert_int_equal(hylo_svr_check(&m, NULL), HYLO_OK);
	assert_true(hylo_svr_speed_trained(&m, hylo_state_speed(HYLO_MODE_FLIGHT, at_bound)));
	assert_true(hylo_svr_speed_trained(&m, 0));
	assert_false(hylo_svr_speed_trained(&m, 8.001));
	assert_false(hylo_svr_speed_trained(&m, -0.001));
	assert_false(hylo_svr_speed_trained(&m, NAN));
	m.speed_max_mps = 0;   /* no range: any speed, but not NaN */
	assert_true(hylo_svr_speed_trained(&m, -100));
	assert_false(hylo_svr_speed_trained(&m, NAN));
	m.speed_min_mps = 2;
	m.speed_max_mps = 1;
	assert_int_equal(hylo_svr_check(&m, NULL), HYLO_E_BAD_VALUE);
	m.speed_max_mps = INFINITY;
	assert_int_equal(hylo_svr_check(&m, NULL), HYLO_E_BAD_VALUE);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_batch_matches_one_at_a_time),
		cmocka_unit_test(test_exponential_against_libm),
		cmocka_unit_test(test_speed_range),
	};

	hylo_svr_cache_attach(&cache, cache_mem, sizeof cache_mem);
	return cmocka_run_group_tests_name("svr", tests, NULL, NULL);
}
