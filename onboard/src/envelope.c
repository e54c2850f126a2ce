#include <math.h>
#include <stddef.h>
#include "hylo/envelope.h"
#include "hylo/features.h"
#include "hylo/modes.h"

hylo_real hylo_envelope_turn_of(hylo_real bearing, hylo_real dtheta)
{
	hylo_real s = bearing < 0 ? -1 : 1, b = fabs(bearing);

	return b + fabs(hylo_wrap_angle(s * hylo_half_turn_towards(dtheta, bearing) - b));
}

hylo_real hylo_envelope_turn(hylo_real phi, hylo_real theta1, hylo_real theta2)
{
	return hylo_envelope_turn_of(hylo_wrap_angle(phi - theta1), hylo_wrap_angle(theta2 - theta1));
}

hylo_real hylo_envelope_flight_turn_of(hylo_real phi, hylo_real psi1, int moving1, hylo_real psi2,
				       int moving2)
{
	hylo_real a1 = moving1 ? fabs(hylo_wrap_angle(psi1 - phi)) : 0;
	hylo_real a2 = moving2 ? fabs(hylo_wrap_angle(psi2 - phi)) : 0;

	return a1 + a2;
}

int hylo_envelope_flight_turn(const hylo_real *tail, const hylo_real *head, hylo_real *turn)
{
	hylo_real dx, dy;
	int moving1, moving2;

	if (!tail || !head || !turn || tail[5] != 0 || head[5] != 0)
		return 0;
	dx = head[0] - tail[0];
	dy = head[1] - tail[1];
	if (dx == 0 && dy == 0)
		return 0;
	moving1 = tail[3] != 0 || tail[4] != 0;
	moving2 = head[3] != 0 || head[4] != 0;
	*turn = hylo_envelope_flight_turn_of(atan2(dy, dx), moving1 ? atan2(tail[4], tail[3]) : 0, moving1,
					     moving2 ? atan2(head[4], head[3]) : 0, moving2);
	return isfinite(*turn);
}

int hylo_envelope_args(hylo_mode mode, const hylo_real *tail, const hylo_real *head,
		       hylo_real *args)
{
	const hylo_feature_layout *layout = hylo_mode_layout(mode);
	hylo_real dx, dy;

	if (!tail || !head || !args)
		return 0;
	dx = head[0] - tail[0];
	dy = head[1] - tail[1];
	switch (layout ? layout->kind : HYLO_LAYOUT_NONE) {
	case HYLO_LAYOUT_PLANAR:
		args[0] = sqrt(dx * dx + dy * dy);
		/* Coincident positions: turn 0 (the features' turn there depends
		 * on the tail heading's quadrant; the table's first cell holds
		 * every such edge). */
		args[1] = dx == 0 && dy == 0 ? 0 : hylo_envelope_turn(atan2(dy, dx), tail[3], head[3]);
		args[2] = tail[2];
		args[3] = head[2];
		return 1;
	case HYLO_LAYOUT_SPATIAL:
		if (tail[5] != 0 || head[5] != 0)
			return 0;
		args[0] = sqrt(dx * dx + dy * dy);
		args[1] = head[2] - tail[2];
		args[2] = sqrt(tail[3] * tail[3] + tail[4] * tail[4]);
		args[3] = sqrt(head[3] * head[3] + head[4] * head[4]);
		return 1;
	default:
		return 0;
	}
}

hylo_real hylo_envelope_of_edge(const hylo_svr_model *m, hylo_mode mode, const hylo_real *tail_xs,
				const hylo_real *head_xs)
{
	hylo_real a[4], e, turn, t;

	if (!m || !m->envelope || m->n_features != hylo_feature_count(mode) ||
	    !hylo_envelope_args(mode, tail_xs, head_xs, a))
		return 0;
	e = hylo_svr_envelope_bound(m, a[0], a[1], a[2], a[3]);
	if (m->turn_envelope && hylo_mode_layout(mode)->kind == HYLO_LAYOUT_SPATIAL &&
	    hylo_envelope_flight_turn(tail_xs, head_xs, &turn) &&
	    (t = hylo_svr_turn_envelope_bound(m, a[0], a[1], turn, a[2], a[3])) > e)
		e = t;
	return e;
}
