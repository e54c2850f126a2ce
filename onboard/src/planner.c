#include "hylo/planner.h"

#include <math.h>
#include <string.h>

#include "hylo/features.h"

/*
 * The search graph is implicit: a node is (position, combination); its
 * successors are every combination of every neighbouring position of the
 * same mode, the guard twin's switch edges, and the goal when it is in reach.
 * Edge costs are evaluated when the tail is expanded, in one batch per
 * expansion, and only for heads that are not closed yet.
 */

static double now_ms(const hylo_planner *pl)
{
	return pl->cfg.clock ? pl->cfg.clock(pl->cfg.clock_ctx) : 0.0;
}

static const hylo_mode_model *mode_model(const hylo_planner *pl, hylo_mode mode)
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

static hylo_real max_distance(const hylo_mode_model *mm)
{
	return mm->model ? mm->model->max_distance_m : mm->max_distance_m;
}

hylo_status hylo_planner_init(hylo_planner *pl, const hylo_planner_config *cfg)
{
	uint32_t k;
	hylo_status st;

	if (!pl || !cfg || (cfg->n_robots > 0 && !cfg->robots))
		return pl ? hylo_fail(&pl->reason, HYLO_E_NULL, "hylo_planner_init: NULL argument")
			  : HYLO_E_NULL;
	pl->initialized = 0;
	pl->has_map = 0;
	pl->map_status = HYLO_E_NO_MAP;
	pl->robot = NULL;
	pl->roadmap.built = 0;
	pl->n_goal_adj = 0;
	memset(pl->links_goal, 0, sizeof pl->links_goal);
	if (cfg->n_robots > HYLO_MAX_ROBOTS)
		return hylo_fail(&pl->reason, HYLO_E_CAP_ROBOTS,
				 "%u robots, more than HYLO_MAX_ROBOTS = %d",
				 (unsigned)cfg->n_robots, HYLO_MAX_ROBOTS);
	for (k = 0; k < cfg->n_robots; k++) {
		st = hylo_robot_check(&cfg->robots[k], &pl->reason);
		if (st != HYLO_OK)
			return st;
		pl->robots[k] = cfg->robots[k];
	}
	pl->cfg = *cfg;
	pl->cfg.robots = pl->robots;
	pl->map_generation = 0;
	hylo_svr_cache_reset(&pl->svr_cache[0]);
	hylo_svr_cache_reset(&pl->svr_cache[1]);
	hylo_svr_cache_reset(&pl->feas_cache[0]);
	hylo_svr_cache_reset(&pl->feas_cache[1]);
	hylo_reason_clear(&pl->reason);
	pl->initialized = 1;
	return HYLO_OK;
}

const char *hylo_planner_reason(const hylo_planner *pl)
{
	return pl ? pl->reason.text : "planner is NULL";
}

const hylo_roadmap *hylo_planner_roadmap(const hylo_planner *pl)
{
	return pl && pl->has_map && pl->roadmap.built ? &pl->roadmap : NULL;
}

static const hylo_robot *find_robot(const hylo_planner *pl, const char *name)
{
	uint32_t k;

	for (k = 0; k < pl->cfg.n_robots; k++)
		if (strcmp(pl->robots[k].name, name) == 0)
			return &pl->robots[k];
	return NULL;
}

/* Some cell must belong to a domain of the robot. */
static int map_has_domain(const hylo_map *m, const hylo_robot *robot)
{
	uint32_t k, cells = (uint32_t)m->nx * (uint32_t)m->ny;

	for (k = 0; k < robot->n_modes; k++) {
		switch (robot->modes[k].mode) {
		case HYLO_MODE_GROUND:
			if (m->n_ground > 0)
				return 1;
			break;
		case HYLO_MODE_MARINE:
			if (m->n_water > 0)
				return 1;
			break;
		case HYLO_MODE_FLIGHT:
			return 1;
		default:
			if (m->n_obstacle < cells)
				return 1;
			break;
		}
	}
	return 0;
}

static hylo_status ingest_map(hylo_planner *pl, const hylo_map_view *map)
{
	hylo_status st;

	pl->has_map = 0;
	pl->roadmap.built = 0;
	pl->map_generation++;
	st = hylo_map_ingest(&pl->map, map, &pl->reason);
	if (st != HYLO_OK)
		return st;
	pl->robot = find_robot(pl, pl->map.robot);
	if (!pl->robot)
		return hylo_fail(&pl->reason, HYLO_E_UNKNOWN_ROBOT,
				 "map %lld is for robot \"%s\", which this planner does not know",
				 (long long)pl->map.map_id, pl->map.robot);
	if (!map_has_domain(&pl->map, pl->robot))
		return hylo_fail(&pl->reason, HYLO_E_EMPTY_DOMAIN,
				 "map %lld has no cell where robot %s can move (e.g. no drivable cell)",
				 (long long)pl->map.map_id, pl->robot->name);
	hylo_svr_cache_reset(&pl->svr_cache[0]);
	hylo_svr_cache_reset(&pl->svr_cache[1]);
	hylo_svr_cache_reset(&pl->feas_cache[0]);
	hylo_svr_cache_reset(&pl->feas_cache[1]);
	pl->has_map = 1;
	hylo_reason_clear(&pl->reason);
	return HYLO_OK;
}

hylo_status hylo_planner_set_map(hylo_planner *pl, const hylo_map_view *map)
{
	hylo_status st;

	if (!pl || !map)
		return pl ? hylo_fail(&pl->reason, HYLO_E_NULL, "hylo_planner_set_map: NULL argument")
			  : HYLO_E_NULL;
	if (!pl->initialized)
		return hylo_fail(&pl->reason, HYLO_E_NULL, "planner not initialized");
	st = ingest_map(pl, map);
	/* Goals until the next map are answered with why this one was refused. */
	pl->map_status = st;
	if (st != HYLO_OK)
		hylo_fail(&pl->map_reason, st, "map %lld was refused: %s", (long long)map->map_id,
			  pl->reason.text);
	return st;
}

/* ---- request validation ------------------------------------------------ */

static hylo_status copy_grid(hylo_real *dst, const hylo_real *src, uint32_t n,
			     const char *name, hylo_reason *r)
{
	if (n > HYLO_MAX_GRID)
		return hylo_fail(r, HYLO_E_CAP_GRID, "%s has %u entries, more than HYLO_MAX_GRID = %d",
				 name, (unsigned)n, HYLO_MAX_GRID);
	if (n > 0 && !src)
		return hylo_fail(r, HYLO_E_NULL, "%s is NULL", name);
	if (n > 0)
		memcpy(dst, src, n * sizeof *dst);
	return HYLO_OK;
}

static hylo_status make_sampling(const hylo_goal *g, hylo_sampling *s, hylo_reason *r)
{
	hylo_status st;

	memset(s, 0, sizeof *s);
	s->seed = g->seed;
	s->spacing = g->spacing;
	s->air_spacing = g->air_spacing;
	s->guard_spacing = g->guard_spacing;
	s->connect_radius = g->connect_radius;
	s->air_connect_radius = g->air_connect_radius;
	s->n_speeds = g->n_speeds;
	s->n_headings = g->n_headings;
	s->n_air_speeds = g->n_air_speeds;
	st = copy_grid(s->speeds, g->speeds, g->n_speeds, "speeds_mps", r);
	if (st == HYLO_OK)
		st = copy_grid(s->headings, g->headings, g->n_headings, "headings_rad", r);
	if (st == HYLO_OK)
		st = copy_grid(s->air_speeds, g->air_speeds, g->n_air_speeds, "air_speeds_mps", r);
	return st;
}

/* Where a state of mode sits in the work space. */
static hylo_point state_point(const hylo_map *m, hylo_mode mode, const hylo_real *xs)
{
	hylo_point p;

	p.x = xs[0];
	p.y = xs[1];
	p.z = 0;
	if (mode == HYLO_MODE_GROUND || mode == HYLO_MODE_MARINE)
		p.z = hylo_map_height(m, xs[0], xs[1]);
	else if (mode == HYLO_MODE_FLIGHT)
		p.z = xs[2];
	return p;
}

static const char *domain_of(const hylo_planner *pl, hylo_point p)
{
	int k;

	for (k = HYLO_MODE_GROUND; k < HYLO_MODE_COUNT; k++)
		if (hylo_robot_mode_index(pl->robot, (hylo_mode)k) >= 0 &&
		    hylo_domain_contains(&pl->map, (hylo_mode)k, p))
			return hylo_mode_str((hylo_mode)k);
	return NULL;
}

static hylo_status check_state(hylo_planner *pl, const char *what, int mode,
			       const hylo_real *xs, hylo_point *p)
{
	unsigned k, dim;
	const char *other;
	const hylo_svr_model *model;
	hylo_real speed;
	int idx = hylo_robot_mode_index(pl->robot, (hylo_mode)mode);

	if (!hylo_mode_valid(mode) || idx < 0)
		return hylo_fail(&pl->reason, HYLO_E_WRONG_MODE,
				 "%s mode %d (%s) is not a mode of robot %s", what, mode,
				 hylo_mode_str((hylo_mode)mode), pl->robot->name);
	dim = hylo_mode_dim((hylo_mode)mode);
	for (k = 0; k < dim; k++)
		if (!isfinite(xs[k]))
			return hylo_fail(&pl->reason, HYLO_E_BAD_VALUE,
					 "%s coordinate %u is %g", what, k, xs[k]);
	/* The model's costs from a speed it never saw are extrapolations. */
	model = pl->robot->modes[idx].model;
	speed = hylo_state_speed((hylo_mode)mode, xs);
	if (model && !hylo_svr_speed_trained(model, speed))
		return hylo_fail(&pl->reason, HYLO_E_BAD_VALUE,
				 "%s speed %g m/s is outside the %s model's training range [%g, %g] m/s",
				 what, speed, hylo_mode_str((hylo_mode)mode), model->speed_min_mps,
				 model->speed_max_mps);
	*p = state_point(&pl->map, (hylo_mode)mode, xs);
	if (hylo_domain_contains(&pl->map, (hylo_mode)mode, *p))
		return HYLO_OK;
	other = domain_of(pl, *p);
	if (other)
		return hylo_fail(&pl->reason, HYLO_E_WRONG_MODE,
				 "%s (%g, %g, %g) lies in the %s domain, not in %s", what, p->x,
				 p->y, p->z, other, hylo_mode_str((hylo_mode)mode));
	return hylo_fail(&pl->reason, HYLO_E_OUTSIDE_DOMAIN,
			 "%s (%g, %g, %g) lies outside the %s domain (obstacle, off the map, or out of the air space)",
			 what, p->x, p->y, p->z, hylo_mode_str((hylo_mode)mode));
}

static hylo_status check_goal(hylo_planner *pl, const hylo_goal *g, hylo_point *ps,
			      hylo_point *pg)
{
	hylo_status st;
	uint32_t k;

	if (!pl->has_map)
		return pl->map_status == HYLO_E_NO_MAP
			       ? hylo_fail(&pl->reason, HYLO_E_NO_MAP, "no map has been set yet")
			       : hylo_fail(&pl->reason, pl->map_status, "%s", pl->map_reason.text);
	for (k = 0; k < pl->robot->n_modes; k++)
		if (!pl->robot->modes[k].model && !pl->robot->modes[k].cost_fn)
			return hylo_fail(&pl->reason, HYLO_E_NO_MODEL,
					 "robot %s has no cost model for mode %s", pl->robot->name,
					 hylo_mode_str(pl->robot->modes[k].mode));
	if (g->map_id != 0 && g->map_id != pl->map.map_id)
		return hylo_fail(&pl->reason, HYLO_E_MAP_MISMATCH,
				 "goal is for map %lld, the current map is %lld",
				 (long long)g->map_id, (long long)pl->map.map_id);
	if (g->algorithm != HYLO_ASTAR && g->algorithm != HYLO_DIJKSTRA)
		return hylo_fail(&pl->reason, HYLO_E_BAD_VALUE, "unknown algorithm %d", g->algorithm);
	if (!isfinite(g->time_budget_ms) || g->time_budget_ms < 0)
		return hylo_fail(&pl->reason, HYLO_E_BAD_VALUE, "time_budget_ms = %g", g->time_budget_ms);
	if (g->time_budget_ms > 0 && !pl->cfg.clock)
		return hylo_fail(&pl->reason, HYLO_E_BAD_VALUE,
				 "a time budget needs a clock, and this planner has none");
	st = check_state(pl, "start", g->start_mode, g->start, ps);
	if (st == HYLO_OK)
		st = check_state(pl, "goal", g->goal_mode, g->goal, pg);
	if (st != HYLO_OK)
		return st;
	for (k = 0; k < pl->robot->n_modes; k++) {
		const hylo_mode_model *mm = &pl->robot->modes[k];
		hylo_real reach = max_distance(mm);
		hylo_real radius = mm->mode == HYLO_MODE_FLIGHT ? g->air_connect_radius
								: g->connect_radius;

		if (reach > 0 && radius > reach)
			return hylo_fail(&pl->reason, HYLO_E_BAD_VALUE,
					 "connection radius %g m exceeds the %s model's training range %g m",
					 radius, hylo_mode_str(mm->mode), reach);
	}
	return HYLO_OK;
}

/* ---- start and goal ---------------------------------------------------- */

static void set_terminal(hylo_planner *pl, uint32_t i, hylo_point p, int mode,
			 hylo_position_kind kind, uint32_t node)
{
	hylo_position *q = &pl->roadmap.pos[i];

	memset(q, 0, sizeof *q);
	q->p = p;
	q->mode = (uint8_t)mode;
	q->kind = (uint8_t)kind;
	q->n_combos = 1;
	q->twin = HYLO_NO_POSITION;
	q->node_base = node;
	pl->roadmap.node_pos[node] = i;
}

static hylo_status connect_terminals(hylo_planner *pl, const hylo_goal *g, hylo_point ps,
				     hylo_point pg)
{
	hylo_roadmap *rm = &pl->roadmap;
	uint32_t k;
	hylo_status st;

	for (k = 0; k < pl->n_goal_adj; k++)
		pl->links_goal[pl->goal_adj[k]] = 0;
	pl->n_goal_adj = 0;
	pl->n_start_adj = 0;
	pl->start_pos = rm->n_positions;
	pl->goal_pos = rm->n_positions + 1;
	memcpy(pl->start_xs, g->start, sizeof pl->start_xs);
	memcpy(pl->goal_xs, g->goal, sizeof pl->goal_xs);
	set_terminal(pl, pl->start_pos, ps, g->start_mode, HYLO_POS_START, rm->n_nodes);
	set_terminal(pl, pl->goal_pos, pg, g->goal_mode, HYLO_POS_GOAL, rm->n_nodes + 1);
	st = hylo_roadmap_neighbours(rm, &pl->build_ws, &pl->map, ps, (hylo_mode)g->start_mode,
				     HYLO_NO_POSITION, pl->start_adj, &pl->n_start_adj, &pl->reason);
	if (st == HYLO_OK)
		st = hylo_roadmap_neighbours(rm, &pl->build_ws, &pl->map, pg,
					     (hylo_mode)g->goal_mode, HYLO_NO_POSITION,
					     pl->goal_adj, &pl->n_goal_adj, &pl->reason);
	if (st != HYLO_OK)
		return st;
	for (k = 0; k < pl->n_goal_adj; k++)
		pl->links_goal[pl->goal_adj[k]] = 1;
	pl->start_goal_linked =
		g->start_mode == g->goal_mode &&
		hylo_roadmap_distance(ps, pg) <= hylo_roadmap_radius(rm, (hylo_mode)g->goal_mode) &&
		hylo_domain_segment(&pl->map, (hylo_mode)g->goal_mode, ps, pg);
	return HYLO_OK;
}

/* ---- graph callbacks --------------------------------------------------- */

static void node_state(const hylo_planner *pl, uint32_t i, uint32_t c, hylo_real *xs)
{
	if (i == pl->start_pos)
		memcpy(xs, pl->start_xs, sizeof pl->start_xs);
	else if (i == pl->goal_pos)
		memcpy(xs, pl->goal_xs, sizeof pl->goal_xs);
	else
		hylo_roadmap_state(&pl->roadmap, i, c, xs);
}

/* Appends the open nodes of position j as heads of an edge from a tail at
 * tail_p whose cost so far is g_tail (s is NULL during the bound's walk:
 * nothing is closed then). */
static hylo_status add_heads(hylo_planner *pl, const hylo_search *s, uint32_t j, hylo_point tail_p,
			     hylo_real g_tail, hylo_real floor_j_tail, hylo_real floor_m_tail,
			     uint32_t *heads, uint32_t cap, uint32_t *n)
{
	const hylo_position *q = &pl->roadmap.pos[j];
	hylo_real dist;
	uint32_t c;

	/* A position that cannot reach the goal is a dead end (A* only: plain
	 * Dijkstra stays textbook). */
	if (pl->use_heuristic && !isfinite(pl->h_pos[j]))
		return HYLO_OK;
	dist = hylo_roadmap_distance(tail_p, q->p);
	/* No path through this edge can beat the bound's path (A* only). */
	if (pl->use_heuristic &&
	    g_tail + floor_j_tail + floor_m_tail * dist + pl->h_pos[j] > pl->bound * (1 + 1e-9))
		return HYLO_OK;
	for (c = 0; c < q->n_combos; c++) {
		uint32_t v = q->node_base + c;

		if (s && hylo_search_closed(s, v))
			continue;
		if (*n >= cap)
			return hylo_fail(&pl->reason, HYLO_E_CAP_SUCCESSORS,
					 "more than HYLO_MAX_SUCCESSORS = %d successors",
					 HYLO_MAX_SUCCESSORS);
		heads[*n] = v;
		node_state(pl, j, c, pl->head_xs[*n]);
		pl->head_dist[*n] = dist;
		(*n)++;
	}
	return HYLO_OK;
}

/* Costs of edges tail -> heads[0 .. n), raised to the model's floor; an edge
 * the mode's feasibility classifier rejects gets +inf (dropped by the caller). */
static hylo_status evaluate(hylo_planner *pl, hylo_mode mode, const hylo_real *tail,
			    uint32_t n, hylo_real *costs)
{
	const hylo_mode_model *mm = mode_model(pl, mode);
	int k = hylo_robot_mode_index(pl->robot, mode);
	unsigned nf = hylo_feature_count(mode);
	hylo_real fl, fj;
	uint32_t i;
	hylo_status st;

	if (n == 0)
		return HYLO_OK;
	if (mm->model || mm->feasibility)
		for (i = 0; i < n; i++)
			hylo_features(mode, tail, pl->head_xs[i], &pl->features[i * nf]);
	if (mm->model) {
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
	fl = floor_per_m(mm);
	fj = floor_j(mm);
	for (i = 0; i < n; i++) {
		hylo_real lo = fj + fl * pl->head_dist[i];

		if (!isfinite(costs[i]))
			return hylo_fail(&pl->reason, HYLO_E_BAD_COST,
					 "the %s cost model returned %g", hylo_mode_str(mode), costs[i]);
		if (costs[i] < 0)
			pl->n_negative++;
		if (costs[i] < lo) {
			costs[i] = lo;
			pl->n_clamped++;
		}
	}
	if (mm->feasibility) {
		st = hylo_svr_predict_batch(mm->feasibility, &pl->feas_cache[k], pl->features, n,
					    pl->feas_d);
		if (st != HYLO_OK)
			return hylo_fail(&pl->reason, st, "feasibility evaluation failed: %s",
					 hylo_status_str(st));
		for (i = 0; i < n; i++)
			if (!(pl->feas_d[i] >= 0)) {
				costs[i] = INFINITY;
				pl->n_infeasible++;
			}
	}
	return HYLO_OK;
}

/* Removes the edges evaluate() marked infeasible, keeping the order. */
static uint32_t drop_infeasible(uint32_t *heads, hylo_real *costs, uint32_t n)
{
	uint32_t i, kept = 0;

	for (i = 0; i < n; i++)
		if (isfinite(costs[i])) {
			heads[kept] = heads[i];
			costs[kept++] = costs[i];
		}
	return kept;
}

static hylo_status expand_node(void *ctx, const hylo_search *s, uint32_t u, uint32_t *heads,
			       hylo_real *costs, uint32_t cap, uint32_t *n_out, hylo_reason *r)
{
	hylo_planner *pl = ctx;
	const hylo_roadmap *rm = &pl->roadmap;
	uint32_t i = rm->node_pos[u], c = u - rm->pos[i].node_base;
	const hylo_position *p = &rm->pos[i];
	const uint32_t *adj;
	uint32_t k, n_adj, n = 0, combos[HYLO_MAX_COMBOS];
	hylo_real tail[HYLO_XS_DIM], g = s ? hylo_search_cost(s, u) : 0, fj, fm;
	const hylo_mode_model *mm;
	hylo_status st = HYLO_OK;

	(void)r;
	*n_out = 0;
	if (i == pl->goal_pos)
		return HYLO_OK;
	mm = mode_model(pl, (hylo_mode)p->mode);
	fj = floor_j(mm);
	fm = floor_per_m(mm);
	node_state(pl, i, c, tail);
	if (i == pl->start_pos) {
		adj = pl->start_adj;
		n_adj = pl->n_start_adj;
	} else {
		adj = &rm->adjacency[p->adj_begin];
		n_adj = p->adj_end - p->adj_begin;
	}
	for (k = 0; k < n_adj && st == HYLO_OK; k++)
		st = add_heads(pl, s, adj[k], p->p, g, fj, fm, heads, cap, &n);
	if (st == HYLO_OK && ((i == pl->start_pos && pl->start_goal_linked) ||
			      (i < rm->n_positions && pl->links_goal[i])))
		st = add_heads(pl, s, pl->goal_pos, p->p, g, fj, fm, heads, cap, &n);
	if (st == HYLO_OK)
		st = evaluate(pl, (hylo_mode)p->mode, tail, n, costs);
	if (st != HYLO_OK)
		return st;
	n = drop_infeasible(heads, costs, n);
	if (i < rm->n_positions && p->twin != HYLO_NO_POSITION) {
		const hylo_position *t = &rm->pos[p->twin];
		hylo_real sw = pl->robot->switch_cost[p->mode == pl->robot->modes[0].mode ? 0 : 1];
		uint32_t m = hylo_roadmap_switch_heads(rm, i, c, combos);

		for (k = 0; k < m; k++) {
			uint32_t v = t->node_base + combos[k];

			if ((s && hylo_search_closed(s, v)) ||
			    (pl->use_heuristic && !isfinite(pl->h_pos[p->twin])))
				continue;
			if (n >= cap)
				return hylo_fail(&pl->reason, HYLO_E_CAP_SUCCESSORS,
						 "more than HYLO_MAX_SUCCESSORS = %d successors",
						 HYLO_MAX_SUCCESSORS);
			heads[n] = v;
			costs[n] = sw;
			n++;
		}
	}
	*n_out = n;
	return HYLO_OK;
}

static hylo_real node_heuristic(void *ctx, uint32_t u)
{
	const hylo_planner *pl = ctx;

	return pl->h_pos[pl->roadmap.node_pos[u]];
}

/*
 * The A* heuristic: exact shortest distances to the goal on the position
 * graph, with each edge weighted by a lower bound of every node edge it
 * stands for (the mode's cost floors: per edge plus per metre; the switch cost).
 * Every node edge costs at least that (costs are raised to the floor), so
 * the heuristic is admissible and consistent, and it sees obstacles, water
 * and mode changes that a straight-line bound would not. Computed by a
 * backward Dijkstra over positions, with one extra node that is never
 * reached so that the search runs to exhaustion.
 */
static hylo_real lower_bound(const hylo_planner *pl, uint32_t a, uint32_t b)
{
	const hylo_position *pa = &pl->roadmap.pos[a];
	const hylo_mode_model *mm = mode_model(pl, (hylo_mode)pa->mode);

	return floor_j(mm) + floor_per_m(mm) * hylo_roadmap_distance(pa->p, pl->roadmap.pos[b].p);
}

static hylo_status expand_backward(void *ctx, const hylo_search *s, uint32_t u,
				   uint32_t *heads, hylo_real *costs, uint32_t cap,
				   uint32_t *n_out, hylo_reason *r)
{
	hylo_planner *pl = ctx;
	const hylo_roadmap *rm = &pl->roadmap;
	uint32_t k, n = 0, n_pred;
	const uint32_t *pred;

	(void)r;
	*n_out = 0;
	if (u >= rm->n_positions && u != pl->goal_pos)
		return HYLO_OK;
	if (u == pl->goal_pos) {
		pred = pl->goal_adj;
		n_pred = pl->n_goal_adj;
	} else {
		pred = &rm->adjacency[rm->pos[u].adj_begin];
		n_pred = rm->pos[u].adj_end - rm->pos[u].adj_begin;
	}
	if (n_pred + 1 > cap)
		return hylo_fail(&pl->reason, HYLO_E_CAP_SUCCESSORS,
				 "more than HYLO_MAX_SUCCESSORS = %d predecessors", HYLO_MAX_SUCCESSORS);
	for (k = 0; k < n_pred; k++) {
		if (hylo_search_closed(s, pred[k]))
			continue;
		heads[n] = pred[k];
		costs[n] = lower_bound(pl, pred[k], u);
		n++;
	}
	if (u < rm->n_positions && rm->pos[u].twin != HYLO_NO_POSITION) {
		uint32_t t = rm->pos[u].twin;

		heads[n] = t;
		costs[n] = pl->robot->switch_cost[rm->pos[t].mode == pl->robot->modes[0].mode ? 0 : 1];
		n++;
	}
	*n_out = n;
	return HYLO_OK;
}

static hylo_status compute_heuristic(hylo_planner *pl, const hylo_budget *budget)
{
	const hylo_roadmap *rm = &pl->roadmap;
	hylo_graph g;
	hylo_outcome outcome;
	hylo_real best;
	uint32_t i, k;
	hylo_status st;

	g.n_nodes = rm->n_positions + 3;
	g.expand = expand_backward;
	g.heuristic = NULL;
	g.ctx = pl;
	st = hylo_search_run(&pl->search, &g, pl->goal_pos, rm->n_positions + 2, budget,
			     &outcome, &pl->reason);
	if (st != HYLO_OK)
		return st;
	for (i = 0; i < rm->n_positions + 2; i++)
		pl->h_pos[i] = hylo_search_cost(&pl->search, i);
	/* The start has no incoming edges; its bound comes from its edges out. */
	best = pl->start_goal_linked ? lower_bound(pl, pl->start_pos, pl->goal_pos) : INFINITY;
	for (k = 0; k < pl->n_start_adj; k++) {
		uint32_t j = pl->start_adj[k];
		hylo_real v = lower_bound(pl, pl->start_pos, j) + pl->h_pos[j];

		if (v < best)
			best = v;
	}
	pl->h_pos[pl->start_pos] = best;
	return HYLO_OK;
}

/*
 * An upper bound for A*: the cost of a real path, found by a greedy walk from
 * the start that takes, at every node, the evaluated edge with the least cost
 * plus heuristic among those that get strictly nearer the goal by the
 * heuristic (a mode switch may keep the heuristic, but not twice in a row).
 * The optimum is at most this bound, so A* skips, without evaluating them,
 * the edges u -> v with g(u) + lower_bound(u, v) + h(v) above it: no path
 * through them can do better (g(u) is final when u is expanded, the
 * heuristic being consistent). Infinity, and no pruning, when the walk gets
 * stuck, runs past HYLO_MAX_WAYPOINTS steps or past the deadline [ms, on the
 * planner's clock]. Its evaluations are counted with the search's.
 */
static hylo_real greedy_bound(hylo_planner *pl, double deadline)
{
	const hylo_roadmap *rm = &pl->roadmap;
	uint32_t u = rm->n_nodes, goal = rm->n_nodes + 1, step, k, n;
	hylo_real total = 0;
	int switched = 0;
	hylo_reason r;

	pl->bound = INFINITY;
	for (step = 0; step < HYLO_MAX_WAYPOINTS; step++) {
		uint32_t best_v = goal + 1, ui = rm->node_pos[u];
		hylo_real best = INFINITY, best_c = 0, hu = pl->h_pos[ui];
		int best_switch = 0;

		if (u == goal)
			return total;
		if (now_ms(pl) > deadline)
			return INFINITY;
		if (expand_node(pl, NULL, u, pl->walk_heads, pl->walk_costs, HYLO_MAX_SUCCESSORS, &n, &r) !=
		    HYLO_OK)
			return INFINITY;
		pl->n_walk_evaluated += n;
		for (k = 0; k < n; k++) {
			uint32_t v = pl->walk_heads[k], vi = rm->node_pos[v];
			hylo_real hv = pl->h_pos[vi];
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

/* ---- plan extraction --------------------------------------------------- */

static int is_switch(const hylo_roadmap *rm, uint32_t a, uint32_t b)
{
	return a < rm->n_positions && rm->pos[a].twin == b;
}

static hylo_status extract(hylo_planner *pl, uint32_t goal_node, hylo_plan *plan)
{
	const hylo_roadmap *rm = &pl->roadmap;
	uint32_t k, n;
	hylo_status st;

	st = hylo_search_path(&pl->search, goal_node, pl->path, HYLO_MAX_WAYPOINTS, &n,
			      &pl->reason);
	if (st != HYLO_OK)
		return st;
	plan->n_waypoints = n;
	plan->n_modes = 0;
	for (k = 0; k < n; k++) {
		uint32_t u = pl->path[k], i = rm->node_pos[u];
		uint8_t mode = rm->pos[i].mode;

		plan->mode[k] = mode;
		node_state(pl, i, u - rm->pos[i].node_base, plan->state[k]);
		plan->cost[k] = hylo_search_cost(&pl->search, u);
		plan->guard[k] =
			(k + 1 < n && is_switch(rm, i, rm->node_pos[pl->path[k + 1]])) ||
			(k > 0 && is_switch(rm, i, rm->node_pos[pl->path[k - 1]]));
		if (plan->n_modes == 0 || plan->mode_sequence[plan->n_modes - 1] != mode)
			plan->mode_sequence[plan->n_modes++] = mode;
	}
	plan->total_cost = plan->cost[n - 1];
	return HYLO_OK;
}

/* ---- planning ---------------------------------------------------------- */

static void plan_begin(const hylo_planner *pl, const hylo_goal *g, hylo_plan *plan)
{
	plan->status = HYLO_OK;
	plan->outcome = HYLO_NO_PATH;
	plan->request_id = g ? g->request_id : 0;
	plan->map_id = pl->has_map ? pl->map.map_id : 0;
	memset(plan->robot, 0, sizeof plan->robot);
	if (pl->has_map)
		memcpy(plan->robot, pl->map.robot, sizeof plan->robot);
	plan->total_cost = 0;
	plan->n_waypoints = 0;
	plan->n_modes = 0;
	plan->n_nodes = 0;
	plan->n_edges = 0;
	plan->n_edges_evaluated = 0;
	plan->n_expansions = 0;
	plan->n_clamped = 0;
	plan->n_negative = 0;
	plan->n_infeasible = 0;
	plan->roadmap_reused = 0;
	plan->plan_ms = 0;
}

static uint64_t terminal_edges(const hylo_planner *pl)
{
	const hylo_roadmap *rm = &pl->roadmap;
	uint64_t n = pl->start_goal_linked ? 1 : 0;
	uint32_t k;

	for (k = 0; k < pl->n_start_adj; k++)
		n += rm->pos[pl->start_adj[k]].n_combos;
	for (k = 0; k < pl->n_goal_adj; k++)
		n += rm->pos[pl->goal_adj[k]].n_combos;
	return n;
}

static hylo_status run(hylo_planner *pl, const hylo_goal *g, hylo_plan *plan, double t0)
{
	hylo_roadmap *rm = &pl->roadmap;
	hylo_sampling s;
	hylo_point ps, pg;
	hylo_budget budget;
	hylo_graph graph;
	hylo_status st;

	st = check_goal(pl, g, &ps, &pg);
	if (st == HYLO_OK)
		st = make_sampling(g, &s, &pl->reason);
	if (st != HYLO_OK)
		return st;
	if (rm->built && hylo_sampling_equal(&rm->sampling, &s)) {
		plan->roadmap_reused = 1;
	} else {
		st = hylo_roadmap_build(rm, &pl->build_ws, &pl->map, pl->robot, &s, &pl->reason);
		if (st != HYLO_OK)
			return st;
		/* The old goal's links refer to positions that no longer exist. */
		memset(pl->links_goal, 0, sizeof pl->links_goal);
		pl->n_goal_adj = 0;
	}
	st = connect_terminals(pl, g, ps, pg);
	if (st != HYLO_OK)
		return st;
	plan->n_nodes = rm->n_nodes + 2;
	plan->n_edges = rm->n_edges + terminal_edges(pl);

	memset(&budget, 0, sizeof budget);
	budget.clock = pl->cfg.clock;
	budget.clock_ctx = pl->cfg.clock_ctx;
	pl->use_heuristic = 0;
	if (g->algorithm == HYLO_ASTAR) {
		st = compute_heuristic(pl, &budget);
		if (st != HYLO_OK)
			return st;
		pl->use_heuristic = 1;
	}
	pl->n_clamped = 0;
	pl->n_negative = 0;
	pl->n_infeasible = 0;
	pl->n_walk_evaluated = 0;
	pl->bound = INFINITY;
	if (pl->use_heuristic)
		pl->bound = greedy_bound(pl, g->time_budget_ms > 0 ? t0 + g->time_budget_ms : INFINITY);
	budget.max_expansions = g->max_expansions;
	budget.time_budget_ms = g->time_budget_ms > 0 ? g->time_budget_ms - (now_ms(pl) - t0) : 0;
	if (g->time_budget_ms > 0 && budget.time_budget_ms <= 0) {
		plan->outcome = HYLO_BUDGET_EXHAUSTED;
		return HYLO_OK;
	}
	graph.n_nodes = rm->n_nodes + 2;
	graph.expand = expand_node;
	graph.heuristic = pl->use_heuristic ? node_heuristic : NULL;
	graph.ctx = pl;
	st = hylo_search_run(&pl->search, &graph, rm->n_nodes, rm->n_nodes + 1, &budget,
			     &plan->outcome, &pl->reason);
	plan->n_edges_evaluated = pl->search.stats.edges_evaluated + pl->n_walk_evaluated;
	plan->n_expansions = pl->search.stats.expansions;
	plan->n_clamped = pl->n_clamped;
	plan->n_negative = pl->n_negative;
	plan->n_infeasible = pl->n_infeasible;
	if (st != HYLO_OK || plan->outcome != HYLO_FOUND)
		return st;
	return extract(pl, rm->n_nodes + 1, plan);
}

hylo_status hylo_planner_plan(hylo_planner *pl, const hylo_goal *goal, hylo_plan *plan)
{
	double t0;
	hylo_status st;

	if (!pl || !plan)
		return pl ? hylo_fail(&pl->reason, HYLO_E_NULL, "hylo_planner_plan: NULL argument")
			  : HYLO_E_NULL;
	plan_begin(pl, goal, plan);
	if (!pl->initialized) {
		st = hylo_fail(&pl->reason, HYLO_E_NULL, "planner not initialized");
	} else if (!goal) {
		st = hylo_fail(&pl->reason, HYLO_E_NULL, "hylo_planner_plan: goal is NULL");
	} else {
		t0 = now_ms(pl);
		hylo_reason_clear(&pl->reason);
		st = run(pl, goal, plan, t0);
		plan->plan_ms = now_ms(pl) - t0;
		if (st == HYLO_OK && plan->outcome != HYLO_FOUND)
			hylo_fail(&pl->reason, HYLO_OK, "%s", hylo_outcome_str(plan->outcome));
	}
	plan->status = st;
	plan->reason = pl->reason;
	return st;
}
