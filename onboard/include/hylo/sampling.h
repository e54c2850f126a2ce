/*
 * The sampling options of a goal: everything besides the map that shapes
 * the roadmap. A goal carries them (hylo_goal.sampling); the planner keeps
 * the roadmap, and the edge costs on it, while goals bring equal options.
 */
#ifndef HYLO_SAMPLING_H
#define HYLO_SAMPLING_H

#include <stdint.h>
#include "hylo/config.h"
#include "hylo/types.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
	uint64_t seed;
	hylo_real spacing;              /* Poisson radius: ground, water, phase plane [m] */
	hylo_real air_spacing;          /* Poisson radius: air [m] */
	hylo_real guard_spacing;        /* guard sample spacing [m] */
	hylo_real connect_radius;       /* ground, water, phase plane [m] */
	hylo_real air_connect_radius;   /* air [m] */
	/* The grids: the first n_* entries count (n_* <= HYLO_MAX_GRID). */
	uint32_t n_speeds, n_headings, n_air_speeds;
	hylo_real speeds[HYLO_MAX_GRID];      /* [m/s] */
	hylo_real headings[HYLO_MAX_GRID];    /* [rad] */
	hylo_real air_speeds[HYLO_MAX_GRID];  /* [m/s] */
} hylo_sampling;

#ifdef __cplusplus
}
#endif

#endif
