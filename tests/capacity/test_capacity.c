/*
 * Capacities past their limit, with the planning core compiled for small
 * capacities (mk/onboard.mk: CAPACITY_FLAGS) so that ordinary scenes exceed
 * them. Each exceeded capacity returns the status naming it, with a reason,
 * and the planner keeps serving requests that fit. (Exact-at-capacity cases
 * are in the module tests: cells in test_map, positions in test_poisson,
 * nodes and successors in test_search, grids and combinations in
 * test_planner.) The ASan build proves no write goes out of bounds.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdlib.h>

#include "onboard/testutil_planner.h"

static hylo_planner *pl;
static hylo_plan *plan;
static hylo_robot robots[TU_N_ROBOTS];
static tu_cost costs;
static tu_map river, di;

static void expect_cap(hylo_status want, const hylo_goal *g)
{
	hylo_status st = hylo_planner_plan(pl, g, plan);

	if (st != want)
		fail_msg("expected %s, got %s: %s", hylo_status_str(want), hylo_status_str(st),
			 plan->reason.text);
	assert_true(strstr(plan->reason.text, "HYLO_MAX_") != NULL);
	assert_int_equal(plan->n_waypoints, 0);
}

static void set(tu_map *m)
{
	hylo_map_view v = tu_view(m);

	assert_int_equal(hylo_planner_set_map(pl, &v), HYLO_OK);
}

/* Goal g sampled with other spacings, radius and grid sizes (the fixture's
 * grids cut to n_speeds and n_headings entries). */
static hylo_goal resampled(hylo_goal g, hylo_real spacing, hylo_real guard_spacing,
			   hylo_real connect_radius, uint32_t n_speeds, uint32_t n_headings)
{
	g.sampling.spacing = spacing;
	g.sampling.guard_spacing = guard_spacing;
	g.sampling.connect_radius = connect_radius;
	g.sampling.n_speeds = n_speeds;
	g.sampling.n_headings = n_headings;
	return g;
}

/* A request that fits, answered correctly after each failure. */
static void fits(void)
{
	hylo_goal g = resampled(tu_goal_river(), 3, 3, 5, 1, 2);

	set(&river);
	assert_int_equal(hylo_planner_plan(pl, &g, plan), HYLO_OK);
	assert_int_equal(plan->outcome, HYLO_FOUND);
}

static void test_positions(void **state)
{
	hylo_goal g = resampled(tu_goal_river(), 0.5, 2, 4.5, 3, 4);

	(void)state;
	set(&river);
	expect_cap(HYLO_E_CAP_POSITIONS, &g);
	fits();
}

static void test_nodes(void **state)
{
	/* 241 positions x 12 combinations */
	hylo_goal g = resampled(tu_goal_river(), 1.5, 1.5, 3, 3, 4);

	(void)state;
	set(&river);
	expect_cap(HYLO_E_CAP_NODES, &g);
	fits();
}

static void test_adjacency(void **state)
{
	/* 215 positions, about 9000 neighbour entries */
	hylo_goal g = resampled(tu_goal_river(), 1.5, 4, 10, 1, 1);

	(void)state;
	set(&river);
	expect_cap(HYLO_E_CAP_ADJACENCY, &g);
	fits();
}

static void test_successors(void **state)
{
	/* about 26 neighbours x 12 combinations */
	hylo_goal g = resampled(tu_goal_river(), 3, 3, 14, 3, 4);

	(void)state;
	set(&river);
	expect_cap(HYLO_E_CAP_SUCCESSORS, &g);
	fits();
}

static void test_waypoints(void **state)
{
	/* a path of about 22 waypoints */
	hylo_goal g = resampled(tu_goal_di(), 0.1, 0.1, 0.15, 0, 0);

	(void)state;
	set(&di);
	expect_cap(HYLO_E_CAP_WAYPOINTS, &g);
	fits();
}

static int setup(void **state)
{
	hylo_planner_config cfg;

	(void)state;
	pl = malloc(TU_PLANNER_BYTES);
	plan = malloc(sizeof *plan);
	if (!pl || !plan)
		return -1;
	tu_robots(robots, &costs);
	cfg = tu_config(robots, TU_N_ROBOTS);
	if (hylo_planner_init(pl, TU_PLANNER_BYTES, &cfg) != HYLO_OK)
		return -1;
	tu_river(&river);
	tu_di(&di);
	return 0;
}

static int teardown(void **state)
{
	(void)state;
	tu_map_free(&river);
	tu_map_free(&di);
	free(pl);
	free(plan);
	return 0;
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_positions),
		cmocka_unit_test(test_nodes),
		cmocka_unit_test(test_adjacency),
		cmocka_unit_test(test_successors),
		cmocka_unit_test(test_waypoints),
	};

	return cmocka_run_group_tests_name("capacity", tests, setup, teardown);
}
