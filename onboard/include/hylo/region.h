/*
 * The region a cost model was trained on (onboard/models/README.md,
 * "Trained region"): the training pairs' displacement (max_distance_m),
 * their states' speed (speed_min_mps .. speed_max_mps, hylo_state_speed)
 * and every other sampled coordinate the training draw restricted
 * (state_bounded, state_min, state_max; e.g. flight vz: level velocities
 * only). A model's cost outside it is an extrapolation: the planner refuses
 * a start or goal outside it and never evaluates an edge outside it.
 * Bounds hold to a rounding slack of 1e-9 relative (1e-9 absolute for a
 * bound at 0). No allocation, no state; safe in a control loop.
 */
#ifndef HYLO_REGION_H
#define HYLO_REGION_H

#include <stddef.h>
#include "hylo/svr.h"
#include "hylo/types.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum {
	HYLO_REGION_INSIDE = 0,
	HYLO_REGION_SPEED,      /* a state's speed (hylo_state_speed) is outside [lo, hi] */
	HYLO_REGION_COORD,      /* a state's sampled coordinate `coord` is outside [lo, hi] */
	HYLO_REGION_DISTANCE    /* the displacement (hylo_edge_distance) is beyond hi */
} hylo_region_part;

/* What lies outside the region, and where. */
typedef struct {
	hylo_region_part part;
	unsigned end;           /* edges: 0 the tail, 1 the head */
	unsigned coord;         /* HYLO_REGION_COORD: the coordinate's index in x^s */
	hylo_real value;        /* the speed, coordinate or displacement */
	hylo_real lo, hi;       /* its trained range (DISTANCE: [0, max_distance_m]) */
} hylo_region_miss;

/** 1 when state xs of mode (sampled coordinates) lies in m's trained
 * region (its speed and bounded coordinates), else 0 with what lies
 * outside in *miss (may be NULL). NaN lies outside. */
int hylo_region_state(const hylo_svr_model *m, hylo_mode mode, const hylo_real *xs,
                      hylo_region_miss *miss);

/** 1 when both ends of the edge tail -> head lie in m's trained region and
 * its displacement is within max_distance_m (0: any), else 0 with the first
 * thing outside (the displacement, then the tail, then the head) in *miss
 * (may be NULL). */
int hylo_region_edge(const hylo_svr_model *m, hylo_mode mode, const hylo_real *tail,
                     const hylo_real *head, hylo_region_miss *miss);

/** The displacement a model's max_distance_m bounds: flight |p2 - p1| in
 * 3-D; ground, marine the horizontal distance; double integrator the
 * distance in the phase plane (p, v). 0 for an invalid mode. */
hylo_real hylo_edge_distance(hylo_mode mode, const hylo_real *tail, const hylo_real *head);

/** Name ("px", "vz", "theta", "p", ...) and unit ("m", "m/s", "rad") of
 * sampled coordinate k of mode; "?" when there is none. Never NULL. */
const char *hylo_coord_name(hylo_mode mode, unsigned k);
const char *hylo_coord_unit(hylo_mode mode, unsigned k);

/** Writes what *miss says into buf (size n, always terminated), e.g.
 * "vz = -2.7 m/s is outside the trained range [0, 0] m/s". */
void hylo_region_describe(hylo_mode mode, const hylo_region_miss *miss, char *buf, size_t n);

#ifdef __cplusplus
}
#endif

#endif
