/*
 * A robot as the planner sees it: its modes, each mode's edge-cost model,
 * and the costs of switching between its two modes. The guard between the
 * modes follows from the pair: ground/marine -> shoreline, ground/flight ->
 * takeoff/landing points, di_neg/di_pos -> p = 0.
 */
#ifndef HYLO_ROBOT_H
#define HYLO_ROBOT_H

#include <stdint.h>
#include "hylo/status.h"
#include "hylo/svr.h"
#include "hylo/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/*
 * Edge-cost callback: costs of the n edges tail -> heads[i] in one mode.
 * tail and each heads[i] are sampled coordinates (HYLO_XS_DIM entries, only
 * the mode's first hylo_mode_dim() used). Writes cost[0 .. n). A cost must be
 * finite; the planner raises it to the mode's floor. Returns HYLO_OK or an
 * error with a reason. This is how exact trajectory optimization plugs in.
 */
typedef hylo_status (*hylo_cost_fn)(void *ctx, hylo_mode mode, const hylo_real *tail,
                                    const hylo_real (*heads)[HYLO_XS_DIM], uint32_t n,
                                    hylo_real *cost, hylo_reason *r);

/* The cost model of one mode: either an SVR (model != NULL; the planner
 * evaluates it with its own cache) or a callback. With neither, the robot is
 * known but cannot be planned for: plans say HYLO_E_NO_MODEL. */
typedef struct {
	hylo_mode mode;
	const hylo_svr_model *model;   /* built-in SVR evaluation, or NULL */
	hylo_cost_fn cost_fn;          /* used when model is NULL */
	void *cost_ctx;
	hylo_real cost_floor_per_m;    /* when model is NULL: every cost >= this * displacement ... */
	hylo_real cost_floor_j;        /* ... + this [J]; both >= 0 */
	hylo_real max_distance_m;      /* when model is NULL: longest edge the costs are valid for; 0 = any */
	/* Optional feasibility classifier (same format, decision >= 0: the
	 * trajectory optimization has a solution): edges it predicts infeasible
	 * are dropped. NULL: every edge is feasible. */
	const hylo_svr_model *feasibility;
} hylo_mode_model;

typedef struct {
	const char *name;              /* matched against map_t.robot */
	uint32_t n_modes;              /* 1 or 2 */
	hylo_mode_model modes[2];
	/* switch_cost[0]: modes[0] -> modes[1] (e.g. takeoff), switch_cost[1]:
	 * modes[1] -> modes[0] (e.g. landing) [J], >= 0. */
	hylo_real switch_cost[2];
	/* The body: a disc (ground, marine) or a sphere (flight, every attitude)
	 * of this radius round the robot's position [m], >= 0 (0: a point). The
	 * planner keeps it, plus the configured margin, clear of every hazard
	 * of the mode (hylo/clearance.h, hylo_planner_config.margin_m). */
	hylo_real body_radius_m;
} hylo_robot;

/**
 * Checks a robot description: name, 1-2 valid distinct modes, a known guard
 * for a pair, finite non-negative switch costs and floors, a finite
 * non-negative body radius, valid SVR models with the mode's feature count.
 */
hylo_status hylo_robot_check(const hylo_robot *robot, hylo_reason *r);

/** Index (0 or 1) of mode among the robot's modes, or -1. */
int hylo_robot_mode_index(const hylo_robot *robot, hylo_mode mode);

#ifdef __cplusplus
}
#endif

#endif
