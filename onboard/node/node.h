/*
 * The LCM planner node: subscribes <prefix>HYLO_MAP and <prefix>HYLO_GOAL,
 * answers every goal with exactly one <prefix>HYLO_PLAN. Messages are checked
 * (onboard/msg/wire.c) and decoded here, at the edge; the planning core only
 * sees views and keeps its no-allocation guarantee. One log line per request.
 */
#ifndef HYLO_NODE_H
#define HYLO_NODE_H

#include <stdint.h>
#include <stdio.h>
#include <lcm/lcm.h>

#include "hylo/planner.h"
#include "hylo_msg.h"

#ifdef __cplusplus
extern "C" {
#endif

#define HYLO_NODE_CHANNEL_LEN 128

typedef struct {
	lcm_t *in, *out;                /* subscribe on in, publish on out (may be equal) */
	hylo_planner *planner;          /* caller-provided workspace */
	hylo_plan *plan;
	hylo_plan_msg_buf *msg_buf;
	char ch_map[HYLO_NODE_CHANNEL_LEN], ch_goal[HYLO_NODE_CHANNEL_LEN];
	char ch_plan[HYLO_NODE_CHANNEL_LEN];
	FILE *log;                      /* one line per request; NULL: silent */
	int verbose;
	int64_t map_id;                 /* id of the current map, 0 before any */
	uint64_t n_goals, n_maps;       /* messages answered / ingested or refused */
	uint64_t goal_limit;            /* stop answering after this many goals; 0 = no limit */
	uint64_t n_publish_errors;
} hylo_node;

/**
 * Sets up the node on the given LCM instances with channel prefix (may be
 * ""), and subscribes. planner must have been initialized with
 * hylo_planner_init. Returns 0, or -1 with a message on log when a channel
 * name is too long or subscribing fails.
 */
int hylo_node_init(hylo_node *node, lcm_t *in, lcm_t *out, const char *prefix,
                   hylo_planner *planner, hylo_plan *plan, hylo_plan_msg_buf *buf,
                   FILE *log, int verbose);

/** Answers one encoded goal message as the subscription does (for tests). */
void hylo_node_goal(hylo_node *node, const void *data, int len);

/** Takes one encoded map message as the subscription does (for tests). */
void hylo_node_map(hylo_node *node, const void *data, int len);

#ifdef __cplusplus
}
#endif

#endif
