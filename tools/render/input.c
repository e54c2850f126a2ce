#include "input.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <lcm/lcm.h>
#include <lcm/eventlog.h>
#include "hylo_msg.h"

/* Appends a decoded copy of one message to its list; undecodable ones are
 * counted and reported, never fatal (a log may hold other traffic). */
#define KEEP(list, n, type, data, len)                                          \
	do {                                                                        \
		type *m_ = calloc(1, sizeof(type));                                     \
		void *grown_ = realloc((list), sizeof(type *) * (size_t)((n) + 1));     \
		if (!m_ || !grown_) {                                                   \
			free(m_);                                                           \
			if (grown_)                                                         \
				(list) = grown_;                                                \
			return -1;                                                          \
		}                                                                       \
		(list) = grown_;                                                        \
		if (type##_decode((data), 0, (len), m_) < 0) {                          \
			type##_decode_cleanup(m_);                                          \
			free(m_);                                                           \
			return 1;                                                           \
		}                                                                       \
		(list)[(n)++] = m_;                                                     \
	} while (0)

static int channel_is(const char *channel, const input_options *o, const char *name)
{
	size_t k = strlen(o->prefix);

	return strncmp(channel, o->prefix, k) == 0 && strcmp(channel + k, name) == 0;
}

/* 0 kept or not ours, 1 undecodable, -1 out of memory. */
static int take(input_set *in, const input_options *o, const char *channel, const void *data,
                int len)
{
	int64_t id;
	hylo_reason r;

	if (channel_is(channel, o, "HYLO_MAP")) {
		if (hylo_msg_check_map(data, len, &id, &r) != HYLO_OK)
			return 1;
		KEEP(in->maps, in->n_maps, hylo_map_t, data, len);
	} else if (channel_is(channel, o, "HYLO_GOAL")) {
		if (hylo_msg_check_goal(data, len, &id, &r) != HYLO_OK)
			return 1;
		KEEP(in->goals, in->n_goals, hylo_goal_t, data, len);
	} else if (channel_is(channel, o, "HYLO_PLAN")) {
		KEEP(in->plans, in->n_plans, hylo_plan_t, data, len);
	} else if (channel_is(channel, o, "HYLO_PLAN_ALTERNATIVE")) {
		if (o->want_alternatives)
			KEEP(in->alts, in->n_alts, hylo_plan_alternative_t, data, len);
	} else if (channel_is(channel, o, "HYLO_TRAJ")) {
		KEEP(in->trajs, in->n_trajs, hylo_traj_t, data, len);
	} else if (channel_is(channel, o, "HYLO_BASELINE")) {
		KEEP(in->baselines, in->n_baselines, hylo_traj_t, data, len);
	}
	return 0;
}

static int account(input_set *in, int rc, char *err, size_t errlen)
{
	if (rc < 0) {
		snprintf(err, errlen, "out of memory while reading messages");
		return -1;
	}
	in->n_undecodable += rc;
	return 0;
}

int input_read_log(input_set *in, const input_options *o, const char *path, char *err,
                   size_t errlen)
{
	lcm_eventlog_t *log;
	lcm_eventlog_event_t *ev;
	long n_events = 0;
	FILE *probe = fopen(path, "rb");

	if (!probe) {
		snprintf(err, errlen, "cannot open log %s", path);
		return -1;
	}
	fclose(probe);
	log = lcm_eventlog_create(path, "r");
	if (!log) {
		snprintf(err, errlen, "%s is not an LCM log", path);
		return -1;
	}
	while ((ev = lcm_eventlog_read_next_event(log)) != NULL) {
		int rc = take(in, o, ev->channel, ev->data, ev->datalen);
		lcm_eventlog_free_event(ev);
		n_events++;
		if (account(in, rc, err, errlen) != 0) {
			lcm_eventlog_destroy(log);
			return -1;
		}
	}
	lcm_eventlog_destroy(log);
	if (n_events == 0) {
		snprintf(err, errlen, "%s holds no LCM events (not an LCM log, or empty)", path);
		return -1;
	}
	return 0;
}

typedef struct {
	input_set *in;
	const input_options *o;
	int oom;
} listen_ctx;

static void on_message(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
	listen_ctx *ctx = user;
	int rc = take(ctx->in, ctx->o, channel, rbuf->data, (int)rbuf->data_size);

	if (rc < 0)
		ctx->oom = 1;
	else
		ctx->in->n_undecodable += rc;
}

static double now_s(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* 1 once what we wait for is there: a plan whose map has arrived. */
static int complete(const input_set *in, const input_options *o)
{
	int i, j;

	if (!o->want_plan)
		return in->n_maps > 0;
	for (i = 0; i < in->n_plans; i++) {
		const hylo_plan_t *p = in->plans[i];
		if (o->request_id >= 0 && p->request_id != o->request_id)
			continue;
		for (j = 0; j < in->n_maps; j++)
			if (in->maps[j]->map_id == p->map_id)
				return 1;
	}
	return 0;
}

int input_listen(input_set *in, const input_options *o, const char *url, double timeout_s,
                 char *err, size_t errlen)
{
	lcm_t *lcm = lcm_create(url);
	char pattern[256];
	listen_ctx ctx;
	double t0 = now_s(), done_at = -1;
	const double grace_s = 0.5;   /* the smoother answers after the planner */

	if (!lcm) {
		snprintf(err, errlen, "cannot open the LCM bus %s", url ? url : "(default)");
		return -1;
	}
	ctx.in = in;
	ctx.o = o;
	ctx.oom = 0;
	snprintf(pattern, sizeof pattern, "%sHYLO_.*", o->prefix);
	lcm_subscribe(lcm, pattern, on_message, &ctx);
	for (;;) {
		double t = now_s();
		if (done_at < 0 && complete(in, o))
			done_at = t;
		if (done_at >= 0 && t - done_at >= grace_s)
			break;
		if (t - t0 > timeout_s) {
			lcm_destroy(lcm);
			snprintf(err, errlen, "no %s arrived on %s within %.1f s",
			         o->want_plan ? "plan with its map" : "map", url ? url : "the bus",
			         timeout_s);
			return -1;
		}
		if (lcm_handle_timeout(lcm, 50) < 0)
			break;
		if (ctx.oom) {
			lcm_destroy(lcm);
			snprintf(err, errlen, "out of memory while reading messages");
			return -1;
		}
	}
	lcm_destroy(lcm);
	return 0;
}

/* The alternatives of the selected plan: for each index the last message
 * with the plan's request_id (they follow their plan; a log may repeat a
 * request), all of the last one's count. */
static int select_alternatives(input_set *in, char *err, size_t errlen)
{
	const hylo_plan_t *p = in->plan;
	int i, count = -1;

	for (i = in->n_alts - 1; i >= 0; i--) {
		const hylo_plan_alternative_t *a = in->alts[i];
		if (a->request_id != p->request_id)
			continue;
		if (count < 0) {
			count = a->count;
			if (count < 1 || count > INPUT_MAX_ALTERNATIVES) {
				snprintf(err, errlen, "plan %lld comes with %d alternatives; hylo-render draws "
				         "1 to %d (--no-alternatives leaves them out)",
				         (long long)p->request_id, count, INPUT_MAX_ALTERNATIVES);
				return -1;
			}
		}
		if (a->count != count)
			continue;   /* an earlier answer to the same request_id */
		if (a->index < 0 || a->index >= count || a->plan.map_id != p->map_id) {
			snprintf(err, errlen, "alternative with index %d of %d for plan %lld (map %lld) "
			         "does not fit the plan (index 0 .. count - 1, map %lld)", a->index, count,
			         (long long)p->request_id, (long long)a->plan.map_id, (long long)p->map_id);
			return -1;
		}
		if (!in->alternative[a->index])
			in->alternative[a->index] = a;
	}
	in->n_alternatives = count < 0 ? 0 : count;
	return 0;
}

int input_select(input_set *in, const input_options *o, char *err, size_t errlen)
{
	int i;

	if (in->n_maps == 0) {
		snprintf(err, errlen, "no map (channel %sHYLO_MAP) in the input", o->prefix);
		return -1;
	}
	if (!o->want_plan) {
		in->map = in->maps[in->n_maps - 1];
		return 0;
	}
	for (i = in->n_plans - 1; i >= 0; i--)
		if (o->request_id < 0 || in->plans[i]->request_id == o->request_id) {
			in->plan = in->plans[i];
			break;
		}
	if (!in->plan) {
		if (o->request_id >= 0)
			snprintf(err, errlen, "no plan with request_id %lld in the input (use --map-only to "
			         "draw the map alone)", (long long)o->request_id);
		else
			snprintf(err, errlen, "no plan (channel %sHYLO_PLAN) in the input (use --map-only "
			         "to draw the map alone)", o->prefix);
		return -1;
	}
	if (in->plan->map_id == 0) {
		snprintf(err, errlen, "plan %lld was made on no map (status %d: %s)",
		         (long long)in->plan->request_id, in->plan->status, in->plan->reason);
		return -1;
	}
	/* The plan's own map: the last one with its id published before or
	 * after it (a log may hold the map once for many plans). */
	for (i = in->n_maps - 1; i >= 0; i--)
		if (in->maps[i]->map_id == in->plan->map_id) {
			in->map = in->maps[i];
			break;
		}
	if (!in->map) {
		snprintf(err, errlen, "plan %lld is for map %lld, which is not in the input (maps seen:",
		         (long long)in->plan->request_id, (long long)in->plan->map_id);
		for (i = 0; i < in->n_maps && i < 8; i++) {
			size_t k = strlen(err);
			snprintf(err + k, errlen - k, " %lld", (long long)in->maps[i]->map_id);
		}
		strncat(err, ")", errlen - strlen(err) - 1);
		return -1;
	}
	for (i = in->n_goals - 1; i >= 0; i--)
		if (in->goals[i]->request_id == in->plan->request_id) {
			in->goal = in->goals[i];
			break;
		}
	for (i = in->n_trajs - 1; i >= 0; i--)
		if (in->trajs[i]->request_id == in->plan->request_id && in->trajs[i]->status == 0) {
			in->traj = in->trajs[i];
			break;
		}
	for (i = in->n_baselines - 1; i >= 0; i--)
		if (in->baselines[i]->map_id == in->plan->map_id && in->baselines[i]->status == 0) {
			in->baseline = in->baselines[i];
			break;
		}
	return select_alternatives(in, err, errlen);
}

#define FREE_LIST(list, n, type)                    \
	do {                                            \
		int k_;                                     \
		for (k_ = 0; k_ < (n); k_++) {              \
			type##_decode_cleanup((list)[k_]);      \
			free((list)[k_]);                       \
		}                                           \
		free(list);                                 \
	} while (0)

void input_free(input_set *in)
{
	FREE_LIST(in->maps, in->n_maps, hylo_map_t);
	FREE_LIST(in->goals, in->n_goals, hylo_goal_t);
	FREE_LIST(in->plans, in->n_plans, hylo_plan_t);
	FREE_LIST(in->alts, in->n_alts, hylo_plan_alternative_t);
	FREE_LIST(in->trajs, in->n_trajs, hylo_traj_t);
	FREE_LIST(in->baselines, in->n_baselines, hylo_traj_t);
	memset(in, 0, sizeof *in);
}
