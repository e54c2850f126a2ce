/*
 * Seeded pseudo-random numbers (xoshiro256**, seeded through splitmix64):
 * the same seed gives the same sequence on every platform.
 *
 * Internal: not part of hylo's API. Installed (hylo/internal/) only because
 * struct hylo_planner embeds this module's types; its declarations may
 * change in any release. Include "hylo/planner.h" instead.
 */
#ifndef HYLO_RNG_H
#define HYLO_RNG_H

#include <stdint.h>
#include "hylo/types.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
	uint64_t s[4];
} hylo_rng;

/* Seeds the generator; any seed, 0 included, is valid. */
void hylo_rng_seed(hylo_rng *rng, uint64_t seed);

/* Next 64 random bits. */
uint64_t hylo_rng_u64(hylo_rng *rng);

/* Uniform in [0, 1), 53 random bits. */
hylo_real hylo_rng_uniform(hylo_rng *rng);

/* Uniform integer in [0, n); n > 0. */
uint32_t hylo_rng_below(hylo_rng *rng, uint32_t n);

#ifdef __cplusplus
}
#endif

#endif
