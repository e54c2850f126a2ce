/*
 * Poisson-disc sampling (onboard/src/poisson.c) on random domains, convex and
 * not (blobs, rings, corridors, noise): separation (no two samples closer
 * than r), maximality (no domain point farther than 2r from a sample, checked
 * on a dense grid of domain points), samples inside their domain, guard
 * samples on their guard, determinism, and the positions capacity exactly at
 * and one past its limit.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hylo/internal/poisson.h"

#define CAP 4096

static hylo_map *map;
static hylo_poisson_ws *ws;
static hylo_point pts[CAP], pts2[CAP];

/* A random map of nx x ny cells: ground with obstacle and water features. */
static void random_map(uint64_t seed, const char *robot, int kind)
{
	static int8_t terrain[64 * 64];
	static float height[64 * 64];
	hylo_map_view v;
	hylo_rng rng;
	hylo_reason r;
	int32_t nx, ny, ix, iy, k;

	hylo_rng_seed(&rng, seed);
	nx = 12 + (int32_t)hylo_rng_below(&rng, 30);
	ny = 12 + (int32_t)hylo_rng_below(&rng, 30);
	for (iy = 0; iy < ny; iy++)
		for (ix = 0; ix < nx; ix++) {
			terrain[iy * nx + ix] = HYLO_TERRAIN_GROUND;
			height[iy * nx + ix] = 0;
		}
	if (kind == 0) {          /* blobs of obstacle and water */
		for (k = 0; k < 6; k++) {
			int32_t cx = (int32_t)hylo_rng_below(&rng, (uint32_t)nx);
			int32_t cy = (int32_t)hylo_rng_below(&rng, (uint32_t)ny);
			int32_t rad = 2 + (int32_t)hylo_rng_below(&rng, 5);
			int8_t cls = k % 2 ? HYLO_TERRAIN_WATER : HYLO_TERRAIN_OBSTACLE;

			for (iy = 0; iy < ny; iy++)
				for (ix = 0; ix < nx; ix++)
					if ((ix - cx) * (ix - cx) + (iy - cy) * (iy - cy) <= rad * rad)
						terrain[iy * nx + ix] = cls;
		}
	} else if (kind == 1) {   /* a ring of ground in water, an obstacle core */
		for (iy = 0; iy < ny; iy++)
			for (ix = 0; ix < nx; ix++) {
				double d = hypot(ix - nx / 2.0, iy - ny / 2.0);

				terrain[iy * nx + ix] = d < 3 ? HYLO_TERRAIN_OBSTACLE
						       : d < 6 ? HYLO_TERRAIN_GROUND : HYLO_TERRAIN_WATER;
			}
	} else if (kind == 2) {   /* an L-shaped corridor through obstacle */
		for (iy = 0; iy < ny; iy++)
			for (ix = 0; ix < nx; ix++)
				terrain[iy * nx + ix] = ((iy >= 2 && iy < 5) || (ix >= nx - 5 && ix < nx - 2))
								? HYLO_TERRAIN_GROUND : HYLO_TERRAIN_OBSTACLE;
	} else {                  /* noise: scattered single cells */
		for (iy = 0; iy < ny; iy++)
			for (ix = 0; ix < nx; ix++) {
				uint32_t u = hylo_rng_below(&rng, 10);

				terrain[iy * nx + ix] = u < 2 ? HYLO_TERRAIN_OBSTACLE
						       : u < 4 ? HYLO_TERRAIN_WATER : HYLO_TERRAIN_GROUND;
				height[iy * nx + ix] = terrain[iy * nx + ix] == HYLO_TERRAIN_OBSTACLE ? 2.0f : 0.0f;
			}
	}
	memset(&v, 0, sizeof v);
	v.map_id = 1;
	v.robot = robot;
	v.nx = nx;
	v.ny = ny;
	v.resolution = strcmp(robot, "di") == 0 ? 2.0 / nx : 0.5;
	v.origin_x = strcmp(robot, "di") == 0 ? -1.0 : 0.0;
	v.origin_y = strcmp(robot, "di") == 0 ? -1.0 : 0.0;
	v.ceiling = 4;
	v.max_step = 0.1;
	v.n_cells = nx * ny;
	v.terrain = terrain;
	v.height = height;
	if (strcmp(robot, "di") == 0)
		v.resolution = 2.0 / nx, v.ny = ny = nx, v.n_cells = nx * nx;
	assert_int_equal(hylo_map_ingest(map, &v, &r), HYLO_OK);
}

static double dist(hylo_point a, hylo_point b, int three_d)
{
	double dz = three_d ? a.z - b.z : 0;

	return sqrt((a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y) + dz * dz);
}

/* Separation, containment and maximality of one sample set. */
static void check_samples(hylo_mode mode, double r, const hylo_point *p, uint32_t n)
{
	int three_d = mode == HYLO_MODE_FLIGHT;
	double step = map->resolution / 4, worst = 0;
	uint32_t i, j, checked = 0;
	int ix, iy, iz, nz = three_d ? 9 : 1;

	for (i = 0; i < n; i++) {
		if (!hylo_domain_contains(map, mode, p[i]))
			fail_msg("%s sample %u (%g, %g, %g) lies outside its domain", hylo_mode_str(mode),
				 i, p[i].x, p[i].y, p[i].z);
		for (j = 0; j < i; j++)
			if (dist(p[i], p[j], three_d) < r * (1 - 1e-12))
				fail_msg("%s samples %u and %u are %g apart, radius %g", hylo_mode_str(mode),
					 i, j, dist(p[i], p[j], three_d), r);
	}
	for (iy = 0; iy <= map->ny * 4; iy++)
		for (ix = 0; ix <= map->nx * 4; ix++)
			for (iz = 0; iz < nz; iz++) {
				hylo_point q;
				double best = INFINITY;

				q.x = map->origin_x + ix * step;
				q.y = map->origin_y + iy * step;
				q.z = three_d ? map->ceiling * iz / (nz - 1.0) : hylo_map_height(map, q.x, q.y);
				if (mode == HYLO_MODE_DI_NEG || mode == HYLO_MODE_DI_POS)
					q.z = 0;
				if (!hylo_domain_contains(map, mode, q))
					continue;
				checked++;
				for (i = 0; i < n; i++)
					best = fmin(best, dist(q, p[i], three_d));
				worst = fmax(worst, best);
				if (!(best <= 2 * r))
					fail_msg("%s: domain point (%g, %g, %g) is %g from every sample, radius %g",
						 hylo_mode_str(mode), q.x, q.y, q.z, best, r);
			}
	if (checked > 0)
		assert_true(n > 0);
}

static void sample_and_check(hylo_mode mode, double r, uint64_t seed)
{
	hylo_rng rng;
	hylo_reason why;
	uint32_t n = 0;

	hylo_rng_seed(&rng, seed);
	assert_int_equal(hylo_poisson_sample(map, mode, r, &rng, ws, pts, CAP, &n, &why), HYLO_OK);
	check_samples(mode, r, pts, n);
}

static void test_planar_random_domains(void **state)
{
	int trial;

	(void)state;
	for (trial = 0; trial < 24; trial++) {
		double r = 0.4 + 0.05 * (trial % 20);

		random_map(1000 + (uint64_t)trial, "ambot", trial % 4);
		sample_and_check(HYLO_MODE_GROUND, r, (uint64_t)trial);
		sample_and_check(HYLO_MODE_MARINE, r, (uint64_t)trial + 7);
	}
}

static void test_phase_plane(void **state)
{
	int trial;

	(void)state;
	for (trial = 0; trial < 12; trial++) {
		double r = 0.06 + 0.01 * trial;

		random_map(2000 + (uint64_t)trial, "di", trial % 4 == 1 ? 0 : trial % 4);
		sample_and_check(HYLO_MODE_DI_NEG, r, (uint64_t)trial);
		sample_and_check(HYLO_MODE_DI_POS, r, (uint64_t)trial + 3);
	}
}

static void test_flight(void **state)
{
	int trial;

	(void)state;
	for (trial = 0; trial < 6; trial++) {
		random_map(3000 + (uint64_t)trial, "drivocopter", 3);
		sample_and_check(HYLO_MODE_FLIGHT, 1.2 + 0.2 * trial, (uint64_t)trial);
	}
}

/* Is q on the common edge of a ground and a water cell? */
static int on_shoreline(hylo_point q)
{
	double fx = (q.x - map->origin_x) / map->resolution, fy = (q.y - map->origin_y) / map->resolution;
	int dx, dy;

	for (dx = -1; dx <= 0; dx++)
		for (dy = -1; dy <= 0; dy++) {
			long ax = (long)floor(fx + 1e-9) + dx, ay = (long)floor(fy + 1e-9) + dy;
			/* candidate cell pairs sharing an edge through q */
			long bx = ax + 1, by = ay + 1;
			int8_t t = ax >= 0 && ax < map->nx && ay >= 0 && ay < map->ny ? map->terrain[ay * map->nx + ax] : -1;
			int8_t tr = bx >= 0 && bx < map->nx && ay >= 0 && ay < map->ny ? map->terrain[ay * map->nx + bx] : -1;
			int8_t tu = ax >= 0 && ax < map->nx && by >= 0 && by < map->ny ? map->terrain[by * map->nx + ax] : -1;
			int vert = fabs(fx - (ax + 1)) < 1e-9 && fy >= ay - 1e-9 && fy <= ay + 1 + 1e-9;
			int horz = fabs(fy - (ay + 1)) < 1e-9 && fx >= ax - 1e-9 && fx <= ax + 1 + 1e-9;

			if (vert && ((t == 1 && tr == 2) || (t == 2 && tr == 1)))
				return 1;
			if (horz && ((t == 1 && tu == 2) || (t == 2 && tu == 1)))
				return 1;
		}
	return 0;
}

static void test_guards(void **state)
{
	hylo_rng rng;
	hylo_reason why;
	uint32_t n, i, j;
	int trial;

	(void)state;
	for (trial = 0; trial < 12; trial++) {
		double s = 0.5 + 0.1 * trial;

		random_map(4000 + (uint64_t)trial, "ambot", trial % 4);
		hylo_rng_seed(&rng, (uint64_t)trial);
		assert_int_equal(hylo_guard_sample(map, HYLO_GUARD_SHORELINE, s, &rng, ws, pts, CAP, &n, &why), HYLO_OK);
		for (i = 0; i < n; i++) {
			if (!on_shoreline(pts[i]))
				fail_msg("shoreline sample (%g, %g) is not on a ground/water edge", pts[i].x, pts[i].y);
			for (j = 0; j < i; j++)
				assert_true(dist(pts[i], pts[j], 0) >= s * (1 - 1e-12));
		}
		if (trial % 4 == 1)   /* the ring always has a shoreline */
			assert_true(n > 0);

		random_map(5000 + (uint64_t)trial, "drivocopter", trial % 4);
		assert_int_equal(hylo_guard_sample(map, HYLO_GUARD_TAKEOFF, s, &rng, ws, pts, CAP, &n, &why), HYLO_OK);
		for (i = 0; i < n; i++) {
			hylo_point twin = pts[i];

			twin.z += HYLO_TAKEOFF_HEIGHT_M;
			assert_true(hylo_domain_contains(map, HYLO_MODE_GROUND, pts[i]));
			assert_true(hylo_domain_contains(map, HYLO_MODE_FLIGHT, twin));
			for (j = 0; j < i; j++)
				assert_true(dist(pts[i], pts[j], 0) >= s * (1 - 1e-12));
		}

		random_map(6000 + (uint64_t)trial, "di", 3);
		assert_int_equal(hylo_guard_sample(map, HYLO_GUARD_DI, 0.05 + 0.01 * trial, &rng, ws, pts, CAP, &n, &why), HYLO_OK);
		for (i = 0; i < n; i++) {
			assert_true(pts[i].x == 0);
			assert_true(hylo_domain_contains(map, HYLO_MODE_DI_NEG, pts[i]));
			assert_true(hylo_domain_contains(map, HYLO_MODE_DI_POS, pts[i]));
		}
	}
}

static void test_determinism_and_capacity(void **state)
{
	hylo_rng rng;
	hylo_reason why;
	uint32_t n = 0, n2 = 0, n3 = 0;

	(void)state;
	random_map(77, "ambot", 0);
	hylo_rng_seed(&rng, 5);
	assert_int_equal(hylo_poisson_sample(map, HYLO_MODE_GROUND, 0.6, &rng, ws, pts, CAP, &n, &why), HYLO_OK);
	hylo_rng_seed(&rng, 5);
	assert_int_equal(hylo_poisson_sample(map, HYLO_MODE_GROUND, 0.6, &rng, ws, pts2, CAP, &n2, &why), HYLO_OK);
	assert_int_equal(n, n2);
	assert_memory_equal(pts, pts2, n * sizeof pts[0]);
	hylo_rng_seed(&rng, 6);
	assert_int_equal(hylo_poisson_sample(map, HYLO_MODE_GROUND, 0.6, &rng, ws, pts2, CAP, &n3, &why), HYLO_OK);
	assert_true(n3 != n || memcmp(pts, pts2, n * sizeof pts[0]) != 0);
	/* Exactly at capacity: fits; one below: the capacity error. */
	hylo_rng_seed(&rng, 5);
	assert_int_equal(hylo_poisson_sample(map, HYLO_MODE_GROUND, 0.6, &rng, ws, pts2, n, &n2, &why), HYLO_OK);
	assert_int_equal(n2, n);
	hylo_rng_seed(&rng, 5);
	assert_int_equal(hylo_poisson_sample(map, HYLO_MODE_GROUND, 0.6, &rng, ws, pts2, n - 1, &n2, &why),
			 HYLO_E_CAP_POSITIONS);
	assert_non_null(strstr(why.text, "HYLO_MAX_POSITIONS"));
	/* Bad radius. */
	assert_int_equal(hylo_poisson_sample(map, HYLO_MODE_GROUND, NAN, &rng, ws, pts2, CAP, &n2, &why),
			 HYLO_E_BAD_VALUE);
	assert_int_equal(hylo_poisson_sample(map, HYLO_MODE_GROUND, -1, &rng, ws, pts2, CAP, &n2, &why),
			 HYLO_E_BAD_VALUE);
}

static int setup(void **state)
{
	(void)state;
	map = malloc(sizeof *map);
	ws = malloc(sizeof *ws);
	return map && ws ? 0 : -1;
}

static int teardown(void **state)
{
	(void)state;
	free(map);
	free(ws);
	return 0;
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_planar_random_domains),
		cmocka_unit_test(test_phase_plane),
		cmocka_unit_test(test_flight),
		cmocka_unit_test(test_guards),
		cmocka_unit_test(test_determinism_and_capacity),
	};

	return cmocka_run_group_tests_name("poisson", tests, setup, teardown);
}
