#include "hylo/internal/edgecache.h"

#include <math.h>

void hylo_edge_cache_reset(hylo_edge_cache *c, const hylo_roadmap *rm)
{
	uint32_t i, k, u;
	uint64_t n = 0;

	c->enabled = 0;
	c->n_groups = 0;
	c->n_used = 0;
	c->hits = c->stored = c->dropped = 0;
	for (i = 0; i < rm->n_positions; i++) {
		const hylo_position *p = &rm->pos[i];
		uint32_t deg = p->adj_end - p->adj_begin;

		for (k = 0; k < p->n_combos; k++) {
			u = p->node_base + k;
			if (n + deg > HYLO_MAX_GROUPS)
				return;
			c->group_base[u] = (uint32_t)n;
			n += deg;
		}
	}
	for (k = 0; k < (uint32_t)n; k++)
		c->slot[k] = HYLO_NO_SLOT;
	c->n_groups = (uint32_t)n;
	c->enabled = 1;
}

hylo_real *hylo_edge_cache_group(hylo_edge_cache *c, const hylo_roadmap *rm, uint32_t u,
				 uint32_t k, int create)
{
	uint32_t g, i, n, m;

	if (!c->enabled || u >= rm->n_nodes)
		return 0;
	g = c->group_base[u] + k;
	if (c->slot[g] != HYLO_NO_SLOT)
		return &c->cost[c->slot[g]];
	if (!create)
		return 0;
	i = rm->node_pos[u];
	n = rm->pos[rm->adjacency[rm->pos[i].adj_begin + k]].n_combos;
	if (n > HYLO_MAX_CACHED_COSTS - c->n_used)
		return 0;
	c->slot[g] = c->n_used;
	for (m = 0; m < n; m++)
		c->cost[c->n_used + m] = NAN;
	c->n_used += n;
	return &c->cost[c->slot[g]];
}
