/* The trained region (hylo/region.h): states, edges, the displacement, the
 * rounding slack, the texts; and hylo_svr_check on bad region fields. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>
#include <cmocka.h>

#include "hylo/region.h"

static const double zeros[9] = { 0 };
static const double ones[9] = { 1, 1, 1, 1, 1, 1, 1, 1, 1 };

static hylo_svr_model flight_model(void)
{
	hylo_svr_model m = {
		.name = "flight", .n_features = 9, .gamma = 1, .feature_offset = zeros,
		.feature_scale = ones, .label_scale = 1, .max_distance_m = 9,
		.speed_min_mps = 0, .speed_max_mps = 8,
		.state_bounded = 7u << 3,
		.state_min = { 0, 0, 0, -8, -8, 0 },
		.state_max = { 0, 0, 0, 8, 8, 0 },
	};
	return m;
}

static void test_state(void **state)
{
	hylo_svr_model m = flight_model();
	hylo_real x[HYLO_XS_DIM] = { 100, -50, 30, 3, -4, 0 };
	hylo_region_miss miss;

	(void)state;
	assert_true(hylo_region_state(&m, HYLO_MODE_FLIGHT, x, &miss));   /* positions are free */
	assert_int_equal(miss.part, HYLO_REGION_INSIDE);
	x[5] = 1e-10;   /* rounding */
	assert_true(hylo_region_state(&m, HYLO_MODE_FLIGHT, x, NULL));
	x[5] = -2.7;
	assert_false(hylo_region_state(&m, HYLO_MODE_FLIGHT, x, &miss));
	assert_int_equal(miss.part, HYLO_REGION_COORD);
	assert_int_equal(miss.coord, 5);
	assert_true(miss.value == -2.7 && miss.lo == 0 && miss.hi == 0);
	x[5] = NAN;
	assert_false(hylo_region_state(&m, HYLO_MODE_FLIGHT, x, &miss));
	x[5] = 0;
	x[3] = 7;   /* each component within [-8, 8], |v| above 8: the speed */
	assert_false(hylo_region_state(&m, HYLO_MODE_FLIGHT, x, &miss));
	assert_int_equal(miss.part, HYLO_REGION_SPEED);
	m.state_bounded = 0;   /* no bounds: the speed range alone */
	x[3] = 3;
	x[5] = -2.7;
	assert_true(hylo_region_state(&m, HYLO_MODE_FLIGHT, x, NULL));
}

static void test_edge(void **state)
{
	hylo_svr_model m = flight_model();
	hylo_real a[HYLO_XS_DIM] = { 0, 0, 0, 0, 0, 0 }, b[HYLO_XS_DIM] = { 3, 4, 0, 0, 0, 0 };
	hylo_region_miss miss;

	(void)state;
	assert_true(hylo_edge_distance(HYLO_MODE_FLIGHT, a, b) == 5);
	b[2] = 12;
	assert_true(hylo_edge_distance(HYLO_MODE_FLIGHT, a, b) == 13);
	assert_true(hylo_edge_distance(HYLO_MODE_GROUND, a, b) == 5);   /* horizontal */
	assert_false(hylo_region_edge(&m, HYLO_MODE_FLIGHT, a, b, &miss));
	assert_int_equal(miss.part, HYLO_REGION_DISTANCE);
	assert_true(miss.value == 13 && miss.hi == 9);
	b[2] = 0;
	assert_true(hylo_region_edge(&m, HYLO_MODE_FLIGHT, a, b, &miss));
	b[5] = 0.5;
	assert_false(hylo_region_edge(&m, HYLO_MODE_FLIGHT, a, b, &miss));
	assert_int_equal(miss.end, 1);
	assert_int_equal(miss.coord, 5);
	a[5] = -1;
	assert_false(hylo_region_edge(&m, HYLO_MODE_FLIGHT, a, b, &miss));
	assert_int_equal(miss.end, 0);
	m.max_distance_m = 0;   /* any displacement */
	a[5] = b[5] = 0;
	b[0] = 1000;
	assert_true(hylo_region_edge(&m, HYLO_MODE_FLIGHT, a, b, NULL));
}

static void test_texts(void **state)
{
	hylo_region_miss miss = { HYLO_REGION_COORD, 0, 5, -2.7, 0, 0 };
	char buf[200];

	(void)state;
	hylo_region_describe(HYLO_MODE_FLIGHT, &miss, buf, sizeof buf);
	assert_string_equal(buf, "vz = -2.7 m/s is outside the training range [0, 0] m/s");
	miss.part = HYLO_REGION_SPEED;
	miss.value = 12;
	miss.hi = 8;
	hylo_region_describe(HYLO_MODE_FLIGHT, &miss, buf, sizeof buf);
	assert_string_equal(buf, "speed 12 m/s is outside the training range [0, 8] m/s");
	miss.part = HYLO_REGION_DISTANCE;
	miss.value = 13;
	miss.hi = 9;
	hylo_region_describe(HYLO_MODE_FLIGHT, &miss, buf, sizeof buf);
	assert_string_equal(buf, "displacement 13 m is beyond the training range 9 m");
	hylo_region_describe(HYLO_MODE_FLIGHT, &miss, buf, 8);   /* truncated, terminated */
	assert_int_equal(strlen(buf), 7);
	assert_string_equal(hylo_coord_name(HYLO_MODE_GROUND, 3), "theta");
	assert_string_equal(hylo_coord_unit(HYLO_MODE_GROUND, 3), "rad");
	assert_string_equal(hylo_coord_name(HYLO_MODE_DI_POS, 0), "p");
	assert_string_equal(hylo_coord_name(HYLO_MODE_GROUND, 4), "?");
	assert_string_equal(hylo_coord_name(HYLO_MODE_NONE, 0), "?");
}

static void test_check(void **state)
{
	hylo_svr_model m = flight_model();
	hylo_reason r;

	(void)state;
	assert_int_equal(hylo_svr_check(&m, &r), HYLO_OK);
	m.state_min[5] = 1;   /* min > max */
	assert_int_equal(hylo_svr_check(&m, &r), HYLO_E_BAD_VALUE);
	assert_non_null(strstr(r.text, "coordinate 5"));
	m = flight_model();
	m.state_max[4] = INFINITY;
	assert_int_equal(hylo_svr_check(&m, &r), HYLO_E_BAD_VALUE);
	m = flight_model();
	m.state_bounded |= 1u << 6;
	assert_int_equal(hylo_svr_check(&m, &r), HYLO_E_BAD_VALUE);
	assert_non_null(strstr(r.text, "state_bounded"));
	m = flight_model();
	m.state_bounded = 0;
	m.state_min[5] = 1;   /* unbounded coordinates' values are ignored */
	assert_int_equal(hylo_svr_check(&m, &r), HYLO_OK);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_state),
		cmocka_unit_test(test_edge),
		cmocka_unit_test(test_texts),
		cmocka_unit_test(test_check),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
