#include "hylo/map.h"
#include "hylo/modes.h"
#include "hylo/clearance.h"

#include <math.h>
#include <string.h>

/*
 * Cells are addressed in grid units: u = (x - ox) / res, v = (y - oy) / res,
 * so that cell (ix, iy) is [ix, ix + 1] x [iy, iy + 1] and grid lines sit at
 * integer u or v. A point on a grid line touches the cells on both sides.
 */

/* Up to four cells touch a point (a grid vertex). */
typedef struct {
	int32_t idx[4];
	int n;
} cell_set;

static void map_mark_empty(hylo_map *m)
{
	m->map_id = 0;
	m->robot[0] = '\0';
	m->nx = 0;
	m->ny = 0;
	m->n_ground = 0;
	m->n_water = 0;
	m->n_obstacle = 0;
	m->inflation = 0;
}

static int real_finite(hylo_real x)
{
	return x == x && x - x == 0;
}

static hylo_status map_check_header(const hylo_map_view *v, hylo_reason *r)
{
	int64_t cells;
	size_t len = 0;

	if (!v->terrain)
		return hylo_fail(r, HYLO_E_NULL, "map: terrain array is NULL");
	if (!v->height)
		return hylo_fail(r, HYLO_E_NULL, "map: height array is NULL");
	if (!v->robot)
		return hylo_fail(r, HYLO_E_BAD_MAP, "map: robot name is missing (NULL)");
	/* Bounded scan: the name may not be terminated within our buffer. */
	while (len < HYLO_NAME_LEN && v->robot[len] != '\0')
		len++;
	if (len == 0 || len > HYLO_NAME_LEN - 1)
		return hylo_fail(r, HYLO_E_BAD_MAP,
				 "map: robot name is %s (1 to %d characters allowed)",
				 len == 0 ? "empty" : "too long", HYLO_NAME_LEN - 1);
	if (v->nx <= 0 || v->ny <= 0)
		return hylo_fail(r, HYLO_E_BAD_MAP, "map: nx = %ld, ny = %ld must be positive",
				 (long)v->nx, (long)v->ny);
	cells = (int64_t)v->nx * v->ny;
	if (v->n_cells != cells)
		return hylo_fail(r, HYLO_E_BAD_MAP, "map: n_cells = %ld but nx * ny = %lld",
				 (long)v->n_cells, (long long)cells);
	if (cells > HYLO_MAX_CELLS)
		return hylo_fail(r, HYLO_E_CAP_CELLS,
				 "map: n_cells = %lld exceeds HYLO_MAX_CELLS = %ld",
				 (long long)cells, (long)HYLO_MAX_CELLS);
	if (!real_finite(v->resolution) || !(v->resolution > 0))
		return hylo_fail(r, HYLO_E_BAD_MAP, "map: resolution = %g must be finite and > 0",
				 v->resolution);
	if (!real_finite(v->origin_x) || !real_finite(v->origin_y))
		return hylo_fail(r, HYLO_E_BAD_VALUE, "map: origin_x = %g, origin_y = %g must be finite",
				 v->origin_x, v->origin_y);
	/* The far corner must be representable too. */
	if (!real_finite(v->origin_x + v->nx * v->resolution) ||
	    !real_finite(v->origin_y + v->ny * v->resolution))
		return hylo_fail(r, HYLO_E_BAD_VALUE, "map: origin + size * resolution overflows");
	if (!real_finite(v->ceiling))
		return hylo_fail(r, HYLO_E_BAD_VALUE, "map: ceiling = %g must be finite", v->ceiling);
	if (!real_finite(v->max_step) || v->max_step < 0)
		return hylo_fail(r, HYLO_E_BAD_VALUE, "map: max_step = %g must be finite and >= 0",
				 v->max_step);
	return HYLO_OK;
}

hylo_status hylo_map_ingest(hylo_map *m, const hylo_map_view *v, hylo_reason *r)
{
	int32_t i, n;
	hylo_status st;

	if (!m || !v)
		return hylo_fail(r, HYLO_E_NULL, "map: %s is NULL", !m ? "workspace map" : "map view");
	map_mark_empty(m);
	st = map_check_header(v, r);
	if (st != HYLO_OK)
		return st;
	n = v->n_cells;
	for (i = 0; i < n; i++) {
		int8_t t = v->terrain[i];
		float h = v->height[i];

		if (t != HYLO_TERRAIN_OBSTACLE && t != HYLO_TERRAIN_GROUND && t != HYLO_TERRAIN_WATER) {
			map_mark_empty(m);
			return hylo_fail(r, HYLO_E_BAD_MAP,
					 "map: terrain at cell (%ld, %ld) is %d, not a known class",
					 (long)(i % v->nx), (long)(i / v->nx), (int)t);
		}
		if (!real_finite((hylo_real)h)) {
			map_mark_empty(m);
			return hylo_fail(r, HYLO_E_BAD_VALUE,
					 "map: height at cell (%ld, %ld) is %g, not finite",
					 (long)(i % v->nx), (long)(i / v->nx), (double)h);
		}
		m->terrain[i] = t;
		m->height[i] = h;
		m->n_ground += t == HYLO_TERRAIN_GROUND;
		m->n_water += t == HYLO_TERRAIN_WATER;
		m->n_obstacle += t == HYLO_TERRAIN_OBSTACLE;
	}
	strcpy(m->robot, v->robot); /* length checked above */
	m->resolution = v->resolution;
	m->origin_x = v->origin_x;
	m->origin_y = v->origin_y;
	m->ceiling = v->ceiling;
	m->max_step = v->max_step;
	m->nx = v->nx;
	m->ny = v->ny;
	m->map_id = v->map_id;
	hylo_reason_clear(r);
	return HYLO_OK;
}

/* Grid coordinates of (x, y); 0 when outside the closed map rectangle or NaN. */
static int map_grid(const hylo_map *m, hylo_real x, hylo_real y, hylo_real *u, hylo_real *v)
{
	if (!m || m->nx <= 0 || m->ny <= 0)
		return 0;
	*u = (x - m->origin_x) / m->resolution;
	*v = (y - m->origin_y) / m->resolution;
	return *u >= 0 && *u <= m->nx && *v >= 0 && *v <= m->ny;
}

/* Cell columns touching grid coordinate u in [0, n]: one, or two on a line. */
static int map_span(hylo_real u, int32_t n, int32_t *lo, int32_t *hi)
{
	hylo_real f = floor(u);
	int32_t i = (int32_t)f;

	*lo = i;
	*hi = i;
	if (f == u)
		*lo = i - 1;
	if (*lo < 0)
		*lo = 0;
	if (*hi > n - 1)
		*hi = n - 1;
	return *hi - *lo + 1;
}

static void map_touching(const hylo_map *m, hylo_real u, hylo_real v, cell_set *s)
{
	int32_t x0, x1, y0, y1, ix, iy;

	map_span(u, m->nx, &x0, &x1);
	map_span(v, m->ny, &y0, &y1);
	s->n = 0;
	for (iy = y0; iy <= y1; iy++)
		for (ix = x0; ix <= x1; ix++)
			s->idx[s->n++] = iy * m->nx + ix;
}

hylo_real hylo_map_height(const hylo_map *m, hylo_real x, hylo_real y)
{
	hylo_real u, v;
	int32_t x0, x1, y0, y1;

	if (!map_grid(m, x, y, &u, &v))
		return 0;
	map_span(u, m->nx, &x0, &x1);
	map_span(v, m->ny, &y0, &y1);
	return m->height[y0 * m->nx + x0];
}

int hylo_map_cell_clear(const hylo_map *m, hylo_mode mode, int32_t c)
{
	switch (hylo_mode_domain(mode)) {
	case HYLO_DOMAIN_LAND:
		return m->inflation > 0 ? m->clear[c] && m->terrain[c] == HYLO_TERRAIN_GROUND
					: m->terrain[c] == HYLO_TERRAIN_GROUND;
	case HYLO_DOMAIN_WATER:
		return m->inflation > 0 ? m->clear[c] && m->terrain[c] == HYLO_TERRAIN_WATER
					: m->terrain[c] == HYLO_TERRAIN_WATER;
	case HYLO_DOMAIN_PHASE:
		return m->terrain[c] != HYLO_TERRAIN_OBSTACLE;
	default:
		return 0;
	}
}

hylo_real hylo_map_flight_floor(const hylo_map *m, int32_t c)
{
	return m->inflation > 0 ? m->floor[c] : (hylo_real)m->height[c] + HYLO_AIR_CLEARANCE_M;
}

hylo_real hylo_map_flight_top(const hylo_map *m)
{
	return m->ceiling - m->inflation;
}

static int flight_ok(const hylo_map *m, int32_t c, hylo_real zlo, hylo_real zhi)
{
	return zlo >= hylo_map_flight_floor(m, c) && zhi <= hylo_map_flight_top(m);
}

static int side_ok(hylo_mode mode, hylo_real x)
{
	const hylo_mode_desc *d = hylo_mode_describe(mode);

	if (d && d->domain == HYLO_DOMAIN_PHASE && d->side < 0)
		return x <= 0;
	if (d && d->domain == HYLO_DOMAIN_PHASE && d->side > 0)
		return x >= 0;
	return 1;
}

int hylo_domain_contains(const hylo_map *m, hylo_mode mode, hylo_point p)
{
	hylo_real u, v;
	cell_set s;
	int k;

	if (!hylo_mode_valid((int)mode) || !map_grid(m, p.x, p.y, &u, &v))
		return 0;
	if (!side_ok(mode, p.x))
		return 0;
	map_touching(m, u, v, &s);
	if (hylo_mode_domain(mode) == HYLO_DOMAIN_AIR) {
		/* On a boundary the highest touching cell counts. */
		if (p.z != p.z)
			return 0;
		for (k = 0; k < s.n; k++)
			if (!flight_ok(m, s.idx[k], p.z, p.z))
				return 0;
		return 1;
	}
	for (k = 0; k < s.n; k++)
		if (hylo_map_cell_clear(m, mode, s.idx[k]))
			return 1;
	return 0;
}

/* State of the walk along one segment. */
typedef struct {
	const hylo_map *m;
	hylo_mode mode;
	hylo_real ua, va, du, dv, za, dz;
	int started;             /* ground: a previous cell set exists */
	int prev_n;
	float prev_h[2];
} seg_walk;

/* Land: some choice of qualifying cells keeps every step <= max_step. */
static int walk_ground(seg_walk *w, const int32_t *c, int n)
{
	float h[2];
	int k, j, cnt = 0;

	for (k = 0; k < n; k++) {
		int ok;

		if (!hylo_map_cell_clear(w->m, w->mode, c[k]))
			continue;
		ok = !w->started;
		for (j = 0; j < w->prev_n && !ok; j++)
			ok = fabs((hylo_real)w->m->height[c[k]] - (hylo_real)w->prev_h[j]) <=
			     w->m->max_step;
		if (ok)
			h[cnt++] = w->m->height[c[k]];
	}
	if (cnt == 0)
		return 0;
	w->started = 1;
	w->prev_n = cnt;
	for (k = 0; k < cnt; k++)
		w->prev_h[k] = h[k];
	return 1;
}

/* Checks the piece [t0, t1] of the segment, which lies in one cell, or on a
 * grid line between two cells. */
static int walk_piece(seg_walk *w, hylo_real t0, hylo_real t1)
{
	const hylo_map *m = w->m;
	hylo_real tm = 0.5 * (t0 + t1);
	int32_t x0, x1, y0, y1, c[2];
	int n = 0, k;

	/* Only an axis-parallel segment can run along a grid line. */
	if (w->du == 0) {
		map_span(w->ua, m->nx, &x0, &x1);
	} else {
		hylo_real f = floor(w->ua + tm * w->du);

		x0 = x1 = f < 0 ? 0 : (f > m->nx - 1 ? m->nx - 1 : (int32_t)f);
	}
	if (w->dv == 0) {
		map_span(w->va, m->ny, &y0, &y1);
	} else {
		hylo_real f = floor(w->va + tm * w->dv);

		y0 = y1 = f < 0 ? 0 : (f > m->ny - 1 ? m->ny - 1 : (int32_t)f);
	}
	c[n++] = y0 * m->nx + x0;
	if (x1 != x0)
		c[n++] = y0 * m->nx + x1;
	else if (y1 != y0)
		c[n++] = y1 * m->nx + x0;

	if (hylo_mode_domain(w->mode) == HYLO_DOMAIN_LAND)
		return walk_ground(w, c, n);
	if (hylo_mode_domain(w->mode) == HYLO_DOMAIN_AIR) {
		hylo_real z0 = w->za + t0 * w->dz, z1 = w->za + t1 * w->dz;
		hylo_real lo = z0 < z1 ? z0 : z1, hi = z0 < z1 ? z1 : z0;

		/* On a line both neighbours apply (closed domain: max height). */
		for (k = 0; k < n; k++)
			if (!flight_ok(m, c[k], lo, hi))
				return 0;
		return 1;
	}
	for (k = 0; k < n; k++)
		if (hylo_map_cell_clear(m, w->mode, c[k]))
			return 1;
	return 0;
}

/* First crossing of an integer grid line after a (t in (0, 1)), as the line
 * value k and step dk; returns HUGE_VAL when there is none. */
static hylo_real first_cross(hylo_real a, hylo_real d, hylo_real *k, hylo_real *dk)
{
	if (d > 0) {
		*k = floor(a) + 1;
		*dk = 1;
	} else if (d < 0) {
		*k = ceil(a) - 1;
		*dk = -1;
	} else {
		return HUGE_VAL;
	}
	return (*k - a) / d;
}

int hylo_domain_segment(const hylo_map *m, hylo_mode mode, hylo_point a, hylo_point b)
{
	hylo_real ub, vb, t, tx, ty, kx = 0, ky = 0, dkx = 0, dky = 0;
	seg_walk w;
	int32_t iter, bound;

	if (!hylo_domain_contains(m, mode, a) || !hylo_domain_contains(m, mode, b))
		return 0;
	/* Both ends in the rectangle and on the right side of x = 0: so is the
	 * whole segment (both sets are convex). */
	memset(&w, 0, sizeof w);
	w.m = m;
	w.mode = mode;
	map_grid(m, a.x, a.y, &w.ua, &w.va);
	map_grid(m, b.x, b.y, &ub, &vb);
	w.du = ub - w.ua;
	w.dv = vb - w.va;
	w.za = a.z;
	w.dz = b.z - a.z;
	if (hylo_mode_domain(mode) == HYLO_DOMAIN_AIR && b.z != b.z)
		return 0;
	if (w.du == 0 && w.dv == 0)
		return 1; /* a point, or a vertical flight segment: ends checked */

	tx = first_cross(w.ua, w.du, &kx, &dkx);
	ty = first_cross(w.va, w.dv, &ky, &dky);
	bound = m->nx + m->ny + 4;
	t = 0;
	for (iter = 0; iter < bound && t < 1; iter++) {
		hylo_real tn = tx < ty ? tx : ty;

		if (tn > 1)
			tn = 1;
		if (tn > t && !walk_piece(&w, t, tn))
			return 0;
		/* Passing exactly through a vertex touches two more cells. */
		if (hylo_mode_domain(mode) == HYLO_DOMAIN_AIR && tx == tn && ty == tn && tn < 1) {
			hylo_real z = w.za + tn * w.dz;
			cell_set s;
			int k;

			map_touching(m, kx, ky, &s);
			for (k = 0; k < s.n; k++)
				if (!flight_ok(m, s.idx[k], z, z))
					return 0;
		}
		if (tx == tn) {
			kx += dkx;
			tx = (kx - w.ua) / w.du;
		}
		if (ty == tn) {
			ky += dky;
			ty = (ky - w.va) / w.dv;
		}
		t = tn;
	}
	return t >= 1;
}
