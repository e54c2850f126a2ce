/*
 * Plans fixed requests on the test scenes (tests/onboard/testutil_planner.h:
 * river, chasm, double integrator on the committed SVR models; A* and
 * Dijkstra) and prints one line per
 * plan with an FNV-1a digest of every number in it, so that builds for
 * different machines can be compared bit for bit (make cross-test).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "onboard/testutil_planner.h"
/* The committed double-integrator models: SVR evaluation (libm exp) too. */
#include "di_di_neg.h"
#include "di_di_pos.h"

static uint64_t fnv(uint64_t h, const void *p, size_t n)
{
	const unsigned char *b = p;
	size_t i;

	for (i = 0; i < n; i++) {
		h ^= b[i];
		h *= 1099511628211ULL;
	}
	return h;
}

int main(void)
{
	hylo_planner *pl = malloc(TU_PLANNER_BYTES);
	hylo_plan *plan = malloc(sizeof *plan);
	hylo_robot robots[TU_N_ROBOTS];
	hylo_planner_config cfg;
	tu_cost costs;
	tu_map maps[3];
	hylo_goal goals[3];
	const char *names[3] = { "river", "chasm", "di" };
	int k, alg;

	if (!pl || !plan)
		return 1;
	tu_robots(robots, &costs);
	robots[2].modes[0].model = &hylo_model_di_di_neg;   /* di on the trained SVRs */
	robots[2].modes[1].model = &hylo_model_di_di_pos;
	memset(&cfg, 0, sizeof cfg);
	cfg.robots = robots;
	cfg.n_robots = TU_N_ROBOTS;
	if (hylo_planner_init(pl, TU_PLANNER_BYTES, &cfg) != HYLO_OK)
		return 1;
	tu_river(&maps[0]);
	tu_chasm(&maps[1]);
	tu_di(&maps[2]);
	goals[0] = tu_goal_river();
	goals[1] = tu_goal_chasm();
	goals[2] = tu_goal_di();
	for (k = 0; k < 3; k++) {
		hylo_map_view v = tu_view(&maps[k]);

		if (hylo_planner_set_map(pl, &v) != HYLO_OK)
			return 1;
		for (alg = 0; alg < 2; alg++) {
			uint64_t h = 1469598103934665603ULL;
			uint32_t w;

			goals[k].algorithm = alg;
			if (hylo_planner_plan(pl, &goals[k], plan) != HYLO_OK)
				return 1;
			h = fnv(h, &plan->total_cost, sizeof plan->total_cost);
			for (w = 0; w < plan->n_waypoints; w++) {
				h = fnv(h, plan->state[w], sizeof plan->state[w]);
				h = fnv(h, &plan->cost[w], sizeof plan->cost[w]);
				h = fnv(h, &plan->mode[w], 1);
			}
			printf("%-6s %-8s cost %.17g  %u waypoints  %lu edges evaluated  digest %016llx\n",
			       names[k], alg ? "dijkstra" : "astar", plan->total_cost,
			       (unsigned)plan->n_waypoints, (unsigned long)plan->n_edges_evaluated,
			       (unsigned long long)h);
		}
	}
	for (k = 0; k < 3; k++)
		tu_map_free(&maps[k]);
	free(pl);
	free(plan);
	return 0;
}
