#include <inttypes.h>
#include <string.h>
#include <sys/time.h>

#include "node/node.h"

static int64_t utime_now(void)
{
	struct timeval tv;

	gettimeofday(&tv, NULL);
	return (int64_t)tv.tv_sec * 1000000 + tv.tv_usec;
}

static void publish_plan(hylo_node *node, const hylo_plan *plan)
{
	hylo_plan_t msg;

	hylo_msg_plan(plan, utime_now(), node->msg_buf, &msg);
	if (hylo_plan_t_publish(node->out, node->ch_plan, &msg) != 0) {
		node->n_publish_errors++;
		if (node->log)
			fprintf(node->log, "hylo-planner: could not publish on %s\n", node->ch_plan);
	}
}

static void log_request(hylo_node *node, const hylo_plan *plan)
{
	static const char *const names[] = { "ok", "no map", "no path", "bad request",
					     "over capacity", "budget exhausted", "map replaced",
					     "no model" };
	int8_t st = hylo_msg_plan_status(plan->status, plan->outcome);

	if (!node->log)
		return;
	fprintf(node->log,
		"request %" PRId64 ": %s, cost %.6g J, %u nodes, %" PRIu64 " edges evaluated, "
		"%.2f ms",
		plan->request_id, st >= 0 && st < 8 ? names[st] : "?", plan->total_cost,
		(unsigned)plan->n_nodes, plan->n_edges_evaluated, plan->plan_ms);
	if (st != HYLO_PLAN_T_STATUS_OK)
		fprintf(node->log, " (%s)", plan->reason.text);
	fputc('\n', node->log);
	fflush(node->log);
}

/* A plan that answers a request the planner never saw (undecodable goal). */
static void refuse(hylo_node *node, int64_t request_id, hylo_status st, const char *why)
{
	hylo_plan *plan = node->plan;

	plan->status = st;
	plan->outcome = HYLO_NO_PATH;
	plan->request_id = request_id;
	plan->map_id = node->map_id;
	plan->robot[0] = '\0';
	plan->total_cost = 0;
	plan->n_waypoints = 0;
	plan->n_modes = 0;
	plan->n_nodes = 0;
	plan->n_edges = plan->n_edges_evaluated = plan->n_expansions = 0;
	plan->n_clamped = plan->n_negative = 0;
	plan->plan_ms = 0;
	hylo_fail(&plan->reason, st, "%s", why);
}

void hylo_node_goal(hylo_node *node, const void *data, int len)
{
	hylo_goal_t msg;
	hylo_goal goal;
	hylo_reason r;
	int64_t request_id;

	/* --once: a provider may deliver several messages in one handle call. */
	if (node->goal_limit && node->n_goals >= node->goal_limit)
		return;
	node->n_goals++;
	if (hylo_msg_check_goal(data, len, &request_id, &r) != HYLO_OK ||
	    hylo_goal_t_decode(data, 0, len, &msg) < 0) {
		refuse(node, request_id, HYLO_E_BAD_VALUE, r.text);
	} else {
		hylo_msg_goal_view(&msg, &goal);
		hylo_planner_plan(node->planner, &goal, node->plan);
		hylo_goal_t_decode_cleanup(&msg);
	}
	publish_plan(node, node->plan);
	log_request(node, node->plan);
}

void hylo_node_map(hylo_node *node, const void *data, int len)
{
	hylo_map_t msg;
	hylo_map_view view;
	hylo_reason r;
	hylo_status st;
	int64_t map_id;

	node->n_maps++;
	/* An undecodable message is not a map: the current one stays. */
	if (hylo_msg_check_map(data, len, &map_id, &r) != HYLO_OK ||
	    hylo_map_t_decode(data, 0, len, &msg) < 0) {
		if (node->log)
			fprintf(node->log, "map message ignored (map %" PRId64 " stays): %s\n",
				node->map_id, r.text);
		return;
	}
	hylo_msg_map_view(&msg, &view);
	st = hylo_planner_set_map(node->planner, &view);
	node->map_id = msg.map_id;
	if (st != HYLO_OK) {
		if (node->log)
			fprintf(node->log, "map %" PRId64 " refused: %s\n", msg.map_id,
				hylo_planner_reason(node->planner));
	} else if (node->log && node->verbose) {
		fprintf(node->log, "map %" PRId64 ": robot %s, %d x %d cells of %g m\n",
			msg.map_id, msg.robot, msg.nx, msg.ny, msg.resolution_m);
	}
	if (node->log)
		fflush(node->log);
	hylo_map_t_decode_cleanup(&msg);
}

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
	memset(node, 0, sizeof *node);
	node->in = in;
	node->out = out;
	node->planner = planner;
	node->plan = plan;
	node->msg_buf = buf;
	node->log = log;
	node->verbose = verbose;
	if (channel(node->ch_map, prefix, "HYLO_MAP", log) ||
	    channel(node->ch_goal, prefix, "HYLO_GOAL", log) ||
	    channel(node->ch_plan, prefix, "HYLO_PLAN", log))
		return -1;
	/* Raw subscriptions: a goal that does not decode still gets an answer. */
	if (!lcm_subscribe(in, node->ch_map, on_map, node) ||
	    !lcm_subscribe(in, node->ch_goal, on_goal, node)) {
		if (log)
			fprintf(log, "hylo-planner: cannot subscribe\n");
		return -1;
	}
	return 0;
}
