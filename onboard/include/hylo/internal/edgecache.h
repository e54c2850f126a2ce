/*
 * The edge-cost cache: costs of evaluated edges, kept for as long as the
 * roadmap is (edge costs do not depend on the goal, so a second goal on the
 * same map evaluates only edges the first did not). Edges are grouped by
 * (tail node, neighbour position): group base[u] + k holds the costs from
 * node u to every combination of the k-th neighbour in u's position's
 * adjacency list, NaN until evaluated, +inf when infeasible. Fixed memory:
 * when the pool is full, further costs are simply not kept (counted).
 *
 * Internal: not part of hylo's API. Installed (hylo/internal/) only because
 * struct hylo_planner embeds this module's types; its declarations may
 * change in any release. Include "hylo/planner.h" instead.
 */
#ifndef HYLO_EDGECACHE_H
#define HYLO_EDGECACHE_H

#include <stdint.h>
#include "hylo/config.h"
#include "hylo/internal/roadmap.h"
#include "hylo/types.h"

#ifdef __cplusplus
extern "C" {
#endif

#define HYLO_NO_SLOT UINT32_MAX

typedef struct {
	int enabled;                          /* 0: the roadmap has more groups than HYLO_MAX_GROUPS */
	uint32_t n_groups;                    /* groups of the current roadmap */
	uint32_t n_used;                      /* costs of the pool in use */
	uint64_t hits;                        /* costs found in the cache */
	uint64_t stored;                      /* costs stored */
	uint64_t dropped;                     /* costs not kept: the pool was full */
	uint32_t group_base[HYLO_MAX_NODES];  /* first group of each node */
	uint32_t slot[HYLO_MAX_GROUPS];       /* offset of each group in cost[], or HYLO_NO_SLOT */
	hylo_real cost[HYLO_MAX_CACHED_COSTS];
} hylo_edge_cache;

/** Empties the cache and lays out its groups for roadmap rm (built). O(nodes + groups); no allocation. */
void hylo_edge_cache_reset(hylo_edge_cache *c, const hylo_roadmap *rm);

/**
 * The costs of group (node u, neighbour k of its position): an array of the
 * neighbour's n_combos entries (NaN: not evaluated), or NULL when the group
 * has none and create is 0, or there is no room (then nothing is kept).
 * u must be a node of rm and k below its position's neighbour count.
 */
hylo_real *hylo_edge_cache_group(hylo_edge_cache *c, const hylo_roadmap *rm, uint32_t u,
                                 uint32_t k, int create);

#ifdef __cplusplus
}
#endif

#endif
