/*
 * The robots the planner node serves, with the cost models compiled in from
 * onboard/models/ (a generated list, tools/gen-model-registry). ambot
 * (ground, marine), drivocopter (ground, flight) and di (di_neg, di_pos) are
 * always known; a mode without a committed model makes plans for that robot
 * answer "no model". Any other <robot>_<mode>.h adds a robot of its own.
 * Each robot's body radius comes from its robot file,
 * trainer/params/<robot>.yaml (body: radius_m); a robot without one gets 0.
 */
#ifndef HYLO_NODE_REGISTRY_H
#define HYLO_NODE_REGISTRY_H

#include <stdint.h>
#include "hylo/robot.h"
#include "hylo/svr.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
	const hylo_svr_model *model;
	const hylo_svr_model *feasibility;   /* NULL: none */
	const char *robot;
	hylo_mode mode;
	double takeoff_j, landing_j;    /* flight models: switch costs into and out of the mode; else -1 */
} hylo_registry_model;

extern const hylo_registry_model hylo_registry_models[];
extern const uint32_t hylo_registry_n_models;

/* The body radius of each robot with a robot file. */
typedef struct {
	const char *robot;
	double radius_m;
} hylo_registry_body;

extern const hylo_registry_body hylo_registry_bodies[];
extern const uint32_t hylo_registry_n_bodies;

/** The registry's entry for robot's body, or NULL when it has no robot file
 * (its body radius is then 0). */
const hylo_registry_body *hylo_registry_body_of(const char *robot);

/**
 * Fills robots[0 .. cap) from the registry (models, switch costs, body
 * radii) and returns their number, or 0 with *reason set when cap is too
 * small or a model would give a robot a third mode. A model's takeoff_j is
 * the switch into its mode from the robot's other mode, landing_j the
 * switch back, whichever of the two modes comes first. No allocation.
 */
uint32_t hylo_registry_robots(hylo_robot *robots, uint32_t cap, hylo_reason *reason);

/** hylo_registry_robots from the given tables instead of the generated ones
 * (tests/node/test_registry.c). */
uint32_t hylo_registry_robots_of(const hylo_registry_model *models, uint32_t n_models,
				 const hylo_registry_body *bodies, uint32_t n_bodies, hylo_robot *robots,
				 uint32_t cap, hylo_reason *reason);

#ifdef __cplusplus
}
#endif

#endif
