/*
 * The planner node's robot registry (onboard/node/registry.c) from tables
 * of its own: a model's takeoff and landing are the switches into and out
 * of its mode whichever of the robot's two modes comes first, and a model
 * that would give a robot a third mode fails naming the robot and the mode
 * (the registry kept two modes and dropped the third without a word).
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <string.h>

#include "node/registry.h"

/* hylo_registry_robots' own tables: none (these tests pass theirs). */
const hylo_registry_model hylo_registry_models[] = { { 0, 0, "", HYLO_MODE_NONE, -1, -1 } };
const uint32_t hylo_registry_n_models = 0;
const hylo_registry_body hylo_registry_bodies[] = { { "", 0 } };
const uint32_t hylo_registry_n_bodies = 0;

static const hylo_svr_model flight = { .name = "rotor_flight" }, ground = { .name = "rotor_ground" },
			    marine = { .name = "rotor_marine" };

static const hylo_robot *find(const hylo_robot *robots, uint32_t n, const char *name)
{
	uint32_t k;

	for (k = 0; k < n; k++)
		if (strcmp(robots[k].name, name) == 0)
			return &robots[k];
	return NULL;
}

static void test_switch_costs_by_mode(void **state)
{
	/* Flight listed first: modes[0] is flight, so modes[0] -> modes[1] is
	 * the landing. */
	static const hylo_registry_model models[] = {
		{ &flight, NULL, "rotor", HYLO_MODE_FLIGHT, 70, 20 },
		{ &ground, NULL, "rotor", HYLO_MODE_GROUND, -1, -1 },
	};
	static const hylo_registry_body bodies[] = { { "rotor", 0.4 } };
	hylo_robot robots[HYLO_MAX_ROBOTS];
	hylo_reason reason;
	const hylo_robot *r;
	uint32_t n;

	(void)state;
	n = hylo_registry_robots_of(models, 2, bodies, 1, robots, HYLO_MAX_ROBOTS, &reason);
	assert_true(n > 0);
	assert_non_null(r = find(robots, n, "rotor"));
	assert_int_equal(r->n_modes, 2);
	assert_int_equal(r->modes[0].mode, HYLO_MODE_FLIGHT);
	assert_int_equal(r->modes[1].mode, HYLO_MODE_GROUND);
	assert_true(r->switch_cost[0] == 20);   /* flight -> ground: landing */
	assert_true(r->switch_cost[1] == 70);   /* ground -> flight: takeoff */
	assert_true(r->body_radius_m == 0.4);
	/* The standard drivocopter (ground first) takes them the other way. */
	{
		static const hylo_registry_model std_models[] = {
			{ &flight, NULL, "drivocopter", HYLO_MODE_FLIGHT, 70, 20 },
		};

		n = hylo_registry_robots_of(std_models, 1, bodies, 1, robots, HYLO_MAX_ROBOTS, &reason);
		assert_non_null(r = find(robots, n, "drivocopter"));
		assert_int_equal(r->modes[0].mode, HYLO_MODE_GROUND);
		assert_true(r->switch_cost[0] == 70 && r->switch_cost[1] == 20);
	}
}

static void test_third_mode_fails(void **state)
{
	static const hylo_registry_model models[] = {
		{ &ground, NULL, "rotor", HYLO_MODE_GROUND, -1, -1 },
		{ &flight, NULL, "rotor", HYLO_MODE_FLIGHT, 70, 20 },
		{ &marine, NULL, "rotor", HYLO_MODE_MARINE, -1, -1 },
	};
	hylo_robot robots[HYLO_MAX_ROBOTS];
	hylo_reason reason;

	(void)state;
	assert_int_equal(hylo_registry_robots_of(models, 3, NULL, 0, robots, HYLO_MAX_ROBOTS, &reason), 0);
	assert_non_null(strstr(reason.text, "robot rotor"));
	assert_non_null(strstr(reason.text, "rotor_marine adds mode marine"));
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_switch_costs_by_mode),
		cmocka_unit_test(test_third_mode_fails),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
