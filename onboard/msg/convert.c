#include "hylo_msg.h"

#include <string.h>

void hylo_msg_map_view(const hylo_map_t *msg, hylo_map_view *v)
{
	v->map_id = msg->map_id;
	v->robot = msg->robot;
	v->nx = msg->nx;
	v->ny = msg->ny;
	v->resolution = msg->resolution_m;
	v->origin_x = msg->origin_x_m;
	v->origin_y = msg->origin_y_m;
	v->ceiling = msg->ceiling_m;
	v->max_step = msg->max_step_m;
	v->n_cells = msg->n_cells;
	v->terrain = msg->terrain;
	v->height = msg->height_m;
}

void hylo_msg_map(const hylo_map_view *v, hylo_map_t *msg)
{
	memset(msg, 0, sizeof *msg);
	msg->map_id = v->map_id;
	msg->robot = (char *)v->robot;
	msg->nx = v->nx;
	msg->ny = v->ny;
	msg->resolution_m = v->resolution;
	msg->origin_x_m = v->origin_x;
	msg->origin_y_m = v->origin_y;
	msg->ceiling_m = v->ceiling;
	msg->max_step_m = v->max_step;
	msg->n_cells = v->n_cells;
	msg->terrain = (int8_t *)v->terrain;
	msg->height_m = (float *)v->height;
}

typedef char hylo_check_default_alternatives[HYLO_GOAL_T_DEFAULT_ALTERNATIVES == HYLO_DEFAULT_ALTERNATIVES ? 1 : -1];

static uint32_t count(int32_t n)
{
	/* A negative count from the wire is out of range: say so as too large. */
	return n < 0 ? UINT32_MAX : (uint32_t)n;
}

/* Copies a grid of n entries from the wire into dst (HYLO_MAX_GRID entries)
 * and returns its count; a longer grid is not copied, its count stays for
 * hylo_goal_check to refuse. */
static uint32_t grid(hylo_real *dst, const double *src, int32_t n)
{
	if (n > 0 && n <= HYLO_MAX_GRID)
		memcpy(dst, src, (size_t)n * sizeof *dst);
	return count(n);
}

void hylo_msg_goal_view(const hylo_goal_t *msg, hylo_goal *g)
{
	memset(g, 0, sizeof *g);
	g->request_id = msg->request_id;
	g->map_id = msg->map_id;
	g->algorithm = msg->algorithm;
	g->start_mode = msg->start_mode;
	g->goal_mode = msg->goal_mode;
	memcpy(g->start, msg->start, sizeof g->start);
	memcpy(g->goal, msg->goal, sizeof g->goal);
	g->sampling.seed = (uint64_t)msg->seed;
	g->sampling.spacing = msg->spacing_m;
	g->sampling.air_spacing = msg->air_spacing_m;
	g->sampling.guard_spacing = msg->guard_spacing_m;
	g->sampling.connect_radius = msg->connect_radius_m;
	g->sampling.air_connect_radius = msg->air_connect_radius_m;
	g->sampling.n_speeds = grid(g->sampling.speeds, msg->speeds_mps, msg->n_speeds);
	g->sampling.n_headings = grid(g->sampling.headings, msg->headings_rad, msg->n_headings);
	g->sampling.n_air_speeds = grid(g->sampling.air_speeds, msg->air_speeds_mps, msg->n_air_speeds);
	g->time_budget_ms = msg->time_budget_ms;
	/* Negative: refused by hylo_msg_check_goal; 0 (no limit) if it gets here. */
	g->max_expansions = msg->max_expansions < 0 ? 0 : (uint64_t)msg->max_expansions;
	g->suboptimality = msg->suboptimality;
	g->alternatives = msg->alternatives == 0 ? HYLO_DEFAULT_ALTERNATIVES : count(msg->alternatives);
	g->alternatives_within = msg->alternatives_within;
}

/* A grid's count on the wire: at most the HYLO_MAX_GRID entries a goal holds. */
static int32_t wire_count(uint32_t n)
{
	return (int32_t)(n < HYLO_MAX_GRID ? n : HYLO_MAX_GRID);
}

void hylo_msg_goal(const hylo_goal *g, hylo_goal_t *msg)
{
	const hylo_sampling *s = &g->sampling;

	memset(msg, 0, sizeof *msg);
	msg->request_id = g->request_id;
	msg->map_id = g->map_id;
	msg->algorithm = (int8_t)g->algorithm;
	msg->start_mode = (int8_t)g->start_mode;
	msg->goal_mode = (int8_t)g->goal_mode;
	memcpy(msg->start, g->start, sizeof msg->start);
	memcpy(msg->goal, g->goal, sizeof msg->goal);
	msg->seed = (int64_t)s->seed;
	msg->spacing_m = s->spacing;
	msg->air_spacing_m = s->air_spacing;
	msg->guard_spacing_m = s->guard_spacing;
	msg->connect_radius_m = s->connect_radius;
	msg->air_connect_radius_m = s->air_connect_radius;
	msg->n_speeds = wire_count(s->n_speeds);
	msg->speeds_mps = (double *)s->speeds;
	msg->n_headings = wire_count(s->n_headings);
	msg->headings_rad = (double *)s->headings;
	msg->n_air_speeds = wire_count(s->n_air_speeds);
	msg->air_speeds_mps = (double *)s->air_speeds;
	msg->time_budget_ms = g->time_budget_ms;
	msg->max_expansions = (int32_t)g->max_expansions;
	msg->suboptimality = g->suboptimality;
	msg->alternatives = (int8_t)g->alternatives;
	msg->alternatives_within = g->alternatives_within;
}

const char *hylo_msg_plan_status_name(int8_t status)
{
	/* Indexed by plan_t.STATUS_* (msgs/plan_t.lcm). */
	static const char *const names[] = {
		"ok", "no map", "no path", "bad request", "over capacity", "budget exhausted",
		"map replaced", "no model", "not proven optimal", "superseded", "unknown map",
		"queue full"
	};

	return status >= 0 && status < (int)(sizeof names / sizeof *names) ? names[status] : "unknown";
}

int8_t hylo_msg_plan_status(hylo_status status, hylo_outcome outcome)
{
	if (status == HYLO_OK) {
		if (outcome == HYLO_FOUND)
			return HYLO_PLAN_T_STATUS_OK;
		if (outcome == HYLO_BUDGET_EXHAUSTED)
			return HYLO_PLAN_T_STATUS_BUDGET_EXHAUSTED;
		if (outcome == HYLO_FOUND_UNPROVEN)
			return HYLO_PLAN_T_STATUS_NOT_PROVEN;
		return HYLO_PLAN_T_STATUS_NO_PATH;
	}
	if (status >= HYLO_E_CAP_CELLS && status <= HYLO_E_CAP_ROBOTS)
		return HYLO_PLAN_T_STATUS_OVER_CAPACITY;
	switch (status) {
	case HYLO_E_NO_MAP:
		return HYLO_PLAN_T_STATUS_NO_MAP;
	case HYLO_E_MAP_MISMATCH:
		return HYLO_PLAN_T_STATUS_MAP_REPLACED;
	case HYLO_E_NO_MODEL:
		return HYLO_PLAN_T_STATUS_NO_MODEL;
	default:
		return HYLO_PLAN_T_STATUS_BAD_REQUEST;
	}
}

void hylo_msg_plan_empty(int64_t request_id, int64_t map_id, int8_t status, const char *reason,
			 int64_t utime, hylo_plan_t *msg)
{
	memset(msg, 0, sizeof *msg);
	msg->utime = utime;
	msg->request_id = request_id;
	msg->map_id = map_id;
	msg->status = status;
	msg->reason = (char *)reason;
	msg->robot = "";
}

void hylo_msg_plan(const hylo_plan *plan, int64_t utime, hylo_plan_msg_buf *buf,
		   hylo_plan_t *msg)
{
	uint32_t k, n = plan->n_waypoints;

	hylo_msg_plan_empty(plan->request_id, plan->map_id, hylo_msg_plan_status(plan->status, plan->outcome),
			    plan->reason.text, utime, msg);
	msg->robot = (char *)plan->robot;
	msg->total_cost_j = plan->total_cost;
	msg->suboptimality = plan->suboptimality;
	msg->lower_bound_j = plan->lower_bound;
	msg->n_waypoints = (int32_t)n;
	for (k = 0; k < n; k++) {
		buf->mode[k] = (int8_t)plan->mode[k];
		buf->guard[k] = (int8_t)plan->guard[k];
		buf->state_rows[k] = (double *)plan->state[k];
	}
	for (k = 0; k < plan->n_modes; k++)
		buf->mode_sequence[k] = (int8_t)plan->mode_sequence[k];
	msg->mode = buf->mode;
	msg->state = buf->state_rows;
	msg->cost_j = (double *)plan->cost;
	msg->guard = buf->guard;
	msg->n_modes = (int32_t)plan->n_modes;
	msg->mode_sequence = buf->mode_sequence;
	msg->n_nodes = (int32_t)plan->n_nodes;
	msg->n_edges = (int64_t)plan->n_edges;
	msg->n_edges_evaluated = (int64_t)plan->n_edges_evaluated;
	msg->n_edges_cached = (int64_t)plan->n_edges_cached;
	msg->n_expansions = (int64_t)plan->n_expansions;
	msg->n_clamped = (int64_t)plan->n_clamped;
	msg->plan_ms = plan->plan_ms;
}
