/*
 * Best-first search (search.h): Dijkstra and A* on random graphs against
 * Floyd-Warshall and against a naive O(V^2) best-first reference that uses
 * the same ordering rule, lazy evaluation, budgets, capacities, bad input
 * and determinism.
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

#include "hylo/internal/search.h"

/* Several MB each: allocated once, dirtied before every test. */
static hylo_search *ws;
static hylo_search *ws2;

static int setup(void **state)
{
	(void)state;
	memset(ws, 0xa5, sizeof *ws);
	memset(ws2, 0x5a, sizeof *ws2);
	return 0;
}

static hylo_budget no_budget(void)
{
	hylo_budget b;

	memset(&b, 0, sizeof b);
	return b;
}

static int close_rel(double a, double b)
{
	if (isinf(a) || isinf(b))
		return a == b;
	return fabs(a - b) <= 1e-12 * fmax(1.0, fmax(fabs(a), fabs(b)));
}

/* ---- random graphs in the plane, stored as CSR --------------------------- */

#define MAXN 60
#define MAXE (MAXN * MAXN * 2)
#define N_GRAPHS 200
#define N_QUERIES 3

typedef struct {
	uint32_t n;
	double x[MAXN], y[MAXN];
	uint32_t row[MAXN + 1];
	uint32_t col[MAXE];
	double cost[MAXE];
	double d[MAXN][MAXN];        /* Floyd-Warshall distances */
	/* the current query */
	uint32_t start, goal;
	int h_mode;                  /* 0: none, 1: Euclidean, 2: also +inf at dead ends */
	int skip_closed;
	int instrument;
	uint32_t calls[MAXN];
	uint32_t order[MAXN];        /* nodes in the order they were expanded */
	uint32_t n_calls;
	uint64_t out_edges;          /* out-degrees of the expanded nodes */
} tgraph;

static tgraph tg;

static uint64_t rng_state;

static uint64_t rnd(void)
{
	/* splitmix64: seeded, so every run sees the same graphs */
	uint64_t z = (rng_state += 0x9e3779b97f4a7c15ULL);

	z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
	z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
	return z ^ (z >> 31);
}

static double rnd01(void)
{
	return (double)(rnd() >> 11) / 9007199254740992.0;
}

static double dist(const tgraph *t, uint32_t a, uint32_t b)
{
	double dx = t->x[a] - t->x[b], dy = t->y[a] - t->y[b];

	return sqrt(dx * dx + dy * dy);
}

static double edge_cost(const tgraph *t, uint32_t u, uint32_t v)
{
	/* Exactly the distance (many ties, zero costs between equal points)
	 * or longer: h = distance to the goal stays consistent. */
	if (rnd() % 3 == 0)
		return dist(t, u, v);
	return dist(t, u, v) * (1.0 + 2.0 * rnd01());
}

static void floyd_warshall(tgraph *t)
{
	uint32_t i, j, k, e;

	for (i = 0; i < t->n; i++)
		for (j = 0; j < t->n; j++)
			t->d[i][j] = i == j ? 0 : INFINITY;
	for (i = 0; i < t->n; i++)
		for (e = t->row[i]; e < t->row[i + 1]; e++)
			if (t->cost[e] < t->d[i][t->col[e]])
				t->d[i][t->col[e]] = t->cost[e];
	for (k = 0; k < t->n; k++)
		for (i = 0; i < t->n; i++)
			for (j = 0; j < t->n; j++)
				if (t->d[i][k] + t->d[k][j] < t->d[i][j])
					t->d[i][j] = t->d[i][k] + t->d[k][j];
}

/* Kinds: 0 uniform points, 1 points on a 4x4 grid (coincident points, zero
 * costs), 2 sparse, 3 two components with no edge between, 4 dense. */
static void gen_graph(tgraph *t, int idx)
{
	static const double density[] = { 0.04, 0.1, 0.2, 0.4, 0.8 };
	int kind = idx % 5;
	double p = kind == 2 ? 0.03 : kind == 4 ? 0.8 : density[rnd() % 5];
	uint32_t n = 2 + (uint32_t)(rnd() % (MAXN - 1)), u, v, ne = 0;

	memset(t, 0, sizeof *t);
	t->n = n;
	for (u = 0; u < n; u++) {
		if (kind == 1) {
			t->x[u] = (double)(rnd() % 4);
			t->y[u] = (double)(rnd() % 4);
		} else {
			t->x[u] = 10.0 * rnd01();
			t->y[u] = 10.0 * rnd01();
		}
	}
	for (u = 0; u < n; u++) {
		uint32_t r0 = ne, k;

		t->row[u] = ne;
		for (v = 0; v < n; v++) {
			if (kind == 3 && (u < n / 2) != (v < n / 2))
				continue;
			if (rnd01() >= p)
				continue;
			t->col[ne] = v;
			t->cost[ne++] = edge_cost(t, u, v);
			if (rnd() % 10 == 0) { /* a parallel edge */
				t->col[ne] = v;
				t->cost[ne++] = edge_cost(t, u, v);
			}
		}
		/* Shuffle the row so that relaxation order is arbitrary. */
		for (k = ne - r0; k > 1; k--) {
			uint32_t a = r0 + k - 1, b = r0 + (uint32_t)(rnd() % k), c = t->col[a];
			double w = t->cost[a];

			t->col[a] = t->col[b];
			t->cost[a] = t->cost[b];
			t->col[b] = c;
			t->cost[b] = w;
		}
	}
	t->row[n] = ne;
	floyd_warshall(t);
}

static uint32_t count_closed(const hylo_search *s, uint32_t n)
{
	uint32_t v, c = 0;

	for (v = 0; v < n; v++)
		c += (uint32_t)hylo_search_closed(s, v);
	return c;
}

static hylo_status csr_expand(void *ctx, hylo_search *s, uint32_t u, uint32_t *heads,
			      hylo_real *costs, uint32_t cap, uint32_t *n, hylo_reason *r)
{
	tgraph *t = ctx;
	uint32_t e, k = 0;

	(void)r;
	assert_true(u < t->n);
	if (t->instrument) {
		/* Once per node, at the moment it is closed: the closed set is
		 * exactly the nodes expanded so far, and u's cost is final. */
		assert_int_equal(t->calls[u], 0);
		t->calls[u]++;
		t->order[t->n_calls++] = u;
		assert_true(hylo_search_closed(s, u));
		assert_int_equal(count_closed(s, t->n), t->n_calls);
		if (!close_rel(hylo_search_cost(s, u), t->d[t->start][u]))
			fail_msg("closed node %u: cost %.17g, Floyd-Warshall %.17g (h_mode %d)",
				 (unsigned)u, hylo_search_cost(s, u), t->d[t->start][u], t->h_mode);
		t->out_edges += t->row[u + 1] - t->row[u];
	}
	for (e = t->row[u]; e < t->row[u + 1]; e++) {
		if (t->skip_closed && hylo_search_closed(s, t->col[e]))
			continue;
		assert_true(k < cap);
		heads[k] = t->col[e];
		costs[k++] = t->cost[e];
	}
	*n = k;
	return HYLO_OK;
}

static hylo_real csr_h(void *ctx, uint32_t u)
{
	const tgraph *t = ctx;

	if (t->h_mode == 2 && isinf(t->d[u][t->goal]))
		return INFINITY;
	return dist(t, u, t->goal);
}

/* ---- the reference: O(V^2) best-first with the same ordering rule ------- */

typedef struct {
	hylo_outcome outcome;
	double g[MAXN];
	uint32_t parent[MAXN];
	int closed[MAXN];
	uint32_t order[MAXN + 1];
	uint32_t n_order;
	uint64_t pushes, decrease_keys;
} ref_result;

static ref_result ref;

static int ref_better(const double *f, const double *g, uint32_t a, uint32_t b)
{
	if (f[a] != f[b])
		return f[a] < f[b];
	if (g[a] != g[b])
		return g[a] > g[b];
	return a < b;
}

static void ref_search(const tgraph *t, ref_result *o)
{
	double f[MAXN];
	int open[MAXN];
	uint32_t u, v, e;

	memset(o, 0, sizeof *o);
	memset(open, 0, sizeof open);
	for (v = 0; v < t->n; v++) {
		o->g[v] = INFINITY;
		o->parent[v] = HYLO_NO_NODE;
	}
	f[t->start] = t->h_mode ? csr_h((void *)t, t->start) : 0;
	if (isfinite(f[t->start]) || t->start == t->goal) {
		o->g[t->start] = 0;
		open[t->start] = 1;
		o->pushes = 1;
	}
	for (;;) {
		u = HYLO_NO_NODE;
		for (v = 0; v < t->n; v++)
			if (open[v] && (u == HYLO_NO_NODE || ref_better(f, o->g, v, u)))
				u = v;
		if (u == HYLO_NO_NODE) {
			o->outcome = HYLO_NO_PATH;
			return;
		}
		open[u] = 0;
		o->closed[u] = 1;
		o->order[o->n_order++] = u;
		if (u == t->goal) {
			o->outcome = HYLO_FOUND;
			return;
		}
		for (e = t->row[u]; e < t->row[u + 1]; e++) {
			double ng = o->g[u] + t->cost[e], h;

			v = t->col[e];
			if (o->closed[v] || !(ng < o->g[v]))
				continue;
			/* +inf: v cannot reach the goal, never queue it. */
			h = t->h_mode ? csr_h((void *)t, v) : 0;
			if (isinf(h) && v != t->goal)
				continue;
			if (open[v])
				o->decrease_keys++;
			else
				o->pushes++;
			o->g[v] = ng;
			o->parent[v] = u;
			f[v] = ng + h;
			open[v] = 1;
		}
	}
}

/* ---- one query, checked against both references ------------------------ */

typedef struct {
	hylo_outcome outcome;
	hylo_search_stats stats;
	uint32_t n_calls;
	uint64_t out_edges;
	double g[MAXN];
	uint32_t parent[MAXN];
	uint32_t order[MAXN];
} run_result;

static void check_path(const tgraph *t, const hylo_search *s)
{
	uint32_t path[MAXN], n = 0, k, e;
	double sum = 0;
	hylo_reason r;

	assert_int_equal(hylo_search_path(s, t->goal, path, MAXN, &n, &r), HYLO_OK);
	assert_true(n >= 1);
	assert_int_equal(path[0], t->start);
	assert_int_equal(path[n - 1], t->goal);
	for (k = 0; k + 1 < n; k++) {
		double best = INFINITY;

		for (e = t->row[path[k]]; e < t->row[path[k] + 1]; e++)
			if (t->col[e] == path[k + 1] && t->cost[e] < best)
				best = t->cost[e];
		assert_true(isfinite(best)); /* a real edge */
		sum += best;
	}
	assert_true(close_rel(sum, hylo_search_cost(s, t->goal)));
}

static void run_query(tgraph *t, int h_mode, int skip_closed, run_result *o)
{
	hylo_graph g = { 0, NULL, NULL, NULL, 1, NULL, NULL, NULL };
	hylo_budget b = no_budget();
	hylo_reason r;
	hylo_status st;
	uint32_t v;

	t->h_mode = h_mode;
	t->skip_closed = skip_closed;
	t->instrument = 1;
	memset(t->calls, 0, sizeof t->calls);
	t->n_calls = 0;
	t->out_edges = 0;
	g.n_nodes = t->n;
	g.expand = csr_expand;
	g.heuristic = h_mode ? csr_h : NULL;
	g.ctx = t;
	st = hylo_search_run(ws, &g, t->start, t->goal, &b, &o->outcome, &r);
	if (st != HYLO_OK)
		fail_msg("search: %s: %s", hylo_status_str(st), r.text);
	o->stats = ws->stats;
	o->n_calls = t->n_calls;
	o->out_edges = t->out_edges;
	memcpy(o->order, t->order, sizeof o->order);
	for (v = 0; v < t->n; v++) {
		o->g[v] = hylo_search_cost(ws, v);
		o->parent[v] = hylo_search_parent(ws, v);
	}

	/* Against Floyd-Warshall. */
	if (isinf(t->d[t->start][t->goal])) {
		assert_int_equal(o->outcome, HYLO_NO_PATH);
	} else {
		assert_int_equal(o->outcome, HYLO_FOUND);
		assert_true(close_rel(hylo_search_cost(ws, t->goal), t->d[t->start][t->goal]));
		check_path(t, ws);
	}

	/* Against the naive best-first reference: same expansion order, same
	 * g and parent everywhere, same heap traffic. */
	ref_search(t, &ref);
	assert_int_equal(o->outcome, ref.outcome);
	assert_int_equal(o->stats.expansions, ref.n_order);
	assert_int_equal(o->stats.pushes, ref.pushes);
	assert_int_equal(o->stats.decrease_keys, ref.decrease_keys);
	for (v = 0; v < o->n_calls; v++)
		assert_int_equal(o->order[v], ref.order[v]);
	for (v = 0; v < t->n; v++) {
		assert_true(o->g[v] == ref.g[v]);
		assert_int_equal(o->parent[v], ref.parent[v]);
		assert_int_equal(hylo_search_closed(ws, v), ref.closed[v]);
	}

	/* Each expansion but the goal's calls expand once; the statistics
	 * count what the callback returned. */
	assert_int_equal(o->n_calls + (o->outcome == HYLO_FOUND ? 1 : 0), o->stats.expansions);
	if (!skip_closed)
		assert_int_equal(o->stats.edges_evaluated, o->out_edges);
	else
		assert_true(o->stats.edges_evaluated <= o->out_edges);
}

static void same_run(const run_result *a, const run_result *b, uint32_t n)
{
	assert_int_equal(a->outcome, b->outcome);
	assert_int_equal(a->stats.expansions, b->stats.expansions);
	assert_int_equal(a->n_calls, b->n_calls);
	assert_memory_equal(a->order, b->order, a->n_calls * sizeof a->order[0]);
	assert_memory_equal(a->g, b->g, n * sizeof a->g[0]);
	assert_memory_equal(a->parent, b->parent, n * sizeof a->parent[0]);
}

static run_result rr_dij, rr_dij_skip, rr_astar, rr_astar_skip, rr_astar_inf;

/*
 * 200 seeded graphs of 2..60 nodes, 3 queries each: Dijkstra and A* (with
 * and without skipping closed heads, and A* with +inf at dead ends) are
 * optimal against Floyd-Warshall, agree with the naive reference step by
 * step, and A* never expands more nodes than Dijkstra.
 */
static void test_random_graphs(void **state)
{
	uint64_t skipped = 0, dks = 0, zero_cost = 0, found = 0, no_path = 0, fewer = 0;
	int i, q;

	(void)state;
	rng_state = 12345;
	for (i = 0; i < N_GRAPHS; i++) {
		uint32_t e;

		gen_graph(&tg, i);
		for (e = 0; e < tg.row[tg.n]; e++)
			zero_cost += tg.cost[e] == 0;
		for (q = 0; q < N_QUERIES; q++) {
			tg.start = (uint32_t)(rnd() % tg.n);
			tg.goal = q == 2 && rnd() % 4 == 0 ? tg.start : (uint32_t)(rnd() % tg.n);

			run_query(&tg, 0, 0, &rr_dij);
			run_query(&tg, 0, 1, &rr_dij_skip);
			run_query(&tg, 1, 0, &rr_astar);
			run_query(&tg, 1, 1, &rr_astar_skip);
			run_query(&tg, 2, 0, &rr_astar_inf);
			same_run(&rr_dij, &rr_dij_skip, tg.n);
			same_run(&rr_astar, &rr_astar_skip, tg.n);
			assert_true(rr_astar.stats.expansions <= rr_dij.stats.expansions);
			assert_true(rr_astar_inf.stats.expansions <= rr_dij.stats.expansions);
			skipped += rr_dij.stats.edges_evaluated - rr_dij_skip.stats.edges_evaluated;
			dks += rr_dij.stats.decrease_keys + rr_astar.stats.decrease_keys;
			fewer += rr_astar.stats.expansions < rr_dij.stats.expansions;
			found += rr_dij.outcome == HYLO_FOUND;
			no_path += rr_dij.outcome == HYLO_NO_PATH;
		}
	}
	/* The sample exercises what it claims to. */
	assert_true(skipped > 0);
	assert_true(dks > 100);
	assert_true(zero_cost > 0);
	assert_true(found > 100);
	assert_true(no_path > 20);
	assert_true(fewer > 50);
}

/* ---- a heuristic that grows (hylo_found_fn) ------------------------------ */

#define GROW_GOALS 3

/* Three goals; h = the Euclidean distance to the nearest goal not closed
 * yet (consistent towards each open goal; it grows as goals close). */
typedef struct {
	tgraph *t;
	uint32_t goals[GROW_GOALS];
	int open[GROW_GOALS];
	int grow;                    /* 0: found is not told, h stays the minimum over all */
	int staged;                  /* after a goal, only half of the growth until the keys pass level */
	double alpha, level;
	uint32_t n_refresh;
	uint32_t n_exp;
	double exp_f[MAXN];          /* g + current h of each expansion */
	uint32_t exp_phase[MAXN];    /* goals closed before it */
	uint32_t phase;
} grow_ctx;

static grow_ctx gc;

static hylo_real grow_h(void *ctx, uint32_t u)
{
	const grow_ctx *c = ctx;
	double h = INFINITY, h0 = INFINITY;
	int k;

	for (k = 0; k < GROW_GOALS; k++) {
		if (c->open[k] && dist(c->t, u, c->goals[k]) < h)
			h = dist(c->t, u, c->goals[k]);
		if (dist(c->t, u, c->goals[k]) < h0)
			h0 = dist(c->t, u, c->goals[k]);
	}
	/* Staged: the larger of the first heuristic and a part of the grown
	 * one, both consistent. */
	if (c->staged && isfinite(h))
		return fmax(h0, c->alpha * h);
	return h;
}

static hylo_status grow_expand(void *ctx, hylo_search *s, uint32_t u, uint32_t *heads,
			       hylo_real *costs, uint32_t cap, uint32_t *n, hylo_reason *r)
{
	grow_ctx *c = ctx;

	c->exp_f[c->n_exp] = hylo_search_cost(s, u) + grow_h(c, u);
	c->exp_phase[c->n_exp++] = c->phase;
	return csr_expand(c->t, s, u, heads, costs, cap, n, r);
}

static hylo_status grow_found(void *ctx, hylo_search *s, uint32_t goal, int *grew, hylo_reason *r)
{
	grow_ctx *c = ctx;
	int k;

	(void)r;
	*grew = 1;
	if (goal == HYLO_NO_NODE) {
		/* Asked only once every key has passed the level it set. */
		assert_true(c->staged);
		assert_true(hylo_search_min_key(s) > c->level);
		c->n_refresh++;
		c->alpha = 1;
		return HYLO_OK;
	}
	c->phase++;
	for (k = 0; k < GROW_GOALS; k++)
		if (c->goals[k] == goal)
			c->open[k] = 0;
	/* Half the growth after the first goal only: it never shrinks. */
	if (c->staged && c->phase == 1) {
		c->alpha = 0.5;
		c->level = hylo_search_cost(s, goal) * 1.1;
		hylo_search_refresh_above(s, c->level);
	}
	return HYLO_OK;
}

/* The group key of the tests' graphs: they never defer. */
static hylo_real grow_group_key(void *ctx, hylo_search *s, uint32_t u, uint32_t group)
{
	(void)ctx;
	(void)s;
	(void)u;
	(void)group;
	return INFINITY;
}

/* Costs from the start with the goals as dead ends (the search does not
 * expand a goal it closed): O(n^2) Dijkstra. */
static void dist_avoiding_goals(const tgraph *t, double *d)
{
	int done[MAXN] = { 0 };
	uint32_t v, e, k, u;

	for (v = 0; v < t->n; v++)
		d[v] = INFINITY;
	d[t->start] = 0;
	for (;;) {
		u = t->n;
		for (v = 0; v < t->n; v++)
			if (!done[v] && isfinite(d[v]) && (u == t->n || d[v] < d[u]))
				u = v;
		if (u == t->n)
			return;
		done[u] = 1;
		for (k = 0; k < GROW_GOALS && gc.goals[k] != u; k++)
			;
		if (k < GROW_GOALS)
			continue;
		for (e = t->row[u]; e < t->row[u + 1]; e++)
			if (d[u] + t->cost[e] < d[t->col[e]])
				d[t->col[e]] = d[u] + t->cost[e];
	}
}

static uint64_t run_grow(tgraph *t, int grow, int staged, hylo_real *cost)
{
	double d[MAXN];
	hylo_graph g = { 0, NULL, NULL, NULL, 1, NULL, NULL, NULL };
	hylo_budget b = no_budget();
	hylo_outcome out;
	hylo_reason r;
	hylo_status st;
	uint32_t k, e, want = 0, n_found;

	dist_avoiding_goals(t, d);
	for (k = 0; k < GROW_GOALS; k++) {
		gc.open[k] = 1;
		want += isfinite(d[gc.goals[k]]);
	}
	gc.t = t;
	gc.grow = grow;
	gc.staged = staged;
	gc.alpha = 1;
	gc.level = INFINITY;
	gc.n_exp = 0;
	gc.phase = 0;
	t->instrument = 0;
	t->skip_closed = 0;
	g.n_nodes = t->n;
	g.expand = grow_expand;
	g.heuristic = grow_h;
	g.ctx = &gc;
	g.found = grow ? grow_found : NULL;
	g.group_key = grow ? grow_group_key : NULL;
	st = hylo_search_run_goals(ws, &g, t->start, gc.goals, GROW_GOALS, want ? want : 1, INFINITY, &b,
				   &out, &r);
	if (st != HYLO_OK)
		fail_msg("search: %s: %s", hylo_status_str(st), r.text);
	n_found = hylo_search_n_found(ws);
	assert_int_equal(n_found, want);
	/* Every reachable goal, at its Floyd-Warshall cost, cheapest first. */
	for (k = 0; k < n_found; k++) {
		cost[k] = hylo_search_cost(ws, hylo_search_found(ws, k));
		for (e = 0; e < GROW_GOALS && gc.goals[e] != hylo_search_found(ws, k); e++)
			;
		assert_true(e < GROW_GOALS);
		assert_true(close_rel(cost[k], d[gc.goals[e]]));
		if (k > 0)
			assert_true(cost[k] >= cost[k - 1]);
	}
	/* With the heuristic grown, no node is expanded on a stale key: each
	 * one's current f is at most the cost of the goal closed next. */
	for (k = 0; grow && k < gc.n_exp; k++)
		if (gc.exp_phase[k] < n_found && !(gc.exp_f[k] <= cost[gc.exp_phase[k]] * (1 + 1e-12)))
			fail_msg("expansion %u: f %.17g above the next goal's cost %.17g", (unsigned)k,
				 gc.exp_f[k], cost[gc.exp_phase[k]]);
	return ws->stats.expansions;
}

/*
 * 200 seeded graphs, three goals each: a heuristic that grows as goals close
 * (towards the nearest goal still open) finds every goal at its optimal cost
 * (goals are dead ends) in order, never expands a node whose current f exceeds the next goal's
 * cost (the keys it took were current), and expands no more than the
 * heuristic that stays the minimum over all goals. Staged (half the growth
 * after the first goal, the rest once every key has passed 1.1 times its cost:
 * hylo_search_refresh_above) it finds the same costs, and is asked again
 * only when the keys have passed that level.
 */
static void test_growing_heuristic(void **state)
{
	hylo_real c_grow[GROW_GOALS], c_fixed[GROW_GOALS], c_staged[GROW_GOALS];
	uint64_t fewer = 0, multi = 0, refreshed = 0;
	int i, k;

	(void)state;
	rng_state = 777;
	for (i = 0; i < N_GRAPHS; i++) {
		uint64_t e_grow, e_fixed;

		gen_graph(&tg, i);
		tg.start = (uint32_t)(rnd() % tg.n);
		for (k = 0; k < GROW_GOALS; k++)
			gc.goals[k] = (uint32_t)((tg.start + 1 + rnd() % (tg.n - 1)) % tg.n);
		if (gc.goals[0] == gc.goals[1] || gc.goals[1] == gc.goals[2] || gc.goals[0] == gc.goals[2])
			continue;
		tg.goal = gc.goals[0];
		e_fixed = run_grow(&tg, 0, 0, c_fixed);
		gc.n_refresh = 0;
		run_grow(&tg, 1, 1, c_staged);
		refreshed += gc.n_refresh > 0;
		e_grow = run_grow(&tg, 1, 0, c_grow);
		for (k = 0; k < (int)hylo_search_n_found(ws); k++) {
			assert_true(c_grow[k] == c_fixed[k]);
			assert_true(c_staged[k] == c_fixed[k]);
		}
		assert_true(e_grow <= e_fixed);
		fewer += e_grow < e_fixed;
		multi += hylo_search_n_found(ws) >= 2;
	}
	assert_true(multi > 50);
	assert_true(fewer > 10);
	assert_true(refreshed > 10);
}

/* ---- stopping at a limit and going on ------------------------------------ */

/* After a stop at limit: the nodes closed are exactly those whose f (exact
 * cost from the start plus h) is at most limit, ties at the limit aside,
 * each at its exact cost, and every key left is above limit. */
static void check_below(const tgraph *t, const hylo_search *s, double limit)
{
	uint32_t v;

	assert_true(hylo_search_min_key(s) > limit);
	for (v = 0; v < t->n; v++) {
		double f = t->d[t->start][v] + dist(t, v, t->goal);

		if (hylo_search_closed(s, v)) {
			assert_true(f <= limit * (1 + 1e-12));
			assert_true(close_rel(hylo_search_cost(s, v), t->d[t->start][v]));
		} else if (v != t->goal) {
			assert_false(f < limit * (1 - 1e-12));
		}
	}
}

/*
 * 200 seeded graphs, 3 queries each: A* run below 40% of the goal's cost,
 * resumed up to 80%, then to the end, stops where it should each time
 * (check_below), and ends exactly as one run: same outcome, expansions,
 * costs and parents. Resume refuses a lower limit, a NaN and another graph.
 */
static void test_resume(void **state)
{
	hylo_graph g = { 0, NULL, NULL, NULL, 1, NULL, NULL, NULL };
	hylo_budget b = no_budget();
	hylo_outcome out, out2;
	hylo_reason r;
	uint64_t stopped = 0;
	uint32_t v;
	int i, q;

	(void)state;
	rng_state = 4242;
	g.expand = csr_expand;
	g.heuristic = csr_h;
	g.ctx = &tg;
	for (i = 0; i < N_GRAPHS; i++) {
		gen_graph(&tg, i);
		g.n_nodes = tg.n;
		tg.h_mode = 1;
		tg.skip_closed = 0;
		tg.instrument = 0;
		for (q = 0; q < N_QUERIES; q++) {
			double d;

			tg.start = (uint32_t)(rnd() % tg.n);
			tg.goal = (uint32_t)(rnd() % tg.n);
			d = tg.d[tg.start][tg.goal];
			if (tg.goal == tg.start || !isfinite(d) || d == 0)
				continue;
			assert_int_equal(hylo_search_run(ws, &g, tg.start, tg.goal, &b, &out, &r), HYLO_OK);
			assert_int_equal(hylo_search_run_below(ws2, &g, tg.start, tg.goal, 0.4 * d, &b, &out2, &r),
					 HYLO_OK);
			assert_int_equal(out2, HYLO_NO_PATH);
			check_below(&tg, ws2, 0.4 * d);
			stopped += ws2->stats.expansions < ws->stats.expansions;
			assert_int_equal(hylo_search_resume(ws2, &g, 0.8 * d, 0, &b, &out2, &r), HYLO_OK);
			assert_int_equal(out2, HYLO_NO_PATH);
			check_below(&tg, ws2, 0.8 * d);
			assert_int_equal(hylo_search_resume(ws2, &g, INFINITY, 0, &b, &out2, &r), HYLO_OK);
			assert_int_equal(out2, out);
			assert_int_equal(ws2->stats.expansions, ws->stats.expansions);
			for (v = 0; v < tg.n; v++) {
				assert_true(hylo_search_cost(ws2, v) == hylo_search_cost(ws, v));
				assert_int_equal(hylo_search_parent(ws2, v), hylo_search_parent(ws, v));
			}
		}
	}
	assert_true(stopped > 100);
	/* Bad input: nothing changes. */
	gen_graph(&tg, 0);
	g.n_nodes = tg.n;
	tg.start = 0;
	tg.goal = tg.n - 1;
	assert_int_equal(hylo_search_run_below(ws2, &g, 0, tg.n - 1, 0, &b, &out2, &r), HYLO_OK);
	assert_int_equal(hylo_search_resume(ws2, &g, -1, 0, &b, &out2, &r), HYLO_E_BAD_VALUE);
	assert_non_null(strstr(r.text, "below the last run's"));
	assert_int_equal(hylo_search_resume(ws2, &g, NAN, 0, &b, &out2, &r), HYLO_E_BAD_VALUE);
	g.n_nodes = tg.n + 1;
	assert_int_equal(hylo_search_resume(ws2, &g, INFINITY, 0, &b, &out2, &r), HYLO_E_BAD_VALUE);
	assert_non_null(strstr(r.text, "no run of this graph"));
	assert_int_equal(hylo_search_resume(NULL, &g, INFINITY, 0, &b, &out2, &r), HYLO_E_NULL);
	assert_int_equal(hylo_search_run_below(ws2, &g, 0, 1, NAN, &b, &out2, &r), HYLO_E_BAD_VALUE);
}

/* ---- hand-made graphs ---------------------------------------------------- */

/* A small explicit graph for the targeted tests. */
typedef struct {
	uint32_t n_edges;
	uint32_t from[64], to[64];
	double cost[64];
	double h[16];
	int use_h;
	uint32_t order[16];
	uint32_t n_calls;
} small_graph;

static hylo_status small_expand(void *ctx, hylo_search *s, uint32_t u, uint32_t *heads,
				hylo_real *costs, uint32_t cap, uint32_t *n, hylo_reason *r)
{
	small_graph *sg = ctx;
	uint32_t e, k = 0;

	(void)s;
	(void)r;
	sg->order[sg->n_calls++] = u;
	for (e = 0; e < sg->n_edges; e++) {
		if (sg->from[e] != u)
			continue;
		assert_true(k < cap);
		heads[k] = sg->to[e];
		costs[k++] = sg->cost[e];
	}
	*n = k;
	return HYLO_OK;
}

static hylo_real small_h(void *ctx, uint32_t u)
{
	return ((small_graph *)ctx)->h[u];
}

static void add_edge(small_graph *sg, uint32_t a, uint32_t b, double c)
{
	sg->from[sg->n_edges] = a;
	sg->to[sg->n_edges] = b;
	sg->cost[sg->n_edges++] = c;
}

static hylo_status run_small(small_graph *sg, uint32_t n, uint32_t start, uint32_t goal,
			     hylo_outcome *out, hylo_reason *r)
{
	hylo_graph g = { 0, NULL, NULL, NULL, 1, NULL, NULL, NULL };
	hylo_budget b = no_budget();

	g.n_nodes = n;
	g.expand = small_expand;
	g.heuristic = sg->use_h ? small_h : NULL;
	g.ctx = sg;
	sg->n_calls = 0;
	return hylo_search_run(ws, &g, start, goal, &b, out, r);
}

/*
 * Decrease-key: node 1 is first reached at cost 10, then at 2 via node 2;
 * its heap entry must move ahead of nodes 3..6 (cost 5), or it would be
 * expanded after them.
 */
static void test_decrease_key(void **state)
{
	small_graph sg;
	hylo_outcome out;
	hylo_reason r;
	uint32_t path[8], n;
	static const uint32_t want[] = { 0, 2, 1, 7, 3, 4, 5, 6 };
	uint32_t k;

	(void)state;
	memset(&sg, 0, sizeof sg);
	add_edge(&sg, 0, 1, 10);
	add_edge(&sg, 0, 3, 5);
	add_edge(&sg, 0, 4, 5);
	add_edge(&sg, 0, 5, 5);
	add_edge(&sg, 0, 6, 5);
	add_edge(&sg, 0, 2, 1);
	add_edge(&sg, 2, 1, 1);
	add_edge(&sg, 1, 7, 1);
	assert_int_equal(run_small(&sg, 9, 0, 8, &out, &r), HYLO_OK);
	assert_int_equal(out, HYLO_NO_PATH);
	assert_int_equal(ws->stats.decrease_keys, 1);
	assert_int_equal(ws->stats.pushes, 8);
	assert_int_equal(sg.n_calls, 8);
	for (k = 0; k < 8; k++)
		assert_int_equal(sg.order[k], want[k]);
	assert_true(hylo_search_cost(ws, 1) == 2);
	assert_int_equal(hylo_search_parent(ws, 1), 2);
	assert_true(hylo_search_cost(ws, 7) == 3);
	assert_true(isinf(hylo_search_cost(ws, 8)));
	assert_int_equal(hylo_search_parent(ws, 8), HYLO_NO_NODE);
	assert_int_equal(hylo_search_parent(ws, 0), HYLO_NO_NODE);
	assert_int_equal(hylo_search_path(ws, 7, path, 8, &n, &r), HYLO_OK);
	assert_int_equal(n, 4);
	assert_int_equal(path[0], 0);
	assert_int_equal(path[1], 2);
	assert_int_equal(path[2], 1);
	assert_int_equal(path[3], 7);
}

/*
 * Ties: equal f goes to the larger g, then to the smaller id; pushed in an
 * order that a heap without the rule would not sort this way.
 */
static void test_tie_breaking(void **state)
{
	small_graph sg;
	hylo_outcome out;
	hylo_reason r;
	uint32_t k;
	static const uint32_t want_dij[] = { 0, 1, 2, 3, 4, 5 };
	static const uint32_t want_astar[] = { 0, 5, 3, 1, 2, 4 };

	(void)state;
	/* Dijkstra, all costs equal: by id. */
	memset(&sg, 0, sizeof sg);
	add_edge(&sg, 0, 5, 1);
	add_edge(&sg, 0, 3, 1);
	add_edge(&sg, 0, 4, 1);
	add_edge(&sg, 0, 1, 1);
	add_edge(&sg, 0, 2, 1);
	assert_int_equal(run_small(&sg, 7, 0, 6, &out, &r), HYLO_OK);
	assert_int_equal(out, HYLO_NO_PATH);
	assert_int_equal(sg.n_calls, 6);
	for (k = 0; k < 6; k++)
		assert_int_equal(sg.order[k], want_dij[k]);

	/* A*, f = 4 everywhere: g 3 (node 5), g 2 (node 3), then g 1 by id. */
	memset(&sg, 0, sizeof sg);
	sg.use_h = 1;
	add_edge(&sg, 0, 4, 1);
	add_edge(&sg, 0, 2, 1);
	add_edge(&sg, 0, 3, 2);
	add_edge(&sg, 0, 1, 1);
	add_edge(&sg, 0, 5, 3);
	sg.h[0] = 4;
	sg.h[1] = 3;
	sg.h[2] = 3;
	sg.h[3] = 2;
	sg.h[4] = 3;
	sg.h[5] = 1;
	assert_int_equal(run_small(&sg, 7, 0, 6, &out, &r), HYLO_OK);
	assert_int_equal(sg.n_calls, 6);
	for (k = 0; k < 6; k++)
		assert_int_equal(sg.order[k], want_astar[k]);
}

/*
 * h = +inf says the goal cannot be reached from a node: A* never queues
 * it, so its edges are never evaluated; the goal itself is always queued.
 */
static void test_infinite_heuristic(void **state)
{
	small_graph sg;
	hylo_outcome out;
	hylo_reason r;

	(void)state;
	memset(&sg, 0, sizeof sg);
	sg.use_h = 1;
	add_edge(&sg, 0, 1, 1);
	add_edge(&sg, 0, 2, 3);
	add_edge(&sg, 1, 4, 1);
	add_edge(&sg, 2, 3, 1);
	sg.h[1] = INFINITY;
	sg.h[4] = INFINITY;
	assert_int_equal(run_small(&sg, 5, 0, 3, &out, &r), HYLO_OK);
	assert_int_equal(out, HYLO_FOUND);
	assert_true(hylo_search_cost(ws, 3) == 4);
	assert_int_equal(sg.n_calls, 2);
	assert_int_equal(sg.order[0], 0);
	assert_int_equal(sg.order[1], 2);
	assert_true(isinf(hylo_search_cost(ws, 1)));
	assert_false(hylo_search_closed(ws, 1));
	assert_int_equal(ws->stats.pushes, 3);
	/* An inconsistent +inf at the goal does not hide it. */
	sg.h[3] = INFINITY;
	assert_int_equal(run_small(&sg, 5, 0, 3, &out, &r), HYLO_OK);
	assert_int_equal(out, HYLO_FOUND);
	sg.h[0] = INFINITY;
	assert_int_equal(run_small(&sg, 5, 0, 0, &out, &r), HYLO_OK);
	assert_int_equal(out, HYLO_FOUND);
	assert_true(hylo_search_cost(ws, 0) == 0);
}

/*
 * An inconsistent heuristic may find a cheaper way into a closed node; the
 * node stays closed with its cost, parent and single expansion (the result
 * is then not optimal, as the contract says).
 */
static void test_inconsistent_heuristic(void **state)
{
	small_graph sg;
	hylo_outcome out;
	hylo_reason r;

	(void)state;
	memset(&sg, 0, sizeof sg);
	sg.use_h = 1;
	add_edge(&sg, 0, 1, 2);
	add_edge(&sg, 0, 2, 0);
	add_edge(&sg, 2, 1, 0);
	add_edge(&sg, 1, 3, 10);
	sg.h[2] = 5; /* > c(2, 1) + h(1) */
	assert_int_equal(run_small(&sg, 4, 0, 3, &out, &r), HYLO_OK);
	assert_int_equal(out, HYLO_FOUND);
	assert_int_equal(sg.n_calls, 3);
	assert_int_equal(sg.order[1], 1);
	assert_int_equal(sg.order[2], 2);
	assert_true(hylo_search_cost(ws, 1) == 2);
	assert_int_equal(hylo_search_parent(ws, 1), 0);
	assert_true(hylo_search_cost(ws, 3) == 12);
	assert_int_equal(ws->stats.decrease_keys, 0);
}

/* start == goal: cost 0, a path of one node, nothing expanded but it. */
static void test_start_is_goal(void **state)
{
	small_graph sg;
	hylo_outcome out;
	hylo_reason r;
	uint32_t path[2] = { 99, 99 }, n = 99;

	(void)state;
	memset(&sg, 0, sizeof sg);
	add_edge(&sg, 3, 1, 1);
	assert_int_equal(run_small(&sg, 5, 3, 3, &out, &r), HYLO_OK);
	assert_int_equal(out, HYLO_FOUND);
	assert_int_equal(sg.n_calls, 0);
	assert_int_equal(ws->stats.expansions, 1);
	assert_true(hylo_search_cost(ws, 3) == 0);
	assert_int_equal(hylo_search_path(ws, 3, path, 1, &n, &r), HYLO_OK);
	assert_int_equal(n, 1);
	assert_int_equal(path[0], 3);
}

/* ---- lazy evaluation ---------------------------------------------------- */

/*
 * A complete graph on 40 nodes with costs that make many nodes reach the
 * goal late: each node is expanded at most once, never after it was closed,
 * and the edges into closed heads, when skipped, are never evaluated while
 * the result stays the same.
 */
static void test_lazy_evaluation(void **state)
{
	run_result a, b;
	uint32_t u, v, ne = 0;

	(void)state;
	rng_state = 777;
	memset(&tg, 0, sizeof tg);
	tg.n = 40;
	for (u = 0; u < tg.n; u++) {
		tg.x[u] = 10.0 * rnd01();
		tg.y[u] = 10.0 * rnd01();
	}
	for (u = 0; u < tg.n; u++) {
		tg.row[u] = ne;
		for (v = 0; v < tg.n; v++) {
			tg.col[ne] = v;
			tg.cost[ne++] = dist(&tg, u, v) * (1.0 + rnd01());
		}
	}
	tg.row[tg.n] = ne;
	floyd_warshall(&tg);
	tg.start = 0;
	tg.goal = 39;
	/* csr_expand asserts once-per-node and closed-set == expanded-set. */
	run_query(&tg, 0, 0, &a);
	run_query(&tg, 0, 1, &b);
	same_run(&a, &b, tg.n);
	for (u = 0; u < tg.n; u++)
		assert_true(tg.calls[u] <= 1);
	/* Complete graph: the k-th expansion sees k-1 closed heads plus itself. */
	assert_int_equal(a.stats.edges_evaluated, (uint64_t)a.n_calls * tg.n);
	assert_int_equal(b.stats.edges_evaluated,
			 (uint64_t)a.n_calls * tg.n - (uint64_t)a.n_calls * (a.n_calls + 1) / 2);
	/* Not every node was needed: the rest were never evaluated. */
	assert_true(a.n_calls < tg.n - 1);
}

/* ---- budgets ------------------------------------------------------------ */

/* Long chains, kept within a reduced HYLO_MAX_NODES. */
#define LONG_CHAIN (HYLO_MAX_NODES < 10000 ? HYLO_MAX_NODES : 10000)

typedef struct {
	uint32_t n;
	uint32_t calls;
	uint32_t skip;           /* chain_expand: also an edge u -> u + skip */
} chain_ctx;

static hylo_status chain_expand(void *ctx, hylo_search *s, uint32_t u, uint32_t *heads,
				hylo_real *costs, uint32_t cap, uint32_t *n, hylo_reason *r)
{
	chain_ctx *c = ctx;
	uint32_t k = 0;

	(void)s;
	(void)r;
	(void)cap;
	c->calls++;
	if (u + 1 < c->n) {
		heads[k] = u + 1;
		costs[k++] = 1.0;
	}
	if (c->skip && u + c->skip < c->n) {
		heads[k] = u + c->skip;
		costs[k++] = 0.5 * c->skip + 1.0;
	}
	*n = k;
	return HYLO_OK;
}

static hylo_graph chain_graph(chain_ctx *c, uint32_t n)
{
	hylo_graph g = { 0, NULL, NULL, NULL, 1, NULL, NULL, NULL };

	memset(c, 0, sizeof *c);
	c->n = n;
	g.n_nodes = n;
	g.expand = chain_expand;
	g.heuristic = NULL;
	g.ctx = c;
	return g;
}

/* max_expansions = k stops after exactly k expansions; k = path length finds. */
static void test_expansion_budget(void **state)
{
	chain_ctx c;
	hylo_graph g = chain_graph(&c, 100);
	hylo_budget b = no_budget();
	hylo_outcome out;
	hylo_reason r;
	static const uint64_t ks[] = { 1, 2, 10, 63, 64, 65, 99 };
	size_t i;

	(void)state;
	for (i = 0; i < sizeof ks / sizeof ks[0]; i++) {
		c.calls = 0;
		b.max_expansions = ks[i];
		assert_int_equal(hylo_search_run(ws, &g, 0, 99, &b, &out, &r), HYLO_OK);
		assert_int_equal(out, HYLO_BUDGET_EXHAUSTED);
		assert_int_equal(ws->stats.expansions, ks[i]);
		assert_int_equal(c.calls, ks[i]);
		assert_true(hylo_search_closed(ws, (uint32_t)ks[i] - 1));
		assert_false(hylo_search_closed(ws, (uint32_t)ks[i]));
	}
	/* The goal is the 100th node popped. */
	b.max_expansions = 100;
	assert_int_equal(hylo_search_run(ws, &g, 0, 99, &b, &out, &r), HYLO_OK);
	assert_int_equal(out, HYLO_FOUND);
	assert_true(hylo_search_cost(ws, 99) == 99);
	/* An empty heap is reported as such even with the budget spent. */
	b.max_expansions = 1;
	assert_int_equal(hylo_search_run(ws, &g, 99, 0, &b, &out, &r), HYLO_OK);
	assert_int_equal(out, HYLO_NO_PATH);
}

typedef struct {
	double t, step;
	uint32_t calls;
} fake_clock;

static double fake_now(void *ctx)
{
	fake_clock *fc = ctx;

	fc->calls++;
	fc->t += fc->step;
	return fc->t;
}

/* A clock that advances 1 ms per reading, read once at the start and then
 * every 64 expansions: a 3 ms budget runs out at the third check. */
static void test_time_budget(void **state)
{
	chain_ctx c;
	hylo_graph g = chain_graph(&c, LONG_CHAIN);
	hylo_budget b = no_budget();
	fake_clock fc = { 100.0, 1.0, 0 };
	hylo_outcome out;
	hylo_reason r;

	(void)state;
	b.time_budget_ms = 3.0;
	b.clock = fake_now;
	b.clock_ctx = &fc;
	assert_int_equal(hylo_search_run(ws, &g, 0, LONG_CHAIN - 1, &b, &out, &r), HYLO_OK);
	assert_int_equal(out, HYLO_BUDGET_EXHAUSTED);
	assert_int_equal(fc.calls, 4);
	assert_int_equal(ws->stats.expansions, 3 * 64);

	/* A clock that does not move never stops the search. */
	fc.t = 0;
	fc.step = 0;
	fc.calls = 0;
	assert_int_equal(hylo_search_run(ws, &g, 0, LONG_CHAIN - 1, &b, &out, &r), HYLO_OK);
	assert_int_equal(out, HYLO_FOUND);
	/* Read at the start and before pops 65, 129, ... up to the goal's. */
	assert_int_equal(fc.calls, 1 + (LONG_CHAIN - 1) / 64);

	/* Both budgets: the smaller one wins. */
	fc.t = 0;
	fc.step = 1.0;
	b.max_expansions = 70;
	assert_int_equal(hylo_search_run(ws, &g, 0, LONG_CHAIN - 1, &b, &out, &r), HYLO_OK);
	assert_int_equal(out, HYLO_BUDGET_EXHAUSTED);
	assert_int_equal(ws->stats.expansions, 70);

	/* A time budget without a clock, a negative one, a broken clock. */
	b.max_expansions = 0;
	b.clock = NULL;
	r.text[0] = '\0';
	assert_int_equal(hylo_search_run(ws, &g, 0, LONG_CHAIN - 1, &b, &out, &r), HYLO_E_NULL);
	assert_true(strlen(r.text) > 0);
	b.clock = fake_now;
	b.time_budget_ms = -1;
	assert_int_equal(hylo_search_run(ws, &g, 0, LONG_CHAIN - 1, &b, &out, &r), HYLO_E_BAD_VALUE);
	b.time_budget_ms = NAN;
	assert_int_equal(hylo_search_run(ws, &g, 0, LONG_CHAIN - 1, &b, &out, &r), HYLO_E_BAD_VALUE);
	b.time_budget_ms = 3.0;
	fc.t = NAN;
	assert_int_equal(hylo_search_run(ws, &g, 0, LONG_CHAIN - 1, &b, &out, &r), HYLO_E_BAD_VALUE);
	assert_non_null(strstr(r.text, "clock"));
}

/* ---- capacities --------------------------------------------------------- */

/*
 * Exactly HYLO_MAX_NODES nodes: a chain (path of every node) and a sparse
 * graph with heavy heap traffic, the latter certified optimal by
 * g(v) <= g(u) + c(u, v) on every edge and a tight parent edge.
 * One node more is refused.
 */
static hylo_status big_expand(void *ctx, hylo_search *s, uint32_t u, uint32_t *heads,
			      hylo_real *costs, uint32_t cap, uint32_t *n, hylo_reason *r)
{
	const uint32_t N = HYLO_MAX_NODES;
	uint32_t k = 0;

	(void)ctx;
	(void)s;
	(void)r;
	(void)cap;
	/* Node N - 1 has no incoming edge, so the search runs to exhaustion. */
	if (u + 1 < N - 1) {
		heads[k] = u + 1;
		costs[k++] = 1.0 + (u % 7) * 0.25;
	}
	heads[k] = (uint32_t)(((uint64_t)u * 31 + 7) % (N - 1));
	costs[k++] = 2.5 + u % 3;
	heads[k] = u / 2;
	costs[k++] = 0.5;
	heads[k] = (uint32_t)(((uint64_t)u * 17 + 1) % (N - 1));
	costs[k++] = 0.125 * (u % 13);
	*n = k;
	return HYLO_OK;
}

static void test_capacity_nodes(void **state)
{
	const uint32_t N = HYLO_MAX_NODES;
	chain_ctx c;
	hylo_graph g = chain_graph(&c, N);
	hylo_budget b = no_budget();
	hylo_outcome out;
	hylo_reason r;
	uint32_t *path = malloc((size_t)N * sizeof *path), n, u, k;
	uint32_t heads[4];
	double costs[4];
	uint64_t reached = 0;

	(void)state;
	assert_non_null(path);
	assert_int_equal(hylo_search_run(ws, &g, 0, N - 1, &b, &out, &r), HYLO_OK);
	assert_int_equal(out, HYLO_FOUND);
	assert_true(hylo_search_cost(ws, N - 1) == (double)(N - 1));
	assert_int_equal(hylo_search_path(ws, N - 1, path, N, &n, &r), HYLO_OK);
	assert_int_equal(n, N);
	for (u = 0; u < N; u++)
		assert_int_equal(path[u], u);
	assert_int_equal(hylo_search_path(ws, N - 1, path, N - 1, &n, &r),
			 HYLO_E_CAP_WAYPOINTS);
	assert_int_equal(n, 0);
	assert_non_null(strstr(r.text, "cap"));

	g.expand = big_expand;
	assert_int_equal(hylo_search_run(ws, &g, 0, N - 1, &b, &out, &r), HYLO_OK);
	assert_int_equal(out, HYLO_NO_PATH);
	assert_true(ws->stats.decrease_keys > 0);
	for (u = 0; u < N; u++) {
		double gu = hylo_search_cost(ws, u);
		uint32_t p = hylo_search_parent(ws, u), m;
		int tight = u == 0;

		if (isinf(gu))
			continue;
		reached++;
		assert_true(hylo_search_closed(ws, u));
		big_expand(NULL, ws, u, heads, costs, 4, &m, &r);
		for (k = 0; k < m; k++)
			assert_true(hylo_search_cost(ws, heads[k]) <= gu + costs[k]);
		if (u == 0) {
			assert_true(gu == 0);
			continue;
		}
		big_expand(NULL, ws, p, heads, costs, 4, &m, &r);
		for (k = 0; k < m; k++)
			tight |= heads[k] == u && hylo_search_cost(ws, p) + costs[k] == gu;
		assert_true(tight);
	}
	assert_int_equal(reached, N - 1);
	assert_int_equal(ws->stats.pushes, reached);
	assert_int_equal(ws->stats.expansions, reached);

	g = chain_graph(&c, N + 1);
	r.text[0] = '\0';
	assert_int_equal(hylo_search_run(ws, &g, 0, 1, &b, &out, &r), HYLO_E_CAP_NODES);
	assert_true(strlen(r.text) > 0);
	assert_int_equal(c.calls, 0);
	free(path);
}

typedef struct {
	uint32_t report;         /* what to report in *n, relative to cap: 0 or 1 extra */
	uint32_t cap_seen;
} fill_ctx;

/* Fills every one of the cap slots, then reports cap or cap + 1. */
static hylo_status fill_expand(void *ctx, hylo_search *s, uint32_t u, uint32_t *heads,
			       hylo_real *costs, uint32_t cap, uint32_t *n, hylo_reason *r)
{
	fill_ctx *f = ctx;
	uint32_t k;

	(void)s;
	(void)r;
	f->cap_seen = cap;
	if (u != 0) {
		*n = 0;
		return HYLO_OK;
	}
	for (k = 0; k < cap; k++) {
		heads[k] = 1 + k % 50;
		costs[k] = 100.0 - (double)k / cap;
	}
	*n = cap + f->report;
	return HYLO_OK;
}

static void test_capacity_successors(void **state)
{
	fill_ctx f = { 0, 0 };
	hylo_graph g = { 0, NULL, NULL, NULL, 1, NULL, NULL, NULL };
	hylo_budget b = no_budget();
	hylo_outcome out;
	hylo_reason r;
	char want[32];

	(void)state;
	g.n_nodes = 60;
	g.expand = fill_expand;
	g.heuristic = NULL;
	g.ctx = &f;
	assert_int_equal(hylo_search_run(ws, &g, 0, 59, &b, &out, &r), HYLO_OK);
	assert_int_equal(out, HYLO_NO_PATH);
	assert_int_equal(f.cap_seen, HYLO_MAX_SUCCESSORS);
	assert_int_equal(ws->stats.edges_evaluated, HYLO_MAX_SUCCESSORS);
	/* The last write to each head is its cheapest. */
	assert_true(hylo_search_cost(ws, 1) ==
		    100.0 - (double)(HYLO_MAX_SUCCESSORS - 1 - (HYLO_MAX_SUCCESSORS - 1) % 50) /
				    HYLO_MAX_SUCCESSORS);

	f.report = 1;
	r.text[0] = '\0';
	assert_int_equal(hylo_search_run(ws, &g, 0, 59, &b, &out, &r), HYLO_E_CAP_SUCCESSORS);
	snprintf(want, sizeof want, "%lu", (unsigned long)HYLO_MAX_SUCCESSORS + 1);
	assert_non_null(strstr(r.text, want));
	assert_int_equal(ws->stats.edges_evaluated, 0);
}

/* ---- bad input ---------------------------------------------------------- */

static void expect_fail(small_graph *sg, uint32_t n, hylo_status want, const char *a,
			const char *bstr)
{
	hylo_outcome out;
	hylo_reason r;

	memset(&r, 0, sizeof r);
	assert_int_equal(run_small(sg, n, 0, n - 1, &out, &r), want);
	if (a && !strstr(r.text, a))
		fail_msg("reason \"%s\" lacks \"%s\"", r.text, a);
	if (bstr && !strstr(r.text, bstr))
		fail_msg("reason \"%s\" lacks \"%s\"", r.text, bstr);
	assert_true(strlen(r.text) > 0);
	/* Same without a reason: no crash. */
	assert_int_equal(run_small(sg, n, 0, n - 1, &out, NULL), want);
}

typedef struct {
	int with_reason;
} err_ctx;

static hylo_status err_expand(void *ctx, hylo_search *s, uint32_t u, uint32_t *heads,
			      hylo_real *costs, uint32_t cap, uint32_t *n, hylo_reason *r)
{
	const err_ctx *e = ctx;

	(void)s;
	(void)heads;
	(void)costs;
	(void)cap;
	*n = 0;
	if (e->with_reason)
		return hylo_fail(r, HYLO_E_BAD_MAP, "cell of node %u is odd", (unsigned)u);
	return HYLO_E_BAD_MAP;
}

static void test_bad_input(void **state)
{
	small_graph sg;
	chain_ctx c;
	hylo_graph g = chain_graph(&c, 10);
	hylo_budget b = no_budget();
	hylo_outcome out;
	hylo_reason r;
	uint32_t path[4], n;
	err_ctx ec;

	(void)state;
	/* NULL arguments. */
	assert_int_equal(hylo_search_run(NULL, &g, 0, 9, &b, &out, &r), HYLO_E_NULL);
	assert_true(strlen(r.text) > 0);
	assert_int_equal(hylo_search_run(ws, NULL, 0, 9, &b, &out, &r), HYLO_E_NULL);
	assert_int_equal(hylo_search_run(ws, &g, 0, 9, NULL, &out, &r), HYLO_E_NULL);
	assert_int_equal(hylo_search_run(ws, &g, 0, 9, &b, NULL, &r), HYLO_E_NULL);
	assert_int_equal(hylo_search_run(NULL, NULL, 0, 9, NULL, NULL, NULL), HYLO_E_NULL);
	g.expand = NULL;
	assert_int_equal(hylo_search_run(ws, &g, 0, 9, &b, &out, &r), HYLO_E_NULL);
	g.expand = chain_expand;

	/* Start or goal out of range; a failed run leaves nothing reached. */
	assert_int_equal(hylo_search_run(ws, &g, 0, 9, &b, &out, &r), HYLO_OK);
	c.calls = 0;
	assert_int_equal(hylo_search_run(ws, &g, 10, 9, &b, &out, &r), HYLO_E_BAD_VALUE);
	assert_non_null(strstr(r.text, "10"));
	assert_true(isinf(hylo_search_cost(ws, 9)));
	assert_false(hylo_search_closed(ws, 0));
	assert_int_equal(hylo_search_run(ws, &g, 0, 10, &b, &out, &r), HYLO_E_BAD_VALUE);
	assert_int_equal(hylo_search_run(ws, &g, 0, UINT32_MAX, &b, &out, &r), HYLO_E_BAD_VALUE);
	g.n_nodes = 0;
	assert_int_equal(hylo_search_run(ws, &g, 0, 0, &b, &out, &r), HYLO_E_BAD_VALUE);
	assert_int_equal(c.calls, 0);

	/* Bad costs name the edge and the value. */
	memset(&sg, 0, sizeof sg);
	add_edge(&sg, 0, 3, 1);
	add_edge(&sg, 3, 4, -1);
	expect_fail(&sg, 6, HYLO_E_BAD_COST, "3 -> 4", "-1");
	sg.cost[1] = NAN;
	expect_fail(&sg, 6, HYLO_E_BAD_COST, "3 -> 4", "nan");
	sg.cost[1] = INFINITY;
	expect_fail(&sg, 6, HYLO_E_BAD_COST, "3 -> 4", "inf");
	sg.cost[1] = -INFINITY;
	expect_fail(&sg, 6, HYLO_E_BAD_COST, "3 -> 4", "inf");
	/* ... also on an edge into a closed node. */
	sg.cost[1] = 1;
	add_edge(&sg, 4, 0, -0.5);
	expect_fail(&sg, 6, HYLO_E_BAD_COST, "4 -> 0", "-0.5");
	/* A head out of range. */
	sg.cost[2] = 1;
	add_edge(&sg, 4, 6, 1);
	expect_fail(&sg, 6, HYLO_E_BAD_VALUE, "4 -> 6", NULL);
	/* Costs whose sum overflows. */
	memset(&sg, 0, sizeof sg);
	add_edge(&sg, 0, 1, 1e308);
	add_edge(&sg, 1, 2, 1e308);
	expect_fail(&sg, 4, HYLO_E_BAD_COST, "2", NULL);

	/* Heuristic NaN or negative, at the start or later. */
	memset(&sg, 0, sizeof sg);
	sg.use_h = 1;
	add_edge(&sg, 0, 2, 1);
	sg.h[2] = NAN;
	expect_fail(&sg, 4, HYLO_E_BAD_VALUE, "node 2", "nan");
	sg.h[2] = -0.25;
	expect_fail(&sg, 4, HYLO_E_BAD_VALUE, "node 2", "-0.25");
	sg.h[2] = 0;
	sg.h[0] = NAN;
	expect_fail(&sg, 4, HYLO_E_BAD_VALUE, "node 0", "nan");
	/* +inf is a valid bound: the goal is unreachable from there. */
	sg.h[0] = INFINITY;
	assert_int_equal(run_small(&sg, 4, 0, 3, &out, &r), HYLO_OK);
	assert_int_equal(out, HYLO_NO_PATH);
	assert_int_equal(ws->stats.expansions, 0);

	/* expand's own error passes through, with its reason or a default. */
	g.n_nodes = 10;
	g.expand = err_expand;
	g.ctx = &ec;
	ec.with_reason = 1;
	assert_int_equal(hylo_search_run(ws, &g, 0, 9, &b, &out, &r), HYLO_E_BAD_MAP);
	assert_string_equal(r.text, "cell of node 0 is odd");
	ec.with_reason = 0;
	assert_int_equal(hylo_search_run(ws, &g, 0, 9, &b, &out, &r), HYLO_E_BAD_MAP);
	assert_non_null(strstr(r.text, "node 0"));
	assert_int_equal(hylo_search_run(ws, &g, 0, 9, &b, &out, NULL), HYLO_E_BAD_MAP);

	/* Path and queries: edges u -> u + 1 (cost 1) and u -> u + 3 (2.5). */
	g = chain_graph(&c, 10);
	c.skip = 3;
	assert_int_equal(hylo_search_run(ws, &g, 2, 5, &b, &out, &r), HYLO_OK);
	assert_int_equal(out, HYLO_FOUND);
	assert_true(hylo_search_cost(ws, 5) == 2.5);
	assert_int_equal(hylo_search_path(NULL, 5, path, 4, &n, &r), HYLO_E_NULL);
	assert_int_equal(hylo_search_path(ws, 5, NULL, 4, &n, &r), HYLO_E_NULL);
	assert_int_equal(hylo_search_path(ws, 5, path, 4, NULL, &r), HYLO_E_NULL);
	assert_int_equal(hylo_search_path(ws, 1, path, 4, &n, &r), HYLO_E_BAD_VALUE);
	assert_non_null(strstr(r.text, "node 1 "));
	assert_int_equal(hylo_search_path(ws, 10, path, 4, &n, &r), HYLO_E_BAD_VALUE);
	assert_int_equal(hylo_search_path(ws, 5, path, 1, &n, &r), HYLO_E_CAP_WAYPOINTS);
	assert_int_equal(hylo_search_path(ws, 5, path, 2, &n, NULL), HYLO_OK);
	assert_int_equal(n, 2);
	assert_int_equal(path[0], 2);
	assert_int_equal(path[1], 5);
	/* Reached but not closed: a real path, not yet known optimal. */
	assert_true(hylo_search_cost(ws, 6) == 3.5);
	assert_false(hylo_search_closed(ws, 6));
	assert_int_equal(hylo_search_path(ws, 6, path, 4, &n, &r), HYLO_OK);
	assert_int_equal(n, 3);
	assert_int_equal(path[1], 3);
	assert_false(hylo_search_closed(NULL, 0));
	assert_false(hylo_search_closed(ws, 10));
	assert_true(isinf(hylo_search_cost(NULL, 0)));
	assert_true(isinf(hylo_search_cost(ws, 10)));
	assert_int_equal(hylo_search_parent(NULL, 0), HYLO_NO_NODE);
	assert_int_equal(hylo_search_parent(ws, 10), HYLO_NO_NODE);
	assert_int_equal(hylo_search_parent(ws, 5), 2);
	assert_int_equal(hylo_search_parent(ws, 2), HYLO_NO_NODE);
}

/* ---- determinism -------------------------------------------------------- */

/*
 * The same query twice, once on a workspace dirtied by a larger earlier
 * search: identical g, parent and closed marks on every node, identical
 * statistics.
 */
static void test_determinism(void **state)
{
	hylo_graph g = { 0, NULL, NULL, NULL, 1, NULL, NULL, NULL };
	hylo_budget b = no_budget();
	hylo_outcome o1, o2;
	hylo_reason r;
	chain_ctx c;
	hylo_graph big = chain_graph(&c, LONG_CHAIN);
	uint32_t v;
	int i;

	(void)state;
	rng_state = 4242;
	for (i = 0; i < 20; i++) {
		gen_graph(&tg, 1 + 5 * (i % 3));
		tg.start = 0;
		tg.goal = tg.n - 1;
		tg.h_mode = i % 2;
		tg.instrument = 0;
		tg.skip_closed = 0;
		g.n_nodes = tg.n;
		g.expand = csr_expand;
		g.heuristic = tg.h_mode ? csr_h : NULL;
		g.ctx = &tg;
		memset(ws2, i, sizeof *ws2);
		c.skip = 7;
		assert_int_equal(hylo_search_run(ws2, &big, 0, LONG_CHAIN - 1, &b, &o2, &r), HYLO_OK);
		assert_int_equal(hylo_search_run(ws, &g, 0, tg.n - 1, &b, &o1, &r), HYLO_OK);
		assert_int_equal(hylo_search_run(ws2, &g, 0, tg.n - 1, &b, &o2, &r), HYLO_OK);
		assert_int_equal(o1, o2);
		assert_memory_equal(&ws->stats, &ws2->stats, sizeof ws->stats);
		assert_int_equal(ws->n_nodes, ws2->n_nodes);
		assert_memory_equal(ws->g, ws2->g, tg.n * sizeof ws->g[0]);
		assert_memory_equal(ws->parent, ws2->parent, tg.n * sizeof ws->parent[0]);
		for (v = 0; v < tg.n; v++)
			assert_int_equal(hylo_search_closed(ws, v), hylo_search_closed(ws2, v));
	}
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test_setup(test_random_graphs, setup),
		cmocka_unit_test_setup(test_growing_heuristic, setup),
		cmocka_unit_test_setup(test_resume, setup),
		cmocka_unit_test_setup(test_decrease_key, setup),
		cmocka_unit_test_setup(test_tie_breaking, setup),
		cmocka_unit_test_setup(test_infinite_heuristic, setup),
		cmocka_unit_test_setup(test_inconsistent_heuristic, setup),
		cmocka_unit_test_setup(test_start_is_goal, setup),
		cmocka_unit_test_setup(test_lazy_evaluation, setup),
		cmocka_unit_test_setup(test_expansion_budget, setup),
		cmocka_unit_test_setup(test_time_budget, setup),
		cmocka_unit_test_setup(test_capacity_nodes, setup),
		cmocka_unit_test_setup(test_capacity_successors, setup),
		cmocka_unit_test_setup(test_bad_input, setup),
		cmocka_unit_test_setup(test_determinism, setup),
	};
	int rc;

	ws = malloc(sizeof *ws);
	ws2 = malloc(sizeof *ws2);
	if (!ws || !ws2)
		return 1;
	rc = cmocka_run_group_tests(tests, NULL, NULL);
	free(ws);
	free(ws2);
	return rc;
}
