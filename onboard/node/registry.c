#include <string.h>

#include "node/registry.h"

static const struct {
	const char *name;
	hylo_mode modes[2];
} standard[] = {
	{ "ambot", { HYLO_MODE_GROUND, HYLO_MODE_MARINE } },
	{ "drivocopter", { HYLO_MODE_GROUND, HYLO_MODE_FLIGHT } },
	{ "di", { HYLO_MODE_DI_NEG, HYLO_MODE_DI_POS } },
};
#define N_STANDARD (sizeof standard / sizeof standard[0])

static int find_robot(const hylo_robot *robots, uint32_t n, const char *name)
{
	uint32_t k;

	for (k = 0; k < n; k++)
		if (strcmp(robots[k].name, name) == 0)
			return (int)k;
	return -1;
}

/* Binds model entry e to its robot's mode, adding the mode if the robot
 * does not have it yet (non-standard robots); fails naming the robot and
 * the mode when the robot has two other modes already. */
static hylo_status bind(hylo_robot *rb, const hylo_registry_model *e, hylo_reason *reason)
{
	int k = hylo_robot_mode_index(rb, e->mode), n_max = sizeof rb->modes / sizeof rb->modes[0];

	if (k < 0) {
		if ((int)rb->n_modes >= n_max)
			return hylo_fail(reason, HYLO_E_BAD_VALUE,
					 "robot %s: model %s adds mode %s to its %s and %s (a robot has "
					 "at most %d modes)", rb->name, e->model ? e->model->name : "?",
					 hylo_mode_str(e->mode), hylo_mode_str(rb->modes[0].mode),
					 hylo_mode_str(rb->modes[1].mode), n_max);
		k = (int)rb->n_modes++;
		memset(&rb->modes[k], 0, sizeof rb->modes[k]);
		rb->modes[k].mode = e->mode;
	}
	rb->modes[k].model = e->model;
	rb->modes[k].feasibility = e->feasibility;
	/* A model's switch costs are into its mode (takeoff) and out of it
	 * (landing); switch_cost[0] is modes[0] -> modes[1]. */
	if (e->takeoff_j >= 0 && e->landing_j >= 0) {
		rb->switch_cost[k == 1 ? 0 : 1] = e->takeoff_j;
		rb->switch_cost[k == 1 ? 1 : 0] = e->landing_j;
	}
	return HYLO_OK;
}

static const hylo_registry_body *body_of(const hylo_registry_body *bodies, uint32_t n_bodies,
					const char *robot)
{
	uint32_t k;

	for (k = 0; k < n_bodies; k++)
		if (strcmp(bodies[k].robot, robot) == 0)
			return &bodies[k];
	return NULL;
}

const hylo_registry_body *hylo_registry_body_of(const char *robot)
{
	return body_of(hylo_registry_bodies, hylo_registry_n_bodies, robot);
}

uint32_t hylo_registry_robots(hylo_robot *robots, uint32_t cap, hylo_reason *reason)
{
	return hylo_registry_robots_of(hylo_registry_models, hylo_registry_n_models, hylo_registry_bodies,
				       hylo_registry_n_bodies, robots, cap, reason);
}

uint32_t hylo_registry_robots_of(const hylo_registry_model *models, uint32_t n_models,
				 const hylo_registry_body *bodies, uint32_t n_bodies, hylo_robot *robots,
				 uint32_t cap, hylo_reason *reason)
{
	uint32_t n = 0, k, m;

	for (k = 0; k < N_STANDARD; k++) {
		if (n == cap)
			goto full;
		memset(&robots[n], 0, sizeof robots[n]);
		robots[n].name = standard[k].name;
		robots[n].n_modes = 2;
		for (m = 0; m < 2; m++)
			robots[n].modes[m].mode = standard[k].modes[m];
		n++;
	}
	for (k = 0; k < n_models; k++) {
		const hylo_registry_model *e = &models[k];
		int r = find_robot(robots, n, e->robot);

		if (r < 0) {
			if (n == cap)
				goto full;
			memset(&robots[n], 0, sizeof robots[n]);
			robots[n].name = e->robot;
			r = (int)n++;
		}
		if (bind(&robots[r], e, reason) != HYLO_OK)
			return 0;
	}
	for (k = 0; k < n; k++) {
		const hylo_registry_body *b = body_of(bodies, n_bodies, robots[k].name);

		robots[k].body_radius_m = b ? b->radius_m : 0;
	}
	return n;
full:
	hylo_fail(reason, HYLO_E_CAP_ROBOTS, "more robots than HYLO_MAX_ROBOTS = %d",
		  HYLO_MAX_ROBOTS);
	return 0;
}
