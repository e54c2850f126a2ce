/*
 * The envelope lookup (hylo_svr_envelope_bound, svr.h) and the edge
 * arguments it is looked up with (hylo_envelope_args, hylo_envelope_turn
 * and hylo_envelope_of_edge, envelope.h) on small hand-made tables: a speed
 * on a node and within 1e-9 of it, between nodes, outside the table, flight
 * climbs and vertical velocities, planar turn cells, the flight turn table;
 * the turn itself (known
 * cases, symmetries, agreement with the features' turn); hylo_svr_check
 * refusing bad tables; and the two feature symmetries the trainer's
 * envelope relies on (a planar goal's mirror image, a flight edge turned
 * about z give the same features).
 * The committed models' tables against their own predictions:
 * tests/export/test_envelope_models.c.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <string.h>

#include "hylo/envelope.h"
#include "hylo/features.h"
#include "hylo/svr.h"

#define PI 3.14159265358979323846

static double sv[HYLO_MAX_FEATURES], coef[1] = { 1 };
static const double offset[HYLO_MAX_FEATURES] = { 0 };
static const double scale[HYLO_MAX_FEATURES] = { 1, 1, 1, 1, 1, 1, 1, 1, 1 };

/* Planar: 3 distance cells of 0.5 m, speed nodes 0, 0.5, 1; value 100 (k +
 * 1) + 10 i1 + i2. */
static float planar_values[3 * 3 * 3];
static hylo_svr_envelope planar_env = { 3, 1, 3, 0.5, 0, 0, 0, 0.5, planar_values };
/* Flight: 2 distance cells of 1 m, 4 climb cells of 1 m from -2, speed nodes
 * 0, 4, 8; value 10000 + 1000 k + 100 j + 10 i1 + i2. */
static float flight_values[2 * 4 * 3 * 3];
static hylo_svr_envelope flight_env = { 2, 4, 3, 1.0, -2.0, 1.0, 0, 4.0, flight_values };
/* Planar with turn cells: 2 distance cells of 1 m, 16 turn cells of 2 pi /
 * 16, speed nodes 0, 1; value 1000 k + 10 j + 2 i1 + i2 + 1. */
#define TURN_STEP (2 * PI / 16)
static float turn_values[2 * 16 * 2 * 2];
static hylo_svr_envelope turn_env = { 2, 16, 2, 1.0, 0, TURN_STEP, 0, 1.0, turn_values };

/* Flight's turn table: flight_env's distance cells and speed nodes, 16 turn
 * cells; value 20000 + 1000 k + 10 j + 3 i1 + i2. */
static float flight_turn_values[2 * 16 * 3 * 3];
static hylo_svr_envelope flight_turn_env = { 2, 16, 3, 1.0, 0, TURN_STEP, 0, 4.0, flight_turn_values };

static uint64_t rng_state = 12345;

static double uniform(double lo, double hi)
{
	rng_state = rng_state * 6364136223846793005ULL + 1442695040888963407ULL;
	return lo + (hi - lo) * (double)(rng_state >> 11) * 0x1.0p-53;
}

static hylo_svr_model model(uint32_t n_features, const hylo_svr_envelope *env)
{
	hylo_svr_model m;

	memset(&m, 0, sizeof m);
	m.name = "envelope_test";
	m.n_sv = 1;
	m.n_features = n_features;
	m.gamma = 0.5;
	m.sv = sv;
	m.coef = coef;
	m.feature_offset = offset;
	m.feature_scale = scale;
	m.label_scale = 1;
	m.envelope = env;
	return m;
}

static int setup(void **state)
{
	uint32_t k, j, a, b;

	(void)state;
	for (k = 0; k < 3; k++)
		for (a = 0; a < 3; a++)
			for (b = 0; b < 3; b++)
				planar_values[(k * 3 + a) * 3 + b] = (float)(100 * (k + 1) + 10 * a + b);
	for (k = 0; k < 2; k++)
		for (j = 0; j < 4; j++)
			for (a = 0; a < 3; a++)
				for (b = 0; b < 3; b++)
					flight_values[((k * 4 + j) * 3 + a) * 3 + b] =
						(float)(10000 + 1000 * k + 100 * j + 10 * a + b);
	for (k = 0; k < 2; k++)
		for (j = 0; j < 16; j++)
			for (a = 0; a < 3; a++)
				for (b = 0; b < 3; b++)
					flight_turn_values[((k * 16 + j) * 3 + a) * 3 + b] =
						(float)(20000 + 1000 * k + 10 * j + 3 * a + b);
	for (k = 0; k < 2; k++)
		for (j = 0; j < 16; j++)
			for (a = 0; a < 2; a++)
				for (b = 0; b < 2; b++)
					turn_values[((k * 16 + j) * 2 + a) * 2 + b] =
						(float)(1000 * k + 10 * j + 2 * a + b + 1);
	return 0;
}

static void test_node_speeds(void **state)
{
	hylo_svr_model m = model(HYLO_FEATURES_PLANAR, &planar_env);

	(void)state;
	assert_int_equal(hylo_svr_check(&m, NULL), HYLO_OK);
	assert_true(hylo_svr_envelope_bound(&m, 0.7, 0, 0.5, 1.0) == 212);
	assert_true(hylo_svr_envelope_bound(&m, 0, 0, 0, 0) == 100);
	assert_true(hylo_svr_envelope_bound(&m, 0.2, 123.0, 1.0, 0.0) == 120);  /* climb ignored */
	assert_true(hylo_svr_envelope_bound(&m, 1.4999, 0, 1.0, 1.0) == 322);
	/* Within 1e-9 m/s of a node: that node, on either side. */
	assert_true(hylo_svr_envelope_bound(&m, 0.7, 0, 0.5 + 9e-10, 1.0 - 9e-10) == 212);
	assert_true(hylo_svr_envelope_bound(&m, 0.7, 0, 0.5 - 9e-10, 0.0 - 9e-10) == 210);
	assert_true(hylo_svr_envelope_bound(&m, 0.7, 0, 1.0 + 9e-10, 0.5) == 221);
	/* Cell edges: [k d_step, (k+1) d_step). */
	assert_true(hylo_svr_envelope_bound(&m, 0.5, 0, 0, 0) == 200);
	assert_true(hylo_svr_envelope_bound(&m, 0.49999999, 0, 0, 0) == 100);
}

static void test_between_nodes(void **state)
{
	hylo_svr_model m = model(HYLO_FEATURES_PLANAR, &planar_env);

	(void)state;
	/* The least value over the bracketing nodes (not a guaranteed bound). */
	assert_true(hylo_svr_envelope_bound(&m, 0.7, 0, 0.75, 1.0) == 212);
	assert_true(hylo_svr_envelope_bound(&m, 0.7, 0, 0.75, 0.25) == 210);
	assert_true(hylo_svr_envelope_bound(&m, 1.2, 0, 0.25, 0.6) == 301);
	assert_true(hylo_svr_envelope_bound(&m, 1.2, 0, 0.5 + 2e-9, 1.0) == 312);
	/* Values that do not grow with speed: still the least of the four. */
	planar_values[(1 * 3 + 2) * 3 + 2] = 5;
	assert_true(hylo_svr_envelope_bound(&m, 0.7, 0, 0.75, 0.75) == 5);
	planar_values[(1 * 3 + 2) * 3 + 2] = 222;
}

static void test_out_of_range(void **state)
{
	hylo_svr_model m = model(HYLO_FEATURES_PLANAR, &planar_env), none = model(HYLO_FEATURES_PLANAR, NULL);

	(void)state;
	assert_true(hylo_svr_envelope_bound(&m, 1.5, 0, 0, 0) == 0);  /* past the last cell */
	assert_true(hylo_svr_envelope_bound(&m, 1e300, 0, 0, 0) == 0);
	assert_true(hylo_svr_envelope_bound(&m, -1e-12, 0, 0, 0) == 0);
	assert_true(hylo_svr_envelope_bound(&m, NAN, 0, 0, 0) == 0);
	assert_true(hylo_svr_envelope_bound(&m, INFINITY, 0, 0, 0) == 0);
	assert_true(hylo_svr_envelope_bound(&m, 0.7, 0, -2e-9, 0) == 0);  /* speed below the nodes */
	assert_true(hylo_svr_envelope_bound(&m, 0.7, 0, 0, 1.0 + 2e-9) == 0);  /* above */
	assert_true(hylo_svr_envelope_bound(&m, 0.7, 0, -0.3, 0) == 0);
	assert_true(hylo_svr_envelope_bound(&m, 0.7, 0, NAN, 0) == 0);
	assert_true(hylo_svr_envelope_bound(&m, 0.7, 0, 0, -INFINITY) == 0);
	assert_true(hylo_svr_envelope_bound(&none, 0.7, 0, 0.5, 0.5) == 0);  /* no envelope */
	assert_true(hylo_svr_envelope_bound(NULL, 0.7, 0, 0.5, 0.5) == 0);
}

static void test_flight(void **state)
{
	hylo_svr_model m = model(HYLO_FEATURES_FLIGHT, &flight_env);
	const double tail[6] = { 10, 20, 5, 0, 4, 0 };
	double head[6] = { 10.3, 20.4, 4.5, 8 * 0.6, -8 * 0.8, 0 }, a[4];

	(void)state;
	assert_int_equal(hylo_svr_check(&m, NULL), HYLO_OK);
	assert_true(hylo_svr_envelope_bound(&m, 1.5, 0.5, 4, 8) == 11212);
	assert_true(hylo_svr_envelope_bound(&m, 0.5, -2.0, 0, 0) == 10000);
	assert_true(hylo_svr_envelope_bound(&m, 0.5, -2.0 - 1e-12, 0, 0) == 0);  /* below the climbs */
	assert_true(hylo_svr_envelope_bound(&m, 0.5, 1.999, 8, 8) == 10322);
	assert_true(hylo_svr_envelope_bound(&m, 0.5, 2.0, 8, 8) == 0);  /* above */
	assert_true(hylo_svr_envelope_bound(&m, 0.5, NAN, 8, 8) == 0);
	/* The edge's arguments: horizontal distance 0.5, climb -0.5, |v| 4 and 8. */
	assert_int_equal(hylo_envelope_args(HYLO_MODE_FLIGHT, tail, head, a), 1);
	assert_true(fabs(a[0] - 0.5) < 1e-12 && a[1] == -0.5);
	assert_true(a[2] == 4 && fabs(a[3] - 8) < 1e-12);
	assert_true(hylo_envelope_of_edge(&m, HYLO_MODE_FLIGHT, tail, head) == 10112);
	/* A vertical velocity: no envelope (the roadmap flies level). */
	head[5] = 0.1;
	assert_int_equal(hylo_envelope_args(HYLO_MODE_FLIGHT, tail, head, a), 0);
	assert_true(hylo_envelope_of_edge(&m, HYLO_MODE_FLIGHT, tail, head) == 0);
	head[5] = -1e-300;
	assert_true(hylo_envelope_of_edge(&m, HYLO_MODE_FLIGHT, tail, head) == 0);
	head[5] = 0;
	/* The model's features are not the mode's. */
	assert_true(hylo_envelope_of_edge(&m, HYLO_MODE_GROUND, tail, head) == 0);
}

/* The flight turn (hylo_envelope_flight_turn) and the turn table: looked up
 * by distance and turn within the training ball, and hylo_envelope_of_edge
 * takes the larger of its bound and the climb table's. */
static void test_flight_turn_table(void **state)
{
	hylo_svr_model m = model(HYLO_FEATURES_FLIGHT, &flight_env);
	const double tail[6] = { 10, 20, 5, 0, 4, 0 };
	double head[6] = { 10.3, 20.4, 4.5, 8 * 0.6, -8 * 0.8, 0 }, t = -1, want;
	const double ahead[6] = { 0, 0, 0, 4, 0, 0 }, end[6] = { 1, 0, 0, 8, 0, 0 };
	const double back[6] = { 1, 0, 0, -8, 0, 0 }, up[6] = { 0, 0, 1, 8, 0, 0 };
	const double left[6] = { 0, 0, 0, 0, 4, 0 }, right[6] = { 1, 0, 0, 0, -8, 0 };
	const double still[6] = { 0, 0, 0, 0, 0, 0 };

	(void)state;
	m.max_distance_m = 3;
	m.turn_envelope = &flight_turn_env;
	assert_int_equal(hylo_svr_check(&m, NULL), HYLO_OK);
	/* Both velocities along the displacement: 0; the head's reversed: pi;
	 * both across it: pi / 2 each; a zero velocity adds nothing. */
	assert_int_equal(hylo_envelope_flight_turn(ahead, end, &t), 1);
	assert_true(t == 0);
	assert_int_equal(hylo_envelope_flight_turn(ahead, back, &t), 1);
	assert_true(fabs(t - PI) < 1e-15);
	assert_int_equal(hylo_envelope_flight_turn(left, right, &t), 1);
	assert_true(fabs(t - PI) < 1e-15);
	assert_int_equal(hylo_envelope_flight_turn(still, right, &t), 1);
	assert_true(fabs(t - PI / 2) < 1e-15);
	/* No horizontal displacement, or a velocity that is not level: none. */
	t = -1;
	assert_int_equal(hylo_envelope_flight_turn(ahead, up, &t), 0);
	head[5] = 0.5;
	assert_int_equal(hylo_envelope_flight_turn(tail, head, &t), 0);
	head[5] = 0;
	assert_true(t == -1);
	/* The lookup: cell (1, 8), speeds 4 and 8; outside the ball, none. */
	assert_true(hylo_svr_turn_envelope_bound(&m, 1.5, 0.5, PI + 1e-3, 4, 8) == 21085);
	assert_true(hylo_svr_turn_envelope_bound(&m, 1.5, 2.7, PI + 1e-3, 4, 8) == 0);
	assert_true(hylo_svr_turn_envelope_bound(&m, 1.5, 0.5, 2 * PI, 4, 8) == 21155);
	assert_true(hylo_svr_turn_envelope_bound(&m, 1.5, 0.5, 2 * PI + 1e-9, 4, 8) == 0);
	/* The edge of test_flight: turn = (pi/2 - phi) + (phi + atan2(0.8, 0.6))
	 * with phi = atan2(0.4, 0.3), cell 6; the larger of the two tables. */
	assert_int_equal(hylo_envelope_flight_turn(tail, head, &t), 1);
	want = fabs(hylo_wrap_angle(PI / 2 - atan2(0.4, 0.3))) + fabs(hylo_wrap_angle(-atan2(0.8, 0.6) - atan2(0.4, 0.3)));
	assert_true(fabs(t - want) < 1e-12 && (int)(t / TURN_STEP) == 6);
	assert_true(hylo_envelope_of_edge(&m, HYLO_MODE_FLIGHT, tail, head) == 20065);
	m.turn_envelope = NULL;
	assert_true(hylo_envelope_of_edge(&m, HYLO_MODE_FLIGHT, tail, head) == 10112);
	assert_true(hylo_svr_turn_envelope_bound(&m, 1.5, 0.5, PI, 4, 8) == 0);
}

static void test_edge_args(void **state)
{
	hylo_svr_model m = model(HYLO_FEATURES_PLANAR, &planar_env);
	const double tail[4] = { 1, 2, 0.5, 2.0 }, head[4] = { 1.45, 1.4, 1.0, -3.0 };
	const double di_a[2] = { -0.5, 0.1 }, di_b[2] = { -0.2, 0.3 };
	double a[4] = { -1, -1, -1, -1 };

	(void)state;
	assert_int_equal(hylo_envelope_args(HYLO_MODE_MARINE, tail, head, a), 1);
	assert_true(fabs(a[0] - 0.75) < 1e-12 && a[2] == 0.5 && a[3] == 1.0);
	assert_true(a[1] == hylo_envelope_turn(atan2(-0.6, 0.45), 2.0, -3.0));
	/* One climb cell: the turn is ignored. */
	assert_true(hylo_envelope_of_edge(&m, HYLO_MODE_GROUND, tail, head) == 212);
	assert_true(hylo_envelope_of_edge(&m, HYLO_MODE_MARINE, tail, head) == 212);
	/* The double integrator and invalid modes have none. */
	a[0] = -1;
	assert_int_equal(hylo_envelope_args(HYLO_MODE_DI_NEG, di_a, di_b, a), 0);
	assert_int_equal(hylo_envelope_args((hylo_mode)99, tail, head, a), 0);
	assert_true(a[0] == -1);
	assert_true(hylo_envelope_of_edge(&m, HYLO_MODE_DI_POS, di_a, di_b) == 0);
	assert_int_equal(hylo_envelope_args(HYLO_MODE_GROUND, NULL, head, a), 0);
	assert_true(hylo_envelope_of_edge(&m, HYLO_MODE_GROUND, tail, NULL) == 0);
	assert_true(hylo_envelope_of_edge(NULL, HYLO_MODE_GROUND, tail, head) == 0);
}

/* The turn (hylo_envelope_turn): the least total heading change of a path
 * from the tail's pose to the head's. */
static void test_turn_known(void **state)
{
	const double t1s[] = { 0, 0.7, -2.0, PI, -PI, 3 * PI / 4, 100.0 };
	unsigned i;

	(void)state;
	for (i = 0; i < sizeof t1s / sizeof t1s[0]; i++) {
		double t1 = t1s[i];

		/* Straight ahead, the same heading: no turn. */
		assert_true(fabs(hylo_envelope_turn(t1, t1, t1)) < 1e-12);
		/* Straight ahead, arriving reversed: pi. */
		assert_true(fabs(hylo_envelope_turn(t1, t1, t1 + PI) - PI) < 1e-12);
		/* Straight behind: face it (pi) and keep that heading (pi in all)... */
		assert_true(fabs(hylo_envelope_turn(t1 + PI, t1, t1 + PI) - PI) < 1e-12);
		/* ... or arrive with the start's heading (turn round again: 2 pi). */
		assert_true(fabs(hylo_envelope_turn(t1 + PI, t1, t1) - 2 * PI) < 1e-12);
		/* To the left: face it (pi / 2), then back to the start's heading. */
		assert_true(fabs(hylo_envelope_turn(t1 + PI / 2, t1, t1) - PI) < 1e-12);
		assert_true(fabs(hylo_envelope_turn(t1 + PI / 2, t1, t1 + PI / 2) - PI / 2) < 1e-12);
		/* To the right, arriving 45 degrees further right: pi / 2 + pi / 4. */
		assert_true(fabs(hylo_envelope_turn(t1 - PI / 2, t1, t1 - 3 * PI / 4) - 3 * PI / 4) < 1e-12);
		/* Ahead-left at 30 degrees, arriving 30 degrees to the right: 30 + 60. */
		assert_true(fabs(hylo_envelope_turn(t1 + PI / 6, t1, t1 - PI / 6) - PI / 2) < 1e-12);
	}
	/* Exactly 0 and 2 pi where the arguments are exact. */
	assert_true(hylo_envelope_turn(0, 0, 0) == 0);
	assert_true(hylo_envelope_turn(PI, 0, 0) == 2 * PI);
	assert_true(hylo_envelope_turn(-PI / 2, PI / 2, PI / 2) == 2 * PI);
	assert_true(!isfinite(hylo_envelope_turn(0, NAN, 0)));
	assert_true(!isfinite(hylo_envelope_turn(0, 0, INFINITY)));
	assert_true(!isfinite(hylo_envelope_turn(-INFINITY, 0, 0)));
	assert_true(!isfinite(hylo_envelope_turn(NAN, 0, 0)));
}

/* Mirror image (y -> -y, headings negated) and turns about z leave it; it
 * lies in [0, 2 pi]; and it is the features' turn (feature 6) to 1e-12, with
 * hylo_envelope_args() giving it bit for bit. */
static void test_turn_symmetry_and_features(void **state)
{
	int i;

	(void)state;
	for (i = 0; i < 20000; i++) {
		double phi = uniform(-PI, PI), t1 = uniform(-2 * PI, 2 * PI), t2 = uniform(-2 * PI, 2 * PI);
		double a = uniform(-PI, PI), turn = hylo_envelope_turn(phi, t1, t2);
		double t[4], h[4], f[HYLO_FEATURES_PLANAR], args[4], d = uniform(1e-6, 5);

		assert_true(turn >= 0 && turn <= 2 * PI);
		assert_true(fabs(hylo_envelope_turn(-phi, -t1, -t2) - turn) < 1e-12);
		assert_true(fabs(hylo_envelope_turn(phi + a, t1 + a, t2 + a) - turn) < 1e-12);
		t[0] = uniform(-50, 50), t[1] = uniform(-50, 50), t[2] = 0.5, t[3] = t1;
		h[0] = t[0] + d * cos(phi), h[1] = t[1] + d * sin(phi), h[2] = 1, h[3] = t2;
		hylo_features(i % 2 ? HYLO_MODE_GROUND : HYLO_MODE_MARINE, t, h, f);
		assert_int_equal(hylo_envelope_args(HYLO_MODE_GROUND, t, h, args), 1);
		assert_true(args[1] == hylo_envelope_turn(atan2(h[1] - t[1], h[0] - t[0]), t1, t2));
		if (!(fabs(args[1] - f[6]) <= 1e-12))
			fail_msg("edge %d: turn %.17g, the features' %.17g", i, args[1], f[6]);
	}
	/* Coincident positions: turn 0, whatever the headings. */
	{
		double t[4] = { 3, -4, 0.5, -2.0 }, h[4] = { 3, -4, 1, 1.0 }, args[4];

		assert_int_equal(hylo_envelope_args(HYLO_MODE_MARINE, t, h, args), 1);
		assert_true(args[0] == 0 && args[1] == 0);
	}
}

/* Planar turn cells: [j 2 pi / 16, (j + 1) 2 pi / 16), the last also
 * holding 2 pi; the lookup through hylo_envelope_of_edge. */
static void test_turn_cells(void **state)
{
	hylo_svr_model m = model(HYLO_FEATURES_PLANAR, &turn_env), f = model(HYLO_FEATURES_FLIGHT, &turn_env);
	const double tail[4] = { 1, 2, 0, PI / 2 };
	double head[4] = { 1, 1.5, 1, PI / 2 };
	int j;

	(void)state;
	assert_int_equal(hylo_svr_check(&m, NULL), HYLO_OK);
	for (j = 0; j < 16; j++) {
		assert_true(hylo_svr_envelope_bound(&m, 0.5, j * TURN_STEP * (1 + 1e-12), 0, 0) == 10 * j + 1);
		assert_true(hylo_svr_envelope_bound(&m, 1.5, (j + 0.5) * TURN_STEP, 1, 0) == 1000 + 10 * j + 3);
		if (j > 0)
			assert_true(hylo_svr_envelope_bound(&m, 0.5, j * TURN_STEP * (1 - 1e-12), 0, 0) ==
				    10 * (j - 1) + 1);
	}
	assert_true(hylo_svr_envelope_bound(&m, 0.5, 0, 0, 1) == 2);
	assert_true(hylo_svr_envelope_bound(&m, 0.5, 2 * PI, 0, 1) == 152);  /* closed: the last cell */
	assert_true(hylo_svr_envelope_bound(&m, 0.5, nextafter(2 * PI, 0), 0, 1) == 152);
	assert_true(hylo_svr_envelope_bound(&m, 0.5, nextafter(2 * PI, 7), 0, 1) == 0);
	assert_true(hylo_svr_envelope_bound(&m, 0.5, -1e-300, 0, 1) == 0);
	assert_true(hylo_svr_envelope_bound(&m, 0.5, NAN, 0, 1) == 0);
	/* Only planar tables close their last cell; flight climbs stay open. */
	assert_true(hylo_svr_envelope_bound(&f, 0.5, 2 * PI, 0, 1) == 0);
	/* Straight behind with the same heading: 2 pi. */
	assert_true(hylo_envelope_of_edge(&m, HYLO_MODE_GROUND, tail, head) == 152);
	/* Straight behind, arriving facing it: pi, cell 8. */
	head[3] = -PI / 2;
	assert_true(hylo_envelope_of_edge(&m, HYLO_MODE_GROUND, tail, head) == 82);
	/* Ahead, the same heading: cell 0; in place: turn 0, cell 0. */
	head[1] = 2.5, head[3] = PI / 2;
	assert_true(hylo_envelope_of_edge(&m, HYLO_MODE_MARINE, tail, head) == 2);
	head[1] = 2, head[3] = -PI / 2;
	assert_true(hylo_envelope_of_edge(&m, HYLO_MODE_MARINE, tail, head) == 2);
}

static void expect_refused(hylo_svr_model *m, hylo_status want)
{
	hylo_reason r;

	assert_int_equal(hylo_svr_check(m, &r), want);
	assert_non_null(strstr(r.text, "envelope"));
}

static void test_check_refuses_bad_tables(void **state)
{
	hylo_svr_envelope e = planar_env;
	hylo_svr_model m = model(HYLO_FEATURES_PLANAR, &e), f = model(HYLO_FEATURES_FLIGHT, &e);
	hylo_svr_model di = model(HYLO_FEATURES_DI, &planar_env);

	(void)state;
	assert_int_equal(hylo_svr_check(&m, NULL), HYLO_OK);
	e.value = NULL;
	expect_refused(&m, HYLO_E_NULL);
	e = planar_env, e.n_d = 0;
	expect_refused(&m, HYLO_E_BAD_VALUE);
	e = planar_env, e.n_v = 0;
	expect_refused(&m, HYLO_E_BAD_VALUE);
	e = planar_env, e.n_z = 0;
	expect_refused(&m, HYLO_E_BAD_VALUE);
	/* Planar tables have one climb cell or turn cells covering [0, 2 pi]. */
	e = planar_env, e.n_z = 2, e.z_step = 1;
	expect_refused(&m, HYLO_E_BAD_VALUE);
	e = turn_env;
	assert_int_equal(hylo_svr_check(&m, NULL), HYLO_OK);
	e = turn_env, e.z_min = -1e-9;
	expect_refused(&m, HYLO_E_BAD_VALUE);
	e = turn_env, e.n_z = 15;
	expect_refused(&m, HYLO_E_BAD_VALUE);
	e = turn_env, e.n_z = 8, e.z_step = 2 * TURN_STEP;
	assert_int_equal(hylo_svr_check(&m, NULL), HYLO_OK);
	e = turn_env, e.z_step = TURN_STEP * (1 + 1e-9);
	expect_refused(&m, HYLO_E_BAD_VALUE);
	e = planar_env, e.d_step = 0;
	expect_refused(&m, HYLO_E_BAD_VALUE);
	e = planar_env, e.d_step = NAN;
	expect_refused(&m, HYLO_E_BAD_VALUE);
	e = planar_env, e.v_step = -0.5;
	expect_refused(&m, HYLO_E_BAD_VALUE);
	e = planar_env, e.v_min = INFINITY;
	expect_refused(&m, HYLO_E_BAD_VALUE);
	e = planar_env, e.n_d = 1u << 20, e.n_v = 1u << 10;  /* 2^40 values */
	expect_refused(&m, HYLO_E_BAD_VALUE);
	e = planar_env, e.n_v = 1u << 16;
	expect_refused(&m, HYLO_E_BAD_VALUE);
	/* Values: finite and >= 0. */
	e = planar_env;
	planar_values[7] = -1;
	expect_refused(&m, HYLO_E_BAD_VALUE);
	planar_values[7] = NAN;
	expect_refused(&m, HYLO_E_BAD_VALUE);
	planar_values[7] = INFINITY;
	expect_refused(&m, HYLO_E_BAD_VALUE);
	planar_values[7] = 121;
	assert_int_equal(hylo_svr_check(&m, NULL), HYLO_OK);
	/* Flight: climb cells need a climb step. */
	e = flight_env;
	assert_int_equal(hylo_svr_check(&f, NULL), HYLO_OK);
	e.z_step = 0;
	expect_refused(&f, HYLO_E_BAD_VALUE);
	e = flight_env, e.z_min = NAN;
	expect_refused(&f, HYLO_E_BAD_VALUE);
	/* The double integrator has no envelope. */
	expect_refused(&di, HYLO_E_BAD_VALUE);
	/* A turn table: flight only, with the envelope's distance cells and
	 * speed nodes, turn cells over [0, 2 pi]. */
	e = flight_env;
	f.turn_envelope = &flight_turn_env;
	assert_int_equal(hylo_svr_check(&f, NULL), HYLO_OK);
	{
		hylo_svr_envelope t = flight_turn_env;

		f.turn_envelope = &t;
		t.v_step = 2;
		expect_refused(&f, HYLO_E_BAD_VALUE);
		t = flight_turn_env, t.n_z = 8;
		expect_refused(&f, HYLO_E_BAD_VALUE);
		t = flight_turn_env, t.d_step = 0.5;
		expect_refused(&f, HYLO_E_BAD_VALUE);
		f.envelope = NULL;
		t = flight_turn_env;
		expect_refused(&f, HYLO_E_BAD_VALUE);
		m.envelope = &planar_env;
		m.turn_envelope = &flight_turn_env;
		expect_refused(&m, HYLO_E_BAD_VALUE);
	}
}

static void assert_features_close(const double *a, const double *b, unsigned n)
{
	unsigned k;

	for (k = 0; k < n; k++)
		if (!(fabs(a[k] - b[k]) <= 1e-12 * fmax(1, fabs(b[k]))))
			fail_msg("feature %u: %.17g vs %.17g", k, a[k], b[k]);
}

/* The envelope minimizes over b in [0, pi] only and over headings of the
 * tail fixed at 0, relying on the mirror image (y -> -y, headings negated)
 * and turns about z giving the same features; and for flight on turns about
 * z. Away from the heading feature's seam at dtheta = +-pi, exactly so to
 * rounding. */
static void test_symmetries(void **state)
{
	int i, k;

	(void)state;
	for (i = 0; i < 2000; i++) {
		double t[4], h[4], mt[4], mh[4], rt[4], rh[4], f[8], g[8];
		double phi = uniform(-PI, PI), c = cos(phi), s = sin(phi);

		t[0] = uniform(-9, 9), t[1] = uniform(-9, 9), t[2] = uniform(0, 1.2), t[3] = uniform(-PI, PI);
		h[0] = t[0] + uniform(-4, 4), h[1] = t[1] + uniform(-4, 4), h[2] = uniform(0, 1.2);
		h[3] = t[3] + uniform(-3.1, 3.1);
		hylo_features(HYLO_MODE_GROUND, t, h, f);
		for (k = 0; k < 4; k++)
			mt[k] = k == 1 || k == 3 ? -t[k] : t[k], mh[k] = k == 1 || k == 3 ? -h[k] : h[k];
		hylo_features(HYLO_MODE_GROUND, mt, mh, g);
		assert_features_close(g, f, 8);
		rt[0] = c * t[0] - s * t[1], rt[1] = s * t[0] + c * t[1], rt[2] = t[2], rt[3] = t[3] + phi;
		rh[0] = c * h[0] - s * h[1], rh[1] = s * h[0] + c * h[1], rh[2] = h[2], rh[3] = h[3] + phi;
		hylo_features(HYLO_MODE_GROUND, rt, rh, g);
		assert_features_close(g, f, 8);
	}
	for (i = 0; i < 2000; i++) {
		double t[6], h[6], rt[6], rh[6], f[9], g[9];
		double phi = uniform(-PI, PI), c = cos(phi), s = sin(phi), a1 = uniform(-PI, PI);
		double a2 = uniform(-PI, PI), s1 = uniform(0, 8), s2 = uniform(0, 8);

		for (k = 0; k < 3; k++)
			t[k] = uniform(-9, 9), h[k] = t[k] + uniform(-5, 5);
		t[3] = s1 * cos(a1), t[4] = s1 * sin(a1), t[5] = 0;
		h[3] = s2 * cos(a2), h[4] = s2 * sin(a2), h[5] = 0;
		hylo_features(HYLO_MODE_FLIGHT, t, h, f);
		for (k = 0; k < 6; k += 3) {
			const double *x = k ? h : t;
			double *y = k ? rh : rt;

			y[0] = c * x[0] - s * x[1], y[1] = s * x[0] + c * x[1], y[2] = x[2];
			y[3] = c * x[3] - s * x[4], y[4] = s * x[3] + c * x[4], y[5] = x[5];
		}
		hylo_features(HYLO_MODE_FLIGHT, rt, rh, g);
		assert_features_close(g, f, 9);
	}
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_node_speeds),
		cmocka_unit_test(test_between_nodes),
		cmocka_unit_test(test_out_of_range),
		cmocka_unit_test(test_flight),
		cmocka_unit_test(test_flight_turn_table),
		cmocka_unit_test(test_edge_args),
		cmocka_unit_test(test_turn_known),
		cmocka_unit_test(test_turn_symmetry_and_features),
		cmocka_unit_test(test_turn_cells),
		cmocka_unit_test(test_check_refuses_bad_tables),
		cmocka_unit_test(test_symmetries),
	};

	return cmocka_run_group_tests(tests, setup, NULL);
}
