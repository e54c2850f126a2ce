/*
 * The robots the planner node serves, with the cost models compiled in from
 * onboard/models/ (a generated list, tools/gen-model-registry). ambot
 * (ground, marine), drivocopter (ground, flight) and di (di_neg, di_pos) are
 * always known; a mode without a committed model makes plans for that robot
 * answer "no model". Any other <robot>_<mode>.h adds a robot of its own.
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
	double takeoff_j, landing_j;    /* flight models: switch costs; else -1 */
} hylo_registry_model;

extern const hylo_registry_model hylo_registry_models[];
extern const uint32_t hylo_registry_n_models;

/**
 * Fills robots[0 .. cap) from the registry and returns their number, or 0
 * with *reason set when cap is too small. No allocation.
 */
uint32_t hylo_registry_robots(hylo_robot *robots, uint32_t cap, hylo_reason *reason);

#ifdef __cplusplus
}
#endif

#endif
