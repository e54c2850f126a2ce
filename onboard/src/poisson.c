#include "hylo/clearance.h"
#include "hylo/modes.h"
#include "hylo/internal/poisson.h"

#include <math.h>

/*
 * Both samplers keep their accepted points in the caller's out array and
 * index them in ws->grid, so "is any sample closer than r" costs a few bucket
 * visits. Only +, -, *, / and floor/ceil are used on coordinates (no
 * trigonometry), so results are bit-identical across CPUs.
 */

/* Rejection draws from the square (cube) per annulus (shell) candidate: the
 * acceptance rate is 0.59 (0.46), so failing all of them is negligible. */
#define PS_REJECT_DRAWS 32

/* Subdivisions per cell edge or z column are capped here: a finer sweep
 * would need far more than HYLO_MAX_POSITIONS samples, so the capacity
 * error is met long before the cap matters. */
#define PS_MAX_SUB 1048576.0

typedef struct {
	const hylo_map *m;
	hylo_mode mode;          /* domain mode; HYLO_MODE_NONE for guards */
	const hylo_mode_desc *desc;  /* its record; NULL for guards */
	int air;                 /* airborne: points in 3-D */
	int side;                /* phase plane: -1 p <= 0, +1 p >= 0; else 0 */
	hylo_real r;             /* separation radius */
	hylo_rng *rng;
	hylo_poisson_ws *ws;
	hylo_point *out;
	uint32_t cap;            /* min(cap, HYLO_MAX_POSITIONS) */
	uint32_t n;
	uint32_t n_active;
	const char *what;        /* for reasons: "ground", "shoreline guard", ... */
	hylo_reason *reason;
} ps_ctx;

static int real_finite(hylo_real x)
{
	return x == x && x - x == 0;
}

/* Subdivisions of length len so that each piece is <= step. */
static hylo_real ps_subdiv(hylo_real len, hylo_real step)
{
	hylo_real k = ceil(len / step);

	if (!(k >= 1))
		return 1;
	return k > PS_MAX_SUB ? PS_MAX_SUB : k;
}

static hylo_status ps_add(ps_ctx *c, hylo_point p, int activate)
{
	hylo_status st;

	if (c->n >= c->cap)
		return hylo_fail(c->reason, HYLO_E_CAP_POSITIONS,
				 "poisson: %s with spacing %g needs more than %lu positions "
				 "(cap %lu, HYLO_MAX_POSITIONS = %ld)",
				 c->what, c->r, (unsigned long)c->cap, (unsigned long)c->cap,
				 (long)HYLO_MAX_POSITIONS);
	c->out[c->n] = p;
	st = hylo_spatial_insert(&c->ws->grid, c->n, c->out);
	if (st != HYLO_OK)
		return hylo_fail(c->reason, st, "poisson: cannot index sample %lu",
				 (unsigned long)c->n);
	if (activate)
		c->ws->active[c->n_active++] = c->n;
	c->n++;
	return HYLO_OK;
}

static int ps_free(const ps_ctx *c, hylo_point p)
{
	return !hylo_spatial_any_closer(&c->ws->grid, c->out, p, c->r);
}

/* Uniform offset with r <= |d| <= 2r (a disc annulus, or a spherical shell
 * in flight), by rejection from the enclosing square or cube. */
static int ps_offset(ps_ctx *c, hylo_point *d)
{
	hylo_real r2 = c->r * c->r, a = 2 * c->r;
	int k;

	for (k = 0; k < PS_REJECT_DRAWS; k++) {
		hylo_real q;

		d->x = (2 * hylo_rng_uniform(c->rng) - 1) * a;
		d->y = (2 * hylo_rng_uniform(c->rng) - 1) * a;
		d->z = c->air ? (2 * hylo_rng_uniform(c->rng) - 1) * a : 0;
		q = d->x * d->x + d->y * d->y + d->z * d->z;
		if (q >= r2 && q <= 4 * r2)
			return 1;
	}
	return 0;
}

/* Bridson growth from the active samples until none is left. Every pass
 * either adds a sample or retires one, so 2 * cap + 1 passes bound it. */
static hylo_status ps_grow(ps_ctx *c)
{
	uint32_t pass, bound = 2 * c->cap + 1;

	for (pass = 0; pass < bound && c->n_active > 0; pass++) {
		uint32_t k = hylo_rng_below(c->rng, c->n_active);
		hylo_point s = c->out[c->ws->active[k]];
		int t, added = 0;

		for (t = 0; t < HYLO_POISSON_TRIES && !added; t++) {
			hylo_point d, p;
			hylo_status st;

			if (!ps_offset(c, &d))
				continue;
			p.x = s.x + d.x;
			p.y = s.y + d.y;
			p.z = s.z + d.z;
			if (!hylo_domain_contains(c->m, c->mode, p) || !ps_free(c, p))
				continue;
			st = ps_add(c, p, 1);
			if (st != HYLO_OK)
				return st;
			added = 1;
		}
		if (!added)
			c->ws->active[k] = c->ws->active[--c->n_active];
	}
	return HYLO_OK;
}

/* A sweep candidate: when it is in the domain and free, grow from it. */
static hylo_status ps_seed(ps_ctx *c, hylo_point p)
{
	hylo_status st;

	if (!hylo_domain_contains(c->m, c->mode, p) || !ps_free(c, p))
		return HYLO_OK;
	st = ps_add(c, p, 1);
	if (st != HYLO_OK)
		return st;
	return ps_grow(c);
}

/* Whether a cell can hold domain points, and the z range of flight. */
static int ps_cell_relevant(const ps_ctx *c, int32_t ix, int32_t cell, hylo_real *zlo,
			    hylo_real *zhi)
{
	const hylo_map *m = c->m;
	hylo_real x0 = m->origin_x + ix * m->resolution;

	switch (c->desc ? c->desc->domain : HYLO_DOMAIN_NONE) {
	case HYLO_DOMAIN_LAND:
	case HYLO_DOMAIN_WATER:
		return hylo_map_cell_clear(m, c->mode, cell);
	case HYLO_DOMAIN_PHASE:
		return hylo_map_cell_clear(m, c->mode, cell) &&
		       (c->side < 0 ? x0 <= 0 : c->side > 0 ? x0 + m->resolution >= 0 : 1);
	case HYLO_DOMAIN_AIR:
		*zlo = hylo_map_flight_floor(m, cell);
		*zhi = hylo_map_flight_top(m);
		return *zlo <= *zhi;
	default:
		return 0;
	}
}

/* The sweep over every domain cell: sub-square centres spaced <= r/4 (and
 * z layers <= r/4 apart in flight) all lie within r/4 of any domain point of
 * their cell; each ends within r of a sample, so every domain point does
 * within 2r. */
static hylo_status ps_sweep(ps_ctx *c)
{
	const hylo_map *m = c->m;
	hylo_real res = m->resolution, step = c->r / 4;
	hylo_real sub = ps_subdiv(res, step);
	int32_t ix, iy;
	hylo_status st;

	for (iy = 0; iy < m->ny; iy++)
		for (ix = 0; ix < m->nx; ix++) {
			int32_t cell = iy * m->nx + ix;
			hylo_real zlo = 0, zhi = 0, nz = 1, i, j, k;

			if (!ps_cell_relevant(c, ix, cell, &zlo, &zhi))
				continue;
			if (c->air)
				nz = ps_subdiv(zhi - zlo, step) + 1;
			for (j = 0; j < sub; j++)
				for (i = 0; i < sub; i++)
					for (k = 0; k < nz; k++) {
						hylo_point p;

						p.x = m->origin_x + (ix + (i + 0.5) / sub) * res;
						p.y = m->origin_y + (iy + (j + 0.5) / sub) * res;
						p.z = 0;
						if (c->air)
							p.z = k == nz - 1 ? zhi :
							      zlo + k * ((zhi - zlo) / (nz - 1));
						/* Projection onto x = 0 keeps the point in
						 * its (straddling) cell and only gets closer
						 * to the half-plane's points. */
						if ((c->side < 0 && p.x > 0) || (c->side > 0 && p.x < 0))
							p.x = 0;
						st = ps_seed(c, p);
						if (st != HYLO_OK)
							return st;
					}
		}
	return HYLO_OK;
}

static hylo_status ps_start(ps_ctx *c, const hylo_map *m, hylo_real r, hylo_rng *rng,
			    hylo_poisson_ws *ws, hylo_point *out, uint32_t cap, uint32_t *n,
			    hylo_reason *reason)
{
	c->m = m;
	c->r = r;
	c->rng = rng;
	c->ws = ws;
	c->out = out;
	c->cap = cap < HYLO_MAX_POSITIONS ? cap : HYLO_MAX_POSITIONS;
	c->n = 0;
	c->n_active = 0;
	c->reason = reason;
	if (n)
		*n = 0;
	if (!m || !rng || !ws || !out || !n)
		return hylo_fail(reason, HYLO_E_NULL, "poisson: %s is NULL",
				 !m ? "map" : !rng ? "rng" : !ws ? "workspace" : !out ? "out" : "n");
	if (!real_finite(r) || !(r > 0))
		return hylo_fail(reason, HYLO_E_BAD_VALUE,
				 "poisson: spacing %g must be finite and > 0", r);
	if (m->nx <= 0 || m->ny <= 0)
		return HYLO_OK; /* an empty map has an empty domain */
	return hylo_spatial_init(&ws->grid, m->origin_x, m->origin_y,
				 m->origin_x + m->nx * m->resolution,
				 m->origin_y + m->ny * m->resolution, r, reason);
}

hylo_status hylo_poisson_sample(const hylo_map *m, hylo_mode mode, hylo_real r,
				hylo_rng *rng, hylo_poisson_ws *ws,
				hylo_point *out, uint32_t cap, uint32_t *n,
				hylo_reason *reason)
{
	ps_ctx c;
	hylo_status st;
	uint32_t i;

	c.mode = mode;
	c.desc = hylo_mode_describe(mode);
	c.air = c.desc && c.desc->air;
	c.side = c.desc && c.desc->domain == HYLO_DOMAIN_PHASE ? c.desc->side : 0;
	c.what = hylo_mode_str(mode);
	st = ps_start(&c, m, r, rng, ws, out, cap, n, reason);
	if (st != HYLO_OK)
		return st;
	if (!hylo_mode_valid((int)mode))
		return hylo_fail(reason, HYLO_E_BAD_VALUE, "poisson: invalid mode %d", (int)mode);
	if (m->nx <= 0 || m->ny <= 0)
		return HYLO_OK;
	st = ps_sweep(&c);
	if (st != HYLO_OK)
		return st;
	/* Ground and water were sampled in the plane (their domains ignore z);
	 * now they sit on the surface. */
	if (c.desc->domain == HYLO_DOMAIN_LAND || c.desc->domain == HYLO_DOMAIN_WATER)
		for (i = 0; i < c.n; i++)
			out[i].z = hylo_map_height(m, out[i].x, out[i].y);
	*n = c.n;
	hylo_reason_clear(reason);
	return HYLO_OK;
}

/*
 * Guards. Candidates are numbered implicitly: index = group * per_group +
 * k, where a group is a (cell, edge direction) for the shoreline, a cell for
 * takeoff and a cell row for the double integrator. Groups that cannot hold
 * a candidate are skipped whole.
 */
typedef struct {
	hylo_guard_kind kind;
	uint64_t per_group, n_groups;
	hylo_real sub;           /* points per edge minus one, or sub-squares per side */
	int32_t col0, col1;      /* di: cell columns touching x = 0 */
} guard_set;

static int guard_group_ok(const hylo_map *m, const guard_set *g, uint64_t grp)
{
	int8_t a, b;
	int32_t cell, ix, iy;

	switch (g->kind) {
	case HYLO_GUARD_SHORELINE:
		cell = (int32_t)(grp / 2);
		ix = cell % m->nx;
		iy = cell / m->nx;
		if (grp % 2 == 0 ? ix + 1 >= m->nx : iy + 1 >= m->ny)
			return 0;
		a = m->terrain[cell];
		b = m->terrain[grp % 2 == 0 ? cell + 1 : cell + m->nx];
		return (a == HYLO_TERRAIN_GROUND && b == HYLO_TERRAIN_WATER) ||
		       (a == HYLO_TERRAIN_WATER && b == HYLO_TERRAIN_GROUND);
	case HYLO_GUARD_TAKEOFF:
		cell = (int32_t)grp;
		return m->terrain[cell] == HYLO_TERRAIN_GROUND &&
		       (hylo_real)m->height[cell] + HYLO_TAKEOFF_HEIGHT_M <= m->ceiling;
	case HYLO_GUARD_DI:
		iy = (int32_t)grp;
		return m->terrain[iy * m->nx + g->col0] != HYLO_TERRAIN_OBSTACLE ||
		       m->terrain[iy * m->nx + g->col1] != HYLO_TERRAIN_OBSTACLE;
	default:
		return 0;
	}
}

/* Candidate idx (in a group that passed guard_group_ok); 1 when it lies on
 * the guard. */
static int guard_point(const hylo_map *m, const guard_set *g, uint64_t idx, hylo_point *p)
{
	uint64_t grp = idx / g->per_group;
	hylo_real k = (hylo_real)(idx % g->per_group), res = m->resolution;
	int32_t cell, ix, iy;
	hylo_point twin;

	switch (g->kind) {
	case HYLO_GUARD_SHORELINE: {
		int32_t other;

		cell = (int32_t)(grp / 2);
		ix = cell % m->nx;
		iy = cell / m->nx;
		other = grp % 2 == 0 ? cell + 1 : cell + m->nx;
		/* Endpoints included: k / sub runs over [0, 1]. */
		if (grp % 2 == 0) {
			p->x = m->origin_x + (ix + 1) * res;
			p->y = m->origin_y + (iy + k / g->sub) * res;
		} else {
			p->x = m->origin_x + (ix + k / g->sub) * res;
			p->y = m->origin_y + (iy + 1) * res;
		}
		p->z = m->height[m->terrain[cell] == HYLO_TERRAIN_GROUND ? cell : other];
		/* Both twins keep the clearance (hylo_map_inflate): the ground
		 * cell's and the water cell's own hazards. */
		return hylo_domain_contains(m, HYLO_MODE_GROUND, *p) &&
		       hylo_domain_contains(m, HYLO_MODE_MARINE, *p);
	}
	case HYLO_GUARD_TAKEOFF: {
		hylo_real i = fmod(k, g->sub), j = floor(k / g->sub);

		cell = (int32_t)grp;
		ix = cell % m->nx;
		iy = cell / m->nx;
		p->x = m->origin_x + (ix + (i + 0.5) / g->sub) * res;
		p->y = m->origin_y + (iy + (j + 0.5) / g->sub) * res;
		p->z = m->height[cell];
		twin = *p;
		twin.z += HYLO_TAKEOFF_HEIGHT_M;
		return hylo_domain_contains(m, HYLO_MODE_GROUND, *p) &&
		       hylo_domain_contains(m, HYLO_MODE_FLIGHT, twin);
	}
	case HYLO_GUARD_DI:
		iy = (int32_t)grp;
		p->x = 0;
		p->y = m->origin_y + (iy + k / g->sub) * res;
		p->z = 0;
		return hylo_domain_contains(m, HYLO_MODE_DI_NEG, *p) &&
		       hylo_domain_contains(m, HYLO_MODE_DI_POS, *p);
	default:
		return 0;
	}
}

/* Sets up the candidate numbering; 0 when the guard has no candidates. */
static int guard_setup(const hylo_map *m, hylo_guard_kind kind, hylo_real s, guard_set *g)
{
	hylo_real step = s / 4, u;

	g->kind = kind;
	g->col0 = g->col1 = 0;
	switch (kind) {
	case HYLO_GUARD_SHORELINE:
		g->sub = ps_subdiv(m->resolution, step);
		g->per_group = (uint64_t)g->sub + 1;
		g->n_groups = 2 * (uint64_t)m->nx * (uint64_t)m->ny;
		return 1;
	case HYLO_GUARD_TAKEOFF:
		g->sub = ps_subdiv(m->resolution, step);
		g->per_group = (uint64_t)g->sub * (uint64_t)g->sub;
		g->n_groups = (uint64_t)m->nx * (uint64_t)m->ny;
		return 1;
	case HYLO_GUARD_DI:
		u = -m->origin_x / m->resolution;
		if (!(u >= 0 && u <= m->nx))
			return 0;
		g->col0 = (int32_t)floor(u);
		g->col1 = g->col0;
		if (floor(u) == u)
			g->col0--;
		if (g->col0 < 0)
			g->col0 = 0;
		if (g->col1 > m->nx - 1)
			g->col1 = m->nx - 1;
		g->sub = ps_subdiv(m->resolution, step);
		g->per_group = (uint64_t)g->sub + 1;
		g->n_groups = (uint64_t)m->ny;
		return 1;
	default:
		return 0;
	}
}

/* Collects the next chunk of up to HYLO_MAX_POSITIONS valid candidates,
 * stored as offsets from *base in ws->active; advances *idx. */
static uint32_t guard_collect(const ps_ctx *c, const guard_set *g, uint64_t *idx, uint64_t base)
{
	uint64_t total = g->per_group * g->n_groups;
	uint32_t cnt = 0;
	hylo_point p;

	while (*idx < total && cnt < HYLO_MAX_POSITIONS && *idx - base <= UINT32_MAX) {
		uint64_t grp = *idx / g->per_group;

		if (!guard_group_ok(c->m, g, grp)) {
			*idx = (grp + 1) * g->per_group;
			continue;
		}
		if (guard_point(c->m, g, *idx, &p))
			c->ws->active[cnt++] = (uint32_t)(*idx - base);
		(*idx)++;
	}
	return cnt;
}

hylo_status hylo_guard_sample(const hylo_map *m, hylo_guard_kind kind, hylo_real s,
			      hylo_rng *rng, hylo_poisson_ws *ws,
			      hylo_point *out, uint32_t cap, uint32_t *n,
			      hylo_reason *reason)
{
	static const char *const names[] = { "shoreline guard", "takeoff guard", "di guard" };
	ps_ctx c;
	guard_set g;
	hylo_status st;
	uint64_t idx = 0;

	c.mode = HYLO_MODE_NONE;
	c.desc = NULL;
	c.air = c.side = 0;
	c.what = (unsigned)kind < 3 ? names[kind] : "guard";
	st = ps_start(&c, m, s, rng, ws, out, cap, n, reason);
	if (st != HYLO_OK)
		return st;
	if ((unsigned)kind > HYLO_GUARD_DI)
		return hylo_fail(reason, HYLO_E_BAD_VALUE, "poisson: invalid guard kind %d",
				 (int)kind);
	if (m->nx <= 0 || m->ny <= 0 || !guard_setup(m, kind, s, &g)) {
		hylo_reason_clear(reason);
		return HYLO_OK;
	}
	/* Each pass consumes at least one candidate index or ends the loop;
	 * chunks hold HYLO_MAX_POSITIONS candidates each, in seeded order. */
	while (idx < g.per_group * g.n_groups) {
		uint64_t base = idx;
		uint32_t cnt = guard_collect(&c, &g, &idx, base), i;

		for (i = cnt; i > 1; i--) {
			uint32_t j = hylo_rng_below(rng, i), t = ws->active[i - 1];

			ws->active[i - 1] = ws->active[j];
			ws->active[j] = t;
		}
		for (i = 0; i < cnt; i++) {
			hylo_point p;

			guard_point(m, &g, base + ws->active[i], &p);
			if (!ps_free(&c, p))
				continue;
			st = ps_add(&c, p, 0);
			if (st != HYLO_OK)
				return st;
		}
	}
	*n = c.n;
	hylo_reason_clear(reason);
	return HYLO_OK;
}
