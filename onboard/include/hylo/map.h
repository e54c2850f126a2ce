/*
 * Map ingestion and the per-mode domains.
 *
 * The map is a grid of square cells; cell (ix, iy) covers
 * [ox + ix*res, ox + (ix+1)*res] x [oy + iy*res, oy + (iy+1)*res] and is
 * stored at index iy*nx + ix. Domains are closed sets:
 *   ground:  the union of GROUND cells (z is ignored); a segment must also
 *            not cross a height step larger than max_step between the
 *            consecutive ground cells it passes through;
 *   marine:  the union of WATER cells (z is ignored);
 *   flight:  points (x, y, z) over the map with
 *            h(x, y) + HYLO_AIR_CLEARANCE_M <= z <= ceiling, where on a cell
 *            boundary h is the largest height of the touching cells;
 *   di_neg:  non-OBSTACLE cells with x <= 0 (x is p, y is v);
 *   di_pos:  non-OBSTACLE cells with x >= 0.
 * Points outside the map's rectangle belong to no domain. hylo_map_inflate
 * (hylo/clearance.h) shrinks the ground, marine and flight domains to the
 * points that keep a clearance from every hazard.
 */
#ifndef HYLO_MAP_H
#define HYLO_MAP_H

#include <stdint.h>
#include "hylo/config.h"
#include "hylo/status.h"
#include "hylo/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Terrain classes; values as map_t.TERRAIN_*. */
typedef enum {
	HYLO_TERRAIN_OBSTACLE = 0,
	HYLO_TERRAIN_GROUND = 1,
	HYLO_TERRAIN_WATER = 2
} hylo_terrain;

/* Flight positions keep at least this height above the terrain [m]. */
#ifndef HYLO_AIR_CLEARANCE_M
#define HYLO_AIR_CLEARANCE_M 0.5
#endif

/* A takeoff/landing point's flight twin hovers this high above it [m]
 * (docs/models.md section 6). */
#define HYLO_TAKEOFF_HEIGHT_M 1.0

/* The caller's view of a decoded map_t. Nothing is copied until
 * hylo_map_ingest; the arrays may be freed afterwards. */
typedef struct {
	int64_t map_id;
	const char *robot;        /* NUL-terminated robot name */
	int32_t nx, ny;           /* cells along x and y */
	hylo_real resolution;     /* cell edge [m], > 0 */
	hylo_real origin_x, origin_y; /* corner of cell (0, 0) [m] */
	hylo_real ceiling;        /* flight ceiling [m] */
	hylo_real max_step;       /* largest drivable height step [m], >= 0 */
	int32_t n_cells;          /* must equal nx * ny */
	const int8_t *terrain;    /* n_cells terrain classes */
	const float *height;      /* n_cells surface heights [m] */
} hylo_map_view;

/* An ingested map, held in the caller's workspace. */
typedef struct {
	int64_t map_id;
	char robot[HYLO_NAME_LEN];
	int32_t nx, ny;
	hylo_real resolution, origin_x, origin_y, ceiling, max_step;
	uint32_t n_ground, n_water, n_obstacle; /* cell counts per class */
	int8_t terrain[HYLO_MAX_CELLS];
	float height[HYLO_MAX_CELLS];
	/* hylo_map_inflate (hylo/clearance.h): the clearance r the domains keep
	 * (0: the plain domains), per cell whether it is a clear ground or
	 * water cell, and the lowest flight height over it. */
	hylo_real inflation;
	uint8_t clear[HYLO_MAX_CELLS];
	hylo_real floor[HYLO_MAX_CELLS];
} hylo_map;

/**
 * Validates v and copies it into m. Errors (m is left marked empty, map_id 0,
 * nx = ny = 0): HYLO_E_NULL, HYLO_E_BAD_MAP (non-positive or inconsistent
 * sizes, resolution not finite and > 0, unknown terrain class, robot name
 * missing or longer than HYLO_NAME_LEN - 1), HYLO_E_BAD_VALUE (NaN or
 * infinite height, origin, ceiling or step), HYLO_E_CAP_CELLS. The reason
 * names the offending field and, for a cell, its (ix, iy).
 * Does not allocate; O(n_cells).
 */
hylo_status hylo_map_ingest(hylo_map *m, const hylo_map_view *v, hylo_reason *r);

/** Terrain height at (x, y): the height of the cell containing the point
 * (on a boundary, the cell with the lower index); 0 outside the map. */
hylo_real hylo_map_height(const hylo_map *m, hylo_real x, hylo_real y);

/** 1 when p lies in the closed domain of mode (see the top of this file),
 * 0 otherwise (also for an invalid mode or a NaN coordinate). */
int hylo_domain_contains(const hylo_map *m, hylo_mode mode, hylo_point p);

/** 1 when every point of the straight segment a-b lies in the domain of mode
 * (exact: it walks the cells the segment passes through, no sampling), and
 * for ground the height rule holds. 0 otherwise. Bounded: O(nx + ny). */
int hylo_domain_segment(const hylo_map *m, hylo_mode mode, hylo_point a, hylo_point b);

/*
 * The exact walk of a straight segment over a grid's cells, in grid units
 * (u = (x - origin_x) / resolution, v likewise: cell (ix, iy) is
 * [ix, ix + 1] x [iy, iy + 1]): hylo_domain_segment's, and the smoother's
 * wall crossings (trainer/map_guards.cpp) walk with it. The segment
 * a + t (b - a), t in [0, 1], is cut at every grid line it crosses into
 * pieces, each in one cell, or, when it runs along a grid line, on the line
 * between two cells.
 */
/** The cell columns lo..hi touching grid coordinate u in [0, n] (rows: v,
 * ny): one, or the two either side of a grid line; returns how many. */
int hylo_cell_span(hylo_real u, int32_t n, int32_t *lo, int32_t *hi);

typedef struct {
	hylo_real t0, t1;        /* the piece: t in [t0, t1], t0 < t1 */
	int32_t x0, x1, y0, y1;  /* its cells: columns x0..x1, rows y0..y1 */
	/* Where it ends, unless t1 = 1: on the grid line u = cross_u, v =
	 * cross_v, or both at a vertex (-1: not on one), a point touching the
	 * cells of columns ex0..ex1 and rows ey0..ey1. */
	int32_t cross_u, cross_v;
	int32_t ex0, ex1, ey0, ey1;
} hylo_cell_piece;

typedef struct {
	int32_t nx, ny;
	hylo_real ua, va, du, dv;
	hylo_real t;             /* where the walk is: 1 once it has reached b */
	hylo_real tx, ty, kx, ky, dkx, dky;
	int32_t left;            /* pieces it may still take */
} hylo_cell_walk;

/** Starts the walk of a -> b = (ua, va) -> (ub, vb) over nx x ny cells. A
 * segment of zero length has no pieces (its walk is complete at once). */
void hylo_cell_walk_start(hylo_cell_walk *w, int32_t nx, int32_t ny, hylo_real ua, hylo_real va, hylo_real ub,
			  hylo_real vb);

/** The next piece into p: 1, or 0 when the walk has reached b or the next
 * piece lies outside [0, nx] x [0, ny] (a segment leaving the grid; one
 * starting outside it, or an empty grid, has no pieces). Bounded: nx + ny
 * + 4 pieces; t < 1 after the last one says the walk did not reach b.
 * Does not allocate. */
int hylo_cell_walk_next(hylo_cell_walk *w, hylo_cell_piece *p);

#ifdef __cplusplus
}
#endif

#endif
