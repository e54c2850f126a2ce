/*
 * The LCM planner node: subscribes <prefix>HYLO_MAP and <prefix>HYLO_GOAL,
 * answers every goal with exactly one <prefix>HYLO_PLAN (and, when the goal
 * asks for alternatives, one <prefix>HYLO_PLAN_ALTERNATIVE each) and reports maps and
 * counters on <prefix>HYLO_STATUS. Messages are checked (onboard/msg/wire.c)
 * and decoded here, at the edge; the planning core only sees views and keeps
 * its no-allocation guarantee. One log line per request.
 *
 * Two sides (docs/node.md):
 *  - admission (hylo_node_goal, hylo_node_map; the LCM callbacks) runs
 *    wherever lcm_handle runs and never plans: it checks a goal, answers it
 *    at once when it is refused, else puts it into the queue (one slot per
 *    requester_id, newest wins, the replaced goal answered SUPERSEDED); a map
 *    goes into the pending-map slot.
 *  - work (hylo_node_step) takes the pending map, then the oldest waiting
 *    goal, plans it and publishes the plan.
 * hylo-planner runs the two in two threads on a live provider, so that LCM's
 * queue never fills while a plan runs; a test or a log replay alternates
 * them in one thread. All state is in the struct (fixed arrays; the pending
 * map slots are 2 x HYLO_MAX_CELLS cells): place it in static storage or
 * allocate it once at start-up.
 */
#ifndef HYLO_NODE_H
#define HYLO_NODE_H

#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <lcm/lcm.h>

#include "hylo/planner.h"
#include "hylo_msg.h"
#include "hylo_node_status_t.h"
#include "hylo_plan_alternative_t.h"

#ifdef __cplusplus
extern "C" {
#endif

#define HYLO_NODE_CHANNEL_LEN 128

/* Requesters that can have a goal waiting; a goal from one more is answered
 * STATUS_QUEUE_FULL. */
#ifndef HYLO_NODE_QUEUE_LEN
#define HYLO_NODE_QUEUE_LEN 32
#endif
/* Map ids remembered to tell STATUS_MAP_REPLACED from STATUS_UNKNOWN_MAP. */
#ifndef HYLO_NODE_MAP_HISTORY
#define HYLO_NODE_MAP_HISTORY 64
#endif
/* LCM's own queue per subscription (lcm_subscription_set_queue_capacity):
 * large enough that admission, which never plans, drains it before it
 * fills; the node's queue policy decides what is dropped. */
#ifndef HYLO_NODE_LCM_QUEUE
#define HYLO_NODE_LCM_QUEUE 100000
#endif

/* A waiting goal (a copy: it holds its grids). */
typedef struct {
	hylo_goal goal;
	int64_t requester_id;
} hylo_node_slot;

/* A received map, copied out of its message. */
typedef struct {
	hylo_map_view view;             /* points into this slot */
	char robot[HYLO_NAME_LEN];
	int8_t terrain[HYLO_MAX_CELLS];
	float height[HYLO_MAX_CELLS];
} hylo_node_map_slot;

typedef struct {
	lcm_t *in, *out;                /* subscribe on in, publish on out (may be equal) */
	hylo_planner *planner;          /* caller-provided workspace */
	hylo_plan *plan;
	hylo_plan_msg_buf *msg_buf;
	char ch_map[HYLO_NODE_CHANNEL_LEN], ch_goal[HYLO_NODE_CHANNEL_LEN];
	char ch_plan[HYLO_NODE_CHANNEL_LEN], ch_status[HYLO_NODE_CHANNEL_LEN];
	char ch_alternative[HYLO_NODE_CHANNEL_LEN];
	FILE *log;                      /* one line per request; NULL: silent */
	int verbose;
	int32_t recv_buf_bytes;         /* reported in node_status_t */
	uint64_t goal_limit;            /* stop admitting after this many goals; 0 = no limit */

	/* Everything below is shared by admission and work: under lock. */
	pthread_mutex_t lock;
	pthread_mutex_t pub_lock;       /* serializes publishing; taken inside lock, never around it */
	pthread_cond_t wake;            /* a goal or map is waiting, or stop */
	int stop;
	hylo_node_slot queue[HYLO_NODE_QUEUE_LEN];   /* FIFO ring */
	uint32_t q_head, q_len;
	hylo_node_slot current;         /* the goal being planned (work side) */
	hylo_node_map_slot maps[2];
	hylo_node_map_slot *map_pending;  /* waiting to be taken; NULL when none */
	hylo_node_map_slot *map_busy;     /* being taken by the work side; NULL when none */
	int64_t map_id;                 /* the current (last taken) map, 0 before any */
	int64_t map_ids[HYLO_NODE_MAP_HISTORY];  /* received map ids, ring */
	uint32_t n_map_ids;
	int8_t map_status;              /* plan_t status of the current map */
	uint64_t n_goals, n_answered, n_planned, n_superseded, n_refused;
	uint64_t n_maps, n_maps_taken, n_maps_refused;
	uint64_t n_publish_errors;
} hylo_node;

/**
 * Sets up the node on the given LCM instances with channel prefix (may be
 * ""), and subscribes with LCM queues of HYLO_NODE_LCM_QUEUE messages.
 * planner must have been initialized with hylo_planner_init. Returns 0, or
 * -1 with a message on log when a channel name is too long or subscribing
 * fails. Call hylo_node_destroy when done.
 */
int hylo_node_init(hylo_node *node, lcm_t *in, lcm_t *out, const char *prefix,
                   hylo_planner *planner, hylo_plan *plan, hylo_plan_msg_buf *buf,
                   FILE *log, int verbose);

/** Releases the lock and condition variable (not the LCM instances). */
void hylo_node_destroy(hylo_node *node);

/** Admits one encoded goal message as the subscription does (answers it at
 * once when refused or when it replaces a waiting goal). Never plans. */
void hylo_node_goal(hylo_node *node, const void *data, int len);

/** Admits one encoded map message as the subscription does. Never plans. */
void hylo_node_map(hylo_node *node, const void *data, int len);

/**
 * Work: takes the pending map, if any, then plans the oldest waiting goal,
 * if any, and publishes its plan. Returns the number of goals planned (0 or
 * 1); -1 when nothing was waiting.
 */
int hylo_node_step(hylo_node *node);

/**
 * Blocks until a goal or map is waiting, hylo_node_stop was called, or
 * timeout_ms passed. Returns 1 when there is work, 0 when not, -1 after
 * hylo_node_stop.
 */
int hylo_node_wait(hylo_node *node, int timeout_ms);

/** Wakes hylo_node_wait for good (the worker then exits). */
void hylo_node_stop(hylo_node *node);

/** Publishes a node_status_t with the counters (event: EVENT_*). */
void hylo_node_publish_status(hylo_node *node, int8_t event);

/** Goals waiting now. */
uint32_t hylo_node_queue_depth(hylo_node *node);

/** Goals admitted, answered so far (under the lock). */
void hylo_node_counts(hylo_node *node, uint64_t *received, uint64_t *answered);

#ifdef __cplusplus
}
#endif

#endif
