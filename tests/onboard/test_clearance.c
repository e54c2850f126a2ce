/*
 * Clearance (onboard/src/clearance.c): exact hazard distances on small maps
 * worked by hand, and on random maps the inflated domains keep what they
 * promise: every point they contain (and every point of every segment they
 * accept) is at least r from every hazard by the exact distance; r = 0 gives
 * the plain domains.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "hylo/clearance.h"
#include "hylo/internal/rng.h"

static hylo_map *map, *plain;
static int8_t terrain[HYLO_MAX_CELLS];
static float height[HYLO_MAX_CELLS];

/* A 10 x 10 map of 1 m cells at the origin, flat ground at height 0. */
static void ingest(hylo_map *m, int32_t nx, int32_t ny, hylo_real res)
{
	hylo_map_view v;
	hylo_reason r;

	memset(&v, 0, sizeof v);
	v.map_id = 1;
	v.robot = "ambot";
	v.nx = nx;
	v.ny = ny;
	v.resolution = res;
	v.ceiling = 6;
	v.max_step = 0.2;
	v.n_cells = nx * ny;
	v.terrain = terrain;
	v.height = height;
	assert_int_equal(hylo_map_ingest(m, &v, &r), HYLO_OK);
}

static void flat(int32_t n)
{
	int32_t i;

	for (i = 0; i < n; i++) {
		terrain[i] = HYLO_TERRAIN_GROUND;
		height[i] = 0;
	}
}

static hylo_point pt(hylo_real x, hylo_real y, hylo_real z)
{
	hylo_point p;

	p.x = x;
	p.y = y;
	p.z = z;
	return p;
}

static void test_distances_by_hand(void **state)
{
	(void)state;
	flat(100);
	terrain[5 * 10 + 5] = HYLO_TERRAIN_OBSTACLE;   /* [5, 6] x [5, 6] */
	terrain[2 * 10 + 7] = HYLO_TERRAIN_WATER;      /* [7, 8] x [2, 3] */
	height[8 * 10 + 2] = 1.0f;                     /* a 1 m block at [2, 3] x [8, 9] */
	ingest(map, 10, 10, 1.0);

	/* Obstacle: 1.5 m to its left side; 2.5 m to its corner diagonally. */
	assert_float_equal(hylo_hazard_distance(map, HYLO_MODE_GROUND, pt(3.5, 5.5, 0), 9), 1.5, 1e-12);
	assert_float_equal(hylo_hazard_distance(map, HYLO_MODE_GROUND, pt(3.5, 3.5, 0), 9),
			   hypot(1.5, 1.5), 1e-12);
	/* The map's boundary: 0.5 m from x = 0. */
	assert_float_equal(hylo_hazard_distance(map, HYLO_MODE_MARINE, pt(0.5, 3.0, 0), 9), 0.5, 1e-12);
	/* Water is not a hazard for ground; the block's wall edges are (its
	 * lower edge y = 8, 0.7 m away), and not for marine. */
	assert_float_equal(hylo_hazard_distance(map, HYLO_MODE_GROUND, pt(7.5, 2.5, 0), 1), 1, 1e-12);
	assert_float_equal(hylo_hazard_distance(map, HYLO_MODE_GROUND, pt(2.5, 7.3, 0), 9), 0.7, 1e-12);
	assert_float_equal(hylo_hazard_distance(map, HYLO_MODE_GROUND, pt(1.6, 8.5, 0), 9), 0.4, 1e-12);
	assert_float_equal(hylo_hazard_distance(map, HYLO_MODE_GROUND, pt(3.3, 8.5, 0), 9), 0.3, 1e-12);
	assert_float_equal(hylo_hazard_distance(map, HYLO_MODE_MARINE, pt(2.5, 7.3, 0), 1.2), 1.2, 1e-12);
	/* Capped at reach; 0 off the map or inside an obstacle. */
	assert_float_equal(hylo_hazard_distance(map, HYLO_MODE_GROUND, pt(3.5, 5.5, 0), 0.25), 0.25, 0);
	assert_float_equal(hylo_hazard_distance(map, HYLO_MODE_GROUND, pt(-0.1, 5, 0), 9), 0, 0);
	assert_float_equal(hylo_hazard_distance(map, HYLO_MODE_GROUND, pt(5.5, 5.5, 0), 9), 0, 0);
	assert_float_equal(hylo_hazard_distance(map, HYLO_MODE_GROUND, pt(NAN, 5.5, 0), 9), 0, 0);
	/* Flight: 1.6 m above the block's top edge, 0.6 m beside it. */
	assert_float_equal(hylo_hazard_distance(map, HYLO_MODE_FLIGHT, pt(2.5, 7.4, 2.6), 9),
			   hypot(0.6, 1.6), 1e-12);
	/* ... and 0.9 m below the ceiling, which is nearer. */
	assert_float_equal(hylo_hazard_distance(map, HYLO_MODE_FLIGHT, pt(2.5, 7.4, 5.1), 9), 0.9, 1e-12);
	/* Straight above flat ground: the height. */
	assert_float_equal(hylo_hazard_distance(map, HYLO_MODE_FLIGHT, pt(4.5, 2.5, 0.8), 9), 0.8, 1e-12);
	/* The double integrator has no hazards. */
	assert_float_equal(hylo_hazard_distance(map, HYLO_MODE_DI_POS, pt(5.5, 5.5, 0), 3), 3, 0);
}

static void test_inflated_cells_by_hand(void **state)
{
	hylo_reason r;

	(void)state;
	flat(100);
	terrain[5 * 10 + 5] = HYLO_TERRAIN_OBSTACLE;
	height[8 * 10 + 2] = 1.0f;
	ingest(map, 10, 10, 1.0);
	assert_int_equal(hylo_map_inflate(map, 0.9, &r), HYLO_OK);
	/* Beside the obstacle: out; one cell further (1 m gap): in. */
	assert_false(hylo_map_cell_clear(map, HYLO_MODE_GROUND, 5 * 10 + 4));
	assert_false(hylo_map_cell_clear(map, HYLO_MODE_GROUND, 4 * 10 + 4));
	assert_true(hylo_map_cell_clear(map, HYLO_MODE_GROUND, 5 * 10 + 3));
	/* The boundary cells are out. */
	assert_false(hylo_map_cell_clear(map, HYLO_MODE_GROUND, 3 * 10 + 0));
	/* Flight beside the block: 0.9 m above its top; over open ground 0.9 m
	 * too (more than the air clearance); the ceiling comes down by 0.9 m. */
	assert_float_equal(hylo_map_flight_floor(map, 8 * 10 + 3), 1.9, 1e-6);
	assert_float_equal(hylo_map_flight_floor(map, 3 * 10 + 5), 0.9, 1e-6);
	assert_int_equal(hylo_map_inflate(map, 0.3, &r), HYLO_OK);
	assert_float_equal(hylo_map_flight_floor(map, 3 * 10 + 5), HYLO_AIR_CLEARANCE_M, 1e-6);
	assert_int_equal(hylo_map_inflate(map, 0.9, &r), HYLO_OK);
	assert_float_equal(hylo_map_flight_top(map), 5.1, 1e-12);
	assert_true(hylo_map_flight_floor(map, 3 * 10 + 0) > 1e30);
	/* Bad clearances are refused, naming the value. */
	assert_int_equal(hylo_map_inflate(map, -1, &r), HYLO_E_BAD_VALUE);
	assert_non_null(strstr(r.text, "-1"));
	assert_int_equal(hylo_map_inflate(map, NAN, &r), HYLO_E_BAD_VALUE);
	assert_int_equal(hylo_map_inflate(map, HUGE_VAL, &r), HYLO_E_BAD_VALUE);
}

/* Random terrain: ground with steps, water, obstacles, blocks. */
static void random_map(hylo_rng *rng, int32_t n)
{
	int32_t i;

	for (i = 0; i < n; i++) {
		uint32_t u = hylo_rng_below(rng, 14);

		terrain[i] = u == 0 ? HYLO_TERRAIN_OBSTACLE : u < 4 ? HYLO_TERRAIN_WATER : HYLO_TERRAIN_GROUND;
		height[i] = u == 0 ? 2.5f : u == 4 ? 1.0f : (float)(0.1 * hylo_rng_below(rng, 2));
	}
}

static void test_inflated_domains_keep_clearance(void **state)
{
	static const hylo_mode modes[] = { HYLO_MODE_GROUND, HYLO_MODE_MARINE, HYLO_MODE_FLIGHT };
	hylo_rng rng;
	hylo_reason why;
	int trial, k, inside = 0, segments = 0, same = 0;

	(void)state;
	hylo_rng_seed(&rng, 7);
	for (trial = 0; trial < 30; trial++) {
		hylo_real r = 0.1 + 0.8 * hylo_rng_uniform(&rng), res = trial % 2 ? 0.5 : 1.0;

		random_map(&rng, 24 * 20);
		ingest(map, 24, 20, res);
		ingest(plain, 24, 20, res);
		assert_int_equal(hylo_map_inflate(map, r, &why), HYLO_OK);
		for (k = 0; k < 600; k++) {
			hylo_mode mode = modes[k % 3];
			hylo_point a = pt(24 * res * hylo_rng_uniform(&rng), 20 * res * hylo_rng_uniform(&rng),
					  1.5 + 4 * hylo_rng_uniform(&rng));
			hylo_point b = pt(a.x + 3 * (hylo_rng_uniform(&rng) - 0.5), a.y + 3 * (hylo_rng_uniform(&rng) - 0.5),
					  a.z + hylo_rng_uniform(&rng) - 0.5);
			int j;

			if (hylo_domain_contains(map, mode, a)) {
				inside++;
				if (hylo_hazard_distance(map, mode, a, r + 1) < r - 1e-9)
					fail_msg("%s point (%g, %g, %g) in the domain inflated by %g is %g from a hazard",
						 hylo_mode_str(mode), a.x, a.y, a.z, r,
						 hylo_hazard_distance(map, mode, a, r + 1));
				if (!hylo_domain_contains(plain, mode, a))
					fail_msg("the inflated %s domain is not inside the plain one", hylo_mode_str(mode));
			}
			if (!hylo_domain_segment(map, mode, a, b))
				continue;
			segments++;
			for (j = 0; j <= 200; j++) {
				hylo_real t = j / 200.0;
				hylo_point q = pt(a.x + t * (b.x - a.x), a.y + t * (b.y - a.y), a.z + t * (b.z - a.z));

				if (hylo_hazard_distance(map, mode, q, r + 1) < r - 1e-9)
					fail_msg("%s segment accepted with clearance %g but a point at %g from a hazard",
						 hylo_mode_str(mode), r, hylo_hazard_distance(map, mode, q, r + 1));
			}
		}
		/* r = 0: the plain domains, point for point. */
		assert_int_equal(hylo_map_inflate(map, 0, &why), HYLO_OK);
		for (k = 0; k < 300; k++) {
			hylo_mode mode = modes[k % 3];
			hylo_point a = pt(24 * res * hylo_rng_uniform(&rng), 20 * res * hylo_rng_uniform(&rng),
					  3 * hylo_rng_uniform(&rng));
			hylo_point b = pt(a.x + 3 * (hylo_rng_uniform(&rng) - 0.5), a.y + 3 * (hylo_rng_uniform(&rng) - 0.5),
					  a.z);

			assert_int_equal(hylo_domain_contains(map, mode, a), hylo_domain_contains(plain, mode, a));
			assert_int_equal(hylo_domain_segment(map, mode, a, b), hylo_domain_segment(plain, mode, a, b));
			same++;
		}
	}
	/* The checks above ran on many points and segments. */
	assert_true(inside > 500 && segments > 300 && same == 30 * 300);
}

static int setup(void **state)
{
	(void)state;
	map = malloc(sizeof *map);
	plain = malloc(sizeof *plain);
	return map && plain ? 0 : -1;
}

static int teardown(void **state)
{
	(void)state;
	free(map);
	free(plain);
	return 0;
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_distances_by_hand),
		cmocka_unit_test(test_inflated_cells_by_hand),
		cmocka_unit_test(test_inflated_domains_keep_clearance),
	};

	return cmocka_run_group_tests_name("clearance", tests, setup, teardown);
}
