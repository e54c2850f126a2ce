/*
 * Support-vector regression cost models (libsvm epsilon-SVR, RBF kernel).
 *
 * A model is plain constant data: the trainer exports each one as a C header
 * (onboard/models/<robot>_<mode>.h, format in onboard/models/README.md) that
 * defines `static const` arrays and one `static const hylo_svr_model`.
 *
 * Prediction of a raw feature vector x (n_features):
 *   z_k  = (x_k - feature_offset[k]) / feature_scale[k]
 *   d    = sum_i coef[i] * exp(-gamma * |z - sv_i|^2) - rho   (libsvm's decision value)
 *   y    = d * label_scale + label_offset
 *   cost = label_log ? exp(y) : y
 * The planner then raises the cost to at least cost_floor_j + cost_floor_per_m
 * times the edge's displacement (so to at least 0), counting how often it does.
 */
#ifndef HYLO_SVR_H
#define HYLO_SVR_H

#include <stdint.h>
#include "hylo/config.h"
#include "hylo/status.h"
#include "hylo/types.h"

/*
 * The model-header format this library reads (onboard/models/README.md).
 * Every exported header states the format it was written in,
 * HYLO_MODEL_<NAME>_FORMAT_VERSION, and stops the compilation with an #error
 * naming both when they differ (or when this macro is missing: a library
 * older than format versions). The trainer writes this format. Bump it with
 * any change to hylo_svr_model, hylo_svr_envelope or the header's layout
 * that makes an older header mean something else, and regenerate the models.
 */
#define HYLO_MODEL_FORMAT_VERSION 2

#ifdef __cplusplus
extern "C" {
#endif

/*
 * A cost model's envelope (onboard/models/README.md, "Envelope"): a table of
 * lower bounds of the model's predicted cost (hylo_svr_predict, before the
 * planner's floor) that depend only on an edge's distance, its turn (ground,
 * marine) or climb (flight) and its speeds, each the least predicted cost
 * over every heading / velocity direction of the edges in its cell, minus a
 * measured margin. The planner's A* uses it as an admissible edge bound far
 * tighter than the per-metre floor.
 *   distance cell k: [k d_step, (k+1) d_step), k < n_d
 *   climb cell j:    [z_min + j z_step, z_min + (j+1) z_step), j < n_z
 *                    flight: the climb [m]; ground and marine: the turn
 *                    (hylo_envelope_turn) [rad], z_min = 0 and n_z z_step =
 *                    2 pi, the last cell closed (it holds 2 pi), each cell
 *                    also holding turns within 1e-9 rad of its ends (the
 *                    features' turn may differ from hylo_envelope_turn's in
 *                    the last bits); n_z = 1: the climb or turn is ignored
 *   speed node i:    v_min + i v_step, i < n_v
 *   value[((k * n_z + j) * n_v + i1) * n_v + i2] [J]: the bound for tail
 *   speed node i1 and head speed node i2.
 * Speeds as hylo_envelope_args() measures them (ground and marine vx,
 * flight the horizontal |v|). Values are floats, exactly representable in
 * double, so the lookup needs no libm and gives the same bits everywhere.
 */
typedef struct {
	uint32_t n_d, n_z, n_v;        /* distance, climb (turn) cells, speed nodes; each >= 1 */
	double d_step;                 /* distance cell width [m], > 0 */
	double z_min, z_step;          /* climb [m] or turn [rad] cells; z_step > 0 when n_z > 1 */
	double v_min, v_step;          /* speed nodes [m/s]; v_step > 0 */
	const float *value;            /* n_d * n_z * n_v * n_v bounds [J], finite, >= 0 */
} hylo_svr_envelope;

typedef struct {
	const char *name;              /* "<robot>_<mode>", a C identifier */
	uint32_t n_sv;                 /* support vectors, <= HYLO_MAX_SV */
	uint32_t n_features;           /* features, <= HYLO_MAX_FEATURES */
	double gamma;                  /* RBF kernel width, > 0 */
	double rho;                    /* libsvm's rho[0] */
	const double *sv;              /* n_sv x n_features, row-major, standardized units */
	const double *coef;            /* n_sv, libsvm's sv_coef[0] */
	const double *feature_offset;  /* n_features */
	const double *feature_scale;   /* n_features, each > 0 */
	double label_offset;           /* y = d * label_scale + label_offset */
	double label_scale;            /* > 0 */
	int label_log;                 /* 1: cost = exp(y); 0: cost = y */
	double cost_floor_per_m;       /* every true cost is >= this * displacement [J/m] ... */
	double cost_floor_j;           /* ... + this [J] (e.g. drain power * shortest time), >= 0 */
	double max_distance_m;         /* training displacements reach this far [m]; 0 = any */
	double speed_min_mps;          /* training speeds span [speed_min_mps, speed_max_mps] */
	double speed_max_mps;          /* (hylo_state_speed); both 0 = any */
	/* The rest of the trained region (hylo/region.h): bit k set: sampled
	 * coordinate k of both states of every training pair lay in
	 * [state_min[k], state_max[k]] (e.g. flight vz in [0, 0]: level
	 * velocities only); clear: that coordinate was not restricted (or the
	 * features do not see it: positions). 0: no such bounds. */
	uint32_t state_bounded;
	double state_min[HYLO_XS_DIM];
	double state_max[HYLO_XS_DIM];
	const char *provenance;        /* samples, seed, hashes, errors, version; may be NULL */
	const hylo_svr_envelope *envelope;  /* NULL: none (the double integrator, classifiers) */
	/* Flight only (else NULL): a second table by horizontal distance and
	 * turn (hylo_envelope_flight_turn: how far both velocities point away
	 * from the displacement) instead of climb, each value the least
	 * predicted cost over every climb within max_distance_m; envelope's
	 * distance cells and speed nodes, n_z turn cells over [0, 2 pi] as a
	 * planar table's. The planner takes the larger of the two bounds. */
	const hylo_svr_envelope *turn_envelope;
} hylo_svr_model;

/**
 * Checks a model: non-NULL arrays, sizes within capacity (HYLO_E_CAP_SV),
 * finite numbers, positive gamma and scales (HYLO_E_BAD_VALUE); and its
 * envelope, if any: only on a planar (8 features) or flight (9) model,
 * every count >= 1 and n_d * n_z * n_v * n_v below 2^32, steps finite and
 * > 0 (z_step only when n_z > 1), a planar table's turn cells (n_z > 1)
 * covering [0, 2 pi] (z_min = 0, n_z z_step = 2 pi to 1e-12 relative), every
 * value finite and >= 0
 * (HYLO_E_BAD_VALUE; a NULL value array: HYLO_E_NULL). O(n_sv * n_features
 * + envelope values). No allocation.
 */
hylo_status hylo_svr_check(const hylo_svr_model *m, hylo_reason *r);

/**
 * libsvm's decision value for standardized features z (n_features):
 * sum_i coef[i] * exp(-gamma*|z - sv_i|^2) - rho, summed in SV order exactly
 * as svm_predict does. No allocation; O(n_sv * n_features).
 */
double hylo_svr_decision(const hylo_svr_model *m, const double *z);

/**
 * Cost for raw features x (n_features): standardize, decision value, label
 * transform. Not clamped. No allocation; safe in a control loop.
 */
double hylo_svr_predict(const hylo_svr_model *m, const double *x);

/** 1 when speed (hylo_state_speed) lies in m's training speed range (to
 * 1e-9 relative), or m declares none (both bounds 0); 0 otherwise, and for
 * NaN. */
int hylo_svr_speed_trained(const hylo_svr_model *m, double speed);

/**
 * m's envelope bound [J] for an edge of horizontal distance d [m], climb dz
 * [m] (flight) or turn dz [rad] (ground, marine; ignored when the envelope
 * has one climb cell) and tail and head speeds v1, v2 [m/s]
 * (hylo_envelope_args() computes these from two sampled states): the table
 * value of the cell holding (d, dz) for the speed nodes
 * v1 and v2, a lower bound of hylo_svr_predict for every such edge. A speed
 * within 1e-9 m/s of a node uses that node; a speed between two nodes uses
 * the least value over the bracketing nodes, which is NOT a guaranteed bound
 * (the model's cost between nodes is not bounded by its values at them).
 * Returns 0 ("no envelope": the planner keeps its floor) when m is NULL or
 * has no envelope, and when d, dz or a speed is outside the table or NaN.
 * No libm, no allocation, O(1); safe in a control loop. Same bits on every
 * target.
 */
double hylo_svr_envelope_bound(const hylo_svr_model *m, double d, double dz, double v1,
                               double v2);

/*
 * The same lookup in its three parts, for callers that look up many edges
 * sharing a distance or speeds (the planner): the speed nodes of a speed
 * (0: none), the cell of a distance and climb or turn (0: outside), and the
 * value of a cell for two speeds' nodes. hylo_svr_envelope_bound() is
 * exactly hylo_svr_envelope_value() of the other two. No allocation; safe
 * in a control loop.
 */
int hylo_svr_envelope_speed(const hylo_svr_model *m, double v, uint32_t nodes[2]);
int hylo_svr_envelope_cell(const hylo_svr_model *m, double d, double dz, size_t *cell);
double hylo_svr_envelope_value(const hylo_svr_model *m, size_t cell, const uint32_t tail[2],
                               const uint32_t head[2]);

/*
 * The turn table's bound (turn_envelope, flight models) for a flight edge of
 * horizontal distance d [m], climb dz [m], turn [rad]
 * (hylo_envelope_flight_turn) and tail and head horizontal speeds v1, v2:
 * as hylo_svr_envelope_bound(), and 0 (no bound) also when m has no turn
 * table or d^2 + dz^2 > max_distance_m^2. Its parts as above: the cell of
 * a distance and turn (0: none; the climb only decides whether there is
 * one) and its value for two speeds' nodes (the speed nodes are the
 * envelope's). No libm, no allocation; safe in a control loop.
 */
double hylo_svr_turn_envelope_bound(const hylo_svr_model *m, double d, double dz, double turn,
                                    double v1, double v2);
int hylo_svr_turn_envelope_cell(const hylo_svr_model *m, double d, double dz, double turn,
                                size_t *cell);
double hylo_svr_turn_envelope_value(const hylo_svr_model *m, size_t cell, const uint32_t tail[2],
                                    const uint32_t head[2]);

/** The floor the planner raises m's prediction for an edge of length
 * distance_m to: cost_floor_j + cost_floor_per_m * distance_m [J]. */
double hylo_svr_cost_floor(const hylo_svr_model *m, double distance_m);

/*
 * Batch evaluation for a search expansion: the planner evaluates many edges
 * from one tail, whose features repeat values (the tail's speed, a head
 * position's displacement and heading shared by its speeds, the grid of head
 * speeds). The RBF kernel factorizes over groups G of features,
 *   exp(-gamma*|z - s|^2) = prod_G exp(-gamma*|z_G - s_G|^2),
 * the groups being what changes together: planar (vx1), (the displacement
 * and heading: dx', |dy'|, s*dtheta, d, turn, arc), (vx2); flight (v1),
 * (dp), (v2); the double integrator (p1, v1), (p2, v2). The cache keeps, per
 * group, the factor vectors (one value per SV) of the last
 * HYLO_SVR_CACHE_VALUES distinct values seen. It also keeps the running
 * products coef_i * f_G0 * f_G1 * ... of the previous prediction in that
 * group order (tail first, then the head's pose, then its speed), so that an
 * edge differing from a recent one only in its head speed or heading costs
 * one or two multiplications per SV, and a new head pose one exponential
 * per SV. The product order is fixed, so results do not depend on what was
 * evaluated before.
 */
typedef struct {
	const hylo_svr_model *model;   /* the cache is valid for this model only */
	uint32_t n_groups;
	uint32_t order[HYLO_MAX_FEATURES];            /* features, grouped */
	uint32_t group_begin[HYLO_MAX_FEATURES + 1];  /* group g: order[begin[g] .. begin[g+1]) */
	uint32_t n_used[HYLO_MAX_FEATURES];           /* per group */
	uint32_t clock;                /* for least-recently-used replacement */
	uint32_t last_use[HYLO_MAX_FEATURES][HYLO_SVR_CACHE_VALUES];
	double value[HYLO_MAX_FEATURES][HYLO_SVR_CACHE_VALUES][HYLO_MAX_FEATURES];
	uint32_t n_prefix;             /* valid running-product levels (groups) */
	double prefix_value[HYLO_MAX_FEATURES];  /* the features of those levels, in order */
	uint64_t hits, misses;         /* statistics */
	/* The caller's memory (hylo_svr_cache_attach), laid out for the model:
	 * factor rows [group][value][sv], the SVs feature-major [feature][sv],
	 * running products [group][sv]. */
	double *mem;
	size_t mem_doubles;
	double *factor;
	double *sv_col;
	double *prefix;
} hylo_svr_cache;

/** Bytes of memory a cache needs for model m (sized by its support vectors
 * and feature groups); 0 for NULL. */
size_t hylo_svr_cache_size(const hylo_svr_model *m);

/**
 * Gives cache c its memory: mem (aligned for double) of bytes bytes, enough
 * for any model whose hylo_svr_cache_size is at most bytes. Empties the
 * cache. No allocation.
 */
void hylo_svr_cache_attach(hylo_svr_cache *c, double *mem, size_t bytes);

/** Empties the cache (its memory stays attached). */
void hylo_svr_cache_reset(hylo_svr_cache *c);

/**
 * Costs of n raw feature vectors x (n x n_features, row-major) into cost[n],
 * each equal to hylo_svr_predict to within about 1e-14 relative. Resets the
 * cache itself when c->model differs from m. Errors: HYLO_E_NULL,
 * HYLO_E_CAP_SV (the cache's memory is too small for m). No allocation.
 */
hylo_status hylo_svr_predict_batch(const hylo_svr_model *m, hylo_svr_cache *c,
                                   const double *x, uint32_t n, double *cost);

#ifdef __cplusplus
}
#endif

#endif
