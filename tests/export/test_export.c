/*
 * The exported-header path end to end: a model trained by libsvm in
 * make_test_model.cpp, exported by trainer/svr_export.cpp, compiled here.
 * The onboard evaluator must reproduce libsvm's svm_predict (cost) and
 * svm_predict_values (feasibility) to 1e-9 relative on held-out points, one
 * at a time and in batches, and the header must carry its size macros.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

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

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_header_shape),
		cmocka_unit_test(test_cost_matches_libsvm),
		cmocka_unit_test(test_feasibility_matches_libsvm),
	};

	if (hylo_svr_cache_size(&hylo_model_testbot_ground) > sizeof cache_mem ||
	    hylo_svr_cache_size(&hylo_model_testbot_ground_feasibility) > sizeof cache_mem) {
		fprintf(stderr, "test_export: the test models outgrew the cache memory\n");
		return 1;
	}
	hylo_svr_cache_attach(&cache, cache_mem, sizeof cache_mem);
	return cmocka_run_group_tests_name("export", tests, NULL, NULL);
}
