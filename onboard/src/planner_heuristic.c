#include <math.h>
#include <string.h>

#include "planner_internal.h"

/*
 * The A* heuristic: exact shortest distances to the goal on the search graph
 * itself, every edge weighted by its bound (hylo_planner_bound: the model's
 * floor raised to its envelope for the edge's distance, speeds and, where
 * the envelope has them, turn or climb; the switch cost). Edge costs are
 * raised to their bound, so the heuristic is admissible and consistent, and
 * it sees obstacles, water, mode switches and the costs of changing speed
 * and heading. One backward Dijkstra from the goal (no model evaluation, one
 * envelope lookup per edge) settles the nodes in order of their distance;
 * it stops once it has passed the start's own distance by a factor (reach),
 * and every node not settled by then gets that radius R, no more: still
 * admissible and consistent (an unsettled node's distance is at least R),
 * and a node beyond R could only be on a plan costing more than R. A new
 * start on the same goal reuses the distances when it lies well inside R.
 */


/* Node ids around the graph's: the goal's, and a sentinel the search
 * reaches once the radius is pl->h_reach times the start's distance. */
static uint32_t sentinel(const hylo_planner *pl)
{
	return pl->roadmap.n_nodes + 2;
}

/* Which copies of a tail an edge comes from: node ids tail + off[k] of the
 * search s, those closed left out (the plain heuristic: one copy, offset 0;
 * the layered one: the layers an edge can come from, planner_graph.c). */
typedef struct {
	const hylo_search *s;
	uint32_t off[2];
	uint32_t n_off;
	/* The search being expanded and its tail's cost g (NULL: none): heads
	 * the edge would not improve are left out, and, with beyond, those the
	 * search would never take: beyond[v] plus the head's cost reaches cap
	 * (the layered search's pruning by L; the forward search's keys after
	 * the last cap). */
	const hylo_search *improve;
	const hylo_real *beyond;
	hylo_real g, cap;
} copies;

/* 1 when the edge into v at cost would change nothing (see copies). */
static int useless(const copies *cp, uint32_t v, hylo_real cost)
{
	hylo_real g;

	if (!cp->improve)
		return 0;
	g = cp->g + cost;   /* as the search adds them */
	return !(g < hylo_search_cost_of(cp->improve, v)) ||
	       (cp->beyond && cp->beyond[v] + g >= cp->cap);
}

static hylo_status push(hylo_planner *pl, const copies *cp, uint32_t u, hylo_real cost,
			uint32_t *heads, hylo_real *costs, uint32_t cap, uint32_t *n)
{
	uint32_t k;

	for (k = 0; k < cp->n_off; k++) {
		if ((cp->s && hylo_search_closed(cp->s, u + cp->off[k])) ||
		    useless(cp, u + cp->off[k], cost))
			continue;
		if (*n >= cap)
			return hylo_fail(&pl->reason, HYLO_E_CAP_SUCCESSORS,
					 "the heuristic: more than HYLO_MAX_SUCCESSORS = %d predecessors",
					 HYLO_MAX_SUCCESSORS);
		heads[*n] = u + cp->off[k];
		costs[(*n)++] = cost;
	}
	return HYLO_OK;
}

/* Marks in open[c] the copies (bit k: off[k]) of node c of position i that
 * are not closed; 0 when none is. */
static int open_copies(const hylo_planner *pl, const copies *cp, uint32_t i, uint8_t *open)
{
	const hylo_position *p = &pl->roadmap.pos[i];
	uint32_t k;
	int any = 0;

	memset(open, 0, p->n_combos);
	for (k = 0; k < cp->n_off; k++)
		any |= hylo_search_mark_open(cp->s, p->node_base + cp->off[k], p->n_combos,
					     (uint8_t)(1u << k), open);
	return any;
}

/* 1 when every copy marked in open[] of the nodes of position p would be
 * left out as useless even through an edge costing floor (the least bound
 * of the pair's edges): their bounds need not be computed. */
static int all_useless(const copies *cp, const hylo_position *p, const uint8_t *open,
		       hylo_real floor)
{
	uint32_t c, k;

	for (c = 0; c < p->n_combos; c++)
		for (k = 0; k < cp->n_off; k++)
			if ((open[c] & (1u << k)) && !useless(cp, p->node_base + c + cp->off[k], floor))
				return 0;
	return 1;
}

/* Appends the copies open_copies marked in open[] of the nodes of
 * position p, node c's with cost lb[c]. */
static hylo_status push_open(hylo_planner *pl, const copies *cp, const hylo_position *p,
			     const uint8_t *open, const hylo_real *lb, uint32_t *heads, hylo_real *costs,
			     uint32_t cap, uint32_t *n)
{
	uint32_t c, k, m = *n;

	for (c = 0; c < p->n_combos; c++)
		for (k = 0; k < cp->n_off; k++) {
			if (!(open[c] & (1u << k)) ||
			    useless(cp, p->node_base + c + cp->off[k], lb[c]))
				continue;
			if (m >= cap)
				return hylo_fail(&pl->reason, HYLO_E_CAP_SUCCESSORS,
						 "the heuristic: more than HYLO_MAX_SUCCESSORS = %d predecessors",
						 HYLO_MAX_SUCCESSORS);
			heads[m] = p->node_base + c + cp->off[k];
			costs[m++] = lb[c];
		}
	*n = m;
	return HYLO_OK;
}

/* The switch edges into node v (position j) from j's guard twin. */
static hylo_status switch_predecessors(hylo_planner *pl, const copies *cp, uint32_t v,
				       uint32_t *heads, hylo_real *costs, uint32_t cap, uint32_t *n)
{
	const hylo_roadmap *rm = &pl->roadmap;
	uint32_t j = rm->node_pos[v], t = rm->pos[j].twin, c, k, m, combos[HYLO_MAX_COMBOS];
	hylo_status st = HYLO_OK;

	if (j >= rm->n_positions || t == HYLO_NO_POSITION)
		return HYLO_OK;
	for (c = 0; c < rm->pos[t].n_combos && st == HYLO_OK; c++) {
		m = hylo_roadmap_switch_heads(rm, t, c, combos);
		for (k = 0; k < m && st == HYLO_OK; k++)
			if (rm->pos[j].node_base + combos[k] == v)
				st = push(pl, cp, rm->pos[t].node_base + c, hylo_planner_switch_cost(pl, t),
					  heads, costs, cap, n);
	}
	return st;
}

/* The edges from the nodes of position i into node v (position j, state
 * head); a: the pair's entry in j's adjacency list, or UINT32_MAX. Their
 * bounds are not computed when every tail is closed already. */
static hylo_status position_predecessors(hylo_planner *pl, const copies *cp, uint32_t i,
					 uint32_t j, uint32_t a, uint32_t cj, const hylo_real *head,
					 uint32_t *heads, hylo_real *costs, uint32_t cap, uint32_t *n)
{
	const hylo_position *p = &pl->roadmap.pos[i];
	hylo_real lb[HYLO_MAX_COMBOS];
	uint8_t open[HYLO_MAX_COMBOS];
	hylo_pair_bound pb;

	/* The layered search's pruning leaves out half at once (the plain
	 * search's few: not worth the look there). */
	if (!open_copies(pl, cp, i, open) ||
	    (cp->beyond && all_useless(cp, p, open, hylo_planner_pair_floor(pl, i, j))))
		return HYLO_OK;
	if (a == UINT32_MAX)
		hylo_planner_pair_bound(pl, i, j, &pb);
	else
		hylo_planner_pair_bound_into(pl, i, j, a, &pb);
	hylo_planner_bounds_into(&pb, i, cj, head, lb);
	return push_open(pl, cp, p, open, lb, heads, costs, cap, n);
}

/* The edges into node v (position j, not the start's), from the copies
 * `moves` of its same-mode predecessors and `switches` of its guard twin's. */
static hylo_status predecessors(hylo_planner *pl, const copies *moves, const copies *switches,
				uint32_t v, uint32_t *heads, hylo_real *costs, uint32_t cap, uint32_t *n)
{
	const hylo_roadmap *rm = &pl->roadmap;
	uint32_t j = rm->node_pos[v], cj = v - rm->pos[j].node_base, k, n_pred, a0 = UINT32_MAX;
	const uint32_t *pred;
	hylo_real head[HYLO_XS_DIM];
	hylo_status st = HYLO_OK;

	hylo_planner_node_state(pl, j, cj, head);
	/* Same-mode neighbours are symmetric: j's list is also its predecessors. */
	if (j == pl->goal_pos) {
		pred = pl->goal_adj;
		n_pred = pl->n_goal_adj;
	} else {
		pred = hylo_planner_neighbours(pl, j, &n_pred);
		a0 = rm->pos[j].adj_begin;
	}
	for (k = 0; k < n_pred && st == HYLO_OK; k++)
		st = position_predecessors(pl, moves, pred[k], j, a0 == UINT32_MAX ? a0 : a0 + k, cj, head,
					   heads, costs, cap, n);
	if (st == HYLO_OK && ((j == pl->goal_pos && pl->start_goal_linked) ||
			      (j < rm->n_positions && pl->links_start[j])))
		st = position_predecessors(pl, moves, pl->start_pos, j, UINT32_MAX, cj, head, heads, costs,
					   cap, n);
	if (st == HYLO_OK)
		st = switch_predecessors(pl, switches, v, heads, costs, cap, n);
	return st;
}

static hylo_status expand_backward(void *ctx, hylo_search *s, uint32_t v, uint32_t *heads,
				   hylo_real *costs, uint32_t cap, uint32_t *n, hylo_reason *r)
{
	hylo_planner *pl = ctx;
	const hylo_roadmap *rm = &pl->roadmap;
	copies cp;

	(void)r;
	*n = 0;
	if (v >= rm->n_nodes + 2)
		return HYLO_OK;
	cp.s = s;
	cp.off[0] = 0;
	cp.n_off = 1;
	cp.improve = s;
	cp.beyond = NULL;
	cp.g = hylo_search_cost(s, v);
	if (rm->node_pos[v] == pl->start_pos && !isfinite(pl->h_reach))   /* every node is wanted */
		return HYLO_OK;
	if (rm->node_pos[v] == pl->start_pos)   /* its distance is known: go on to the sentinel */
		return push(pl, &cp, sentinel(pl), (pl->h_reach - 1) * hylo_search_cost(s, v), heads,
			    costs, cap, n);
	return predecessors(pl, &cp, &cp, v, heads, costs, cap, n);
}

/* The start's distance from the kept distances (its successors'), to see
 * whether they reach far enough for it. */
static hylo_real start_distance(const hylo_planner *pl)
{
	const hylo_roadmap *rm = &pl->roadmap;
	uint32_t k, c, n_adj;
	const uint32_t *adj = hylo_planner_neighbours(pl, pl->start_pos, &n_adj);
	hylo_real best = INFINITY, head[HYLO_XS_DIM];
	hylo_pair_bound pb;

	if (pl->start_goal_linked) {
		hylo_planner_pair_bound(pl, pl->start_pos, pl->goal_pos, &pb);
		best = hylo_planner_bound(&pb, 0, pl->start_xs, 0, pl->goal_xs);
	}
	for (k = 0; k < n_adj; k++) {
		const hylo_position *q = &rm->pos[adj[k]];

		hylo_planner_pair_bound(pl, pl->start_pos, adj[k], &pb);
		for (c = 0; c < q->n_combos; c++) {
			hylo_real v;

			hylo_roadmap_state(rm, adj[k], c, head);
			v = hylo_planner_bound(&pb, 0, pl->start_xs, c, head) + pl->h_node[q->node_base + c];
			if (v < best)
				best = v;
		}
	}
	return best;
}

/* 1 when the kept distances were computed for this goal on this roadmap
 * and reach well past the start's. */
static int still_valid(hylo_planner *pl)
{
	hylo_real d;

	if (!pl->h_valid || pl->h_goal_mode != pl->roadmap.pos[pl->goal_pos].mode ||
	    memcmp(pl->h_goal_xs, pl->goal_xs, sizeof pl->h_goal_xs) != 0)
		return 0;
	d = start_distance(pl);
	if (!(pl->h_reach * d <= pl->h_radius))
		return 0;
	pl->h_node[pl->roadmap.n_nodes] = d;
	return 1;
}

hylo_status hylo_planner_heuristic(hylo_planner *pl, const hylo_budget *budget)
{
	const hylo_roadmap *rm = &pl->roadmap;
	hylo_graph g;
	hylo_outcome outcome;
	hylo_real radius, h;
	uint32_t v;
	hylo_status st;

	if (still_valid(pl))
		return HYLO_OK;
	pl->h_valid = 0;
	g.n_nodes = rm->n_nodes + 3;
	g.expand = expand_backward;
	g.resolve = NULL;
	g.heuristic = NULL;
	g.weight = 1;
	g.ctx = pl;
	st = hylo_search_run(&pl->search, &g, rm->n_nodes + 1, sentinel(pl), budget, &outcome,
			     &pl->reason);
	if (st != HYLO_OK)
		return st;
	/* Found: every node with a distance below the radius is settled. */
	radius = outcome == HYLO_FOUND ? hylo_search_cost(&pl->search, sentinel(pl)) : INFINITY;
	for (v = 0; v < rm->n_nodes + 2; v++) {
		h = hylo_search_cost(&pl->search, v);
		pl->h_node[v] = h < radius ? h : radius;
	}
	pl->h_radius = radius;
	pl->h_valid = 1;
	pl->h_goal_mode = rm->pos[pl->goal_pos].mode;
	memcpy(pl->h_goal_xs, pl->goal_xs, sizeof pl->h_goal_xs);
	return HYLO_OK;
}

/*
 * The layered heuristic (alternatives), computed when the alternatives'
 * search closes a goal copy (before that, the plain heuristic: with every
 * sequence still open it is nearly the same): the backward search over the
 * search's copies of the graph (planner_graph.c, offer_for: layer l counts
 * the changes of travel mode so far; a move in another mode than layer l's
 * leads to l + 1, the last layer keeps everything), from every goal copy not
 * closed yet. A node's value is its exact bound-distance to the nearest
 * sequence still sought: in a layer whose own sequence is found only the way
 * to a further change of mode counts, and a layer that cannot reach its goal
 * copy with its number of changes is pruned.
 *
 * Both searches only need the nodes that could lie on a path within a cap
 * c. A forward A* search from the start (on the current heuristic h, run up
 * to c) gives every node a lower bound L of its bound-distance from the
 * start: the exact one where it closed the node, else c - h (the node's f
 * is above c). L is consistent (L(v) <= L(u) + c(u, v)), and the backward
 * search does not expand a node whose L plus its distance reaches c. The
 * cap follows the search: a step beyond the latest goal found, raised again
 * when every key has passed it (hylo_search_refresh_above), and the forward
 * search goes on from where it stopped. At the last cap, alternatives_within
 * times the first goal's cost, a node never reached gets +inf (a path
 * within it through the node would have reached it); below it, min(its
 * distance, c - L), at least 0: consistent as L is, and never below h (c -
 * L >= h). The search re-checks its keys (search.h). Node ids: the layered
 * ones, then a source linked to the open goal copies.
 */

static uint32_t layered_source(const hylo_planner *pl)
{
	return pl->layers * pl->layer_stride;
}

/* 1 when a move in mode m from layer l leads into layer lh (see offer_for). */
static int moves_into(const hylo_planner *pl, uint32_t l, uint8_t m, uint32_t lh)
{
	uint32_t next = l + 1 < pl->layers && m != pl->layer_mode[l % 2] ? l + 1 : l;

	return next == lh;
}

/* The forward search's heuristic: the current one (A* from the start, so
 * that the cap can grow and the search go on), +inf in the layers above
 * the live ones (n_live, live_layers; they only shrink as goal copies
 * close): no path comes down from them. */
static hylo_real forward_h(void *ctx, uint32_t u)
{
	const hylo_planner *pl = ctx;

	if (u >= layered_source(pl))
		return 0;
	return u / pl->layer_stride < pl->n_live ? hylo_planner_h(pl, u) : INFINITY;
}

/* The forward bound-distances from the start's copy in layer 0, in order of
 * those plus the current heuristic. */
static hylo_status expand_forward(void *ctx, hylo_search *s, uint32_t u, uint32_t *heads,
				  hylo_real *costs, uint32_t cap, uint32_t *n, hylo_reason *r)
{
	hylo_planner *pl = ctx;
	const hylo_roadmap *rm = &pl->roadmap;
	uint32_t stride = pl->layer_stride, i, c, k, c2, n_adj, m, l, v, combos[HYLO_MAX_COMBOS];
	const uint32_t *adj;
	hylo_real tail[HYLO_XS_DIM], lb[HYLO_MAX_COMBOS];
	uint8_t open[HYLO_MAX_COMBOS];
	hylo_pair_bound pb;
	hylo_status st = HYLO_OK;
	copies moves, switches;

	(void)r;
	*n = 0;
	if (u >= layered_source(pl))
		return HYLO_OK;
	l = u / stride;
	v = u % stride;
	i = rm->node_pos[v];
	if (i == pl->goal_pos)
		return HYLO_OK;
	c = v - rm->pos[i].node_base;
	moves.s = s;
	moves.off[0] = (moves_into(pl, l, rm->pos[i].mode, l) ? l : l + 1) * stride;
	moves.n_off = 1;
	moves.improve = s;
	moves.g = hylo_search_cost(s, u);
	/* After the last cap it is not resumed: keys above it never come. */
	moves.beyond = pl->cap == pl->bound && pl->h_layered ? pl->h_node : NULL;
	moves.cap = nextafter(pl->layered_cap, INFINITY);   /* a key above layered_cap */
	switches = moves;
	switches.off[0] = l * stride;
	hylo_planner_node_state(pl, i, c, tail);
	adj = hylo_planner_neighbours(pl, i, &n_adj);
	for (k = 0; k <= n_adj && st == HYLO_OK; k++) {
		uint32_t j = k < n_adj ? adj[k] : pl->goal_pos;

		if (k == n_adj && !((i == pl->start_pos && pl->start_goal_linked) ||
				    (i < rm->n_positions && pl->links_goal[i])))
			break;
		if (!open_copies(pl, &moves, j, open))
			continue;
		hylo_planner_pair_bound_to(pl, i, k < n_adj ? k : HYLO_GOAL_GROUP, j, &pb);
		hylo_planner_bounds_from(&pb, c, tail, j, lb);
		for (c2 = 0; c2 < rm->pos[j].n_combos; c2++)
			if (!isfinite(lb[c2]))
				open[c2] = 0;   /* no such edge */
		st = push_open(pl, &moves, &rm->pos[j], open, lb, heads, costs, cap, n);
	}
	if (st != HYLO_OK || i >= rm->n_positions || rm->pos[i].twin == HYLO_NO_POSITION)
		return st;
	m = hylo_roadmap_switch_heads(rm, i, c, combos);
	for (k = 0; k < m && st == HYLO_OK; k++)
		st = push(pl, &switches, rm->pos[rm->pos[i].twin].node_base + combos[k],
			  hylo_planner_switch_cost(pl, i), heads, costs, cap, n);
	return st;
}

static hylo_status expand_layered(void *ctx, hylo_search *s, uint32_t u, uint32_t *heads,
				  hylo_real *costs, uint32_t cap, uint32_t *n, hylo_reason *r)
{
	hylo_planner *pl = ctx;
	const hylo_roadmap *rm = &pl->roadmap;
	uint32_t src = layered_source(pl), stride = pl->layer_stride, lh, v, l;
	copies moves, switches, goal;
	uint8_t mode;
	hylo_status st = HYLO_OK;

	(void)r;
	*n = 0;
	if (u == src) {
		goal.s = pl->layered_forward;   /* its closed goal copies are found */
		goal.n_off = 1;
		goal.improve = NULL;
		for (l = 0; l < pl->layers && st == HYLO_OK; l++) {
			goal.off[0] = l * stride;
			st = push(pl, &goal, rm->n_nodes + 1, 0, heads, costs, cap, n);
		}
		return st;
	}
	if (u > src)
		return HYLO_OK;
	lh = u / stride;
	v = u % stride;
	/* No edge leads into the start; beyond cap nothing is wanted. */
	if (rm->node_pos[v] == pl->start_pos ||
	    pl->h_forward[u] + hylo_search_cost(s, u) >= pl->layered_cap)
		return HYLO_OK;
	/* A move into v is in v's mode: from layer lh when that is lh's travel
	 * mode (or lh is the last), from lh - 1 when it is not lh - 1's. */
	mode = rm->pos[rm->node_pos[v]].mode;
	moves.s = s;
	moves.n_off = 0;
	moves.improve = s;
	moves.beyond = pl->h_forward;
	moves.g = hylo_search_cost(s, u);
	moves.cap = pl->layered_cap;
	if (moves_into(pl, lh, mode, lh))
		moves.off[moves.n_off++] = lh * stride;
	if (lh > 0 && moves_into(pl, lh - 1, mode, lh))
		moves.off[moves.n_off++] = (lh - 1) * stride;
	switches = moves;
	switches.off[0] = lh * stride;
	switches.n_off = 1;
	return predecessors(pl, &moves, &switches, v, heads, costs, cap, n);
}

/* The budget left until the goal's deadline (none: no limit). 0 when it
 * has passed. */
static int budget_left(const hylo_planner *pl, hylo_budget *b)
{
	memset(b, 0, sizeof *b);
	if (!isfinite(pl->deadline))
		return 1;
	b->clock = pl->cfg.clock;
	b->clock_ctx = pl->cfg.clock_ctx;
	b->time_budget_ms = pl->deadline - hylo_planner_now(pl);
	return b->time_budget_ms > 0;
}

/* A step of the cap, as a fraction of the first goal's cost (the paper's
 * scenes' later sequences lie 6-16% above their first; docs/decisions.md). */
#define CAP_STEP 0.07

/* L (see above) into h_forward, from the forward search run up to
 * pl->layered_cap; +inf where the current heuristic says no goal copy still
 * open can be reached. */
static void forward_bounds(hylo_planner *pl)
{
	const hylo_search *f = &pl->forward_search;
	uint32_t u, src = layered_source(pl);

	for (u = 0; u < src; u++) {
		hylo_real h = hylo_planner_h(pl, u), rough = pl->layered_cap - h, d = hylo_search_cost(f, u);

		if (isinf(h))
			pl->h_forward[u] = INFINITY;
		else
			pl->h_forward[u] = hylo_search_closed(f, u) && d < rough ? d : rough;
	}
}

/* Runs the forward search up to pl->layered_cap, or goes on with it (the
 * heuristic has grown since); *done = 1 when it got there. */
static hylo_status forward(hylo_planner *pl, int *done)
{
	hylo_budget budget;
	hylo_outcome outcome = HYLO_NO_PATH;
	hylo_graph g;
	hylo_status st;
	uint32_t src = layered_source(pl);

	*done = 0;
	if (!budget_left(pl, &budget))
		return HYLO_OK;
	memset(&g, 0, sizeof g);
	g.n_nodes = src + 2;
	g.expand = expand_forward;
	g.heuristic = forward_h;
	g.weight = 1;
	g.ctx = pl;
	/* Its goal is a node no edge reaches: it stops at the cap. */
	if (pl->forward_begun)
		st = hylo_search_resume(&pl->forward_search, &g, pl->layered_cap, 1, &budget, &outcome,
					&pl->reason);
	else
		st = hylo_search_run_below(&pl->forward_search, &g, pl->roadmap.n_nodes, src + 1,
					   pl->layered_cap, &budget, &outcome, &pl->reason);
	pl->forward_begun = st == HYLO_OK;
	*done = st == HYLO_OK && outcome == HYLO_NO_PATH;
	return st;
}

/* 1 when a move can enter the goal's copy in layer lh: a move in the goal's
 * mode ends in lh (from lh or from lh - 1) only when that is lh's travel
 * mode or lh is the last layer, and the goal's position has no switch
 * edges. */
static int goal_enterable(const hylo_planner *pl, uint32_t lh)
{
	return moves_into(pl, lh, pl->roadmap.pos[pl->goal_pos].mode, lh);
}

/* The layers up to the highest whose goal copy the search fwd has not
 * closed and a move can enter: a path never goes down a layer, so from the
 * layers above no open goal copy can be reached at all, whatever the cap. */
static uint32_t live_layers(const hylo_planner *pl, const hylo_search *fwd)
{
	uint32_t l = pl->layers;

	while (l > 0 && (hylo_search_closed(fwd, (l - 1) * pl->layer_stride + pl->roadmap.n_nodes + 1) ||
			 !goal_enterable(pl, l - 1)))
		l--;
	return l;
}

/* h_node for every layered node towards the goal copies fwd has not closed,
 * for paths costing at most cap (last: the last cap, +inf beyond it); *done
 * = 0 (h_node unchanged, still a valid heuristic) when the goal's time
 * budget ran out first. */
static hylo_status layer_heuristic(hylo_planner *pl, const hylo_search *fwd, hylo_real cap,
				   int last, int *done)
{
	hylo_search *s = &pl->layer_search;
	uint32_t src = layered_source(pl), u;
	hylo_budget budget;
	hylo_outcome outcome = HYLO_NO_PATH;
	hylo_graph g;
	hylo_status st;
	int reached;

	*done = 0;
	/* Room for slightly different rounding of the same sums in the search. */
	pl->layered_cap = cap * (1 + 1e-9) + 1e-9;
	pl->n_live = live_layers(pl, fwd);
	st = forward(pl, &reached);
	if (st != HYLO_OK || !reached || !budget_left(pl, &budget))
		return st;
	forward_bounds(pl);
	memset(&g, 0, sizeof g);
	g.n_nodes = src + 2;
	g.expand = expand_layered;
	g.weight = 1;
	g.ctx = pl;
	pl->layered_forward = fwd;
	/* It runs until nothing is left: its goal is a node no edge reaches. */
	st = hylo_search_run(s, &g, src, src + 1, &budget, &outcome, &pl->reason);
	pl->layered_forward = NULL;
	if (st != HYLO_OK || outcome != HYLO_NO_PATH)
		return st;
	pl->h_valid = 0;   /* h_node is indexed by layer now */
	for (u = 0; u < src; u++) {
		hylo_real d = hylo_search_cost(s, u), rough = pl->layered_cap - pl->h_forward[u];

		if (isinf(pl->h_forward[u]) || u / pl->layer_stride >= pl->n_live)
			d = INFINITY;
		else if (!last && d > rough)
			d = rough > 0 ? rough : 0;
		pl->h_node[u] = d;
	}
	pl->h_layered = 1;
	*done = 1;
	return HYLO_OK;
}

hylo_status hylo_planner_found(void *ctx, hylo_search *s, uint32_t goal, int *grew,
			       hylo_reason *r)
{
	hylo_planner *pl = ctx;
	hylo_real first, last, level, cap;
	hylo_status st;

	*grew = 0;
	if (!pl->use_heuristic)
		return HYLO_OK;
	first = hylo_search_cost(s, hylo_search_found(s, 0));
	last = pl->layered_within * first;
	/* No edge on a path dearer than last is worth a cost any more. */
	pl->bound = last;
	/* After a goal, one step beyond it; when the keys passed the cap, a
	 * step twice the last one beyond them. */
	pl->cap_step = goal == HYLO_NO_NODE ? 2 * pl->cap_step : CAP_STEP * first;
	level = goal == HYLO_NO_NODE ? hylo_search_min_key(s) : hylo_search_cost(s, goal);
	cap = level + pl->cap_step;
	if (cap < pl->cap)
		cap = pl->cap;
	/* A weighted search (w > 1) runs ahead of its keys: the last cap at once. */
	if (!(cap < last) || pl->weight != 1)
		cap = last;
	/* The forward search may have got there even when the budget stops
	 * the rest: the cap never goes back. */
	pl->cap = cap;
	st = layer_heuristic(pl, s, cap, cap == last, grew);
	if (st == HYLO_OK && *grew && cap < last)
		hylo_search_refresh_above(s, pl->layered_cap);
	if (st != HYLO_OK && r != &pl->reason)
		*r = pl->reason;
	return st;
}
