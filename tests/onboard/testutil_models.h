/*
 * Fixtures with the committed cost models (onboard/models/): the three
 * robots and small scenes a planner solves in milliseconds, for the tests
 * and the plan digests that compare builds (tools/cross/plan_digest.c).
 */
#ifndef TESTUTIL_MODELS_H
#define TESTUTIL_MODELS_H

#include "ambot_ground.h"
#include "ambot_marine.h"
#include "di_di_neg.h"
#include "di_di_pos.h"
#include "drivocopter_flight.h"
#include "drivocopter_ground.h"
#include "onboard/testutil_planner.h"

#define TM_N_ROBOTS 3

static inline hylo_mode_model tm_mode(hylo_mode mode, const hylo_svr_model *m, const hylo_svr_model *f)
{
	hylo_mode_model mm;

	memset(&mm, 0, sizeof mm);
	mm.mode = mode;
	mm.model = m;
	mm.feasibility = f;
	return mm;
}

static inline void tm_robots(hylo_robot robots[TM_N_ROBOTS])
{
	memset(robots, 0, TM_N_ROBOTS * sizeof *robots);
	tu_robot2(&robots[0], "ambot",
		  tm_mode(HYLO_MODE_GROUND, &hylo_model_ambot_ground, &hylo_model_ambot_ground_feasibility),
		  tm_mode(HYLO_MODE_MARINE, &hylo_model_ambot_marine, &hylo_model_ambot_marine_feasibility));
	tu_robot2(&robots[1], "drivocopter",
		  tm_mode(HYLO_MODE_GROUND, &hylo_model_drivocopter_ground, &hylo_model_drivocopter_ground_feasibility),
		  tm_mode(HYLO_MODE_FLIGHT, &hylo_model_drivocopter_flight, &hylo_model_drivocopter_flight_feasibility));
	robots[1].switch_cost[0] = HYLO_MODEL_DRIVOCOPTER_FLIGHT_TAKEOFF_J;
	robots[1].switch_cost[1] = HYLO_MODEL_DRIVOCOPTER_FLIGHT_LANDING_J;
	tu_robot2(&robots[2], "di",
		  tm_mode(HYLO_MODE_DI_NEG, &hylo_model_di_di_neg, &hylo_model_di_di_neg_feasibility),
		  tm_mode(HYLO_MODE_DI_POS, &hylo_model_di_di_pos, &hylo_model_di_di_pos_feasibility));
}

/* 14 m x 8 m of ground with water at x in [5, 9). */
static inline void tm_small_river(tu_map *m)
{
	int32_t ix, iy;

	tu_map_alloc(m, "ambot", 28, 16, 0.5, 0, 0);
	for (iy = 0; iy < m->ny; iy++)
		for (ix = 0; ix < m->nx; ix++)
			m->terrain[iy * m->nx + ix] = ix >= 10 && ix < 18 ? HYLO_TERRAIN_WATER : HYLO_TERRAIN_GROUND;
}

/* Two 3 m platforms (x < 5 and x >= 13) around a floor, 4 m wide. */
static inline void tm_small_chasm(tu_map *m)
{
	int32_t ix, iy;

	tu_map_alloc(m, "drivocopter", 18, 4, 1.0, 0, 0);
	m->ceiling = 8;
	m->max_step = 0.2;
	for (iy = 0; iy < m->ny; iy++)
		for (ix = 0; ix < m->nx; ix++) {
			m->terrain[iy * m->nx + ix] = HYLO_TERRAIN_GROUND;
			m->height[iy * m->nx + ix] = ix < 5 || ix >= 13 ? 3.0f : 0.0f;
		}
}

static const hylo_real tm_fast[] = { 0.0, 1.0 };

static inline hylo_goal tm_river_goal(void)
{
	hylo_goal g = tu_goal(HYLO_MODE_GROUND, 1, 4, HYLO_MODE_GROUND, 13, 5, 3, 2.0, 3.5);

	tu_grids(&g.sampling, tu_speeds, 3, tu_headings, 4, NULL, 0);
	return g;
}

static inline hylo_goal tm_chasm_goal(void)
{
	hylo_goal g = tu_goal(HYLO_MODE_GROUND, 2, 2, HYLO_MODE_GROUND, 16, 2, 5, 2.0, 3.0);

	g.sampling.air_spacing = 3.0;
	g.sampling.air_connect_radius = 6.0;
	tu_grids(&g.sampling, tm_fast, 2, tu_headings_x, 2, tu_air_speeds, 2);
	return g;
}

static inline hylo_goal tm_di_goal(void)
{
	return tu_goal(HYLO_MODE_DI_POS, 0.8, 0.2, HYLO_MODE_DI_NEG, -0.8, 0, 1, 0.15, 0.4);
}

#endif
