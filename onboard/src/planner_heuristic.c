#include <math.h>
#include <string.h>

#include "planner_internal.h"

/*
 * The A* heuristic: exact shortest distances to the goal on the search graph
 * itself, every edge weighted by its bound (hylo_planner_bound: the
 * model's floor raised to its envelope for the edge's distance, speeds and,
 * where the envelope has them, turn or climb; the switch cost). Edge costs
 * are raised to their bound, so the heuristic is admissible and consistent,
 * and it sees obstacles, water, mode changes and the costs of changing
 * speed and heading. Computed by one backward Dijkstra over every node (no
 * model evaluation, one envelope lookup per edge), with one extra node that
 * is never reached so that it runs to exhaustion; nodes that cannot reach
 * the goal get +inf and are never expanded. It depends on the goal and the
 * roadmap only: a new start on the same goal reuses it.
 */

/* The switch edges into node v (position j) from j's guard twin. */
static hylo_status switch_predecessors(hylo_planner *pl, const hylo_search *s, uint32_t v,
				       uint32_t *heads, hylo_real *costs, uint32_t cap, uint32_t *n)
{
	const hylo_roadmap *rm = &pl->roadmap;
	uint32_t j = rm->node_pos[v], t = rm->pos[j].twin, c, k, m, combos[HYLO_MAX_COMBOS];

	if (j >= rm->n_positions || t == HYLO_NO_POSITION)
		return HYLO_OK;
	for (c = 0; c < rm->pos[t].n_combos; c++) {
		uint32_t u = rm->pos[t].node_base + c;

		if (hylo_search_closed(s, u))
			continue;
		m = hylo_roadmap_switch_heads(rm, t, c, combos);
		for (k = 0; k < m; k++) {
			if (rm->pos[j].node_base + combos[k] != v)
				continue;
			if (*n >= cap)
				return hylo_fail(&pl->reason, HYLO_E_CAP_SUCCESSORS,
						 "the heuristic: more than HYLO_MAX_SUCCESSORS = %d predecessors",
						 HYLO_MAX_SUCCESSORS);
			heads[*n] = u;
			costs[(*n)++] = hylo_planner_switch_cost(pl, t);
		}
	}
	return HYLO_OK;
}

static hylo_status expand_backward(void *ctx, hylo_search *s, uint32_t v, uint32_t *heads,
				   hylo_real *costs, uint32_t cap, uint32_t *n, hylo_reason *r)
{
	hylo_planner *pl = ctx;
	const hylo_roadmap *rm = &pl->roadmap;
	uint32_t j, k, c, n_pred;
	const uint32_t *pred;
	hylo_real head[HYLO_XS_DIM], tail[HYLO_XS_DIM];

	(void)r;
	*n = 0;
	if (v >= rm->n_nodes + 2)
		return HYLO_OK;
	j = rm->node_pos[v];
	if (j == pl->start_pos)
		return HYLO_OK;
	hylo_planner_node_state(pl, j, v - rm->pos[j].node_base, head);
	/* Same-mode neighbours are symmetric: j's list is also its predecessors. */
	if (j == pl->goal_pos) {
		pred = pl->goal_adj;
		n_pred = pl->n_goal_adj;
	} else {
		pred = hylo_planner_neighbours(pl, j, &n_pred);
	}
	for (k = 0; k < n_pred; k++) {
		const hylo_position *p = &rm->pos[pred[k]];
		hylo_pair_bound pb;

		hylo_planner_pair_bound(pl, pred[k], j, &pb);
		for (c = 0; c < p->n_combos; c++) {
			uint32_t u = p->node_base + c;

			if (hylo_search_closed(s, u))
				continue;
			if (*n >= cap)
				return hylo_fail(&pl->reason, HYLO_E_CAP_SUCCESSORS,
						 "the heuristic: more than HYLO_MAX_SUCCESSORS = %d predecessors",
						 HYLO_MAX_SUCCESSORS);
			hylo_roadmap_state(rm, pred[k], c, tail);
			heads[*n] = u;
			costs[(*n)++] = hylo_planner_bound(&pb, tail, head);
		}
	}
	return switch_predecessors(pl, s, v, heads, costs, cap, n);
}

/* 1 when h was computed for this goal on this roadmap. */
static int still_valid(const hylo_planner *pl)
{
	return pl->h_valid && pl->h_goal_mode == pl->roadmap.pos[pl->goal_pos].mode &&
	       memcmp(pl->h_goal_xs, pl->goal_xs, sizeof pl->h_goal_xs) == 0;
}

/* The start has no incoming edges; its bound comes from its edges out. */
static void start_heuristic(hylo_planner *pl)
{
	const hylo_roadmap *rm = &pl->roadmap;
	uint32_t k, c, n_adj;
	const uint32_t *adj = hylo_planner_neighbours(pl, pl->start_pos, &n_adj);
	hylo_real best = INFINITY, head[HYLO_XS_DIM];
	hylo_pair_bound pb;

	if (pl->start_goal_linked) {
		hylo_planner_pair_bound(pl, pl->start_pos, pl->goal_pos, &pb);
		best = hylo_planner_bound(&pb, pl->start_xs, pl->goal_xs);
	}
	for (k = 0; k < n_adj; k++) {
		const hylo_position *q = &rm->pos[adj[k]];

		hylo_planner_pair_bound(pl, pl->start_pos, adj[k], &pb);
		for (c = 0; c < q->n_combos; c++) {
			hylo_real v;

			hylo_roadmap_state(rm, adj[k], c, head);
			v = hylo_planner_bound(&pb, pl->start_xs, head) + pl->h_node[q->node_base + c];
			if (v < best)
				best = v;
		}
	}
	pl->h_node[rm->n_nodes] = best;
}

hylo_status hylo_planner_heuristic(hylo_planner *pl, const hylo_budget *budget)
{
	const hylo_roadmap *rm = &pl->roadmap;
	hylo_graph g;
	hylo_outcome outcome;
	uint32_t v;
	hylo_status st;

	if (!still_valid(pl)) {
		pl->h_valid = 0;
		g.n_nodes = rm->n_nodes + 3;
		g.expand = expand_backward;
		g.resolve = NULL;
		g.heuristic = NULL;
		g.weight = 1;
		g.ctx = pl;
		st = hylo_search_run(&pl->search, &g, rm->n_nodes + 1, rm->n_nodes + 2, budget, &outcome,
				     &pl->reason);
		if (st != HYLO_OK)
			return st;
		for (v = 0; v < rm->n_nodes + 2; v++)
			pl->h_node[v] = hylo_search_cost(&pl->search, v);
		pl->h_valid = 1;
		pl->h_goal_mode = rm->pos[pl->goal_pos].mode;
		memcpy(pl->h_goal_xs, pl->goal_xs, sizeof pl->h_goal_xs);
	}
	start_heuristic(pl);
	return HYLO_OK;
}
