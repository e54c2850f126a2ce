/*
 * The exported-header path end to end: a model trained by libsvm in
 * make_test_model.cpp, exported by trainer/svr_export.cpp, compiled here.
 * The onboard evaluator must reproduce libsvm's svm_predict (cost) and
 * svm_predict_values (feasibility) to 1e-9 relative on held-out points, one
 * at a time and in batches, and the header must carry its size macros. The
 * exported envelope (trainer/envelope.cpp) bounds the model's cost from
 * below on random edges.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "hylo/envelope.h"
#include "hylo/features.h"
#include "testbot_ground.h"

#define N_MAX 512

static double x[N_MAX][HYLO_FEATURES_PLANAR], want_cost[N_MAX], want_feas[N_MAX];
static int n;
static hylo_svr_cache cache;
static double cache_mem[1 << 18];

static void load(void)
{
	FILE *f = fopen(REFERENCE_TXT, "r");
	int k;

	assert_non_null(f);
	for (n = 0; n < N_MAX; n++) {
		for (k = 0; k < HYLO_FEATURES_PLANAR; k++)
			if (fscanf(f, "%lf", &x[n][k]) != 1)
				goto done;
		if (fscanf(f, "%lf %lf", &want_cost[n], &want_feas[n]) != 2)
			break;
	}
done:
	fclose(f);
	assert_true(n >= 100);
}

static void assert_close(double got, double want)
{
	if (!(fabs(got - want) <= 1e-9 * fmax(fabs(want), 1e-300)))
		fail_msg("%.17g vs libsvm %.17g", got, want);
}

static void test_header_shape(void **state)
{
	(void)state;
	assert_int_equal(HYLO_MODEL_TESTBOT_GROUND_N_FEATURES, HYLO_FEATURES_PLANAR);
	assert_int_equal(HYLO_MODEL_TESTBOT_GROUND_MODE, HYLO_MODE_GROUND);
	assert_int_equal(hylo_model_testbot_ground.n_sv, HYLO_MODEL_TESTBOT_GROUND_N_SV);
	assert_true(HYLO_MODEL_TESTBOT_GROUND_N_SV > 10);
	assert_int_equal(hylo_model_testbot_ground_feasibility.n_sv,
			 HYLO_MODEL_TESTBOT_GROUND_FEASIBILITY_N_SV);
	assert_int_equal(hylo_svr_check(&hylo_model_testbot_ground, NULL), HYLO_OK);
	assert_int_equal(hylo_svr_check(&hylo_model_testbot_ground_feasibility, NULL), HYLO_OK);
	assert_string_equal(hylo_model_testbot_ground.name, "testbot_ground");
}

static void test_cost_matches_libsvm(void **state)
{
	double got[N_MAX];
	int i;

	(void)state;
	load();
	for (i = 0; i < n; i++)
		assert_close(hylo_svr_predict(&hylo_model_testbot_ground, x[i]), want_cost[i]);
	hylo_svr_cache_reset(&cache);
	assert_int_equal(hylo_svr_predict_batch(&hylo_model_testbot_ground, &cache, &x[0][0],
						(uint32_t)n, got), HYLO_OK);
	for (i = 0; i < n; i++)
		assert_close(got[i], want_cost[i]);
}

static void test_feasibility_matches_libsvm(void **state)
{
	double got[N_MAX];
	int i, agree = 0;

	(void)state;
	load();
	assert_int_equal(hylo_svr_predict_batch(&hylo_model_testbot_ground_feasibility, &cache,
						&x[0][0], (uint32_t)n, got), HYLO_OK);
	for (i = 0; i < n; i++) {
		assert_close(got[i], want_feas[i]);
		assert_close(hylo_svr_predict(&hylo_model_testbot_ground_feasibility, x[i]),
			     want_feas[i]);
		agree += (got[i] >= 0) == (want_feas[i] >= 0);
	}
	assert_int_equal(agree, n);
}

/* 20,000 random edges with speeds on the envelope's nodes cost no less than
 * its bound, which exists for each of them. */
static void test_envelope_bounds_cost(void **state)
{
	const hylo_svr_model *m = &hylo_model_testbot_ground;
	const hylo_svr_envelope *e = m->envelope;
	uint64_t s = 99;
	int i, below = 0, none = 0;

	(void)state;
	assert_non_null(e);
	assert_int_equal(e->n_d, HYLO_MODEL_TESTBOT_GROUND_ENVELOPE_N_D);
	assert_int_equal(e->n_v, HYLO_MODEL_TESTBOT_GROUND_ENVELOPE_N_V);
	for (i = 0; i < 20000; i++) {
		double u[6], tail[4], head[4], f[HYLO_FEATURES_PLANAR], bound;
		int k;

		for (k = 0; k < 6; k++) {
			s = s * 6364136223846793005ULL + 1442695040888963407ULL;
			u[k] = (double)(s >> 11) * 0x1.0p-53;
		}
		tail[0] = 1, tail[1] = -2, tail[2] = e->v_min + (int)(u[0] * e->n_v) * e->v_step;
		tail[3] = 6.28 * u[1];
		head[0] = 1 + m->max_distance_m * u[2] * cos(6.28 * u[3]);
		head[1] = -2 + m->max_distance_m * u[2] * sin(6.28 * u[3]);
		head[2] = e->v_min + (int)(u[4] * e->n_v) * e->v_step;
		head[3] = 6.28 * u[5];
		hylo_features(HYLO_MODE_GROUND, tail, head, f);
		bound = hylo_envelope_of_edge(m, HYLO_MODE_GROUND, tail, head);
		below += hylo_svr_predict(m, f) < bound;
		none += bound == 0;
	}
	assert_int_equal(below, 0);
	assert_int_equal(none, 0);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_header_shape),
		cmocka_unit_test(test_cost_matches_libsvm),
		cmocka_unit_test(test_feasibility_matches_libsvm),
		cmocka_unit_test(test_envelope_bounds_cost),
	};

	if (hylo_svr_cache_size(&hylo_model_testbot_ground) > sizeof cache_mem ||
	    hylo_svr_cache_size(&hylo_model_testbot_ground_feasibility) > sizeof cache_mem) {
		fprintf(stderr, "test_export: the test models outgrew the cache memory\n");
		return 1;
	}
	hylo_svr_cache_attach(&cache, cache_mem, sizeof cache_mem);
	return cmocka_run_group_tests_name("export", tests, NULL, NULL);
}
