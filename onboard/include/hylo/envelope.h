/*
 * The envelope of an edge: what a cost model's envelope table
 * (hylo_svr_envelope, svr.h) is looked up with, computed from the edge's two
 * sampled states, so that the planner, the tools and the trainer measure
 * edges the same way.
 *   ground, marine: (d, turn, vx1, vx2), d = |(x2 - x1, y2 - y1)| and turn =
 *                   hylo_envelope_turn(atan2(y2 - y1, x2 - x1), theta1,
 *                   theta2), 0 when the two positions coincide
 *   flight:         (d, z2 - z1, |(vx1, vy1)|, |(vx2, vy2)|), d the
 *                   horizontal distance; only level velocities (vz = 0):
 *                   the roadmap uses no others and the model was trained on
 *                   no others, so an edge with a vertical velocity has none
 *   double integrator: none (its features are absolute positions)
 * The bound holds for every heading (ground, marine: every tail and head
 * heading of that turn; flight: every direction of either level velocity
 * and of the displacement), because the table is the least cost over all
 * of them. Flight models also carry a turn table (svr.h, turn_envelope):
 * by distance and hylo_envelope_flight_turn() instead of climb.
 */
#ifndef HYLO_ENVELOPE_H
#define HYLO_ENVELOPE_H

#include "hylo/svr.h"
#include "hylo/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/**
 * The turn of a planar edge [rad], in [0, 2 pi]: the least total heading
 * change of a path from the tail's pose to the head's (face the goal, drive,
 * turn to the goal's heading), the SVR's turn feature (features.h, feature
 * 6), computed from the world bearing phi = atan2(dy, dx) of the
 * displacement and the tail and head headings theta1, theta2 [rad]:
 *   b = wrap(phi - theta1), s = b < 0 ? -1 : 1, b = |b|,
 *   dth = s * wrap(theta2 - theta1), turn = b + |wrap(dth - b)|
 * (wrap: hylo_wrap_angle; a half turn, within HYLO_HALF_TURN_TIE of pi,
 * turns towards the goal, dth = +|dth|, as in the features:
 * hylo_half_turn_towards). Straight ahead with the same heading 0; the goal
 * straight behind with the same heading 2 pi. A caller can compute phi once
 * per pair of positions; the result is bit for bit hylo_envelope_args()'s.
 * The features compute it along another path (in the tail's frame), so the
 * two may differ in the last bits: every envelope turn cell holds for edges
 * on either side of its boundaries (onboard/models/README.md, "Envelope").
 * fmod and fabs only (exact). Not finite when an argument is not (the
 * lookup then gives no bound). No allocation; safe in a control loop.
 */
hylo_real hylo_envelope_turn(hylo_real phi, hylo_real theta1, hylo_real theta2);

/**
 * The same turn from its parts: bearing = wrap(phi - theta1), the
 * displacement's bearing in the tail's frame, and dtheta = wrap(theta2 -
 * theta1); hylo_envelope_turn() is exactly this of those. For callers that
 * turn many heading pairs of one pair of positions. No allocation.
 */
hylo_real hylo_envelope_turn_of(hylo_real bearing, hylo_real dtheta);

/**
 * The turn of a flight edge [rad], in [0, 2 pi]: how far its level
 * velocities point away from the horizontal displacement, the turn table's
 * argument (svr.h, turn_envelope):
 *   turn = |wrap(psi1 - phi)| + |wrap(psi2 - phi)|
 * with phi = atan2(dy, dx) the displacement's heading and psi = atan2(vy,
 * vx) a velocity's, a zero velocity's term 0. Writes it and returns 1;
 * returns 0 when the positions coincide horizontally (the features then
 * take another frame) or a velocity is not level. libm's atan2, as the
 * features; no allocation; safe in a control loop.
 */
int hylo_envelope_flight_turn(const hylo_real *tail_xs, const hylo_real *head_xs, hylo_real *turn);

/**
 * The same from its parts, for callers that turn many velocity pairs of one
 * displacement: phi the displacement's heading, psi1 and psi2 the
 * velocities' (ignored where moving1, moving2 are 0: a zero velocity).
 * hylo_envelope_flight_turn() is exactly this of those. No allocation.
 */
hylo_real hylo_envelope_flight_turn_of(hylo_real phi, hylo_real psi1, int moving1, hylo_real psi2,
                                       int moving2);

/**
 * Writes the envelope arguments (distance [m], turn [rad] or climb [m],
 * tail speed, head speed [m/s]; see above) of the edge tail_xs -> head_xs
 * (sampled coordinates of mode, HYLO_XS_DIM at most) into args[4] and
 * returns 1; returns 0 and leaves args untouched when the edge has none
 * (the double integrator, an invalid mode, a flight state with vz != 0).
 * Uses sqrt and, for ground and marine, atan2 (libm's, as the features
 * do). No allocation; safe in a control loop.
 */
int hylo_envelope_args(hylo_mode mode, const hylo_real *tail_xs, const hylo_real *head_xs,
                       hylo_real *args);

/**
 * m's envelope bound [J] for the edge tail_xs -> head_xs of mode:
 * hylo_svr_envelope_bound() at hylo_envelope_args(), for flight the larger
 * of that and hylo_svr_turn_envelope_bound() at the edge's
 * hylo_envelope_flight_turn(). A lower bound of
 * hylo_svr_predict() for the edge when both speeds lie on the table's speed
 * nodes (to 1e-9 m/s); between nodes see hylo_svr_envelope_bound(). 0 ("no
 * envelope") when m or a state is NULL, m has no envelope, m's feature count
 * is not mode's, or the edge has no arguments or lies outside the table.
 * No allocation; safe in a control loop.
 */
hylo_real hylo_envelope_of_edge(const hylo_svr_model *m, hylo_mode mode, const hylo_real *tail_xs,
                                const hylo_real *head_xs);

#ifdef __cplusplus
}
#endif

#endif
