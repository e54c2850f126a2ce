#include "hylo/planner.h"

#include <math.h>
#include <string.h>

#include "hylo/region.h"
#include "hylo/modes.h"
#include "planner_internal.h"

/*
 * Requests: validation, the roadmap (reused while the map and the sampling
 * options stay), the heuristic, the greedy walk's upper bound, the search
 * (planner_graph.c) and the plan. See planner_internal.h for the graph.
 */

static double now_ms(const hylo_planner *pl)
{
	return hylo_planner_now(pl);
}

static hylo_real max_distance(const hylo_mode_model *mm)
{
	return mm->model ? mm->model->max_distance_m : mm->max_distance_m;
}

/* The SVR caches' memory, after the struct: the largest robot's models. */
static size_t robot_cache_bytes(const hylo_robot *robot)
{
	size_t n = 0;
	uint32_t k;

	for (k = 0; k < robot->n_modes; k++)
		n += hylo_svr_cache_size(robot->modes[k].model) +
		     hylo_svr_cache_size(robot->modes[k].feasibility);
	return n;
}

static size_t cache_bytes(const hylo_planner_config *cfg)
{
	size_t n = 0, m;
	uint32_t k;

	for (k = 0; cfg && cfg->robots && k < cfg->n_robots && k < HYLO_MAX_ROBOTS; k++) {
		m = robot_cache_bytes(&cfg->robots[k]);
		if (m > n)
			n = m;
	}
	return n;
}

size_t hylo_planner_size(const hylo_planner_config *cfg)
{
	return sizeof(hylo_planner) + cache_bytes(cfg);
}

static double *arena(hylo_planner *pl)
{
	return (double *)(void *)(pl + 1);
}

/* Gives the SVR caches of the map's robot their memory. */
static void attach_caches(hylo_planner *pl)
{
	double *mem = arena(pl);
	size_t a;
	uint32_t k;

	for (k = 0; k < 2; k++) {
		const hylo_mode_model *mm = k < pl->robot->n_modes ? &pl->robot->modes[k] : NULL;

		a = mm ? hylo_svr_cache_size(mm->model) : 0;
		hylo_svr_cache_attach(&pl->svr_cache[k], a ? mem : NULL, a);
		mem += a / sizeof(double);
		a = mm ? hylo_svr_cache_size(mm->feasibility) : 0;
		hylo_svr_cache_attach(&pl->feas_cache[k], a ? mem : NULL, a);
		mem += a / sizeof(double);
	}
}

/* The model needing the most cache memory of the robots in cfg, for the
 * reason a too small workspace gives. */
static void largest_model(const hylo_planner_config *cfg, const char **name, size_t *bytes)
{
	uint32_t k, m;

	*name = "(none)";
	*bytes = 0;
	for (k = 0; k < cfg->n_robots; k++)
		for (m = 0; m < cfg->robots[k].n_modes; m++) {
			const hylo_svr_model *x = cfg->robots[k].modes[m].model;

			if (x && hylo_svr_cache_size(x) > *bytes) {
				*bytes = hylo_svr_cache_size(x);
				*name = x->name ? x->name : "(unnamed)";
			}
		}
}

hylo_real hylo_planner_margin(const hylo_planner_config *cfg)
{
	if (!cfg)
		return -1;
	if (cfg->margin_m == 0)
		return HYLO_DEFAULT_MARGIN_M;
	if (cfg->margin_m == HYLO_NO_MARGIN)
		return 0;
	return isfinite(cfg->margin_m) && cfg->margin_m > 0 ? cfg->margin_m : -1;
}

hylo_real hylo_planner_clearance(const hylo_planner *pl)
{
	return pl && pl->has_map ? pl->map.inflation : 0;
}

/* The start's and the goal's links and the heuristic belong to one roadmap
 * (and goal): a new roadmap forgets them. */
static void forget_terminals(hylo_planner *pl)
{
	memset(pl->links_goal, 0, sizeof pl->links_goal);
	memset(pl->links_start, 0, sizeof pl->links_start);
	pl->n_goal_adj = 0;
	pl->n_start_adj = 0;
	pl->h_valid = 0;
}

/* No roadmap, nor anything planned on one (a new map, or none yet). */
static void forget_roadmap(hylo_planner *pl)
{
	pl->roadmap.built = 0;
	pl->n_found = 0;
	forget_terminals(pl);
}

hylo_status hylo_planner_init(hylo_planner *pl, size_t size, const hylo_planner_config *cfg)
{
	uint32_t k;
	hylo_status st;

	if (!pl || !cfg || (cfg->n_robots > 0 && !cfg->robots))
		return pl && size >= sizeof *pl
			       ? hylo_fail(&pl->reason, HYLO_E_NULL, "hylo_planner_init: NULL argument")
			       : HYLO_E_NULL;
	if (size < sizeof *pl)
		return HYLO_E_CAP_SV;
	pl->initialized = 0;
	pl->has_map = 0;
	pl->map_status = HYLO_E_NO_MAP;
	pl->robot = NULL;
	forget_roadmap(pl);
	pl->cache.enabled = 0;
	pl->layers = 1;
	pl->layer_stride = 0;
	pl->layered_forward = NULL;
	pl->h_layered = 0;
	if (hylo_planner_margin(cfg) < 0)
		return hylo_fail(&pl->reason, HYLO_E_BAD_VALUE,
				 "margin_m = %g: finite and > 0, 0 (the default, %g m) or HYLO_NO_MARGIN",
				 cfg->margin_m, HYLO_DEFAULT_MARGIN_M);
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
	if (size < hylo_planner_size(cfg)) {
		const char *name;
		size_t need;

		largest_model(cfg, &name, &need);
		return hylo_fail(&pl->reason, HYLO_E_CAP_SV,
				 "the workspace has %lu bytes, its models need %lu (hylo_planner_size; the largest, %s, %lu bytes of SVR cache)",
				 (unsigned long)size, (unsigned long)hylo_planner_size(cfg), name,
				 (unsigned long)need);
	}
	pl->cfg = *cfg;
	pl->cfg.robots = pl->robots;
	pl->map_generation = 0;
	for (k = 0; k < 2; k++) {
		hylo_svr_cache_attach(&pl->svr_cache[k], NULL, 0);
		hylo_svr_cache_attach(&pl->feas_cache[k], NULL, 0);
	}
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

/* Some cell belongs to a domain of the robot (as far as m's inflation
 * leaves them: hylo_map_ingest leaves none). */
static int map_has_domain(const hylo_map *m, const hylo_robot *robot)
{
	int32_t c, cells = m->nx * m->ny;
	uint32_t k;

	for (k = 0; k < robot->n_modes; k++)
		for (c = 0; c < cells; c++)
			if (hylo_mode_describe(robot->modes[k].mode)->air
				    ? hylo_map_flight_floor(m, c) <= hylo_map_flight_top(m)
				    : hylo_map_cell_clear(m, robot->modes[k].mode, c))
				return 1;
	return 0;
}

static hylo_status ingest_map(hylo_planner *pl, const hylo_map_view *map)
{
	hylo_status st;
	hylo_real margin;

	pl->has_map = 0;
	forget_roadmap(pl);
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
	margin = hylo_planner_margin(&pl->cfg);
	st = hylo_map_inflate(&pl->map, pl->robot->body_radius_m + margin, &pl->reason);
	if (st != HYLO_OK)
		return st;
	if (!map_has_domain(&pl->map, pl->robot))
		return hylo_fail(&pl->reason, HYLO_E_EMPTY_DOMAIN,
				 "map %lld has no cell where robot %s keeps its clearance of %g m (body %g m + margin %g m) from every hazard",
				 (long long)pl->map.map_id, pl->robot->name, pl->map.inflation,
				 pl->robot->body_radius_m, margin);
	attach_caches(pl);
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

/* Where a state of mode sits in the work space. */
static hylo_point state_point(const hylo_map *m, hylo_mode mode, const hylo_real *xs)
{
	const hylo_mode_desc *d = hylo_mode_describe(mode);
	hylo_point p;

	p.x = xs[0];
	p.y = xs[1];
	p.z = 0;
	if (d->planar)
		p.z = hylo_map_height(m, xs[0], xs[1]);
	else if (d->air)
		p.z = xs[2];
	return p;
}

/* p in the plain domain of mode, without the clearance (inflation 0 is
 * the plain domains, hylo/clearance.h). */
static int plain_contains(hylo_planner *pl, hylo_mode mode, hylo_point p)
{
	hylo_real r = pl->map.inflation;
	int in;

	pl->map.inflation = 0;
	in = hylo_domain_contains(&pl->map, mode, p);
	pl->map.inflation = r;
	return in;
}

static const char *domain_of(hylo_planner *pl, hylo_point p)
{
	int k;

	for (k = HYLO_MODE_NONE + 1; k < HYLO_MODE_COUNT; k++)
		if (hylo_robot_mode_index(pl->robot, (hylo_mode)k) >= 0 &&
		    plain_contains(pl, (hylo_mode)k, p))
			return hylo_mode_str((hylo_mode)k);
	return NULL;
}

/* A start or goal in its mode's domain but not in the part that keeps the
 * clearance: the planner could not leave it, or reach it, on edges that
 * keep it, so the request is refused naming what is missing. */
static hylo_status lacks_clearance(hylo_planner *pl, const char *what, hylo_mode mode,
				   hylo_point p)
{
	hylo_real need = pl->map.inflation, d = hylo_hazard_distance(&pl->map, mode, p, need);
	hylo_real margin = hylo_planner_margin(&pl->cfg);

	if (d < need)
		return hylo_fail(&pl->reason, HYLO_E_OUTSIDE_DOMAIN,
				 "%s (%g, %g, %g) is %.3g m from the nearest %s hazard; robot %s needs %g m (body %g m + margin %g m)",
				 what, p.x, p.y, p.z, d, hylo_mode_str(mode), pl->robot->name, need,
				 pl->robot->body_radius_m, margin);
	return hylo_fail(&pl->reason, HYLO_E_OUTSIDE_DOMAIN,
			 "%s (%g, %g, %g) keeps %g m (body %g m + margin %g m) from every %s hazard, but its cell does not: the planner keeps the clearance cell by cell",
			 what, p.x, p.y, p.z, need, pl->robot->body_radius_m, margin,
			 hylo_mode_str(mode));
}

static hylo_status check_state(hylo_planner *pl, const char *what, int mode,
			       const hylo_real *xs, hylo_point *p)
{
	const char *other;
	const hylo_svr_model *model;
	hylo_region_miss miss;
	int idx = hylo_robot_mode_index(pl->robot, (hylo_mode)mode);

	if (!hylo_mode_valid(mode) || idx < 0)
		return hylo_fail(&pl->reason, HYLO_E_WRONG_MODE,
				 "%s mode %d (%s) is not a mode of robot %s", what, mode,
				 hylo_mode_str((hylo_mode)mode), pl->robot->name);
	/* Every coordinate is finite (hylo_goal_check). */
	/* The model's costs from a state it never saw (a speed, a vertical
	 * velocity, ...) are extrapolations. */
	model = pl->robot->modes[idx].model;
	if (model && !hylo_region_state(model, (hylo_mode)mode, xs, &miss)) {
		if (miss.part == HYLO_REGION_SPEED)
			return hylo_fail(&pl->reason, HYLO_E_BAD_VALUE,
					 "%s speed %g m/s is outside the %s model's training range [%g, %g] m/s",
					 what, miss.value, hylo_mode_str((hylo_mode)mode), miss.lo, miss.hi);
		return hylo_fail(&pl->reason, HYLO_E_BAD_VALUE,
				 "%s %s = %g %s is outside the %s model's training range [%g, %g] %s",
				 what, hylo_coord_name((hylo_mode)mode, miss.coord), miss.value,
				 hylo_coord_unit((hylo_mode)mode, miss.coord),
				 hylo_mode_str((hylo_mode)mode), miss.lo, miss.hi,
				 hylo_coord_unit((hylo_mode)mode, miss.coord));
	}
	*p = state_point(&pl->map, (hylo_mode)mode, xs);
	if (hylo_domain_contains(&pl->map, (hylo_mode)mode, *p))
		return HYLO_OK;
	if (plain_contains(pl, (hylo_mode)mode, *p))
		return lacks_clearance(pl, what, (hylo_mode)mode, *p);
	other = domain_of(pl, *p);
	if (other)
		return hylo_fail(&pl->reason, HYLO_E_WRONG_MODE,
				 "%s (%g, %g, %g) lies in the %s domain, not in %s", what, p->x,
				 p->y, p->z, other, hylo_mode_str((hylo_mode)mode));
	return hylo_fail(&pl->reason, HYLO_E_OUTSIDE_DOMAIN,
			 "%s (%g, %g, %g) lies outside the %s domain (obstacle, off the map, or out of the air space)",
			 what, p->x, p->y, p->z, hylo_mode_str((hylo_mode)mode));
}

/* A finite number (and >= 0 when non_negative), or a reason naming the field. */
static hylo_status check_real(hylo_real v, const char *field, int index, int non_negative,
			      hylo_reason *r)
{
	if (isfinite(v) && !(non_negative && v < 0))
		return HYLO_OK;
	if (index >= 0)
		return hylo_fail(r, HYLO_E_BAD_VALUE, "%s[%d] = %g must be finite%s", field, index,
				 v, non_negative ? " and >= 0" : "");
	return hylo_fail(r, HYLO_E_BAD_VALUE, "%s = %g must be finite%s", field, v,
			 non_negative ? " and >= 0" : "");
}

static hylo_status check_reals(const hylo_real *v, uint32_t n, const char *field,
			       int non_negative, hylo_reason *r)
{
	uint32_t k;
	hylo_status st = HYLO_OK;

	for (k = 0; k < n && st == HYLO_OK; k++)
		st = check_real(v[k], field, (int)k, non_negative, r);
	return st;
}

hylo_status hylo_goal_check(const hylo_goal *g, hylo_reason *r)
{
	hylo_status st;

	if (!g)
		return hylo_fail(r, HYLO_E_NULL, "goal is NULL");
	if (g->algorithm != HYLO_ASTAR && g->algorithm != HYLO_DIJKSTRA)
		return hylo_fail(r, HYLO_E_BAD_VALUE, "unknown algorithm %d", g->algorithm);
	if (!hylo_mode_valid(g->start_mode))
		return hylo_fail(r, HYLO_E_WRONG_MODE, "start_mode %d is not a mode", g->start_mode);
	if (!hylo_mode_valid(g->goal_mode))
		return hylo_fail(r, HYLO_E_WRONG_MODE, "goal_mode %d is not a mode", g->goal_mode);
	/* Every entry, also those the mode does not use: they are echoed. */
	st = check_reals(g->start, HYLO_XS_DIM, "start", 0, r);
	if (st == HYLO_OK)
		st = check_reals(g->goal, HYLO_XS_DIM, "goal", 0, r);
	if (st == HYLO_OK)
		st = check_real(g->sampling.spacing, "spacing_m", -1, 1, r);
	if (st == HYLO_OK)
		st = check_real(g->sampling.air_spacing, "air_spacing_m", -1, 1, r);
	if (st == HYLO_OK)
		st = check_real(g->sampling.guard_spacing, "guard_spacing_m", -1, 1, r);
	if (st == HYLO_OK)
		st = check_real(g->sampling.connect_radius, "connect_radius_m", -1, 1, r);
	if (st == HYLO_OK)
		st = check_real(g->sampling.air_connect_radius, "air_connect_radius_m", -1, 1, r);
	if (st == HYLO_OK)
		st = check_real(g->time_budget_ms, "time_budget_ms", -1, 1, r);
	if (st != HYLO_OK)
		return st;
	if (!isfinite(g->suboptimality) || (g->suboptimality != 0 && g->suboptimality < 1))
		return hylo_fail(r, HYLO_E_BAD_VALUE,
				 "suboptimality %g must be 0 (the optimum) or a finite number >= 1",
				 g->suboptimality);
	if (isnan(g->alternatives_within) || (g->alternatives_within != 0 && g->alternatives_within < 1))
		return hylo_fail(r, HYLO_E_BAD_VALUE,
				 "alternatives_within %g must be 0 (the default, %g) or >= 1",
				 g->alternatives_within, HYLO_ALTERNATIVES_WITHIN);
	if (g->alternatives > HYLO_MAX_ALTERNATIVES)
		return hylo_fail(r, HYLO_E_BAD_VALUE,
				 "alternatives %lu: at most HYLO_MAX_ALTERNATIVES = %d",
				 (unsigned long)g->alternatives, HYLO_MAX_ALTERNATIVES);
	st = hylo_sampling_check_grids(&g->sampling, r);
	if (st != HYLO_OK)
		return st;
	hylo_reason_clear(r);
	return HYLO_OK;
}

static hylo_status check_goal(hylo_planner *pl, const hylo_goal *g, hylo_point *ps,
			      hylo_point *pg)
{
	hylo_status st;
	uint32_t k;

	st = hylo_goal_check(g, &pl->reason);
	if (st != HYLO_OK)
		return st;
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
		hylo_real radius = hylo_mode_describe(mm->mode)->air ? g->sampling.air_connect_radius
								      : g->sampling.connect_radius;

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
	for (k = 0; k < pl->n_start_adj; k++)
		pl->links_start[pl->start_adj[k]] = 0;
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
	for (k = 0; k < pl->n_start_adj; k++)
		pl->links_start[pl->start_adj[k]] = 1;
	pl->start_goal_linked =
		g->start_mode == g->goal_mode &&
		hylo_roadmap_distance(ps, pg) <= hylo_roadmap_radius(rm, (hylo_mode)g->goal_mode) &&
		hylo_domain_segment(&pl->map, (hylo_mode)g->goal_mode, ps, pg);
	return HYLO_OK;
}

static hylo_real node_heuristic(void *ctx, uint32_t u)
{
	return hylo_planner_h((const hylo_planner *)ctx, u);
}

/* ---- plan extraction --------------------------------------------------- */

static int is_switch(const hylo_roadmap *rm, uint32_t a, uint32_t b)
{
	return a < rm->n_positions && rm->pos[a].twin == b;
}

/* The plan of the node path path[0 .. n), with cost[k] from the start. */
static void fill_plan(hylo_planner *pl, const uint32_t *path, const hylo_real *cost, uint32_t n,
		      hylo_plan *plan)
{
	const hylo_roadmap *rm = &pl->roadmap;
	uint32_t k;

	plan->n_waypoints = n;
	plan->n_modes = 0;
	for (k = 0; k < n; k++) {
		uint32_t u = path[k], i = rm->node_pos[u];
		uint8_t mode = rm->pos[i].mode;

		plan->mode[k] = mode;
		hylo_planner_node_state(pl, i, u - rm->pos[i].node_base, plan->state[k]);
		plan->cost[k] = cost[k];
		plan->guard[k] = (k + 1 < n && is_switch(rm, i, rm->node_pos[path[k + 1]])) ||
				 (k > 0 && is_switch(rm, i, rm->node_pos[path[k - 1]]));
		if (plan->n_modes == 0 || plan->mode_sequence[plan->n_modes - 1] != mode)
			plan->mode_sequence[plan->n_modes++] = mode;
	}
	plan->total_cost = plan->cost[n - 1];
}

/* The search's path to its node goal_node (the goal, or a copy of it). */
static hylo_status extract(hylo_planner *pl, uint32_t goal_node, hylo_plan *plan)
{
	uint32_t k, n;
	hylo_status st;

	st = hylo_search_path(&pl->search, goal_node, pl->path, HYLO_MAX_WAYPOINTS, &n,
			      &pl->reason);
	if (st != HYLO_OK)
		return st;
	for (k = 0; k < n; k++) {
		pl->path_cost[k] = hylo_search_cost(&pl->search, pl->path[k]);
		pl->path[k] = hylo_planner_graph_node(pl, pl->path[k]);
	}
	fill_plan(pl, pl->path, pl->path_cost, n, plan);
	return HYLO_OK;
}

/* Changes of travel mode on the search's best path to its node v (moves
 * are edges within a mode; a switch edge alone changes nothing). */
static uint32_t switches_to(const hylo_planner *pl, uint32_t v)
{
	const hylo_roadmap *rm = &pl->roadmap;
	uint32_t n = 0, steps = 0, u;
	int last = -1;

	for (u = hylo_search_parent(&pl->search, v); u != HYLO_NO_NODE && steps < pl->search.n_nodes;
	     v = u, u = hylo_search_parent(&pl->search, u), steps++) {
		int mu = rm->pos[rm->node_pos[hylo_planner_graph_node(pl, u)]].mode;
		int mv = rm->pos[rm->node_pos[hylo_planner_graph_node(pl, v)]].mode;

		if (mu != mv)
			continue;
		n += last >= 0 && mu != last;
		last = mu;
	}
	return n;
}

/* The same for a plan's waypoints: consecutive ones in one mode are a move. */
static uint32_t travel_changes(const hylo_plan *plan)
{
	uint32_t n = 0, w;
	int last = -1;

	for (w = 1; w < plan->n_waypoints; w++) {
		if (plan->mode[w] != plan->mode[w - 1])
			continue;
		n += last >= 0 && plan->mode[w] != last;
		last = plan->mode[w];
	}
	return n;
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
	plan->suboptimality = 1;
	plan->lower_bound = 0;
	plan->n_waypoints = 0;
	plan->n_modes = 0;
	plan->n_alternatives = 0;
	plan->max_switches = 0;
	plan->n_nodes = 0;
	plan->n_edges = 0;
	plan->n_edges_evaluated = 0;
	plan->n_edges_cached = 0;
	plan->n_expansions = 0;
	plan->n_clamped = 0;
	plan->n_negative = 0;
	plan->n_infeasible = 0;
	plan->n_untrained = 0;
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

/* The roadmap for the goal's sampling options: the current one, or a new
 * one (which empties the edge cache). */
static hylo_status roadmap_for(hylo_planner *pl, const hylo_sampling *s, hylo_plan *plan)
{
	hylo_roadmap *rm = &pl->roadmap;
	hylo_status st;

	if (rm->built && hylo_sampling_equal(&rm->sampling, s)) {
		plan->roadmap_reused = 1;
		return HYLO_OK;
	}
	st = hylo_roadmap_build(rm, &pl->build_ws, &pl->map, pl->robot, s, &pl->reason);
	if (st != HYLO_OK)
		return st;
	/* The old goal's links refer to positions that no longer exist. */
	forget_terminals(pl);
	hylo_edge_cache_reset(&pl->cache, rm);
	hylo_planner_bound_tables(pl);
	return HYLO_OK;
}

/* The walk's path as the plan (it costs pl->bound). */
static void walk_plan(hylo_planner *pl, hylo_plan *plan)
{
	fill_plan(pl, pl->walk_path, pl->walk_cost, pl->walk_len, plan);
}

/*
 * After the search: the plan and its outcome. A search that found no path
 * although the walk did was pruned by the walk's cost, so the walk's path is
 * optimal. When the budget ran out, the better of the walk's path and the
 * search's best path to the goal so far is returned, not proven optimal,
 * with the search's least open f-value as a lower bound (A*).
 */
static hylo_status finish(hylo_planner *pl, hylo_plan *plan)
{
	uint32_t goal = pl->roadmap.n_nodes + 1;
	hylo_real reached = hylo_search_cost(&pl->search, goal), lower;

	if (plan->outcome == HYLO_FOUND) {
		plan->lower_bound = 0;
		pl->n_found = 1;
		pl->found[0] = goal;
		return extract(pl, goal, plan);
	}
	if (plan->outcome == HYLO_NO_PATH) {
		if (pl->walk_len > 0) {
			walk_plan(pl, plan);
			plan->outcome = HYLO_FOUND;
			pl->n_found = 1;
			pl->found[0] = HYLO_NO_NODE;
		}
		return HYLO_OK;
	}
	if (!isfinite(reached) && pl->walk_len == 0)
		return HYLO_OK;
	pl->n_found = 1;
	if (isfinite(reached) && !(pl->walk_len > 0 && pl->bound <= reached)) {
		hylo_status st = extract(pl, goal, plan);

		if (st != HYLO_OK)
			return st;
		pl->found[0] = goal;
	} else {
		walk_plan(pl, plan);
		pl->found[0] = HYLO_NO_NODE;
	}
	plan->outcome = HYLO_FOUND_UNPROVEN;
	lower = pl->use_heuristic && pl->weight == 1 ? hylo_search_min_key(&pl->search) : 0;
	plan->lower_bound = isfinite(lower) && lower < plan->total_cost ? lower : 0;
	return HYLO_OK;
}

static void reset_counts(hylo_planner *pl)
{
	pl->n_clamped = 0;
	pl->n_negative = 0;
	pl->n_infeasible = 0;
	pl->n_untrained = 0;
	pl->n_evaluated = 0;
	pl->n_cached = 0;
	pl->walk_len = 0;
	pl->bound = INFINITY;
	pl->n_found = 0;
	pl->layers = 1;
	pl->layer_stride = pl->roadmap.n_nodes + 2;
}

static void report_counts(const hylo_planner *pl, hylo_plan *plan)
{
	plan->n_edges_evaluated = pl->n_evaluated;
	plan->n_edges_cached = pl->n_cached;
	plan->n_expansions = pl->search.stats.expansions;
	plan->n_clamped = pl->n_clamped;
	plan->n_negative = pl->n_negative;
	plan->n_infeasible = pl->n_infeasible;
	plan->n_untrained = pl->n_untrained;
}

/* Copies of the graph for k alternatives: one per number of mode switches
 * so far, as many as HYLO_MAX_SWITCH_LAYERS and HYLO_MAX_NODES allow (the
 * last holds that many switches or more); 1 (the graph) for one plan. */
static uint32_t layers_for(const hylo_planner *pl, uint32_t k)
{
	/* room for the layered heuristic's source and sentinel too */
	uint32_t l = (HYLO_MAX_NODES - 2) / pl->layer_stride;

	if (k <= 1 || l < 2)
		return 1;
	return l < HYLO_MAX_SWITCH_LAYERS ? l : HYLO_MAX_SWITCH_LAYERS;
}

/*
 * After a search over copies of the graph: the goal copies it closed are the
 * best paths of distinct mode sequences, cheapest first (each the optimum
 * of its number of switches on the roadmap, or w times it). The plan is the
 * first; the budget cuts only the later ones.
 */
static hylo_status finish_alternatives(hylo_planner *pl, hylo_plan *plan)
{
	uint32_t k, n = hylo_search_n_found(&pl->search);

	if (n == 0)
		return HYLO_OK;
	plan->outcome = HYLO_FOUND;
	plan->lower_bound = 0;
	pl->n_found = n;
	for (k = 0; k < n; k++) {
		pl->found[k] = hylo_search_found(&pl->search, k);
		plan->alternative_cost[k] = hylo_search_cost(&pl->search, pl->found[k]);
		plan->alternative_switches[k] = switches_to(pl, pl->found[k]);
	}
	return extract(pl, pl->found[0], plan);
}

static hylo_status search(hylo_planner *pl, const hylo_goal *g, hylo_plan *plan, double t0)
{
	hylo_roadmap *rm = &pl->roadmap;
	hylo_budget budget, unlimited;
	hylo_graph graph;
	hylo_status st = HYLO_OK;
	double deadline = g->time_budget_ms > 0 ? t0 + g->time_budget_ms : INFINITY;
	uint32_t goals[HYLO_MAX_SEARCH_GOALS], k, want;
	hylo_real within = g->alternatives_within > 0 ? g->alternatives_within : HYLO_ALTERNATIVES_WITHIN;

	memset(&unlimited, 0, sizeof unlimited);
	memset(&budget, 0, sizeof budget);
	budget.clock = pl->cfg.clock;
	budget.clock_ctx = pl->cfg.clock_ctx;
	pl->use_heuristic = g->algorithm == HYLO_ASTAR;
	pl->h_reach = g->alternatives > 1 && within > HYLO_HEURISTIC_REACH ? within : HYLO_HEURISTIC_REACH;
	pl->layers = layers_for(pl, g->alternatives);
	pl->layer_mode[0] = (uint8_t)g->start_mode;
	pl->layer_mode[1] = pl->robot->n_modes == 2 && (int)pl->robot->modes[0].mode == g->start_mode
				    ? (uint8_t)pl->robot->modes[1].mode
				    : (uint8_t)pl->robot->modes[0].mode;
	pl->h_layered = 0;
	pl->forward_begun = 0;
	pl->n_live = pl->layers;
	pl->cap = 0;
	pl->cap_step = 0;
	pl->layered_within = within;
	pl->deadline = deadline;
	if (pl->use_heuristic)
		st = hylo_planner_heuristic(pl, &unlimited);
	if (st != HYLO_OK)
		return st;
	/* The walk's bound would prune every path dearer than the best. */
	plan->max_switches = pl->layers - 1;
	if (pl->use_heuristic && pl->layers == 1)
		pl->bound = hylo_planner_greedy_walk(pl, deadline);
	budget.max_expansions = g->max_expansions;
	budget.time_budget_ms = g->time_budget_ms > 0 ? deadline - now_ms(pl) : 0;
	plan->outcome = HYLO_BUDGET_EXHAUSTED;
	if (g->time_budget_ms > 0 && budget.time_budget_ms <= 0)
		return finish(pl, plan);
	graph.n_nodes = pl->layer_stride * pl->layers;
	graph.expand = hylo_planner_expand;
	graph.resolve = hylo_planner_resolve;
	graph.heuristic = pl->use_heuristic ? node_heuristic : NULL;
	graph.weight = pl->weight;
	graph.ctx = pl;
	graph.found = pl->layers > 1 ? hylo_planner_found : NULL;
	graph.group_key = pl->layers > 1 ? hylo_planner_group_key : NULL;
	for (k = 0; k < pl->layers; k++)
		goals[k] = k * pl->layer_stride + rm->n_nodes + 1;
	want = pl->layers == 1 ? 1 : g->alternatives < pl->layers ? g->alternatives : pl->layers;
	st = hylo_search_run_goals(&pl->search, &graph, rm->n_nodes, goals, pl->layers, want,
				   within, &budget, &plan->outcome, &pl->reason);
	if (st != HYLO_OK)
		return st;
	return pl->layers == 1 ? finish(pl, plan) : finish_alternatives(pl, plan);
}

static hylo_status run(hylo_planner *pl, const hylo_goal *g, hylo_plan *plan, double t0)
{
	hylo_roadmap *rm = &pl->roadmap;
	hylo_point ps, pg;
	hylo_status st;

	st = check_goal(pl, g, &ps, &pg);
	if (st == HYLO_OK)
		st = roadmap_for(pl, &g->sampling, plan);
	if (st == HYLO_OK)
		st = connect_terminals(pl, g, ps, pg);
	if (st != HYLO_OK)
		return st;
	plan->n_nodes = rm->n_nodes + 2;
	plan->n_edges = rm->n_edges + terminal_edges(pl);
	pl->weight = g->suboptimality > 1 ? g->suboptimality : 1;
	plan->suboptimality = pl->weight;
	reset_counts(pl);
	st = search(pl, g, plan, t0);
	report_counts(pl, plan);
	if (st == HYLO_OK && pl->n_found > 0) {
		plan->n_alternatives = pl->n_found;
		if (pl->layers == 1) {
			plan->alternative_cost[0] = plan->total_cost;
			plan->alternative_switches[0] = travel_changes(plan);
		}
	} else {
		pl->n_found = 0;
	}
	return st;
}

hylo_status hylo_planner_alternative(hylo_planner *pl, uint32_t k, hylo_plan *plan)
{
	if (!pl || !plan)
		return pl ? hylo_fail(&pl->reason, HYLO_E_NULL, "hylo_planner_alternative: NULL argument")
			  : HYLO_E_NULL;
	if (k >= pl->n_found)
		return hylo_fail(&pl->reason, HYLO_E_BAD_VALUE,
				 "alternative %lu: the last plan has %lu", (unsigned long)k,
				 (unsigned long)pl->n_found);
	if (pl->found[k] == HYLO_NO_NODE) {
		walk_plan(pl, plan);
		return HYLO_OK;
	}
	return extract(pl, pl->found[k], plan);
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
		pl->n_found = 0;
		st = run(pl, goal, plan, t0);
		plan->plan_ms = now_ms(pl) - t0;
		if (st == HYLO_OK && plan->outcome != HYLO_FOUND)
			hylo_fail(&pl->reason, HYLO_OK, "%s", hylo_outcome_str(plan->outcome));
		if (st == HYLO_OK && plan->outcome == HYLO_FOUND_UNPROVEN && plan->lower_bound > 0)
			hylo_fail(&pl->reason, HYLO_OK, "%s; the optimum is at least %.6g",
				  hylo_outcome_str(plan->outcome), plan->lower_bound);
	}
	plan->status = st;
	plan->reason = pl->reason;
	return st;
}
