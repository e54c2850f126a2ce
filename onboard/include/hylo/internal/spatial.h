/*
 * A uniform bucket grid over the map's xy rectangle for radius queries on
 * points (2-D or 3-D: buckets are xy columns, distances are 3-D). Used by the
 * Poisson-disc sampler and by the roadmap's neighbour search, so that no
 * all-pairs loop is needed. Fixed memory; no allocation.
 *
 * Internal: not part of hylo's API. Installed (hylo/internal/) only because
 * struct hylo_planner embeds this module's types; its declarations may
 * change in any release. Include "hylo/planner.h" instead.
 */
#ifndef HYLO_SPATIAL_H
#define HYLO_SPATIAL_H

#include <stdint.h>
#include "hylo/config.h"
#include "hylo/status.h"
#include "hylo/types.h"

#ifdef __cplusplus
extern "C" {
#endif

#define HYLO_SPATIAL_NONE UINT32_MAX

typedef struct {
	hylo_real x0, y0;       /* lower corner of the covered rectangle */
	hylo_real cell;         /* bucket edge, >= the requested minimum */
	uint32_t nx, ny;        /* buckets along x and y; nx*ny <= HYLO_MAX_BUCKETS */
	uint32_t count;         /* points inserted */
	uint32_t head[HYLO_MAX_BUCKETS];   /* first point id of each bucket */
	uint32_t next[HYLO_MAX_POSITIONS]; /* next point id in the same bucket */
} hylo_spatial;

/**
 * Empties g and covers [x0, x1] x [y0, y1] with buckets of edge at least
 * min_cell, enlarged as needed to fit HYLO_MAX_BUCKETS. Errors:
 * HYLO_E_BAD_VALUE (non-finite, x1 < x0, min_cell <= 0).
 */
hylo_status hylo_spatial_init(hylo_spatial *g, hylo_real x0, hylo_real y0,
                              hylo_real x1, hylo_real y1, hylo_real min_cell,
                              hylo_reason *r);

/**
 * Inserts point id, whose coordinates are pts[id]. Points outside the
 * rectangle go into the nearest border bucket. Errors: HYLO_E_CAP_POSITIONS
 * when id >= HYLO_MAX_POSITIONS.
 */
hylo_status hylo_spatial_insert(hylo_spatial *g, uint32_t id, const hylo_point *pts);

/**
 * Writes to out the ids of inserted points within distance radius of q
 * (3-D Euclidean, inclusive), in increasing id order. Errors:
 * HYLO_E_CAP_SUCCESSORS when more than cap match (*n is then cap).
 */
hylo_status hylo_spatial_query(const hylo_spatial *g, const hylo_point *pts,
                               hylo_point q, hylo_real radius,
                               uint32_t *out, uint32_t cap, uint32_t *n);

/** 1 when some inserted point lies strictly closer than radius to q. */
int hylo_spatial_any_closer(const hylo_spatial *g, const hylo_point *pts,
                            hylo_point q, hylo_real radius);

#ifdef __cplusplus
}
#endif

#endif
