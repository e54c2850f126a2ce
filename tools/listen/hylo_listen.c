/*
 * hylo-listen: prints the plans (<prefix>HYLO_PLAN, and their alternatives on
 * <prefix>HYLO_PLAN_ALTERNATIVE) and trajectories (<prefix>HYLO_TRAJ, and what
 * the smoother made of each alternative on <prefix>HYLO_TRAJ_ALTERNATIVE) seen
 * on the bus, as text or as JSON lines. See --help.
 * Exit codes: 0 after --count messages or a signal or the end of a file://
 * log, 1 when --timeout passes with nothing received or LCM fails, 2 usage.
 */
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <lcm/lcm.h>

#include "hylo_node_status_t.h"
#include "hylo_plan_alternative_t.h"
#include "hylo_plan_t.h"
#include "hylo_msg.h"
#include "hylo_traj_alternative_t.h"
#include "hylo_traj_t.h"

static volatile sig_atomic_t stop_requested;
static int json, waypoints, stats;
static long count;
static const char *event_names[] = { "periodic", "map", "stop" };

static void on_signal(int sig)
{
	(void)sig;
	stop_requested = 1;
}

static const char *status_str(int s)
{
	return hylo_msg_plan_status_name((int8_t)s);
}

/* The library's mode names, and "none" for mode 0. */
static const char *mode_str(int m)
{
	return m == HYLO_MODE_NONE ? "none" : hylo_mode_str((hylo_mode)m);
}

/* JSON number: NaN and infinities are not JSON; they become null. */
static void jnum(double v)
{
	if (isfinite(v))
		printf("%.17g", v);
	else
		printf("null");
}

static void jstr(const char *s)
{
	putchar('"');
	for (; s && *s; s++) {
		unsigned char c = (unsigned char)*s;

		if (c == '"' || c == '\\')
			printf("\\%c", c);
		else if (c < 0x20)
			printf("\\u%04x", c);
		else
			putchar(c);
	}
	putchar('"');
}

/* ,"name":v */
static void jnum_field(const char *name, double v)
{
	printf(",\"%s\":", name);
	jnum(v);
}

static void jstr_field(const char *name, const char *s)
{
	printf(",\"%s\":", name);
	jstr(s);
}

/* A mode sequence: JSON strings between commas, or names between " > ". */
static void print_modes(const int8_t *seq, int n, int as_json)
{
	int k;

	for (k = 0; k < n; k++)
		printf(as_json ? "%s\"%s\"" : "%s%s", k ? (as_json ? "," : " > ") : "", mode_str(seq[k]));
}

/* A plan as one JSON object (no newline). */
static void plan_json(const hylo_plan_t *p)
{
	int k, j;

	printf("{\"type\":\"plan\",\"request_id\":%lld,\"map_id\":%lld,\"status\":",
	       (long long)p->request_id, (long long)p->map_id);
	jstr(status_str(p->status));
	jstr_field("reason", p->reason);
	printf(",\"superseded_by\":%lld,\"robot\":", (long long)p->superseded_by);
	jstr(p->robot);
	jnum_field("total_cost_j", p->total_cost_j);
	jnum_field("suboptimality", p->suboptimality);
	jnum_field("lower_bound_j", p->lower_bound_j);
	printf(",\"mode_sequence\":[");
	print_modes(p->mode_sequence, p->n_modes, 1);
	printf("],\"waypoints\":[");
	for (k = 0; k < p->n_waypoints; k++) {
		printf("%s{\"mode\":\"%s\",\"state\":[", k ? "," : "", mode_str(p->mode[k]));
		for (j = 0; j < 6; j++) {
			if (j)
				putchar(',');
			jnum(p->state[k][j]);
		}
		printf("],\"cost_j\":");
		jnum(p->cost_j[k]);
		printf(",\"guard\":%d}", p->guard[k]);
	}
	printf("],\"n_nodes\":%d,\"n_edges\":%lld,\"n_edges_evaluated\":%lld,"
	       "\"n_edges_cached\":%lld,\"n_expansions\":%lld,\"n_clamped\":%lld,\"plan_ms\":",
	       p->n_nodes, (long long)p->n_edges, (long long)p->n_edges_evaluated,
	       (long long)p->n_edges_cached, (long long)p->n_expansions, (long long)p->n_clamped);
	jnum(p->plan_ms);
	putchar('}');
}

static void print_plan_json(const hylo_plan_t *p)
{
	plan_json(p);
	putchar('\n');
}

static void print_plan_text(const hylo_plan_t *p)
{
	int k;

	printf("plan %lld (map %lld, %s): %s", (long long)p->request_id, (long long)p->map_id,
	       p->robot[0] ? p->robot : "-", status_str(p->status));
	if (p->status == HYLO_PLAN_T_STATUS_SUPERSEDED)
		printf(" by request %lld", (long long)p->superseded_by);
	if (p->status == HYLO_PLAN_T_STATUS_OK || p->status == HYLO_PLAN_T_STATUS_NOT_PROVEN) {
		printf(", %.6g J", p->total_cost_j);
		if (p->suboptimality > 1)
			printf(" (at most %g x the optimum)", p->suboptimality);
		if (p->status == HYLO_PLAN_T_STATUS_NOT_PROVEN && p->lower_bound_j > 0)
			printf(" (the optimum is at least %.6g J)", p->lower_bound_j);
		printf(", %d waypoints, modes ", p->n_waypoints);
		print_modes(p->mode_sequence, p->n_modes, 0);
	} else {
		printf(" (%s)", p->reason);
	}
	printf("; %d nodes, %lld edges, %lld evaluated, %lld cached, %.2f ms\n", p->n_nodes,
	       (long long)p->n_edges, (long long)p->n_edges_evaluated,
	       (long long)p->n_edges_cached, p->plan_ms);
	if (waypoints)
		for (k = 0; k < p->n_waypoints; k++)
			printf("  %3d %-7s (%10.4f %10.4f %10.4f %10.4f %10.4f %10.4f) %12.6g J%s\n", k,
			       mode_str(p->mode[k]), p->state[k][0], p->state[k][1], p->state[k][2],
			       p->state[k][3], p->state[k][4], p->state[k][5], p->cost_j[k],
			       p->guard[k] ? "  guard" : "");
}

/* One JSON array of n numbers, after a comma when comma is set. */
static void jrow(const double *v, int n, int comma)
{
	int j;

	printf(comma ? ",[" : "[");
	for (j = 0; j < n; j++) {
		if (j)
			putchar(',');
		jnum(v[j]);
	}
	putchar(']');
}

/* traj_t.method: the step of the smoother's fallback chain (docs/smoothing.md). */
static const char *method_str(int8_t m)
{
	switch (m) {
	case HYLO_TRAJ_T_METHOD_FULL: return "full";
	case HYLO_TRAJ_T_METHOD_STRAIGHTENED: return "straightened";
	case HYLO_TRAJ_T_METHOD_FINER_MESH: return "finer mesh";
	case HYLO_TRAJ_T_METHOD_PHASE_BY_PHASE: return "phase by phase";
	case HYLO_TRAJ_T_METHOD_GRAPH_PATH: return "graph path";
	case HYLO_TRAJ_T_METHOD_VIA_POINTS: return "via points";
	default: return "unknown";
	}
}

static void print_traj(const hylo_traj_t *t)
{
	if (json) {
		int k;

		printf("{\"type\":\"traj\",\"request_id\":%lld,\"map_id\":%lld,\"status\":",
		       (long long)t->request_id, (long long)t->map_id);
		jstr(status_str(t->status));
		jstr_field("reason", t->reason);
		jstr_field("robot", t->robot);
		jnum_field("energy_j", t->energy_j);
		jnum_field("replay_energy_j", t->replay_energy_j);
		jnum_field("replay_error", t->replay_error);
		jstr_field("method", method_str(t->method));
		jnum_field("gap_j", t->gap_j);
		printf(",\"safe\":%s,\"body_radius_m\":", t->safe ? "true" : "false");
		jnum(t->body_radius_m);
		jnum_field("margin_m", t->margin_m);
		jnum_field("min_clearance_m", t->min_clearance_m);
		jnum_field("clearance_t_s", t->clearance_t_s);
		printf(",\"clearance_xyz\":");
		jrow(t->clearance_xyz, 3, 0);
		printf(",\"t_s\":[");
		for (k = 0; k < t->n_samples; k++) {
			if (k)
				putchar(',');
			jnum(t->t_s[k]);
		}
		printf("],\"mode\":[");
		for (k = 0; k < t->n_samples; k++)
			printf(k ? ",%d" : "%d", t->mode[k]);
		printf("],\"state\":[");
		for (k = 0; k < t->n_samples; k++)
			jrow(t->state[k], 16, k > 0);
		printf("],\"input\":[");
		for (k = 0; k < t->n_samples; k++)
			jrow(t->input[k], 4, k > 0);
		printf("],\"n_samples\":%d}\n", t->n_samples);
		return;
	}
	printf("traj %lld (map %lld, %s): %s, energy %.6g J, replay %.6g J, replay error %.3g, "
	       "%d samples, %.3f s", (long long)t->request_id, (long long)t->map_id,
	       t->robot[0] ? t->robot : "-", status_str(t->status), t->energy_j,
	       t->replay_energy_j, t->replay_error, t->n_samples,
	       t->n_samples > 0 ? t->t_s[t->n_samples - 1] : 0.0);
	if (t->status == HYLO_PLAN_T_STATUS_OK && t->method != HYLO_TRAJ_T_METHOD_FULL)
		printf(", fallback %s (up to %.4g J above the optimum)", method_str(t->method), t->gap_j);
	if (t->status == HYLO_PLAN_T_STATUS_OK)
		printf(", %s: clearance %.3g m (margin %.3g m) at t = %.3g s", t->safe ? "safe" : "NOT SAFE",
		       t->min_clearance_m, t->margin_m, t->clearance_t_s);
	if (t->status != HYLO_PLAN_T_STATUS_OK || !t->safe)
		printf(": %s", t->reason);
	putchar('\n');
}

static long received;

/* An alternative of a plan (goal_t.alternatives >= 2), after its plan. */
static void print_alternative(const hylo_plan_alternative_t *a)
{
	if (json) {
		printf("{\"type\":\"alternative\",\"request_id\":%lld,\"index\":%d,\"count\":%d,"
		       "\"mode_changes\":%d,\"plan\":",
		       (long long)a->request_id, a->index, a->count, a->mode_changes);
		plan_json(&a->plan);
		printf("}\n");
	} else {
		printf("  alternative %d of %d for plan %lld: %.6g J, %d waypoints, %d mode change%s, modes ",
		       a->index + 1, a->count, (long long)a->request_id, a->plan.total_cost_j,
		       a->plan.n_waypoints, a->mode_changes, a->mode_changes == 1 ? "" : "s");
		print_modes(a->plan.mode_sequence, a->plan.n_modes, 0);
		putchar('\n');
	}
}

/* What the smoother made of an alternative (traj_alternative_t), after the traj_t. */
static void print_traj_alternative(const hylo_traj_alternative_t *a)
{
	if (json) {
		printf("{\"type\":\"traj_alternative\",\"request_id\":%lld,\"map_id\":%lld,\"index\":%d,"
		       "\"count\":%d,\"planned\":%d,\"mode_changes\":%d,\"mode_sequence\":[",
		       (long long)a->request_id, (long long)a->map_id, a->index, a->count, a->planned,
		       a->mode_changes);
		print_modes(a->mode_sequence, a->n_modes, 1);
		printf("],\"predicted_j\":");
		jnum(a->predicted_j);
		jstr_field("status", status_str(a->status));
		jstr_field("reason", a->reason);
		jstr_field("method", a->status == HYLO_PLAN_T_STATUS_OK ? method_str(a->method) : "none");
		jnum_field("smoothed_j", a->smoothed_j);
		jnum_field("gap_j", a->gap_j);
		printf(",\"chosen\":%d}\n", a->chosen);
	} else {
		printf("  smoothed alternative %d of %d for traj %lld (graph rank %d): ", a->index + 1, a->planned,
		       (long long)a->request_id, a->index + 1);
		print_modes(a->mode_sequence, a->n_modes, 0);
		printf(", predicted %.6g J, ", a->predicted_j);
		if (a->status == HYLO_PLAN_T_STATUS_OK)
			printf("smoothed %.6g J (%s)", a->smoothed_j, method_str(a->method));
		else
			printf("%s: %s", status_str(a->status), a->reason);
		printf("%s\n", a->chosen ? ", chosen" : "");
	}
}

static void print_plan(const hylo_plan_t *p)
{
	if (json)
		print_plan_json(p);
	else
		print_plan_text(p);
}

/* --stats: the node's counters and map reports (<prefix>HYLO_STATUS). */
static void print_status(const hylo_node_status_t *s)
{
	const char *ev = s->event >= 0 && s->event < 3 ? event_names[s->event] : "unknown";

	if (json) {
		printf("{\"type\":\"status\",\"event\":");
		jstr(ev);
		printf(",\"map_id\":%lld,\"map_status\":", (long long)s->map_id);
		jstr(status_str(s->map_status));
		jstr_field("reason", s->reason);
		printf(",\"current_map_id\":%lld,\"goals_received\":%lld,\"goals_answered\":%lld,"
		       "\"goals_planned\":%lld,\"goals_superseded\":%lld,\"goals_refused\":%lld,"
		       "\"queue_depth\":%d,\"queue_capacity\":%d,\"maps_received\":%lld,"
		       "\"maps_taken\":%lld,\"maps_refused\":%lld,\"recv_buf_bytes\":%d}\n",
		       (long long)s->current_map_id, (long long)s->goals_received,
		       (long long)s->goals_answered, (long long)s->goals_planned,
		       (long long)s->goals_superseded, (long long)s->goals_refused, s->queue_depth,
		       s->queue_capacity, (long long)s->maps_received, (long long)s->maps_taken,
		       (long long)s->maps_refused, s->recv_buf_bytes);
	} else {
		if (s->event == HYLO_NODE_STATUS_T_EVENT_MAP)
			printf("map %lld: %s%s%s\n", (long long)s->map_id, status_str(s->map_status),
			       s->reason[0] ? ", " : "", s->reason);
		printf("status (%s): goals %lld received, %lld answered (%lld planned, %lld superseded, "
		       "%lld refused), queue %d of %d; maps %lld received, %lld taken, %lld refused; "
		       "current map %lld\n", ev, (long long)s->goals_received,
		       (long long)s->goals_answered, (long long)s->goals_planned,
		       (long long)s->goals_superseded, (long long)s->goals_refused, s->queue_depth,
		       s->queue_capacity, (long long)s->maps_received, (long long)s->maps_taken,
		       (long long)s->maps_refused, (long long)s->current_map_id);
	}
}

/* on_WHAT, the LCM handler of message type T: prints the message with
 * print_WHAT, then flushes and counts it. */
#define HANDLER(what, T)                                                                         \
	static void on_##what(const lcm_recv_buf_t *rbuf, const char *ch, const T *msg, void *u) \
	{                                                                                        \
		(void)rbuf;                                                                      \
		(void)ch;                                                                        \
		(void)u;                                                                         \
		print_##what(msg);                                                               \
		fflush(stdout);                                                                  \
		received++;                                                                      \
	}
HANDLER(plan, hylo_plan_t)
HANDLER(alternative, hylo_plan_alternative_t)
HANDLER(traj, hylo_traj_t)
HANDLER(traj_alternative, hylo_traj_alternative_t)
HANDLER(status, hylo_node_status_t)

static void usage(FILE *f)
{
	fprintf(f,
		"usage: hylo-listen [options]\n"
		"Prints every plan (<prefix>HYLO_PLAN), its alternatives when the goal asked for\n"
		"them (<prefix>HYLO_PLAN_ALTERNATIVE), smoothed trajectory (<prefix>HYLO_TRAJ) and\n"
		"what the smoother made of each alternative (<prefix>HYLO_TRAJ_ALTERNATIVE).\n"
		"\n"
		"  --lcm-url URL        LCM provider (default: $LCM_DEFAULT_URL, else LCM's default)\n"
		"  --channel-prefix P   prefix of the channel names (default: none)\n"
		"  --json               one JSON object per line instead of text\n"
		"  --waypoints          text mode: also print every waypoint\n"
		"  --stats              print the node's status (<prefix>HYLO_STATUS: goals\n"
		"                       answered, superseded, refused, queue depth, maps)\n"
		"                       instead of plans and trajectories\n"
		"  --count N            exit after N messages (default: run until a signal)\n"
		"  --timeout S          exit with status 1 if S seconds pass without a message\n"
		"                       (default: wait forever)\n"
		"  --help               this text\n");
}

int main(int argc, char **argv)
{
	const char *url = NULL, *prefix = "";
	double timeout_s = 0;
	char ch_plan[160], ch_alternative[160], ch_traj[160], ch_traj_alternative[160], ch_status[160];
	struct sigaction sa;
	struct timespec last, now;
	lcm_t *lcm;
	int i, rc = 0;

	for (i = 1; i < argc; i++) {
		const char *a = argv[i];
		char *end = NULL;

		if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
			usage(stdout);
			return 0;
		} else if (strcmp(a, "--json") == 0) {
			json = 1;
		} else if (strcmp(a, "--stats") == 0) {
			stats = 1;
		} else if (strcmp(a, "--waypoints") == 0) {
			waypoints = 1;
		} else if (strcmp(a, "--lcm-url") == 0 && i + 1 < argc) {
			url = argv[++i];
		} else if (strcmp(a, "--channel-prefix") == 0 && i + 1 < argc) {
			prefix = argv[++i];
		} else if (strcmp(a, "--count") == 0 && i + 1 < argc) {
			count = strtol(argv[++i], &end, 10);
			if (*end || count <= 0) {
				fprintf(stderr, "hylo-listen: --count needs a positive integer, not '%s'\n", argv[i]);
				return 2;
			}
		} else if (strcmp(a, "--timeout") == 0 && i + 1 < argc) {
			timeout_s = strtod(argv[++i], &end);
			if (*end || !(timeout_s > 0)) {
				fprintf(stderr, "hylo-listen: --timeout needs a positive number of seconds, not '%s'\n", argv[i]);
				return 2;
			}
		} else {
			fprintf(stderr, "hylo-listen: unknown or incomplete option '%s' (see --help)\n", a);
			return 2;
		}
	}
	if (strlen(prefix) > 100) {
		fprintf(stderr, "hylo-listen: channel prefix too long\n");
		return 2;
	}
	snprintf(ch_plan, sizeof ch_plan, "%sHYLO_PLAN", prefix);
	snprintf(ch_alternative, sizeof ch_alternative, "%sHYLO_PLAN_ALTERNATIVE", prefix);
	snprintf(ch_traj, sizeof ch_traj, "%sHYLO_TRAJ", prefix);
	snprintf(ch_traj_alternative, sizeof ch_traj_alternative, "%sHYLO_TRAJ_ALTERNATIVE", prefix);
	snprintf(ch_status, sizeof ch_status, "%sHYLO_STATUS", prefix);
	lcm = lcm_create(url);
	if (!lcm) {
		fprintf(stderr, "hylo-listen: cannot open LCM provider '%s'\n", url ? url : "(default)");
		return 1;
	}
	if (stats) {
		hylo_node_status_t_subscribe(lcm, ch_status, on_status, NULL);
	} else {
		hylo_plan_t_subscribe(lcm, ch_plan, on_plan, NULL);
		hylo_plan_alternative_t_subscribe(lcm, ch_alternative, on_alternative, NULL);
		hylo_traj_t_subscribe(lcm, ch_traj, on_traj, NULL);
		hylo_traj_alternative_t_subscribe(lcm, ch_traj_alternative, on_traj_alternative, NULL);
	}
	memset(&sa, 0, sizeof sa);
	sa.sa_handler = on_signal;
	sigemptyset(&sa.sa_mask);
	sigaction(SIGINT, &sa, NULL);
	sigaction(SIGTERM, &sa, NULL);
	clock_gettime(CLOCK_MONOTONIC, &last);
	while (!stop_requested && !(count > 0 && received >= count)) {
		long before = received;
		int r = lcm_handle_timeout(lcm, 100);

		if (r < 0) {
			if (!(url && strncmp(url, "file://", 7) == 0))
				rc = 1;
			break;
		}
		clock_gettime(CLOCK_MONOTONIC, &now);
		if (received != before)
			last = now;
		else if (timeout_s > 0 && (double)(now.tv_sec - last.tv_sec) +
						  1e-9 * (double)(now.tv_nsec - last.tv_nsec) > timeout_s) {
			fprintf(stderr, "hylo-listen: nothing received for %g s\n", timeout_s);
			rc = 1;
			break;
		}
	}
	lcm_destroy(lcm);
	return rc;
}
