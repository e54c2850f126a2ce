#include <errno.h>
#include <inttypes.h>
#include <stdarg.h>
#include <string.h>
#include <sys/time.h>
#include <time.h>

#include "node/node.h"

static int64_t utime_now(void)
{
	struct timeval tv;

	gettimeofday(&tv, NULL);
	return (int64_t)tv.tv_sec * 1000000 + tv.tv_usec;
}

/* Publishing is serialized: udpm:// locks its socket, but an --out-url log
 * (file://) would be written from both threads. pub_lock nests inside lock. */
static void publish(hylo_node *node, const hylo_plan_t *msg)
{
	int r;

	pthread_mutex_lock(&node->pub_lock);
	r = hylo_plan_t_publish(node->out, node->ch_plan, msg);
	pthread_mutex_unlock(&node->pub_lock);
	if (r != 0) {
		node->n_publish_errors++;
		if (node->log)
			fprintf(node->log, "hylo-planner: could not publish on %s\n", node->ch_plan);
	}
}

/*
 * The alternatives of the plan just published (goal.alternatives >= 2), one
 * plan_alternative_t each, cheapest first. Each is extracted into the node's
 * plan in turn (its path fields; the rest stays the goal's plan's), so the
 * plan must be published before this.
 */
static void publish_alternatives(hylo_node *node, int64_t utime)
{
	hylo_plan *plan = node->plan;
	uint32_t k, n = plan->n_alternatives;
	hylo_plan_alternative_t alt;
	int r;

	if (node->current.goal.alternatives < 2 || plan->status != HYLO_OK)
		return;
	for (k = 0; k < n; k++) {
		if (hylo_planner_alternative(node->planner, k, plan) != HYLO_OK)
			return;
		memset(&alt, 0, sizeof alt);
		alt.utime = utime;
		alt.request_id = plan->request_id;
		alt.index = (int32_t)k;
		alt.count = (int32_t)n;
		alt.mode_changes = (int32_t)plan->alternative_switches[k];
		hylo_msg_plan(plan, utime, node->msg_buf, &alt.plan);
		pthread_mutex_lock(&node->pub_lock);
		r = hylo_plan_alternative_t_publish(node->out, node->ch_alternative, &alt);
		pthread_mutex_unlock(&node->pub_lock);
		if (r != 0) {
			node->n_publish_errors++;
			if (node->log)
				fprintf(node->log, "hylo-planner: could not publish on %s\n",
					node->ch_alternative);
			return;
		}
	}
}

static void log_request(hylo_node *node, const hylo_plan *plan)
{
	int8_t st = hylo_msg_plan_status(plan->status, plan->outcome);

	if (!node->log)
		return;
	fprintf(node->log,
		"request %" PRId64 ": %s, cost %.6g J, %u nodes, %" PRIu64 " edges evaluated, "
		"%.2f ms",
		plan->request_id, hylo_msg_plan_status_name(st), plan->total_cost, (unsigned)plan->n_nodes,
		plan->n_edges_evaluated, plan->plan_ms);
	if (st != HYLO_PLAN_T_STATUS_OK)
		fprintf(node->log, " (%s)", plan->reason.text);
	fputc('\n', node->log);
	fflush(node->log);
}

/*
 * Answers a goal at once, without planning (refused, superseded): an empty
 * plan. Admission side, under the lock; touches neither node->plan nor
 * node->msg_buf, which belong to the work side.
 */
#if defined(__GNUC__)
__attribute__((format(printf, 6, 7)))
#endif
static void answer_now(hylo_node *node, int64_t request_id, int8_t status, int64_t superseded_by,
		       int64_t map_id, const char *fmt, ...)
{
	char reason[HYLO_REASON_LEN];
	hylo_plan_t msg;
	va_list ap;

	va_start(ap, fmt);
	vsnprintf(reason, sizeof reason, fmt, ap);
	va_end(ap);
	hylo_msg_plan_empty(request_id, map_id, status, reason, utime_now(), &msg);
	msg.superseded_by = superseded_by;
	publish(node, &msg);
	node->n_answered++;
	if (status == HYLO_PLAN_T_STATUS_SUPERSEDED)
		node->n_superseded++;
	else
		node->n_refused++;
	if (node->log) {
		fprintf(node->log, "request %" PRId64 ": %s (%s)\n", request_id, hylo_msg_plan_status_name(status),
			reason);
		fflush(node->log);
	}
}

/* ---- status ------------------------------------------------------------- */

static void fill_status(hylo_node *node, hylo_node_status_t *s, int8_t event)
{
	memset(s, 0, sizeof *s);
	s->utime = utime_now();
	s->event = event;
	s->map_id = node->map_id;
	s->map_status = node->map_status;
	s->reason = "";
	s->current_map_id = node->map_id;
	s->goals_received = (int64_t)node->n_goals;
	s->goals_answered = (int64_t)node->n_answered;
	s->goals_planned = (int64_t)node->n_planned;
	s->goals_superseded = (int64_t)node->n_superseded;
	s->goals_refused = (int64_t)node->n_refused;
	s->queue_depth = (int32_t)node->q_len;
	s->queue_capacity = HYLO_NODE_QUEUE_LEN;
	s->maps_received = (int64_t)node->n_maps;
	s->maps_taken = (int64_t)node->n_maps_taken;
	s->maps_refused = (int64_t)node->n_maps_refused;
	s->recv_buf_bytes = node->recv_buf_bytes;
}

static void publish_status_msg(hylo_node *node, const hylo_node_status_t *s)
{
	int r;

	pthread_mutex_lock(&node->pub_lock);
	r = hylo_node_status_t_publish(node->out, node->ch_status, s);
	pthread_mutex_unlock(&node->pub_lock);
	if (r != 0)
		node->n_publish_errors++;
}

/* A map message was taken or refused: EVENT_MAP. Under the lock. */
static void map_event(hylo_node *node, int64_t map_id, int8_t status, const char *reason)
{
	hylo_node_status_t s;

	fill_status(node, &s, HYLO_NODE_STATUS_T_EVENT_MAP);
	s.map_id = map_id;
	s.map_status = status;
	s.reason = (char *)reason;
	publish_status_msg(node, &s);
	if (node->log && (status != HYLO_PLAN_T_STATUS_OK || node->verbose)) {
		fprintf(node->log, "map %" PRId64 ": %s%s%s\n", map_id, hylo_msg_plan_status_name(status),
			*reason ? ", " : "", reason);
		fflush(node->log);
	}
}

void hylo_node_publish_status(hylo_node *node, int8_t event)
{
	hylo_node_status_t s;

	pthread_mutex_lock(&node->lock);
	fill_status(node, &s, event);
	publish_status_msg(node, &s);
	pthread_mutex_unlock(&node->lock);
}

uint32_t hylo_node_queue_depth(hylo_node *node)
{
	uint32_t n;

	pthread_mutex_lock(&node->lock);
	n = node->q_len;
	pthread_mutex_unlock(&node->lock);
	return n;
}

void hylo_node_counts(hylo_node *node, uint64_t *received, uint64_t *answered)
{
	pthread_mutex_lock(&node->lock);
	if (received)
		*received = node->n_goals;
	if (answered)
		*answered = node->n_answered;
	pthread_mutex_unlock(&node->lock);
}

/* ---- admission ---------------------------------------------------------- */

static int map_known(const hylo_node *node, int64_t map_id)
{
	uint32_t k, n = node->n_map_ids < HYLO_NODE_MAP_HISTORY ? node->n_map_ids
								 : HYLO_NODE_MAP_HISTORY;

	for (k = 0; k < n; k++)
		if (node->map_ids[k] == map_id)
			return 1;
	return 0;
}

static void slot_fill(hylo_node_slot *s, const hylo_goal *g, int64_t requester_id)
{
	s->goal = *g;
	s->requester_id = requester_id;
}

/* The queue policy: one slot per requester, the newest goal wins and keeps
 * the replaced goal's place in the line. */
static void admit(hylo_node *node, const hylo_goal *g, int64_t requester_id)
{
	uint32_t k;

	for (k = 0; k < node->q_len; k++) {
		hylo_node_slot *s = &node->queue[(node->q_head + k) % HYLO_NODE_QUEUE_LEN];

		if (s->requester_id == requester_id) {
			int64_t old = s->goal.request_id;

			slot_fill(s, g, requester_id);
			answer_now(node, old, HYLO_PLAN_T_STATUS_SUPERSEDED, g->request_id,
				   node->map_id, "superseded by request %" PRId64
				   " of requester %" PRId64 " before it was planned",
				   g->request_id, requester_id);
			return;
		}
	}
	if (node->q_len == HYLO_NODE_QUEUE_LEN) {
		answer_now(node, g->request_id, HYLO_PLAN_T_STATUS_QUEUE_FULL, 0, node->map_id,
			   "goal queue full: %d other requesters have a goal waiting "
			   "(HYLO_NODE_QUEUE_LEN); send again later", HYLO_NODE_QUEUE_LEN);
		return;
	}
	slot_fill(&node->queue[(node->q_head + node->q_len) % HYLO_NODE_QUEUE_LEN], g,
		  requester_id);
	node->q_len++;
}

/* Under the lock. */
static void goal_locked(hylo_node *node, const void *data, int len)
{
	hylo_goal_t msg;
	hylo_goal goal;
	hylo_reason r;
	hylo_status st;
	int64_t request_id;
	/* A map waiting, or being taken right now (set_map runs unlocked): the
	 * goal waits for it like a goal for the current map. */
	const hylo_node_map_slot *pending = node->map_pending, *taking = node->map_busy;

	node->n_goals++;
	if (hylo_msg_check_goal(data, len, &request_id, &r) != HYLO_OK) {
		answer_now(node, request_id, HYLO_PLAN_T_STATUS_BAD_REQUEST, 0, node->map_id, "%s",
			   r.text);
		return;
	}
	if (hylo_goal_t_decode(data, 0, len, &msg) < 0) {
		answer_now(node, request_id, HYLO_PLAN_T_STATUS_BAD_REQUEST, 0, node->map_id,
			   "goal_t message could not be decoded");
		return;
	}
	hylo_msg_goal_view(&msg, &goal);
	st = hylo_goal_check(&goal, &r);
	if (msg.request_id == HYLO_GOAL_T_REQUEST_ID_UNREADABLE)
		answer_now(node, msg.request_id, HYLO_PLAN_T_STATUS_BAD_REQUEST, 0, node->map_id,
			   "request_id %" PRId64 " is reserved (goal_t.REQUEST_ID_UNREADABLE)",
			   msg.request_id);
	else if (st != HYLO_OK)
		answer_now(node, msg.request_id, hylo_msg_plan_status(st, HYLO_NO_PATH), 0,
			   node->map_id, "%s", r.text);
	else if (goal.map_id != 0 && goal.map_id != node->map_id &&
		 !(pending && goal.map_id == pending->view.map_id) &&
		 !(taking && goal.map_id == taking->view.map_id)) {
		if (map_known(node, goal.map_id))
			answer_now(node, msg.request_id, HYLO_PLAN_T_STATUS_MAP_REPLACED, 0,
				   node->map_id, "goal is for map %" PRId64 ", which has been "
				   "replaced; the current map is %" PRId64, goal.map_id,
				   node->map_id);
		else
			answer_now(node, msg.request_id, HYLO_PLAN_T_STATUS_UNKNOWN_MAP, 0,
				   node->map_id, "goal is for map %" PRId64 ", which this node "
				   "has not received or not taken (see HYLO_STATUS); the current "
				   "map is %" PRId64, goal.map_id, node->map_id);
	} else {
		admit(node, &goal, msg.requester_id);
	}
	hylo_goal_t_decode_cleanup(&msg);
}

void hylo_node_goal(hylo_node *node, const void *data, int len)
{
	pthread_mutex_lock(&node->lock);
	/* --once: a provider may deliver several messages in one handle call. */
	if (!(node->goal_limit && node->n_goals >= node->goal_limit)) {
		goal_locked(node, data, len);
		pthread_cond_signal(&node->wake);
	}
	pthread_mutex_unlock(&node->lock);
}

/* A decoded map the node can store: 0, or -1 with a status event. */
static int map_fits(hylo_node *node, const hylo_map_t *msg)
{
	char why[HYLO_REASON_LEN];

	if (msg->n_cells > HYLO_MAX_CELLS) {
		snprintf(why, sizeof why, "map: %ld cells, more than HYLO_MAX_CELLS = %ld",
			 (long)msg->n_cells, (long)HYLO_MAX_CELLS);
		map_event(node, msg->map_id, HYLO_PLAN_T_STATUS_OVER_CAPACITY, why);
		return -1;
	}
	if (strlen(msg->robot) >= HYLO_NAME_LEN) {
		snprintf(why, sizeof why, "map: robot name longer than %d characters",
			 HYLO_NAME_LEN - 1);
		map_event(node, msg->map_id, HYLO_PLAN_T_STATUS_BAD_REQUEST, why);
		return -1;
	}
	return 0;
}

static void map_copy(const hylo_map_t *msg, hylo_node_map_slot *slot)
{
	size_t n = (size_t)msg->n_cells;

	hylo_msg_map_view(msg, &slot->view);
	strcpy(slot->robot, msg->robot);
	memcpy(slot->terrain, msg->terrain, n);
	memcpy(slot->height, msg->height_m, n * sizeof *slot->height);
	slot->view.robot = slot->robot;
	slot->view.terrain = slot->terrain;
	slot->view.height = slot->height;
}

void hylo_node_map(hylo_node *node, const void *data, int len)
{
	hylo_map_t msg;
	hylo_node_map_slot *slot;
	hylo_reason r;
	int64_t map_id;

	pthread_mutex_lock(&node->lock);
	node->n_maps++;
	/* An undecodable message is not a map: the current one stays. */
	if (hylo_msg_check_map(data, len, &map_id, &r) != HYLO_OK ||
	    hylo_map_t_decode(data, 0, len, &msg) < 0) {
		node->n_maps_refused++;
		map_event(node, map_id, HYLO_PLAN_T_STATUS_BAD_REQUEST, r.text);
		pthread_mutex_unlock(&node->lock);
		return;
	}
	if (map_fits(node, &msg) != 0) {
		node->n_maps_refused++;
	} else {
		/* A map still waiting is replaced; else the slot the work side is not in. */
		slot = node->map_pending;
		if (slot) {
			node->n_maps_refused++;
			map_event(node, slot->view.map_id, HYLO_PLAN_T_STATUS_SUPERSEDED,
				  "a newer map arrived before this one was taken");
		} else {
			slot = node->map_busy == &node->maps[0] ? &node->maps[1] : &node->maps[0];
		}
		map_copy(&msg, slot);
		node->map_ids[node->n_map_ids++ % HYLO_NODE_MAP_HISTORY] = msg.map_id;
		node->map_pending = slot;
		pthread_cond_signal(&node->wake);
	}
	pthread_mutex_unlock(&node->lock);
	hylo_map_t_decode_cleanup(&msg);
}

/* ---- work --------------------------------------------------------------- */

/* Takes the pending map, if any: 1 when one was taken or refused. */
static int take_map(hylo_node *node)
{
	hylo_node_map_slot *slot;
	hylo_status st;
	int8_t status;

	pthread_mutex_lock(&node->lock);
	slot = node->map_pending;
	node->map_pending = NULL;
	node->map_busy = slot;
	pthread_mutex_unlock(&node->lock);
	if (!slot)
		return 0;
	st = hylo_planner_set_map(node->planner, &slot->view);
	status = st == HYLO_OK ? HYLO_PLAN_T_STATUS_OK : hylo_msg_plan_status(st, HYLO_NO_PATH);
	pthread_mutex_lock(&node->lock);
	node->map_busy = NULL;
	node->map_id = slot->view.map_id;
	node->map_status = status;
	if (st == HYLO_OK)
		node->n_maps_taken++;
	else
		node->n_maps_refused++;
	map_event(node, slot->view.map_id, status,
		  st == HYLO_OK ? "" : hylo_planner_reason(node->planner));
	if (st == HYLO_OK && node->log && node->verbose)
		fprintf(node->log, "map %" PRId64 ": robot %s, %d x %d cells of %g m\n",
			slot->view.map_id, slot->view.robot, (int)slot->view.nx,
			(int)slot->view.ny, slot->view.resolution);
	pthread_mutex_unlock(&node->lock);
	return 1;
}

int hylo_node_step(hylo_node *node)
{
	hylo_node_slot *cur = &node->current;
	hylo_plan_t msg;
	int64_t utime;
	int took_map = take_map(node);

	pthread_mutex_lock(&node->lock);
	if (node->q_len == 0) {
		pthread_mutex_unlock(&node->lock);
		return took_map ? 0 : -1;
	}
	*cur = node->queue[node->q_head];
	node->q_head = (node->q_head + 1) % HYLO_NODE_QUEUE_LEN;
	node->q_len--;
	pthread_mutex_unlock(&node->lock);

	hylo_planner_plan(node->planner, &cur->goal, node->plan);
	utime = utime_now();
	hylo_msg_plan(node->plan, utime, node->msg_buf, &msg);
	publish(node, &msg);
	log_request(node, node->plan);
	publish_alternatives(node, utime);

	pthread_mutex_lock(&node->lock);
	node->n_planned++;
	node->n_answered++;
	pthread_mutex_unlock(&node->lock);
	return 1;
}

int hylo_node_wait(hylo_node *node, int timeout_ms)
{
	struct timespec until;
	int work;

	clock_gettime(CLOCK_REALTIME, &until);
	until.tv_sec += timeout_ms / 1000;
	until.tv_nsec += (long)(timeout_ms % 1000) * 1000000L;
	if (until.tv_nsec >= 1000000000L) {
		until.tv_sec++;
		until.tv_nsec -= 1000000000L;
	}
	pthread_mutex_lock(&node->lock);
	while (!node->stop && !node->map_pending && node->q_len == 0)
		if (pthread_cond_timedwait(&node->wake, &node->lock, &until) == ETIMEDOUT)
			break;
	work = node->stop ? -1 : node->map_pending || node->q_len > 0;
	pthread_mutex_unlock(&node->lock);
	return work;
}

void hylo_node_stop(hylo_node *node)
{
	pthread_mutex_lock(&node->lock);
	node->stop = 1;
	pthread_cond_broadcast(&node->wake);
	pthread_mutex_unlock(&node->lock);
}

/* ---- set-up ------------------------------------------------------------- */

static void on_goal(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
	(void)channel;
	hylo_node_goal(user, rbuf->data, (int)rbuf->data_size);
}

static void on_map(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
	(void)channel;
	hylo_node_map(user, rbuf->data, (int)rbuf->data_size);
}

static int channel(char *out, const char *prefix, const char *name, FILE *log)
{
	int n = snprintf(out, HYLO_NODE_CHANNEL_LEN, "%s%s", prefix, name);

	if (n < 0 || n >= HYLO_NODE_CHANNEL_LEN) {
		if (log)
			fprintf(log, "hylo-planner: channel prefix too long (at most %d characters)\n",
				HYLO_NODE_CHANNEL_LEN - 1 - (int)strlen(name));
		return -1;
	}
	return 0;
}

int hylo_node_init(hylo_node *node, lcm_t *in, lcm_t *out, const char *prefix,
		   hylo_planner *planner, hylo_plan *plan, hylo_plan_msg_buf *buf,
		   FILE *log, int verbose)
{
	lcm_subscription_t *s_map, *s_goal;

	memset(node, 0, sizeof *node);
	node->in = in;
	node->out = out;
	node->planner = planner;
	node->plan = plan;
	node->msg_buf = buf;
	node->log = log;
	node->verbose = verbose;
	node->map_status = HYLO_PLAN_T_STATUS_NO_MAP;
	if (pthread_mutex_init(&node->lock, NULL) != 0)
		return -1;
	if (pthread_mutex_init(&node->pub_lock, NULL) != 0) {
		pthread_mutex_destroy(&node->lock);
		return -1;
	}
	if (pthread_cond_init(&node->wake, NULL) != 0) {
		pthread_mutex_destroy(&node->pub_lock);
		pthread_mutex_destroy(&node->lock);
		return -1;
	}
	if (channel(node->ch_map, prefix, "HYLO_MAP", log) ||
	    channel(node->ch_goal, prefix, "HYLO_GOAL", log) ||
	    channel(node->ch_plan, prefix, "HYLO_PLAN", log) ||
	    channel(node->ch_alternative, prefix, "HYLO_PLAN_ALTERNATIVE", log) ||
	    channel(node->ch_status, prefix, "HYLO_STATUS", log))
		goto fail;
	/* Raw subscriptions: a goal that does not decode still gets an answer. */
	s_map = lcm_subscribe(in, node->ch_map, on_map, node);
	s_goal = lcm_subscribe(in, node->ch_goal, on_goal, node);
	if (!s_map || !s_goal) {
		if (log)
			fprintf(log, "hylo-planner: cannot subscribe\n");
		goto fail;
	}
	lcm_subscription_set_queue_capacity(s_map, HYLO_NODE_LCM_QUEUE);
	lcm_subscription_set_queue_capacity(s_goal, HYLO_NODE_LCM_QUEUE);
	return 0;
fail:
	pthread_cond_destroy(&node->wake);
	pthread_mutex_destroy(&node->pub_lock);
	pthread_mutex_destroy(&node->lock);
	return -1;
}

void hylo_node_destroy(hylo_node *node)
{
	pthread_cond_destroy(&node->wake);
	pthread_mutex_destroy(&node->pub_lock);
	pthread_mutex_destroy(&node->lock);
}
