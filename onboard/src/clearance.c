#include "hylo/clearance.h"
#include "hylo/modes.h"

#include <math.h>

/* Distances between axis-aligned rectangles [x0, x1] x [y0, y1] (a cell's
 * square, an edge, a point): the gaps along each axis combined. */
static hylo_real gap(hylo_real a0, hylo_real a1, hylo_real b0, hylo_real b1)
{
	if (b0 > a1)
		return b0 - a1;
	if (a0 > b1)
		return a0 - b1;
	return 0;
}

typedef struct {
	hylo_real x0, x1, y0, y1;
} rect;

static hylo_real rect_distance(rect a, rect b)
{
	return hypot(gap(a.x0, a.x1, b.x0, b.x1), gap(a.y0, a.y1, b.y0, b.y1));
}

static rect cell_rect(const hylo_map *m, int32_t ix, int32_t iy)
{
	rect r;

	r.x0 = m->origin_x + ix * m->resolution;
	r.x1 = r.x0 + m->resolution;
	r.y0 = m->origin_y + iy * m->resolution;
	r.y1 = r.y0 + m->resolution;
	return r;
}

/* Distance from the inside of rectangle a to the map's boundary (0 when a
 * reaches outside the map). */
static hylo_real boundary_distance(const hylo_map *m, rect a)
{
	hylo_real x1 = m->origin_x + m->nx * m->resolution, y1 = m->origin_y + m->ny * m->resolution;
	hylo_real d = a.x0 - m->origin_x;

	if (x1 - a.x1 < d)
		d = x1 - a.x1;
	if (a.y0 - m->origin_y < d)
		d = a.y0 - m->origin_y;
	if (y1 - a.y1 < d)
		d = y1 - a.y1;
	return d > 0 ? d : 0;
}

/* The wall edge between cells a and b (adjacent), if it is one: both GROUND
 * and a height step over max_step. */
static int wall_between(const hylo_map *m, int32_t a, int32_t b)
{
	return m->terrain[a] == HYLO_TERRAIN_GROUND && m->terrain[b] == HYLO_TERRAIN_GROUND &&
	       fabs((hylo_real)m->height[a] - (hylo_real)m->height[b]) > m->max_step;
}

/* Distance from rectangle a to the nearest ground or marine hazard among
 * the cells of [ix0, ix1] x [iy0, iy1], at most best. */
static hylo_real planar_hazards(const hylo_map *m, hylo_mode mode, rect a, int32_t ix0, int32_t ix1,
				int32_t iy0, int32_t iy1, hylo_real best)
{
	int32_t ix, iy;

	for (iy = iy0; iy <= iy1; iy++)
		for (ix = ix0; ix <= ix1; ix++) {
			int32_t c = iy * m->nx + ix;
			rect s = cell_rect(m, ix, iy), e;
			hylo_real d;

			if (m->terrain[c] == HYLO_TERRAIN_OBSTACLE) {
				d = rect_distance(a, s);
				if (d < best)
					best = d;
				continue;
			}
			if (hylo_mode_domain(mode) != HYLO_DOMAIN_LAND)
				continue;
			/* The edges to the right and above: each wall edge once. */
			if (ix + 1 < m->nx && wall_between(m, c, c + 1)) {
				e = s;
				e.x0 = s.x1;
				d = rect_distance(a, e);
				if (d < best)
					best = d;
			}
			if (iy + 1 < m->ny && wall_between(m, c, c + m->nx)) {
				e = s;
				e.y0 = s.y1;
				d = rect_distance(a, e);
				if (d < best)
					best = d;
			}
		}
	return best;
}

/* The cells within reach of rectangle a, clipped to the map. */
static void window(const hylo_map *m, rect a, hylo_real reach, int32_t *ix0, int32_t *ix1, int32_t *iy0,
		   int32_t *iy1)
{
	hylo_real res = m->resolution;
	hylo_real u0 = floor((a.x0 - reach - m->origin_x) / res), u1 = floor((a.x1 + reach - m->origin_x) / res);
	hylo_real v0 = floor((a.y0 - reach - m->origin_y) / res), v1 = floor((a.y1 + reach - m->origin_y) / res);

	*ix0 = u0 < 0 ? 0 : (int32_t)u0;
	*iy0 = v0 < 0 ? 0 : (int32_t)v0;
	*ix1 = u1 > m->nx - 1 ? m->nx - 1 : (int32_t)u1;
	*iy1 = v1 > m->ny - 1 ? m->ny - 1 : (int32_t)v1;
}

static int point_on_map(const hylo_map *m, hylo_point p)
{
	return p.x >= m->origin_x && p.x <= m->origin_x + m->nx * m->resolution && p.y >= m->origin_y &&
	       p.y <= m->origin_y + m->ny * m->resolution;
}

hylo_real hylo_hazard_distance(const hylo_map *m, hylo_mode mode, hylo_point p, hylo_real reach)
{
	rect a;
	int32_t ix0, ix1, iy0, iy1, ix, iy;
	hylo_real best = reach;

	if (!m || m->nx <= 0 || !(reach >= 0) || p.x != p.x || p.y != p.y)
		return 0;
	if (hylo_mode_domain(mode) == HYLO_DOMAIN_PHASE)
		return reach;
	if (!point_on_map(m, p))
		return 0;
	a.x0 = a.x1 = p.x;
	a.y0 = a.y1 = p.y;
	if (boundary_distance(m, a) < best)
		best = boundary_distance(m, a);
	window(m, a, best, &ix0, &ix1, &iy0, &iy1);
	if (hylo_mode_domain(mode) != HYLO_DOMAIN_AIR)
		return planar_hazards(m, mode, a, ix0, ix1, iy0, iy1, best);
	if (p.z != p.z)
		return 0;
	if (m->ceiling - p.z < best)
		best = m->ceiling - p.z > 0 ? m->ceiling - p.z : 0;
	for (iy = iy0; iy <= iy1; iy++)
		for (ix = ix0; ix <= ix1; ix++) {
			hylo_real up = p.z - (hylo_real)m->height[iy * m->nx + ix];
			hylo_real d = hypot(rect_distance(a, cell_rect(m, ix, iy)), up > 0 ? up : 0);

			if (d < best)
				best = d;
		}
	return best;
}

hylo_status hylo_map_inflate(hylo_map *m, hylo_real r, hylo_reason *why)
{
	int32_t ix, iy, jx, jy, ix0, ix1, iy0, iy1;

	if (!m)
		return hylo_fail(why, HYLO_E_NULL, "inflate: map is NULL");
	if (!(r >= 0) || r - r != 0)
		return hylo_fail(why, HYLO_E_BAD_VALUE, "inflate: clearance %g must be finite and >= 0", r);
	m->inflation = r;
	for (iy = 0; iy < m->ny; iy++)
		for (ix = 0; ix < m->nx; ix++) {
			int32_t c = iy * m->nx + ix;
			rect s = cell_rect(m, ix, iy);
			int near_edge = boundary_distance(m, s) < r;
			hylo_real top = m->height[c];

			window(m, s, r, &ix0, &ix1, &iy0, &iy1);
			m->clear[c] = 0;
			if (!near_edge && m->terrain[c] == HYLO_TERRAIN_GROUND &&
			    !(planar_hazards(m, HYLO_MODE_GROUND, s, ix0, ix1, iy0, iy1, r) < r))
				m->clear[c] = 1;
			if (!near_edge && m->terrain[c] == HYLO_TERRAIN_WATER &&
			    !(planar_hazards(m, HYLO_MODE_MARINE, s, ix0, ix1, iy0, iy1, r) < r))
				m->clear[c] = 1;
			for (jy = iy0; jy <= iy1; jy++)
				for (jx = ix0; jx <= ix1; jx++)
					if (m->height[jy * m->nx + jx] > top &&
					    rect_distance(s, cell_rect(m, jx, jy)) < r)
						top = m->height[jy * m->nx + jx];
			m->floor[c] = near_edge ? HUGE_VAL : top + r;
			if ((hylo_real)m->height[c] + HYLO_AIR_CLEARANCE_M > m->floor[c])
				m->floor[c] = (hylo_real)m->height[c] + HYLO_AIR_CLEARANCE_M;
		}
	hylo_reason_clear(why);
	return HYLO_OK;
}
