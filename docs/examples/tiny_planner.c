/*
 * The smallest program on the onboard planner: one ground robot whose edge
 * cost is a formula (a cost callback, no trained model), a 20 m x 10 m map
 * with a wall, one plan. Build it against an installed hylo:
 *   cc -std=c99 tiny_planner.c $(pkg-config --cflags --libs hylo) -o tiny_planner
 * or against a build tree:
 *   cc -std=c99 -Ionboard/include docs/examples/tiny_planner.c build/lib/libhylo.a -lm -o tiny_planner
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hylo/features.h"
#include "hylo/planner.h"

#define NX 40
#define NY 20

/* Energy of an edge [J]: 20 J per metre plus 5 J per radian of turning. */
static hylo_status cost(void *ctx, hylo_mode mode, const hylo_real *tail,
                        const hylo_real (*heads)[HYLO_XS_DIM], uint32_t n,
                        hylo_real *out, hylo_reason *r)
{
	uint32_t i;

	(void)ctx, (void)mode, (void)r;
	for (i = 0; i < n; i++) {
		double dx = heads[i][0] - tail[0], dy = heads[i][1] - tail[1];
		out[i] = 20 * sqrt(dx * dx + dy * dy) + 5 * fabs(hylo_wrap_angle(heads[i][3] - tail[3]));
	}
	return HYLO_OK;
}

int main(void)
{
	static int8_t terrain[NX * NY];
	static float height[NX * NY];
	static const hylo_real speeds[] = { 0.0, 1.0 };
	static const hylo_real headings[] = { 0.0, 1.5707963267948966, 3.141592653589793, -1.5707963267948966 };
	hylo_robot rover;
	hylo_planner_config cfg;
	hylo_map_view map;
	hylo_goal goal;
	static hylo_plan plan;
	hylo_planner *pl;
	size_t size;
	uint32_t i;
	int ix, iy;

	memset(&rover, 0, sizeof rover);
	rover.name = "rover";
	rover.n_modes = 1;
	rover.modes[0].mode = HYLO_MODE_GROUND;
	rover.modes[0].cost_fn = cost;
	rover.modes[0].cost_floor_per_m = 20;   /* every edge costs at least this per metre */
	rover.body_radius_m = 0.3;              /* plans keep it + the margin from every obstacle */

	/* Ground everywhere but a wall at x = 10 m with a gap at the top. */
	for (iy = 0; iy < NY; iy++)
		for (ix = 0; ix < NX; ix++)
			terrain[iy * NX + ix] = ix == 20 && iy < 14 ? HYLO_TERRAIN_OBSTACLE : HYLO_TERRAIN_GROUND;
	memset(&map, 0, sizeof map);
	map.map_id = 1;
	map.robot = "rover";
	map.nx = NX;
	map.ny = NY;
	map.resolution = 0.5;
	map.n_cells = NX * NY;
	map.terrain = terrain;
	map.height = height;
	map.max_step = 0.2;

	memset(&goal, 0, sizeof goal);
	goal.request_id = 1;
	goal.algorithm = HYLO_ASTAR;
	goal.start_mode = goal.goal_mode = HYLO_MODE_GROUND;
	goal.start[0] = 2, goal.start[1] = 2;       /* px, py [m], vx [m/s], heading [rad] */
	goal.goal[0] = 18, goal.goal[1] = 2;
	goal.sampling.seed = 1;
	goal.sampling.spacing = 1.0;
	goal.sampling.connect_radius = 2.5;
	goal.sampling.n_speeds = 2;                 /* the grids: at most HYLO_MAX_GRID entries */
	memcpy(goal.sampling.speeds, speeds, sizeof speeds);
	goal.sampling.n_headings = 4;
	memcpy(goal.sampling.headings, headings, sizeof headings);

	memset(&cfg, 0, sizeof cfg);
	cfg.robots = &rover;
	cfg.n_robots = 1;                           /* margin_m 0: HYLO_DEFAULT_MARGIN_M */
	size = hylo_planner_size(&cfg);
	pl = malloc(size);                          /* the only allocation, at start-up */
	if (!pl || hylo_planner_init(pl, size, &cfg) != HYLO_OK ||
	    hylo_planner_set_map(pl, &map) != HYLO_OK) {
		fprintf(stderr, "tiny_planner: %s\n", pl ? hylo_planner_reason(pl) : "out of memory");
		return 1;
	}
	if (hylo_planner_plan(pl, &goal, &plan) != HYLO_OK || plan.outcome != HYLO_FOUND) {
		fprintf(stderr, "tiny_planner: %s: %s\n", hylo_outcome_str(plan.outcome), plan.reason.text);
		return 1;
	}
	printf("workspace %.1f MB; plan: %.1f J over %u waypoints, %llu of %llu edges evaluated\n",
	       size / 1e6, plan.total_cost, (unsigned)plan.n_waypoints,
	       (unsigned long long)plan.n_edges_evaluated, (unsigned long long)plan.n_edges);
	for (i = 0; i < plan.n_waypoints; i++)
		printf("  (%5.2f, %5.2f)  %6.1f J\n", plan.state[i][0], plan.state[i][1], plan.cost[i]);
	free(pl);
	return 0;
}
