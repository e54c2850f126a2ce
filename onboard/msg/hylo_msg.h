/*
 * Conversion between decoded LCM messages (msgs/, generated C types) and the
 * planning core's views. Lives outside the core so that the core needs no
 * LCM header; nothing here allocates: views point into the message, and a
 * plan message points into the caller's hylo_plan and hylo_plan_msg_buf.
 */
#ifndef HYLO_MSG_H
#define HYLO_MSG_H

#include "hylo/planner.h"
#include "hylo_goal_t.h"
#include "hylo_map_t.h"
#include "hylo_plan_t.h"

#ifdef __cplusplus
extern "C" {
#endif

/**
 * Checks an encoded goal_t (buf, len bytes) before decoding: fingerprint,
 * non-negative array counts and max_expansions, exact length. HYLO_OK, or
 * HYLO_E_BAD_VALUE with a reason naming the field. *request_id gets the
 * goal's request id when the buffer reaches it, else
 * HYLO_GOAL_T_REQUEST_ID_UNREADABLE, so that even a corrupt goal can be answered.
 * No allocation.
 */
hylo_status hylo_msg_check_goal(const void *buf, int len, int64_t *request_id,
                                hylo_reason *r);

/** The same for an encoded map_t; *map_id as far as readable, else 0. */
hylo_status hylo_msg_check_map(const void *buf, int len, int64_t *map_id, hylo_reason *r);

/** A view of map message msg (no copy; valid while msg lives). */
void hylo_msg_map_view(const hylo_map_t *msg, hylo_map_view *view);

/** The map message of view v, the inverse of hylo_msg_map_view: utime 0,
 * the arrays pointing into v's (valid while they live). */
void hylo_msg_map(const hylo_map_view *v, hylo_map_t *msg);

/** The goal of goal message msg (copied: the grids too). */
void hylo_msg_goal_view(const hylo_goal_t *msg, hylo_goal *goal);

/** The goal message of goal g, the inverse of hylo_msg_goal_view: utime and
 * requester_id 0, the grids pointing into g (valid while g lives). A grid
 * count above HYLO_MAX_GRID (which hylo_goal_check refuses) is sent as
 * HYLO_MAX_GRID: g holds no more. */
void hylo_msg_goal(const hylo_goal *g, hylo_goal_t *msg);

/* Storage a plan message points into. */
typedef struct {
	int8_t mode[HYLO_MAX_WAYPOINTS];
	int8_t guard[HYLO_MAX_WAYPOINTS];
	int8_t mode_sequence[HYLO_MAX_WAYPOINTS];
	double *state_rows[HYLO_MAX_WAYPOINTS];
} hylo_plan_msg_buf;

/** plan_t.STATUS_* for a plan's status and outcome. */
int8_t hylo_msg_plan_status(hylo_status status, hylo_outcome outcome);

/** Name of a plan_t.STATUS_* value ("ok", "no path", ...; "unknown" for any
 * other), as the node logs it and hylo-listen prints it. */
const char *hylo_msg_plan_status_name(int8_t status);

/**
 * A plan message without a plan (no waypoints, no statistics, robot ""):
 * the answer to a goal that was not planned (refused, superseded). reason
 * must outlive msg.
 */
void hylo_msg_plan_empty(int64_t request_id, int64_t map_id, int8_t status, const char *reason,
			 int64_t utime, hylo_plan_t *msg);

/**
 * Fills msg from plan (utime as given). msg's arrays point into plan and
 * buf, which must outlive msg. The plan's reason becomes msg->reason.
 */
void hylo_msg_plan(const hylo_plan *plan, int64_t utime, hylo_plan_msg_buf *buf,
                   hylo_plan_t *msg);

#ifdef __cplusplus
}
#endif

#endif
