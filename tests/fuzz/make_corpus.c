/*
 * Writes the fuzz seed corpus (tests/fuzz/corpus/) from the test scenes:
 * well-formed map + goal pairs for each robot, and damaged variants
 * (truncated, wrong fingerprint, negative and huge counts, NaN start, goal
 * without a map). Run by `make fuzz-corpus`; its output is committed.
 *   make_corpus DIR
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hylo_msg.h"
#include "onboard/testutil_planner.h"

static int n_written;

static int enc_map(const tu_map *m, uint8_t *out, int cap)
{
	hylo_map_view v = tu_view(m);
	hylo_map_t msg;

	hylo_msg_map(&v, &msg);
	return hylo_map_t_encode(out, 0, cap, &msg);
}

static int enc_goal(const hylo_goal *g, uint8_t *out, int cap)
{
	hylo_goal_t msg;

	hylo_msg_goal(g, &msg);
	return hylo_goal_t_encode(out, 0, cap, &msg);
}

static void put(const char *dir, const char *name, const uint8_t *map, int ml, const uint8_t *goal, int gl)
{
	char path[512];
	FILE *f;
	uint8_t len[4] = { (uint8_t)(ml >> 24), (uint8_t)(ml >> 16), (uint8_t)(ml >> 8), (uint8_t)ml };

	snprintf(path, sizeof path, "%s/%s", dir, name);
	f = fopen(path, "wb");
	if (!f) {
		perror(path);
		exit(1);
	}
	fwrite(len, 1, 4, f);
	fwrite(map, 1, (size_t)ml, f);
	fwrite(goal, 1, (size_t)gl, f);
	fclose(f);
	n_written++;
}

int main(int argc, char **argv)
{
	static uint8_t map[1 << 20], goal[1 << 16], bad[1 << 16];
	tu_map river, chasm, di;
	hylo_goal gr = tu_goal_river(), gc = tu_goal_chasm(), gd = tu_goal_di(), g;
	int ml, gl;

	if (argc != 2) {
		fprintf(stderr, "usage: make_corpus DIR\n");
		return 2;
	}
	tu_river(&river);
	tu_chasm(&chasm);
	tu_di(&di);
	gr.sampling.spacing = gr.sampling.guard_spacing = 3;
	gr.sampling.connect_radius = 6;
	ml = enc_map(&river, map, sizeof map);
	gl = enc_goal(&gr, goal, sizeof goal);
	put(argv[1], "river", map, ml, goal, gl);
	put(argv[1], "river-truncated-goal", map, ml, goal, gl / 2);
	put(argv[1], "river-truncated-map", map, ml / 3, goal, gl);
	put(argv[1], "goal-without-map", map, 0, goal, gl);
	memcpy(bad, goal, (size_t)gl);
	bad[0] ^= 0xff;                                     /* fingerprint */
	put(argv[1], "wrong-fingerprint", map, ml, bad, gl);
	memcpy(bad, goal, (size_t)gl);
	memset(bad + 8 + 8 + 8 + 8 + 1 + 1 + 48 + 1 + 48 + 8 + 40, 0xff, 4);   /* n_speeds = -1 */
	put(argv[1], "negative-count", map, ml, bad, gl);
	memcpy(bad, goal, (size_t)gl);
	memset(bad + 8 + 8 + 8 + 8 + 1 + 1 + 48 + 1 + 48 + 8 + 40, 0x7f, 1);   /* huge n_speeds */
	put(argv[1], "huge-count", map, ml, bad, gl);
	g = gr;
	g.start[0] = NAN;
	gl = enc_goal(&g, goal, sizeof goal);
	put(argv[1], "nan-start", map, ml, goal, gl);
	g = gr;
	g.start[0] = 3.5;
	g.start[1] = 8;
	gl = enc_goal(&g, goal, sizeof goal);
	put(argv[1], "start-in-obstacle", map, ml, goal, gl);
	g = gr;
	g.algorithm = HYLO_DIJKSTRA;
	g.goal[0] = 15;
	g.goal_mode = HYLO_MODE_MARINE;
	gl = enc_goal(&g, goal, sizeof goal);
	put(argv[1], "river-dijkstra-to-water", map, ml, goal, gl);
	gc.sampling.spacing = 4;
	gc.sampling.air_spacing = 6;
	gc.sampling.connect_radius = 9;
	gc.sampling.air_connect_radius = 12;
	ml = enc_map(&chasm, map, sizeof map);
	gl = enc_goal(&gc, goal, sizeof goal);
	put(argv[1], "chasm", map, ml, goal, gl);
	ml = enc_map(&di, map, sizeof map);
	gl = enc_goal(&gd, goal, sizeof goal);
	put(argv[1], "di", map, ml, goal, gl);
	g = gd;
	g.max_expansions = 5;
	gl = enc_goal(&g, goal, sizeof goal);
	put(argv[1], "di-budget", map, ml, goal, gl);
	di.robot = "nobody";
	ml = enc_map(&di, map, sizeof map);
	put(argv[1], "unknown-robot", map, ml, goal, gl);
	tu_map_free(&river);
	tu_map_free(&chasm);
	tu_map_free(&di);
	printf("%d corpus files in %s\n", n_written, argv[1]);
	return 0;
}
