/*
 * Best-first shortest-path search over an implicit graph: Dijkstra, A* with
 * a consistent heuristic, or weighted A* (f = g + w h, cost at most w times
 * the optimum). Edges are produced by an expand callback when their tail is
 * expanded; expand may also defer a group of successors with a lower bound
 * of the f-value any of them could get (hylo_search_defer), and the search
 * asks for their costs (resolve) only when that bound comes first, so edge
 * costs are computed only where they could matter (lazy evaluation). Binary
 * heaps: nodes with decrease-key (size <= nodes), deferred groups (size <=
 * HYLO_MAX_DEFERRED). Deterministic: ties in f are broken by larger g, then
 * smaller node id; a deferred group comes before a node of equal key.
 *
 * Internal: not part of hylo's API. Installed (hylo/internal/) only because
 * struct hylo_planner embeds this module's types; its declarations may
 * change in any release. Include "hylo/planner.h" instead.
 */
#ifndef HYLO_SEARCH_H
#define HYLO_SEARCH_H

#include <stdint.h>
#include "hylo/config.h"
#include "hylo/status.h"
#include "hylo/types.h"

#ifdef __cplusplus
extern "C" {
#endif

#define HYLO_NO_NODE UINT32_MAX

typedef struct hylo_search hylo_search;

/*
 * Successors of node u: writes up to cap (heads[i], costs[i]) pairs and their
 * number to *n. It may leave out heads that are already closed
 * (hylo_search_closed), and it may defer groups of heads instead
 * (hylo_search_defer). Costs must be finite and >= 0. Returns HYLO_OK or an
 * error, which stops the search.
 */
typedef hylo_status (*hylo_expand_fn)(void *ctx, hylo_search *s, uint32_t u,
                                      uint32_t *heads, hylo_real *costs,
                                      uint32_t cap, uint32_t *n, hylo_reason *r);

/*
 * The successors of a group that expand of node u deferred (group is the
 * caller's own number for it), written as expand writes them. Called once
 * each time the group comes first, after u was closed; it may return some
 * of them and defer the group again with a larger key for the rest (there
 * is room: the group has just been taken out).
 */
typedef hylo_status (*hylo_resolve_fn)(void *ctx, hylo_search *s, uint32_t u, uint32_t group,
                                       uint32_t *heads, hylo_real *costs, uint32_t cap,
                                       uint32_t *n, hylo_reason *r);

/* Lower bound on the cost from u to the goal; must be consistent
 * (h(u) <= c(u, v) + h(v)) for A* to return the optimum. */
typedef hylo_real (*hylo_heuristic_fn)(void *ctx, uint32_t u);

/*
 * Called when a run towards several goals closed goal and goes on, and with
 * goal = HYLO_NO_NODE when every key has passed the level the callback set
 * with hylo_search_refresh_above: the heuristic may then grow (towards the
 * goals still open, never below what it was: it stays consistent towards
 * each of them). Sets *grew to 1 when it did; the search then checks every
 * key it takes against the heuristic's current value (a node's, and a
 * deferred group's through group_key) and puts it back when it has grown.
 */
typedef hylo_status (*hylo_found_fn)(void *ctx, hylo_search *s, uint32_t goal, int *grew,
                                     hylo_reason *r);

/* The current key of the group that expand of node u deferred: a lower bound
 * of its successors' f-values, +inf when none is wanted any more. */
typedef hylo_real (*hylo_group_key_fn)(void *ctx, hylo_search *s, uint32_t u, uint32_t group);

typedef struct {
	uint32_t n_nodes;              /* node ids are 0 .. n_nodes-1, <= HYLO_MAX_NODES */
	hylo_expand_fn expand;
	hylo_resolve_fn resolve;       /* NULL when expand never defers */
	hylo_heuristic_fn heuristic;   /* NULL: Dijkstra */
	hylo_real weight;              /* f = g + weight * h, >= 1 (1: the optimum) */
	void *ctx;                     /* passed to expand, resolve and heuristic */
	hylo_found_fn found;           /* NULL: the heuristic never changes */
	hylo_group_key_fn group_key;   /* with found: re-checks deferred groups */
} hylo_graph;

typedef struct {
	uint64_t max_expansions;       /* 0: no limit */
	double time_budget_ms;         /* 0: no limit; needs clock */
	hylo_clock_fn clock;           /* may be NULL when time_budget_ms is 0 */
	void *clock_ctx;
} hylo_budget;

typedef struct {
	uint64_t expansions;           /* nodes expanded (popped and closed) */
	uint64_t edges_evaluated;      /* successor costs returned by expand and resolve */
	uint64_t pushes;               /* heap insertions */
	uint64_t decrease_keys;        /* improved open nodes */
	uint64_t deferred;             /* groups deferred by expand, or again by resolve */
	uint64_t resolved;             /* of those, resolved (the rest never came first) */
} hylo_search_stats;

struct hylo_search {
	uint32_t n_nodes;
	uint32_t heap_size;
	hylo_search_stats stats;
	hylo_real g[HYLO_MAX_NODES];         /* cost from the start; +inf when unreached */
	uint32_t parent[HYLO_MAX_NODES];     /* predecessor on the best path, HYLO_NO_NODE */
	uint32_t heap_pos[HYLO_MAX_NODES];   /* position in heap, or a closed/unseen mark */
	uint32_t heap[HYLO_MAX_NODES];       /* node ids, a binary min-heap on heap_f */
	hylo_real heap_f[HYLO_MAX_NODES];    /* f = g + w h of heap[i] */
	uint32_t n_deferred;                 /* deferred groups waiting: a min-heap on defer_key */
	uint32_t defer_node[HYLO_MAX_DEFERRED];
	uint32_t defer_group[HYLO_MAX_DEFERRED];
	hylo_real defer_key[HYLO_MAX_DEFERRED];
	hylo_real weight;                    /* of the current run */
	uint32_t goals[HYLO_MAX_SEARCH_GOALS];  /* of the current run */
	uint32_t n_goals, want;
	hylo_real within;                    /* later goals: at most within * the first's cost */
	uint32_t found[HYLO_MAX_SEARCH_GOALS];  /* goals closed, in order of cost */
	uint32_t n_found;
	int rekey;                           /* the heuristic grew: keys are checked when taken */
	hylo_real refresh_above;             /* found(HYLO_NO_NODE) once every key is above; +inf: never */
	hylo_real limit;                     /* the run stops once every key is above; +inf: never */
	uint32_t heads[HYLO_MAX_SUCCESSORS]; /* scratch for expand */
	hylo_real costs[HYLO_MAX_SUCCESSORS];
};

/**
 * Runs the search from start to goal. On HYLO_OK, *outcome says whether the
 * goal was reached (HYLO_FOUND: hylo_search_cost(s, goal) is optimal),
 * unreachable, or the budget ran out. Errors: HYLO_E_NULL,
 * HYLO_E_BAD_VALUE (start/goal out of range), HYLO_E_CAP_NODES,
 * HYLO_E_CAP_SUCCESSORS, HYLO_E_BAD_COST (negative or non-finite cost),
 * or whatever expand returned. No allocation; O((V + E) log V).
 */
hylo_status hylo_search_run(hylo_search *s, const hylo_graph *g, uint32_t start,
                            uint32_t goal, const hylo_budget *budget,
                            hylo_outcome *outcome, hylo_reason *r);

/**
 * The same search towards several goals (goals[0 .. n_goals), at most
 * HYLO_MAX_SEARCH_GOALS): it goes on after the first goal is closed until
 * want of them are (1 <= want <= n_goals), or nothing is left to expand,
 * or nothing left could reach a goal at most within (>= 1, +inf: any) times
 * the first one's cost.
 * Each closed goal's cost is optimal (A*: the heuristic must be consistent
 * towards every goal). *outcome is HYLO_FOUND when at least one goal was
 * closed (hylo_search_n_found, hylo_search_found), else HYLO_NO_PATH or
 * HYLO_BUDGET_EXHAUSTED. Errors as hylo_search_run. No allocation.
 */
hylo_status hylo_search_run_goals(hylo_search *s, const hylo_graph *g, uint32_t start,
                                  const uint32_t *goals, uint32_t n_goals, uint32_t want,
                                  hylo_real within, const hylo_budget *budget, hylo_outcome *outcome,
                                  hylo_reason *r);

/**
 * hylo_search_run that stops (HYLO_NO_PATH unless the goal was closed) once
 * every key is above limit: the nodes closed so far are those whose f is at
 * most limit, each with its optimal cost (A*, consistent heuristic).
 * hylo_search_resume goes on from there. Errors as hylo_search_run.
 */
hylo_status hylo_search_run_below(hylo_search *s, const hylo_graph *g, uint32_t start,
                                  uint32_t goal, hylo_real limit, const hylo_budget *budget,
                                  hylo_outcome *outcome, hylo_reason *r);

/**
 * Goes on with the last run of s, on the same graph, up to limit (+inf: to
 * the end), after it stopped at its limit or its budget. grew = 1 when the
 * heuristic has grown since (still consistent): the keys are then checked
 * as they are taken (hylo_found_fn). Errors as hylo_search_run.
 */
hylo_status hylo_search_resume(hylo_search *s, const hylo_graph *g, hylo_real limit, int grew,
                               const hylo_budget *budget, hylo_outcome *outcome, hylo_reason *r);

/** Goals closed by the last run, and the k-th of them in the order they were
 * closed, i.e. of their costs (HYLO_NO_NODE beyond). */
uint32_t hylo_search_n_found(const hylo_search *s);
uint32_t hylo_search_found(const hylo_search *s, uint32_t k);

/**
 * For expand of node u (or resolve of one of its groups): defers a group of
 * u's successors (group: the caller's number, passed back to resolve) whose
 * f-values will all be at least key. Returns 1, or 0 when HYLO_MAX_DEFERRED
 * groups are waiting already: then expand must return those successors
 * itself. No allocation.
 */
int hylo_search_defer(hylo_search *s, uint32_t u, uint32_t group, hylo_real key);

/** The least key still waiting (node or deferred group), +inf when none: a
 * lower bound of the optimum while an A* (w = 1) run is under way or after
 * it ran out of budget. */
hylo_real hylo_search_min_key(const hylo_search *s);

/* For a found callback: call it again (goal HYLO_NO_NODE) once every key is
 * above `key`, where its heuristic is only a rough bound. Each call of the
 * callback clears it. */
void hylo_search_refresh_above(hylo_search *s, hylo_real key);

/* heap_pos[v] of a node expanded (closed): above any heap index. */
#define HYLO_SEARCH_CLOSED (HYLO_NO_NODE - 1u)

/** 1 when v has been expanded (its cost is final). Inline: expand callbacks
 * ask it for every head. */
static inline int hylo_search_closed(const hylo_search *s, uint32_t v)
{
	return s && v < s->n_nodes && s->heap_pos[v] == HYLO_SEARCH_CLOSED;
}

/** Sets bit in open[c] for every c < n whose node first + c is not closed;
 * 1 when any is. The callbacks' row-at-a-time form of hylo_search_closed. */
static inline int hylo_search_mark_open(const hylo_search *s, uint32_t first, uint32_t n,
					uint8_t bit, uint8_t *open)
{
	uint32_t c;
	int any = 0;

	for (c = 0; c < n; c++)
		if (!hylo_search_closed(s, first + c)) {
			open[c] |= bit;
			any = 1;
		}
	return any;
}

/** Best known cost from the start to v; +inf when v was not reached. */
hylo_real hylo_search_cost(const hylo_search *s, uint32_t v);

/** The same for v < n_nodes, unchecked and inline: expand callbacks ask it
 * for every head, to leave out those the edge would not improve. */
static inline hylo_real hylo_search_cost_of(const hylo_search *s, uint32_t v)
{
	return s->g[v];
}

/** Predecessor of v on its best path; HYLO_NO_NODE for the start or unreached. */
uint32_t hylo_search_parent(const hylo_search *s, uint32_t v);

/**
 * The path start .. goal into out[0 .. *n). Errors: HYLO_E_BAD_VALUE when
 * goal was not reached, HYLO_E_CAP_WAYPOINTS when longer than cap.
 */
hylo_status hylo_search_path(const hylo_search *s, uint32_t goal, uint32_t *out,
                             uint32_t cap, uint32_t *n, hylo_reason *r);

#ifdef __cplusplus
}
#endif

#endif
