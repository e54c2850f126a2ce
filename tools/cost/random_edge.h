/*
 * Seeded random edges within a model's training range, for measuring and
 * testing its envelope (tools/cost/envelope_tightness.c,
 * tests/export/test_envelope_models.c). A 64-bit LCG seeded through
 * rng_state: the same edges on every platform.
 */
#ifndef HYLO_TOOLS_RANDOM_EDGE_H
#define HYLO_TOOLS_RANDOM_EDGE_H

#include <math.h>
#include <stdint.h>

#include "hylo/svr.h"
#include "hylo/types.h"

#define PI 3.14159265358979323846

/* Random: positions, headings and speeds at random; aligned (ground,
 * marine: the goal straight ahead with the start's heading; flight: both
 * velocities along the horizontal displacement); turning (the goal, or
 * flight's start velocity, within 10 degrees of straight behind). */
enum edge_kind { EDGE_RANDOM, EDGE_ALIGNED, EDGE_TURNING };

static uint64_t rng_state;

static inline double uniform(double lo, double hi)
{
	rng_state = rng_state * 6364136223846793005ULL + 1442695040888963407ULL;
	return lo + (hi - lo) * (double)(rng_state >> 11) * 0x1.0p-53;
}

static inline double node(const hylo_svr_envelope *e)
{
	uint32_t i = (uint32_t)uniform(0, e->n_v);

	return e->v_min + (i < e->n_v ? i : e->n_v - 1) * e->v_step;
}

static inline void random_edge(const hylo_svr_model *m, hylo_mode mode, enum edge_kind kind,
			       double *t, double *h)
{
	double r = m->max_distance_m, s1 = node(m->envelope), s2 = node(m->envelope);

	if (mode == HYLO_MODE_FLIGHT) {
		double dh, dz, phi = uniform(-PI, PI), a1 = uniform(-PI, PI), a2 = uniform(-PI, PI);
		int k;

		do {
			dh = uniform(0, r);
			dz = uniform(-r, r);
		} while (dh * dh + dz * dz > r * r);
		if (kind == EDGE_ALIGNED)
			a1 = a2 = phi;
		else if (kind == EDGE_TURNING)
			a1 = phi + PI + uniform(-PI / 18, PI / 18);
		for (k = 0; k < 3; k++)
			t[k] = uniform(-50, 50);
		t[3] = s1 * cos(a1), t[4] = s1 * sin(a1), t[5] = 0;
		h[0] = t[0] + dh * cos(phi), h[1] = t[1] + dh * sin(phi), h[2] = t[2] + dz;
		h[3] = s2 * cos(a2), h[4] = s2 * sin(a2), h[5] = 0;
	} else {
		double d = uniform(0, r), bearing = uniform(-PI, PI), turn = uniform(-PI, PI);

		if (kind == EDGE_ALIGNED)
			bearing = turn = 0;
		else if (kind == EDGE_TURNING)
			bearing = PI + uniform(-PI / 18, PI / 18);
		t[0] = uniform(-50, 50), t[1] = uniform(-50, 50), t[2] = s1, t[3] = uniform(-PI, PI);
		h[0] = t[0] + d * cos(t[3] + bearing), h[1] = t[1] + d * sin(t[3] + bearing);
		h[2] = s2, h[3] = t[3] + turn;
	}
}

#endif
