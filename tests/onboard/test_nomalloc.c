/*
 * The planning core never allocates: the allocator is wrapped at link time
 * (-Wl,--wrap=malloc,...; see mk/onboard.mk) and every call made while the
 * planner runs is counted. The test itself allocates only while disarmed.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdlib.h>

#include "onboard/testutil_planner.h"

void *__real_malloc(size_t n);
void *__real_calloc(size_t n, size_t size);
void *__real_realloc(void *p, size_t n);
void __real_free(void *p);

static int armed;
static long calls;

void *__wrap_malloc(size_t n)
{
	calls += armed;
	return __real_malloc(n);
}

void *__wrap_calloc(size_t n, size_t size)
{
	calls += armed;
	return __real_calloc(n, size);
}

void *__wrap_realloc(void *p, size_t n)
{
	calls += armed;
	return __real_realloc(p, n);
}

void __wrap_free(void *p)
{
	calls += armed;
	__real_free(p);
}

/* A small SVR model, so that the built-in SVR path runs too. */
#define NSV 24
static double sv[NSV * HYLO_FEATURES_PLANAR], coef[NSV];
static const double offset[HYLO_FEATURES_PLANAR] = { 0, 0, 0, 0.5, 0.5, 2, 2, 1.5 };
static const double scale[HYLO_FEATURES_PLANAR] = { 3, 3, 2, 0.5, 0.5, 3, 2, 1 };
static hylo_svr_model model = {
	.name = "test_ground", .n_sv = NSV, .n_features = HYLO_FEATURES_PLANAR,
	.gamma = 0.5, .rho = -20.0, .sv = sv, .coef = coef,
	.feature_offset = offset, .feature_scale = scale,
	.label_offset = 0.0, .label_scale = 1.0, .label_log = 0,
	.cost_floor_per_m = 3.0, .max_distance_m = 0.0, .provenance = "test",
};

/* The control: the wrapper does see calls made from linked objects. */
static void test_wrap_works(void **state)
{
	/* Through volatile pointers, so that the compiler cannot elide the pair. */
	void *(*volatile alloc)(size_t) = malloc;
	void (*volatile release)(void *) = free;
	void *p;

	(void)state;
	calls = 0;
	armed = 1;
	p = alloc(16);
	release(p);
	armed = 0;
	assert_int_equal(calls, 2);
}

static void run_scenes(hylo_planner *pl, hylo_plan *plan, tu_map *maps, hylo_goal *goals, int n_maps)
{
	hylo_goal bad;
	hylo_map_view v;
	int k, alg;

	for (k = 0; k < n_maps; k++) {
		v = tu_view(&maps[k]);
		assert_int_equal(hylo_planner_set_map(pl, &v), HYLO_OK);
		for (alg = 0; alg < 2; alg++) {
			goals[k].algorithm = alg;
			assert_int_equal(hylo_planner_plan(pl, &goals[k], plan), HYLO_OK);
			assert_int_equal(plan->outcome, HYLO_FOUND);
		}
		/* Failures format reasons: no allocation there either. */
		bad = goals[k];
		bad.start[0] = NAN;
		assert_int_equal(hylo_planner_plan(pl, &bad, plan), HYLO_E_BAD_VALUE);
		bad = goals[k];
		bad.map_id = 77;
		assert_int_equal(hylo_planner_plan(pl, &bad, plan), HYLO_E_MAP_MISMATCH);
	}
	v = tu_view(&maps[0]);
	v.robot = "nobody";
	assert_int_equal(hylo_planner_set_map(pl, &v), HYLO_E_UNKNOWN_ROBOT);
}

static void test_planner_never_allocates(void **state)
{
	hylo_planner *pl = malloc(TU_PLANNER_BYTES);
	hylo_plan *plan = malloc(sizeof *plan);
	hylo_robot robots[TU_N_ROBOTS];
	hylo_planner_config cfg;
	tu_cost costs;
	tu_map maps[TU_N_SCENES];
	hylo_goal goals[TU_N_SCENES];
	int k;

	(void)state;
	assert_non_null(pl);
	assert_non_null(plan);
	for (k = 0; k < NSV * HYLO_FEATURES_PLANAR; k++)
		sv[k] = ((k * 7919) % 200) / 100.0 - 1.0;
	for (k = 0; k < NSV; k++)
		coef[k] = 0.5 + 0.1 * (k % 5);
	tu_robots(robots, &costs);
	robots[0].modes[0].model = &model;   /* ambot drives on the SVR */
	tu_scenes(maps, goals);
	cfg = tu_config(robots, TU_N_ROBOTS);

	calls = 0;
	armed = 1;
	assert_int_equal(hylo_planner_init(pl, TU_PLANNER_BYTES, &cfg), HYLO_OK);
	run_scenes(pl, plan, maps, goals, TU_N_SCENES);
	armed = 0;
	assert_int_equal(calls, 0);
	for (k = 0; k < TU_N_SCENES; k++)
		tu_map_free(&maps[k]);
	free(plan);
	free(pl);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_wrap_works),
		cmocka_unit_test(test_planner_never_allocates),
	};

	return cmocka_run_group_tests_name("nomalloc", tests, NULL, NULL);
}
