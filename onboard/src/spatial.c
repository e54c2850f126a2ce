#include "hylo/internal/spatial.h"

#include <math.h>

/* Enlarging the bucket edge by this factor per step until the grid fits. */
#define SPATIAL_GROW 1.0625
#define SPATIAL_GROW_STEPS 2048

static int real_finite(hylo_real x)
{
	return x == x && x - x == 0;
}

/* Buckets needed along an extent w with edge cell (at least one); a value
 * above HYLO_MAX_BUCKETS means "too many". */
static hylo_real spatial_count(hylo_real w, hylo_real cell)
{
	hylo_real n = floor(w / cell) + 1;

	return n < 1 ? 1 : n;
}

hylo_status hylo_spatial_init(hylo_spatial *g, hylo_real x0, hylo_real y0,
			      hylo_real x1, hylo_real y1, hylo_real min_cell,
			      hylo_reason *r)
{
	hylo_real cell, nx = 0, ny = 0;
	uint32_t i;
	int step;

	if (!g)
		return hylo_fail(r, HYLO_E_NULL, "spatial: grid is NULL");
	if (!real_finite(x0) || !real_finite(y0) || !real_finite(x1) || !real_finite(y1) ||
	    !real_finite(x1 - x0) || !real_finite(y1 - y0) || x1 < x0 || y1 < y0)
		return hylo_fail(r, HYLO_E_BAD_VALUE,
				 "spatial: rectangle [%g, %g] x [%g, %g] is not finite and ordered",
				 x0, x1, y0, y1);
	if (!real_finite(min_cell) || !(min_cell > 0))
		return hylo_fail(r, HYLO_E_BAD_VALUE, "spatial: min_cell = %g must be finite and > 0",
				 min_cell);
	/* Start near the area-based size, then grow until the grid fits. */
	cell = sqrt((x1 - x0) * (y1 - y0) / HYLO_MAX_BUCKETS);
	if (cell < (x1 - x0) / HYLO_MAX_BUCKETS)
		cell = (x1 - x0) / HYLO_MAX_BUCKETS;
	if (cell < (y1 - y0) / HYLO_MAX_BUCKETS)
		cell = (y1 - y0) / HYLO_MAX_BUCKETS;
	if (!(cell > min_cell))
		cell = min_cell;
	for (step = 0; step < SPATIAL_GROW_STEPS; step++) {
		nx = spatial_count(x1 - x0, cell);
		ny = spatial_count(y1 - y0, cell);
		if (nx <= HYLO_MAX_BUCKETS && ny <= HYLO_MAX_BUCKETS &&
		    nx * ny <= HYLO_MAX_BUCKETS)
			break;
		cell *= SPATIAL_GROW;
	}
	if (step == SPATIAL_GROW_STEPS)
		return hylo_fail(r, HYLO_E_CAP_BUCKETS,
				 "spatial: rectangle needs more than HYLO_MAX_BUCKETS = %ld buckets",
				 (long)HYLO_MAX_BUCKETS);
	g->x0 = x0;
	g->y0 = y0;
	g->cell = cell;
	g->nx = (uint32_t)nx;
	g->ny = (uint32_t)ny;
	g->count = 0;
	for (i = 0; i < g->nx * g->ny; i++)
		g->head[i] = HYLO_SPATIAL_NONE;
	return HYLO_OK;
}

/* Bucket column of coordinate x: clamped, so that points outside the
 * rectangle (and NaN) land in a border bucket. */
static uint32_t spatial_col(hylo_real x, hylo_real x0, hylo_real cell, uint32_t n)
{
	hylo_real f = floor((x - x0) / cell);

	if (!(f >= 0))
		return 0;
	if (f >= (hylo_real)n - 1)
		return n - 1;
	return (uint32_t)f;
}

hylo_status hylo_spatial_insert(hylo_spatial *g, uint32_t id, const hylo_point *pts)
{
	uint32_t b;

	if (!g || !pts)
		return HYLO_E_NULL;
	if (id >= HYLO_MAX_POSITIONS)
		return HYLO_E_CAP_POSITIONS;
	if (g->nx == 0 || g->ny == 0)
		return HYLO_E_BAD_VALUE;
	b = spatial_col(pts[id].y, g->y0, g->cell, g->ny) * g->nx +
	    spatial_col(pts[id].x, g->x0, g->cell, g->nx);
	g->next[id] = g->head[b];
	g->head[b] = id;
	g->count++;
	return HYLO_OK;
}

static hylo_real spatial_d2(hylo_point a, hylo_point b)
{
	hylo_real dx = a.x - b.x, dy = a.y - b.y, dz = a.z - b.z;

	return dx * dx + dy * dy + dz * dz;
}

/* In-place heapsort (no recursion, O(k log k)) for long result lists. */
static void sift_down(uint32_t *a, uint32_t root, uint32_t n)
{
	uint32_t child, v = a[root];

	while ((child = 2 * root + 1) < n) {
		if (child + 1 < n && a[child + 1] > a[child])
			child++;
		if (a[child] <= v)
			break;
		a[root] = a[child];
		root = child;
	}
	a[root] = v;
}

static void sort_ids(uint32_t *a, uint32_t n)
{
	uint32_t i, j;

	if (n <= 32) {
		for (i = 1; i < n; i++) {
			uint32_t v = a[i];

			for (j = i; j > 0 && a[j - 1] > v; j--)
				a[j] = a[j - 1];
			a[j] = v;
		}
		return;
	}
	for (i = n / 2; i-- > 0;)
		sift_down(a, i, n);
	for (i = n - 1; i > 0; i--) {
		uint32_t t = a[0];

		a[0] = a[i];
		a[i] = t;
		sift_down(a, 0, i);
	}
}

/* A walk over the points in the bins that the disc of radius r around q
 * touches (a superset of those within r): rows, then columns, then each
 * bin's list. */
typedef struct {
	uint32_t bx0, bx1, by1, bx, by, id;
} spatial_walk;

static void walk_start(const hylo_spatial *g, hylo_point q, hylo_real r, spatial_walk *w)
{
	w->bx0 = spatial_col(q.x - r, g->x0, g->cell, g->nx);
	w->bx1 = spatial_col(q.x + r, g->x0, g->cell, g->nx);
	w->by = spatial_col(q.y - r, g->y0, g->cell, g->ny);
	w->by1 = spatial_col(q.y + r, g->y0, g->cell, g->ny);
	w->bx = w->bx0;
	w->id = g->head[w->by * g->nx + w->bx];
}

/* The next point's id, or HYLO_SPATIAL_NONE at the end. */
static uint32_t walk_next(const hylo_spatial *g, spatial_walk *w)
{
	uint32_t id;

	while (w->id == HYLO_SPATIAL_NONE) {
		if (w->bx < w->bx1) {
			w->bx++;
		} else if (w->by < w->by1) {
			w->bx = w->bx0;
			w->by++;
		} else {
			return HYLO_SPATIAL_NONE;
		}
		w->id = g->head[w->by * g->nx + w->bx];
	}
	id = w->id;
	w->id = g->next[id];
	return id;
}

hylo_status hylo_spatial_query(const hylo_spatial *g, const hylo_point *pts,
			       hylo_point q, hylo_real radius,
			       uint32_t *out, uint32_t cap, uint32_t *n)
{
	spatial_walk w;
	uint32_t id, found = 0;
	hylo_real r2 = radius * radius;

	if (n)
		*n = 0;
	if (!g || !pts || !out || !n)
		return HYLO_E_NULL;
	if (radius != radius || q.x != q.x || q.y != q.y || q.z != q.z)
		return HYLO_E_BAD_VALUE;
	if (radius < 0 || g->nx == 0)
		return HYLO_OK;
	for (walk_start(g, q, radius, &w); (id = walk_next(g, &w)) != HYLO_SPATIAL_NONE;) {
		if (!(spatial_d2(pts[id], q) <= r2))
			continue;
		if (found == cap) {
			sort_ids(out, found);
			*n = found;
			return HYLO_E_CAP_SUCCESSORS;
		}
		out[found++] = id;
	}
	sort_ids(out, found);
	*n = found;
	return HYLO_OK;
}

int hylo_spatial_any_closer(const hylo_spatial *g, const hylo_point *pts,
			    hylo_point q, hylo_real radius)
{
	spatial_walk w;
	uint32_t id;
	hylo_real r2 = radius * radius;

	if (!g || !pts || g->nx == 0 || !(radius > 0))
		return 0;
	for (walk_start(g, q, radius, &w); (id = walk_next(g, &w)) != HYLO_SPATIAL_NONE;)
		if (spatial_d2(pts[id], q) < r2)
			return 1;
	return 0;
}
