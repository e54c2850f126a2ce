/*
 * Fixtures for the planner tests: three small scenes (a river for an
 * Ambot-like robot, a chasm for a Drivocopter-like robot, the double
 * integrator's phase plane), robots whose edge costs are analytic callbacks,
 * and goals. Costs are positive, smooth in the states and at least the
 * declared floor per metre, so the A* heuristic is admissible.
 */
#ifndef TESTUTIL_PLANNER_H
#define TESTUTIL_PLANNER_H

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "hylo/features.h"
#include "hylo/planner.h"

#define TU_PI 3.14159265358979323846

/* Workspace for the test robots: their models are small; this leaves room
 * for the feasibility classifiers some tests add. */
#define TU_PLANNER_BYTES (sizeof(hylo_planner) + ((size_t)1 << 22))

typedef struct {
	int32_t nx, ny;
	double res, ox, oy, ceiling, max_step;
	int8_t *terrain;
	float *height;
	const char *robot;
	int64_t map_id;
} tu_map;

static inline void tu_map_alloc(tu_map *m, const char *robot, int32_t nx, int32_t ny, double res,
				double ox, double oy)
{
	m->nx = nx;
	m->ny = ny;
	m->res = res;
	m->ox = ox;
	m->oy = oy;
	m->ceiling = 0;
	m->max_step = 0.1;
	m->robot = robot;
	m->map_id = 1;
	m->terrain = calloc((size_t)nx * ny, 1);
	m->height = calloc((size_t)nx * ny, sizeof(float));
}

static inline void tu_map_free(tu_map *m)
{
	free(m->terrain);
	free(m->height);
}

static inline hylo_map_view tu_view(const tu_map *m)
{
	hylo_map_view v;

	memset(&v, 0, sizeof v);
	v.map_id = m->map_id;
	v.robot = m->robot;
	v.nx = m->nx;
	v.ny = m->ny;
	v.resolution = m->res;
	v.origin_x = m->ox;
	v.origin_y = m->oy;
	v.ceiling = m->ceiling;
	v.max_step = m->max_step;
	v.n_cells = m->nx * m->ny;
	v.terrain = m->terrain;
	v.height = m->height;
	return v;
}

/* 30 m x 20 m of ground with a 6 m river at x in [12, 18) and an obstacle
 * block at x in [2.5, 4.5), y in [5, 13). */
static inline void tu_river(tu_map *m)
{
	int32_t ix, iy;

	tu_map_alloc(m, "ambot", 60, 40, 0.5, 0, 0);
	for (iy = 0; iy < m->ny; iy++)
		for (ix = 0; ix < m->nx; ix++) {
			int8_t t = HYLO_TERRAIN_GROUND;

			if (ix >= 24 && ix < 36)
				t = HYLO_TERRAIN_WATER;
			if (ix >= 5 && ix < 9 && iy >= 10 && iy < 26)
				t = HYLO_TERRAIN_OBSTACLE;
			m->terrain[iy * m->nx + ix] = t;
		}
}

/* Two 6 m platforms (x < 15 and x >= 45) and a flat chasm floor between, all
 * drivable, 6 m wide, ceiling 12 m: the walls are height steps. */
static inline void tu_chasm(tu_map *m)
{
	int32_t ix, iy;

	tu_map_alloc(m, "drivocopter", 60, 6, 1.0, 0, 0);
	m->ceiling = 12;
	for (iy = 0; iy < m->ny; iy++)
		for (ix = 0; ix < m->nx; ix++) {
			m->terrain[iy * m->nx + ix] = HYLO_TERRAIN_GROUND;
			m->height[iy * m->nx + ix] = (ix < 15 || ix >= 45) ? 6.0f : 0.0f;
		}
}

/* The phase plane p, v in [-1, 1], free but for an obstacle blob. */
static inline void tu_di(tu_map *m)
{
	int32_t ix, iy;

	tu_map_alloc(m, "di", 40, 40, 0.05, -1, -1);
	for (iy = 0; iy < m->ny; iy++)
		for (ix = 0; ix < m->nx; ix++)
			m->terrain[iy * m->nx + ix] =
				(ix >= 8 && ix < 12 && iy >= 4 && iy < 14) ? HYLO_TERRAIN_OBSTACLE
									 : HYLO_TERRAIN_GROUND;
}

/* Analytic costs. Per-mode rate [J/m] is also the declared floor. */
typedef struct {
	double rate[HYLO_MODE_COUNT];
	double offset;          /* added to every cost; negative to test clamping */
	long calls;             /* edges evaluated through the callback */
} tu_cost;

static inline double tu_edge_cost(const tu_cost *tc, hylo_mode mode, const double *a,
				  const double *b)
{
	double d, dv = 0, dth = 0;

	if (mode == HYLO_MODE_FLIGHT) {
		d = sqrt((b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]) +
			 (b[2] - a[2]) * (b[2] - a[2]));
		dv = sqrt((b[3] - a[3]) * (b[3] - a[3]) + (b[4] - a[4]) * (b[4] - a[4]) +
			  (b[5] - a[5]) * (b[5] - a[5]));
	} else {
		d = sqrt((b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]));
		if (mode == HYLO_MODE_GROUND || mode == HYLO_MODE_MARINE) {
			dv = fabs(b[2] - a[2]);
			dth = fabs(hylo_wrap_angle(b[3] - a[3]));
		}
	}
	return tc->rate[mode] * d * (1.0 + 0.2 * dv) + 0.3 * dth + 0.1 + tc->offset;
}

static inline hylo_status tu_cost_fn(void *ctx, hylo_mode mode, const hylo_real *tail,
				     const hylo_real (*heads)[HYLO_XS_DIM], uint32_t n,
				     hylo_real *cost, hylo_reason *r)
{
	tu_cost *tc = ctx;
	uint32_t i;

	(void)r;
	for (i = 0; i < n; i++)
		cost[i] = tu_edge_cost(tc, mode, tail, heads[i]);
	tc->calls += n;
	return HYLO_OK;
}

static inline hylo_mode_model tu_mode(hylo_mode mode, tu_cost *tc)
{
	hylo_mode_model mm;

	memset(&mm, 0, sizeof mm);
	mm.mode = mode;
	mm.cost_fn = tu_cost_fn;
	mm.cost_ctx = tc;
	mm.cost_floor_per_m = tc->rate[mode];
	mm.cost_floor_j = 0.1;     /* the constant of tu_edge_cost */
	return mm;
}

/* Names robot r and gives it the two modes a and b. */
static inline void tu_robot2(hylo_robot *r, const char *name, hylo_mode_model a, hylo_mode_model b)
{
	r->name = name;
	r->n_modes = 2;
	r->modes[0] = a;
	r->modes[1] = b;
}

/* ambot, drivocopter, di, a ground-only rover, all on one cost context, and
 * a ghost robot that has no cost model. */
#define TU_N_ROBOTS 5
static inline void tu_robots(hylo_robot robots[TU_N_ROBOTS], tu_cost *tc)
{
	memset(tc, 0, sizeof *tc);
	tc->rate[HYLO_MODE_GROUND] = 3.0;
	tc->rate[HYLO_MODE_MARINE] = 9.0;
	tc->rate[HYLO_MODE_FLIGHT] = 40.0;
	tc->rate[HYLO_MODE_DI_NEG] = 1.0;
	tc->rate[HYLO_MODE_DI_POS] = 2.0;
	memset(robots, 0, TU_N_ROBOTS * sizeof *robots);
	tu_robot2(&robots[0], "ambot", tu_mode(HYLO_MODE_GROUND, tc), tu_mode(HYLO_MODE_MARINE, tc));
	tu_robot2(&robots[1], "drivocopter", tu_mode(HYLO_MODE_GROUND, tc), tu_mode(HYLO_MODE_FLIGHT, tc));
	robots[1].switch_cost[0] = 300; /* takeoff */
	robots[1].switch_cost[1] = 150; /* landing */
	tu_robot2(&robots[2], "di", tu_mode(HYLO_MODE_DI_NEG, tc), tu_mode(HYLO_MODE_DI_POS, tc));
	robots[3].name = "rover";
	robots[3].n_modes = 1;
	robots[3].modes[0] = tu_mode(HYLO_MODE_GROUND, tc);
	robots[4].name = "ghost";
	robots[4].n_modes = 1;
	robots[4].modes[0].mode = HYLO_MODE_GROUND;
}

/* A planner config for n robots: no clock, the default margin. */
static inline hylo_planner_config tu_config(const hylo_robot *robots, uint32_t n)
{
	hylo_planner_config cfg;

	memset(&cfg, 0, sizeof cfg);
	cfg.robots = robots;
	cfg.n_robots = n;
	return cfg;
}

static const hylo_real tu_speeds[] = { 0.0, 0.5, 1.0 };
static const hylo_real tu_headings[] = { 0.0, TU_PI / 2, TU_PI, -TU_PI / 2 };
static const hylo_real tu_air_speeds[] = { 0.0, 4.0 };
static const hylo_real tu_headings_x[] = { 0.0, TU_PI };

/* A goal from (sx, sy) in start_mode to (gx, gy) in goal_mode (the other
 * coordinates 0, A*), sampled with seed, spacing and connect_radius (the
 * guard spacing as the spacing); no grids, nothing in the air. */
static inline hylo_goal tu_goal(int start_mode, hylo_real sx, hylo_real sy, int goal_mode,
				hylo_real gx, hylo_real gy, uint64_t seed, hylo_real spacing,
				hylo_real connect_radius)
{
	hylo_goal g;

	memset(&g, 0, sizeof g);
	g.algorithm = HYLO_ASTAR;
	g.start_mode = start_mode;
	g.start[0] = sx;
	g.start[1] = sy;
	g.goal_mode = goal_mode;
	g.goal[0] = gx;
	g.goal[1] = gy;
	g.sampling.seed = seed;
	g.sampling.spacing = spacing;
	g.sampling.guard_spacing = spacing;
	g.sampling.connect_radius = connect_radius;
	return g;
}

/* Sets a sampling grid (speeds, headings or air_speeds) and its count to
 * the n values of v (n <= HYLO_MAX_GRID; v may be NULL when n is 0). */
static inline void tu_grid(hylo_real grid[HYLO_MAX_GRID], uint32_t *count, const hylo_real *v,
			   uint32_t n)
{
	if (n)
		memcpy(grid, v, n * sizeof *grid);
	*count = n;
}

/* The three grids of s at once. */
static inline void tu_grids(hylo_sampling *s, const hylo_real *speeds, uint32_t n_speeds,
			    const hylo_real *headings, uint32_t n_headings, const hylo_real *air_speeds,
			    uint32_t n_air_speeds)
{
	tu_grid(s->speeds, &s->n_speeds, speeds, n_speeds);
	tu_grid(s->headings, &s->n_headings, headings, n_headings);
	tu_grid(s->air_speeds, &s->n_air_speeds, air_speeds, n_air_speeds);
}

static inline hylo_goal tu_goal_river(void)
{
	hylo_goal g = tu_goal(HYLO_MODE_GROUND, 2, 16, HYLO_MODE_GROUND, 28, 4, 1, 2.0, 4.5);

	g.request_id = 7;
	tu_grids(&g.sampling, tu_speeds, 3, tu_headings, 4, NULL, 0);
	return g;
}

static inline hylo_goal tu_goal_chasm(void)
{
	hylo_goal g = tu_goal(HYLO_MODE_GROUND, 5, 3, HYLO_MODE_GROUND, 55, 3, 2, 3.0, 7.0);

	g.request_id = 8;
	g.sampling.air_spacing = 4.0;
	g.sampling.guard_spacing = 4.0;
	g.sampling.air_connect_radius = 9.0;
	tu_grids(&g.sampling, tu_speeds, 2, tu_headings_x, 2, tu_air_speeds, 2);
	return g;
}

static inline hylo_goal tu_goal_di(void)
{
	hylo_goal g = tu_goal(HYLO_MODE_DI_POS, 0.8, 0.2, HYLO_MODE_DI_NEG, -0.8, 0.0, 3, 0.15, 0.35);

	g.request_id = 9;
	return g;
}

/* The three scenes of the fixtures, each with its goal: river, chasm, di
 * (free the maps with tu_map_free). */
#define TU_N_SCENES 3

static inline void tu_scenes(tu_map maps[TU_N_SCENES], hylo_goal goals[TU_N_SCENES])
{
	tu_river(&maps[0]);
	tu_chasm(&maps[1]);
	tu_di(&maps[2]);
	goals[0] = tu_goal_river();
	goals[1] = tu_goal_chasm();
	goals[2] = tu_goal_di();
}

#endif
