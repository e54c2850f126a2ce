#include "hylo/internal/search.h"

#include <math.h>

/*
 * heap_pos[] holds a node's index in the heap while it is open; these
 * marks lie above any index (heap size <= HYLO_MAX_NODES < 0x7fffffff).
 * A dead node has h = +inf: it cannot reach the goal, so it is never queued.
 */
#define SEARCH_UNSEEN HYLO_NO_NODE
#define SEARCH_CLOSED HYLO_SEARCH_CLOSED
#define SEARCH_DEAD (HYLO_NO_NODE - 2u)

/* Reading the clock costs more than a cheap expansion: look every so often. */
#define SEARCH_CLOCK_EVERY 64u

/* Heap order: smaller f, then larger g (deeper, nearer the goal), then smaller id. */
static int heap_less(const hylo_search *s, uint32_t i, uint32_t j)
{
	hylo_real fi = s->heap_f[i], fj = s->heap_f[j];
	uint32_t a = s->heap[i], b = s->heap[j];

	if (fi != fj)
		return fi < fj;
	if (s->g[a] != s->g[b])
		return s->g[a] > s->g[b];
	return a < b;
}

static void heap_swap(hylo_search *s, uint32_t i, uint32_t j)
{
	uint32_t a = s->heap[i], b = s->heap[j];
	hylo_real f = s->heap_f[i];

	s->heap[i] = b;
	s->heap[j] = a;
	s->heap_f[i] = s->heap_f[j];
	s->heap_f[j] = f;
	s->heap_pos[b] = i;
	s->heap_pos[a] = j;
}

/* Two binary heaps share the sifting: the open list (heap_less, heap_swap)
 * and the deferred groups (defer_less, defer_swap). */
typedef int (*order_fn)(const hylo_search *s, uint32_t i, uint32_t j);
typedef void (*swap_fn)(hylo_search *s, uint32_t i, uint32_t j);

/* Each step halves i, so at most log2(size) steps. */
static inline void sift_up(hylo_search *s, uint32_t i, order_fn less, swap_fn swap)
{
	while (i > 0) {
		uint32_t p = (i - 1) / 2;

		if (!less(s, i, p))
			break;
		swap(s, i, p);
		i = p;
	}
}

/* Each step at least doubles i, so at most log2(n) steps. */
static inline void sift_down(hylo_search *s, uint32_t i, uint32_t n, order_fn less, swap_fn swap)
{
	for (;;) {
		uint32_t l = 2 * i + 1, r = l + 1, m = i;

		if (l < n && less(s, l, m))
			m = l;
		if (r < n && less(s, r, m))
			m = r;
		if (m == i)
			break;
		swap(s, i, m);
		i = m;
	}
}

static void heap_up(hylo_search *s, uint32_t i)
{
	sift_up(s, i, heap_less, heap_swap);
}

static void heap_down(hylo_search *s, uint32_t i)
{
	sift_down(s, i, s->heap_size, heap_less, heap_swap);
}

static void heap_push(hylo_search *s, uint32_t v, hylo_real f)
{
	uint32_t i = s->heap_size++;

	s->heap[i] = v;
	s->heap_f[i] = f;
	s->heap_pos[v] = i;
	heap_up(s, i);
}

/* Deferred groups: smaller key first, then the one whose tail is deeper (larger
 * g), then smaller tail id and group number. */
static int defer_less(const hylo_search *s, uint32_t i, uint32_t j)
{
	uint32_t a = s->defer_node[i], b = s->defer_node[j];

	if (s->defer_key[i] != s->defer_key[j])
		return s->defer_key[i] < s->defer_key[j];
	if (s->g[a] != s->g[b])
		return s->g[a] > s->g[b];
	if (a != b)
		return a < b;
	return s->defer_group[i] < s->defer_group[j];
}

static void defer_swap(hylo_search *s, uint32_t i, uint32_t j)
{
	uint32_t u = s->defer_node[i], grp = s->defer_group[i];
	hylo_real k = s->defer_key[i];

	s->defer_node[i] = s->defer_node[j];
	s->defer_group[i] = s->defer_group[j];
	s->defer_key[i] = s->defer_key[j];
	s->defer_node[j] = u;
	s->defer_group[j] = grp;
	s->defer_key[j] = k;
}

int hylo_search_defer(hylo_search *s, uint32_t u, uint32_t group, hylo_real key)
{
	uint32_t i;

	if (!s || s->n_deferred >= HYLO_MAX_DEFERRED || isnan(key))
		return 0;
	i = s->n_deferred++;
	s->defer_node[i] = u;
	s->defer_group[i] = group;
	s->defer_key[i] = key;
	s->stats.deferred++;
	sift_up(s, i, defer_less, defer_swap);
	return 1;
}

/* Removes the first deferred group into *u, *group. */
static void defer_pop(hylo_search *s, uint32_t *u, uint32_t *group)
{
	*u = s->defer_node[0];
	*group = s->defer_group[0];
	s->n_deferred--;
	if (s->n_deferred == 0)
		return;
	s->defer_node[0] = s->defer_node[s->n_deferred];
	s->defer_group[0] = s->defer_group[s->n_deferred];
	s->defer_key[0] = s->defer_key[s->n_deferred];
	sift_down(s, 0, s->n_deferred, defer_less, defer_swap);
}

static uint32_t heap_pop(hylo_search *s)
{
	uint32_t v = s->heap[0];

	s->heap_size--;
	if (s->heap_size > 0) {
		s->heap[0] = s->heap[s->heap_size];
		s->heap_f[0] = s->heap_f[s->heap_size];
		s->heap_pos[s->heap[0]] = 0;
		heap_down(s, 0);
	}
	s->heap_pos[v] = SEARCH_CLOSED;
	return v;
}

/* h(v), or 0 for Dijkstra. +inf is allowed: no path from v to the goal. */
static hylo_status heuristic(const hylo_graph *g, uint32_t v, hylo_real *h, hylo_reason *r)
{
	if (!g->heuristic) {
		*h = 0;
		return HYLO_OK;
	}
	*h = g->heuristic(g->ctx, v);
	if (isnan(*h) || *h < 0)
		return hylo_fail(r, HYLO_E_BAD_VALUE,
				 "search: heuristic at node %lu is %g, must be >= 0 and not NaN",
				 (unsigned long)v, *h);
	return HYLO_OK;
}

static void reset(hylo_search *s, uint32_t n_nodes)
{
	uint32_t i;

	s->n_nodes = n_nodes;
	s->heap_size = 0;
	s->n_deferred = 0;
	s->weight = 1;
	s->stats.expansions = 0;
	s->stats.edges_evaluated = 0;
	s->stats.pushes = 0;
	s->stats.decrease_keys = 0;
	s->stats.deferred = 0;
	s->stats.resolved = 0;
	s->n_goals = 0;
	s->n_found = 0;
	s->want = 0;
	s->within = INFINITY;
	s->rekey = 0;
	s->refresh_above = INFINITY;
	s->limit = INFINITY;
	for (i = 0; i < n_nodes; i++) {
		s->g[i] = INFINITY;
		s->parent[i] = HYLO_NO_NODE;
		s->heap_pos[i] = SEARCH_UNSEEN;
	}
}

static hylo_status check_budget(const hylo_budget *b, hylo_reason *r)
{
	if (isnan(b->time_budget_ms) || b->time_budget_ms < 0)
		return hylo_fail(r, HYLO_E_BAD_VALUE,
				 "search: time_budget_ms = %g must be >= 0", b->time_budget_ms);
	if (b->time_budget_ms > 0 && !b->clock)
		return hylo_fail(r, HYLO_E_NULL,
				 "search: time_budget_ms = %g needs a clock", b->time_budget_ms);
	return HYLO_OK;
}

static hylo_status check_args(const hylo_graph *g, uint32_t start, const uint32_t *goals,
			      uint32_t n_goals, uint32_t want, const hylo_budget *b, hylo_reason *r)
{
	uint32_t k;

	if (!g->expand)
		return hylo_fail(r, HYLO_E_NULL, "hylo_search_run: graph has no expand callback");
	if (!(g->weight >= 1) || !isfinite(g->weight))
		return hylo_fail(r, HYLO_E_BAD_VALUE, "search: weight %g must be finite and >= 1",
				 g->weight);
	if (g->n_nodes > HYLO_MAX_NODES)
		return hylo_fail(r, HYLO_E_CAP_NODES,
				 "search: %lu nodes, more than HYLO_MAX_NODES = %lu",
				 (unsigned long)g->n_nodes, (unsigned long)HYLO_MAX_NODES);
	if (n_goals < 1 || n_goals > HYLO_MAX_SEARCH_GOALS || want < 1 || want > n_goals)
		return hylo_fail(r, HYLO_E_BAD_VALUE,
				 "search: %lu goals, %lu wanted: need 1 <= wanted <= goals <= HYLO_MAX_SEARCH_GOALS = %d",
				 (unsigned long)n_goals, (unsigned long)want, HYLO_MAX_SEARCH_GOALS);
	if (start >= g->n_nodes)
		return hylo_fail(r, HYLO_E_BAD_VALUE, "search: start %lu not below n_nodes = %lu",
				 (unsigned long)start, (unsigned long)g->n_nodes);
	for (k = 0; k < n_goals; k++)
		if (goals[k] >= g->n_nodes)
			return hylo_fail(r, HYLO_E_BAD_VALUE, "search: goal %lu not below n_nodes = %lu",
					 (unsigned long)goals[k], (unsigned long)g->n_nodes);
	return check_budget(b, r);
}

/* At most HYLO_MAX_SEARCH_GOALS compares. */
static int is_goal(const hylo_search *s, uint32_t v)
{
	uint32_t k;

	for (k = 0; k < s->n_goals; k++)
		if (s->goals[k] == v)
			return 1;
	return 0;
}

/* Milliseconds since t0 into *elapsed; a broken clock stops the search. */
static hylo_status clock_elapsed(const hylo_budget *b, double t0, double *elapsed,
				 hylo_reason *r)
{
	double t = b->clock(b->clock_ctx);

	if (!isfinite(t))
		return hylo_fail(r, HYLO_E_BAD_VALUE, "search: clock returned %g", t);
	*elapsed = t - t0;
	return HYLO_OK;
}

/* Relaxes edge u -> v of cost c. Closed heads are final (consistent h). */
static hylo_status relax(hylo_search *s, const hylo_graph *g, uint32_t u, uint32_t v,
			 hylo_real c, hylo_reason *r)
{
	hylo_real ng, h;
	hylo_status st;

	if (v >= s->n_nodes)
		return hylo_fail(r, HYLO_E_BAD_VALUE,
				 "search: edge %lu -> %lu: head not below n_nodes = %lu",
				 (unsigned long)u, (unsigned long)v, (unsigned long)s->n_nodes);
	if (!isfinite(c) || c < 0)
		return hylo_fail(r, HYLO_E_BAD_COST,
				 "search: edge %lu -> %lu has cost %g, must be finite and >= 0",
				 (unsigned long)u, (unsigned long)v, c);
	if (s->heap_pos[v] == SEARCH_CLOSED || s->heap_pos[v] == SEARCH_DEAD)
		return HYLO_OK;
	ng = s->g[u] + c;
	if (!isfinite(ng))
		return hylo_fail(r, HYLO_E_BAD_COST,
				 "search: cost to node %lu via %lu overflows (%g + %g)",
				 (unsigned long)v, (unsigned long)u, s->g[u], c);
	if (!(ng < s->g[v]))
		return HYLO_OK;
	/* h is not stored: asked again on a decrease-key, so f is exact. */
	st = heuristic(g, v, &h, r);
	if (st != HYLO_OK)
		return st;
	if (isinf(h) && !is_goal(s, v)) {
		s->heap_pos[v] = SEARCH_DEAD;
		return HYLO_OK;
	}
	s->g[v] = ng;
	s->parent[v] = u;
	if (s->heap_pos[v] == SEARCH_UNSEEN) {
		heap_push(s, v, ng + s->weight * h);
		s->stats.pushes++;
	} else {
		s->heap_f[s->heap_pos[v]] = ng + s->weight * h;
		heap_up(s, s->heap_pos[v]);
		s->stats.decrease_keys++;
	}
	return HYLO_OK;
}

/* Expands node u, or resolves its deferred group (group != HYLO_NO_NODE),
 * and relaxes the successors it returns. */
static hylo_status successors(hylo_search *s, const hylo_graph *g, uint32_t u, uint32_t group,
			      hylo_reason *r)
{
	uint32_t k, n = 0;
	hylo_status st;

	/* An empty reason after a failure means the callback gave none. */
	r->text[0] = '\0';
	if (group == HYLO_NO_NODE)
		st = g->expand(g->ctx, s, u, s->heads, s->costs, HYLO_MAX_SUCCESSORS, &n, r);
	else if (g->resolve)
		st = g->resolve(g->ctx, s, u, group, s->heads, s->costs, HYLO_MAX_SUCCESSORS, &n, r);
	else
		st = hylo_fail(r, HYLO_E_NULL, "search: node %lu deferred a group, and the graph has no resolve callback",
			       (unsigned long)u);
	if (st != HYLO_OK) {
		if (r->text[0] == '\0')
			hylo_fail(r, st, "search: %s of node %lu failed: %s",
				  group == HYLO_NO_NODE ? "expand" : "resolve", (unsigned long)u,
				  hylo_status_str(st));
		return st;
	}
	if (n > HYLO_MAX_SUCCESSORS)
		return hylo_fail(r, HYLO_E_CAP_SUCCESSORS,
				 "search: node %lu has %lu successors, more than HYLO_MAX_SUCCESSORS = %lu",
				 (unsigned long)u, (unsigned long)n,
				 (unsigned long)HYLO_MAX_SUCCESSORS);
	s->stats.edges_evaluated += n;
	for (k = 0; k < n; k++) {
		st = relax(s, g, u, s->heads[k], s->costs[k], r);
		if (st != HYLO_OK)
			return st;
	}
	return HYLO_OK;
}

/* When the search ends: every wanted goal closed (found), nothing left
 * (found when some goal was), or the budget spent (found when some goal was:
 * those are final, only the later ones are missing). */
static hylo_outcome ended(const hylo_search *s, hylo_outcome none)
{
	return s->n_found > 0 ? HYLO_FOUND : none;
}

/*
 * After the heuristic grew (hylo_found_fn): the first open node's key
 * brought up to date. Returns 1 when it had to grow (the node went back into
 * the heap, or died when it can no longer reach an open goal), 0 when the key
 * is current and the node can be taken.
 */
static int stale_node(hylo_search *s, const hylo_graph *g, hylo_reason *r, hylo_status *st)
{
	uint32_t u = s->heap[0];
	hylo_real h, f;

	*st = heuristic(g, u, &h, r);
	if (*st != HYLO_OK)
		return 1;
	if (isinf(h) && !is_goal(s, u)) {
		heap_pop(s);
		s->heap_pos[u] = SEARCH_DEAD;
		return 1;
	}
	f = s->g[u] + s->weight * h;
	if (!(f > s->heap_f[0]))
		return 0;
	s->heap_f[0] = f;
	heap_down(s, 0);
	return 1;
}

/* The same for the first deferred group. */
static int stale_group(hylo_search *s, const hylo_graph *g)
{
	uint32_t u, group;
	hylo_real key = g->group_key(g->ctx, s, s->defer_node[0], s->defer_group[0]);

	if (!(key > s->defer_key[0]))
		return 0;
	defer_pop(s, &u, &group);
	/* Room: one was just taken. Not a new group for the statistics. */
	if (isfinite(key) && hylo_search_defer(s, u, group, key))
		s->stats.deferred--;
	return 1;
}

/* Lets the heuristic grow (hylo_found_fn) after goal was closed, or when
 * the keys passed the refresh level (goal HYLO_NO_NODE). */
static hylo_status heuristic_grows(hylo_search *s, const hylo_graph *g, uint32_t goal,
				   hylo_reason *r)
{
	int grew = 0;
	hylo_status st;

	/* A callback that cannot grow it (budget spent) is not asked again. */
	s->refresh_above = INFINITY;
	st = g->found(g->ctx, s, goal, &grew, r);
	s->rekey |= grew && g->heuristic;
	return st;
}

static hylo_status search_loop(hylo_search *s, const hylo_graph *g, const hylo_budget *b,
			       double t0, hylo_outcome *outcome, hylo_reason *r)
{
	hylo_status st;
	uint32_t u;

	/* Each pass closes one node or resolves one deferred group; a node
	 * defers at most HYLO_MAX_SUCCESSORS groups when it is closed. */
	for (;;) {
		hylo_real least = hylo_search_min_key(s);

		if ((s->heap_size == 0 && s->n_deferred == 0) || least > s->limit ||
		    (s->n_found > 0 && least > s->within * s->g[s->found[0]])) {
			*outcome = ended(s, HYLO_NO_PATH);
			return HYLO_OK;
		}
		if (b->max_expansions > 0 && s->stats.expansions >= b->max_expansions) {
			*outcome = ended(s, HYLO_BUDGET_EXHAUSTED);
			return HYLO_OK;
		}
		if (b->time_budget_ms > 0 && s->stats.expansions > 0 &&
		    s->stats.expansions % SEARCH_CLOCK_EVERY == 0) {
			double elapsed = 0;

			st = clock_elapsed(b, t0, &elapsed, r);
			if (st != HYLO_OK)
				return st;
			if (elapsed >= b->time_budget_ms) {
				*outcome = ended(s, HYLO_BUDGET_EXHAUSTED);
				return HYLO_OK;
			}
		}
		if (g->found && least > s->refresh_above) {
			st = heuristic_grows(s, g, HYLO_NO_NODE, r);
			if (st != HYLO_OK)
				return st;
			continue;
		}
		if (s->n_deferred > 0 && (s->heap_size == 0 || s->defer_key[0] <= s->heap_f[0])) {
			uint32_t group;

			if (s->rekey && g->group_key && stale_group(s, g))
				continue;
			defer_pop(s, &u, &group);
			s->stats.resolved++;
			st = successors(s, g, u, group, r);
			if (st != HYLO_OK)
				return st;
			continue;
		}
		if (s->rekey && stale_node(s, g, r, &st)) {
			if (st != HYLO_OK)
				return st;
			continue;
		}
		u = heap_pop(s);
		s->stats.expansions++;
		if (is_goal(s, u)) {
			s->found[s->n_found++] = u;
			if (s->n_found == s->want) {
				*outcome = HYLO_FOUND;
				return HYLO_OK;
			}
			if (g->found) {
				st = heuristic_grows(s, g, u, r);
				if (st != HYLO_OK)
					return st;
			}
			continue;
		}
		st = successors(s, g, u, HYLO_NO_NODE, r);
		if (st != HYLO_OK)
			return st;
	}
}

/* The clock's reading at the start of a run into *t0 (0 without a time budget). */
static hylo_status clock_start(const hylo_budget *budget, double *t0, hylo_reason *r)
{
	*t0 = 0;
	if (budget->time_budget_ms <= 0)
		return HYLO_OK;
	*t0 = budget->clock(budget->clock_ctx);
	if (!isfinite(*t0))
		return hylo_fail(r, HYLO_E_BAD_VALUE, "search: clock returned %g", *t0);
	return HYLO_OK;
}

static hylo_status run(hylo_search *s, const hylo_graph *g, uint32_t start, const uint32_t *goals,
		       uint32_t n_goals, uint32_t want, hylo_real within, hylo_real limit,
		       const hylo_budget *budget, hylo_outcome *outcome, hylo_reason *r)
{
	hylo_reason local;
	hylo_real h;
	double t0 = 0;
	hylo_status st;
	uint32_t k;

	/* expand may write into r, so it always gets one. */
	if (!r)
		r = &local;
	if (!s || !g || !goals || !budget || !outcome)
		return hylo_fail(r, HYLO_E_NULL, "hylo_search_run: NULL argument");
	*outcome = HYLO_NO_PATH;
	/* A failed call leaves no stale results behind. */
	reset(s, 0);
	st = check_args(g, start, goals, n_goals, want, budget, r);
	if (st == HYLO_OK && !(within >= 1))
		st = hylo_fail(r, HYLO_E_BAD_VALUE, "search: within = %g must be >= 1", within);
	if (st == HYLO_OK && isnan(limit))
		st = hylo_fail(r, HYLO_E_BAD_VALUE, "search: limit is NaN");
	if (st == HYLO_OK)
		st = clock_start(budget, &t0, r);
	if (st != HYLO_OK)
		return st;
	reset(s, g->n_nodes);
	for (k = 0; k < n_goals; k++)
		s->goals[k] = goals[k];
	s->n_goals = n_goals;
	s->want = want;
	s->within = within;
	s->limit = limit;
	s->weight = g->weight;
	st = heuristic(g, start, &h, r);
	if (st != HYLO_OK)
		return st;
	if (isinf(h) && !is_goal(s, start)) {
		s->heap_pos[start] = SEARCH_DEAD;
	} else {
		s->g[start] = 0;
		heap_push(s, start, s->weight * h);
		s->stats.pushes++;
	}
	st = search_loop(s, g, budget, t0, outcome, r);
	if (st == HYLO_OK)
		hylo_reason_clear(r);
	return st;
}

hylo_status hylo_search_run_goals(hylo_search *s, const hylo_graph *g, uint32_t start,
				  const uint32_t *goals, uint32_t n_goals, uint32_t want, hylo_real within,
				  const hylo_budget *budget, hylo_outcome *outcome, hylo_reason *r)
{
	return run(s, g, start, goals, n_goals, want, within, INFINITY, budget, outcome, r);
}

hylo_status hylo_search_run_below(hylo_search *s, const hylo_graph *g, uint32_t start,
				  uint32_t goal, hylo_real limit, const hylo_budget *budget,
				  hylo_outcome *outcome, hylo_reason *r)
{
	return run(s, g, start, &goal, 1, 1, INFINITY, limit, budget, outcome, r);
}

hylo_status hylo_search_resume(hylo_search *s, const hylo_graph *g, hylo_real limit, int grew,
			       const hylo_budget *budget, hylo_outcome *outcome, hylo_reason *r)
{
	hylo_reason local;
	double t0 = 0;
	hylo_status st;

	if (!r)
		r = &local;
	if (!s || !g || !budget || !outcome)
		return hylo_fail(r, HYLO_E_NULL, "hylo_search_resume: NULL argument");
	if (g->n_nodes != s->n_nodes || s->n_goals == 0)
		return hylo_fail(r, HYLO_E_BAD_VALUE,
				 "hylo_search_resume: no run of this graph (%lu nodes) to go on with",
				 (unsigned long)g->n_nodes);
	if (isnan(limit) || limit < s->limit)
		return hylo_fail(r, HYLO_E_BAD_VALUE,
				 "hylo_search_resume: limit %g below the last run's %g", limit, s->limit);
	st = check_budget(budget, r);
	if (st == HYLO_OK)
		st = clock_start(budget, &t0, r);
	if (st != HYLO_OK)
		return st;
	s->limit = limit;
	s->rekey |= grew && g->heuristic;
	*outcome = HYLO_NO_PATH;
	st = search_loop(s, g, budget, t0, outcome, r);
	if (st == HYLO_OK)
		hylo_reason_clear(r);
	return st;
}

hylo_status hylo_search_run(hylo_search *s, const hylo_graph *g, uint32_t start,
			    uint32_t goal, const hylo_budget *budget,
			    hylo_outcome *outcome, hylo_reason *r)
{
	return hylo_search_run_goals(s, g, start, &goal, 1, 1, INFINITY, budget, outcome, r);
}

uint32_t hylo_search_n_found(const hylo_search *s)
{
	return s ? s->n_found : 0;
}

uint32_t hylo_search_found(const hylo_search *s, uint32_t k)
{
	return s && k < s->n_found ? s->found[k] : HYLO_NO_NODE;
}

hylo_real hylo_search_min_key(const hylo_search *s)
{
	hylo_real k = INFINITY;

	if (!s)
		return k;
	if (s->heap_size > 0)
		k = s->heap_f[0];
	if (s->n_deferred > 0 && s->defer_key[0] < k)
		k = s->defer_key[0];
	return k;
}

void hylo_search_refresh_above(hylo_search *s, hylo_real key)
{
	if (s && !isnan(key))
		s->refresh_above = key;
}

hylo_real hylo_search_cost(const hylo_search *s, uint32_t v)
{
	if (!s || v >= s->n_nodes)
		return INFINITY;
	return s->g[v];
}

uint32_t hylo_search_parent(const hylo_search *s, uint32_t v)
{
	if (!s || v >= s->n_nodes)
		return HYLO_NO_NODE;
	return s->parent[v];
}

hylo_status hylo_search_path(const hylo_search *s, uint32_t goal, uint32_t *out,
			     uint32_t cap, uint32_t *n, hylo_reason *r)
{
	uint32_t len = 0, k, v;

	if (n)
		*n = 0;
	if (!s || !out || !n)
		return hylo_fail(r, HYLO_E_NULL, "hylo_search_path: NULL argument");
	if (goal >= s->n_nodes || !isfinite(s->g[goal]))
		return hylo_fail(r, HYLO_E_BAD_VALUE, "search: node %lu was not reached",
				 (unsigned long)goal);
	/* A path visits each node at most once; longer means a parent cycle. */
	for (v = goal; v != HYLO_NO_NODE && len <= s->n_nodes; v = s->parent[v]) {
		if (v >= s->n_nodes)
			break;
		len++;
	}
	if (v != HYLO_NO_NODE)
		return hylo_fail(r, HYLO_E_BAD_VALUE,
				 "search: parent chain of node %lu is broken at node %lu",
				 (unsigned long)goal, (unsigned long)v);
	if (len > cap)
		return hylo_fail(r, HYLO_E_CAP_WAYPOINTS,
				 "search: path to node %lu has %lu nodes, more than its capacity (HYLO_MAX_WAYPOINTS) cap = %lu",
				 (unsigned long)goal, (unsigned long)len, (unsigned long)cap);
	v = goal;
	for (k = len; k > 0; k--) {
		out[k - 1] = v;
		v = s->parent[v];
	}
	*n = len;
	return HYLO_OK;
}
