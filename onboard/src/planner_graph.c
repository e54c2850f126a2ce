#include <math.h>
#include <string.h>

#include "hylo/envelope.h"
#include "hylo/features.h"
#include "hylo/modes.h"
#include "hylo/region.h"
#include "planner_internal.h"

/*
 * Edge costs and the search's callbacks. An edge costs the model's
 * prediction raised to the edge bound (floor and envelope,
 * hylo_planner_bound); A* evaluates edges lazily: expand hands the
 * search each neighbouring position's still-unknown edges as one deferred
 * group with the least f-value any of them could get, and resolve evaluates
 * the group when that value comes first. Known costs come from the edge
 * cache. Edges that cannot beat the greedy walk's path are never evaluated.
 */

/* Pruning against the walk's cost keeps paths within this relative rounding
 * slack of it. */
#define BOUND_SLACK 1e-9

/* pair_turn entries: not computed yet; no turn cell (the bound is the floor). */
#define TURN_UNKNOWN 0xFE
#define TURN_NONE 0xFF

double hylo_planner_now(const hylo_planner *pl)
{
	return pl->cfg.clock ? pl->cfg.clock(pl->cfg.clock_ctx) : 0.0;
}

const hylo_mode_model *hylo_planner_mode_model(const hylo_planner *pl, hylo_mode mode)
{
	int k = hylo_robot_mode_index(pl->robot, mode);

	return k < 0 ? NULL : &pl->robot->modes[k];
}

static hylo_real floor_per_m(const hylo_mode_model *mm)
{
	return mm->model ? mm->model->cost_floor_per_m : mm->cost_floor_per_m;
}

static hylo_real floor_j(const hylo_mode_model *mm)
{
	return mm->model ? mm->model->cost_floor_j : mm->cost_floor_j;
}

void hylo_planner_node_state(const hylo_planner *pl, uint32_t i, uint32_t c, hylo_real *xs)
{
	if (i == pl->start_pos)
		memcpy(xs, pl->start_xs, sizeof pl->start_xs);
	else if (i == pl->goal_pos)
		memcpy(xs, pl->goal_xs, sizeof pl->goal_xs);
	else
		hylo_roadmap_state(&pl->roadmap, i, c, xs);
}

const uint32_t *hylo_planner_neighbours(const hylo_planner *pl, uint32_t i, uint32_t *n)
{
	const hylo_position *p = &pl->roadmap.pos[i];

	if (i == pl->start_pos) {
		*n = pl->n_start_adj;
		return pl->start_adj;
	}
	if (i == pl->goal_pos) {
		*n = 0;
		return pl->start_adj;
	}
	*n = p->adj_end - p->adj_begin;
	return &pl->roadmap.adjacency[p->adj_begin];
}

/* The envelope's speed nodes of every combination of each mode, and the
 * heading changes of the heading grid, for the bounds' fast path (as
 * hylo_envelope_args would compute them from the combinations' states). */
void hylo_planner_bound_tables(hylo_planner *pl)
{
	const hylo_roadmap *rm = &pl->roadmap;
	const hylo_sampling *s = &rm->sampling;
	uint32_t k, c, h1, h2;

	for (k = 0; k < pl->robot->n_modes; k++) {
		hylo_mode mode = pl->robot->modes[k].mode;
		const hylo_svr_model *m = pl->robot->modes[k].model;
		uint32_t n = hylo_roadmap_combos(rm, mode);

		for (c = 0; c < n && c < HYLO_MAX_COMBOS; c++) {
			hylo_real xs[HYLO_XS_DIM], v;

			memset(xs, 0, sizeof xs);
			pl->combo_speed_ok[k][c] = 0;
			if (hylo_mode_describe(mode)->air) {
				xs[3] = rm->air_velocity[c][0];
				xs[4] = rm->air_velocity[c][1];
				v = sqrt(xs[3] * xs[3] + xs[4] * xs[4]);
				/* As hylo_envelope_flight_turn measures them. */
				pl->air_moving[c] = xs[3] != 0 || xs[4] != 0;
				pl->air_heading[c] = pl->air_moving[c] ? atan2(xs[4], xs[3]) : 0;
			} else if (hylo_mode_describe(mode)->planar) {
				v = s->speeds[c / s->n_headings];
			} else {
				continue;   /* the double integrator: no envelope */
			}
			pl->combo_speed_ok[k][c] = (uint8_t)hylo_svr_envelope_speed(m, v, pl->combo_speed[k][c]);
		}
	}
	for (h1 = 0; h1 < s->n_headings; h1++)
		for (h2 = 0; h2 < s->n_headings; h2++)
			pl->heading_change[h1][h2] = hylo_wrap_angle(s->headings[h2] - s->headings[h1]);
	pl->pair_turn_stride = s->n_headings * s->n_headings;
	if ((uint64_t)rm->n_adjacency * pl->pair_turn_stride > HYLO_MAX_PAIR_TURNS)
		pl->pair_turn_stride = 0;
	else
		memset(pl->pair_turn, TURN_UNKNOWN, (size_t)rm->n_adjacency * pl->pair_turn_stride);
}

/* The floor of mode model mm for an edge from a to b. */
static hylo_real floor_of(const hylo_mode_model *mm, hylo_point a, hylo_point b)
{
	return floor_j(mm) + floor_per_m(mm) * hylo_roadmap_distance(a, b);
}

hylo_real hylo_planner_pair_floor(const hylo_planner *pl, uint32_t i, uint32_t j)
{
	const hylo_roadmap *rm = &pl->roadmap;
	int k = hylo_robot_mode_index(pl->robot, (hylo_mode)rm->pos[i].mode);

	return floor_of(&pl->robot->modes[k], rm->pos[i].p, rm->pos[j].p);
}

/* The pair's bound parameters; the bearing and its wrap per heading only
 * with_bearings (the turn cells come from the cache otherwise). */
static void pair_setup(const hylo_planner *pl, uint32_t i, uint32_t j, int with_bearings,
		       hylo_pair_bound *pb)
{
	const hylo_roadmap *rm = &pl->roadmap;
	const hylo_point a = rm->pos[i].p, b = rm->pos[j].p;
	const hylo_mode_model *mm;
	hylo_real dx = b.x - a.x, dy = b.y - a.y;
	uint32_t h;
	int air;

	pb->pl = pl;
	pb->mode = (hylo_mode)rm->pos[i].mode;
	air = hylo_mode_describe(pb->mode)->air;
	pb->slot = hylo_robot_mode_index(pl->robot, pb->mode);
	mm = &pl->robot->modes[pb->slot];
	pb->floor = floor_of(mm, a, b);
	pb->model = mm->model && mm->model->envelope &&
			    mm->model->n_features == hylo_feature_count(pb->mode)
		    ? mm->model : NULL;
	/* As hylo_envelope_args measures them. */
	pb->dx = dx;
	pb->dy = dy;
	pb->d = sqrt(dx * dx + dy * dy);
	pb->dz = b.z - a.z;
	pb->by_flight_turn = pb->model && air && pb->model->turn_envelope && !(dx == 0 && dy == 0);
	pb->phi = with_bearings || pb->by_flight_turn ? atan2(dy, dx) : 0;
	pb->roadmap_ends = i < rm->n_positions && j < rm->n_positions;
	pb->by_turn = pb->model && !air && pb->model->envelope->n_z > 1 &&
		      !(dx == 0 && dy == 0);
	pb->turn_cells = NULL;
	/* The first turn cell of the distance (turn cells start at 0). */
	pb->turn_base_ok = pb->by_turn && hylo_svr_envelope_cell(pb->model, pb->d, 0, &pb->turn_base);
	/* A cell for the whole pair (flight: the climb; planar without turns:
	 * distance only, or in place: turn 0), else per heading pair. */
	pb->cell_ok = pb->model && !pb->by_turn &&
		      hylo_svr_envelope_cell(pb->model, pb->d, air ? pb->dz : 0,
					     &pb->cell);
	if (with_bearings && pb->by_turn && pb->roadmap_ends)
		for (h = 0; h < rm->sampling.n_headings; h++)
			pb->bearing[h] = hylo_wrap_angle(pb->phi - rm->sampling.headings[h]);
	/* Flight: each combination's term of the turn once per pair (the
	 * arithmetic of hylo_envelope_flight_turn_of). */
	pb->flight_turn_base_ok = pb->by_flight_turn && pb->roadmap_ends &&
				  hylo_svr_turn_envelope_cell(pb->model, pb->d, pb->dz, 0, &pb->flight_turn_base);
	if (pb->flight_turn_base_ok)
		for (h = 0; h < hylo_roadmap_combos(rm, pb->mode) && h < HYLO_MAX_COMBOS; h++)
			pb->air_off[h] = pl->air_moving[h] ? fabs(hylo_wrap_angle(pl->air_heading[h] - pb->phi)) : 0;
}

void hylo_planner_pair_bound(const hylo_planner *pl, uint32_t i, uint32_t j, hylo_pair_bound *pb)
{
	pair_setup(pl, i, j, 1, pb);
}

/* The turn cell of the edge from heading h1 to h2 (TURN_NONE: no cell). */
static uint8_t turn_cell(const hylo_pair_bound *pb, uint32_t h1, uint32_t h2)
{
	const hylo_svr_envelope *e = pb->model->envelope;
	size_t cell;

	if (!pb->turn_base_ok ||
	    !hylo_svr_envelope_cell(pb->model, pb->d,
				    hylo_envelope_turn_of(pb->bearing[h1], pb->pl->heading_change[h1][h2]),
				    &cell))
		return TURN_NONE;
	return (uint8_t)((cell - pb->turn_base) / ((size_t)e->n_v * e->n_v));
}

void hylo_planner_pair_bound_into(hylo_planner *pl, uint32_t i, uint32_t j, uint32_t a,
				  hylo_pair_bound *pb)
{
	uint32_t nh = pl->roadmap.sampling.n_headings, h1, h2;
	uint8_t *cells;

	if (!pl->pair_turn_stride || i >= pl->roadmap.n_positions || j >= pl->roadmap.n_positions) {
		pair_setup(pl, i, j, 1, pb);
		return;
	}
	cells = &pl->pair_turn[(size_t)a * pl->pair_turn_stride];
	if (cells[0] != TURN_UNKNOWN) {
		pair_setup(pl, i, j, 0, pb);
		pb->turn_cells = cells;
		return;
	}
	pair_setup(pl, i, j, 1, pb);
	cells[0] = TURN_NONE;   /* known: not by turn, or no cell */
	if (pb->by_turn && pb->turn_base_ok && pb->model->envelope->n_z < TURN_NONE)
		for (h1 = 0; h1 < nh; h1++)
			for (h2 = 0; h2 < nh; h2++)
				cells[h1 * nh + h2] = turn_cell(pb, h1, h2);
	pb->turn_cells = cells;
}

void hylo_planner_pair_bound_to(hylo_planner *pl, uint32_t i, uint32_t k, uint32_t j,
				hylo_pair_bound *pb)
{
	const hylo_roadmap *rm = &pl->roadmap;
	uint32_t a;

	if (k == HYLO_GOAL_GROUP || i >= rm->n_positions ||
	    (a = rm->adj_reverse[rm->pos[i].adj_begin + k]) == UINT32_MAX) {
		hylo_planner_pair_bound(pl, i, j, pb);
		return;
	}
	hylo_planner_pair_bound_into(pl, i, j, a, pb);
}

/* hylo_svr_envelope_value, one lookup when both speeds are on nodes. */
static double envelope_value(const hylo_svr_model *m, size_t cell, const uint32_t tail[2],
			     const uint32_t head[2])
{
	if (tail[0] == tail[1] && head[0] == head[1])
		return m->envelope->value[cell + (size_t)tail[0] * m->envelope->n_v + head[0]];
	return hylo_svr_envelope_value(m, cell, tail, head);
}

/* The envelope from the states: hylo_envelope_of_edge's arithmetic, for
 * edges from or to the start and the goal. */
static hylo_real envelope_of_states(const hylo_pair_bound *pb, const hylo_real *tail,
				    const hylo_real *head)
{
	if (hylo_mode_describe(pb->mode)->air) {
		hylo_real v1 = sqrt(tail[3] * tail[3] + tail[4] * tail[4]);
		hylo_real v2 = sqrt(head[3] * head[3] + head[4] * head[4]), e, t, turn;

		if (tail[5] != 0 || head[5] != 0)
			return 0;
		e = hylo_svr_envelope_bound(pb->model, pb->d, pb->dz, v1, v2);
		if (pb->by_flight_turn && hylo_envelope_flight_turn(tail, head, &turn) &&
		    (t = hylo_svr_turn_envelope_bound(pb->model, pb->d, pb->dz, turn, v1, v2)) > e)
			e = t;
		return e;
	}
	return hylo_svr_envelope_bound(pb->model, pb->d,
				       pb->by_turn ? hylo_envelope_turn(pb->phi, tail[3], head[3]) : 0,
				       tail[2], head[2]);
}

/* The turn table's cell of turn at the pair's distance: hylo_svr_turn_envelope_cell's
 * arithmetic from the distance's cell at turn 0. */
static int flight_turn_cell(const hylo_pair_bound *pb, hylo_real turn, size_t *cell)
{
	const hylo_svr_envelope *e = pb->model->turn_envelope;
	hylo_real x;

	if (e->n_z == 1) {
		*cell = pb->flight_turn_base;
		return 1;
	}
	x = turn / e->z_step;
	if (x == (hylo_real)e->n_z)
		x = e->n_z - 1;
	if (!(x >= 0 && x < (hylo_real)e->n_z))
		return 0;
	*cell = pb->flight_turn_base + (size_t)(uint32_t)x * e->n_v * e->n_v;
	return 1;
}

/* The same from the combinations' precomputed speed nodes and bearings. */
static hylo_real envelope_of_combos(const hylo_pair_bound *pb, uint32_t ci, uint32_t cj)
{
	const hylo_planner *pl = pb->pl;
	uint32_t nh = pl->roadmap.sampling.n_headings;
	size_t cell = pb->cell, tcell;
	hylo_real e = 0, t;

	if (!pl->combo_speed_ok[pb->slot][ci] || !pl->combo_speed_ok[pb->slot][cj])
		return 0;
	if (pb->by_flight_turn) {
		if (pb->cell_ok)
			e = hylo_svr_envelope_value(pb->model, cell, pl->combo_speed[pb->slot][ci],
						    pl->combo_speed[pb->slot][cj]);
		if (pb->flight_turn_base_ok &&
		    flight_turn_cell(pb, pb->air_off[ci] + pb->air_off[cj], &tcell) &&
		    (t = hylo_svr_turn_envelope_value(pb->model, tcell, pl->combo_speed[pb->slot][ci],
						      pl->combo_speed[pb->slot][cj])) > e)
			e = t;
		return e;
	}
	if (pb->by_turn) {
		if (!hylo_svr_envelope_cell(pb->model, pb->d,
					    hylo_envelope_turn_of(pb->bearing[ci % nh],
								  pl->heading_change[ci % nh][cj % nh]),
					    &cell))
			return 0;
	} else if (!pb->cell_ok) {
		return 0;
	}
	return hylo_svr_envelope_value(pb->model, cell, pl->combo_speed[pb->slot][ci],
				       pl->combo_speed[pb->slot][cj]);
}

hylo_real hylo_planner_bound(const hylo_pair_bound *pb, uint32_t ci, const hylo_real *tail,
			     uint32_t cj, const hylo_real *head)
{
	hylo_real e;

	if (!pb->model)
		return pb->floor;
	e = pb->roadmap_ends ? envelope_of_combos(pb, ci, cj) : envelope_of_states(pb, tail, head);
	return e > pb->floor ? e : pb->floor;
}

/* The bounds of the edges between one combination (fixed, at end `at` of
 * the pair: 0 the tail, 1 the head) and every combination of the other
 * position, into out[]: hylo_planner_bound()'s numbers, each cell and turn
 * computed once for all the speeds that share it. */
static void bounds_batch(const hylo_pair_bound *pb, int at, uint32_t fixed, const hylo_real *fixed_xs,
			 uint32_t other, hylo_real *out)
{
	const hylo_planner *pl = pb->pl;
	const hylo_roadmap *rm = &pl->roadmap;
	const hylo_position *q = &rm->pos[other];
	uint32_t nh = rm->sampling.n_headings, h, sp, c;
	hylo_real xs[HYLO_XS_DIM];
	size_t n_vv;

	if (pb->model && pb->roadmap_ends && !pb->by_turn) {
		/* Flight, or planar without turn cells: from the combinations
		 * alone (hylo_planner_bound needs no states between roadmap nodes). */
		for (c = 0; c < q->n_combos; c++) {
			hylo_real e = at == 0 ? envelope_of_combos(pb, fixed, c) : envelope_of_combos(pb, c, fixed);

			out[c] = e > pb->floor ? e : pb->floor;
		}
		return;
	}
	if (!pb->model || !pb->roadmap_ends || !pb->by_turn) {
		for (c = 0; c < q->n_combos; c++) {
			hylo_planner_node_state(pl, other, c, xs);
			out[c] = at == 0 ? hylo_planner_bound(pb, fixed, fixed_xs, c, xs)
					 : hylo_planner_bound(pb, c, xs, fixed, fixed_xs);
		}
		return;
	}
	n_vv = (size_t)pb->model->envelope->n_v * pb->model->envelope->n_v;
	for (h = 0; h < nh; h++) {
		uint32_t h1 = at == 0 ? fixed % nh : h, h2 = at == 0 ? h : fixed % nh;
		uint8_t tc = pb->turn_cells ? pb->turn_cells[h1 * nh + h2] : turn_cell(pb, h1, h2);
		int ok = pb->turn_base_ok && tc != TURN_NONE;
		size_t cell = pb->turn_base + (size_t)tc * n_vv;

		for (sp = 0; sp * nh + h < q->n_combos; sp++) {
			uint32_t ci, cj;
			hylo_real e = 0;

			c = sp * nh + h;
			ci = at == 0 ? fixed : c;
			cj = at == 0 ? c : fixed;
			if (ok && pl->combo_speed_ok[pb->slot][ci] && pl->combo_speed_ok[pb->slot][cj])
				e = envelope_value(pb->model, cell, pl->combo_speed[pb->slot][ci],
						   pl->combo_speed[pb->slot][cj]);
			out[c] = e > pb->floor ? e : pb->floor;
		}
	}
}

void hylo_planner_bounds_from(const hylo_pair_bound *pb, uint32_t ci, const hylo_real *tail,
			      uint32_t j, hylo_real *out)
{
	bounds_batch(pb, 0, ci, tail, j, out);
}

void hylo_planner_bounds_into(const hylo_pair_bound *pb, uint32_t i, uint32_t cj,
			      const hylo_real *head, hylo_real *out)
{
	bounds_batch(pb, 1, cj, head, i, out);
}

hylo_real hylo_planner_switch_cost(const hylo_planner *pl, uint32_t i)
{
	return pl->robot->switch_cost[pl->roadmap.pos[i].mode == pl->robot->modes[0].mode ? 0 : 1];
}

hylo_real hylo_planner_h(const hylo_planner *pl, uint32_t u)
{
	return pl->h_node[pl->h_layered ? u : hylo_planner_graph_node(pl, u)];
}

/* The states of the combinations combos[0 .. n) of position j into pl->head_xs. */
static void head_states(hylo_planner *pl, uint32_t j, const uint32_t *combos, uint32_t n)
{
	uint32_t m;

	for (m = 0; m < n; m++)
		hylo_planner_node_state(pl, j, combos[m], pl->head_xs[m]);
}

/*
 * Costs of the edges from the tail (position i, state tail) to combinations
 * combos[0 .. n) of position j into costs: the model's prediction (or the
 * cost callback's) raised to the edge bound, +inf where the mode's
 * feasibility classifier rejects the edge.
 */
static hylo_status evaluate(hylo_planner *pl, uint32_t i, uint32_t c, const hylo_real *tail,
			    uint32_t j, const uint32_t *combos, uint32_t n, hylo_real *costs)
{
	hylo_mode mode = (hylo_mode)pl->roadmap.pos[i].mode;
	const hylo_mode_model *mm = hylo_planner_mode_model(pl, mode);
	int k = hylo_robot_mode_index(pl->robot, mode);
	unsigned nf = hylo_feature_count(mode);
	hylo_pair_bound pb;
	uint32_t m;
	hylo_status st;

	if (n == 0)
		return HYLO_OK;
	head_states(pl, j, combos, n);
	hylo_planner_pair_bound(pl, i, j, &pb);
	if (mm->model || mm->feasibility)
		for (m = 0; m < n; m++)
			hylo_features(mode, tail, pl->head_xs[m], &pl->features[m * nf]);
	if (mm->model) {
		/* Counted, not expected: start, goal and grids are checked against
		 * the trained region, and the connection radius against its reach. */
		for (m = 0; m < n; m++)
			if (!hylo_region_edge(mm->model, mode, tail, pl->head_xs[m], NULL))
				pl->n_untrained++;
		st = hylo_svr_predict_batch(mm->model, &pl->svr_cache[k], pl->features, n, costs);
		if (st != HYLO_OK)
			return hylo_fail(&pl->reason, st, "SVR evaluation failed: %s",
					 hylo_status_str(st));
	} else {
		st = mm->cost_fn(mm->cost_ctx, mode, tail,
				 (const hylo_real(*)[HYLO_XS_DIM])pl->head_xs, n, costs, &pl->reason);
		if (st != HYLO_OK)
			return st;
	}
	for (m = 0; m < n; m++) {
		hylo_real lo = hylo_planner_bound(&pb, c, tail, combos[m], pl->head_xs[m]);

		if (!isfinite(costs[m]))
			return hylo_fail(&pl->reason, HYLO_E_BAD_COST,
					 "the %s cost model returned %g", hylo_mode_str(mode), costs[m]);
		if (costs[m] < 0)
			pl->n_negative++;
		if (costs[m] < lo) {
			costs[m] = lo;
			pl->n_clamped++;
		}
	}
	pl->n_evaluated += n;
	if (!mm->feasibility)
		return HYLO_OK;
	st = hylo_svr_predict_batch(mm->feasibility, &pl->feas_cache[k], pl->features, n, pl->feas_d);
	if (st != HYLO_OK)
		return hylo_fail(&pl->reason, st, "feasibility evaluation failed: %s",
				 hylo_status_str(st));
	for (m = 0; m < n; m++)
		if (!(pl->feas_d[m] >= 0)) {
			costs[m] = INFINITY;
			pl->n_infeasible++;
		}
	return HYLO_OK;
}

/* What a group's heads are offered for: the search (s) with A*'s pruning, or
 * the greedy walk (heads whose heuristic is below h_below). With layers
 * (alternatives), the search's node of graph node v in layer l is
 * l * layer_stride + v; a head's layer is given by the edge's kind (move:
 * along a mode; swap: a switch edge). */
typedef struct {
	hylo_search *s;       /* NULL for the walk: nothing is closed */
	uint32_t tail;        /* the tail's node in the search */
	uint32_t move, swap;  /* layer offsets of the heads of moves and of switches */
	hylo_real g;          /* cost of the tail */
	hylo_real h_below;    /* +inf: every head */
} offer;

uint32_t hylo_planner_graph_node(const hylo_planner *pl, uint32_t u)
{
	return pl->layers > 1 ? u % pl->layer_stride : u;
}

/*
 * Layer l counts the changes of mode between the stretches a path has
 * travelled so far: its travel mode is the start's for even l, the other
 * one for odd l. A move in another mode than that starts a new stretch
 * (l + 1, at most the last layer); a switch edge alone does not, so
 * switching to and fro at one guard is no new sequence.
 */
static void offer_for(const hylo_planner *pl, hylo_search *s, uint32_t u, offer *o)
{
	const hylo_roadmap *rm = &pl->roadmap;
	uint32_t layer = pl->layers > 1 ? u / pl->layer_stride : 0, next = layer;
	uint8_t mode = rm->pos[rm->node_pos[hylo_planner_graph_node(pl, u)]].mode;

	if (layer + 1 < pl->layers && mode != pl->layer_mode[layer % 2])
		next = layer + 1;
	o->s = s;
	o->tail = u;
	o->move = next * pl->layer_stride;
	o->swap = layer * pl->layer_stride;
	o->g = hylo_search_cost(s, u);
	o->h_below = INFINITY;
}

/* 1 when head v is worth a cost: open, able to reach the goal, and (A*)
 * possibly on a path cheaper than the walk's with an edge of cost at
 * least lb. */
static int wanted(const hylo_planner *pl, const offer *o, uint32_t v, uint32_t layer, hylo_real lb,
		  hylo_real *hv)
{
	*hv = pl->use_heuristic ? hylo_planner_h(pl, layer + v) : 0;
	if (o->s && hylo_search_closed(o->s, layer + v))
		return 0;
	if (pl->use_heuristic && !isfinite(*hv))
		return 0;
	if (!(*hv < o->h_below))
		return 0;
	return !(pl->use_heuristic && o->g + lb + *hv > pl->bound * (1 + BOUND_SLACK));
}

/* Where group costs come from and go to: the cache for roadmap nodes' groups. */
static hylo_real *group_costs(hylo_planner *pl, uint32_t u, uint32_t group, int create)
{
	if (group == HYLO_GOAL_GROUP || u >= pl->roadmap.n_nodes)
		return NULL;
	return hylo_edge_cache_group(&pl->cache, &pl->roadmap, u, group, create);
}

static hylo_status emit(hylo_planner *pl, uint32_t v, hylo_real cost, uint32_t *heads,
			hylo_real *costs, uint32_t cap, uint32_t *n)
{
	if (*n >= cap)
		return hylo_fail(&pl->reason, HYLO_E_CAP_SUCCESSORS,
				 "more than HYLO_MAX_SUCCESSORS = %d successors", HYLO_MAX_SUCCESSORS);
	heads[*n] = v;
	costs[*n] = cost;
	(*n)++;
	return HYLO_OK;
}

/* The least f-value the wanted heads of group (u, j) could get (those whose
 * costs are not known yet, when skip_known: the others go out at once);
 * *need = 0 (and +inf) when there are none. */
static hylo_real pending_key(hylo_planner *pl, const offer *o, uint32_t u, uint32_t group,
			     uint32_t j, const hylo_real *lb, int skip_known, int *need)
{
	const hylo_position *q = &pl->roadmap.pos[j];
	const hylo_real *cached = skip_known ? group_costs(pl, u, group, 0) : NULL;
	hylo_real key = INFINITY, hv, f;
	uint32_t c2;

	*need = 0;
	for (c2 = 0; c2 < q->n_combos; c2++) {
		if (!wanted(pl, o, q->node_base + c2, o->move, lb[c2], &hv) ||
		    (cached && !isnan(cached[c2])))
			continue;
		*need = 1;
		f = o->g + lb[c2] + pl->weight * hv;
		if (f < key)
			key = f;
	}
	return key;
}

/*
 * Evaluates the wanted heads of group (u, j) whose costs are not known yet,
 * keeps them in the cache, and appends every wanted head with a finite cost.
 * Lazy (A*, on a roadmap node's group): only the heads whose f-bound is not
 * above every key still waiting, which would come next anyway; the others
 * wait as the same group, keyed by the least of theirs, and most are never
 * needed: their heads are closed through cheaper edges first.
 */
static hylo_status resolve_group(hylo_planner *pl, const offer *o, uint32_t u, uint32_t group,
				 uint32_t j, int lazy, uint32_t *heads, hylo_real *costs, uint32_t cap,
				 uint32_t *n)
{
	const hylo_roadmap *rm = &pl->roadmap;
	const hylo_position *q = &rm->pos[j];
	uint32_t i = rm->node_pos[u], c = u - rm->pos[i].node_base;
	hylo_real *cached = group_costs(pl, u, group, 1);
	hylo_real got[HYLO_MAX_COMBOS], tail[HYLO_XS_DIM], lb[HYLO_MAX_COMBOS], hv, fresh[HYLO_MAX_COMBOS];
	hylo_real next = INFINITY, key;
	hylo_pair_bound pb;
	uint32_t c2, m = 0;
	hylo_status st;
	int later = 0, need;

	if (lazy && cached && o->s && pl->use_heuristic)
		next = hylo_search_min_key(o->s);
	hylo_planner_node_state(pl, i, c, tail);
	hylo_planner_pair_bound_to(pl, i, group, j, &pb);
	hylo_planner_bounds_from(&pb, c, tail, j, lb);
	for (c2 = 0; c2 < q->n_combos; c2++) {
		got[c2] = NAN;
		if (!wanted(pl, o, q->node_base + c2, o->move, lb[c2], &hv))
			continue;
		if (cached && !isnan(cached[c2]))
			got[c2] = cached[c2];
		else if (o->g + lb[c2] + pl->weight * hv > next)
			later = 1;
		else
			pl->eval_idx[m++] = c2;
	}
	st = evaluate(pl, i, c, tail, j, pl->eval_idx, m, fresh);
	if (st != HYLO_OK)
		return st;
	for (c2 = 0; c2 < m; c2++) {
		got[pl->eval_idx[c2]] = fresh[c2];
		if (cached)
			cached[pl->eval_idx[c2]] = fresh[c2];
	}
	for (c2 = 0; c2 < q->n_combos && st == HYLO_OK; c2++)
		if (isfinite(got[c2]) &&
		    !(pl->use_heuristic && o->s &&
		      o->g + got[c2] + hylo_planner_h(pl, o->move + q->node_base + c2) >
			      pl->bound * (1 + BOUND_SLACK)))
			st = emit(pl, o->move + q->node_base + c2, got[c2], heads, costs, cap, n);
	if (st != HYLO_OK || !later)
		return st;
	/* Room: the search has just taken this group out. */
	key = pending_key(pl, o, u, group, j, lb, 1, &need);
	if (need && !hylo_search_defer(o->s, o->tail, group, key))
		return hylo_fail(&pl->reason, HYLO_E_BAD_VALUE,
				 "resolve: group %u of node %u could not wait again (key %g)",
				 (unsigned)group, (unsigned)u, key);
	return HYLO_OK;
}

/* Lower bounds lb[] of the edges from u to the combinations of position j. */
static void group_bounds(hylo_planner *pl, uint32_t u, uint32_t group, uint32_t j, hylo_real *lb)
{
	const hylo_roadmap *rm = &pl->roadmap;
	uint32_t i = rm->node_pos[u], c = u - rm->pos[i].node_base;
	hylo_real tail[HYLO_XS_DIM];
	hylo_pair_bound pb;

	hylo_planner_node_state(pl, i, c, tail);
	hylo_planner_pair_bound_to(pl, i, group, j, &pb);
	hylo_planner_bounds_from(&pb, c, tail, j, lb);
}

/*
 * Offers the search the edges from u to position j: known costs at once,
 * the others as one deferred group keyed by the least f-value they could
 * get (A*), or evaluated at once (Dijkstra, or no room to defer).
 */
static hylo_status offer_group(hylo_planner *pl, const offer *o, uint32_t u, uint32_t group,
			       uint32_t j, uint32_t *heads, hylo_real *costs, uint32_t cap, uint32_t *n)
{
	const hylo_position *q = &pl->roadmap.pos[j];
	const hylo_real *cached = group_costs(pl, u, group, 0);
	hylo_real key, hv, lb[HYLO_MAX_COMBOS];
	hylo_status st = HYLO_OK;
	uint32_t c2;
	int need;

	group_bounds(pl, u, group, j, lb);
	for (c2 = 0; c2 < q->n_combos && st == HYLO_OK; c2++) {
		if (!cached || isnan(cached[c2]) || !wanted(pl, o, q->node_base + c2, o->move, lb[c2], &hv))
			continue;
		pl->n_cached++;
		if (isfinite(cached[c2]) &&
		    !(pl->use_heuristic && o->g + cached[c2] + hv > pl->bound * (1 + BOUND_SLACK)))
			st = emit(pl, o->move + q->node_base + c2, cached[c2], heads, costs, cap, n);
	}
	if (st != HYLO_OK)
		return st;
	key = pending_key(pl, o, u, group, j, lb, 1, &need);
	if (!need)
		return HYLO_OK;
	if (pl->use_heuristic && o->s && hylo_search_defer(o->s, o->tail, group, key))
		return HYLO_OK;
	return resolve_group(pl, o, u, group, j, 0, heads, costs, cap, n);
}

/* Appends the switch edges of node u (position i, combination c). */
static hylo_status switch_edges(hylo_planner *pl, const offer *o, uint32_t u, uint32_t *heads,
				hylo_real *costs, uint32_t cap, uint32_t *n)
{
	const hylo_roadmap *rm = &pl->roadmap;
	uint32_t i = rm->node_pos[u], c = u - rm->pos[i].node_base, combos[HYLO_MAX_COMBOS], k, m;
	hylo_real sw, hv;
	hylo_status st = HYLO_OK;

	if (i >= rm->n_positions || rm->pos[i].twin == HYLO_NO_POSITION)
		return HYLO_OK;
	sw = hylo_planner_switch_cost(pl, i);
	m = hylo_roadmap_switch_heads(rm, i, c, combos);
	for (k = 0; k < m && st == HYLO_OK; k++) {
		uint32_t v = rm->pos[rm->pos[i].twin].node_base + combos[k];

		if (wanted(pl, o, v, o->swap, sw, &hv))
			st = emit(pl, o->swap + v, sw, heads, costs, cap, n);
	}
	return st;
}

/* Every successor of u that o wants, known or evaluated (deferred ones aside). */
static hylo_status successors(hylo_planner *pl, const offer *o, uint32_t u, uint32_t *heads,
			      hylo_real *costs, uint32_t cap, uint32_t *n)
{
	const hylo_roadmap *rm = &pl->roadmap;
	uint32_t i = rm->node_pos[u], k, n_adj;
	const uint32_t *adj;
	hylo_status st = HYLO_OK;

	*n = 0;
	if (i == pl->goal_pos)
		return HYLO_OK;
	adj = hylo_planner_neighbours(pl, i, &n_adj);
	for (k = 0; k < n_adj && st == HYLO_OK; k++)
		st = offer_group(pl, o, u, k, adj[k], heads, costs, cap, n);
	if (st == HYLO_OK && ((i == pl->start_pos && pl->start_goal_linked) ||
			      (i < rm->n_positions && pl->links_goal[i])))
		st = offer_group(pl, o, u, HYLO_GOAL_GROUP, pl->goal_pos, heads, costs, cap, n);
	if (st == HYLO_OK)
		st = switch_edges(pl, o, u, heads, costs, cap, n);
	return st;
}

hylo_status hylo_planner_expand(void *ctx, hylo_search *s, uint32_t u, uint32_t *heads,
				hylo_real *costs, uint32_t cap, uint32_t *n, hylo_reason *r)
{
	hylo_planner *pl = ctx;
	offer o;

	(void)r;
	offer_for(pl, s, u, &o);
	return successors(pl, &o, hylo_planner_graph_node(pl, u), heads, costs, cap, n);
}

/* The position of group `group` of graph node v, HYLO_NO_POSITION when it has none. */
static uint32_t group_position(const hylo_planner *pl, uint32_t v, uint32_t group)
{
	uint32_t n_adj;
	const uint32_t *adj = hylo_planner_neighbours(pl, pl->roadmap.node_pos[v], &n_adj);

	if (group == HYLO_GOAL_GROUP)
		return pl->goal_pos;
	return group < n_adj ? adj[group] : HYLO_NO_POSITION;
}

/* 0 when no head of group (v, j) is wanted even at the pair's floor, the
 * least bound of its edges: most groups waiting when the heuristic grows
 * have died so, and their bounds need not be computed. */
static int may_want(const hylo_planner *pl, const offer *o, uint32_t v, uint32_t j)
{
	const hylo_roadmap *rm = &pl->roadmap;
	uint32_t c2;
	hylo_real floor = hylo_planner_pair_floor(pl, rm->node_pos[v], j), hv;

	for (c2 = 0; c2 < rm->pos[j].n_combos; c2++)
		if (wanted(pl, o, rm->pos[j].node_base + c2, o->move, floor, &hv))
			return 1;
	return 0;
}

hylo_real hylo_planner_group_key(void *ctx, hylo_search *s, uint32_t u, uint32_t group)
{
	hylo_planner *pl = ctx;
	uint32_t v = hylo_planner_graph_node(pl, u), j = group_position(pl, v, group);
	hylo_real lb[HYLO_MAX_COMBOS];
	offer o;
	int need;

	if (j == HYLO_NO_POSITION)
		return -INFINITY;   /* not ours: resolve says so */
	offer_for(pl, s, u, &o);
	if (!may_want(pl, &o, v, j))
		return INFINITY;
	group_bounds(pl, v, group, j, lb);
	/* Every wanted head: another layer's copy of v may have filled the
	 * cache since, and this group's heads have not gone out. */
	return pending_key(pl, &o, v, group, j, lb, 0, &need);
}

hylo_status hylo_planner_resolve(void *ctx, hylo_search *s, uint32_t u, uint32_t group,
				 uint32_t *heads, hylo_real *costs, uint32_t cap, uint32_t *n,
				 hylo_reason *r)
{
	hylo_planner *pl = ctx;
	uint32_t v = hylo_planner_graph_node(pl, u), j = group_position(pl, v, group);
	offer o;

	(void)r;
	*n = 0;
	if (j == HYLO_NO_POSITION)
		return hylo_fail(&pl->reason, HYLO_E_BAD_VALUE, "resolve: node %u has no group %u",
				 (unsigned)v, (unsigned)group);
	offer_for(pl, s, u, &o);
	return resolve_group(pl, &o, v, group, j, 1, heads, costs, cap, n);
}

/*
 * The greedy walk: from the start, at every node the edge with the least
 * cost plus heuristic among those that get strictly nearer the goal by the
 * heuristic (a mode switch may keep the heuristic, but not twice in a row).
 * The optimum is at most its cost, so A* skips, without evaluating them,
 * edges u -> v with g(u) + bound(u, v) + h(v) above it. Its evaluations
 * stay in the cache for the search.
 */
hylo_real hylo_planner_greedy_walk(hylo_planner *pl, double deadline)
{
	const hylo_roadmap *rm = &pl->roadmap;
	uint32_t u = rm->n_nodes, goal = rm->n_nodes + 1, step, k, n;
	hylo_real total = 0;
	int switched = 0;
	offer o;

	pl->walk_len = 0;
	o.s = NULL;
	o.tail = u;
	o.move = 0;
	o.swap = 0;
	o.g = 0;
	for (step = 0; step < HYLO_MAX_WAYPOINTS; step++) {
		uint32_t best_v = goal + 1, ui = rm->node_pos[u];
		hylo_real best = INFINITY, best_c = 0, hu = hylo_planner_h(pl, u);
		int best_switch = 0;

		pl->walk_path[step] = u;
		pl->walk_cost[step] = total;
		if (u == goal) {
			pl->walk_len = step + 1;
			return total;
		}
		if (hylo_planner_now(pl) > deadline)
			return INFINITY;
		/* Candidates: heads below u's heuristic, and switch heads at it. */
		o.h_below = switched ? hu : nextafter(hu, INFINITY);
		if (successors(pl, &o, u, pl->walk_heads, pl->walk_costs, HYLO_MAX_SUCCESSORS, &n) != HYLO_OK)
			return INFINITY;
		for (k = 0; k < n; k++) {
			uint32_t v = pl->walk_heads[k], vi = rm->node_pos[v];
			hylo_real hv = hylo_planner_h(pl, v);
			int sw = ui < rm->n_positions && rm->pos[ui].twin == vi;

			if (!(hv < hu || (sw && !switched && hv <= hu)))
				continue;
			if (pl->walk_costs[k] + hv < best) {
				best = pl->walk_costs[k] + hv;
				best_c = pl->walk_costs[k];
				best_v = v;
				best_switch = sw;
			}
		}
		if (best_v > goal)
			return INFINITY;
		total += best_c;
		switched = best_switch;
		u = best_v;
	}
	return INFINITY;
}

/* ---- for references and tests ------------------------------------------ */

hylo_status hylo_planner_successors(hylo_planner *pl, uint32_t tail, uint32_t *heads, uint32_t *n)
{
	const hylo_roadmap *rm;
	uint32_t i, k, c, n_adj, combos[HYLO_MAX_COMBOS];
	const uint32_t *adj;

	if (!pl || !heads || !n)
		return HYLO_E_NULL;
	rm = &pl->roadmap;
	*n = 0;
	if (!pl->has_map || !rm->built || tail >= rm->n_nodes + 2)
		return hylo_fail(&pl->reason, HYLO_E_BAD_VALUE, "no node %u in the last goal's graph",
				 (unsigned)tail);
	i = rm->node_pos[tail];
	if (i == pl->goal_pos)
		return HYLO_OK;
	adj = hylo_planner_neighbours(pl, i, &n_adj);
	for (k = 0; k <= n_adj; k++) {
		uint32_t j = k < n_adj ? adj[k] : pl->goal_pos;

		if (k == n_adj && !((i == pl->start_pos && pl->start_goal_linked) ||
				    (i < rm->n_positions && pl->links_goal[i])))
			continue;
		for (c = 0; c < rm->pos[j].n_combos; c++) {
			if (*n >= HYLO_MAX_SUCCESSORS)
				return hylo_fail(&pl->reason, HYLO_E_CAP_SUCCESSORS,
						 "more than HYLO_MAX_SUCCESSORS = %d successors",
						 HYLO_MAX_SUCCESSORS);
			heads[(*n)++] = rm->pos[j].node_base + c;
		}
	}
	if (i < rm->n_positions && rm->pos[i].twin != HYLO_NO_POSITION) {
		uint32_t m = hylo_roadmap_switch_heads(rm, i, tail - rm->pos[i].node_base, combos);

		for (k = 0; k < m && *n < HYLO_MAX_SUCCESSORS; k++)
			heads[(*n)++] = rm->pos[rm->pos[i].twin].node_base + combos[k];
	}
	return HYLO_OK;
}

hylo_status hylo_planner_edge_costs(hylo_planner *pl, uint32_t tail, const uint32_t *heads,
				    uint32_t n, hylo_real *costs)
{
	const hylo_roadmap *rm;
	uint32_t i, c, k, m;
	hylo_real xs[HYLO_XS_DIM];
	hylo_status st = HYLO_OK;

	if (!pl || (n > 0 && (!heads || !costs)))
		return HYLO_E_NULL;
	rm = &pl->roadmap;
	if (!pl->has_map || !rm->built || tail >= rm->n_nodes + 2)
		return hylo_fail(&pl->reason, HYLO_E_BAD_VALUE, "no node %u in the last goal's graph",
				 (unsigned)tail);
	for (k = 0; k < n; k++)
		if (heads[k] >= rm->n_nodes + 2)
			return hylo_fail(&pl->reason, HYLO_E_BAD_VALUE, "no node %u", (unsigned)heads[k]);
	i = rm->node_pos[tail];
	c = tail - rm->pos[i].node_base;
	hylo_planner_node_state(pl, i, c, xs);
	/* Runs of heads at one position are evaluated as one batch. */
	for (k = 0; k < n && st == HYLO_OK; k += m) {
		uint32_t j = rm->node_pos[heads[k]];

		for (m = 0; k + m < n && rm->node_pos[heads[k + m]] == j && m < HYLO_MAX_COMBOS; m++)
			pl->eval_idx[m] = heads[k + m] - rm->pos[j].node_base;
		if (i < rm->n_positions && rm->pos[i].twin == j) {
			uint32_t t;

			for (t = 0; t < m; t++)
				costs[k + t] = hylo_planner_switch_cost(pl, i);
			continue;
		}
		if (rm->pos[j].mode != rm->pos[i].mode)
			return hylo_fail(&pl->reason, HYLO_E_BAD_VALUE, "node %u is not a successor of %u",
					 (unsigned)heads[k], (unsigned)tail);
		st = evaluate(pl, i, c, xs, j, pl->eval_idx, m, &costs[k]);
	}
	return st;
}
