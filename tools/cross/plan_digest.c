/*
 * Plans fixed requests on the test scenes (tests/onboard/testutil_planner.h:
 * river, chasm, double integrator on the committed SVR models; A* and
 * Dijkstra) and on the small scenes of tests/onboard/testutil_models.h with
 * every committed model, and prints one line per plan with an FNV-1a digest
 * of every number in it, so that builds for different machines, and the
 * SVR evaluator's run-time paths (AVX2 or not), can be compared bit for bit
 * (make cross-test; tests/cross/test_paths.sh).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "onboard/testutil_models.h"

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

static void print_plan(const char *scene, const char *alg, const hylo_plan *plan)
{
	uint64_t h = 1469598103934665603ULL;
	uint32_t w;

	h = fnv(h, &plan->total_cost, sizeof plan->total_cost);
	for (w = 0; w < plan->n_waypoints; w++) {
		h = fnv(h, plan->state[w], sizeof plan->state[w]);
		h = fnv(h, &plan->cost[w], sizeof plan->cost[w]);
		h = fnv(h, &plan->mode[w], 1);
	}
	printf("%-12s %-8s cost %.17g  %u waypoints  %lu edges evaluated  digest %016llx\n", scene, alg,
	       plan->total_cost, (unsigned)plan->n_waypoints, (unsigned long)plan->n_edges_evaluated,
	       (unsigned long long)h);
}

/* The committed models on the small scenes. */
static int model_plans(void)
{
	static hylo_robot robots[TM_N_ROBOTS];
	hylo_planner_config cfg;
	hylo_planner *pl;
	hylo_plan *plan = malloc(sizeof *plan);
	hylo_goal goals[3];
	tu_map maps[3];
	const char *names[3] = { "model_river", "model_chasm", "model_di" };
	size_t size;
	int k, rc = 0;

	tm_robots(robots);
	cfg = tu_config(robots, TM_N_ROBOTS);
	size = hylo_planner_size(&cfg);
	pl = malloc(size);
	if (!pl || !plan || hylo_planner_init(pl, size, &cfg) != HYLO_OK)
		return 1;
	tm_small_river(&maps[0]);
	tm_small_chasm(&maps[1]);
	tu_di(&maps[2]);
	goals[0] = tm_river_goal();
	goals[1] = tm_chasm_goal();
	goals[2] = tm_di_goal();
	for (k = 0; k < 3 && rc == 0; k++) {
		hylo_map_view v = tu_view(&maps[k]);

		if (hylo_planner_set_map(pl, &v) != HYLO_OK || hylo_planner_plan(pl, &goals[k], plan) != HYLO_OK)
			rc = 1;
		else
			print_plan(names[k], "astar", plan);
	}
	for (k = 0; k < 3; k++)
		tu_map_free(&maps[k]);
	free(pl);
	free(plan);
	return rc;
}

int main(void)
{
	hylo_planner *pl = malloc(TU_PLANNER_BYTES);
	hylo_plan *plan = malloc(sizeof *plan);
	hylo_robot robots[TU_N_ROBOTS];
	hylo_planner_config cfg;
	tu_cost costs;
	tu_map maps[TU_N_SCENES];
	hylo_goal goals[TU_N_SCENES];
	const char *names[TU_N_SCENES] = { "river", "chasm", "di" };
	int k, alg;

	if (!pl || !plan)
		return 1;
	tu_robots(robots, &costs);
	robots[2].modes[0].model = &hylo_model_di_di_neg;   /* di on the trained SVRs */
	robots[2].modes[1].model = &hylo_model_di_di_pos;
	cfg = tu_config(robots, TU_N_ROBOTS);
	if (hylo_planner_init(pl, TU_PLANNER_BYTES, &cfg) != HYLO_OK)
		return 1;
	tu_scenes(maps, goals);
	for (k = 0; k < TU_N_SCENES; k++) {
		hylo_map_view v = tu_view(&maps[k]);

		if (hylo_planner_set_map(pl, &v) != HYLO_OK)
			return 1;
		for (alg = 0; alg < 2; alg++) {
			goals[k].algorithm = alg;
			if (hylo_planner_plan(pl, &goals[k], plan) != HYLO_OK)
				return 1;
			print_plan(names[k], alg ? "dijkstra" : "astar", plan);
		}
	}
	for (k = 0; k < TU_N_SCENES; k++)
		tu_map_free(&maps[k]);
	free(pl);
	free(plan);
	return model_plans();
}
