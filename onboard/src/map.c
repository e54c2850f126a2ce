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

int hylo_cell_span(hylo_real u, int32_t n, int32_t *lo, int32_t *hi)
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

	hylo_cell_span(u, m->nx, &x0, &x1);
	hylo_cell_span(v, m->ny, &y0, &y1);
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
	hylo_cell_span(u, m->nx, &x0, &x1);
	hylo_cell_span(v, m->ny, &y0, &y1);
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

/* Cell columns (rows) a piece of the walk lies in: the one under its
 * midpoint um, or both sides of the grid line an axis-parallel walk runs
 * along (d = 0). */
static void walk_span(hylo_real a, hylo_real d, hylo_real um, int32_t n, int32_t *lo, int32_t *hi)
{
	hylo_real f;

	if (d == 0) {
		hylo_cell_span(a, n, lo, hi);
		return;
	}
	f = floor(um);
	*lo = *hi = f < 0 ? 0 : (f > n - 1 ? n - 1 : (int32_t)f);
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

void hylo_cell_walk_start(hylo_cell_walk *w, int32_t nx, int32_t ny, hylo_real ua, hylo_real va, hylo_real ub,
			  hylo_real vb)
{
	memset(w, 0, sizeof *w);
	w->nx = nx;
	w->ny = ny;
	w->ua = ua;
	w->va = va;
	w->du = ub - ua;
	w->dv = vb - va;
	w->tx = first_cross(ua, w->du, &w->kx, &w->dkx);
	w->ty = first_cross(va, w->dv, &w->ky, &w->dky);
	w->left = nx > 0 && ny > 0 ? nx + ny + 4 : 0;
	if (w->du == 0 && w->dv == 0)
		w->t = 1;
}

int hylo_cell_walk_next(hylo_cell_walk *w, hylo_cell_piece *p)
{
	for (; w->left > 0 && w->t < 1; w->left--) {
		hylo_real tn = w->tx < w->ty ? w->tx : w->ty, t0 = w->t, tm, um, vm, cu = -1, cv = -1;

		if (tn > 1)
			tn = 1;
		if (tn < 1 && w->tx == tn)
			cu = w->kx;
		if (tn < 1 && w->ty == tn)
			cv = w->ky;
		if (w->tx == tn) {
			w->kx += w->dkx;
			w->tx = (w->kx - w->ua) / w->du;
		}
		if (w->ty == tn) {
			w->ky += w->dky;
			w->ty = (w->ky - w->va) / w->dv;
		}
		w->t = tn;
		if (!(tn > t0))
			continue;
		tm = 0.5 * (t0 + tn);
		um = w->ua + tm * w->du;
		vm = w->va + tm * w->dv;
		if (!(um >= 0 && um <= w->nx && vm >= 0 && vm <= w->ny)) {
			w->left = 0;   /* it leaves the grid: the walk ends */
			return 0;
		}
		p->t0 = t0;
		p->t1 = tn;
		walk_span(w->ua, w->du, um, w->nx, &p->x0, &p->x1);
		walk_span(w->va, w->dv, vm, w->ny, &p->y0, &p->y1);
		/* Its end is on the lines it crosses, else on its own cells' side. */
		p->cross_u = cu < 0 ? -1 : (int32_t)cu;
		p->cross_v = cv < 0 ? -1 : (int32_t)cv;
		p->ex0 = p->x0;
		p->ex1 = p->x1;
		p->ey0 = p->y0;
		p->ey1 = p->y1;
		if (cu >= 0)
			hylo_cell_span(cu, w->nx, &p->ex0, &p->ex1);
		if (cv >= 0)
			hylo_cell_span(cv, w->ny, &p->ey0, &p->ey1);
		w->left--;
		return 1;
	}
	return 0;
}

/* State of the check along one segment. */
typedef struct {
	const hylo_map *m;
	hylo_mode mode;
	hylo_real za, dz;
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

/* Checks one piece of the walk; a flight also at the vertex it ends on. */
static int walk_piece(seg_walk *w, const hylo_cell_piece *p)
{
	const hylo_map *m = w->m;
	int32_t c[2], ix, iy;
	int n = 0, k;

	c[n++] = p->y0 * m->nx + p->x0;
	if (p->x1 != p->x0)
		c[n++] = p->y0 * m->nx + p->x1;
	else if (p->y1 != p->y0)
		c[n++] = p->y1 * m->nx + p->x0;

	if (hylo_mode_domain(w->mode) == HYLO_DOMAIN_LAND)
		return walk_ground(w, c, n);
	if (hylo_mode_domain(w->mode) == HYLO_DOMAIN_AIR) {
		hylo_real z0 = w->za + p->t0 * w->dz, z1 = w->za + p->t1 * w->dz;
		hylo_real lo = z0 < z1 ? z0 : z1, hi = z0 < z1 ? z1 : z0;

		/* On a line both neighbours apply (closed domain: max height). */
		for (k = 0; k < n; k++)
			if (!flight_ok(m, c[k], lo, hi))
				return 0;
		/* Passing exactly through a vertex touches two more cells. */
		if (p->cross_u >= 0 && p->cross_v >= 0)
			for (iy = p->ey0; iy <= p->ey1; iy++)
				for (ix = p->ex0; ix <= p->ex1; ix++)
					if (!flight_ok(m, iy * m->nx + ix, z1, z1))
						return 0;
		return 1;
	}
	for (k = 0; k < n; k++)
		if (hylo_map_cell_clear(m, w->mode, c[k]))
			return 1;
	return 0;
}

int hylo_domain_segment(const hylo_map *m, hylo_mode mode, hylo_point a, hylo_point b)
{
	hylo_real ua, va, ub, vb;
	hylo_cell_walk walk;
	hylo_cell_piece p;
	seg_walk w;

	if (!hylo_domain_contains(m, mode, a) || !hylo_domain_contains(m, mode, b))
		return 0;
	if (hylo_mode_domain(mode) == HYLO_DOMAIN_AIR && b.z != b.z)
		return 0;
	/* Both ends in the rectangle and on the right side of x = 0: so is the
	 * whole segment (both sets are convex). A point, or a vertical flight
	 * segment, has no pieces: its ends are checked. */
	memset(&w, 0, sizeof w);
	w.m = m;
	w.mode = mode;
	w.za = a.z;
	w.dz = b.z - a.z;
	map_grid(m, a.x, a.y, &ua, &va);
	map_grid(m, b.x, b.y, &ub, &vb);
	hylo_cell_walk_start(&walk, m->nx, m->ny, ua, va, ub, vb);
	while (hylo_cell_walk_next(&walk, &p))
		if (!walk_piece(&w, &p))
			return 0;
	return walk.t >= 1;
}
