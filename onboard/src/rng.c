#include "hylo/internal/rng.h"

/* xoshiro256** by Blackman and Vigna, seeded by splitmix64: integer-only, so
 * the sequence is the same on every platform. */

static uint64_t splitmix64(uint64_t *x)
{
	uint64_t z = (*x += 0x9e3779b97f4a7c15ULL);

	z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
	z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
	return z ^ (z >> 31);
}

static uint64_t rotl(uint64_t x, int k)
{
	return (x << k) | (x >> (64 - k));
}

void hylo_rng_seed(hylo_rng *rng, uint64_t seed)
{
	int i;

	for (i = 0; i < 4; i++)
		rng->s[i] = splitmix64(&seed);
}

uint64_t hylo_rng_u64(hylo_rng *rng)
{
	uint64_t *s = rng->s;
	uint64_t result = rotl(s[1] * 5, 7) * 9;
	uint64_t t = s[1] << 17;

	s[2] ^= s[0];
	s[3] ^= s[1];
	s[1] ^= s[2];
	s[0] ^= s[3];
	s[2] ^= t;
	s[3] = rotl(s[3], 45);
	return result;
}

hylo_real hylo_rng_uniform(hylo_rng *rng)
{
	return (hylo_real)(hylo_rng_u64(rng) >> 11) * (1.0 / 9007199254740992.0);
}

uint32_t hylo_rng_below(hylo_rng *rng, uint32_t n)
{
	/* Lemire's multiply-shift; the bias (< n / 2^32) does not matter here. */
	return (uint32_t)(((hylo_rng_u64(rng) >> 32) * (uint64_t)n) >> 32);
}
