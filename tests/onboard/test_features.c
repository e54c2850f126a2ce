/*
 * The edge features (onboard/include/hylo/features.h): invariance under
 * the motions that leave the optimal cost unchanged (translation, rotation
 * about z; for ground and marine the left-right mirror), the derived
 * quantities at poses where they are known exactly, the double
 * integrator's prior where it has a closed form, and the split into
 * relative coordinates and features.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>

#include "hylo/config.h"
#include "hylo/features.h"
#include "hylo/modes.h"

#define PI 3.14159265358979323846

static void assert_features_equal(const double *a, const double *b, unsigned n)
{
	unsigned k;

	for (k = 0; k < n; k++)
		if (!(fabs(a[k] - b[k]) <= 1e-12 * fmax(1, fabs(b[k]))))
			fail_msg("feature %u: %.17g vs %.17g", k, a[k], b[k]);
}

/* Planar features of tail (x, y, v, theta) -> head. */
static void planar(const double *tail, const double *head, double *f)
{
	assert_int_equal(hylo_features(HYLO_MODE_GROUND, tail, head, f), HYLO_FEATURES_PLANAR);
}

/* The textbook wrap: fmod, then one turn. */
static double wrap_by_fmod(double a)
{
	const double two_pi = 6.283185307179586476925286766559;
	double w;

	if (!isfinite(a))
		return a;
	w = fmod(a, two_pi);
	if (w > two_pi / 2)
		w -= two_pi;
	else if (w <= -two_pi / 2)
		w += two_pi;
	return w;
}

/* hylo_wrap_angle gives fmod's bits, signed zeros included, on random
 * angles, multiples of pi and their neighbours, and beyond two turns. */
static void test_wrap_bits(void **state)
{
	const double pi = 3.141592653589793;
	uint64_t s = 12345;
	double a, w, want;
	int i, k;

	(void)state;
	for (i = 0; i < 2000000; i++) {
		s = s * 6364136223846793005ULL + 1442695040888963407ULL;
		a = ((double)(s >> 11) * 0x1.0p-53 - 0.5) * (i % 3 ? 30 : 1e4);
		if (i % 5 == 0)
			a = (double)((int)(i % 17) - 8) * pi + ((double)(s >> 11) * 0x1.0p-53 - 0.5) * 1e-12;
		w = hylo_wrap_angle(a);
		want = wrap_by_fmod(a);
		assert_memory_equal(&w, &want, sizeof w);
	}
	for (k = -8; k <= 8; k++) {
		a = k * pi;
		w = hylo_wrap_angle(a);
		want = wrap_by_fmod(a);
		assert_memory_equal(&w, &want, sizeof w);
		a = nextafter(a, INFINITY);
		w = hylo_wrap_angle(a);
		want = wrap_by_fmod(a);
		assert_memory_equal(&w, &want, sizeof w);
	}
}

static void test_planar_invariance(void **state)
{
	static const double tails[3][4] = { { 0, 0, 0.3, 0 }, { 2, -1, 1.0, 2.5 }, { -3, 4, 0, -1.2 } };
	static const double heads[4][4] = { { 1.5, 0.7, 1.2, 0.4 }, { -2, 1, 0.5, 3.0 },
					    { 0.3, -2.2, 0.0, -2.8 }, { 4, 0.1, 0.9, 1.6 } };
	unsigned i, j;

	(void)state;
	for (i = 0; i < 3; i++)
		for (j = 0; j < 4; j++) {
			const double *a = tails[i];
			double b[4], f[HYLO_FEATURES_PLANAR], g[HYLO_FEATURES_PLANAR];
			double ta[4], tb[4], ma[4], mb[4];
			double c = cos(0.9), s = sin(0.9);

			b[0] = a[0] + heads[j][0], b[1] = a[1] + heads[j][1];
			b[2] = heads[j][2], b[3] = heads[j][3];
			planar(a, b, f);
			/* Turned by 0.9 rad about the origin and moved. */
			ta[0] = c * a[0] - s * a[1] + 5, ta[1] = s * a[0] + c * a[1] - 7;
			tb[0] = c * b[0] - s * b[1] + 5, tb[1] = s * b[0] + c * b[1] - 7;
			ta[2] = a[2], tb[2] = b[2], ta[3] = a[3] + 0.9, tb[3] = b[3] + 0.9;
			planar(ta, tb, g);
			assert_features_equal(g, f, HYLO_FEATURES_PLANAR);
			/* Mirrored: y -> -y, theta -> -theta. */
			ma[0] = a[0], ma[1] = -a[1], ma[2] = a[2], ma[3] = -a[3];
			mb[0] = b[0], mb[1] = -b[1], mb[2] = b[2], mb[3] = -b[3];
			planar(ma, mb, g);
			assert_features_equal(g, f, HYLO_FEATURES_PLANAR);
		}
}

static void test_planar_known_poses(void **state)
{
	static const double o[4] = { 0, 0, 0.5, 0 };
	double f[HYLO_FEATURES_PLANAR];

	(void)state;
	/* Straight ahead, same heading: no turn, one (straight) arc. */
	{
		const double b[4] = { 3, 0, 1.0, 0 };
		const double want[HYLO_FEATURES_PLANAR] = { 3, 0, 0, 0.5, 1.0, 3, 0, 0 };

		planar(o, b, f);
		assert_features_equal(f, want, HYLO_FEATURES_PLANAR);
	}
	/* A half circle to the right: goal 2 m to the right, heading reversed.
	 * A half turn turns towards the goal (right, dtheta = -pi), whichever
	 * side of pi the heading is written on. Mirrored to the left: dy' = 2,
	 * s * dtheta = pi, bearing pi/2; turn pi, on one arc. */
	{
		const double heading[3] = { PI, -PI, 3.141593 };
		double want[HYLO_FEATURES_PLANAR] = { 0, 2, PI, 0.5, 0.5, 2, PI, 0 };
		unsigned k;

		for (k = 0; k < 3; k++) {
			const double b[4] = { 0, -2, 0.5, heading[k] };

			planar(o, b, f);
			want[2] = fabs(hylo_wrap_angle(heading[k]));
			want[6] = want[2];
			want[7] = PI - want[2];
			assert_features_equal(f, want, HYLO_FEATURES_PLANAR);
		}
	}
	/* The same with the goal on the left turns left; a heading change just
	 * short of the tie keeps its side. */
	{
		const double left[4] = { 0, 2, 0.5, -3.141593 };
		const double shy[4] = { 0, 2, 0.5, -(PI - 2 * HYLO_HALF_TURN_TIE) };
		double r[HYLO_RELATIVE_PLANAR];

		hylo_relative(HYLO_MODE_GROUND, o, left, r);
		assert_true(r[2] > 3.1415 && r[1] > 0);
		hylo_relative(HYLO_MODE_GROUND, o, shy, r);
		assert_true(r[2] < -3.1415);
	}
	/* Behind, same heading: face it (pi), drive, turn back (pi): 2 pi. The
	 * arc through it would need a full turn: mismatch 0 after wrapping;
	 * behind and slightly left, the arc is off by almost nothing either,
	 * but the turn stays near 2 pi. */
	{
		const double b[4] = { -2, 1e-9, 0, 0 };

		planar(o, b, f);
		assert_true(fabs(f[6] - 2 * PI) < 1e-6);
		assert_true(f[7] < 1e-6);
	}
	/* Ahead and to the left, pointing back at the start's line: heading
	 * change 0 but bearing 45 degrees: turn 2 * 45 degrees, arc off by 90. */
	{
		const double b[4] = { 1, 1, 0, 0 };

		planar(o, b, f);
		assert_true(fabs(f[5] - sqrt(2)) < 1e-12);
		assert_true(fabs(f[6] - PI / 2) < 1e-12);
		assert_true(fabs(f[7] - PI / 2) < 1e-12);
	}
}

/* exp of the double integrator's prior feature of the move a -> b. */
static double di_prior(hylo_mode mode, const double *a, const double *b)
{
	double f[HYLO_MAX_FEATURES];

	assert_int_equal(hylo_features(mode, a, b, f), HYLO_FEATURES_DI);
	assert_true(f[0] == a[0] && f[1] == a[1] && f[2] == b[0] && f[3] == b[1]);
	return exp(f[4]);
}

/* The double integrator's prior (features.h) where it is known in closed
 * form: rest to rest over d in di_neg, 12 d^2 / T^3 + rho T at
 * T* = (36 d^2 / rho)^(1/4) (docs/models.md section 2); no move, rho T_min
 * in both modes; coasting for 1 s in di_pos (u = 0, v' = -v) at most
 * rho * 1 s, where di_neg, undamped, must brake (0.2005 by a fine scan). */
static void test_di_prior(void **state)
{
	const double rho = HYLO_DI_PRIOR_RHO, d = 0.2;
	const double T = pow(36 * d * d / rho, 0.25), want = 12 * d * d / (T * T * T) + rho * T;
	const double a[2] = { -0.5, 0 }, b[2] = { -0.5 + d, 0 };
	const double still[2] = { 0.3, 0 };
	const double c[2] = { 0.2, 0.5 }, coast[2] = { 0.2 + 0.5 * (1 - exp(-1.0)), 0.5 * exp(-1.0) };
	double got;

	(void)state;
	got = di_prior(HYLO_MODE_DI_NEG, a, b);
	if (!(fabs(got - want) <= 1e-9 * want))
		fail_msg("di_neg rest to rest over %g: prior %.17g, closed form %.17g", d, got, want);
	assert_true(fabs(di_prior(HYLO_MODE_DI_NEG, still, still) - rho * HYLO_DI_PRIOR_T_MIN) < 1e-15);
	assert_true(fabs(di_prior(HYLO_MODE_DI_POS, still, still) - rho * HYLO_DI_PRIOR_T_MIN) < 1e-15);
	got = di_prior(HYLO_MODE_DI_POS, c, coast);
	if (!(got > 0 && got <= rho * 1.0 + 1e-12))
		fail_msg("di_pos coasting 1 s: prior %.17g above rho * 1 s", got);
	got = di_prior(HYLO_MODE_DI_NEG, c, coast);
	if (!(fabs(got - 0.200468) < 1e-5))
		fail_msg("di_neg, the same move: prior %.17g, want 0.200468", got);
}

static void test_split(void **state)
{
	static const hylo_mode modes[] = { HYLO_MODE_GROUND, HYLO_MODE_MARINE, HYLO_MODE_FLIGHT,
					   HYLO_MODE_DI_NEG, HYLO_MODE_DI_POS };
	const double a[6] = { 0.4, -1.0, 0.2, 0.7, 0.1, 0 }, b[6] = { 2.0, 1.5, -0.3, -2.0, 0.5, 0.2 };
	unsigned i;

	(void)state;
	for (i = 0; i < sizeof modes / sizeof modes[0]; i++) {
		double r[HYLO_MAX_FEATURES], f[HYLO_MAX_FEATURES], g[HYLO_MAX_FEATURES];
		unsigned nr = hylo_relative(modes[i], a, b, r);

		assert_int_equal(nr, hylo_relative_count(modes[i]));
		assert_int_equal(hylo_features_of_relative(modes[i], r, f), hylo_feature_count(modes[i]));
		assert_int_equal(hylo_features(modes[i], a, b, g), hylo_feature_count(modes[i]));
		assert_features_equal(g, f, hylo_feature_count(modes[i]));
	}
	assert_int_equal(hylo_relative_count(HYLO_MODE_GROUND), 5);
	assert_int_equal(hylo_feature_count(HYLO_MODE_GROUND), 8);
	assert_int_equal(hylo_features((hylo_mode)99, a, b, (double[9]){ 0 }), 0);
	assert_int_equal(hylo_relative_count((hylo_mode)99), 0);
}

/* The mode records (hylo/modes.h): each mode's layout gives its feature
 * counts, the layouts' feature counts differ (a model's n_features names its
 * layout, hence its SVR groups), and each layout's groups partition its
 * features. */
static void test_mode_layouts(void **state)
{
	int m, k, j;

	(void)state;
	for (m = HYLO_MODE_NONE + 1; m < HYLO_MODE_COUNT; m++) {
		const hylo_mode_desc *d = hylo_mode_describe((hylo_mode)m);
		const hylo_feature_layout *l = hylo_mode_layout((hylo_mode)m);

		assert_non_null(d);
		assert_non_null(l);
		assert_int_equal(hylo_feature_count((hylo_mode)m), l->n_features);
		assert_int_equal(hylo_relative_count((hylo_mode)m), l->n_relative);
		assert_ptr_equal(hylo_feature_layout_of_count(l->n_features), l);
		assert_true(d->xs_dim >= 1 && d->xs_dim <= HYLO_XS_DIM);
		assert_true(d->speed_index + d->speed_width <= d->xs_dim);
		assert_true(d->distance_dims <= d->xs_dim);
		assert_int_equal(hylo_mode_parse(d->name), m);
	}
	assert_null(hylo_mode_describe(HYLO_MODE_NONE));
	assert_null(hylo_mode_describe(HYLO_MODE_COUNT));
	assert_int_equal(hylo_mode_parse("walking"), HYLO_MODE_NONE);
	for (k = HYLO_LAYOUT_NONE + 1; k < HYLO_LAYOUT_COUNT; k++) {
		const hylo_feature_layout *l = hylo_feature_layout_of((hylo_layout_kind)k);
		unsigned seen = 0;

		assert_non_null(l);
		assert_true(l->n_features <= HYLO_MAX_FEATURES && l->n_groups >= 1);
		assert_int_equal(l->begin[0], 0);
		assert_int_equal(l->begin[l->n_groups], l->n_features);
		for (j = 0; j < l->n_groups; j++)
			assert_true(l->begin[j] < l->begin[j + 1]);
		for (j = 0; j < l->n_features; j++)
			seen |= 1u << l->order[j];
		assert_int_equal(seen, (1u << l->n_features) - 1);
		for (j = HYLO_LAYOUT_NONE + 1; j < k; j++)
			assert_int_not_equal(hylo_feature_layout_of((hylo_layout_kind)j)->n_features, l->n_features);
	}
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_wrap_bits),
		cmocka_unit_test(test_planar_invariance),
		cmocka_unit_test(test_planar_known_poses),
		cmocka_unit_test(test_di_prior),
		cmocka_unit_test(test_split),
		cmocka_unit_test(test_mode_layouts),
	};

	return cmocka_run_group_tests_name("features", tests, NULL, NULL);
}
