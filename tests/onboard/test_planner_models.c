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
 *  - alternatives: with goal.alternatives = K the plan lists the best paths
 *    of up to K distinct mode-switch counts, cheapest first, each costing
 *    what an exhaustive search over (node, switches so far) finds for its
 *    count, each walkable, the first equal to the one-plan answer's cost;
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

#include "hylo/envelope.h"
#include "onboard/testutil_models.h"
#include "src/planner_internal.h"

#define PAIRS 4

static hylo_robot robots[TM_N_ROBOTS];
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

static hylo_planner_config config(hylo_clock_fn clock)
{
	hylo_planner_config cfg;

	cfg = tu_config(robots, TM_N_ROBOTS);
	cfg.clock = clock;
	return cfg;
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
			g.start[3] = base->sampling.headings[(size_t)(unit() * base->sampling.n_headings)];
			g.goal[3] = base->sampling.headings[(size_t)(unit() * base->sampling.n_headings)];
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
	tm_small_river(&m);
	check_optimal(&m, tm_river_goal());
	tu_map_free(&m);
	tm_small_chasm(&m);
	check_optimal(&m, tm_chasm_goal());
	tu_map_free(&m);
	tu_di(&m);
	check_optimal(&m, tm_di_goal());
	tu_map_free(&m);
}

/* ---- edge bounds --------------------------------------------------------- */

/* The planner's per-pair bounds equal the floor raised to
 * hylo_envelope_of_edge, bit for bit, on every edge of the graphs: the
 * heuristic (also from its cache of turn cells), the lazy keys and the
 * costs' clamp all use the same numbers. */
static void check_bounds(const tu_map *m, hylo_goal g)
{
	const hylo_roadmap *rm;
	uint32_t *heads = malloc(HYLO_MAX_SUCCESSORS * sizeof *heads), u, n, k, checked = 0, cached = 0;

	assert_non_null(heads);
	set_map(m);
	hylo_planner_plan(planner, &g, plan);
	assert_int_equal(plan->outcome, HYLO_FOUND);
	rm = hylo_planner_roadmap(planner);
	for (u = 0; u < rm->n_nodes + 1; u++) {
		uint32_t i = rm->node_pos[u];
		hylo_real tail[HYLO_XS_DIM];

		hylo_planner_node_state(planner, i, u - rm->pos[i].node_base, tail);
		assert_int_equal(hylo_planner_successors(planner, u, heads, &n), HYLO_OK);
		for (k = 0; k < n; k++) {
			uint32_t j = rm->node_pos[heads[k]];
			const hylo_mode_model *mm = hylo_planner_mode_model(planner, (hylo_mode)rm->pos[i].mode);
			hylo_real head[HYLO_XS_DIM], want, got, e;
			hylo_pair_bound pb;

			if (rm->pos[j].mode != rm->pos[i].mode)
				continue;   /* a switch edge */
			hylo_planner_node_state(planner, j, heads[k] - rm->pos[j].node_base, head);
			hylo_planner_pair_bound(planner, i, j, &pb);
			got = hylo_planner_bound(&pb, u - rm->pos[i].node_base, tail,
						 heads[k] - rm->pos[j].node_base, head);
			want = mm->model->cost_floor_j + mm->model->cost_floor_per_m * hylo_roadmap_distance(rm->pos[i].p, rm->pos[j].p);
			e = hylo_envelope_of_edge(mm->model, (hylo_mode)rm->pos[i].mode, tail, head);
			if (e > want)
				want = e;
			assert_memory_equal(&got, &want, sizeof got);
			checked++;
			if (i < rm->n_positions && j < rm->n_positions) {
				/* The heuristic's path: the pair's turn cells cached
				 * (filled by the first call, read by the second). */
				hylo_real lb[HYLO_MAX_COMBOS];
				uint32_t a = rm->pos[j].adj_begin, pass;

				while (rm->adjacency[a] != i)
					a++;
				assert_true(a < rm->pos[j].adj_end);
				for (pass = 0; pass < 2; pass++) {
					hylo_planner_pair_bound_into(planner, i, j, a, &pb);
					hylo_planner_bounds_into(&pb, i, heads[k] - rm->pos[j].node_base, head, lb);
					assert_memory_equal(&lb[u - rm->pos[i].node_base], &want, sizeof want);
				}
				assert_true(pb.turn_cells != NULL || !pb.by_turn);
				cached += pb.turn_cells != NULL;
			}
		}
	}
	assert_true(checked > 1000);
	assert_true(cached > 1000);
	free(heads);
}

static void test_bounds_match_envelope(void **state)
{
	tu_map m;

	(void)state;
	tm_small_river(&m);
	check_bounds(&m, tm_river_goal());
	tu_map_free(&m);
	tm_small_chasm(&m);
	check_bounds(&m, tm_chasm_goal());
	tu_map_free(&m);
}

/* ---- anytime ------------------------------------------------------------ */

static void test_anytime(void **state)
{
	hylo_planner_config cfg = config(fake_clock);
	hylo_goal g = tm_river_goal();
	double opt;
	int budget, unproven = 0, found = 0;
	tu_map m;

	(void)state;
	tm_small_river(&m);
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

/* Alternatives under a time budget: the budget also bounds the layered
 * heuristic's searches (one that runs out leaves the heuristic as it was).
 * Every budget gives a prefix of the unlimited run's alternatives, each at
 * its exact cost, or none; some budgets cut the list short. */
static void test_anytime_alternatives(void **state)
{
	hylo_planner_config cfg = config(fake_clock);
	hylo_goal g = tm_river_goal();
	hylo_real full[HYLO_MAX_ALTERNATIVES];
	uint32_t n_full, k;
	int budget, shorter = 0, complete = 0;
	tu_map m;

	(void)state;
	tm_small_river(&m);
	assert_int_equal(hylo_planner_init(planner, planner_bytes, &cfg), HYLO_OK);
	set_map(&m);
	g.alternatives = 3;
	g.alternatives_within = 1.5;
	g.time_budget_ms = 0;
	hylo_planner_plan(planner, &g, plan);
	assert_int_equal(plan->outcome, HYLO_FOUND);
	n_full = plan->n_alternatives;
	assert_true(n_full >= 2);
	memcpy(full, plan->alternative_cost, sizeof full);
	for (budget = 1; budget <= 2000 && !(shorter && complete); budget += 3) {
		g.time_budget_ms = budget;
		hylo_planner_plan(planner, &g, plan);
		assert_int_equal(plan->status, HYLO_OK);
		if (plan->outcome != HYLO_FOUND)
			continue;
		assert_true(plan->n_alternatives >= 1 && plan->n_alternatives <= n_full);
		for (k = 0; k < plan->n_alternatives; k++)
			assert_true(fabs(plan->alternative_cost[k] - full[k]) <= 1e-9 * full[k]);
		shorter |= plan->n_alternatives < n_full;
		complete |= plan->n_alternatives == n_full;
	}
	assert_true(shorter);
	assert_true(complete);
	tu_map_free(&m);
	cfg = config(NULL);
	assert_int_equal(hylo_planner_init(planner, planner_bytes, &cfg), HYLO_OK);
}

/* ---- alternatives -------------------------------------------------------- */

/* The graph's edges, every cost computed once: heads and costs of node u
 * at [first[u], first[u + 1]). */
typedef struct {
	uint32_t n;
	size_t *first;
	uint32_t *head;
	double *cost;
} edge_list;

static edge_list all_edges(hylo_planner *pl)
{
	const hylo_roadmap *rm = hylo_planner_roadmap(pl);
	uint32_t *heads = malloc(HYLO_MAX_SUCCESSORS * sizeof *heads), u, m;
	double *costs = malloc(HYLO_MAX_SUCCESSORS * sizeof *costs);
	edge_list e;
	size_t cap = 1 << 16, used = 0;

	e.n = rm->n_nodes + 2;
	e.first = malloc((e.n + 1) * sizeof *e.first);
	e.head = malloc(cap * sizeof *e.head);
	e.cost = malloc(cap * sizeof *e.cost);
	assert_true(heads && costs && e.first && e.head && e.cost);
	for (u = 0; u < e.n; u++) {
		e.first[u] = used;
		assert_int_equal(hylo_planner_successors(pl, u, heads, &m), HYLO_OK);
		assert_int_equal(hylo_planner_edge_costs(pl, u, heads, m, costs), HYLO_OK);
		while (used + m > cap) {
			cap *= 2;
			e.head = realloc(e.head, cap * sizeof *e.head);
			e.cost = realloc(e.cost, cap * sizeof *e.cost);
			assert_true(e.head && e.cost);
		}
		memcpy(e.head + used, heads, m * sizeof *heads);
		memcpy(e.cost + used, costs, m * sizeof *costs);
		used += m;
	}
	e.first[e.n] = used;
	free(heads);
	free(costs);
	return e;
}

/* Exhaustive Dijkstra over (node, changes of travel mode so far, capped at
 * layers - 1; travel modes first, other, first, ...): best[l] is the least
 * cost of a path to the goal with l changes (l < layers - 1) or at least l
 * (the last). O((V L)^2): small graphs only. */
static void exhaustive_layers(hylo_planner *pl, const edge_list *e, uint32_t layers, uint8_t first,
			      uint8_t other, double *best)
{
	const hylo_roadmap *rm = hylo_planner_roadmap(pl);
	uint32_t n = e->n * layers, u, k, l;
	double *d = malloc(n * sizeof *d);
	char *done = calloc(n, 1);

	assert_true(d && done);
	for (u = 0; u < n; u++)
		d[u] = INFINITY;
	d[rm->n_nodes] = 0;
	for (;;) {
		double b = INFINITY;
		size_t a;

		u = n;
		for (k = 0; k < n; k++)
			if (!done[k] && d[k] < b) {
				b = d[k];
				u = k;
			}
		if (u == n)
			break;
		done[u] = 1;
		l = u / e->n;
		for (a = e->first[u % e->n]; a < e->first[u % e->n + 1]; a++) {
			uint32_t v = e->head[a], lv = l;

			uint8_t mu = rm->pos[rm->node_pos[u % e->n]].mode, travel = l % 2 ? other : first;

			/* A move in another mode than the layer's starts a stretch. */
			if (rm->pos[rm->node_pos[v]].mode == mu && mu != travel && lv + 1 < layers)
				lv++;
			if (isfinite(e->cost[a]) && d[u] + e->cost[a] < d[lv * e->n + v])
				d[lv * e->n + v] = d[u] + e->cost[a];
		}
	}
	for (l = 0; l < layers; l++)
		best[l] = d[l * e->n + rm->n_nodes + 1];
	free(d);
	free(done);
}

static uint8_t other_mode(int mode)
{
	const hylo_robot *r = planner->robot;

	return (uint8_t)(r->n_modes == 2 && (int)r->modes[0].mode == mode ? r->modes[1].mode : r->modes[0].mode);
}

/* Changes of mode between the stretches a plan travels. */
static uint32_t travel_changes(const hylo_plan *p)
{
	uint32_t n = 0, w;
	int last = -1;

	for (w = 1; w < p->n_waypoints; w++)
		if (p->mode[w] == p->mode[w - 1]) {
			n += last >= 0 && p->mode[w] != last;
			last = p->mode[w];
		}
	return n;
}

static void check_alternatives(const tu_map *m, hylo_goal g, uint32_t k_wanted, hylo_real within)
{
	hylo_plan *alt = malloc(sizeof *alt);
	double best[HYLO_MAX_SWITCH_LAYERS], one, last = 0;
	uint32_t k, l, layers, cheaper;
	edge_list e;

	assert_non_null(alt);
	set_map(m);
	hylo_planner_plan(planner, &g, plan);
	assert_int_equal(plan->outcome, HYLO_FOUND);
	assert_int_equal(plan->n_alternatives, 1);
	assert_int_equal(hylo_planner_alternative(planner, 1, alt), HYLO_E_BAD_VALUE);
	one = plan->total_cost;
	g.alternatives = k_wanted;
	g.alternatives_within = within;
	hylo_planner_plan(planner, &g, plan);
	assert_int_equal(plan->status, HYLO_OK);
	assert_int_equal(plan->outcome, HYLO_FOUND);
	assert_true(fabs(plan->total_cost - one) <= 1e-9 * one);
	layers = plan->max_switches + 1;
	assert_true(layers >= 2 && layers <= HYLO_MAX_SWITCH_LAYERS);
	e = all_edges(planner);
	exhaustive_layers(planner, &e, layers, (uint8_t)g.start_mode, other_mode(g.start_mode), best);
	assert_true(plan->n_alternatives >= 1);
	if (within == 0)
		within = HYLO_ALTERNATIVES_WITHIN;
	for (k = 0; k < plan->n_alternatives; k++) {
		uint32_t sw = plan->alternative_switches[k], cls = sw < layers - 1 ? sw : layers - 1;
		double c = plan->alternative_cost[k];

		assert_int_equal(hylo_planner_alternative(planner, k, alt), HYLO_OK);
		assert_walkable(planner, alt, &g);
		assert_true(alt->total_cost == c);
		assert_int_equal(travel_changes(alt), sw);
		if (!(fabs(c - best[cls]) <= 1e-9 * best[cls]))
			fail_msg("%s alternative %u (%u switches): %.12g, exhaustive %.12g", m->robot,
				 (unsigned)k, (unsigned)sw, c, best[cls]);
		assert_true(c >= last);
		assert_true(c <= within * plan->total_cost);
		last = c;
		for (l = 0; l < k; l++) {
			uint32_t s2 = plan->alternative_switches[l];

			assert_true((s2 < layers - 1 ? s2 : layers - 1) != cls);
		}
	}
	/* No class left out is cheaper than the last one listed. */
	for (l = 0, cheaper = 0; l < layers; l++)
		cheaper += best[l] < last * (1 - 1e-12);
	assert_true(cheaper < plan->n_alternatives);
	/* Fewer than asked: every class within reach is listed. */
	if (plan->n_alternatives < k_wanted)
		for (l = 0; l < layers; l++)
			if (isfinite(best[l]) && best[l] <= within * plan->total_cost)
				assert_true(best[l] <= last);
	free(e.first);
	free(e.head);
	free(e.cost);
	free(alt);
}

/* The window's edge: within just above the dearest class's cost over the
 * first, which must still be listed (the searches' pruning keeps paths up
 * to the window, rounding aside). */
static void check_window_edge(const tu_map *m, hylo_goal g)
{
	hylo_goal every = g;
	double first, dearest;

	set_map(m);
	every.alternatives = HYLO_MAX_ALTERNATIVES;
	every.alternatives_within = INFINITY;
	hylo_planner_plan(planner, &every, plan);
	assert_int_equal(plan->outcome, HYLO_FOUND);
	assert_true(plan->n_alternatives >= 2);
	first = plan->alternative_cost[0];
	dearest = plan->alternative_cost[plan->n_alternatives - 1];
	check_alternatives(m, g, HYLO_MAX_ALTERNATIVES, dearest / first * (1 + 1e-7));
	assert_true(plan->alternative_cost[plan->n_alternatives - 1] == dearest);
}

static void test_alternatives(void **state)
{
	tu_map m;

	(void)state;
	tm_small_chasm(&m);
	check_alternatives(&m, tm_chasm_goal(), 3, INFINITY);
	check_alternatives(&m, tm_chasm_goal(), 3, 0);
	tu_map_free(&m);
	tm_small_river(&m);
	check_alternatives(&m, tm_river_goal(), 3, INFINITY);
	check_alternatives(&m, tm_river_goal(), 4, 1.5);
	/* Every class (the goal copies of the top layers close first, and the
	 * layers above the highest open one are pruned). */
	check_alternatives(&m, tm_river_goal(), HYLO_MAX_ALTERNATIVES, INFINITY);
	tu_map_free(&m);
	tm_small_chasm(&m);
	check_alternatives(&m, tm_chasm_goal(), HYLO_MAX_ALTERNATIVES, INFINITY);
	tu_map_free(&m);
}

static void test_alternatives_window_edge(void **state)
{
	tu_map river, chasm;

	(void)state;
	tm_small_river(&river);
	check_window_edge(&river, tm_river_goal());
	tu_map_free(&river);
	tm_small_chasm(&chasm);
	check_window_edge(&chasm, tm_chasm_goal());
	tu_map_free(&chasm);
}

/* ---- half turns ---------------------------------------------------------- */

/* g with every heading of pi (grid, start, goal) written as pi_as. */
static hylo_goal pi_written_as(hylo_goal g, hylo_real pi_as)
{
	uint32_t k;

	for (k = 0; k < g.sampling.n_headings; k++)
		if (g.sampling.headings[k] == TU_PI)
			g.sampling.headings[k] = pi_as;
	if (g.start[3] == TU_PI)
		g.start[3] = pi_as;
	if (g.goal[3] == TU_PI)
		g.goal[3] = pi_as;
	return g;
}

/* A heading of pi costs the same however it is written (a grid's 3.141593
 * lies above pi, and the wrap would make a half turn to it from 0 a right
 * turn, from -3.141593 a left one): half turns turn towards the goal. */
static void check_half_turns(const tu_map *m, hylo_goal base)
{
	static const hylo_real written[2] = { 3.141593, -3.141593 };
	int i, k;

	set_map(m);
	for (i = 0; i < PAIRS; i++) {
		hylo_goal g = i == 0 ? base : random_pair(&base, m);
		double cost;

		hylo_planner_plan(planner, &g, plan);
		assert_int_equal(plan->outcome, HYLO_FOUND);
		cost = plan->total_cost;
		for (k = 0; k < 2; k++) {
			hylo_goal w = pi_written_as(g, written[k]);

			hylo_planner_plan(planner, &w, plan);
			assert_int_equal(plan->outcome, HYLO_FOUND);
			if (!(fabs(plan->total_cost - cost) <= 1e-6 * cost))
				fail_msg("%s pair %d, pi written as %.7f: %.12g, as pi: %.12g", m->robot, i,
					 written[k], plan->total_cost, cost);
		}
	}
}

static void test_half_turns(void **state)
{
	tu_map m;

	(void)state;
	tm_small_chasm(&m);
	check_half_turns(&m, tm_chasm_goal());
	tu_map_free(&m);
	tm_small_river(&m);
	check_half_turns(&m, tm_river_goal());
	tu_map_free(&m);
}

/* ---- sizing ------------------------------------------------------------- */

/* The committed model whose SVR cache is the largest: the one a short
 * workspace's reason names. */
static const char *largest_model_name(const hylo_planner_config *cfg)
{
	const char *name = NULL;
	size_t most = 0;
	uint32_t k, m;

	for (k = 0; k < cfg->n_robots; k++)
		for (m = 0; m < cfg->robots[k].n_modes; m++) {
			const hylo_svr_model *x = cfg->robots[k].modes[m].model;
			const size_t size = x ? hylo_svr_cache_size(x) : 0;

			if (size > most) {
				most = size;
				name = x->name;
			}
		}
	return name;
}

static void test_sizing(void **state)
{
	hylo_planner_config cfg = config(NULL);
	size_t n = hylo_planner_size(&cfg);
	const char *largest = largest_model_name(&cfg);
	uint32_t k;

	(void)state;
	assert_true(n > sizeof(hylo_planner));
	assert_int_equal(hylo_planner_init(planner, n, &cfg), HYLO_OK);
	assert_int_equal(hylo_planner_init(planner, n - 1, &cfg), HYLO_E_CAP_SV);
	assert_non_null(largest);
	assert_non_null(strstr(hylo_planner_reason(planner), largest));
	/* A robot without the largest model needs less than all of them. */
	for (k = 0; k < TM_N_ROBOTS; k++) {
		const char *own;

		cfg.robots = &robots[k];
		cfg.n_robots = 1;
		own = largest_model_name(&cfg);
		if (!own || strcmp(own, largest) != 0)
			break;
	}
	assert_true(k < TM_N_ROBOTS);
	assert_true(hylo_planner_size(&cfg) < n);
	assert_int_equal(hylo_planner_init(planner, hylo_planner_size(&cfg), &cfg), HYLO_OK);
	cfg = config(NULL);
	assert_int_equal(hylo_planner_init(planner, planner_bytes, &cfg), HYLO_OK);
}

static int setup(void **state)
{
	hylo_planner_config cfg;

	(void)state;
	tm_robots(robots);
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
		cmocka_unit_test(test_bounds_match_envelope),
		cmocka_unit_test(test_anytime),
		cmocka_unit_test(test_anytime_alternatives),
		cmocka_unit_test(test_alternatives),
		cmocka_unit_test(test_alternatives_window_edge),
		cmocka_unit_test(test_half_turns),
		cmocka_unit_test(test_sizing),
	};

	return cmocka_run_group_tests_name("planner_models", tests, setup, teardown);
}
