/*
 * SVR evaluations per second: libsvm's svm_predict (the reference) against
 * hylo_svr_predict (one edge at a time) and hylo_svr_predict_batch (the
 * planner's path: all edges of one expansion, whose features repeat across
 * the head's speed/heading grid), on the synthetic 2,000-SV ground model and
 * on every committed model (onboard/models/, through the node's registry).
 * Edges are shaped like the planner's for each mode. Medians of 7 runs.
 * Writes a table to stdout and JSON rows to argv[1].
 */
#include <libsvm/svm.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench/synthetic_ground.h"
#include "hylo/features.h"
#include "hylo/svr.h"
#include "node/registry.h"

#define REPEATS 7
#define N_TAILS 40            /* expansions */
#define N_HEADS 25            /* neighbour positions per expansion */
#define N_SPEEDS 2
#define N_HEADINGS 8
#define N_EDGES (N_TAILS * N_HEADS * N_SPEEDS * N_HEADINGS)
#define PER_TAIL (N_HEADS * N_SPEEDS * N_HEADINGS)
#define PI 3.14159265358979323846

static const hylo_svr_model *model;
static unsigned nf;
static double features[N_EDGES][HYLO_MAX_FEATURES];
static double out_ref[N_EDGES], out_one[N_EDGES], out_batch[N_EDGES];
static hylo_svr_cache cache;

static double now_s(void)
{
	struct timespec t;

	clock_gettime(CLOCK_MONOTONIC, &t);
	return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static int cmp_double(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;

	return (x > y) - (x < y);
}

static double median(double *v, int n)
{
	qsort(v, (size_t)n, sizeof *v, cmp_double);
	return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

static double uniform(unsigned *seed, double lo, double hi)
{
	*seed = *seed * 1103515245u + 12345u;
	return lo + (hi - lo) * (double)((*seed >> 8) % 100000u) / 100000.0;
}

/* Edges as the planner sees them in mode: a tail state, head positions
 * around it (up to the model's reach), each crossed with a grid of speeds
 * and headings (flight: velocities; the double integrator: its heads are
 * distinct phase-plane points). */
static void make_edges(hylo_mode mode)
{
	static const double speeds[N_SPEEDS] = { 0.0, 1.0 };
	double reach = model->max_distance_m > 0 ? model->max_distance_m : 5.0;
	unsigned seed = 12345, t, h, s, k, e = 0;

	nf = hylo_feature_count(mode);
	for (t = 0; t < N_TAILS; t++) {
		double tail[HYLO_XS_DIM] = { 0 }, side = mode == HYLO_MODE_DI_NEG ? -1.0 : 1.0;

		tail[0] = uniform(&seed, 0, 100);
		tail[1] = uniform(&seed, 0, 60);
		tail[2] = mode == HYLO_MODE_FLIGHT ? uniform(&seed, 1, 10) : speeds[t % N_SPEEDS];
		tail[3] = (t % N_HEADINGS) * (2 * PI / N_HEADINGS) - PI;
		if (mode == HYLO_MODE_FLIGHT)
			tail[3] = speeds[t % N_SPEEDS];
		if (mode == HYLO_MODE_DI_NEG || mode == HYLO_MODE_DI_POS) {
			tail[0] = side * uniform(&seed, 0, 1);
			tail[1] = uniform(&seed, -1, 1);
		}
		for (h = 0; h < N_HEADS; h++) {
			double ang = 2 * PI * h / N_HEADS, r = reach * (0.2 + 0.8 * (h % 20) / 19.0);

			for (s = 0; s < N_SPEEDS; s++)
				for (k = 0; k < N_HEADINGS; k++) {
					double head[HYLO_XS_DIM] = { 0 }, hk = k * (2 * PI / N_HEADINGS);

					head[0] = tail[0] + r * cos(ang);
					head[1] = tail[1] + r * sin(ang);
					head[2] = speeds[s];
					head[3] = hk - PI;
					if (mode == HYLO_MODE_FLIGHT) {  /* (p, v): a velocity grid */
						head[2] = tail[2] + 0.5 * r * cos(ang + 1.0);
						head[3] = speeds[s] * cos(hk);
						head[4] = speeds[s] * sin(hk);
						head[5] = 0.5 * speeds[s];
					}
					if (mode == HYLO_MODE_DI_NEG || mode == HYLO_MODE_DI_POS) {
						head[0] = side * uniform(&seed, 0, 1);
						head[1] = uniform(&seed, -1, 1);
					}
					hylo_features(mode, tail, head, features[e++]);
				}
		}
	}
}

/* libsvm's model over a copy of the same numbers. */
static struct svm_node sv_nodes[HYLO_MAX_SV][HYLO_MAX_FEATURES + 1];
static struct svm_node *sv_rows[HYLO_MAX_SV];
static double coef_copy[HYLO_MAX_SV];

static void make_libsvm(struct svm_model *sm, double *rho, double **coef_rows)
{
	uint32_t i, k;

	for (i = 0; i < model->n_sv; i++) {
		for (k = 0; k < nf; k++) {
			sv_nodes[i][k].index = (int)k + 1;
			sv_nodes[i][k].value = model->sv[i * nf + k];
		}
		sv_nodes[i][nf].index = -1;
		sv_rows[i] = sv_nodes[i];
		coef_copy[i] = model->coef[i];
	}
	memset(sm, 0, sizeof *sm);
	sm->param.svm_type = EPSILON_SVR;
	sm->param.kernel_type = RBF;
	sm->param.gamma = model->gamma;
	sm->nr_class = 2;
	sm->l = (int)model->n_sv;
	sm->SV = sv_rows;
	*rho = model->rho;
	coef_rows[0] = coef_copy;
	sm->sv_coef = coef_rows;
	sm->rho = rho;
}

static void run_libsvm(const struct svm_model *sm)
{
	struct svm_node x[HYLO_MAX_FEATURES + 1];
	uint32_t e, k;

	for (e = 0; e < N_EDGES; e++) {
		double y;

		for (k = 0; k < nf; k++) {
			x[k].index = (int)k + 1;
			x[k].value = (features[e][k] - model->feature_offset[k]) / model->feature_scale[k];
		}
		x[nf].index = -1;
		y = svm_predict(sm, x) * model->label_scale + model->label_offset;
		out_ref[e] = model->label_log ? exp(y) : y;
	}
}

static void run_one(void)
{
	uint32_t e;

	for (e = 0; e < N_EDGES; e++)
		out_one[e] = hylo_svr_predict(model, features[e]);
}

static double packed[N_EDGES * HYLO_MAX_FEATURES];  /* rows of nf, as the API reads them */

static void run_batch(void)
{
	uint32_t t;

	hylo_svr_cache_reset(&cache);
	for (t = 0; t < N_TAILS; t++)
		if (hylo_svr_predict_batch(model, &cache, &packed[t * PER_TAIL * nf], PER_TAIL,
					   &out_batch[t * PER_TAIL]) != HYLO_OK) {
			fprintf(stderr, "bench_svr: batch evaluation failed\n");
			exit(1);
		}
}

static double max_rel_diff(const double *a, const double *b)
{
	double worst = 0;
	int e;

	for (e = 0; e < N_EDGES; e++) {
		double d = fabs(a[e] - b[e]) / fmax(fabs(b[e]), 1e-12);

		worst = d > worst ? d : worst;
	}
	return worst;
}

static FILE *json;
static int n_rows;

static void row(const char *name, double value, double ref)
{
	fprintf(json, "%s {\"name\": \"%s\", \"value\": %.6g, \"unit\": \"1/s\", "
		      "\"reference\": \"libsvm svm_predict\", \"reference_value\": %.6g, "
		      "\"ratio\": %.4g}", n_rows++ ? ",\n" : "", name, value, ref, value / ref);
}

/* Benchmarks m in mode; suffix names its JSON rows. Returns 0, or 1 when
 * hylo and libsvm disagree. */
static int bench(const hylo_svr_model *m, hylo_mode mode, const char *suffix)
{
	struct svm_model sm;
	double rho, *coef_rows[1];
	double t_ref[REPEATS], t_one[REPEATS], t_batch[REPEATS], r_ref, r_one, r_batch;
	double d_one, d_batch;
	char name[128];
	uint32_t e, k;
	int i;

	model = m;
	free(cache.mem);
	hylo_svr_cache_attach(&cache, malloc(hylo_svr_cache_size(m)), hylo_svr_cache_size(m));
	if (!cache.mem) {
		fprintf(stderr, "bench_svr: cannot allocate the SVR cache\n");
		exit(1);
	}
	make_edges(mode);
	for (e = 0; e < N_EDGES; e++)
		for (k = 0; k < nf; k++)
			packed[e * nf + k] = features[e][k];
	make_libsvm(&sm, &rho, coef_rows);
	for (i = 0; i < REPEATS; i++) {
		double t0 = now_s();

		run_libsvm(&sm);
		t_ref[i] = now_s() - t0;
		t0 = now_s();
		run_one();
		t_one[i] = now_s() - t0;
		t0 = now_s();
		run_batch();
		t_batch[i] = now_s() - t0;
	}
	d_one = max_rel_diff(out_one, out_ref);
	d_batch = max_rel_diff(out_batch, out_ref);
	r_ref = N_EDGES / median(t_ref, REPEATS);
	r_one = N_EDGES / median(t_one, REPEATS);
	r_batch = N_EDGES / median(t_batch, REPEATS);

	printf("%s: %u SVs x %u features, %d edges (%d expansions), median of %d runs\n",
	       m->name, (unsigned)m->n_sv, nf, N_EDGES, N_TAILS, REPEATS);
	printf("  %-34s %12.0f /s\n", "libsvm svm_predict (reference)", r_ref);
	printf("  %-34s %12.0f /s  %5.2fx  max rel diff %.1e\n", "hylo_svr_predict", r_one,
	       r_one / r_ref, d_one);
	printf("  %-34s %12.0f /s  %5.2fx  max rel diff %.1e  (cache hits %.0f%%)\n",
	       "hylo_svr_predict_batch", r_batch, r_batch / r_ref, d_batch,
	       100.0 * (double)cache.hits / (double)(cache.hits + cache.misses));
	if (d_one > 1e-9 || d_batch > 1e-9) {
		fprintf(stderr, "bench_svr: %s: hylo and libsvm disagree (%.3g, %.3g)\n", m->name,
			d_one, d_batch);
		return 1;
	}
	snprintf(name, sizeof name, "svr_evals_per_s_single%s", suffix);
	row(name, r_one, r_ref);
	snprintf(name, sizeof name, "svr_evals_per_s_batch%s", suffix);
	row(name, r_batch, r_ref);
	return 0;
}

int main(int argc, char **argv)
{
	uint32_t k;
	int bad;

	if (argc != 2 || argv[1][0] == '-') {  /* --help is not a file name */
		fprintf(stderr, "usage: %s RESULTS.json\n", argv[0]);
		return 2;
	}
	json = fopen(argv[1], "w");
	if (!json) {
		perror(argv[1]);
		return 1;
	}
	fprintf(json, "[\n");
	bad = bench(&hylo_model_synthetic_ground, HYLO_MODE_GROUND, "");
	for (k = 0; k < hylo_registry_n_models; k++) {
		const hylo_registry_model *r = &hylo_registry_models[k];
		char suffix[96];

		snprintf(suffix, sizeof suffix, "_%s", r->model->name);
		bad |= bench(r->model, r->mode, suffix);
	}
	fprintf(json, "\n]\n");
	fclose(json);
	return bad;
}
