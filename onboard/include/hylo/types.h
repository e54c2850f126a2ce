/* Basic types shared by every onboard module. */
#ifndef HYLO_TYPES_H
#define HYLO_TYPES_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The planner's floating type. Double throughout: the SVR evaluator must
 * match libsvm to 1e-9 relative. */
typedef double hylo_real;

/* A monotonic clock in milliseconds (the planner's optional time source). */
typedef double (*hylo_clock_fn)(void *ctx);

/* A build may add modes after these, as the toy mode of tests/toymode/
 * does: HYLO_EXTRA_MODES_H names a header that defines
 * HYLO_EXTRA_MODE_ENUM (their enumerators, from 6 on),
 * HYLO_EXTRA_MODE_RECORDS (their records, onboard/src/modes.c) and, for
 * the trainer, their models (trainer/model_table.hpp). */
#ifdef HYLO_EXTRA_MODES_H
#include HYLO_EXTRA_MODES_H
#endif

/* Locomotion modes; the values are those of goal_t.MODE_* in msgs/. Each
 * mode's description is its record in hylo/modes.h. */
typedef enum {
	HYLO_MODE_NONE = 0,
	HYLO_MODE_GROUND = 1,  /* skid-steer driving, x^s = (px, py, vx, theta) */
	HYLO_MODE_MARINE = 2,  /* paddling, x^s = (px, py, vx, theta) */
	HYLO_MODE_FLIGHT = 3,  /* quadrotor, x^s = (px, py, pz, vx, vy, vz) */
	HYLO_MODE_DI_NEG = 4,  /* double integrator on p <= 0, x^s = (p, v) */
	HYLO_MODE_DI_POS = 5,  /* double integrator on p >= 0, x^s = (p, v) */
#ifdef HYLO_EXTRA_MODE_ENUM
	HYLO_EXTRA_MODE_ENUM
#endif
	HYLO_MODE_COUNT        /* 6 */
} hylo_mode;

/* Largest sampled-coordinate dimension (flight). */
#define HYLO_XS_DIM 6

/* A point in the planner's 3-D work space: (x, y, z) in metres. Ground and
 * water points carry the surface height as z; the double integrator's phase
 * plane uses (p, v, 0). */
typedef struct {
	hylo_real x, y, z;
} hylo_point;

/* Dimension of x^s for a mode; 0 for an invalid mode. */
unsigned hylo_mode_dim(hylo_mode mode);

/* Lower-case name of a mode ("ground", "di_neg", ...); "invalid" when out of range. */
const char *hylo_mode_str(hylo_mode mode);

/* 1 when mode is one of the five real modes. */
int hylo_mode_valid(int mode);

/* The speed of x^s that a cost model's training range bounds: ground and
 * marine vx (signed), flight |v|, double integrator v (signed); 0 for an
 * invalid mode. */
hylo_real hylo_state_speed(hylo_mode mode, const hylo_real *xs);

#ifdef __cplusplus
}
#endif

#endif
