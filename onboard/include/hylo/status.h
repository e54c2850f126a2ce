/*
 * Status codes (an action failed, and why) and planning outcomes (the search
 * ran; what it found) are kept apart. Every action returns hylo_status; 0 is
 * success. A readable reason with the details (which capacity, which value,
 * where) goes into a hylo_reason the caller passes.
 */
#ifndef HYLO_STATUS_H
#define HYLO_STATUS_H

#include <stddef.h>
#include "hylo/config.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum {
	HYLO_OK = 0,
	HYLO_E_NULL,            /* a required pointer argument was NULL */
	HYLO_E_BAD_VALUE,       /* NaN, infinity or out-of-range number */
	HYLO_E_BAD_MAP,         /* inconsistent map (sizes, resolution, unknown terrain class) */
	HYLO_E_NO_MAP,          /* planning requested before a map was set */
	HYLO_E_UNKNOWN_ROBOT,   /* the map names a robot the planner does not know */
	HYLO_E_NO_MODEL,        /* a mode of the robot has no cost model */
	HYLO_E_WRONG_MODE,      /* a state's mode is not one of the robot's modes */
	HYLO_E_OUTSIDE_DOMAIN,  /* a start or goal lies outside its mode's domain */
	HYLO_E_EMPTY_DOMAIN,    /* no part of the map belongs to any mode of the robot */
	HYLO_E_BAD_COST,        /* a cost callback returned NaN, infinity or failed */
	HYLO_E_MAP_MISMATCH,    /* the goal names a map other than the current one */
	HYLO_E_CAP_CELLS,       /* map larger than HYLO_MAX_CELLS */
	HYLO_E_CAP_POSITIONS,   /* more sampled positions than HYLO_MAX_POSITIONS */
	HYLO_E_CAP_NODES,       /* more graph nodes than HYLO_MAX_NODES */
	HYLO_E_CAP_ADJACENCY,   /* more neighbour pairs than HYLO_MAX_ADJACENCY */
	HYLO_E_CAP_GRID,        /* a sampling grid longer than HYLO_MAX_GRID */
	HYLO_E_CAP_COMBOS,      /* more combinations per position than HYLO_MAX_COMBOS */
	HYLO_E_CAP_SUCCESSORS,  /* a node with more successors than HYLO_MAX_SUCCESSORS */
	HYLO_E_CAP_WAYPOINTS,   /* a path longer than HYLO_MAX_WAYPOINTS */
	HYLO_E_CAP_BUCKETS,     /* spatial grid needs more than HYLO_MAX_BUCKETS */
	HYLO_E_CAP_SV,          /* a model with more than HYLO_MAX_SV support vectors or HYLO_MAX_FEATURES features */
	HYLO_E_CAP_ROBOTS,      /* more robots than HYLO_MAX_ROBOTS */
	HYLO_STATUS_COUNT
} hylo_status;

/* Outcome of a search that ran. */
typedef enum {
	HYLO_FOUND = 0,             /* a path was found; it is optimal on the graph */
	HYLO_NO_PATH,               /* the goal is unreachable in the graph */
	HYLO_BUDGET_EXHAUSTED,      /* the time or expansion budget ran out before any path was found */
	HYLO_FOUND_UNPROVEN,        /* the budget ran out after a path was found: the best found,
	                             * not proven optimal (the plan gives a lower bound when known) */
	HYLO_OUTCOME_COUNT
} hylo_outcome;

/* Short fixed name of a status ("ok", "capacity exceeded: nodes", ...);
 * "unknown status" when out of range. Never NULL. */
const char *hylo_status_str(hylo_status s);

/* Name of an outcome ("found", "no path", "budget exhausted"). Never NULL. */
const char *hylo_outcome_str(hylo_outcome o);

/* A readable reason for the last failure, filled by the module that failed. */
typedef struct {
	char text[HYLO_REASON_LEN];
} hylo_reason;

/* Writes a printf-style reason into r (truncating) and returns s, so that
 * `return hylo_fail(r, HYLO_E_BAD_VALUE, "goal x is %g", x);` reads well.
 * r may be NULL. Does not allocate. */
hylo_status hylo_fail(hylo_reason *r, hylo_status s, const char *fmt, ...)
#if defined(__GNUC__)
	__attribute__((format(printf, 3, 4)))
#endif
	;

/* Sets r to "ok". r may be NULL. */
void hylo_reason_clear(hylo_reason *r);

#ifdef __cplusplus
}
#endif

#endif
