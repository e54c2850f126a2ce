#include "hylo/internal/roadmap.h"
#include "hylo/modes.h"

#include <math.h>
#include <string.h>

#include "hylo/internal/spatial.h"

/* Two positions are reserved after the sampled ones: start and goal. */
#define TERMINAL_POSITIONS 2

static int finite_positive(hylo_real x)
{
	return isfinite(x) && x > 0;
}

static int has_mode(const hylo_robot *robot, hylo_mode mode)
{
	return hylo_robot_mode_index(robot, mode) >= 0;
}

/* Planar (x^s = (px, py, vx, theta)) and airborne modes (hylo/modes.h). */
static int is_planar(hylo_mode mode)
{
	const hylo_mode_desc *d = hylo_mode_describe(mode);

	return d && d->planar;
}

static int is_air(hylo_mode mode)
{
	const hylo_mode_desc *d = hylo_mode_describe(mode);

	return d && d->air;
}

/* 1 when one of robot's modes is airborne (air) or planar (!air). */
static int has_kind(const hylo_robot *robot, int air)
{
	uint32_t k;

	for (k = 0; k < robot->n_modes; k++)
		if (air ? is_air(robot->modes[k].mode) : is_planar(robot->modes[k].mode))
			return 1;
	return 0;
}

uint32_t hylo_roadmap_combos(const hylo_roadmap *rm, hylo_mode mode)
{
	if (is_planar(mode))
		return rm->sampling.n_speeds * rm->sampling.n_headings;
	if (is_air(mode))
		return rm->n_air_velocities;
	return hylo_mode_valid((int)mode) ? 1 : 0;
}

void hylo_roadmap_state(const hylo_roadmap *rm, uint32_t i, uint32_t c, hylo_real *xs)
{
	const hylo_position *p = &rm->pos[i];
	uint32_t nh = rm->sampling.n_headings;

	memset(xs, 0, HYLO_XS_DIM * sizeof *xs);
	xs[0] = p->p.x;
	xs[1] = p->p.y;
	if (is_planar((hylo_mode)p->mode)) {
		xs[2] = rm->sampling.speeds[c / nh];
		xs[3] = rm->sampling.headings[c % nh];
	} else if (is_air((hylo_mode)p->mode)) {
		xs[2] = p->p.z;
		xs[3] = rm->air_velocity[c][0];
		xs[4] = rm->air_velocity[c][1];
		xs[5] = rm->air_velocity[c][2];
	}
}

uint32_t hylo_roadmap_class_count(const hylo_roadmap *rm, hylo_mode mode)
{
	if (is_planar(mode))
		return rm->sampling.n_speeds;
	if (is_air(mode))
		return rm->sampling.n_air_speeds;
	return 1;
}

uint32_t hylo_roadmap_class(const hylo_roadmap *rm, hylo_mode mode, uint32_t c)
{
	if (is_planar(mode))
		return c / rm->sampling.n_headings;
	if (is_air(mode))
		return rm->air_class[c];
	return 0;
}

int hylo_roadmap_at_rest(const hylo_roadmap *rm, hylo_mode mode, uint32_t c)
{
	if (is_planar(mode))
		return rm->sampling.speeds[c / rm->sampling.n_headings] == 0;
	if (is_air(mode))
		return rm->air_velocity[c][0] == 0 && rm->air_velocity[c][1] == 0 &&
		       rm->air_velocity[c][2] == 0;
	return 1;
}

hylo_real hylo_roadmap_radius(const hylo_roadmap *rm, hylo_mode mode)
{
	return is_air(mode) ? rm->sampling.air_connect_radius
					: rm->sampling.connect_radius;
}

static int grid_equal(const hylo_real *a, const hylo_real *b, uint32_t n)
{
	uint32_t i;

	for (i = 0; i < n; i++)
		if (a[i] != b[i])
			return 0;
	return 1;
}

int hylo_sampling_equal(const hylo_sampling *a, const hylo_sampling *b)
{
	return a->seed == b->seed && a->spacing == b->spacing &&
	       a->air_spacing == b->air_spacing && a->guard_spacing == b->guard_spacing &&
	       a->connect_radius == b->connect_radius &&
	       a->air_connect_radius == b->air_connect_radius &&
	       a->n_speeds == b->n_speeds && a->n_headings == b->n_headings &&
	       a->n_air_speeds == b->n_air_speeds &&
	       grid_equal(a->speeds, b->speeds, a->n_speeds) &&
	       grid_equal(a->headings, b->headings, a->n_headings) &&
	       grid_equal(a->air_speeds, b->air_speeds, a->n_air_speeds);
}

hylo_status hylo_sampling_check_grids(const hylo_sampling *s, hylo_reason *r)
{
	static const char *const names[3] = { "speeds_mps", "headings_rad", "air_speeds_mps" };
	const hylo_real *grids[3];
	uint32_t counts[3], k, i;

	grids[0] = s->speeds;
	grids[1] = s->headings;
	grids[2] = s->air_speeds;
	counts[0] = s->n_speeds;
	counts[1] = s->n_headings;
	counts[2] = s->n_air_speeds;
	for (k = 0; k < 3; k++) {
		if (counts[k] > HYLO_MAX_GRID)
			return hylo_fail(r, HYLO_E_CAP_GRID,
					 "%s has %u entries, more than HYLO_MAX_GRID = %d",
					 names[k], (unsigned)counts[k], HYLO_MAX_GRID);
		for (i = 0; i < counts[k]; i++)
			if (!isfinite(grids[k][i]))
				return hylo_fail(r, HYLO_E_BAD_VALUE, "%s[%d] = %g must be finite",
						 names[k], (int)i, grids[k][i]);
	}
	return HYLO_OK;
}

/* A grid that has passed hylo_sampling_check_grids: non-empty where the
 * robot needs it, >= 0 where it holds speeds' magnitudes. */
static hylo_status check_grid(const char *name, const hylo_real *v, uint32_t n,
			      int need, int non_negative, hylo_reason *r)
{
	uint32_t i;

	if (need && n == 0)
		return hylo_fail(r, HYLO_E_BAD_VALUE, "%s is empty", name);
	for (i = 0; i < n; i++) {
		if (non_negative && v[i] < 0)
			return hylo_fail(r, HYLO_E_BAD_VALUE, "%s[%u] = %g is not a valid value",
					 name, (unsigned)i, v[i]);
	}
	return HYLO_OK;
}

static int grid_has_zero(const hylo_real *v, uint32_t n)
{
	uint32_t i;

	for (i = 0; i < n; i++)
		if (v[i] == 0)
			return 1;
	return 0;
}

/* Every speed of a grid inside the training range of each model of the
 * robot's modes that the grid serves (planar: speeds_mps, flight:
 * air_speeds_mps): costs from speeds a model never saw are extrapolations. */
static hylo_status check_grid_trained(const hylo_robot *robot, const char *name,
				      const hylo_real *v, uint32_t n, int flight_grid,
				      hylo_reason *r)
{
	uint32_t k, i;

	for (k = 0; k < robot->n_modes; k++) {
		const hylo_svr_model *model = robot->modes[k].model;
		hylo_mode mode = robot->modes[k].mode;

		if (!model || (flight_grid ? !is_air(mode) : !is_planar(mode)))
			continue;
		for (i = 0; i < n; i++)
			if (!hylo_svr_speed_trained(model, v[i]))
				return hylo_fail(r, HYLO_E_BAD_VALUE,
						 "%s[%u] = %g m/s is outside the %s model's training range [%g, %g] m/s",
						 name, (unsigned)i, v[i], hylo_mode_str(mode),
						 model->speed_min_mps, model->speed_max_mps);
	}
	return HYLO_OK;
}

static hylo_status check_sampling(const hylo_robot *robot, const hylo_sampling *s,
				  hylo_reason *r)
{
	int planar = has_kind(robot, 0);
	int flight = has_kind(robot, 1);
	hylo_status st;

	if (!finite_positive(s->spacing) && (planar || !flight))
		return hylo_fail(r, HYLO_E_BAD_VALUE, "spacing_m = %g must be finite and > 0", s->spacing);
	if (!finite_positive(s->connect_radius) && (planar || !flight))
		return hylo_fail(r, HYLO_E_BAD_VALUE, "connect_radius_m = %g must be finite and > 0",
				 s->connect_radius);
	if (flight && !finite_positive(s->air_spacing))
		return hylo_fail(r, HYLO_E_BAD_VALUE, "air_spacing_m = %g must be finite and > 0",
				 s->air_spacing);
	if (flight && !finite_positive(s->air_connect_radius))
		return hylo_fail(r, HYLO_E_BAD_VALUE, "air_connect_radius_m = %g must be finite and > 0",
				 s->air_connect_radius);
	if (robot->n_modes == 2 && !finite_positive(s->guard_spacing))
		return hylo_fail(r, HYLO_E_BAD_VALUE, "guard_spacing_m = %g must be finite and > 0",
				 s->guard_spacing);
	st = hylo_sampling_check_grids(s, r);
	if (st == HYLO_OK)
		st = check_grid("speeds_mps", s->speeds, s->n_speeds, planar, 0, r);
	if (st == HYLO_OK)
		st = check_grid("headings_rad", s->headings, s->n_headings, planar || flight, 0, r);
	if (st == HYLO_OK)
		st = check_grid("air_speeds_mps", s->air_speeds, s->n_air_speeds, flight, 1, r);
	if (st == HYLO_OK)
		st = check_grid_trained(robot, "speeds_mps", s->speeds, s->n_speeds, 0, r);
	if (st == HYLO_OK)
		st = check_grid_trained(robot, "air_speeds_mps", s->air_speeds, s->n_air_speeds, 1, r);
	if (st != HYLO_OK)
		return st;
	if (planar && s->n_speeds * s->n_headings > HYLO_MAX_COMBOS)
		return hylo_fail(r, HYLO_E_CAP_COMBOS,
				 "%u speeds x %u headings = %u combinations, more than HYLO_MAX_COMBOS = %d",
				 (unsigned)s->n_speeds, (unsigned)s->n_headings,
				 (unsigned)(s->n_speeds * s->n_headings), HYLO_MAX_COMBOS);
	if (flight && planar && !(grid_has_zero(s->speeds, s->n_speeds) &&
				  grid_has_zero(s->air_speeds, s->n_air_speeds)))
		return hylo_fail(r, HYLO_E_BAD_VALUE,
				 "takeoff and landing happen at rest: speeds_mps and air_speeds_mps must contain 0");
	return HYLO_OK;
}

/* Flight velocities: hover once for a zero speed, otherwise one horizontal
 * velocity per heading (the virtual constraint keeps yaw 0, so the body
 * velocity is the world velocity). */
static hylo_status make_air_velocities(hylo_roadmap *rm, hylo_reason *r)
{
	const hylo_sampling *s = &rm->sampling;
	uint32_t i, k, n = 0;

	for (i = 0; i < s->n_air_speeds; i++) {
		uint32_t count = s->air_speeds[i] == 0 ? 1 : s->n_headings;

		if (n + count > HYLO_MAX_COMBOS)
			return hylo_fail(r, HYLO_E_CAP_COMBOS,
					 "flight velocities exceed HYLO_MAX_COMBOS = %d", HYLO_MAX_COMBOS);
		for (k = 0; k < count; k++) {
			hylo_real sp = s->air_speeds[i];

			rm->air_velocity[n][0] = sp == 0 ? 0 : sp * cos(s->headings[k]);
			rm->air_velocity[n][1] = sp == 0 ? 0 : sp * sin(s->headings[k]);
			rm->air_velocity[n][2] = 0;
			rm->air_class[n] = (uint8_t)i;
			n++;
		}
	}
	rm->n_air_velocities = n;
	return HYLO_OK;
}

static hylo_status add_position(hylo_roadmap *rm, hylo_point p, hylo_mode mode,
				hylo_position_kind kind, hylo_reason *r)
{
	hylo_position *q;

	if (rm->n_positions + TERMINAL_POSITIONS >= HYLO_MAX_POSITIONS)
		return hylo_fail(r, HYLO_E_CAP_POSITIONS,
				 "more than HYLO_MAX_POSITIONS = %d positions (with start and goal)",
				 HYLO_MAX_POSITIONS);
	q = &rm->pos[rm->n_positions++];
	memset(q, 0, sizeof *q);
	q->p = p;
	q->mode = (uint8_t)mode;
	q->kind = (uint8_t)kind;
	q->twin = HYLO_NO_POSITION;
	return HYLO_OK;
}

static hylo_real mode_spacing(const hylo_sampling *s, hylo_mode mode)
{
	return is_air(mode) ? s->air_spacing : s->spacing;
}

static uint32_t free_positions(const hylo_roadmap *rm)
{
	return HYLO_MAX_POSITIONS - TERMINAL_POSITIONS - rm->n_positions;
}

static hylo_status sample_domains(hylo_roadmap *rm, hylo_roadmap_ws *ws, const hylo_map *m,
				  const hylo_robot *robot, hylo_rng *rng, hylo_reason *r)
{
	uint32_t k, i, n;
	hylo_status st;

	for (k = 0; k < robot->n_modes; k++) {
		hylo_mode mode = robot->modes[k].mode;

		st = hylo_poisson_sample(m, mode, mode_spacing(&rm->sampling, mode), rng,
					 &ws->poisson, ws->points, free_positions(rm), &n, r);
		if (st != HYLO_OK)
			return st;
		for (i = 0; i < n; i++) {
			st = add_position(rm, ws->points[i], mode, HYLO_POS_SAMPLE, r);
			if (st != HYLO_OK)
				return st;
		}
		rm->n_per_mode[mode] = n;
	}
	return HYLO_OK;
}

static int guard_kind(const hylo_robot *robot, hylo_guard_kind *kind)
{
	if (has_mode(robot, HYLO_MODE_GROUND) && has_mode(robot, HYLO_MODE_MARINE))
		*kind = HYLO_GUARD_SHORELINE;
	else if (has_mode(robot, HYLO_MODE_GROUND) && has_mode(robot, HYLO_MODE_FLIGHT))
		*kind = HYLO_GUARD_TAKEOFF;
	else if (has_mode(robot, HYLO_MODE_DI_NEG) && has_mode(robot, HYLO_MODE_DI_POS))
		*kind = HYLO_GUARD_DI;
	else
		return 0;
	return 1;
}

/* Each guard sample becomes two twin positions, one per mode (paper,
 * Fig. 2C); the switching cost sits on the edges between them. */
static hylo_status sample_guards(hylo_roadmap *rm, hylo_roadmap_ws *ws, const hylo_map *m,
				 const hylo_robot *robot, hylo_rng *rng, hylo_reason *r)
{
	hylo_guard_kind kind;
	uint32_t i, n;
	hylo_status st;

	if (robot->n_modes < 2 || !guard_kind(robot, &kind))
		return HYLO_OK;
	st = hylo_guard_sample(m, kind, rm->sampling.guard_spacing, rng, &ws->poisson,
			       ws->points, free_positions(rm) / 2, &n, r);
	if (st != HYLO_OK)
		return st;
	for (i = 0; i < n; i++) {
		hylo_point a = ws->points[i], b = ws->points[i];
		uint32_t ia = rm->n_positions;

		if (kind == HYLO_GUARD_TAKEOFF)
			b.z += HYLO_TAKEOFF_HEIGHT_M;
		st = add_position(rm, a, robot->modes[0].mode, HYLO_POS_GUARD, r);
		if (st == HYLO_OK)
			st = add_position(rm, b, robot->modes[1].mode, HYLO_POS_GUARD, r);
		if (st != HYLO_OK)
			return st;
		rm->pos[ia].twin = ia + 1;
		rm->pos[ia + 1].twin = ia;
	}
	rm->n_guards = n;
	return HYLO_OK;
}

static hylo_status assign_nodes(hylo_roadmap *rm, hylo_reason *r)
{
	uint32_t i, c, n = 0;

	for (i = 0; i < rm->n_positions; i++) {
		hylo_position *p = &rm->pos[i];
		uint32_t k = hylo_roadmap_combos(rm, (hylo_mode)p->mode);

		if ((uint64_t)n + k + TERMINAL_POSITIONS > HYLO_MAX_NODES)
			return hylo_fail(r, HYLO_E_CAP_NODES,
					 "more than HYLO_MAX_NODES = %d nodes (%u positions sampled so far)",
					 HYLO_MAX_NODES, (unsigned)i);
		p->node_base = n;
		p->n_combos = (uint16_t)k;
		for (c = 0; c < k; c++)
			rm->node_pos[n + c] = i;
		n += k;
	}
	rm->n_nodes = n;
	return HYLO_OK;
}

hylo_status hylo_roadmap_neighbours(const hylo_roadmap *rm, hylo_roadmap_ws *ws,
				   const hylo_map *m, hylo_point p, hylo_mode mode,
				   uint32_t self, uint32_t *out, uint32_t *n, hylo_reason *r)
{
	uint32_t k, found, count = 0;
	hylo_status st;

	st = hylo_spatial_query(&ws->poisson.grid, ws->points, p, hylo_roadmap_radius(rm, mode),
				ws->neighbours, HYLO_MAX_SUCCESSORS, &found);
	if (st != HYLO_OK)
		return hylo_fail(r, HYLO_E_CAP_SUCCESSORS,
				 "more than HYLO_MAX_SUCCESSORS = %d positions within the connection radius of (%g, %g, %g)",
				 HYLO_MAX_SUCCESSORS, p.x, p.y, p.z);
	for (k = 0; k < found; k++) {
		uint32_t j = ws->neighbours[k];
		hylo_point a = p, b = rm->pos[j].p;

		if (j == self || rm->pos[j].mode != mode)
			continue;
		/* Check the segment in one canonical direction so that the
		 * adjacency is exactly symmetric. */
		if (self != HYLO_NO_POSITION && j < self) {
			a = rm->pos[j].p;
			b = p;
		}
		if (!hylo_domain_segment(m, mode, a, b))
			continue;
		out[count++] = j;
	}
	*n = count;
	return HYLO_OK;
}

/* adj_reverse: for each entry (i names j), j's entry naming i
 * (UINT32_MAX: none, which a symmetric radius never leaves). */
static void link_reverse(hylo_roadmap *rm)
{
	uint32_t i, a, b;

	for (i = 0; i < rm->n_positions; i++)
		for (a = rm->pos[i].adj_begin; a < rm->pos[i].adj_end; a++) {
			const hylo_position *q = &rm->pos[rm->adjacency[a]];

			for (b = q->adj_begin; b < q->adj_end && rm->adjacency[b] != i; b++)
				;
			rm->adj_reverse[a] = b < q->adj_end ? b : UINT32_MAX;
		}
}

static hylo_status connect_positions(hylo_roadmap *rm, hylo_roadmap_ws *ws, const hylo_map *m,
				     hylo_reason *r)
{
	hylo_real cell = rm->sampling.connect_radius;
	uint32_t i, k, n;
	hylo_status st;

	if (rm->sampling.air_connect_radius > 0 &&
	    (!(cell > 0) || rm->sampling.air_connect_radius < cell))
		cell = rm->sampling.air_connect_radius;
	st = hylo_spatial_init(&ws->poisson.grid, m->origin_x, m->origin_y,
			       m->origin_x + m->nx * m->resolution,
			       m->origin_y + m->ny * m->resolution, cell, r);
	if (st != HYLO_OK)
		return st;
	for (i = 0; i < rm->n_positions; i++) {
		ws->points[i] = rm->pos[i].p;
		st = hylo_spatial_insert(&ws->poisson.grid, i, ws->points);
		if (st != HYLO_OK)
			return hylo_fail(r, st, "cannot index position %u", (unsigned)i);
	}
	rm->n_adjacency = 0;
	for (i = 0; i < rm->n_positions; i++) {
		hylo_position *p = &rm->pos[i];
		uint32_t *out = &rm->adjacency[rm->n_adjacency];

		st = hylo_roadmap_neighbours(rm, ws, m, p->p, (hylo_mode)p->mode, i,
					     ws->neighbours, &n, r);
		if (st != HYLO_OK)
			return st;
		if ((uint64_t)rm->n_adjacency + n > HYLO_MAX_ADJACENCY)
			return hylo_fail(r, HYLO_E_CAP_ADJACENCY,
					 "more than HYLO_MAX_ADJACENCY = %d neighbour entries (at position %u of %u)",
					 HYLO_MAX_ADJACENCY, (unsigned)i, (unsigned)rm->n_positions);
		for (k = 0; k < n; k++)
			out[k] = ws->neighbours[k];
		p->adj_begin = rm->n_adjacency;
		rm->n_adjacency += n;
		p->adj_end = rm->n_adjacency;
	}
	link_reverse(rm);
	return HYLO_OK;
}

uint32_t hylo_roadmap_switch_heads(const hylo_roadmap *rm, uint32_t i, uint32_t c,
				   uint32_t *combos)
{
	const hylo_position *p = &rm->pos[i], *t;
	uint32_t k, n = 0;

	if (p->twin == HYLO_NO_POSITION)
		return 0;
	t = &rm->pos[p->twin];
	if (is_air((hylo_mode)p->mode) || is_air((hylo_mode)t->mode)) {
		/* Takeoff and landing join rest states only. */
		if (!hylo_roadmap_at_rest(rm, (hylo_mode)p->mode, c))
			return 0;
		for (k = 0; k < t->n_combos; k++)
			if (hylo_roadmap_at_rest(rm, (hylo_mode)t->mode, k))
				combos[n++] = k;
		return n;
	}
	/* Shoreline and p = 0: identity reset, same sampled coordinates. */
	combos[0] = c < t->n_combos ? c : 0;
	return 1;
}

/* Counts edges and the largest out-degree, so that an over-capacity
 * expansion is reported when the roadmap is built, not mid-search. */
static hylo_status count_edges(hylo_roadmap *rm, hylo_reason *r)
{
	uint32_t combos[HYLO_MAX_COMBOS];
	uint32_t i, k, c;

	rm->n_edges = 0;
	rm->max_successors = 0;
	for (i = 0; i < rm->n_positions; i++) {
		const hylo_position *p = &rm->pos[i];
		uint64_t out = 0;

		for (k = p->adj_begin; k < p->adj_end; k++)
			out += rm->pos[rm->adjacency[k]].n_combos;
		for (c = 0; c < p->n_combos; c++) {
			uint64_t deg = out + hylo_roadmap_switch_heads(rm, i, c, combos);

			rm->n_edges += deg;
			if (deg > rm->max_successors)
				rm->max_successors = (uint32_t)(deg > UINT32_MAX ? UINT32_MAX : deg);
		}
	}
	/* + 1 for a possible edge into the goal. */
	if ((uint64_t)rm->max_successors + 1 > HYLO_MAX_SUCCESSORS)
		return hylo_fail(r, HYLO_E_CAP_SUCCESSORS,
				 "a node has %u successors, more than HYLO_MAX_SUCCESSORS = %d: lower the connection radius or the grids",
				 (unsigned)rm->max_successors, HYLO_MAX_SUCCESSORS);
	return HYLO_OK;
}

hylo_status hylo_roadmap_build(hylo_roadmap *rm, hylo_roadmap_ws *ws, const hylo_map *m,
			       const hylo_robot *robot, const hylo_sampling *s,
			       hylo_reason *r)
{
	hylo_rng rng;
	hylo_status st;

	if (!rm || !ws || !m || !robot || !s)
		return hylo_fail(r, HYLO_E_NULL, "hylo_roadmap_build: NULL argument");
	rm->built = 0;
	rm->n_positions = 0;
	rm->n_nodes = 0;
	rm->n_edges = 0;
	rm->n_guards = 0;
	rm->n_air_velocities = 0;
	memset(rm->n_per_mode, 0, sizeof rm->n_per_mode);
	st = check_sampling(robot, s, r);
	if (st != HYLO_OK)
		return st;
	rm->sampling = *s;
	st = make_air_velocities(rm, r);
	if (st != HYLO_OK)
		return st;
	hylo_rng_seed(&rng, s->seed);
	st = sample_domains(rm, ws, m, robot, &rng, r);
	if (st != HYLO_OK)
		return st;
	if (rm->n_positions == 0)
		return hylo_fail(r, HYLO_E_EMPTY_DOMAIN,
				 "no sample fits in any domain of robot %s on this map", robot->name);
	st = sample_guards(rm, ws, m, robot, &rng, r);
	if (st == HYLO_OK)
		st = assign_nodes(rm, r);
	if (st == HYLO_OK)
		st = connect_positions(rm, ws, m, r);
	if (st == HYLO_OK)
		st = count_edges(rm, r);
	if (st != HYLO_OK)
		return st;
	rm->built = 1;
	return HYLO_OK;
}

hylo_real hylo_roadmap_distance(hylo_point a, hylo_point b)
{
	hylo_real dx = a.x - b.x, dy = a.y - b.y, dz = a.z - b.z;

	return sqrt(dx * dx + dy * dy + dz * dz);
}
