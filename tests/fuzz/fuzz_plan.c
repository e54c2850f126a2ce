/*
 * Fuzz target over message decode, map ingestion and planning: an input is
 * a 4-byte big-endian length L, then L bytes of an encoded map_t, then an
 * encoded goal_t. Both go through the node's own path: wire check, lcm-gen
 * decode, view, hylo_planner_set_map / hylo_planner_plan (robots with the
 * analytic costs of tests/onboard/testutil_planner.h). Nothing may crash,
 * leak or trip ASan/UBSan. To keep each input fast, maps over 64 x 64 cells
 * and very fine samplings are skipped before planning (harness only).
 *
 * Built twice: with clang -fsanitize=fuzzer for `make fuzz`, and with a
 * main() (FUZZ_REPLAY) that runs the committed corpus under ASan+UBSan in
 * `make test`.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hylo_msg.h"
#include "onboard/testutil_planner.h"

static hylo_planner *planner;
static hylo_plan *plan;
static hylo_robot robots[TU_N_ROBOTS];
static tu_cost costs;

static void init(void)
{
	hylo_planner_config cfg;

	if (planner)
		return;
	planner = malloc(TU_PLANNER_BYTES);
	plan = malloc(sizeof *plan);
	if (!planner || !plan)
		abort();
	tu_robots(robots, &costs);
	cfg = tu_config(robots, TU_N_ROBOTS);
	if (hylo_planner_init(planner, TU_PLANNER_BYTES, &cfg) != HYLO_OK)
		abort();
}

static int cheap(const hylo_goal_t *g, const hylo_map *m)
{
	double cells = (double)m->nx * m->ny, res = m->resolution > 0 ? m->resolution : 1;
	double area = cells * res * res, s = g->spacing_m, sa = g->air_spacing_m;

	if (!(s > 0) || area / (s * s) > 3000 || !(g->connect_radius_m <= 4 * s))
		return 0;
	if (g->n_speeds * (double)(g->n_headings ? g->n_headings : 1) > 24)
		return 0;
	if (sa > 0 && (area * (m->ceiling > 0 ? m->ceiling : 1) / (sa * sa * sa) > 3000 ||
		       !(g->air_connect_radius_m <= 4 * sa)))
		return 0;
	return 1;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	hylo_reason r;
	uint32_t L;

	init();
	if (size < 4)
		return 0;
	L = ((uint32_t)data[0] << 24) | ((uint32_t)data[1] << 16) | ((uint32_t)data[2] << 8) | data[3];
	if (L > size - 4)
		L = (uint32_t)(size - 4);
	if (hylo_msg_check_map(data + 4, (int)L, NULL, &r) == HYLO_OK) {
		hylo_map_t m;

		if (hylo_map_t_decode(data + 4, 0, (int)L, &m) >= 0) {
			hylo_map_view v;

			if ((int64_t)m.nx * m.ny <= 64 * 64) {
				hylo_msg_map_view(&m, &v);
				hylo_planner_set_map(planner, &v);
			}
			hylo_map_t_decode_cleanup(&m);
		}
	}
	if (hylo_msg_check_goal(data + 4 + L, (int)(size - 4 - L), NULL, &r) == HYLO_OK) {
		hylo_goal_t g;

		if (hylo_goal_t_decode(data + 4 + L, 0, (int)(size - 4 - L), &g) >= 0) {
			hylo_goal goal;

			if (cheap(&g, &planner->map)) {
				hylo_msg_goal_view(&g, &goal);
				hylo_planner_plan(planner, &goal, plan);
			}
			hylo_goal_t_decode_cleanup(&g);
		}
	}
	return 0;
}

#ifdef FUZZ_REPLAY
/* Regression run: every file named on the command line once; TAP out. */
int main(int argc, char **argv)
{
	int i;

	for (i = 1; i < argc; i++) {
		FILE *f = fopen(argv[i], "rb");
		static uint8_t buf[1 << 20];
		size_t n;

		if (!f) {
			printf("not ok %d - %s (unreadable)\n", i, argv[i]);
			continue;
		}
		n = fread(buf, 1, sizeof buf, f);
		fclose(f);
		LLVMFuzzerTestOneInput(buf, n);
		printf("ok %d - %s\n", i, argv[i]);
		fflush(stdout);
	}
	printf("1..%d\n", argc - 1);
	free(planner);
	free(plan);
	return 0;
}
#endif
