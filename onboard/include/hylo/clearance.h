/*
 * Clearance: how far a robot's body keeps from what its mode must not touch
 * (docs/smoothing.md, "Clearance").
 *
 * A robot's body is a disc (ground, marine) or a sphere (flight, every
 * attitude) of radius R round its position. The hazards of each mode:
 *   ground:  OBSTACLE cells; wall edges (the shared edge of two adjacent
 *            GROUND cells whose heights differ by more than max_step); the
 *            map's boundary. Water is not a hazard: the shore is the
 *            amphibious robot's guard.
 *   marine:  OBSTACLE cells; the map's boundary.
 *   flight:  the terrain solid (each cell's column, its square times
 *            (-inf, height]); the map's boundary (vertical walls); the
 *            ceiling.
 *   di_neg, di_pos: none (a point).
 * A state keeps clearance c when its position is at least R + c from every
 * hazard of its mode (and lies in the mode's domain, hylo/map.h).
 */
#ifndef HYLO_CLEARANCE_H
#define HYLO_CLEARANCE_H

#include "hylo/map.h"
#include "hylo/status.h"
#include "hylo/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The clearance plans and trajectories keep beyond the body, unless the
 * caller chooses another [m]: more than the smoother's open-loop replay
 * drift, less than half a map cell of the committed scenes. */
#define HYLO_DEFAULT_MARGIN_M 0.1

/**
 * Distance from p to the nearest hazard of mode on m, exact (squares, edges
 * and columns), capped at reach (also the result when no hazard is nearer;
 * reach >= 0). 0 for a point off the map, inside an obstacle or a column,
 * or with a NaN coordinate. Cost: the cells within reach of p.
 */
hylo_real hylo_hazard_distance(const hylo_map *m, hylo_mode mode, hylo_point p, hylo_real reach);

/**
 * Shrinks the domains of hylo_domain_contains and hylo_domain_segment to the
 * points that keep r from every hazard, cell by cell (conservative: a cell
 * counts when every point of it keeps r):
 *   ground (marine): GROUND (WATER) cells with no hazard within r of the
 *            cell's square;
 *   flight:  over cell c, max(h[c] + HYLO_AIR_CLEARANCE_M, H[c] + r) <= z <=
 *            ceiling - r, where H[c] is the highest cell within r of c's
 *            square; no flight over a cell within r of the map's boundary.
 * r = 0 restores the plain domains; hylo_map_ingest sets it to 0.
 * HYLO_E_BAD_VALUE for r NaN, negative or infinite. O(cells * (r/res)^2).
 */
hylo_status hylo_map_inflate(hylo_map *m, hylo_real r, hylo_reason *why);

/** 1 when cell c is in the (inflated) domain of a class-based mode
 * (ground, marine, di_neg, di_pos), 0 otherwise. */
int hylo_map_cell_clear(const hylo_map *m, hylo_mode mode, int32_t c);

/** The lowest flight height over cell c (inflated); HUGE_VAL when the
 * cell may not be flown over. The highest: hylo_map_flight_top(m). */
hylo_real hylo_map_flight_floor(const hylo_map *m, int32_t c);
hylo_real hylo_map_flight_top(const hylo_map *m);

#ifdef __cplusplus
}
#endif

#endif
