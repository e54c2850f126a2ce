/*
 * Poisson-disc sampling of a mode's domain (Bridson's algorithm, seeded) and
 * sampling of guard surfaces.
 *
 * Guarantees, for a domain sample set S with radius r:
 *   - separation: every two points of S are at least r apart;
 *   - maximality: every point of the domain is within 2r of a point of S.
 * Bridson's active-list growth alone does not guarantee maximality (and only
 * reaches the connected component it starts in), so it is seeded from a
 * deterministic sweep over candidate points covering every domain cell: any
 * candidate farther than r from all samples starts a new Bridson growth.
 * Same map, mode, radius and seed give the same samples on every platform.
 *
 * Internal: not part of hylo's API. Installed (hylo/internal/) only because
 * struct hylo_planner embeds this module's types; its declarations may
 * change in any release. Include "hylo/planner.h" instead.
 */
#ifndef HYLO_POISSON_H
#define HYLO_POISSON_H

#include <stdint.h>
#include "hylo/config.h"
#include "hylo/map.h"
#include "hylo/internal/rng.h"
#include "hylo/internal/spatial.h"
#include "hylo/status.h"
#include "hylo/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Candidates Bridson draws around an active sample before retiring it. */
#define HYLO_POISSON_TRIES 30

/* Scratch memory of the sampler, reused for every call. */
typedef struct {
	hylo_spatial grid;
	uint32_t active[HYLO_MAX_POSITIONS];
} hylo_poisson_ws;

/**
 * Poisson-disc samples of the domain of mode (map.h) with radius r, written
 * to out[0 .. *n). Ground and water samples get z = terrain height; flight
 * samples are 3-D; di samples are (p, v, 0).
 * Errors: HYLO_E_NULL, HYLO_E_BAD_VALUE (r not finite and > 0, invalid mode),
 * HYLO_E_CAP_POSITIONS when more than cap samples are needed,
 * HYLO_E_CAP_BUCKETS. Does not allocate.
 */
hylo_status hylo_poisson_sample(const hylo_map *m, hylo_mode mode, hylo_real r,
                                hylo_rng *rng, hylo_poisson_ws *ws,
                                hylo_point *out, uint32_t cap, uint32_t *n,
                                hylo_reason *reason);

/* Guard surfaces. */
typedef enum {
	/* Ambot: points on the common edge of a GROUND cell and a WATER cell
	 * that lie in both domains (with hylo_map_inflate's clearance: both
	 * cells clear); z = the ground cell's height. */
	HYLO_GUARD_SHORELINE = 0,
	/* Drivocopter: points of the ground domain whose twin
	 * (x, y, z + HYLO_TAKEOFF_HEIGHT_M) lies in the flight domain (both with
	 * hylo_map_inflate's clearance); z = ground height. */
	HYLO_GUARD_TAKEOFF = 1,
	/* Double integrator: points (0, v, 0) of the phase plane (both domains). */
	HYLO_GUARD_DI = 2
} hylo_guard_kind;

/**
 * Samples the guard of the given kind with spacing s: samples at least s
 * apart, and every guard point within 2s of a sample (over a fine candidate
 * set on the guard, visited in a seeded random order). Output and errors as
 * hylo_poisson_sample.
 */
hylo_status hylo_guard_sample(const hylo_map *m, hylo_guard_kind kind, hylo_real s,
                              hylo_rng *rng, hylo_poisson_ws *ws,
                              hylo_point *out, uint32_t cap, uint32_t *n,
                              hylo_reason *reason);

#ifdef __cplusplus
}
#endif

#endif
