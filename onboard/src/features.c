#include <math.h>
#include <stddef.h>
#include "hylo/features.h"
#include "hylo/modes.h"

/* The kind of mode's features (hylo/modes.h), HYLO_LAYOUT_NONE for an
 * invalid mode. */
static hylo_layout_kind layout_kind(hylo_mode mode)
{
	const hylo_mode_desc *d = hylo_mode_describe(mode);

	return d ? d->layout : HYLO_LAYOUT_NONE;
}

unsigned hylo_relative_count(hylo_mode mode)
{
	const hylo_feature_layout *l = hylo_mode_layout(mode);

	return l ? l->n_relative : 0;
}

unsigned hylo_feature_count(hylo_mode mode)
{
	const hylo_feature_layout *l = hylo_mode_layout(mode);

	return l ? l->n_features : 0;
}

hylo_real hylo_wrap_angle(hylo_real a)
{
	const hylo_real two_pi = 6.283185307179586476925286766559;
	hylo_real w;

	if (!isfinite(a))
		return a;
	/* Within two turns, one exact subtraction gives fmod's bits (its sign of
	 * zero included) without its cost; the planner wraps millions of angles. */
	if (a < 2 * two_pi && a > -2 * two_pi) {
		w = a;
		if (w >= two_pi) {
			w -= two_pi;
		} else if (w <= -two_pi) {
			w += two_pi;
			if (w == 0)
				w = -w;
		}
	} else {
		w = fmod(a, two_pi);      /* (-2pi, 2pi), sign of a */
	}
	if (w > two_pi / 2)
		w -= two_pi;
	else if (w <= -two_pi / 2)
		w += two_pi;
	return w;
}

hylo_real hylo_half_turn_towards(hylo_real dtheta, hylo_real side)
{
	const hylo_real pi = 3.141592653589793238462643383279;

	if (!(fabs(dtheta) >= pi - HYLO_HALF_TURN_TIE))
		return dtheta;
	return side < 0 ? -fabs(dtheta) : fabs(dtheta);
}

/* Flight's frame: the heading of the horizontal displacement, else of the
 * start's horizontal velocity, else of the goal's, else the world's. */
static void flight_frame(const hylo_real *tail, const hylo_real *head, hylo_real *c, hylo_real *s)
{
	hylo_real cand[3][2];
	unsigned i;

	cand[0][0] = head[0] - tail[0];
	cand[0][1] = head[1] - tail[1];
	cand[1][0] = tail[3];
	cand[1][1] = tail[4];
	cand[2][0] = head[3];
	cand[2][1] = head[4];
	for (i = 0; i < 3; i++) {
		hylo_real n = hypot(cand[i][0], cand[i][1]);

		if (n > 0) {
			*c = cand[i][0] / n;
			*s = cand[i][1] / n;
			return;
		}
	}
	*c = 1;
	*s = 0;
}

unsigned hylo_relative(hylo_mode mode, const hylo_real *tail, const hylo_real *head,
		       hylo_real *f)
{
	unsigned k;

	switch (layout_kind(mode)) {
	case HYLO_LAYOUT_PLANAR: {
		hylo_real dx = head[0] - tail[0], dy = head[1] - tail[1];
		hylo_real c = cos(tail[3]), s = sin(tail[3]);

		f[0] = c * dx + s * dy;
		f[1] = -s * dx + c * dy;
		f[2] = hylo_half_turn_towards(hylo_wrap_angle(head[3] - tail[3]), f[1]);
		f[3] = tail[2];
		f[4] = head[2];
		return HYLO_RELATIVE_PLANAR;
	}
	case HYLO_LAYOUT_SPATIAL: {
		hylo_real c, s;

		flight_frame(tail, head, &c, &s);
		for (k = 0; k < 3; k++) {
			const hylo_real *v = k == 0 ? NULL : k == 1 ? tail + 3 : head + 3;
			hylo_real x = v ? v[0] : head[0] - tail[0], y = v ? v[1] : head[1] - tail[1];

			f[3 * k] = c * x + s * y;
			f[3 * k + 1] = -s * x + c * y;
			f[3 * k + 2] = v ? v[2] : head[2] - tail[2];
		}
		return HYLO_FEATURES_FLIGHT;
	}
	case HYLO_LAYOUT_PHASE:
		f[0] = tail[0];
		f[1] = tail[1];
		f[2] = head[0];
		f[3] = head[1];
		return HYLO_RELATIVE_DI;
	default:
		return 0;
	}
}

/* The double integrator's control energy of the move r = (p1, v1, p2, v2)
 * in time T without the bounds on u and p: (x2 - Phi x1)' W^-1 (x2 - Phi x1)
 * with the transition Phi(T) and the controllability Gramian W(T) of
 * p' = v, v' = u (damped: v' = u - v), plus the time weight. */
static hylo_real di_energy(int damped, const hylo_real *r, hylo_real T)
{
	hylo_real w11, w12, w22, dp, dv;

	if (damped) {
		hylo_real e = exp(-T), e1 = 1 - e, e2 = 1 - e * e;

		w11 = T - 2 * e1 + e2 / 2;
		w12 = e1 - e2 / 2;
		w22 = e2 / 2;
		dp = r[2] - (r[0] + e1 * r[1]);
		dv = r[3] - e * r[1];
	} else {
		w11 = T * T * T / 3;
		w12 = T * T / 2;
		w22 = T;
		dp = r[2] - (r[0] + T * r[1]);
		dv = r[3] - r[1];
	}
	return (w22 * dp * dp - 2 * w12 * dp * dv + w11 * dv * dv) / (w11 * w22 - w12 * w12) +
	       HYLO_DI_PRIOR_RHO * T;
}

/* min over T in [HYLO_DI_PRIOR_T_MIN, HYLO_DI_PRIOR_T_MAX] of di_energy: the
 * best of 65 geometrically spaced times, refined by 32 steps of a
 * golden-section search between its neighbours. Fixed work (99
 * evaluations), no allocation. */
static hylo_real di_prior(int damped, const hylo_real *r)
{
	const hylo_real ratio = 1.098138675682947;  /* (T_MAX / T_MIN)^(1/64) */
	const hylo_real g = 0.381966011250105;      /* (3 - sqrt 5) / 2 */
	hylo_real t = HYLO_DI_PRIOR_T_MIN, best_t = t, best = di_energy(damped, r, t);
	hylo_real a, b, m1, m2, c1, c2;
	int k;

	for (k = 1; k <= 64; k++) {
		hylo_real c;

		t = k == 64 ? HYLO_DI_PRIOR_T_MAX : t * ratio;
		c = di_energy(damped, r, t);
		if (c < best) {
			best = c;
			best_t = t;
		}
	}
	a = best_t > HYLO_DI_PRIOR_T_MIN ? best_t / ratio : best_t;
	b = best_t < HYLO_DI_PRIOR_T_MAX ? best_t * ratio : best_t;
	m1 = a + g * (b - a);
	m2 = b - g * (b - a);
	c1 = di_energy(damped, r, m1);
	c2 = di_energy(damped, r, m2);
	for (k = 0; k < 32; k++) {
		if (c1 < c2) {
			b = m2;
			m2 = m1;
			c2 = c1;
			m1 = a + g * (b - a);
			c1 = di_energy(damped, r, m1);
		} else {
			a = m1;
			m1 = m2;
			c1 = c2;
			m2 = b - g * (b - a);
			c2 = di_energy(damped, r, m2);
		}
	}
	if (c1 < best)
		best = c1;
	return c2 < best ? c2 : best;
}

unsigned hylo_features_of_relative(hylo_mode mode, const hylo_real *r, hylo_real *f)
{
	unsigned k, n;

	if (layout_kind(mode) == HYLO_LAYOUT_PLANAR) {
		hylo_real s = r[1] < 0 ? -1 : 1, dy = s * r[1], dth = s * r[2];
		hylo_real b = atan2(dy, r[0]);  /* [0, pi] */

		f[0] = r[0];
		f[1] = dy;
		f[2] = dth;
		f[3] = r[3];
		f[4] = r[4];
		f[5] = hypot(r[0], dy);
		f[6] = b + fabs(hylo_wrap_angle(dth - b));
		f[7] = fabs(hylo_wrap_angle(dth - 2 * b));
		return HYLO_FEATURES_PLANAR;
	}
	n = hylo_relative_count(mode);
	for (k = 0; k < n; k++)
		f[k] = r[k];
	if (layout_kind(mode) == HYLO_LAYOUT_PHASE)
		f[n] = log(di_prior(hylo_mode_describe(mode)->damped, r));
	return hylo_feature_count(mode);
}

unsigned hylo_features(hylo_mode mode, const hylo_real *tail, const hylo_real *head,
		       hylo_real *f)
{
	hylo_real r[HYLO_MAX_FEATURES];  /* as many relative coordinates as any layout's features */

	if (hylo_relative(mode, tail, head, r) == 0)
		return 0;
	return hylo_features_of_relative(mode, r, f);
}
