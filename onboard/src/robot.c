#include "hylo/robot.h"

#include <math.h>
#include <string.h>

#include "hylo/config.h"
#include "hylo/features.h"

int hylo_robot_mode_index(const hylo_robot *robot, hylo_mode mode)
{
	uint32_t k;

	for (k = 0; k < robot->n_modes && k < 2; k++)
		if (robot->modes[k].mode == mode)
			return (int)k;
	return -1;
}

static int known_pair(hylo_mode a, hylo_mode b)
{
	int ground = a == HYLO_MODE_GROUND || b == HYLO_MODE_GROUND;

	if (ground && (a == HYLO_MODE_MARINE || b == HYLO_MODE_MARINE))
		return 1;
	if (ground && (a == HYLO_MODE_FLIGHT || b == HYLO_MODE_FLIGHT))
		return 1;
	return (a == HYLO_MODE_DI_NEG && b == HYLO_MODE_DI_POS) ||
	       (a == HYLO_MODE_DI_POS && b == HYLO_MODE_DI_NEG);
}

static hylo_status check_model(const hylo_robot *robot, const hylo_mode_model *mm,
			       const hylo_svr_model *model, const char *what, hylo_reason *r)
{
	hylo_status st = hylo_svr_check(model, r);

	if (st != HYLO_OK)
		return st;
	if (model->n_features != hylo_feature_count(mm->mode))
		return hylo_fail(r, HYLO_E_BAD_VALUE,
				 "robot %s: the %s %s model has %u features, the mode needs %u",
				 robot->name, hylo_mode_str(mm->mode), what,
				 (unsigned)model->n_features, hylo_feature_count(mm->mode));
	return HYLO_OK;
}

static hylo_status check_mode(const hylo_robot *robot, const hylo_mode_model *mm,
			      hylo_reason *r)
{
	hylo_status st;

	if (!hylo_mode_valid((int)mm->mode))
		return hylo_fail(r, HYLO_E_BAD_VALUE, "robot %s: invalid mode %d", robot->name,
				 (int)mm->mode);
	if (mm->feasibility) {
		st = check_model(robot, mm, mm->feasibility, "feasibility", r);
		if (st != HYLO_OK)
			return st;
	}
	if (mm->model)
		return check_model(robot, mm, mm->model, "cost", r);
	/* No model at all is allowed here: plans on such a robot's maps are
	 * answered with HYLO_E_NO_MODEL. */
	if (!isfinite(mm->cost_floor_per_m) || mm->cost_floor_per_m < 0 ||
	    !isfinite(mm->cost_floor_j) || mm->cost_floor_j < 0 ||
	    !isfinite(mm->max_distance_m) || mm->max_distance_m < 0)
		return hylo_fail(r, HYLO_E_BAD_VALUE,
				 "robot %s: mode %s needs finite cost floors and distance >= 0",
				 robot->name, hylo_mode_str(mm->mode));
	return HYLO_OK;
}

hylo_status hylo_robot_check(const hylo_robot *robot, hylo_reason *r)
{
	uint32_t k;
	hylo_status st;

	if (!robot || !robot->name)
		return hylo_fail(r, HYLO_E_NULL, "robot or robot name is NULL");
	if (robot->name[0] == '\0' || strlen(robot->name) >= HYLO_NAME_LEN)
		return hylo_fail(r, HYLO_E_BAD_VALUE, "robot name must have 1 to %d characters",
				 HYLO_NAME_LEN - 1);
	if (robot->n_modes < 1 || robot->n_modes > 2)
		return hylo_fail(r, HYLO_E_BAD_VALUE, "robot %s: %u modes, expected 1 or 2",
				 robot->name, (unsigned)robot->n_modes);
	for (k = 0; k < robot->n_modes; k++) {
		st = check_mode(robot, &robot->modes[k], r);
		if (st != HYLO_OK)
			return st;
	}
	if (robot->n_modes == 2 && !known_pair(robot->modes[0].mode, robot->modes[1].mode))
		return hylo_fail(r, HYLO_E_BAD_VALUE, "robot %s: no guard between %s and %s",
				 robot->name, hylo_mode_str(robot->modes[0].mode),
				 hylo_mode_str(robot->modes[1].mode));
	for (k = 0; k < 2; k++)
		if (!isfinite(robot->switch_cost[k]) || robot->switch_cost[k] < 0)
			return hylo_fail(r, HYLO_E_BAD_VALUE,
					 "robot %s: switch cost %u = %g must be finite and >= 0",
					 robot->name, (unsigned)k, robot->switch_cost[k]);
	if (!isfinite(robot->body_radius_m) || robot->body_radius_m < 0)
		return hylo_fail(r, HYLO_E_BAD_VALUE,
				 "robot %s: body radius %g m must be finite and >= 0", robot->name,
				 robot->body_radius_m);
	return HYLO_OK;
}
