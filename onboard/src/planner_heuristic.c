#include <math.h>

#include "planner_internal.h"

/*
 * The A* heuristic: exact shortest distances to the goal on the graph of
 * (position, speed class), each edge weighted by the bound of every node
 * edge it stands for (hylo_planner_edge_bound: the model's floor and its
 * envelope for the two speeds; the switch cost). Node edges are raised to
 * their bound, so the heuristic is admissible and consistent, and it sees
 * obstacles, water, mode changes and the cost of changing speed. Computed
 * per goal by one backward Dijkstra, with one extra node that is never
 * reached so that it runs to exhaustion; positions that cannot reach the
 * goal get +inf and are never expanded.
 */

/* Lays out the abstract nodes: abs_base[i] + k for class k of position i. */
static hylo_status layout(hylo_planner *pl)
{
	const hylo_roadmap *rm = &pl->roadmap;
	uint32_t i, k, n = 0, last = rm->n_positions + 2;

	for (i = 0; i < last; i++) {
		uint32_t m = hylo_planner_class_count(pl, i);

		if (m > HYLO_MAX_NODES - 1 - n)
			return hylo_fail(&pl->reason, HYLO_E_CAP_NODES,
					 "the heuristic needs more than HYLO_MAX_NODES = %d nodes",
					 HYLO_MAX_NODES);
		pl->abs_base[i] = n;
		for (k = 0; k < m; k++)
			pl->abs_pos[n + k] = i;
		n += m;
	}
	pl->abs_base[last] = n;
	pl->n_abs = n;
	return HYLO_OK;
}

/* Rest class of position i (speed 0), or HYLO_NO_NODE. */
static uint32_t rest_class(const hylo_planner *pl, uint32_t i)
{
	const hylo_roadmap *rm = &pl->roadmap;
	uint32_t k, m = hylo_planner_class_count(pl, i);

	for (k = 0; k < m; k++)
		if (hylo_roadmap_class_speed(rm, (hylo_mode)rm->pos[i].mode, k) == 0)
			return k;
	return HYLO_NO_NODE;
}

static hylo_status push(hylo_planner *pl, const hylo_search *s, uint32_t a, hylo_real cost,
			uint32_t *heads, hylo_real *costs, uint32_t cap, uint32_t *n)
{
	if (hylo_search_closed(s, a))
		return HYLO_OK;
	if (*n >= cap)
		return hylo_fail(&pl->reason, HYLO_E_CAP_SUCCESSORS,
				 "the heuristic: more than HYLO_MAX_SUCCESSORS = %d predecessors",
				 HYLO_MAX_SUCCESSORS);
	heads[*n] = a;
	costs[*n] = cost;
	(*n)++;
	return HYLO_OK;
}

/* The switch edges into (j, kj) from j's guard twin. */
static hylo_status switch_predecessors(hylo_planner *pl, const hylo_search *s, uint32_t j,
				       uint32_t kj, uint32_t *heads, hylo_real *costs,
				       uint32_t cap, uint32_t *n)
{
	const hylo_roadmap *rm = &pl->roadmap;
	uint32_t t = rm->pos[j].twin, kt = kj;

	if (j >= rm->n_positions || t == HYLO_NO_POSITION)
		return HYLO_OK;
	if (rm->pos[j].mode == HYLO_MODE_FLIGHT || rm->pos[t].mode == HYLO_MODE_FLIGHT) {
		/* Takeoff and landing join rest states only. */
		if (kj != rest_class(pl, j))
			return HYLO_OK;
		kt = rest_class(pl, t);
		if (kt == HYLO_NO_NODE)
			return HYLO_OK;
	}
	return push(pl, s, pl->abs_base[t] + kt, hylo_planner_switch_cost(pl, t), heads, costs, cap, n);
}

static hylo_status expand_backward(void *ctx, hylo_search *s, uint32_t a, uint32_t *heads,
				   hylo_real *costs, uint32_t cap, uint32_t *n, hylo_reason *r)
{
	hylo_planner *pl = ctx;
	const hylo_roadmap *rm = &pl->roadmap;
	uint32_t j, kj, k, ki, n_pred;
	const uint32_t *pred;
	hylo_status st = HYLO_OK;

	(void)r;
	*n = 0;
	if (a >= pl->n_abs)
		return HYLO_OK;
	j = pl->abs_pos[a];
	kj = a - pl->abs_base[j];
	if (j == pl->start_pos)
		return HYLO_OK;
	/* Same-mode neighbours are symmetric: j's list is also its predecessors. */
	if (j == pl->goal_pos) {
		pred = pl->goal_adj;
		n_pred = pl->n_goal_adj;
	} else {
		pred = hylo_planner_neighbours(pl, j, &n_pred);
	}
	for (k = 0; k < n_pred && st == HYLO_OK; k++) {
		uint32_t i = pred[k], m = hylo_planner_class_count(pl, i);

		for (ki = 0; ki < m && st == HYLO_OK; ki++)
			st = push(pl, s, pl->abs_base[i] + ki, hylo_planner_edge_bound(pl, i, ki, j, kj),
				  heads, costs, cap, n);
	}
	if (st == HYLO_OK && j < rm->n_positions)
		st = switch_predecessors(pl, s, j, kj, heads, costs, cap, n);
	return st;
}

hylo_status hylo_planner_heuristic(hylo_planner *pl, const hylo_budget *budget)
{
	hylo_graph g;
	hylo_outcome outcome;
	hylo_real best;
	uint32_t a, k, goal, n_adj;
	const uint32_t *adj;
	hylo_status st;

	st = layout(pl);
	if (st != HYLO_OK)
		return st;
	goal = pl->abs_base[pl->goal_pos];
	g.n_nodes = pl->n_abs + 1;
	g.expand = expand_backward;
	g.resolve = NULL;
	g.heuristic = NULL;
	g.weight = 1;
	g.ctx = pl;
	st = hylo_search_run(&pl->search, &g, goal, pl->n_abs, budget, &outcome, &pl->reason);
	if (st != HYLO_OK)
		return st;
	for (a = 0; a < pl->n_abs; a++)
		pl->h_abs[a] = hylo_search_cost(&pl->search, a);
	/* The start has no incoming edges; its bound comes from its edges out. */
	best = pl->start_goal_linked ? hylo_planner_edge_bound(pl, pl->start_pos, 0, pl->goal_pos, 0)
				     : INFINITY;
	adj = hylo_planner_neighbours(pl, pl->start_pos, &n_adj);
	for (k = 0; k < n_adj; k++) {
		uint32_t j = adj[k], kj, m = hylo_planner_class_count(pl, j);

		for (kj = 0; kj < m; kj++) {
			hylo_real v = hylo_planner_edge_bound(pl, pl->start_pos, 0, j, kj) +
				      pl->h_abs[pl->abs_base[j] + kj];

			if (v < best)
				best = v;
		}
	}
	pl->h_abs[pl->abs_base[pl->start_pos]] = best;
	return HYLO_OK;
}
