/*
 * What a picture is made of: the map, the plan, the goal that asked for it
 * (its sampling options rebuild the roadmap's nodes and edges), the plan's
 * alternatives (other mode sequences, goal_t.alternatives), the smoothed
 * trajectory and an optional baseline trajectory, read from LCM logs or
 * from a live bus.
 */
#ifndef HYLO_RENDER_INPUT_H
#define HYLO_RENDER_INPUT_H

#include <stddef.h>
#include <stdint.h>
#include "hylo_goal_t.h"
#include "hylo/config.h"
#include "hylo_map_t.h"
#include "hylo_plan_alternative_t.h"
#include "hylo_plan_t.h"
#include "hylo_traj_t.h"

typedef struct {
	const char *prefix;       /* channel prefix */
	int64_t request_id;       /* plan to draw; -1: the last one */
	int want_plan;            /* 0: draw the map alone (--map-only) */
	int want_alternatives;    /* 0: leave the plan's alternatives out (--no-alternatives) */
} input_options;

/* Alternatives drawn for one plan: as many as the planner can return. */
#define INPUT_MAX_ALTERNATIVES HYLO_MAX_ALTERNATIVES

typedef struct {
	hylo_map_t *map;          /* NULL until found */
	hylo_goal_t *goal;        /* the plan's goal, or NULL */
	hylo_plan_t *plan;        /* NULL with --map-only */
	hylo_traj_t *traj;        /* smoothed trajectory of the plan, or NULL */
	hylo_traj_t *baseline;    /* channel <prefix>HYLO_BASELINE, or NULL */
	/* the plan's alternatives by index (0: the plan itself), NULL where none
	 * arrived; n_alternatives = their count (0: none) */
	const hylo_plan_alternative_t *alternative[INPUT_MAX_ALTERNATIVES];
	int n_alternatives;
	/* everything seen, kept until selection */
	hylo_map_t **maps;
	hylo_goal_t **goals;
	hylo_plan_t **plans;
	hylo_plan_alternative_t **alts;
	hylo_traj_t **trajs, **baselines;
	int n_maps, n_goals, n_plans, n_alts, n_trajs, n_baselines;
	int n_undecodable;        /* messages on our channels that did not decode */
} input_set;

/* Reads every event of an LCM log file. Returns 0, or -1 with err set. */
int input_read_log(input_set *in, const input_options *o, const char *path,
                   char *err, size_t errlen);

/* Listens on a bus until a plan (or with --map-only a map) has arrived,
 * then a grace period for its trajectory; gives up after timeout_s. */
int input_listen(input_set *in, const input_options *o, const char *url, double timeout_s,
                 char *err, size_t errlen);

/* Picks the map, plan, goal, alternatives and trajectories to draw. Errors:
 * no map, no plan, plan for a map that is not there, alternatives that do
 * not fit the plan or INPUT_MAX_ALTERNATIVES. Returns 0 or -1 with err set. */
int input_select(input_set *in, const input_options *o, char *err, size_t errlen);

void input_free(input_set *in);

#endif
