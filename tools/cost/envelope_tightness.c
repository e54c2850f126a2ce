/*
 * hylo-envelope-tightness: how close each compiled-in model's envelope
 * (onboard/models/README.md, "Envelope") and its classic floor come to the
 * model's predicted cost. For N seeded random edges per ground, marine and
 * flight model (random positions and headings, distances up to
 * max_distance_m, flight climbs within that ball and level velocities of
 * any direction, speeds on the table's nodes), for as many with the
 * headings aligned (ground, marine: the goal straight ahead with the
 * start's heading; flight: both velocities along the horizontal
 * displacement) and for as many that turn round (ground, marine: the goal
 * within 10 degrees of straight behind the start, the goal's heading
 * random; flight: the start's velocity within 10 degrees of pointing away
 * from the horizontal displacement, the goal's random), prints the 10th,
 * 50th and 90th percentiles of envelope / cost and floor / cost, the least
 * cost / envelope, and the table's size. See --help. Exit codes: 0
 * printed, 1 a model without an envelope or an edge below it, 2 usage
 * error.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hylo/envelope.h"
#include "hylo/features.h"
#include "node/registry.h"
#include "random_edge.h"

#define MAX_EDGES 1000000

static const char *kind_name[] = { "random", "aligned", "turning" };

static int compare(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;

	return x < y ? -1 : x > y;
}

static double quantile(double *v, int n, double q)
{
	return v[(int)(q * (n - 1) + 0.5)];
}

static double env_ratio[MAX_EDGES], floor_ratio[MAX_EDGES];

/* Returns the number of edges below the envelope. */
static int measure(const hylo_registry_model *r, enum edge_kind kind, int n, uint64_t seed)
{
	const hylo_svr_model *m = r->model;
	double least = INFINITY;
	int i, below = 0;

	rng_state = seed;
	for (i = 0; i < n; i++) {
		double t[HYLO_XS_DIM], h[HYLO_XS_DIM], f[HYLO_MAX_FEATURES], a[4], cost, env;

		random_edge(m, r->mode, kind, t, h);
		hylo_features(r->mode, t, h, f);
		cost = hylo_svr_predict(m, f);
		env = hylo_envelope_of_edge(m, r->mode, t, h);
		hylo_envelope_args(r->mode, t, h, a);
		env_ratio[i] = env / cost;
		floor_ratio[i] = hylo_svr_cost_floor(m, r->mode == HYLO_MODE_FLIGHT ? hypot(a[0], a[1]) : a[0]) / cost;
		below += cost < env;
		if (cost / env < least)
			least = cost / env;
	}
	qsort(env_ratio, (size_t)n, sizeof env_ratio[0], compare);
	qsort(floor_ratio, (size_t)n, sizeof floor_ratio[0], compare);
	printf("  %-8s envelope/cost p10 %.4f  median %.4f  p90 %.4f | floor/cost p10 %.4f  median %.4f  "
	       "p90 %.4f | least cost/envelope %.6f, %d below\n",
	       kind_name[kind], quantile(env_ratio, n, 0.1), quantile(env_ratio, n, 0.5),
	       quantile(env_ratio, n, 0.9), quantile(floor_ratio, n, 0.1), quantile(floor_ratio, n, 0.5),
	       quantile(floor_ratio, n, 0.9), least, below);
	return below;
}

static void usage(FILE *f)
{
	fprintf(f, "usage: hylo-envelope-tightness [--edges N] [--seed S]\n"
		   "Envelope / cost and floor / cost over N random edges (default 100000, at most\n"
		   "1000000), N aligned ones and N that turn round (the goal behind the start) per\n"
		   "ground, marine and flight model compiled in.\n");
}

int main(int argc, char **argv)
{
	int n = 100000, i, bad = 0;
	uint64_t seed = 7;
	uint32_t k;

	for (i = 1; i < argc; i++) {
		if (strcmp(argv[i], "--edges") == 0 && i + 1 < argc) {
			n = atoi(argv[++i]);
		} else if (strcmp(argv[i], "--seed") == 0 && i + 1 < argc) {
			seed = strtoull(argv[++i], NULL, 10);
		} else if (strcmp(argv[i], "--help") == 0) {
			usage(stdout);
			return 0;
		} else {
			usage(stderr);
			return 2;
		}
	}
	if (n < 1 || n > MAX_EDGES) {
		usage(stderr);
		return 2;
	}
	for (k = 0; k < hylo_registry_n_models; k++) {
		const hylo_registry_model *r = &hylo_registry_models[k];
		const hylo_svr_envelope *e = r->model->envelope;

		if (r->mode == HYLO_MODE_DI_NEG || r->mode == HYLO_MODE_DI_POS)
			continue;
		if (!e) {
			printf("%s: no envelope\n", r->model->name);
			bad = 1;
			continue;
		}
		printf("%s: %u x %u x %u cells (distance %.3g m, %s %.3g %s, speed %.3g m/s), %u floats, "
		       "%u bytes; %d edges each\n",
		       r->model->name, e->n_d, e->n_z, e->n_v, e->d_step,
		       r->mode == HYLO_MODE_FLIGHT ? "climb" : "turn", e->z_step,
		       r->mode == HYLO_MODE_FLIGHT ? "m" : "rad", e->v_step,
		       e->n_d * e->n_z * e->n_v * e->n_v, (unsigned)(e->n_d * e->n_z * e->n_v * e->n_v * sizeof(float)),
		       n);
		bad |= measure(r, EDGE_RANDOM, n, seed) > 0;
		bad |= measure(r, EDGE_ALIGNED, n, seed + 1) > 0;
		bad |= measure(r, EDGE_TURNING, n, seed + 2) > 0;
	}
	return bad;
}
