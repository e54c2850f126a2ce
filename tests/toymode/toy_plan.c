/*
 * Plans with the toy mode (tests/toymode/toy_mode.h) through the planner
 * node's registry: test_toy_mode.sh compiles it with the toy build's flags
 * against a registry generated from the header the toy trainer exported.
 * Prints the toy robot's registry entry and the plan; exits 1 when the
 * robot, its model or a plan is missing.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hylo/modes.h"
#include "hylo/planner.h"
#include "node/registry.h"

#define NX 40
#define NY 40

int main(void)
{
	static hylo_robot robots[HYLO_MAX_ROBOTS];
	static int8_t terrain[NX * NY];
	static float height[NX * NY];
	static hylo_plan plan;
	hylo_reason reason;
	hylo_planner_config cfg;
	hylo_map_view map;
	hylo_goal goal;
	hylo_planner *pl;
	const hylo_robot *toy = NULL;
	size_t size;
	uint32_t n, k;

	n = hylo_registry_robots(robots, HYLO_MAX_ROBOTS, &reason);
	for (k = 0; k < n; k++)
		if (strcmp(robots[k].name, "toy") == 0)
			toy = &robots[k];
	if (!toy || toy->n_modes != 1 || toy->modes[0].mode != HYLO_MODE_TOY || !toy->modes[0].model) {
		fprintf(stderr, "toy_plan: no robot toy with a model of mode toy in the registry (%s)\n",
			n ? "" : reason.text);
		return 1;
	}
	printf("registry: robot toy, mode %s (%d), model %s, %u features\n",
	       hylo_mode_str(toy->modes[0].mode), (int)toy->modes[0].mode, toy->modes[0].model->name,
	       (unsigned)toy->modes[0].model->n_features);

	/* The phase plane p, v in [-1, 1], every cell free. */
	for (k = 0; k < NX * NY; k++)
		terrain[k] = HYLO_TERRAIN_GROUND;
	memset(&map, 0, sizeof map);
	map.map_id = 1;
	map.robot = "toy";
	map.nx = NX;
	map.ny = NY;
	map.resolution = 0.05;
	map.origin_x = map.origin_y = -1;
	map.n_cells = NX * NY;
	map.terrain = terrain;
	map.height = height;

	memset(&goal, 0, sizeof goal);
	goal.request_id = 1;
	goal.algorithm = HYLO_ASTAR;
	goal.start_mode = goal.goal_mode = HYLO_MODE_TOY;
	goal.start[0] = -0.5, goal.start[1] = 0;
	goal.goal[0] = 0.5, goal.goal[1] = 0;
	goal.sampling.seed = 1;
	goal.sampling.spacing = 0.1;
	goal.sampling.guard_spacing = 0.1;
	goal.sampling.connect_radius = 0.3;

	memset(&cfg, 0, sizeof cfg);
	cfg.robots = robots;
	cfg.n_robots = n;
	size = hylo_planner_size(&cfg);
	pl = malloc(size);
	if (!pl || hylo_planner_init(pl, size, &cfg) != HYLO_OK || hylo_planner_set_map(pl, &map) != HYLO_OK) {
		fprintf(stderr, "toy_plan: %s\n", pl ? hylo_planner_reason(pl) : "out of memory");
		return 1;
	}
	if (hylo_planner_plan(pl, &goal, &plan) != HYLO_OK || plan.outcome != HYLO_FOUND) {
		fprintf(stderr, "toy_plan: %s: %s\n", hylo_outcome_str(plan.outcome), plan.reason.text);
		return 1;
	}
	printf("plan: %.6g J over %u waypoints\n", plan.total_cost, (unsigned)plan.n_waypoints);
	for (k = 0; k < plan.n_waypoints; k++)
		printf("  %s (%.3f, %.3f) %.6g J\n", hylo_mode_str((hylo_mode)plan.mode[k]), plan.state[k][0],
		       plan.state[k][1], plan.cost[k]);
	free(pl);
	return 0;
}
