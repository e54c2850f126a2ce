/*
 * The planner node in-process over LCM's memq:// provider: real messages,
 * encoded and decoded by the generated bindings, through the node's
 * subscriptions. Checks that the plan equals the library's own answer, that
 * every bad input of the matrix gets exactly one plan with the right status
 * and a reason while the next valid request is still answered correctly, and
 * a soak of 10,000 goals with flat resident memory.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "node/node.h"
#include "onboard/testutil_planner.h"

#define MAX_PLANS 64

static lcm_t *lcm;
static hylo_node node;
static hylo_planner *planner, *reference;
static hylo_plan *plan, *ref_plan;
static hylo_plan_msg_buf *buf;
static hylo_robot robots[TU_N_ROBOTS];
static tu_cost costs;
static tu_map river;
static hylo_plan_t_subscription_t *plan_sub;
static hylo_node_status_t_subscription_t *status_sub;
static hylo_node_status_t last_status;
static char last_status_reason[512];
static int n_status_map;

/* Plans received on HYLO_PLAN since the last reset. */
static hylo_plan_t *received[MAX_PLANS];
static int n_received;
static uint64_t n_total;

static void on_plan(const lcm_recv_buf_t *rbuf, const char *channel, const hylo_plan_t *msg,
		    void *user)
{
	(void)rbuf;
	(void)channel;
	(void)user;
	n_total++;
	if (n_received < MAX_PLANS)
		received[n_received++] = hylo_plan_t_copy(msg);
}

/* Alternatives received on HYLO_PLAN_ALTERNATIVE since the last reset. */
static hylo_plan_alternative_t_subscription_t *alt_sub;
static hylo_plan_alternative_t *alts[MAX_PLANS];
static int n_alts;

static void on_alternative(const lcm_recv_buf_t *rbuf, const char *channel,
			   const hylo_plan_alternative_t *msg, void *user)
{
	(void)rbuf;
	(void)channel;
	(void)user;
	if (n_alts < MAX_PLANS)
		alts[n_alts++] = hylo_plan_alternative_t_copy(msg);
}

static void on_status(const lcm_recv_buf_t *rbuf, const char *channel,
		      const hylo_node_status_t *msg, void *user)
{
	(void)rbuf;
	(void)channel;
	(void)user;
	if (msg->event != HYLO_NODE_STATUS_T_EVENT_MAP)
		return;
	n_status_map++;
	last_status = *msg;
	snprintf(last_status_reason, sizeof last_status_reason, "%s", msg->reason);
	last_status.reason = last_status_reason;
}

static void clear_received(void)
{
	int k;

	for (k = 0; k < n_received; k++)
		hylo_plan_t_destroy(received[k]);
	n_received = 0;
	for (k = 0; k < n_alts; k++)
		hylo_plan_alternative_t_destroy(alts[k]);
	n_alts = 0;
}

/* Delivers what was published (admission), then lets the node work until
 * nothing waits, as hylo-planner --sync does. */
static void pump(void)
{
	int more;

	do {
		while (lcm_handle_timeout(lcm, 0) > 0)
			;
		more = 0;
		while (hylo_node_step(&node) >= 0)
			more = 1;
	} while (more);
}

/* Delivers what was published without planning: admission only. */
static void deliver(void)
{
	while (lcm_handle_timeout(lcm, 0) > 0)
		;
}

static void map_msg(const tu_map *m, hylo_map_t *msg)
{
	hylo_map_view v = tu_view(m);

	hylo_msg_map(&v, msg);
	msg->utime = 1;
}

static void goal_msg(const hylo_goal *g, hylo_goal_t *msg)
{
	hylo_msg_goal(g, msg);
	msg->utime = 2;
}

static void send_map(const tu_map *m)
{
	hylo_map_t msg;

	map_msg(m, &msg);
	assert_int_equal(hylo_map_t_publish(lcm, "HYLO_MAP", &msg), 0);
	pump();
}

/* Sends goal g and returns the one plan that answers it. */
static const hylo_plan_t *ask_msg(const hylo_goal_t *msg)
{
	clear_received();
	assert_int_equal(hylo_goal_t_publish(lcm, "HYLO_GOAL", msg), 0);
	pump();
	assert_int_equal(n_received, 1);
	assert_true(received[0]->request_id == msg->request_id);
	return received[0];
}

static const hylo_plan_t *ask(const hylo_goal *g)
{
	hylo_goal_t msg;

	goal_msg(g, &msg);
	return ask_msg(&msg);
}

/* Sends raw bytes on a channel and returns the one plan answering them. */
static const hylo_plan_t *ask_raw(const void *data, int len)
{
	clear_received();
	assert_int_equal(lcm_publish(lcm, "HYLO_GOAL", data, (unsigned)len), 0);
	pump();
	assert_int_equal(n_received, 1);
	return received[0];
}

/* The plan message equals what the library answers directly to the goal
 * as the node reads it (goal_t.alternatives 0: the default). */
static void assert_same_as_library(const hylo_plan_t *got, const tu_map *m, const hylo_goal *g)
{
	hylo_map_view v = tu_view(m);
	hylo_goal_t msg;
	hylo_goal read;
	int8_t want_status;
	uint32_t k;

	goal_msg(g, &msg);
	hylo_msg_goal_view(&msg, &read);
	assert_int_equal(hylo_planner_set_map(reference, &v), HYLO_OK);
	hylo_planner_plan(reference, &read, ref_plan);
	want_status = hylo_msg_plan_status(ref_plan->status, ref_plan->outcome);
	assert_int_equal(got->status, want_status);
	assert_string_equal(got->reason, ref_plan->reason.text);
	assert_true(got->total_cost_j == ref_plan->total_cost);
	assert_int_equal(got->n_waypoints, ref_plan->n_waypoints);
	for (k = 0; k < ref_plan->n_waypoints; k++) {
		assert_int_equal(got->mode[k], ref_plan->mode[k]);
		assert_true(got->cost_j[k] == ref_plan->cost[k]);
		assert_memory_equal(got->state[k], ref_plan->state[k], sizeof got->state[k]);
		assert_int_equal(got->guard[k], ref_plan->guard[k]);
	}
	assert_int_equal(got->n_modes, ref_plan->n_modes);
	/* The reference starts with an empty edge cache; the node may have kept
	 * costs from earlier goals on this map. */
	assert_true(got->n_edges_evaluated <= (int64_t)ref_plan->n_edges_evaluated);
}

static void test_end_to_end(void **state)
{
	hylo_goal g = tu_goal_river();
	const hylo_plan_t *p;

	(void)state;
	send_map(&river);
	p = ask(&g);
	assert_int_equal(p->status, HYLO_PLAN_T_STATUS_OK);
	assert_true(p->n_waypoints >= 2);
	assert_true(p->map_id == river.map_id);
	assert_string_equal(p->robot, "ambot");
	assert_int_equal(p->n_modes, 3);   /* ground, marine, ground */
	assert_same_as_library(p, &river, &g);
	/* A second goal on the same map: new start, same roadmap. */
	g.request_id = 8;
	g.start[1] = 4;
	g.algorithm = HYLO_DIJKSTRA;
	p = ask(&g);
	assert_int_equal(p->status, HYLO_PLAN_T_STATUS_OK);
	assert_same_as_library(p, &river, &g);
}

/* A goal asking for alternatives gets its plan on HYLO_PLAN as before and
 * then each alternative on HYLO_PLAN_ALTERNATIVE, cheapest first, equal to
 * the library's; a goal asking for one plan gets none. */
static void test_alternatives(void **state)
{
	hylo_goal g = tu_goal_river();
	const hylo_plan_t *p;
	uint32_t k, w;

	(void)state;
	send_map(&river);
	g.request_id = 31;
	g.alternatives = 3;
	g.alternatives_within = INFINITY;
	p = ask(&g);
	assert_int_equal(p->status, HYLO_PLAN_T_STATUS_OK);
	assert_same_as_library(p, &river, &g);
	assert_true(ref_plan->n_alternatives >= 2);
	assert_int_equal(n_alts, ref_plan->n_alternatives);
	for (k = 0; k < (uint32_t)n_alts; k++) {
		const hylo_plan_alternative_t *a = alts[k];

		assert_true(a->request_id == 31 && a->plan.request_id == 31);
		assert_int_equal(a->index, k);
		assert_int_equal(a->count, n_alts);
		assert_int_equal(a->mode_changes, ref_plan->alternative_switches[k]);
		assert_true(a->plan.total_cost_j == ref_plan->alternative_cost[k]);
		assert_int_equal(hylo_planner_alternative(reference, k, ref_plan), HYLO_OK);
		assert_int_equal(a->plan.n_waypoints, ref_plan->n_waypoints);
		for (w = 0; w < ref_plan->n_waypoints; w++)
			assert_memory_equal(a->plan.state[w], ref_plan->state[w], sizeof a->plan.state[w]);
		if (k == 0) {
			assert_int_equal(a->plan.n_waypoints, p->n_waypoints);
			assert_true(a->plan.total_cost_j == p->total_cost_j);
		}
	}
	g.request_id = 32;
	g.alternatives = 1;
	ask(&g);
	assert_int_equal(n_alts, 0);
	/* 0 on the wire: the default, the alternatives of asking for 3. */
	g.alternatives = HYLO_DEFAULT_ALTERNATIVES;
	g.request_id = 35;
	ask(&g);
	k = (uint32_t)n_alts;
	assert_true(k >= 2);
	g.alternatives = 0;
	g.request_id = 36;
	p = ask(&g);
	assert_same_as_library(p, &river, &g);
	assert_int_equal(n_alts, k);
	/* More than HYLO_MAX_ALTERNATIVES: a bad request naming the field. */
	g.request_id = 33;
	g.alternatives = HYLO_MAX_ALTERNATIVES + 1;
	p = ask(&g);
	assert_int_equal(p->status, HYLO_PLAN_T_STATUS_BAD_REQUEST);
	assert_non_null(strstr(p->reason, "alternatives"));
	assert_int_equal(n_alts, 0);
	/* Negative on the wire: said as it is. */
	{
		hylo_goal_t msg;

		g.request_id = 34;
		g.alternatives = 0;
		goal_msg(&g, &msg);
		msg.alternatives = -1;
		clear_received();
		assert_int_equal(hylo_goal_t_publish(lcm, "HYLO_GOAL", &msg), 0);
		pump();
		assert_int_equal(n_received, 1);
		p = received[0];
		assert_int_equal(p->status, HYLO_PLAN_T_STATUS_BAD_REQUEST);
		assert_non_null(strstr(p->reason, "alternatives is -1, negative"));
		assert_int_equal(n_alts, 0);
	}
}

/* Encodes goal g into a fresh buffer; returns its length. */
static int encode_goal(const hylo_goal *g, uint8_t **out)
{
	hylo_goal_t msg;
	int len;

	goal_msg(g, &msg);
	len = hylo_goal_t_encoded_size(&msg);
	*out = malloc((size_t)len);
	assert_non_null(*out);
	assert_int_equal(hylo_goal_t_encode(*out, 0, len, &msg), len);
	return len;
}

static void expect(const hylo_plan_t *p, int8_t status, const char *needle)
{
	if (p->status != status || !strstr(p->reason, needle))
		fail_msg("expected status %d with '%s', got %d: %s", status, needle, p->status,
			 p->reason);
	assert_int_equal(p->n_waypoints, 0);
}

/* After each bad input, a valid request is still answered correctly. */
static void still_serving(void)
{
	hylo_goal g = tu_goal_river();
	const hylo_plan_t *p;

	send_map(&river);
	g.request_id = 1000;
	p = ask(&g);
	assert_int_equal(p->status, HYLO_PLAN_T_STATUS_OK);
	assert_same_as_library(p, &river, &g);
}

static void test_bad_messages(void **state)
{
	hylo_goal g = tu_goal_river();
	uint8_t *bytes;
	int len, cut;
	hylo_plan_t other;
	const hylo_plan_t *p;

	(void)state;
	send_map(&river);
	g.request_id = 41;
	len = encode_goal(&g, &bytes);
	/* Truncated anywhere: answered with the request id when it was readable. */
	for (cut = 0; cut < len; cut += 37) {
		p = ask_raw(bytes, cut);
		expect(p, HYLO_PLAN_T_STATUS_BAD_REQUEST, "goal_t");
		assert_true(p->request_id == (cut >= 24 ? 41 : HYLO_GOAL_T_REQUEST_ID_UNREADABLE));
	}
	still_serving();
	/* Trailing garbage. */
	{
		uint8_t *longer = calloc((size_t)len + 3, 1);

		memcpy(longer, bytes, (size_t)len);
		expect(ask_raw(longer, len + 3), HYLO_PLAN_T_STATUS_BAD_REQUEST, "after its last field");
		free(longer);
	}
	/* Wrong type fingerprint: a plan_t sent as a goal. */
	{
		uint8_t raw[4096];
		int n;

		memset(&other, 0, sizeof other);
		other.reason = "";
		other.robot = "";
		n = hylo_plan_t_encode(raw, 0, sizeof raw, &other);
		assert_true(n > 0);
		expect(ask_raw(raw, n), HYLO_PLAN_T_STATUS_BAD_REQUEST, "fingerprint");
	}
	/* A negative array size: n_speeds (after the fixed part) set to -1. */
	{
		int at = 8 + 8 + 8 + 8 + 8 + 1 + 1 + 48 + 1 + 48 + 8 + 40;

		bytes[at] = bytes[at + 1] = bytes[at + 2] = bytes[at + 3] = 0xff;
		p = ask_raw(bytes, len);
		expect(p, HYLO_PLAN_T_STATUS_BAD_REQUEST, "n_speeds is -1");
		assert_true(p->request_id == 41);
	}
	free(bytes);
	still_serving();
}

static void test_bad_requests(void **state)
{
	hylo_goal g;
	hylo_goal_t over;
	tu_map m;
	double many[HYLO_MAX_GRID + 1] = { 0 };
	int k;

	(void)state;
	/* Goal before any map: a fresh node. */
	{
		hylo_goal first = tu_goal_river();
		hylo_map_t msg;

		(void)msg;
		assert_int_equal(hylo_planner_set_map(planner, NULL), HYLO_E_NULL);
		expect(ask(&first), HYLO_PLAN_T_STATUS_NO_MAP, "map");
	}
	send_map(&river);
	g = tu_goal_river();
	goal_msg(&g, &over);
	over.n_speeds = HYLO_MAX_GRID + 1;   /* over capacity */
	over.speeds_mps = many;
	expect(ask_msg(&over), HYLO_PLAN_T_STATUS_OVER_CAPACITY, "HYLO_MAX_GRID");
	g = tu_goal_river();
	g.start[0] = NAN;
	expect(ask(&g), HYLO_PLAN_T_STATUS_BAD_REQUEST, "start");
	g = tu_goal_river();
	g.goal[1] = INFINITY;
	expect(ask(&g), HYLO_PLAN_T_STATUS_BAD_REQUEST, "goal");
	g = tu_goal_river();
	g.start[0] = 3.5;                  /* in the obstacle */
	g.start[1] = 8;
	expect(ask(&g), HYLO_PLAN_T_STATUS_BAD_REQUEST, "start");
	g = tu_goal_river();
	g.goal[0] = 3.5;                   /* goal in the obstacle */
	g.goal[1] = 8;
	expect(ask(&g), HYLO_PLAN_T_STATUS_BAD_REQUEST, "goal");
	g = tu_goal_river();
	g.start[0] = 15;                   /* in the river, said to be driving */
	expect(ask(&g), HYLO_PLAN_T_STATUS_BAD_REQUEST, "marine");
	still_serving();

	/* Unreachable goal: a wall of obstacles across the map. */
	tu_river(&m);
	m.map_id = 5;
	for (k = 0; k < m.ny; k++)
		m.terrain[k * m.nx + 45] = HYLO_TERRAIN_OBSTACLE;
	send_map(&m);
	g = tu_goal_river();
	expect(ask(&g), HYLO_PLAN_T_STATUS_NO_PATH, "");
	/* A goal for the map that was just replaced. */
	send_map(&river);
	g = tu_goal_river();
	g.map_id = 5;
	expect(ask(&g), HYLO_PLAN_T_STATUS_MAP_REPLACED, "5");
	still_serving();

	/* Unknown robot: the map is refused and goals say why. */
	g.map_id = 0;
	m.robot = "submarine";
	m.map_id = 6;
	send_map(&m);
	expect(ask(&g), HYLO_PLAN_T_STATUS_BAD_REQUEST, "submarine");
	/* A map with no drivable cell. */
	m.robot = "ambot";
	m.map_id = 7;
	memset(m.terrain, HYLO_TERRAIN_OBSTACLE, (size_t)m.nx * m.ny);
	send_map(&m);
	g.map_id = 0;
	expect(ask(&g), HYLO_PLAN_T_STATUS_BAD_REQUEST, "7");
	/* A robot without a cost model. */
	m.robot = "ghost";
	m.map_id = 8;
	memset(m.terrain, HYLO_TERRAIN_GROUND, (size_t)m.nx * m.ny);
	send_map(&m);
	expect(ask(&g), HYLO_PLAN_T_STATUS_NO_MODEL, "");
	tu_map_free(&m);
	still_serving();
}


/* Publishes goal g from requester without planning; returns nothing. */
static void publish_goal(const hylo_goal *g, int64_t requester)
{
	hylo_goal_t msg;

	goal_msg(g, &msg);
	msg.requester_id = requester;
	assert_int_equal(hylo_goal_t_publish(lcm, "HYLO_GOAL", &msg), 0);
}

static const hylo_plan_t *answer_for(int64_t request_id)
{
	int k, found = -1;

	for (k = 0; k < n_received; k++)
		if (received[k]->request_id == request_id) {
			assert_int_equal(found, -1);    /* exactly one answer */
			found = k;
		}
	if (found < 0)
		fail_msg("no answer for request %" PRId64, request_id);
	return received[found];
}

/*
 * The queue policy while a plan is in progress (goals arrive and are
 * admitted, nothing is planned): a requester's newer goal supersedes its
 * waiting one at once, naming the newer request; one slot per requester;
 * a requester past HYLO_NODE_QUEUE_LEN gets QUEUE_FULL at once; then the
 * waiting goals are planned oldest first. Every goal gets exactly one answer.
 */
static void test_queue_policy(void **state)
{
	hylo_goal g = tu_goal_river();
	int k, n_sent = 0, n_super = 0, n_full = 0, n_ok = 0;
	uint64_t before = n_total;

	(void)state;
	send_map(&river);
	clear_received();
	/* Requester 7: 5 goals in a row; only the newest waits. */
	for (k = 0; k < 5; k++) {
		g.request_id = 500 + k;
		publish_goal(&g, 7);
		n_sent++;
	}
	deliver();
	assert_int_equal(n_received, 4);
	for (k = 0; k < 4; k++) {
		const hylo_plan_t *p = answer_for(500 + k);

		assert_int_equal(p->status, HYLO_PLAN_T_STATUS_SUPERSEDED);
		assert_true(p->superseded_by == 500 + k + 1);
		assert_non_null(strstr(p->reason, "superseded by request"));
	}
	assert_int_equal(hylo_node_queue_depth(&node), 1);
	/* Other requesters fill the queue; one more is refused at once. */
	for (k = 1; k < HYLO_NODE_QUEUE_LEN + 1; k++) {
		g.request_id = 600 + k;
		publish_goal(&g, 1000 + k);
		n_sent++;
	}
	deliver();
	assert_int_equal(hylo_node_queue_depth(&node), HYLO_NODE_QUEUE_LEN);
	assert_int_equal(answer_for(600 + HYLO_NODE_QUEUE_LEN)->status,
			 HYLO_PLAN_T_STATUS_QUEUE_FULL);
	/* A bad goal never replaces a waiting one. */
	g.request_id = 700;
	g.start[0] = NAN;
	publish_goal(&g, 7);
	n_sent++;
	deliver();
	assert_int_equal(answer_for(700)->status, HYLO_PLAN_T_STATUS_BAD_REQUEST);
	g.start[0] = tu_goal_river().start[0];
	/* Work: every waiting goal is planned, requester 7's newest first. */
	pump();
	assert_int_equal(hylo_node_queue_depth(&node), 0);
	assert_int_equal(received[n_received - HYLO_NODE_QUEUE_LEN]->request_id, 504);
	for (k = 0; k < n_received; k++) {
		if (received[k]->status == HYLO_PLAN_T_STATUS_SUPERSEDED)
			n_super++;
		else if (received[k]->status == HYLO_PLAN_T_STATUS_QUEUE_FULL)
			n_full++;
		else if (received[k]->status == HYLO_PLAN_T_STATUS_OK)
			n_ok++;
	}
	assert_int_equal(n_super, 4);
	assert_int_equal(n_full, 1);
	assert_int_equal(n_ok, HYLO_NODE_QUEUE_LEN);
	assert_int_equal((int)(n_total - before), n_sent);
	assert_int_equal(n_received, n_sent);
	clear_received();
}

static void expect_field(hylo_goal *g, const char *field)
{
	expect(ask(g), HYLO_PLAN_T_STATUS_BAD_REQUEST, field);
	*g = tu_goal_river();
}

/* Each validation gap of issue #39 is refused, naming the field. */
static void test_validation(void **state)
{
	hylo_goal g = tu_goal_river();
	uint8_t *bytes;
	int len, at;
	const hylo_plan_t *p;

	(void)state;
	send_map(&river);
	g.start[4] = NAN;               /* an entry a ground start does not use */
	expect_field(&g, "start[4]");
	g.start[5] = INFINITY;
	expect_field(&g, "start[5]");
	g.goal[5] = -INFINITY;
	expect_field(&g, "goal[5]");
	g.sampling.air_spacing = NAN;            /* ambot does not fly */
	expect_field(&g, "air_spacing_m");
	g.sampling.air_spacing = -INFINITY;
	expect_field(&g, "air_spacing_m");
	g.sampling.air_connect_radius = NAN;
	expect_field(&g, "air_connect_radius_m");
	g.sampling.air_connect_radius = -INFINITY;
	expect_field(&g, "air_connect_radius_m");
	g.sampling.guard_spacing = -1;
	expect_field(&g, "guard_spacing_m");
	g.time_budget_ms = -1;
	expect_field(&g, "time_budget_ms");
	/* max_expansions = -1 and -2^31 on the wire. */
	at = 8 + 8 + 8 + 8 + 8 + 1 + 1 + 48 + 1 + 48 + 8 + 40;
	len = encode_goal(&g, &bytes);
	at += 4 + 8 * (int)g.sampling.n_speeds + 4 + 8 * (int)g.sampling.n_headings + 4 + 8 * (int)g.sampling.n_air_speeds + 8;
	bytes[at] = bytes[at + 1] = bytes[at + 2] = bytes[at + 3] = 0xff;
	p = ask_raw(bytes, len);
	expect(p, HYLO_PLAN_T_STATUS_BAD_REQUEST, "max_expansions is -1");
	bytes[at] = 0x80;
	bytes[at + 1] = bytes[at + 2] = bytes[at + 3] = 0;
	p = ask_raw(bytes, len);
	expect(p, HYLO_PLAN_T_STATUS_BAD_REQUEST, "max_expansions is -2147483648");
	assert_true(p->request_id == g.request_id);
	free(bytes);
	/* Unknown map, replaced map. */
	g.map_id = 987654;
	p = ask(&g);
	expect(p, HYLO_PLAN_T_STATUS_UNKNOWN_MAP, "987654");
	g = tu_goal_river();
	/* The reserved request id. */
	g.request_id = HYLO_GOAL_T_REQUEST_ID_UNREADABLE;
	expect_field(&g, "reserved");
	/* An undecodable goal: too short to hold a request id. */
	{
		uint8_t junk[10] = { 1, 2, 3 };

		p = ask_raw(junk, sizeof junk);
		expect(p, HYLO_PLAN_T_STATUS_BAD_REQUEST, "goal_t");
		assert_true(p->request_id == HYLO_GOAL_T_REQUEST_ID_UNREADABLE);
	}
	still_serving();
}

/* Every map message is reported on HYLO_STATUS: taken, or why not. */
static void test_map_status(void **state)
{
	tu_map m;
	uint8_t junk[40] = { 0 };
	hylo_goal g;

	(void)state;
	n_status_map = 0;
	send_map(&river);
	assert_int_equal(n_status_map, 1);
	assert_true(last_status.map_id == river.map_id);
	assert_int_equal(last_status.map_status, HYLO_PLAN_T_STATUS_OK);
	assert_true(last_status.current_map_id == river.map_id);
	/* Undecodable: refused, the current map stays. */
	assert_int_equal(lcm_publish(lcm, "HYLO_MAP", junk, sizeof junk), 0);
	pump();
	assert_int_equal(n_status_map, 2);
	assert_int_equal(last_status.map_status, HYLO_PLAN_T_STATUS_BAD_REQUEST);
	assert_non_null(strstr(last_status.reason, "map_t"));
	assert_true(last_status.current_map_id == river.map_id);
	/* Refused by the planner (NaN height). */
	tu_river(&m);
	m.map_id = 77;
	m.height[3] = NAN;
	send_map(&m);
	assert_int_equal(last_status.map_status, HYLO_PLAN_T_STATUS_BAD_REQUEST);
	assert_true(last_status.map_id == 77);
	assert_non_null(strstr(last_status.reason, "height"));
	/* Two maps before the work side runs: the first is superseded. */
	m.height[3] = 0;
	m.map_id = 78;
	{
		hylo_map_t msg;

		map_msg(&m, &msg);
		assert_int_equal(hylo_map_t_publish(lcm, "HYLO_MAP", &msg), 0);
		map_msg(&river, &msg);
		assert_int_equal(hylo_map_t_publish(lcm, "HYLO_MAP", &msg), 0);
	}
	deliver();
	assert_true(last_status.map_id == 78);
	assert_int_equal(last_status.map_status, HYLO_PLAN_T_STATUS_SUPERSEDED);
	pump();
	assert_true(last_status.map_id == river.map_id);
	assert_int_equal(last_status.map_status, HYLO_PLAN_T_STATUS_OK);
	/* A goal for the superseded map: it was received, then replaced. */
	g = tu_goal_river();
	g.map_id = 78;
	expect(ask(&g), HYLO_PLAN_T_STATUS_MAP_REPLACED, "78");
	tu_map_free(&m);
	still_serving();
}

static long resident_kb(void)
{
	FILE *f = fopen("/proc/self/statm", "r");
	long pages = 0, rss = 0;

	if (!f)
		return -1;
	if (fscanf(f, "%ld %ld", &pages, &rss) != 2)
		rss = -1;
	fclose(f);
	return rss * 4;
}

#if defined(__SANITIZE_ADDRESS__)
#define SOAK_GOALS 1000     /* ASan keeps freed memory in quarantine: no RSS check */
#else
#define SOAK_GOALS 10000
#endif

static void test_soak(void **state)
{
	tu_map di;
	hylo_goal g = tu_goal_di();
	hylo_goal_t msg;
	long rss100 = 0, rss_end;
	uint64_t before;
	int k;

	(void)state;
	tu_di(&di);
	send_map(&di);
	before = n_total;
	for (k = 0; k < SOAK_GOALS; k++) {
		g.request_id = 100000 + k;
		g.start[1] = -0.5 + 0.7 * ((k * 37) % 100) / 100.0;
		g.algorithm = k % 2;
		if (k % 10 == 9)
			g.start[0] = NAN;   /* every tenth request is bad */
		else
			g.start[0] = 0.8;
		clear_received();
		goal_msg(&g, &msg);
		assert_int_equal(hylo_goal_t_publish(lcm, "HYLO_GOAL", &msg), 0);
		pump();
		assert_int_equal(n_received, 1);
		assert_true(received[0]->request_id == g.request_id);
		assert_int_equal(received[0]->status, k % 10 == 9 ? HYLO_PLAN_T_STATUS_BAD_REQUEST
								  : HYLO_PLAN_T_STATUS_OK);
		if (k == 99)
			rss100 = resident_kb();
	}
	clear_received();
	rss_end = resident_kb();
	assert_true(n_total - before == SOAK_GOALS);
	print_message("soak: %d goals answered; resident %ld kB after 100, %ld kB after %d\n",
		      SOAK_GOALS, rss100, rss_end, SOAK_GOALS);
#if !defined(__SANITIZE_ADDRESS__)
	assert_true(rss_end - rss100 <= 256);
#endif
	tu_map_free(&di);
}

static int setup(void **state)
{
	hylo_planner_config cfg;

	(void)state;
	planner = malloc(TU_PLANNER_BYTES);
	reference = malloc(TU_PLANNER_BYTES);
	plan = malloc(sizeof *plan);
	ref_plan = malloc(sizeof *ref_plan);
	buf = malloc(sizeof *buf);
	lcm = lcm_create("memq://");
	if (!planner || !reference || !plan || !ref_plan || !buf || !lcm)
		return -1;
	tu_robots(robots, &costs);
	cfg = tu_config(robots, TU_N_ROBOTS);
	if (hylo_planner_init(planner, TU_PLANNER_BYTES, &cfg) != HYLO_OK ||
	    hylo_planner_init(reference, TU_PLANNER_BYTES, &cfg) != HYLO_OK)
		return -1;
	if (hylo_node_init(&node, lcm, lcm, "", planner, plan, buf, NULL, 0) != 0)
		return -1;
	plan_sub = hylo_plan_t_subscribe(lcm, "HYLO_PLAN", on_plan, NULL);
	status_sub = hylo_node_status_t_subscribe(lcm, "HYLO_STATUS", on_status, NULL);
	alt_sub = hylo_plan_alternative_t_subscribe(lcm, "HYLO_PLAN_ALTERNATIVE", on_alternative, NULL);
	if (!plan_sub || !status_sub || !alt_sub)
		return -1;
	hylo_plan_alternative_t_subscription_set_queue_capacity(alt_sub, 0);
	hylo_plan_t_subscription_set_queue_capacity(plan_sub, 0);
	tu_river(&river);
	return 0;
}

static int teardown(void **state)
{
	(void)state;
	clear_received();
	tu_map_free(&river);
	hylo_plan_t_unsubscribe(lcm, plan_sub);
	hylo_node_status_t_unsubscribe(lcm, status_sub);
	hylo_plan_alternative_t_unsubscribe(lcm, alt_sub);
	hylo_node_destroy(&node);
	lcm_destroy(lcm);
	free(planner);
	free(reference);
	free(plan);
	free(ref_plan);
	free(buf);
	return 0;
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_bad_requests),   /* first: it starts without a map */
		cmocka_unit_test(test_end_to_end),
		cmocka_unit_test(test_alternatives),
		cmocka_unit_test(test_bad_messages),
		cmocka_unit_test(test_queue_policy),
		cmocka_unit_test(test_validation),
		cmocka_unit_test(test_map_status),
		cmocka_unit_test(test_soak),
	};

	return cmocka_run_group_tests_name("node", tests, setup, teardown);
}
