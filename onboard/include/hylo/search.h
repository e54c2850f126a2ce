/*
 * Best-first shortest-path search over an implicit graph: Dijkstra, or A*
 * with a consistent heuristic. Edges are produced lazily by an expand
 * callback when their tail is expanded, so edge costs are computed only for
 * expanded nodes. Binary heap with decrease-key (heap size <= nodes).
 * Deterministic: ties in f are broken by larger g, then smaller node id.
 */
#ifndef HYLO_SEARCH_H
#define HYLO_SEARCH_H

#include <stdint.h>
#include "hylo/config.h"
#include "hylo/status.h"
#include "hylo/types.h"

#define HYLO_NO_NODE UINT32_MAX

typedef struct hylo_search hylo_search;

/*
 * Successors of node u: writes up to cap (heads[i], costs[i]) pairs and their
 * number to *n. It may leave out heads that are already closed
 * (hylo_search_closed), which is what makes evaluation lazy. Costs must be
 * finite and >= 0. Returns HYLO_OK or an error, which stops the search.
 */
typedef hylo_status (*hylo_expand_fn)(void *ctx, const hylo_search *s, uint32_t u,
                                      uint32_t *heads, hylo_real *costs,
                                      uint32_t cap, uint32_t *n, hylo_reason *r);

/* Lower bound on the cost from u to the goal; must be consistent
 * (h(u) <= c(u, v) + h(v)) for A* to return the optimum. */
typedef hylo_real (*hylo_heuristic_fn)(void *ctx, uint32_t u);

/* Monotonic clock in milliseconds. */
typedef double (*hylo_clock_fn)(void *ctx);

typedef struct {
	uint32_t n_nodes;              /* node ids are 0 .. n_nodes-1, <= HYLO_MAX_NODES */
	hylo_expand_fn expand;
	hylo_heuristic_fn heuristic;   /* NULL: Dijkstra */
	void *ctx;                     /* passed to expand and heuristic */
} hylo_graph;

typedef struct {
	uint64_t max_expansions;       /* 0: no limit */
	double time_budget_ms;         /* 0: no limit; needs clock */
	hylo_clock_fn clock;           /* may be NULL when time_budget_ms is 0 */
	void *clock_ctx;
} hylo_budget;

typedef struct {
	uint64_t expansions;           /* nodes expanded (popped and closed) */
	uint64_t edges_evaluated;      /* successor costs returned by expand */
	uint64_t pushes;               /* heap insertions */
	uint64_t decrease_keys;        /* improved open nodes */
} hylo_search_stats;

struct hylo_search {
	uint32_t n_nodes;
	uint32_t heap_size;
	hylo_search_stats stats;
	hylo_real g[HYLO_MAX_NODES];         /* cost from the start; +inf when unreached */
	uint32_t parent[HYLO_MAX_NODES];     /* predecessor on the best path, HYLO_NO_NODE */
	uint32_t heap_pos[HYLO_MAX_NODES];   /* position in heap, or a closed/unseen mark */
	uint32_t heap[HYLO_MAX_NODES];       /* node ids, a binary min-heap on heap_f */
	hylo_real heap_f[HYLO_MAX_NODES];    /* f = g + h of heap[i] */
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

/** 1 when v has been expanded (its cost is final). */
int hylo_search_closed(const hylo_search *s, uint32_t v);

/** Best known cost from the start to v; +inf when v was not reached. */
hylo_real hylo_search_cost(const hylo_search *s, uint32_t v);

/** Predecessor of v on its best path; HYLO_NO_NODE for the start or unreached. */
uint32_t hylo_search_parent(const hylo_search *s, uint32_t v);

/**
 * The path start .. goal into out[0 .. *n). Errors: HYLO_E_BAD_VALUE when
 * goal was not reached, HYLO_E_CAP_WAYPOINTS when longer than cap.
 */
hylo_status hylo_search_path(const hylo_search *s, uint32_t goal, uint32_t *out,
                             uint32_t cap, uint32_t *n, hylo_reason *r);

#endif
