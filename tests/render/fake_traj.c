/*
 * Test inputs for the renderer, written to an LCM log:
 *   fake_traj traj OUT.log IN.log...   a traj_t that follows the last plan of
 *                                      the logs at 1 m/s (robot outlines and
 *                                      the smoothed-path layer without Ipopt)
 *   fake_traj chasm OUT.log MAP_ID     a drive-fly-drive plan_t across the
 *                                      chasm of chasm_050.yaml, and its traj_t
 *   fake_traj plan OUT.log K IN.log... the last plan of the logs again,
 *                                      followed by K plan_alternative_t copies
 *                                      of it (index 0 .. K - 1 of K)
 *   fake_traj keep OUT.log LIST IN.log... the last plan of the logs again with
 *                                      those of its alternatives whose index is
 *                                      in LIST (e.g. 1,2; "-": none)
 * They are drawing inputs only: nothing here is a planner or smoother result.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <lcm/lcm.h>
#include <lcm/eventlog.h>
#include "hylo_plan_alternative_t.h"
#include "hylo_plan_t.h"
#include "hylo_traj_t.h"

#define MAX_SAMPLES 4096
#define MAX_ALTERNATIVES 64
#define PER_SEGMENT 12

static double t_s[MAX_SAMPLES], states[MAX_SAMPLES][16], inputs[MAX_SAMPLES][4];
static double *state_rows[MAX_SAMPLES], *input_rows[MAX_SAMPLES];
static int8_t modes[MAX_SAMPLES];

static int publish_traj(lcm_t *lcm, const hylo_plan_t *p)
{
	hylo_traj_t t;
	int k, j, n = 0;
	double time = 0;

	for (k = 0; k + 1 < p->n_waypoints; k++) {
		const double *a = p->state[k], *b = p->state[k + 1];
		int flight = p->mode[k] == 3 && p->mode[k + 1] == 3;
		double dz = flight ? b[2] - a[2] : 0;
		double len = sqrt((b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]) + dz * dz);
		double heading = atan2(b[1] - a[1], b[0] - a[0]);
		if (len < 1e-9)
			continue;
		for (j = 0; j < PER_SEGMENT && n < MAX_SAMPLES; j++, n++) {
			double s = (double)j / PER_SEGMENT;
			memset(states[n], 0, sizeof states[n]);
			states[n][0] = a[0] + s * (b[0] - a[0]);
			states[n][1] = a[1] + s * (b[1] - a[1]);
			modes[n] = p->mode[k] == p->mode[k + 1] ? p->mode[k] : p->mode[k + 1];
			if (modes[n] == 3) {
				states[n][2] = a[2] + s * dz;
				states[n][8] = heading;
			} else {
				states[n][4] = heading;
			}
			t_s[n] = time + s * len;
		}
		time += len;
	}
	if (n < MAX_SAMPLES) {
		const double *e = p->state[p->n_waypoints - 1];
		memset(states[n], 0, sizeof states[n]);
		states[n][0] = e[0];
		states[n][1] = e[1];
		modes[n] = p->mode[p->n_waypoints - 1];
		if (modes[n] == 3)
			states[n][2] = e[2];
		states[n][4] = n ? states[n - 1][4] : 0;
		t_s[n++] = time;
	}
	for (k = 0; k < n; k++) {
		state_rows[k] = states[k];
		input_rows[k] = inputs[k];
	}
	memset(&t, 0, sizeof t);
	t.request_id = p->request_id;
	t.map_id = p->map_id;
	t.status = 0;
	t.reason = "fake trajectory for renderer tests";
	t.robot = p->robot;
	t.energy_j = p->total_cost_j;
	t.replay_energy_j = p->total_cost_j;
	t.n_samples = n;
	t.t_s = t_s;
	t.mode = modes;
	t.state = state_rows;
	t.input = input_rows;
	return hylo_traj_t_publish(lcm, "HYLO_TRAJ", &t);
}

/* The last plan_t of the logs, decoded into *last. 0, or 1 with a message. */
static int last_plan(int n_logs, char **logs, hylo_plan_t *last)
{
	int have = 0, i;

	memset(last, 0, sizeof *last);
	for (i = 0; i < n_logs; i++) {
		lcm_eventlog_t *log = lcm_eventlog_create(logs[i], "r");
		lcm_eventlog_event_t *ev;
		if (!log) {
			fprintf(stderr, "fake_traj: cannot read %s\n", logs[i]);
			return 1;
		}
		while ((ev = lcm_eventlog_read_next_event(log)) != NULL) {
			if (strcmp(ev->channel, "HYLO_PLAN") == 0) {
				if (have)
					hylo_plan_t_decode_cleanup(last);
				have = hylo_plan_t_decode(ev->data, 0, ev->datalen, last) >= 0;
			}
			lcm_eventlog_free_event(ev);
		}
		lcm_eventlog_destroy(log);
	}
	if (!have || last->status != 0) {
		if (have)
			hylo_plan_t_decode_cleanup(last);
		fprintf(stderr, "fake_traj: no plan with a path in the logs\n");
		return 1;
	}
	return 0;
}

static int from_logs(lcm_t *lcm, int n_logs, char **logs)
{
	hylo_plan_t last;
	int rc;

	if (last_plan(n_logs, logs, &last) != 0)
		return 1;
	rc = publish_traj(lcm, &last);
	hylo_plan_t_decode_cleanup(&last);
	return rc != 0;
}

static int plan_with_copies(lcm_t *lcm, int k, int n_logs, char **logs)
{
	hylo_plan_t last;
	hylo_plan_alternative_t a;
	int i, rc;

	if (last_plan(n_logs, logs, &last) != 0)
		return 1;
	rc = hylo_plan_t_publish(lcm, "HYLO_PLAN", &last);
	memset(&a, 0, sizeof a);
	a.request_id = last.request_id;
	a.count = k;
	a.plan = last;
	for (i = 0; i < k && rc == 0; i++) {
		a.index = i;
		rc = hylo_plan_alternative_t_publish(lcm, "HYLO_PLAN_ALTERNATIVE", &a);
	}
	hylo_plan_t_decode_cleanup(&last);
	return rc != 0;
}

static int chasm(lcm_t *lcm, long long map_id)
{
	/* x, y, z, mode, guard: drive to the edge, take off, fly over, land, drive */
	static const double wp[][5] = {
		{10, 5, 0, 1, 0}, {19.5, 5, 0, 1, 1}, {19.5, 5, 6.4, 3, 1}, {27, 5, 10, 3, 0},
		{35, 5, 11.5, 3, 0}, {43, 5, 10, 3, 0}, {50.5, 5, 6.4, 3, 1}, {50.5, 5, 0, 1, 1},
		{60, 5, 0, 1, 0}};
	enum { N = sizeof wp / sizeof wp[0] };
	double st[N][6], cost[N], *rows[N];
	int8_t mode[N], guard[N], seq[3] = {1, 3, 1};
	hylo_plan_t p;
	int k;

	memset(&p, 0, sizeof p);
	for (k = 0; k < N; k++) {
		memset(st[k], 0, sizeof st[k]);
		st[k][0] = wp[k][0];
		st[k][1] = wp[k][1];
		st[k][2] = wp[k][3] == 3 ? wp[k][2] : 0;
		mode[k] = (int8_t)wp[k][3];
		guard[k] = (int8_t)wp[k][4];
		cost[k] = 10.0 * k;
		rows[k] = st[k];
	}
	p.request_id = 1;
	p.map_id = map_id;
	p.status = 0;
	p.reason = "fake plan for renderer tests";
	p.robot = "drivocopter";
	p.total_cost_j = cost[N - 1];
	p.n_waypoints = N;
	p.mode = mode;
	p.state = rows;
	p.cost_j = cost;
	p.guard = guard;
	p.n_modes = 3;
	p.mode_sequence = seq;
	if (hylo_plan_t_publish(lcm, "HYLO_PLAN", &p) != 0)
		return 1;
	return publish_traj(lcm, &p) != 0;
}

static int in_list(const char *list, int index)
{
	const char *p = list;

	while (*p) {
		char *end;
		long v = strtol(p, &end, 10);
		if (end == p)
			return 0;
		if (v == index)
			return 1;
		p = *end == ',' ? end + 1 : end;
	}
	return 0;
}

static int plan_keeping(lcm_t *lcm, const char *list, int n_logs, char **logs)
{
	static hylo_plan_alternative_t alts[MAX_ALTERNATIVES];
	hylo_plan_t last;
	int n = 0, i, rc;

	if (last_plan(n_logs, logs, &last) != 0)
		return 1;
	for (i = 0; i < n_logs; i++) {
		lcm_eventlog_t *log = lcm_eventlog_create(logs[i], "r");
		lcm_eventlog_event_t *ev;
		while (log && (ev = lcm_eventlog_read_next_event(log)) != NULL) {
			if (strcmp(ev->channel, "HYLO_PLAN_ALTERNATIVE") == 0 && n < MAX_ALTERNATIVES &&
			    hylo_plan_alternative_t_decode(ev->data, 0, ev->datalen, &alts[n]) >= 0) {
				if (alts[n].request_id == last.request_id && in_list(list, alts[n].index))
					n++;
				else
					hylo_plan_alternative_t_decode_cleanup(&alts[n]);
			}
			lcm_eventlog_free_event(ev);
		}
		if (log)
			lcm_eventlog_destroy(log);
	}
	rc = hylo_plan_t_publish(lcm, "HYLO_PLAN", &last);
	for (i = 0; i < n; i++) {
		if (rc == 0)
			rc = hylo_plan_alternative_t_publish(lcm, "HYLO_PLAN_ALTERNATIVE", &alts[i]);
		hylo_plan_alternative_t_decode_cleanup(&alts[i]);
	}
	hylo_plan_t_decode_cleanup(&last);
	return rc != 0;
}

int main(int argc, char **argv)
{
	char url[4200];
	lcm_t *lcm;
	int rc;

	if (argc < 4 || (strcmp(argv[1], "traj") && strcmp(argv[1], "chasm") &&
	                 ((strcmp(argv[1], "plan") && strcmp(argv[1], "keep")) || argc < 5))) {
		fprintf(stderr, "usage: fake_traj traj OUT.log IN.log... | fake_traj chasm OUT.log MAP_ID"
		        " | fake_traj plan OUT.log K IN.log... | fake_traj keep OUT.log LIST IN.log...\n");
		return 2;
	}
	snprintf(url, sizeof url, "file://%s?mode=w", argv[2]);
	lcm = lcm_create(url);
	if (!lcm) {
		fprintf(stderr, "fake_traj: cannot write %s\n", argv[2]);
		return 1;
	}
	if (strcmp(argv[1], "traj") == 0)
		rc = from_logs(lcm, argc - 3, argv + 3);
	else if (strcmp(argv[1], "plan") == 0)
		rc = plan_with_copies(lcm, atoi(argv[3]), argc - 4, argv + 4);
	else if (strcmp(argv[1], "keep") == 0)
		rc = plan_keeping(lcm, argv[3], argc - 4, argv + 4);
	else
		rc = chasm(lcm, atoll(argv[3]));
	lcm_destroy(lcm);
	return rc;
}
