/*
 * SVR evaluations per second on the synthetic 2,000-SV ground model:
 * libsvm's svm_predict (the reference) against hylo_svr_predict (one edge at
 * a time) and hylo_svr_predict_batch (the planner's path: all edges of one
 * expansion, whose features repeat across the head's speed/heading grid).
 * Medians of 7 runs. Writes a table to stdout and JSON rows to argv[1].
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

#define REPEATS 7
#define N_TAILS 40            /* expansions */
#define N_HEADS 25            /* neighbour positions per expansion */
#define N_SPEEDS 2
#define N_HEADINGS 8
#define N_EDGES (N_TAILS * N_HEADS * N_SPEEDS * N_HEADINGS)
#define PER_TAIL (N_HEADS * N_SPEEDS * N_HEADINGS)
#define NF HYLO_FEATURES_PLANAR
#define PI 3.14159265358979323846

static const hylo_svr_model *model = &hylo_model_synthetic_ground;
static double features[N_EDGES][NF];
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

/* Edges as the planner sees them: a tail state, head positions around it,
 * each crossed with the speed and heading grids. */
static void make_edges(void)
{
	static const double speeds[N_SPEEDS] = { 0.0, 1.0 };
	unsigned seed = 12345, t, h, s, k, e = 0;

	for (t = 0; t < N_TAILS; t++) {
		double tail[HYLO_XS_DIM] = { 0 };

		seed = seed * 1103515245u + 12345u;
		tail[0] = (seed >> 8) % 1000 * 0.1;
		tail[1] = (seed >> 4) % 600 * 0.1;
		tail[2] = speeds[t % N_SPEEDS];
		tail[3] = (t % N_HEADINGS) * (2 * PI / N_HEADINGS) - PI;
		for (h = 0; h < N_HEADS; h++) {
			double ang = 2 * PI * h / N_HEADS, r = 1.0 + 0.3 * (h % 20);
			for (s = 0; s < N_SPEEDS; s++)
				for (k = 0; k < N_HEADINGS; k++) {
					double head[HYLO_XS_DIM] = { 0 };

					head[0] = tail[0] + r * cos(ang);
					head[1] = tail[1] + r * sin(ang);
					head[2] = speeds[s];
					head[3] = k * (2 * PI / N_HEADINGS) - PI;
					hylo_features(HYLO_MODE_GROUND, tail, head, features[e++]);
				}
		}
	}
}

/* libsvm's model over the same arrays (pointers into them, nothing copied). */
static struct svm_node sv_nodes[HYLO_MODEL_SYNTHETIC_GROUND_N_SV][NF + 1];
static struct svm_node *sv_rows[HYLO_MODEL_SYNTHETIC_GROUND_N_SV];
static double coef_copy[HYLO_MODEL_SYNTHETIC_GROUND_N_SV];

static void make_libsvm(struct svm_model *sm, double *rho, double **coef_rows)
{
	uint32_t i, k;

	for (i = 0; i < model->n_sv; i++) {
		for (k = 0; k < NF; k++) {
			sv_nodes[i][k].index = (int)k + 1;
			sv_nodes[i][k].value = model->sv[i * NF + k];
		}
		sv_nodes[i][NF].index = -1;
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
	struct svm_node x[NF + 1];
	uint32_t e, k;

	for (e = 0; e < N_EDGES; e++) {
		for (k = 0; k < NF; k++) {
			x[k].index = (int)k + 1;
			x[k].value = (features[e][k] - model->feature_offset[k]) / model->feature_scale[k];
		}
		x[NF].index = -1;
		out_ref[e] = svm_predict(sm, x) * model->label_scale + model->label_offset;
	}
}

static void run_one(void)
{
	uint32_t e;

	for (e = 0; e < N_EDGES; e++)
		out_one[e] = hylo_svr_predict(model, features[e]);
}

static void run_batch(void)
{
	uint32_t t;

	hylo_svr_cache_reset(&cache);
	for (t = 0; t < N_TAILS; t++)
		if (hylo_svr_predict_batch(model, &cache, &features[t * PER_TAIL][0], PER_TAIL,
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

int main(int argc, char **argv)
{
	struct svm_model sm;
	double rho, *coef_rows[1];
	double t_ref[REPEATS], t_one[REPEATS], t_batch[REPEATS], r_ref, r_one, r_batch;
	double d_one, d_batch;
	FILE *f;
	int i;

	if (argc != 2 || argv[1][0] == '-') {  /* --help is not a file name */
		fprintf(stderr, "usage: %s RESULTS.json\n", argv[0]);
		return 2;
	}
	make_edges();
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

	printf("SVR evaluations per second, %u SVs x %d features, %d edges (%d expansions), "
	       "median of %d runs\n", (unsigned)model->n_sv, NF, N_EDGES, N_TAILS, REPEATS);
	printf("  %-34s %12.0f /s\n", "libsvm svm_predict (reference)", r_ref);
	printf("  %-34s %12.0f /s  %5.2fx  max rel diff %.1e\n", "hylo_svr_predict", r_one,
	       r_one / r_ref, d_one);
	printf("  %-34s %12.0f /s  %5.2fx  max rel diff %.1e  (cache hits %.0f%%)\n",
	       "hylo_svr_predict_batch", r_batch, r_batch / r_ref, d_batch,
	       100.0 * (double)cache.hits / (double)(cache.hits + cache.misses));
	if (d_one > 1e-9 || d_batch > 1e-9) {
		fprintf(stderr, "bench_svr: hylo and libsvm disagree (%.3g, %.3g)\n", d_one, d_batch);
		return 1;
	}
	f = fopen(argv[1], "w");
	if (!f) {
		perror(argv[1]);
		return 1;
	}
	fprintf(f, "[\n {\"name\": \"svr_evals_per_s_single\", \"value\": %.6g, \"unit\": \"1/s\", "
		   "\"reference\": \"libsvm svm_predict\", \"reference_value\": %.6g, \"ratio\": %.4g},\n",
		r_one, r_ref, r_one / r_ref);
	fprintf(f, " {\"name\": \"svr_evals_per_s_batch\", \"value\": %.6g, \"unit\": \"1/s\", "
		   "\"reference\": \"libsvm svm_predict\", \"reference_value\": %.6g, \"ratio\": %.4g}\n]\n",
		r_batch, r_ref, r_batch / r_ref);
	fclose(f);
	return 0;
}
