/*
 * The planner end to end through its public API, on three scenes: results
 * against an independent full-graph Dijkstra, roadmap validity, reuse,
 * determinism (encoded plan_t bytes) and bad input.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hylo_msg.h"
#include "onboard/testutil_planner.h"

static hylo_planner *planner;     /* ~tens of MB: allocated once */
static hylo_planner *planner2;
static hylo_plan *plan;
static hylo_plan *plan2;
static hylo_robot robots[TU_N_ROBOTS];
static tu_cost costs;

static void init_planner(hylo_planner *pl)
{
	hylo_planner_config cfg;

	cfg = tu_config(robots, TU_N_ROBOTS);
	assert_int_equal(hylo_planner_init(pl, TU_PLANNER_BYTES, &cfg), HYLO_OK);
}

static void set_scene(hylo_planner *pl, tu_map *m)
{
	hylo_map_view v = tu_view(m);
	hylo_status st = hylo_planner_set_map(pl, &v);

	if (st != HYLO_OK)
		fail_msg("set_map: %s: %s", hylo_status_str(st), hylo_planner_reason(pl));
}

static void plan_ok(hylo_planner *pl, const hylo_goal *g, hylo_plan *p)
{
	hylo_status st = hylo_planner_plan(pl, g, p);

	if (st != HYLO_OK)
		fail_msg("plan: %s: %s", hylo_status_str(st), p->reason.text);
	if (p->outcome != HYLO_FOUND)
		fail_msg("plan outcome: %s", hylo_outcome_str(p->outcome));
}

/* ---- an independent oracle: the full graph, every edge evaluated, plain
 * O(V^2) Dijkstra ------------------------------------------------------ */

typedef struct {
	uint32_t n;
	uint32_t *begin;     /* n + 1 */
	uint32_t *head;
	double *cost;
} oracle_graph;

static double node_xs(const hylo_planner *pl, uint32_t u, double *xs)
{
	const hylo_roadmap *rm = &pl->roadmap;
	uint32_t i = rm->node_pos[u];

	if (i == pl->start_pos)
		memcpy(xs, pl->start_xs, sizeof pl->start_xs);
	else if (i == pl->goal_pos)
		memcpy(xs, pl->goal_xs, sizeof pl->goal_xs);
	else
		hylo_roadmap_state(rm, i, u - rm->pos[i].node_base, xs);
	return 0;
}

static double clamp_cost(const hylo_planner *pl, hylo_mode mode, double c, double dist)
{
	int k = hylo_robot_mode_index(pl->robot, mode);
	double lo = pl->robot->modes[k].cost_floor_j + pl->robot->modes[k].cost_floor_per_m * dist;

	return c < lo ? lo : c;
}

/* Out-edges of every node, from the roadmap's public data. */
static void oracle_build(const hylo_planner *pl, oracle_graph *og)
{
	const hylo_roadmap *rm = &pl->roadmap;
	uint32_t n = rm->n_nodes + 2, cap = 1u << 22, m = 0, u;

	og->n = n;
	og->begin = malloc((n + 1) * sizeof *og->begin);
	og->head = malloc(cap * sizeof *og->head);
	og->cost = malloc(cap * sizeof *og->cost);
	for (u = 0; u < n; u++) {
		uint32_t i = rm->node_pos[u], c = u - rm->pos[i].node_base;
		const hylo_position *p = &rm->pos[i];
		double a[HYLO_XS_DIM], b[HYLO_XS_DIM];
		uint32_t nb[HYLO_MAX_SUCCESSORS + 1], nn = 0, k, cc, combos[HYLO_MAX_COMBOS];

		og->begin[u] = m;
		if (i == pl->goal_pos)
			continue;
		node_xs(pl, u, a);
		if (i == pl->start_pos) {
			for (k = 0; k < pl->n_start_adj; k++)
				nb[nn++] = pl->start_adj[k];
			if (pl->start_goal_linked)
				nb[nn++] = pl->goal_pos;
		} else {
			for (k = p->adj_begin; k < p->adj_end; k++)
				nb[nn++] = rm->adjacency[k];
			if (pl->links_goal[i])
				nb[nn++] = pl->goal_pos;
		}
		for (k = 0; k < nn; k++) {
			const hylo_position *q = &rm->pos[nb[k]];
			double dist = hylo_roadmap_distance(p->p, q->p);

			for (cc = 0; cc < q->n_combos; cc++) {
				assert_true(m < cap);
				og->head[m] = q->node_base + cc;
				node_xs(pl, og->head[m], b);
				og->cost[m] = clamp_cost(pl, (hylo_mode)p->mode,
							 tu_edge_cost(&costs, (hylo_mode)p->mode, a, b),
							 dist);
				m++;
			}
		}
		if (i < rm->n_positions && p->twin != HYLO_NO_POSITION) {
			uint32_t ns = hylo_roadmap_switch_heads(rm, i, c, combos);
			int dir = p->mode == pl->robot->modes[0].mode ? 0 : 1;

			for (k = 0; k < ns; k++) {
				og->head[m] = rm->pos[p->twin].node_base + combos[k];
				og->cost[m] = pl->robot->switch_cost[dir];
				m++;
			}
		}
	}
	og->begin[n] = m;
}

static double oracle_cost(const oracle_graph *og, uint32_t s, uint32_t t)
{
	double *d = malloc(og->n * sizeof *d), best;
	char *done = calloc(og->n, 1);
	uint32_t u, k, it;

	for (u = 0; u < og->n; u++)
		d[u] = INFINITY;
	d[s] = 0;
	for (it = 0; it < og->n; it++) {
		uint32_t bu = UINT32_MAX;

		for (u = 0; u < og->n; u++)
			if (!done[u] && isfinite(d[u]) && (bu == UINT32_MAX || d[u] < d[bu]))
				bu = u;
		if (bu == UINT32_MAX)
			break;
		done[bu] = 1;
		for (k = og->begin[bu]; k < og->begin[bu + 1]; k++)
			if (d[bu] + og->cost[k] < d[og->head[k]])
				d[og->head[k]] = d[bu] + og->cost[k];
	}
	best = d[t];
	free(d);
	free(done);
	return best;
}

static void oracle_free(oracle_graph *og)
{
	free(og->begin);
	free(og->head);
	free(og->cost);
}

static void check_optimal(tu_map *m, hylo_goal g)
{
	oracle_graph og;
	double best, astar;
	uint64_t exp_astar, eval_astar;

	set_scene(planner, m);
	g.algorithm = HYLO_ASTAR;
	plan_ok(planner, &g, plan);
	astar = plan->total_cost;
	exp_astar = plan->n_expansions;
	eval_astar = plan->n_edges_evaluated;
	oracle_build(planner, &og);
	best = oracle_cost(&og, planner->roadmap.n_nodes, planner->roadmap.n_nodes + 1);
	assert_true(plan->n_edges == og.begin[og.n]);
	oracle_free(&og);
	g.algorithm = HYLO_DIJKSTRA;
	plan_ok(planner, &g, plan);
	print_message("%s: %u nodes, %llu edges; optimum %.6f; A* %llu expansions %llu evaluations, Dijkstra %llu / %llu\n",
		      m->robot, (unsigned)plan->n_nodes, (unsigned long long)plan->n_edges, best,
		      (unsigned long long)exp_astar, (unsigned long long)eval_astar,
		      (unsigned long long)plan->n_expansions,
		      (unsigned long long)plan->n_edges_evaluated);
	assert_true(isfinite(best));
	assert_true(fabs(astar - best) <= 1e-9 * best);
	assert_true(fabs(plan->total_cost - best) <= 1e-9 * best);
	assert_true(exp_astar <= plan->n_expansions);
	assert_true(eval_astar <= plan->n_edges_evaluated);
	assert_true(plan->n_edges_evaluated <= plan->n_edges);
}

static void test_optimal_river(void **state)
{
	tu_map m;
	hylo_goal g = tu_goal_river();
	uint64_t seed;

	(void)state;
	tu_river(&m);
	for (seed = 1; seed <= 3; seed++) {
		g.sampling.seed = seed;
		check_optimal(&m, g);
	}
	tu_map_free(&m);
}

static void test_optimal_chasm(void **state)
{
	tu_map m;

	(void)state;
	tu_chasm(&m);
	check_optimal(&m, tu_goal_chasm());
	tu_map_free(&m);
}

static void test_optimal_di(void **state)
{
	tu_map m;
	hylo_goal g = tu_goal_di();

	(void)state;
	tu_di(&m);
	check_optimal(&m, g);
	g.start[0] = 0.7;
	g.start[1] = -0.1;
	g.goal[0] = -0.5;
	g.goal[1] = 0.2;
	check_optimal(&m, g);
	tu_map_free(&m);
}

/* ---- the shape of a plan ---------------------------------------------- */

static int terrain_at(const tu_map *m, long ix, long iy)
{
	if (ix < 0 || ix >= m->nx || iy < 0 || iy >= m->ny)
		return -1;
	return m->terrain[iy * m->nx + ix];
}

static int shore_pair(int a, int b)
{
	return (a == HYLO_TERRAIN_GROUND && b == HYLO_TERRAIN_WATER) ||
	       (a == HYLO_TERRAIN_WATER && b == HYLO_TERRAIN_GROUND);
}

/* On a cell edge (endpoints included) with ground on one side and water on
 * the other. */
static int on_shoreline(const tu_map *m, double x, double y)
{
	double fx = (x - m->ox) / m->res, fy = (y - m->oy) / m->res;
	long ix = lround(fx), iy = lround(fy), k;

	if (fabs(fx - ix) <= 1e-9)      /* on the vertical line x = ix */
		for (k = (long)floor(fy + 1e-9) - 1; k <= (long)floor(fy - 1e-9) + 1; k++)
			if (fy >= k - 1e-9 && fy <= k + 1 + 1e-9 &&
			    shore_pair(terrain_at(m, ix - 1, k), terrain_at(m, ix, k)))
				return 1;
	if (fabs(fy - iy) <= 1e-9)      /* on the horizontal line y = iy */
		for (k = (long)floor(fx + 1e-9) - 1; k <= (long)floor(fx - 1e-9) + 1; k++)
			if (fx >= k - 1e-9 && fx <= k + 1 + 1e-9 &&
			    shore_pair(terrain_at(m, k, iy - 1), terrain_at(m, k, iy)))
				return 1;
	return 0;
}

static void test_river_plan_shape(void **state)
{
	tu_map m;
	hylo_goal g = tu_goal_river();
	uint32_t k, guards = 0;
	double sum = 0;

	(void)state;
	tu_river(&m);
	set_scene(planner, &m);
	plan_ok(planner, &g, plan);
	assert_int_equal(plan->request_id, 7);
	assert_string_equal(plan->robot, "ambot");
	assert_int_equal(plan->n_modes, 3);
	assert_int_equal(plan->mode_sequence[0], HYLO_MODE_GROUND);
	assert_int_equal(plan->mode_sequence[1], HYLO_MODE_MARINE);
	assert_int_equal(plan->mode_sequence[2], HYLO_MODE_GROUND);
	assert_memory_equal(plan->state[0], g.start, sizeof g.start);
	assert_memory_equal(plan->state[plan->n_waypoints - 1], g.goal, sizeof g.goal);
	assert_true(plan->cost[0] == 0);
	for (k = 0; k + 1 < plan->n_waypoints; k++) {
		const double *a = plan->state[k], *b = plan->state[k + 1];

		assert_true(plan->cost[k + 1] >= plan->cost[k]);
		if (plan->mode[k] != plan->mode[k + 1]) {
			/* A switch: twin guard waypoints at one place, zero cost. */
			assert_true(plan->guard[k] && plan->guard[k + 1]);
			assert_true(a[0] == b[0] && a[1] == b[1]);
			assert_true(on_shoreline(&m, a[0], a[1]));
			assert_true(plan->cost[k + 1] == plan->cost[k]);
			guards += 2;
			continue;
		}
		sum += clamp_cost(planner, (hylo_mode)plan->mode[k],
				  tu_edge_cost(&costs, (hylo_mode)plan->mode[k], a, b),
				  hypot(b[0] - a[0], b[1] - a[1]));
		assert_true(fabs(sum - plan->cost[k + 1]) <= 1e-9 * sum);
		assert_true(hypot(b[0] - a[0], b[1] - a[1]) <= g.sampling.connect_radius);
	}
	assert_int_equal(guards, 4);
	assert_true(plan->total_cost == plan->cost[plan->n_waypoints - 1]);
	tu_map_free(&m);
}

static void test_chasm_plan_shape(void **state)
{
	tu_map m;
	hylo_goal g = tu_goal_chasm();
	uint32_t k;
	int takeoffs = 0, landings = 0;

	(void)state;
	tu_chasm(&m);
	set_scene(planner, &m);
	plan_ok(planner, &g, plan);
	for (k = 0; k + 1 < plan->n_waypoints; k++) {
		const double *a = plan->state[k], *b = plan->state[k + 1];

		if (plan->mode[k] == HYLO_MODE_GROUND && plan->mode[k + 1] == HYLO_MODE_FLIGHT) {
			/* Takeoff: from rest on the ground to hover 1 m above. */
			assert_true(a[2] == 0 && b[3] == 0 && b[4] == 0 && b[5] == 0);
			assert_true(a[0] == b[0] && a[1] == b[1]);
			assert_true(fabs(b[2] - (hylo_map_height(&planner->map, a[0], a[1]) + 1.0)) < 1e-12);
			assert_true(fabs(plan->cost[k + 1] - plan->cost[k] - 300) < 1e-9);
			takeoffs++;
		}
		if (plan->mode[k] == HYLO_MODE_FLIGHT && plan->mode[k + 1] == HYLO_MODE_GROUND) {
			assert_true(b[2] == 0 && a[3] == 0 && a[4] == 0 && a[5] == 0);
			assert_true(fabs(plan->cost[k + 1] - plan->cost[k] - 150) < 1e-9);
			landings++;
		}
	}
	/* The platforms are separated by walls: the robot must fly at least once. */
	assert_true(takeoffs >= 1);
	assert_int_equal(takeoffs, landings);
	assert_int_equal(plan->mode_sequence[0], HYLO_MODE_GROUND);
	assert_int_equal(plan->mode_sequence[plan->n_modes - 1], HYLO_MODE_GROUND);
	tu_map_free(&m);
}

/* ---- the roadmap ------------------------------------------------------ */

static int segment_dense(const hylo_map *m, hylo_mode mode, hylo_point a, hylo_point b)
{
	int k;

	for (k = 0; k <= 400; k++) {
		double t = k / 400.0;
		hylo_point p = { a.x + t * (b.x - a.x), a.y + t * (b.y - a.y), a.z + t * (b.z - a.z) };

		if (!hylo_domain_contains(m, mode, p))
			return 0;
	}
	return 1;
}

static void check_roadmap(tu_map *m, hylo_goal g)
{
	const hylo_roadmap *rm = &planner->roadmap;
	const hylo_map *map = &planner->map;
	uint32_t i, j, k, guards = 0;

	set_scene(planner, m);
	plan_ok(planner, &g, plan);
	for (i = 0; i < rm->n_positions; i++) {
		const hylo_position *p = &rm->pos[i];

		assert_true(hylo_domain_contains(map, (hylo_mode)p->mode, p->p));
		for (k = p->adj_begin; k < p->adj_end; k++) {
			const hylo_position *q = &rm->pos[rm->adjacency[k]];
			uint32_t back;
			int found = 0;

			assert_int_equal(q->mode, p->mode);
			assert_true(hylo_roadmap_distance(p->p, q->p) <=
				    hylo_roadmap_radius(rm, (hylo_mode)p->mode));
			assert_true(segment_dense(map, (hylo_mode)p->mode, p->p, q->p));
			for (back = q->adj_begin; back < q->adj_end; back++)
				found |= rm->adjacency[back] == i;
			assert_true(found);
			/* The way back is the entry that names i. */
			back = rm->adj_reverse[k];
			assert_true(back >= q->adj_begin && back < q->adj_end);
			assert_int_equal(rm->adjacency[back], i);
		}
		if (p->twin != HYLO_NO_POSITION) {
			const hylo_position *t = &rm->pos[p->twin];

			guards++;
			assert_int_equal(t->twin, i);
			assert_true(t->mode != p->mode);
			assert_true(p->p.x == t->p.x && p->p.y == t->p.y);
			if (p->mode == HYLO_MODE_DI_NEG || p->mode == HYLO_MODE_DI_POS)
				assert_true(p->p.x == 0);
			if (p->mode == HYLO_MODE_FLIGHT)
				assert_true(fabs(p->p.z - t->p.z - 1.0) < 1e-12);
			if (p->mode == HYLO_MODE_MARINE)
				assert_true(on_shoreline(m, p->p.x, p->p.y));
		}
	}
	/* Completeness, by brute force over all pairs. */
	for (i = 0; i < rm->n_positions; i++)
		for (j = 0; j < rm->n_positions; j++) {
			const hylo_position *p = &rm->pos[i], *q = &rm->pos[j];
			int listed = 0;

			if (i == j || p->mode != q->mode ||
			    hylo_roadmap_distance(p->p, q->p) > hylo_roadmap_radius(rm, (hylo_mode)p->mode) ||
			    !hylo_domain_segment(map, (hylo_mode)p->mode, p->p, q->p))
				continue;
			for (k = p->adj_begin; k < p->adj_end; k++)
				listed |= rm->adjacency[k] == j;
			assert_true(listed);
		}
	assert_int_equal(guards, 2 * rm->n_guards);
	assert_true(rm->n_guards > 0);
}

static void test_roadmap_valid(void **state)
{
	tu_map m;

	(void)state;
	tu_river(&m);
	check_roadmap(&m, tu_goal_river());
	tu_map_free(&m);
	tu_chasm(&m);
	check_roadmap(&m, tu_goal_chasm());
	tu_map_free(&m);
	tu_di(&m);
	check_roadmap(&m, tu_goal_di());
	tu_map_free(&m);
}

/* ---- reuse and determinism -------------------------------------------- */

static size_t encode(const hylo_plan *p, uint8_t *buf, size_t cap)
{
	static hylo_plan_msg_buf mb;
	hylo_plan_t msg;
	int n;

	hylo_msg_plan(p, 0, &mb, &msg);
	n = hylo_plan_t_encoded_size(&msg);
	assert_true(n > 0 && (size_t)n <= cap);
	assert_int_equal(hylo_plan_t_encode(buf, 0, n, &msg), n);
	return (size_t)n;
}

static void assert_same_plan(const hylo_plan *a, const hylo_plan *b)
{
	static uint8_t ba[1 << 20], bb[1 << 20];
	size_t na = encode(a, ba, sizeof ba), nb = encode(b, bb, sizeof bb);

	assert_int_equal(na, nb);
	assert_memory_equal(ba, bb, na);
}

/* The same plan, whatever the edge cache held before: equal but for the
 * counts of evaluated and cached edges. */
static void assert_same_plan_but_counts(hylo_plan *a, hylo_plan *b)
{
	uint64_t ea = a->n_edges_evaluated, ca = a->n_edges_cached;
	uint64_t eb = b->n_edges_evaluated, cb = b->n_edges_cached;

	a->n_edges_evaluated = b->n_edges_evaluated = 0;
	a->n_edges_cached = b->n_edges_cached = 0;
	assert_same_plan(a, b);
	a->n_edges_evaluated = ea;
	a->n_edges_cached = ca;
	b->n_edges_evaluated = eb;
	b->n_edges_cached = cb;
}

static void test_roadmap_reuse(void **state)
{
	tu_map m;
	hylo_goal g1 = tu_goal_river(), g2 = tu_goal_river(), g3 = tu_goal_river();

	(void)state;
	tu_river(&m);
	g2.start[0] = 27;
	g2.start[1] = 18;
	g2.start[2] = 0.5;
	g2.goal[0] = 1;
	g2.goal[1] = 2;
	g2.goal[3] = TU_PI;
	g3.goal[1] += 1.5;
	set_scene(planner, &m);
	plan_ok(planner, &g1, plan);
	assert_int_equal(plan->roadmap_reused, 0);
	/* A nearby goal on the same map: the roadmap and most edge costs are
	 * reused, and the plan is the one a fresh planner returns. */
	plan_ok(planner, &g3, plan);
	assert_int_equal(plan->roadmap_reused, 1);
	init_planner(planner2);
	set_scene(planner2, &m);
	plan_ok(planner2, &g3, plan2);
	assert_int_equal(plan2->roadmap_reused, 0);
	plan2->roadmap_reused = 1;
	assert_true(plan->n_edges_cached > 0);
	assert_true(plan->n_edges_evaluated < plan2->n_edges_evaluated / 2);
	assert_same_plan_but_counts(plan, plan2);
	/* The way back (other edges: costs depend on the direction). */
	plan_ok(planner, &g2, plan);
	plan_ok(planner2, &g2, plan2);
	assert_same_plan_but_counts(plan, plan2);
	/* Back to g1: the old goal's links are gone. */
	plan_ok(planner, &g1, plan);
	plan_ok(planner2, &g1, plan2);
	assert_true(plan->n_edges_evaluated <= plan2->n_edges_evaluated);
	assert_same_plan_but_counts(plan, plan2);
	/* Other options or a new map rebuild, and empty the cache: the same
	 * counts as a fresh planner's. */
	g1.sampling.seed = 99;
	plan_ok(planner, &g1, plan);
	assert_int_equal(plan->roadmap_reused, 0);
	init_planner(planner2);
	set_scene(planner2, &m);
	plan_ok(planner2, &g1, plan2);
	assert_true(plan->n_edges_evaluated == plan2->n_edges_evaluated);
	set_scene(planner, &m);
	g1.sampling.seed = 1;
	plan_ok(planner, &g1, plan);
	assert_int_equal(plan->roadmap_reused, 0);
	tu_map_free(&m);
}

static void test_determinism(void **state)
{
	tu_map m;
	hylo_goal g = tu_goal_river();

	(void)state;
	tu_river(&m);
	init_planner(planner2);
	set_scene(planner, &m);
	set_scene(planner2, &m);
	plan_ok(planner, &g, plan);
	plan_ok(planner2, &g, plan2);
	assert_same_plan(plan, plan2);
	/* Another seed gives another roadmap. */
	g.sampling.seed = 2;
	plan_ok(planner2, &g, plan2);
	assert_true(plan->n_nodes != plan2->n_nodes || plan->total_cost != plan2->total_cost);
	tu_map_free(&m);
}

static void test_negative_costs_clamped(void **state)
{
	tu_map m;
	hylo_goal g = tu_goal_di();
	uint32_t k;

	(void)state;
	tu_di(&m);
	set_scene(planner, &m);
	/* Rates 0 and a negative offset: many predictions below zero. */
	costs.rate[HYLO_MODE_DI_NEG] = 0;
	costs.rate[HYLO_MODE_DI_POS] = 0;
	robots[2].modes[0].cost_floor_per_m = 0;
	robots[2].modes[1].cost_floor_per_m = 0;
	costs.offset = -0.2;
	init_planner(planner);
	set_scene(planner, &m);
	plan_ok(planner, &g, plan);
	assert_true(plan->n_negative > 0);
	assert_true(plan->n_clamped >= plan->n_negative);
	for (k = 0; k + 1 < plan->n_waypoints; k++)
		assert_true(plan->cost[k + 1] >= plan->cost[k]);
	tu_robots(robots, &costs);
	init_planner(planner);
	tu_map_free(&m);
}

/* A feasibility classifier that accepts an edge iff its heading change is at
 * most 1 rad: one SV at the origin, kernel exp(-dtheta^2) (feature 2 is
 * +-dtheta; the others are scaled away), rho = exp(-1). */
static const double feas_sv[HYLO_FEATURES_PLANAR] = { 0 };
static const double feas_coef[1] = { 1 };
static const double feas_offset[HYLO_FEATURES_PLANAR] = { 0 };
static const double feas_scale[HYLO_FEATURES_PLANAR] = { 1e9, 1e9, 1, 1e9, 1e9, 1e9, 1e9, 1e9 };

static void test_feasibility_classifier(void **state)
{
	hylo_svr_model feas = {
		.name = "turn_limit", .n_sv = 1, .n_features = HYLO_FEATURES_PLANAR, .gamma = 1.0,
		.rho = 0.36787944117144233, .sv = feas_sv, .coef = feas_coef,
		.feature_offset = feas_offset, .feature_scale = feas_scale,
		.label_offset = 0, .label_scale = 1, .label_log = 0,
	};
	tu_map m;
	hylo_goal g = tu_goal_river();
	double free_cost;
	uint32_t k;

	(void)state;
	tu_river(&m);
	set_scene(planner, &m);
	plan_ok(planner, &g, plan);
	free_cost = plan->total_cost;
	assert_true(plan->n_infeasible == 0);
	robots[0].modes[0].feasibility = &feas;
	robots[0].modes[1].feasibility = &feas;
	init_planner(planner);
	set_scene(planner, &m);
	plan_ok(planner, &g, plan);
	assert_true(plan->n_infeasible > 0);
	assert_true(plan->total_cost >= free_cost);
	for (k = 0; k + 1 < plan->n_waypoints; k++)
		if (plan->mode[k] == plan->mode[k + 1] && !(plan->guard[k] && plan->guard[k + 1]))
			assert_true(fabs(hylo_wrap_angle(plan->state[k + 1][3] - plan->state[k][3])) <= 1.0);
	/* A classifier that rejects everything leaves no path. */
	feas.rho = 2;
	init_planner(planner);
	set_scene(planner, &m);
	assert_int_equal(hylo_planner_plan(planner, &g, plan), HYLO_OK);
	assert_int_equal(plan->outcome, HYLO_NO_PATH);
	/* A classifier with the wrong feature count is refused at init. */
	feas.n_features = 4;
	{
		hylo_planner_config cfg;

		cfg = tu_config(robots, TU_N_ROBOTS);
		assert_int_equal(hylo_planner_init(planner, TU_PLANNER_BYTES, &cfg), HYLO_E_BAD_VALUE);
		assert_non_null(strstr(hylo_planner_reason(planner), "feasibility"));
	}
	robots[0].modes[0].feasibility = NULL;
	robots[0].modes[1].feasibility = NULL;
	init_planner(planner);
	tu_map_free(&m);
}

/* ---- bad input -------------------------------------------------------- */

static void expect(hylo_status want, hylo_status got, const hylo_plan *p)
{
	if (got != want)
		fail_msg("expected %s, got %s: %s", hylo_status_str(want), hylo_status_str(got),
			 p->reason.text);
	assert_int_equal(p->status, want);
	assert_true(strlen(p->reason.text) > 0 && strcmp(p->reason.text, "ok") != 0);
	assert_int_equal(p->n_waypoints, 0);
}

/* Speeds outside a model's training range: the planner refuses start and
 * goal states and sampling grids with such speeds, naming them, and plans as
 * before within the range. A constant cost model (no SVs: cost exp(-rho))
 * carries the range. */
static void test_speed_range(void **state)
{
	static const double zeros[HYLO_FEATURES_FLIGHT] = { 0 };
	static const double ones[HYLO_FEATURES_FLIGHT] = { 1, 1, 1, 1, 1, 1, 1, 1, 1 };
	static const hylo_real fast_air[] = { 0.0, 4.0, 4.5 };
	static const hylo_real backing[] = { -0.5, 0.0, 0.5 };
	hylo_svr_model ground = {
		.name = "const_ground", .n_features = HYLO_FEATURES_PLANAR, .gamma = 1.0,
		.rho = -2.302585092994046, .feature_offset = zeros, .feature_scale = ones,
		.label_scale = 1, .label_log = 1, .speed_min_mps = 0, .speed_max_mps = 1.0,
	};
	hylo_svr_model flight = ground;
	tu_map river, chasm;
	hylo_goal g;

	(void)state;
	flight.name = "const_flight";
	flight.n_features = HYLO_FEATURES_FLIGHT;
	flight.speed_max_mps = 4.0;
	robots[0].modes[0].model = &ground;
	robots[1].modes[1].model = &flight;
	init_planner(planner);
	tu_river(&river);
	tu_chasm(&chasm);
	set_scene(planner, &river);
	g = tu_goal_river();   /* speeds 0, 0.5, 1.0: inside [0, 1] */
	plan_ok(planner, &g, plan);
	g.start[2] = 1.5;
	expect(HYLO_E_BAD_VALUE, hylo_planner_plan(planner, &g, plan), plan);
	assert_non_null(strstr(plan->reason.text, "start speed 1.5 m/s is outside the ground model's training range [0, 1]"));
	g = tu_goal_river();
	g.goal[2] = -0.25;   /* backing up: never trained */
	expect(HYLO_E_BAD_VALUE, hylo_planner_plan(planner, &g, plan), plan);
	assert_non_null(strstr(plan->reason.text, "goal speed -0.25"));
	g = tu_goal_river();
	tu_grid(g.sampling.speeds, &g.sampling.n_speeds, backing, 3);
	expect(HYLO_E_BAD_VALUE, hylo_planner_plan(planner, &g, plan), plan);
	assert_non_null(strstr(plan->reason.text, "speeds_mps[0] = -0.5 m/s"));
	/* No range declared (both bounds 0): any speed. */
	ground.speed_max_mps = 0;
	g = tu_goal_river();
	tu_grid(g.sampling.speeds, &g.sampling.n_speeds, backing, 3);
	g.start[2] = 1.5;
	plan_ok(planner, &g, plan);

	/* Flight: the grid of air speeds against |v|'s range. */
	set_scene(planner, &chasm);
	g = tu_goal_chasm();   /* air speeds 0 and 4: inside [0, 4] */
	plan_ok(planner, &g, plan);
	tu_grid(g.sampling.air_speeds, &g.sampling.n_air_speeds, fast_air, 3);
	expect(HYLO_E_BAD_VALUE, hylo_planner_plan(planner, &g, plan), plan);
	assert_non_null(strstr(plan->reason.text, "air_speeds_mps[2] = 4.5 m/s is outside the flight model's"));

	robots[0].modes[0].model = NULL;
	robots[1].modes[1].model = NULL;
	init_planner(planner);
	tu_map_free(&river);
	tu_map_free(&chasm);
}

/* The rest of a trained region (hylo/region.h): a flight start or goal
 * whose velocity is not level, like the training pairs', is refused naming
 * vz; level, it plans, and no edge the search evaluates lies outside the
 * region (plan->n_untrained); a region narrower than the roadmap's grid
 * shows in that count. */
static void test_trained_region(void **state)
{
	static const double zeros[HYLO_FEATURES_FLIGHT] = { 0 };
	static const double ones[HYLO_FEATURES_FLIGHT] = { 1, 1, 1, 1, 1, 1, 1, 1, 1 };
	hylo_svr_model flight = {
		.name = "const_flight", .n_features = HYLO_FEATURES_FLIGHT, .gamma = 1.0,
		.rho = -2.302585092994046, .feature_offset = zeros, .feature_scale = ones,
		.label_scale = 1, .label_log = 1, .speed_min_mps = 0, .speed_max_mps = 8.0,
		.state_bounded = 7u << 3,
		.state_min = { 0, 0, 0, -8, -8, 0 },
		.state_max = { 0, 0, 0, 8, 8, 0 },
	};
	tu_map chasm;
	hylo_goal g;

	(void)state;
	robots[1].modes[1].model = &flight;
	init_planner(planner);
	tu_chasm(&chasm);
	set_scene(planner, &chasm);
	g = tu_goal_chasm();
	g.start_mode = HYLO_MODE_FLIGHT;   /* above the chasm, descending at 2.7 m/s */
	g.start[0] = 30;
	g.start[2] = 5;
	g.start[5] = -2.7;
	expect(HYLO_E_BAD_VALUE, hylo_planner_plan(planner, &g, plan), plan);
	assert_non_null(strstr(plan->reason.text,
			       "start vz = -2.7 m/s is outside the flight model's training range [0, 0] m/s"));
	g = tu_goal_chasm();
	g.goal_mode = HYLO_MODE_FLIGHT;
	g.goal[0] = 30;
	g.goal[2] = 5;
	g.goal[3] = 1;
	g.goal[5] = 0.5;   /* |v| = 1.1 m/s: the speed is trained, its direction is not */
	expect(HYLO_E_BAD_VALUE, hylo_planner_plan(planner, &g, plan), plan);
	assert_non_null(strstr(plan->reason.text, "goal vz = 0.5 m/s is outside"));
	g.goal[5] = 0;
	plan_ok(planner, &g, plan);
	assert_true(plan->n_edges_evaluated > 0);
	assert_true(plan->n_untrained == 0);
	/* A region that leaves out the air speed 4 of the grid (the speed
	 * range alone admits it): the search's edges there are counted. */
	flight.state_min[3] = flight.state_min[4] = -1;
	flight.state_max[3] = flight.state_max[4] = 1;
	init_planner(planner);
	set_scene(planner, &chasm);
	plan_ok(planner, &g, plan);
	assert_true(plan->n_untrained > 0);
	assert_true(plan->n_untrained <= plan->n_edges_evaluated);
	robots[1].modes[1].model = NULL;
	init_planner(planner);
	tu_map_free(&chasm);
}

/* After any bad request the planner still answers a good one correctly. */
static void still_serves(tu_map *m, const hylo_goal *g, double want)
{
	set_scene(planner, m);
	plan_ok(planner, g, plan);
	assert_true(plan->total_cost == want);
}

static void test_bad_input(void **state)
{
	tu_map river, empty;
	hylo_goal good = tu_goal_river(), g;
	hylo_map_view v;
	hylo_real many[HYLO_MAX_GRID];
	double want;
	uint32_t k;

	(void)state;
	tu_river(&river);
	assert_int_equal(hylo_planner_init(NULL, 0, NULL), HYLO_E_NULL);
	assert_int_equal(hylo_planner_set_map(planner, NULL), HYLO_E_NULL);
	assert_int_equal(hylo_planner_plan(planner, NULL, plan), HYLO_E_NULL);
	assert_int_equal(hylo_planner_plan(planner, &good, NULL), HYLO_E_NULL);

	/* Goal before any map. */
	init_planner(planner);
	expect(HYLO_E_NO_MAP, hylo_planner_plan(planner, &good, plan), plan);

	set_scene(planner, &river);
	plan_ok(planner, &good, plan);
	want = plan->total_cost;

	g = good;
	g.start[0] = NAN;
	expect(HYLO_E_BAD_VALUE, hylo_planner_plan(planner, &g, plan), plan);
	g = good;
	g.goal[1] = INFINITY;
	expect(HYLO_E_BAD_VALUE, hylo_planner_plan(planner, &g, plan), plan);
	g = good;
	g.start[0] = 3.5;   /* inside the obstacle block */
	g.start[1] = 8;
	expect(HYLO_E_OUTSIDE_DOMAIN, hylo_planner_plan(planner, &g, plan), plan);
	g = good;
	g.goal[0] = 31;     /* off the map */
	expect(HYLO_E_OUTSIDE_DOMAIN, hylo_planner_plan(planner, &g, plan), plan);
	g = good;
	g.start[0] = 15;    /* in the river, but said to be on the ground */
	expect(HYLO_E_WRONG_MODE, hylo_planner_plan(planner, &g, plan), plan);
	assert_non_null(strstr(plan->reason.text, "marine"));
	g = good;
	g.start_mode = HYLO_MODE_FLIGHT;   /* not a mode of ambot */
	expect(HYLO_E_WRONG_MODE, hylo_planner_plan(planner, &g, plan), plan);
	g = good;
	g.goal_mode = 42;
	expect(HYLO_E_WRONG_MODE, hylo_planner_plan(planner, &g, plan), plan);
	g = good;
	g.sampling.spacing = -1;
	expect(HYLO_E_BAD_VALUE, hylo_planner_plan(planner, &g, plan), plan);
	g = good;
	g.sampling.connect_radius = NAN;
	expect(HYLO_E_BAD_VALUE, hylo_planner_plan(planner, &g, plan), plan);
	g = good;
	g.algorithm = 7;
	expect(HYLO_E_BAD_VALUE, hylo_planner_plan(planner, &g, plan), plan);
	g = good;
	g.time_budget_ms = 5;   /* this planner has no clock */
	expect(HYLO_E_BAD_VALUE, hylo_planner_plan(planner, &g, plan), plan);
	g = good;
	g.map_id = 12345;       /* a map that is not the current one */
	expect(HYLO_E_MAP_MISMATCH, hylo_planner_plan(planner, &g, plan), plan);

	/* Grids: exactly HYLO_MAX_GRID entries work, one more does not. */
	for (k = 0; k < HYLO_MAX_GRID; k++)
		many[k] = 0.05 * k;
	g = good;
	tu_grid(g.sampling.speeds, &g.sampling.n_speeds, many, HYLO_MAX_GRID);
	g.sampling.n_speeds = HYLO_MAX_GRID + 1;
	g.sampling.n_headings = 1;
	expect(HYLO_E_CAP_GRID, hylo_planner_plan(planner, &g, plan), plan);
	g.sampling.n_speeds = HYLO_MAX_GRID;
	plan_ok(planner, &g, plan);
	/* Combinations: speeds x headings past HYLO_MAX_COMBOS. */
	g = good;
	tu_grid(g.sampling.speeds, &g.sampling.n_speeds, many, HYLO_MAX_GRID);
	tu_grid(g.sampling.headings, &g.sampling.n_headings, many,
		HYLO_MAX_COMBOS / HYLO_MAX_GRID + 1);
	expect(HYLO_E_CAP_COMBOS, hylo_planner_plan(planner, &g, plan), plan);

	/* The expansion budget runs out: a valid request; the greedy walk's
	 * plan comes back, not proven optimal. */
	g = good;
	g.max_expansions = 3;
	assert_int_equal(hylo_planner_plan(planner, &g, plan), HYLO_OK);
	assert_int_equal(plan->outcome, HYLO_FOUND_UNPROVEN);
	assert_int_equal(plan->n_expansions, 3);
	assert_true(plan->n_waypoints >= 2);
	/* Dijkstra has no walk: no plan at all. */
	g.algorithm = HYLO_DIJKSTRA;
	assert_int_equal(hylo_planner_plan(planner, &g, plan), HYLO_OK);
	assert_int_equal(plan->outcome, HYLO_BUDGET_EXHAUSTED);
	assert_int_equal(plan->n_waypoints, 0);
	still_serves(&river, &good, want);

	/* Unknown robot, inconsistent map, map without any usable cell. */
	v = tu_view(&river);
	v.robot = "submarine";
	assert_int_equal(hylo_planner_set_map(planner, &v), HYLO_E_UNKNOWN_ROBOT);
	assert_non_null(strstr(hylo_planner_reason(planner), "submarine"));
	/* Goals on a refused map say why it was refused. */
	expect(HYLO_E_UNKNOWN_ROBOT, hylo_planner_plan(planner, &good, plan), plan);
	assert_non_null(strstr(plan->reason.text, "map 1 was refused"));
	assert_non_null(strstr(plan->reason.text, "submarine"));
	v = tu_view(&river);
	v.n_cells = 5;
	assert_int_equal(hylo_planner_set_map(planner, &v), HYLO_E_BAD_MAP);
	tu_map_alloc(&empty, "ambot", 10, 10, 1.0, 0, 0);   /* all obstacle */
	v = tu_view(&empty);
	assert_int_equal(hylo_planner_set_map(planner, &v), HYLO_E_EMPTY_DOMAIN);
	expect(HYLO_E_EMPTY_DOMAIN, hylo_planner_plan(planner, &good, plan), plan);
	still_serves(&river, &good, want);

	/* A known robot without a cost model. */
	river.robot = "ghost";
	set_scene(planner, &river);
	expect(HYLO_E_NO_MODEL, hylo_planner_plan(planner, &good, plan), plan);
	assert_non_null(strstr(plan->reason.text, "ghost"));

	/* Unreachable: a ground-only rover cannot cross the river. */
	river.robot = "rover";
	set_scene(planner, &river);
	assert_int_equal(hylo_planner_plan(planner, &good, plan), HYLO_OK);
	assert_int_equal(plan->outcome, HYLO_NO_PATH);
	assert_int_equal(plan->n_waypoints, 0);
	assert_non_null(strstr(plan->reason.text, "no path"));
	river.robot = "ambot";
	still_serves(&river, &good, want);
	tu_map_free(&empty);
	tu_map_free(&river);
}

static void test_msg_status(void **state)
{
	(void)state;
	assert_int_equal(hylo_msg_plan_status(HYLO_OK, HYLO_FOUND), HYLO_PLAN_T_STATUS_OK);
	assert_int_equal(hylo_msg_plan_status(HYLO_OK, HYLO_NO_PATH), HYLO_PLAN_T_STATUS_NO_PATH);
	assert_int_equal(hylo_msg_plan_status(HYLO_OK, HYLO_BUDGET_EXHAUSTED),
			 HYLO_PLAN_T_STATUS_BUDGET_EXHAUSTED);
	assert_int_equal(hylo_msg_plan_status(HYLO_E_NO_MAP, HYLO_NO_PATH), HYLO_PLAN_T_STATUS_NO_MAP);
	assert_int_equal(hylo_msg_plan_status(HYLO_E_CAP_NODES, HYLO_NO_PATH),
			 HYLO_PLAN_T_STATUS_OVER_CAPACITY);
	assert_int_equal(hylo_msg_plan_status(HYLO_E_MAP_MISMATCH, HYLO_NO_PATH),
			 HYLO_PLAN_T_STATUS_MAP_REPLACED);
	assert_int_equal(hylo_msg_plan_status(HYLO_E_OUTSIDE_DOMAIN, HYLO_NO_PATH),
			 HYLO_PLAN_T_STATUS_BAD_REQUEST);
}

static int setup(void **state)
{
	(void)state;
	planner = malloc(TU_PLANNER_BYTES);
	planner2 = malloc(TU_PLANNER_BYTES);
	plan = malloc(sizeof *plan);
	plan2 = malloc(sizeof *plan2);
	if (!planner || !planner2 || !plan || !plan2)
		return -1;
	tu_robots(robots, &costs);
	init_planner(planner);
	return 0;
}

static int teardown(void **state)
{
	(void)state;
	free(planner);
	free(planner2);
	free(plan);
	free(plan2);
	return 0;
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_river_plan_shape),
		cmocka_unit_test(test_chasm_plan_shape),
		cmocka_unit_test(test_optimal_river),
		cmocka_unit_test(test_optimal_chasm),
		cmocka_unit_test(test_optimal_di),
		cmocka_unit_test(test_roadmap_valid),
		cmocka_unit_test(test_roadmap_reuse),
		cmocka_unit_test(test_determinism),
		cmocka_unit_test(test_negative_costs_clamped),
		cmocka_unit_test(test_feasibility_classifier),
		cmocka_unit_test(test_speed_range),
		cmocka_unit_test(test_trained_region),
		cmocka_unit_test(test_bad_input),
		cmocka_unit_test(test_msg_status),
	};

	return cmocka_run_group_tests_name("planner", tests, setup, teardown);
}
