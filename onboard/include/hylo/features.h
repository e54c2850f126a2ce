/*
 * The SVR's inputs for an edge, in two steps.
 *
 * 1. Relative coordinates (docs/models.md section 7; what a training dataset
 *    stores as f0, f1, ...). The optimal cost is invariant to translation
 *    (all modes) and, for ground and marine, to rotation about z:
 *   ground, marine: (dx', dy', wrap(theta2 - theta1), vx1, vx2), where
 *                   (dx', dy') is p2 - p1 rotated into the start's heading
 *                   frame: dx' = cos(t1)*dx + sin(t1)*dy,
 *                   dy' = -sin(t1)*dx + cos(t1)*dy                (5);
 *                   a heading change within HYLO_HALF_TURN_TIE of pi
 *                   is the half turn towards the goal's side (sign of dy')
 *   flight:         (p2 - p1, v1, v2), horizontal components rotated
 *                   into the heading of the horizontal displacement
 *                   (else of v1, else of v2): dx' = |(dx, dy)|, dy' = 0
 *                   (9). docs/models.md has world axes; the cost is
 *                   nearly invariant under a turn about z, and these
 *                   features let every training pair teach every
 *                   heading (docs/decisions.md).
 *   di_neg, di_pos: (p1, v1, p2, v2), absolute: the domain bound
 *                   p = 0 breaks translation invariance            (4)
 *
 * 2. Features, from the relative coordinates. Flight uses them as they
 *    are. The double integrator (5): (p1, v1, p2, v2, log prior), the
 *    prior being the least cost of the move without the bounds on u and p,
 *      prior = min over T in [T_MIN, T_MAX] of
 *              (x2 - Phi x1)' W^-1 (x2 - Phi x1) + rho T,
 *    Phi(T) and W(T) the transition and controllability Gramian of
 *    p' = v, v' = u (di_pos: v' = u - v), rho = HYLO_DI_PRIOR_RHO. Where
 *    the bounds are inactive (most short edges) it is the optimal cost
 *    itself, so the model learns the bounds' effect, not the whole cost
 *    (docs/decisions.md, "The double integrator's prior feature").
 *    Ground and marine (8):
 *      (dx', |dy'|, s*dtheta, vx1, vx2, d, turn, arc)
 *    with s = -1 when dy' < 0, else 1: the robots are left-right symmetric,
 *    so a goal on the right costs what its mirror image on the left does
 *    and the model learns one half; d = |(dx', dy')|; with the bearing
 *    b = atan2(|dy'|, dx') in [0, pi], turn = b + |wrap(s*dtheta - b)|, the
 *    least heading change of any path that ends at the goal (face it, drive,
 *    turn to the goal heading), and arc = |wrap(s*dtheta - 2b)|, zero when one
 *    circular arc joins the two poses. Skid-steer turning pays a Coulomb-like
 *    resistance (docs/models.md section 3), so the cost is kinked along exactly
 *    these quantities, which an RBF kernel on (dx', dy', dtheta) smooths
 *    over (docs/decisions.md, "Ground and marine models see 8 features").
 * The trainer computes the same features with these functions.
 */
#ifndef HYLO_FEATURES_H
#define HYLO_FEATURES_H

#include "hylo/types.h"

#ifdef __cplusplus
extern "C" {
#endif

#define HYLO_RELATIVE_PLANAR 5
#define HYLO_FEATURES_PLANAR 8
#define HYLO_FEATURES_FLIGHT 9
#define HYLO_RELATIVE_DI 4
#define HYLO_FEATURES_DI 5

/* The double integrator's prior feature: the time weight and the bounds of
 * T of docs/models.md section 2 (the defaults; a model trained with another
 * rho still sees a faithful shape, learned from its labels). */
#define HYLO_DI_PRIOR_RHO 0.1
#define HYLO_DI_PRIOR_T_MIN 0.05
#define HYLO_DI_PRIOR_T_MAX 20.0

/* How close to pi a heading change is a half turn (hylo_half_turn_towards):
 * well above a grid's rounding (3.141593 - pi = 3.5e-7), well below any two
 * headings a scene means apart. */
#define HYLO_HALF_TURN_TIE 1e-5

/** Number of relative coordinates of mode (0 for an invalid mode). */
unsigned hylo_relative_count(hylo_mode mode);

/** Number of features of mode (0 for an invalid mode). */
unsigned hylo_feature_count(hylo_mode mode);

/**
 * Writes the relative coordinates of the edge tail -> head (sampled
 * coordinates, as in goal_t) into r and returns their number (0 for an
 * invalid mode, r untouched). No allocation.
 */
unsigned hylo_relative(hylo_mode mode, const hylo_real *tail, const hylo_real *head,
                       hylo_real *r);

/**
 * Writes the features of relative coordinates r into f and returns their
 * number (0 for an invalid mode, f untouched). f must not overlap r.
 */
unsigned hylo_features_of_relative(hylo_mode mode, const hylo_real *r, hylo_real *f);

/**
 * Writes the features of the edge tail -> head into f and returns their
 * number (0 for an invalid mode, f untouched). No allocation.
 */
unsigned hylo_features(hylo_mode mode, const hylo_real *tail, const hylo_real *head,
                       hylo_real *f);

/** a wrapped into (-pi, pi]. */
hylo_real hylo_wrap_angle(hylo_real a);

/**
 * A heading change dtheta (wrapped), with a half turn taken towards side:
 * within HYLO_HALF_TURN_TIE of pi, |dtheta| with the sign of side (side < 0:
 * a right turn, else left); otherwise dtheta. A half turn is two turns, left
 * and right, and the wrap picks one by the headings' last digit (a grid's
 * 3.141593 is above pi); towards the goal (side = dy', the displacement's
 * left component in the tail's frame) is the cheaper one unless the two
 * cost nearly the same (docs/decisions.md, "Half turns and headings across
 * +-pi"). Used by hylo_relative and hylo_envelope_turn_of alike.
 */
hylo_real hylo_half_turn_towards(hylo_real dtheta, hylo_real side);

#ifdef __cplusplus
}
#endif

#endif
