/*
 * Relative features of an edge (models.md section 7), the SVR's inputs. The
 * optimal cost is invariant to translation (all modes) and, for ground and
 * marine, to rotation about z, so features are relative:
 *   ground, marine: (dx', dy', wrap(theta2 - theta1), vx1, vx2), where
 *                   (dx', dy') is p2 - p1 rotated into the start's heading
 *                   frame: dx' = cos(t1)*dx + sin(t1)*dy,
 *                   dy' = -sin(t1)*dx + cos(t1)*dy                (5)
 *   flight:         (p2 - p1, v1, v2), horizontal components rotated
 *                   into the heading of the horizontal displacement
 *                   (else of v1, else of v2): dx' = |(dx, dy)|, dy' = 0
 *                   (9). models.md has world axes (yaw is 0 by the
 *                   virtual constraint); the cost changes by at most
 *                   0.1% under a turn about z (measured at 30 and 45
 *                   degrees), and these features let every training
 *                   pair teach every heading.
 *   di_neg, di_pos: (p1, v1, p2, v2), absolute: the domain bound
 *                   p = 0 breaks translation invariance            (4)
 * The trainer computes the same features in the same order.
 */
#ifndef HYLO_FEATURES_H
#define HYLO_FEATURES_H

#include "hylo/types.h"

#define HYLO_FEATURES_PLANAR 5
#define HYLO_FEATURES_FLIGHT 9
#define HYLO_FEATURES_DI 4

/** Number of features of mode (0 for an invalid mode). */
unsigned hylo_feature_count(hylo_mode mode);

/**
 * Writes the features of the edge tail -> head (sampled coordinates, as in
 * goal_t) into f and returns their number (0 for an invalid mode, f
 * untouched). No allocation.
 */
unsigned hylo_features(hylo_mode mode, const hylo_real *tail, const hylo_real *head,
                       hylo_real *f);

/** a wrapped into (-pi, pi]. */
hylo_real hylo_wrap_angle(hylo_real a);

#endif
