/*
 * The planner with the committed cost models (onboard/models/) on small
 * generated scenes of every robot:
 *  - optimality: the plan costs what an exhaustive search over every edge
 *    of the same graph, with the same edge costs, finds (1e-9 relative), for
 *    several seeded start and goal pairs; with a suboptimality w > 1 the
 *    plan costs at most w times that;
 *  - anytime: a budget too small for the proof returns a complete plan whose
 *    every step is an edge of the graph, with the not-proven outcome and a
 *    lower bound below its cost; a time budget of 0 means no limit;
 *  - sizing: a workspace of hylo_planner_size() bytes takes the models; one
 *    byte less is refused with a reason naming the largest model.
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

#include "ambot_ground.h"
#include "ambot_marine.h"
#include "di_di_neg.h"
#include "di_di_pos.h"
#include "drivocopter_flight.h"
#include "drivocopter_ground.h"
#include "onboard/testutil_planner.h"

#define N_ROBOTS 3
#define PAIRS 4

static hylo_robot robots[N_ROBOTS];
static hylo_planner *planner;
static size_t planner_bytes;
static hylo_plan *plan;
static double fake_ms;

/* A clock that advances 1 ms per reading: budgets run out deterministically. */
static double fake_clock(void *ctx)
{
	(void)ctx;
	fake_ms += 1.0;
	return fake_ms;
}

static hylo_mode_model model_mode(hylo_mode mode, const hylo_svr_model *m, const hylo_svr_model *f)
{
	hylo_mode_model mm;

	memset(&mm, 0, sizeof mm);
	mm.mode = mode;
	mm.model = m;
	mm.feasibility = f;
	return mm;
}

static void make_robots(void)
{
	memset(robots, 0, sizeof robots);
	robots[0].name = "ambot";
	robots[0].n_modes = 2;
	robots[0].modes[0] = model_mode(HYLO_MODE_GROUND, &hylo_model_ambot_ground,
					&hylo_model_ambot_ground_feasibility);
	robots[0].modes[1] = model_mode(HYLO_MODE_MARINE, &hylo_model_ambot_marine,
					&hylo_model_ambot_marine_feasibility);
	robots[1].name = "drivocopter";
	robots[1].n_modes = 2;
	robots[1].modes[0] = model_mode(HYLO_MODE_GROUND, &hylo_model_drivocopter_ground,
					&hylo_model_drivocopter_ground_feasibility);
	robots[1].modes[1] = model_mode(HYLO_MODE_FLIGHT, &hylo_model_drivocopter_flight,
					&hylo_model_drivocopter_flight_feasibility);
	robots[1].switch_cost[0] = HYLO_MODEL_DRIVOCOPTER_FLIGHT_TAKEOFF_J;
	robots[1].switch_cost[1] = HYLO_MODEL_DRIVOCOPTER_FLIGHT_LANDING_J;
	robots[2].name = "di";
	robots[2].n_modes = 2;
	robots[2].modes[0] = model_mode(HYLO_MODE_DI_NEG, &hylo_model_di_di_neg, &hylo_model_di_di_neg_feasibility);
	robots[2].modes[1] = model_mode(HYLO_MODE_DI_POS, &hylo_model_di_di_pos, &hylo_model_di_di_pos_feasibility);
}

static hylo_planner_config config(hylo_clock_fn clock)
{
	hylo_planner_config cfg;

	memset(&cfg, 0, sizeof cfg);
	cfg.robots = robots;
	cfg.n_robots = N_ROBOTS;
	cfg.clock = clock;
	return cfg;
}

/* ---- scenes ------------------------------------------------------------ */

/* 14 m x 8 m of ground with water at x in [5, 9). */
static void small_river(tu_map *m)
{
	int32_t ix, iy;

	tu_map_alloc(m, "ambot", 28, 16, 0.5, 0, 0);
	for (iy = 0; iy < m->ny; iy++)
		for (ix = 0; ix < m->nx; ix++)
			m->terrain[iy * m->nx + ix] = ix >= 10 && ix < 18 ? HYLO_TERRAIN_WATER : HYLO_TERRAIN_GROUND;
}

/* Two 3 m platforms (x < 5 and x >= 13) around a floor, 4 m wide. */
static void small_chasm(tu_map *m)
{
	int32_t ix, iy;

	tu_map_alloc(m, "drivocopter", 18, 4, 1.0, 0, 0);
	m->ceiling = 8;
	m->max_step = 0.2;
	for (iy = 0; iy < m->ny; iy++)
		for (ix = 0; ix < m->nx; ix++) {
			m->terrain[iy * m->nx + ix] = HYLO_TERRAIN_GROUND;
			m->height[iy * m->nx + ix] = ix < 5 || ix >= 13 ? 3.0f : 0.0f;
		}
}

static const hylo_real speeds[] = { 0.0, 0.5, 1.0 };
static const hylo_real fast[] = { 0.0, 1.0 };
static const hylo_real headings4[] = { 0, 1.5707963267948966, 3.141592653589793, -1.5707963267948966 };
static const hylo_real headings2[] = { 0, 3.141592653589793 };
static const hylo_real air[] = { 0.0, 4.0 };

static hylo_goal river_goal(void)
{
	hylo_goal g;

	memset(&g, 0, sizeof g);
	g.algorithm = HYLO_ASTAR;
	g.start_mode = g.goal_mode = HYLO_MODE_GROUND;
	g.start[0] = 1;
	g.start[1] = 4;
	g.goal[0] = 13;
	g.goal[1] = 5;
	g.seed = 3;
	g.spacing = 2.0;
	g.guard_spacing = 2.0;
	g.connect_radius = 3.5;
	g.speeds = speeds;
	g.n_speeds = 3;
	g.headings = headings4;
	g.n_headings = 4;
	return g;
}

static hylo_goal chasm_goal(void)
{
	hylo_goal g;

	memset(&g, 0, sizeof g);
	g.algorithm = HYLO_ASTAR;
	g.start_mode = g.goal_mode = HYLO_MODE_GROUND;
	g.start[0] = 2;
	g.start[1] = 2;
	g.goal[0] = 16;
	g.goal[1] = 2;
	g.seed = 5;
	g.spacing = 2.0;
	g.air_spacing = 3.0;
	g.guard_spacing = 2.0;
	g.connect_radius = 3.0;
	g.air_connect_radius = 6.0;
	g.speeds = fast;
	g.n_speeds = 2;
	g.headings = headings2;
	g.n_headings = 2;
	g.air_speeds = air;
	g.n_air_speeds = 2;
	return g;
}

static hylo_goal di_goal(void)
{
	hylo_goal g;

	memset(&g, 0, sizeof g);
	g.algorithm = HYLO_ASTAR;
	g.start_mode = HYLO_MODE_DI_POS;
	g.goal_mode = HYLO_MODE_DI_NEG;
	g.start[0] = 0.8;
	g.start[1] = 0.2;
	g.goal[0] = -0.8;
	g.seed = 1;
	g.spacing = 0.15;
	g.guard_spacing = 0.15;
	g.connect_radius = 0.4;
	return g;
}

/* ---- the exhaustive search ---------------------------------------------- */

/* Dijkstra over every edge of the planner's last graph (O(V^2), each
 * successor's cost from hylo_planner_edge_costs): the optimum. */
static double exhaustive(hylo_planner *pl)
{
	const hylo_roadmap *rm = hylo_planner_roadmap(pl);
	uint32_t n = rm->n_nodes + 2, start = rm->n_nodes, goal = rm->n_nodes + 1, u, k, m;
	double *d = malloc(n * sizeof *d), *costs = malloc(HYLO_MAX_SUCCESSORS * sizeof *costs), best;
	uint32_t *heads = malloc(HYLO_MAX_SUCCESSORS * sizeof *heads);
	char *done = calloc(n, 1);

	assert_non_null(d);
	assert_non_null(costs);
	assert_non_null(heads);
	assert_non_null(done);
	for (u = 0; u < n; u++)
		d[u] = INFINITY;
	d[start] = 0;
	for (;;) {
		best = INFINITY;
		u = n;
		for (k = 0; k < n; k++)
			if (!done[k] && d[k] < best) {
				best = d[k];
				u = k;
			}
		if (u == n || u == goal)
			break;
		done[u] = 1;
		assert_int_equal(hylo_planner_successors(pl, u, heads, &m), HYLO_OK);
		assert_int_equal(hylo_planner_edge_costs(pl, u, heads, m, costs), HYLO_OK);
		for (k = 0; k < m; k++)
			if (d[u] + costs[k] < d[heads[k]])
				d[heads[k]] = d[u] + costs[k];
	}
	best = d[goal];
	free(d);
	free(costs);
	free(heads);
	free(done);
	return best;
}

/* Every step of the plan is an edge of the graph, and the costs add up. */
static void assert_walkable(hylo_planner *pl, const hylo_plan *p, const hylo_goal *g)
{
	const hylo_roadmap *rm = hylo_planner_roadmap(pl);
	uint32_t *heads = malloc(HYLO_MAX_SUCCESSORS * sizeof *heads), n, k, w, u = rm->n_nodes;
	double c, total = 0;

	assert_non_null(heads);
	assert_true(p->n_waypoints >= 2);
	assert_memory_equal(p->state[0], g->start, sizeof p->state[0]);
	assert_memory_equal(p->state[p->n_waypoints - 1], g->goal, sizeof p->state[0]);
	for (w = 1; w < p->n_waypoints; w++) {
		uint32_t v = HYLO_NO_NODE;

		assert_int_equal(hylo_planner_successors(pl, u, heads, &n), HYLO_OK);
		for (k = 0; k < n && v == HYLO_NO_NODE; k++) {
			hylo_real xs[HYLO_XS_DIM];
			uint32_t j = rm->node_pos[heads[k]];

			if (heads[k] == rm->n_nodes + 1)
				memcpy(xs, g->goal, sizeof xs);
			else
				hylo_roadmap_state(rm, j, heads[k] - rm->pos[j].node_base, xs);
			if (rm->pos[j].mode == p->mode[w] && memcmp(xs, p->state[w], sizeof xs) == 0)
				v = heads[k];
		}
		assert_true(v != HYLO_NO_NODE);
		assert_int_equal(hylo_planner_edge_costs(pl, u, &v, 1, &c), HYLO_OK);
		assert_true(isfinite(c));
		total += c;
		assert_true(fabs(total - p->cost[w]) <= 1e-9 * (1 + total));
		u = v;
	}
	assert_int_equal(u, rm->n_nodes + 1);
	free(heads);
}

static void set_map(const tu_map *m)
{
	hylo_map_view v = tu_view(m);

	assert_int_equal(hylo_planner_set_map(planner, &v), HYLO_OK);
}

/* A start or goal moved to a random position of its mode, until the
 * planner accepts it (seeded). */
static uint64_t rng = 88172645463325252ULL;

static double unit(void)
{
	rng ^= rng << 13;
	rng ^= rng >> 7;
	rng ^= rng << 17;
	return (double)(rng >> 11) * 0x1.0p-53;
}

static hylo_goal random_pair(const hylo_goal *base, const tu_map *m)
{
	int tries;

	for (tries = 0; tries < 200; tries++) {
		hylo_goal g = *base;
		double w = m->nx * m->res, h = m->ny * m->res;

		if (base->start_mode == HYLO_MODE_DI_POS) {
			g.start[0] = 0.05 + 0.9 * unit();
			g.start[1] = -0.8 + 1.6 * unit();
			g.goal[0] = -0.95 + 0.9 * unit();
			g.goal[1] = -0.8 + 1.6 * unit();
		} else {
			g.start[0] = m->ox + w * (0.05 + 0.2 * unit());
			g.start[1] = m->oy + h * (0.1 + 0.8 * unit());
			g.goal[0] = m->ox + w * (0.75 + 0.2 * unit());
			g.goal[1] = m->oy + h * (0.1 + 0.8 * unit());
			g.start[3] = base->headings[(size_t)(unit() * base->n_headings)];
			g.goal[3] = base->headings[(size_t)(unit() * base->n_headings)];
		}
		hylo_planner_plan(planner, &g, plan);
		if (plan->status == HYLO_OK && plan->outcome == HYLO_FOUND)
			return g;
	}
	fail_msg("no valid start and goal found");
	return *base;
}

static void check_optimal(const tu_map *m, hylo_goal base)
{
	int i;

	set_map(m);
	for (i = 0; i < PAIRS; i++) {
		hylo_goal g = i == 0 ? base : random_pair(&base, m);
		double opt, cost;

		hylo_planner_plan(planner, &g, plan);
		assert_int_equal(plan->status, HYLO_OK);
		assert_int_equal(plan->outcome, HYLO_FOUND);
		assert_true(plan->suboptimality == 1);
		cost = plan->total_cost;
		assert_walkable(planner, plan, &g);
		opt = exhaustive(planner);
		if (!(fabs(cost - opt) <= 1e-9 * opt))
			fail_msg("%s pair %d: plan %.12g, exhaustive search %.12g", m->robot, i, cost, opt);
		/* Bounded suboptimality: within w of the optimum, and said so. */
		g.suboptimality = 1.5;
		hylo_planner_plan(planner, &g, plan);
		assert_int_equal(plan->outcome, HYLO_FOUND);
		assert_true(plan->suboptimality == 1.5);
		assert_true(plan->total_cost <= 1.5 * opt * (1 + 1e-12));
		assert_true(plan->total_cost >= opt * (1 - 1e-12));
		assert_walkable(planner, plan, &g);
	}
}

static void test_optimal_every_robot(void **state)
{
	tu_map m;

	(void)state;
	small_river(&m);
	check_optimal(&m, river_goal());
	tu_map_free(&m);
	small_chasm(&m);
	check_optimal(&m, chasm_goal());
	tu_map_free(&m);
	tu_di(&m);
	check_optimal(&m, di_goal());
	tu_map_free(&m);
}

/* ---- anytime ------------------------------------------------------------ */

static void test_anytime(void **state)
{
	hylo_planner_config cfg = config(fake_clock);
	hylo_goal g = river_goal();
	double opt;
	int budget, unproven = 0, found = 0;
	tu_map m;

	(void)state;
	small_river(&m);
	assert_int_equal(hylo_planner_init(planner, planner_bytes, &cfg), HYLO_OK);
	set_map(&m);
	g.time_budget_ms = 0;   /* no limit */
	hylo_planner_plan(planner, &g, plan);
	assert_int_equal(plan->outcome, HYLO_FOUND);
	opt = plan->total_cost;
	/* Time budgets from 1 ms up (the fake clock ticks 1 ms per reading):
	 * each gives the optimum, the best plan found so far (not proven
	 * optimal, with a lower bound of the optimum), or, spent before any plan
	 * was found, none; the not-proven case occurs. */
	for (budget = 1; budget <= 400 && !(unproven && found); budget++) {
		g.time_budget_ms = budget;
		hylo_planner_plan(planner, &g, plan);
		assert_int_equal(plan->status, HYLO_OK);
		if (plan->outcome == HYLO_BUDGET_EXHAUSTED) {
			assert_int_equal(plan->n_waypoints, 0);
			continue;
		}
		assert_walkable(planner, plan, &g);
		if (plan->outcome == HYLO_FOUND) {
			assert_true(fabs(plan->total_cost - opt) <= 1e-9 * opt);
			found = 1;
			continue;
		}
		assert_int_equal(plan->outcome, HYLO_FOUND_UNPROVEN);
		assert_true(plan->total_cost >= opt * (1 - 1e-12));
		assert_true(plan->lower_bound <= opt * (1 + 1e-12));
		assert_non_null(strstr(plan->reason.text, "not proven optimal"));
		unproven = 1;
	}
	assert_true(unproven);
	assert_true(found);
	/* An expansion budget of one: the greedy walk's plan. */
	g.time_budget_ms = 0;
	g.max_expansions = 1;
	hylo_planner_plan(planner, &g, plan);
	assert_int_equal(plan->outcome, HYLO_FOUND_UNPROVEN);
	assert_walkable(planner, plan, &g);
	/* Dijkstra has no walk: an expansion budget of one gives no plan. */
	g.algorithm = HYLO_DIJKSTRA;
	hylo_planner_plan(planner, &g, plan);
	assert_int_equal(plan->outcome, HYLO_BUDGET_EXHAUSTED);
	assert_int_equal(plan->n_waypoints, 0);
	tu_map_free(&m);
	cfg = config(NULL);
	assert_int_equal(hylo_planner_init(planner, planner_bytes, &cfg), HYLO_OK);
}

/* ---- sizing ------------------------------------------------------------- */

static void test_sizing(void **state)
{
	hylo_planner_config cfg = config(NULL);
	size_t n = hylo_planner_size(&cfg);

	(void)state;
	assert_true(n > sizeof(hylo_planner));
	assert_int_equal(hylo_planner_init(planner, n, &cfg), HYLO_OK);
	assert_int_equal(hylo_planner_init(planner, n - 1, &cfg), HYLO_E_CAP_SV);
	assert_non_null(strstr(hylo_planner_reason(planner), "drivocopter_flight"));
	/* Ambot alone needs less than both robots. */
	cfg.n_robots = 1;
	assert_true(hylo_planner_size(&cfg) < n);
	assert_int_equal(hylo_planner_init(planner, hylo_planner_size(&cfg), &cfg), HYLO_OK);
	cfg = config(NULL);
	assert_int_equal(hylo_planner_init(planner, planner_bytes, &cfg), HYLO_OK);
}

static int setup(void **state)
{
	hylo_planner_config cfg;

	(void)state;
	make_robots();
	cfg = config(NULL);
	planner_bytes = hylo_planner_size(&cfg);
	planner = malloc(planner_bytes);
	plan = malloc(sizeof *plan);
	if (!planner || !plan || hylo_planner_init(planner, planner_bytes, &cfg) != HYLO_OK)
		return -1;
	return 0;
}

static int teardown(void **state)
{
	(void)state;
	free(planner);
	free(plan);
	return 0;
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_optimal_every_robot),
		cmocka_unit_test(test_anytime),
		cmocka_unit_test(test_sizing),
	};

	return cmocka_run_group_tests_name("planner_models", tests, setup, teardown);
}
