/*
 * The double integrator's phase-plane scene (tests/onboard/testutil_planner.h
 * tu_di, testutil_models.h tm_di_goal) planned with the committed models, as
 * an out-of-tree program does it against an installed hylo: only installed
 * headers, caller-owned memory. Shared by consumer.c (C99, pkg-config) and
 * cmake/consumer.cpp (C++17, CMake). consumer_plan() prints the plan's line
 * in tools/cross/plan_digest.c's format ("model_di astar cost ... digest
 * ...") so that tests/install/test_install.sh can compare it with the
 * in-tree build's bit for bit, and checks the plan itself.
 */
#ifndef HYLO_TEST_CONSUMER_H
#define HYLO_TEST_CONSUMER_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <hylo/models/di_di_neg.h>
#include <hylo/models/di_di_pos.h>
#include <hylo/planner.h>
#include <hylo/version.h>

#define CONSUMER_NX 40
#define CONSUMER_NY 40

static uint64_t consumer_fnv(uint64_t h, const void *p, size_t n)
{
	const unsigned char *b = (const unsigned char *)p;
	size_t i;

	for (i = 0; i < n; i++) {
		h ^= b[i];
		h *= 1099511628211ULL;
	}
	return h;
}

static int consumer_fail(const char *what, const char *why)
{
	fprintf(stderr, "consumer: %s: %s\n", what, why);
	return 1;
}

/* Plans, prints, checks; 0 when the plan is what it should be. */
static int consumer_plan(void)
{
	static int8_t terrain[CONSUMER_NX * CONSUMER_NY];
	static float height[CONSUMER_NX * CONSUMER_NY];
	hylo_robot robot;
	hylo_planner_config cfg;
	hylo_map_view map;
	hylo_goal goal;
	hylo_plan *plan;
	hylo_planner *pl;
	size_t size;
	uint64_t h = 1469598103934665603ULL;
	uint32_t w, switches = 0;
	int ix, iy, rc = 0;

	if (strcmp(hylo_version(), HYLO_VERSION) != 0)
		return consumer_fail("version", "the library is not the headers' version");
	memset(&robot, 0, sizeof robot);
	robot.name = "di";
	robot.n_modes = 2;
	robot.modes[0].mode = HYLO_MODE_DI_NEG;
	robot.modes[0].model = &hylo_model_di_di_neg;
	robot.modes[0].feasibility = &hylo_model_di_di_neg_feasibility;
	robot.modes[1].mode = HYLO_MODE_DI_POS;
	robot.modes[1].model = &hylo_model_di_di_pos;
	robot.modes[1].feasibility = &hylo_model_di_di_pos_feasibility;
	memset(&cfg, 0, sizeof cfg);
	cfg.robots = &robot;
	cfg.n_robots = 1;

	/* The workspace is the caller's: hylo_planner_size() bytes, once. */
	size = hylo_planner_size(&cfg);
	pl = (hylo_planner *)malloc(size);
	plan = (hylo_plan *)malloc(sizeof *plan);
	if (!pl || !plan)
		return consumer_fail("malloc", "out of memory");
	if (hylo_planner_init(pl, size, &cfg) != HYLO_OK) {
		rc = consumer_fail("hylo_planner_init", hylo_planner_reason(pl));
		goto out;
	}

	/* The phase plane p, v in [-1, 1] at 5 cm, an obstacle blob. */
	for (iy = 0; iy < CONSUMER_NY; iy++)
		for (ix = 0; ix < CONSUMER_NX; ix++)
			terrain[iy * CONSUMER_NX + ix] = (int8_t)((ix >= 8 && ix < 12 && iy >= 4 && iy < 14)
									  ? HYLO_TERRAIN_OBSTACLE
									  : HYLO_TERRAIN_GROUND);
	memset(&map, 0, sizeof map);
	map.map_id = 1;
	map.robot = "di";
	map.nx = CONSUMER_NX;
	map.ny = CONSUMER_NY;
	map.resolution = 0.05;
	map.origin_x = -1;
	map.origin_y = -1;
	map.max_step = 0.1;
	map.n_cells = CONSUMER_NX * CONSUMER_NY;
	map.terrain = terrain;
	map.height = height;
	if (hylo_planner_set_map(pl, &map) != HYLO_OK) {
		rc = consumer_fail("hylo_planner_set_map", hylo_planner_reason(pl));
		goto out;
	}

	/* From (p, v) = (0.8, 0.2) on the positive side to (-0.8, 0). */
	memset(&goal, 0, sizeof goal);
	goal.algorithm = HYLO_ASTAR;
	goal.start_mode = HYLO_MODE_DI_POS;
	goal.goal_mode = HYLO_MODE_DI_NEG;
	goal.start[0] = 0.8;
	goal.start[1] = 0.2;
	goal.goal[0] = -0.8;
	goal.sampling.seed = 1;
	goal.sampling.spacing = 0.15;
	goal.sampling.guard_spacing = 0.15;
	goal.sampling.connect_radius = 0.4;
	if (hylo_planner_plan(pl, &goal, plan) != HYLO_OK) {
		rc = consumer_fail("hylo_planner_plan", plan->reason.text);
		goto out;
	}

	h = consumer_fnv(h, &plan->total_cost, sizeof plan->total_cost);
	for (w = 0; w < plan->n_waypoints; w++) {
		h = consumer_fnv(h, plan->state[w], sizeof plan->state[w]);
		h = consumer_fnv(h, &plan->cost[w], sizeof plan->cost[w]);
		h = consumer_fnv(h, &plan->mode[w], 1);
		switches += plan->guard[w];
	}
	printf("%-12s %-8s cost %.17g  %u waypoints  %lu edges evaluated  digest %016llx\n", "model_di",
	       "astar", plan->total_cost, (unsigned)plan->n_waypoints, (unsigned long)plan->n_edges_evaluated,
	       (unsigned long long)h);
	printf("hylo %s, model format %d\n", hylo_version(), HYLO_MODEL_FORMAT_VERSION);

	/* The plan itself: found, positive cost, from the start to the goal
	 * through the guard p = 0 (a mode switch), costs accumulating. */
	if (plan->outcome != HYLO_FOUND)
		rc = consumer_fail("outcome", hylo_outcome_str(plan->outcome));
	else if (!(plan->total_cost > 0) || !isfinite(plan->total_cost))
		rc = consumer_fail("cost", "not finite and positive");
	else if (plan->n_waypoints < 3)
		rc = consumer_fail("waypoints", "fewer than 3");
	else if (plan->mode[0] != HYLO_MODE_DI_POS || plan->state[0][0] != 0.8 || plan->state[0][1] != 0.2)
		rc = consumer_fail("first waypoint", "not the start");
	else if (plan->mode[plan->n_waypoints - 1] != HYLO_MODE_DI_NEG ||
		 plan->state[plan->n_waypoints - 1][0] != -0.8 || plan->state[plan->n_waypoints - 1][1] != 0)
		rc = consumer_fail("last waypoint", "not the goal");
	else if (plan->cost[plan->n_waypoints - 1] != plan->total_cost)
		rc = consumer_fail("cost", "the last waypoint's cumulative cost is not the total");
	else if (switches == 0)
		rc = consumer_fail("guard", "no mode switch between p > 0 and p < 0");
out:
	free(pl);
	free(plan);
	return rc;
}

#endif
