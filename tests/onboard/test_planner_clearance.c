/*
 * The planner keeps the robot's body and the margin (docs/planner.md, "Body
 * and margin"): a corridor narrower than twice body + margin has no path,
 * a wider one has, and every point of every edge of the plan (sampled every
 * centimetre) keeps body + margin from the nearest hazard by the exact
 * distance (hylo_hazard_distance); a flight over a wall keeps it from the
 * wall's top edge. Without the body and the margin the same maps give
 * plans that come closer, so these checks can fail. Also the config and
 * robot checks, and starts and goals that lack the clearance.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "onboard/testutil_planner.h"

#define BODY 0.3          /* the corridor test's rover [m] */
#define FLIGHT_BODY 0.6   /* the wall test's drivocopter: more than HYLO_AIR_CLEARANCE_M */

static hylo_planner *planner;
static hylo_plan *plan;
static hylo_robot robots[TU_N_ROBOTS];
static tu_cost costs;

static hylo_status init_with(hylo_real margin_m)
{
	hylo_planner_config cfg;

	cfg = tu_config(robots, TU_N_ROBOTS);
	cfg.margin_m = margin_m;
	return hylo_planner_init(planner, TU_PLANNER_BYTES, &cfg);
}

static int setup(void **state)
{
	(void)state;
	planner = malloc(TU_PLANNER_BYTES);
	plan = malloc(sizeof *plan);
	tu_robots(robots, &costs);
	robots[1].body_radius_m = FLIGHT_BODY;
	robots[3].body_radius_m = BODY;
	return planner && plan ? 0 : -1;
}

static int teardown(void **state)
{
	(void)state;
	free(planner);
	free(plan);
	return 0;
}

static void set_map(tu_map *m)
{
	hylo_map_view v = tu_view(m);

	if (hylo_planner_set_map(planner, &v) != HYLO_OK)
		fail_msg("set_map: %s", hylo_planner_reason(planner));
}

static hylo_point point_of(const hylo_map *m, hylo_mode mode, const hylo_real *xs)
{
	hylo_point p;

	p.x = xs[0];
	p.y = xs[1];
	p.z = mode == HYLO_MODE_FLIGHT ? xs[2] : hylo_map_height(m, xs[0], xs[1]);
	return p;
}

/* The least hazard distance over the plan's waypoints and the points of
 * its same-mode edges every centimetre (switch edges: both ends). */
static hylo_real plan_distance(const hylo_plan *p, const hylo_map *m)
{
	hylo_real least = HUGE_VAL;
	uint32_t k;
	int i, n;

	for (k = 0; k < p->n_waypoints; k++) {
		hylo_mode mode = (hylo_mode)p->mode[k];
		hylo_point a = point_of(m, mode, p->state[k]), b, q;
		hylo_real d = hylo_hazard_distance(m, mode, a, 10);

		if (d < least)
			least = d;
		if (k + 1 == p->n_waypoints || p->mode[k + 1] != p->mode[k])
			continue;
		b = point_of(m, mode, p->state[k + 1]);
		n = (int)ceil(sqrt((b.x - a.x) * (b.x - a.x) + (b.y - a.y) * (b.y - a.y) +
				   (b.z - a.z) * (b.z - a.z)) / 0.01);
		for (i = 1; i < n; i++) {
			hylo_real t = (hylo_real)i / n;

			q.x = a.x + t * (b.x - a.x);
			q.y = a.y + t * (b.y - a.y);
			q.z = mode == HYLO_MODE_FLIGHT ? a.z + t * (b.z - a.z) : hylo_map_height(m, q.x, q.y);
			d = hylo_hazard_distance(m, mode, q, 10);
			if (d < least)
				least = d;
		}
	}
	return least;
}

/* 20 m x 10 m of ground in 0.25 m cells, an obstacle wall across it at
 * x in [9, 11) with a gap of `gap` m at y in [5, 5 + gap). */
static void corridor(tu_map *m, hylo_real gap)
{
	int32_t ix, iy;

	tu_map_alloc(m, "rover", 80, 40, 0.25, 0, 0);
	for (iy = 0; iy < m->ny; iy++)
		for (ix = 0; ix < m->nx; ix++) {
			hylo_real y = (iy + 0.5) * m->res;
			int wall = ix >= 36 && ix < 44 && !(y > 5 && y < 5 + gap);

			m->terrain[iy * m->nx + ix] = wall ? HYLO_TERRAIN_OBSTACLE : HYLO_TERRAIN_GROUND;
		}
}

static hylo_goal corridor_goal(void)
{
	hylo_goal g = tu_goal_river();

	g.start[0] = 3;
	g.start[1] = 5;
	g.goal[0] = 17;
	g.goal[1] = 5;
	g.sampling.spacing = 0.5;
	g.sampling.guard_spacing = 0.5;
	g.sampling.connect_radius = 2.5;
	return g;
}

static void test_corridor(void **state)
{
	const hylo_real need = BODY + HYLO_DEFAULT_MARGIN_M;
	hylo_goal g = corridor_goal();
	tu_map narrow, wide;
	hylo_real least;

	(void)state;
	corridor(&narrow, 0.75);   /* < 2 (body + margin) = 0.8 */
	corridor(&wide, 1.5);
	assert_int_equal(init_with(0), HYLO_OK);
	set_map(&narrow);
	assert_true(fabs(hylo_planner_clearance(planner) - need) < 1e-12);
	assert_int_equal(hylo_planner_plan(planner, &g, plan), HYLO_OK);
	assert_int_equal(plan->outcome, HYLO_NO_PATH);

	set_map(&wide);
	assert_int_equal(hylo_planner_plan(planner, &g, plan), HYLO_OK);
	assert_int_equal(plan->outcome, HYLO_FOUND);
	least = plan_distance(plan, &planner->map);
	if (least < need - 1e-9)
		fail_msg("the plan through the corridor comes %g m from a hazard, less than %g", least, need);

	/* A point robot without a margin squeezes through the narrow gap and
	 * passes the wide one's edges closer than the rover may. */
	robots[3].body_radius_m = 0;
	assert_int_equal(init_with(HYLO_NO_MARGIN), HYLO_OK);
	set_map(&narrow);
	assert_true(hylo_planner_clearance(planner) == 0);
	assert_int_equal(hylo_planner_plan(planner, &g, plan), HYLO_OK);
	assert_int_equal(plan->outcome, HYLO_FOUND);
	assert_true(plan_distance(plan, &planner->map) < need);
	robots[3].body_radius_m = BODY;
	tu_map_free(&narrow);
	tu_map_free(&wide);
}

/* 30 m x 6 m in 0.5 m cells: flat ground at 0 and a 1 m thick wall 4 m
 * high across it at x in [14.5, 15.5): the ground path is cut (steps of 4
 * m), so the drivocopter flies over it. Ceiling 12 m. */
static void wall_map(tu_map *m)
{
	int32_t ix, iy;

	tu_map_alloc(m, "drivocopter", 60, 12, 0.5, 0, 0);
	m->ceiling = 12;
	for (iy = 0; iy < m->ny; iy++)
		for (ix = 0; ix < m->nx; ix++) {
			m->terrain[iy * m->nx + ix] = HYLO_TERRAIN_GROUND;
			m->height[iy * m->nx + ix] = ix >= 29 && ix < 31 ? 4.0f : 0.0f;
		}
}

/* The least distance from the plan's flight edges (every centimetre) to the
 * wall's two top edges (x = 14.5 and 15.5 at z = 4). */
static hylo_real top_edge_distance(const hylo_plan *p)
{
	hylo_real least = HUGE_VAL;
	uint32_t k;
	int i, e;

	for (k = 0; k + 1 < p->n_waypoints; k++) {
		const hylo_real *a = p->state[k], *b = p->state[k + 1];

		if (p->mode[k] != HYLO_MODE_FLIGHT || p->mode[k + 1] != HYLO_MODE_FLIGHT)
			continue;
		for (i = 0; i <= 2000; i++) {
			hylo_real t = i / 2000.0, x = a[0] + t * (b[0] - a[0]), z = a[2] + t * (b[2] - a[2]);

			for (e = 0; e < 2; e++) {
				hylo_real d = hypot(x - (14.5 + e), z - 4);

				if (d < least)
					least = d;
			}
		}
	}
	return least;
}

static void test_flight_over_wall(void **state)
{
	const hylo_real need = FLIGHT_BODY + HYLO_DEFAULT_MARGIN_M;
	hylo_goal g = tu_goal_chasm();
	tu_map m;
	hylo_real least;

	(void)state;
	wall_map(&m);
	g.start[0] = 4;
	g.goal[0] = 26;
	assert_int_equal(init_with(0), HYLO_OK);
	set_map(&m);
	assert_int_equal(hylo_planner_plan(planner, &g, plan), HYLO_OK);
	assert_int_equal(plan->outcome, HYLO_FOUND);
	least = plan_distance(plan, &planner->map);
	if (least < need - 1e-9)
		fail_msg("the flight plan comes %g m from a hazard, less than %g", least, need);
	least = top_edge_distance(plan);
	if (least < need - 1e-9)
		fail_msg("the flight passes %g m from the wall's top edge, less than %g", least, need);

	/* Without the body and the margin: HYLO_AIR_CLEARANCE_M (0.5 m) over
	 * the top, closer than the drivocopter's body + margin. */
	robots[1].body_radius_m = 0;
	assert_int_equal(init_with(HYLO_NO_MARGIN), HYLO_OK);
	set_map(&m);
	assert_int_equal(hylo_planner_plan(planner, &g, plan), HYLO_OK);
	assert_int_equal(plan->outcome, HYLO_FOUND);
	assert_true(top_edge_distance(plan) < need);
	robots[1].body_radius_m = FLIGHT_BODY;
	tu_map_free(&m);
}

static void expect_refused(const hylo_goal *g, const char *text)
{
	assert_int_equal(hylo_planner_plan(planner, g, plan), HYLO_E_OUTSIDE_DOMAIN);
	if (!strstr(plan->reason.text, text))
		fail_msg("reason \"%s\" does not say \"%s\"", plan->reason.text, text);
}

/* A start or goal inside its mode's domain that lacks the clearance is a
 * bad request that names the point and what it lacks. */
static void test_start_goal_without_clearance(void **state)
{
	hylo_goal g = corridor_goal();
	tu_map m;

	(void)state;
	corridor(&m, 1.5);
	assert_int_equal(init_with(0), HYLO_OK);
	set_map(&m);
	g.start[0] = 8.8;    /* 0.2 m from the wall */
	expect_refused(&g, "start (8.8, 5, 0) is 0.2 m from the nearest ground hazard; robot rover needs 0.4 m (body 0.3 m + margin 0.1 m)");
	g.start[0] = 3;
	g.goal[1] = 9.75;    /* 0.25 m from the map's edge */
	expect_refused(&g, "goal (17, 9.75, 0) is 0.25 m from the nearest ground hazard");
	/* 0.45 m from the wall, but in a cell that is not: refused too, saying
	 * the planner keeps the clearance cell by cell. */
	g.goal[1] = 5;
	g.goal[0] = 11.45;
	expect_refused(&g, "goal (11.45, 5, 0) keeps 0.4 m (body 0.3 m + margin 0.1 m) from every ground hazard, but its cell does not");
	/* Inside the obstacle: outside the domain, as before. */
	g.goal[0] = 10;
	g.goal[1] = 2;
	expect_refused(&g, "lies outside the ground domain");
	tu_map_free(&m);
}

static void test_config_and_robot_checks(void **state)
{
	tu_map m;

	(void)state;
	assert_int_equal(init_with(-0.5), HYLO_E_BAD_VALUE);
	assert_non_null(strstr(hylo_planner_reason(planner), "margin_m = -0.5"));
	assert_int_equal(init_with(NAN), HYLO_E_BAD_VALUE);
	assert_int_equal(init_with(INFINITY), HYLO_E_BAD_VALUE);
	robots[3].body_radius_m = -0.1;
	assert_int_equal(init_with(0), HYLO_E_BAD_VALUE);
	assert_non_null(strstr(hylo_planner_reason(planner), "robot rover: body radius -0.1 m"));
	robots[3].body_radius_m = NAN;
	assert_int_equal(init_with(0), HYLO_E_BAD_VALUE);
	robots[3].body_radius_m = BODY;

	/* margin 0 is the default, HYLO_NO_MARGIN none, anything else itself. */
	corridor(&m, 1.5);
	assert_int_equal(init_with(0.25), HYLO_OK);
	set_map(&m);
	assert_true(fabs(hylo_planner_clearance(planner) - (BODY + 0.25)) < 1e-12);
	assert_int_equal(init_with(HYLO_NO_MARGIN), HYLO_OK);
	set_map(&m);
	assert_true(hylo_planner_clearance(planner) == BODY);

	/* A map where no cell keeps the clearance is refused, saying why. */
	assert_int_equal(init_with(5), HYLO_OK);
	{
		hylo_map_view v = tu_view(&m);

		assert_int_equal(hylo_planner_set_map(planner, &v), HYLO_E_EMPTY_DOMAIN);
		assert_non_null(strstr(hylo_planner_reason(planner), "keeps its clearance of 5.3 m (body 0.3 m + margin 5 m)"));
	}
	tu_map_free(&m);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_corridor),
		cmocka_unit_test(test_flight_over_wall),
		cmocka_unit_test(test_start_goal_without_clearance),
		cmocka_unit_test(test_config_and_robot_checks),
	};

	return cmocka_run_group_tests(tests, setup, teardown);
}
