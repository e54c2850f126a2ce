/*
 * plan_check IN.log OUT.log [PREFIX]: replays the maps and goals of IN.log
 * through the planning library directly (the node's robots, no LCM in
 * between) and checks that OUT.log holds exactly one plan per goal, in
 * order, equal to the library's answer byte for byte once encoded (utime
 * and plan_ms, the only fields that may differ, are zeroed). Used by
 * tests/node/test_logs.sh and test_udp.sh. Exit 0 when equal, 1 otherwise.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <lcm/eventlog.h>

#include "hylo_msg.h"
#include "node/registry.h"

#define MAX_PLANS 1024

static int encode(hylo_plan_t *msg, unsigned char **out)
{
	int len;

	msg->utime = 0;
	msg->plan_ms = 0;
	len = hylo_plan_t_encoded_size(msg);
	*out = malloc((size_t)len);
	if (!*out || hylo_plan_t_encode(*out, 0, len, msg) != len)
		return -1;
	return len;
}

int main(int argc, char **argv)
{
	static hylo_robot robots[HYLO_MAX_ROBOTS];
	char ch_map[160], ch_goal[160], ch_plan[160];
	const char *prefix = argc > 3 ? argv[3] : "";
	unsigned char *want[MAX_PLANS];
	int want_len[MAX_PLANS], n_want = 0, n_got = 0, bad = 0;
	hylo_planner_config cfg;
	hylo_plan_msg_buf *buf = malloc(sizeof *buf);
	hylo_planner *pl;
	size_t size;
	hylo_plan *plan = malloc(sizeof *plan);
	lcm_eventlog_t *in, *out;
	lcm_eventlog_event_t *ev;
	hylo_reason reason;

	if (argc < 3 || strlen(prefix) > 100) {
		fprintf(stderr, "usage: plan_check IN.log OUT.log [PREFIX]\n");
		return 2;
	}
	snprintf(ch_map, sizeof ch_map, "%sHYLO_MAP", prefix);
	snprintf(ch_goal, sizeof ch_goal, "%sHYLO_GOAL", prefix);
	snprintf(ch_plan, sizeof ch_plan, "%sHYLO_PLAN", prefix);
	memset(&cfg, 0, sizeof cfg);
	cfg.robots = robots;
	cfg.n_robots = hylo_registry_robots(robots, HYLO_MAX_ROBOTS, &reason);
	size = hylo_planner_size(&cfg);
	pl = malloc(size);
	if (!buf || !pl || !plan || hylo_planner_init(pl, size, &cfg) != HYLO_OK)
		return 2;
	in = lcm_eventlog_create(argv[1], "r");
	out = lcm_eventlog_create(argv[2], "r");
	if (!in || !out) {
		fprintf(stderr, "plan_check: cannot read %s or %s\n", argv[1], argv[2]);
		return 2;
	}
	/* The library's answers, in the order the node received the requests. */
	while ((ev = lcm_eventlog_read_next_event(in)) != NULL) {
		if (strcmp(ev->channel, ch_map) == 0) {
			hylo_map_t m;
			hylo_map_view v;

			if (hylo_msg_check_map(ev->data, ev->datalen, NULL, &reason) == HYLO_OK &&
			    hylo_map_t_decode(ev->data, 0, ev->datalen, &m) >= 0) {
				hylo_msg_map_view(&m, &v);
				hylo_planner_set_map(pl, &v);
				hylo_map_t_decode_cleanup(&m);
			}
		} else if (strcmp(ev->channel, ch_goal) == 0 && n_want < MAX_PLANS) {
			hylo_goal_t g;
			hylo_goal goal;
			hylo_plan_t msg;

			if (hylo_msg_check_goal(ev->data, ev->datalen, NULL, &reason) != HYLO_OK ||
			    hylo_goal_t_decode(ev->data, 0, ev->datalen, &g) < 0) {
				fprintf(stderr, "plan_check: undecodable goal in %s\n", argv[1]);
				return 2;
			}
			hylo_msg_goal_view(&g, &goal);
			hylo_planner_plan(pl, &goal, plan);
			hylo_msg_plan(plan, 0, buf, &msg);
			want_len[n_want] = encode(&msg, &want[n_want]);
			n_want++;
			hylo_goal_t_decode_cleanup(&g);
		}
		lcm_eventlog_free_event(ev);
	}
	while ((ev = lcm_eventlog_read_next_event(out)) != NULL) {
		if (strcmp(ev->channel, ch_plan) == 0) {
			hylo_plan_t p;
			unsigned char *got;
			int len;

			if (hylo_plan_t_decode(ev->data, 0, ev->datalen, &p) < 0) {
				fprintf(stderr, "plan_check: undecodable plan %d\n", n_got);
				bad = 1;
			} else {
				len = encode(&p, &got);
				if (n_got >= n_want || len != want_len[n_got] ||
				    memcmp(got, want[n_got], (size_t)len) != 0) {
					fprintf(stderr, "plan_check: plan %d (request %lld, status %d) differs "
						"from the library's answer\n", n_got,
						(long long)p.request_id, p.status);
					bad = 1;
				}
				free(got);
				hylo_plan_t_decode_cleanup(&p);
			}
			n_got++;
		}
		lcm_eventlog_free_event(ev);
	}
	if (n_got != n_want) {
		fprintf(stderr, "plan_check: %d plans for %d goals\n", n_got, n_want);
		bad = 1;
	}
	if (!bad)
		printf("plan_check: %d plans equal the library's answers\n", n_got);
	lcm_eventlog_destroy(in);
	lcm_eventlog_destroy(out);
	return bad;
}
