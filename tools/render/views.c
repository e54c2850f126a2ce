#include "views.h"

#include <math.h>
#include <stdio.h>
#include <string.h>
#include <GL/gl.h>
#include "hylo/types.h"

#define PI 3.14159265358979323846
#define TITLE_H 26      /* pixels of the title strip (annotations on) */
#define LEGEND_H 30     /* pixels of the legend strip */
#define FONT_PX 13
#define AMBOT_LENGTH_M 0.60   /* outline drawn along the smoothed trajectory */
#define AMBOT_WIDTH_M 0.45    /* the track width B of docs/models.md */
#define DRONE_ARM_M 0.35
#define ALT_ROW_H 18          /* pixels per row of the alternatives' list */
#define ALT_WIDTH_PX 2.0      /* alternatives' line width; the path is 3.5 to 4 */
#define TAG_PX 15             /* side of an alternative's numbered tag */

static const rgba_color BG = {0.97f, 0.97f, 0.97f, 1};
static const rgba_color INK = {0.08f, 0.08f, 0.08f, 1};
static const rgba_color OBSTACLE = {0.33f, 0.33f, 0.36f, 1};
static const rgba_color GROUND = {0.87f, 0.81f, 0.66f, 1};
static const rgba_color WATER = {0.56f, 0.75f, 0.93f, 1};
static const rgba_color DI_NEG_BG = {0.86f, 0.91f, 0.98f, 1};
static const rgba_color DI_POS_BG = {0.99f, 0.90f, 0.84f, 1};
static const rgba_color START = {0.10f, 0.62f, 0.24f, 1};
static const rgba_color GOAL = {0.82f, 0.10f, 0.12f, 1};
static const rgba_color WHITE = {1, 1, 1, 1};
static const rgba_color SMOOTH = {0.08f, 0.08f, 0.08f, 1};
static const rgba_color BASELINE = {0.10f, 0.62f, 0.24f, 1};

static rgba_color mode_color(int mode)
{
	static const rgba_color c[HYLO_MODE_COUNT] = {
		{0.5f, 0.5f, 0.5f, 1},      /* none */
		{0.80f, 0.38f, 0.02f, 1},   /* ground */
		{0.04f, 0.26f, 0.72f, 1},   /* marine */
		{0.55f, 0.12f, 0.70f, 1},   /* flight */
		{0.04f, 0.36f, 0.80f, 1},   /* di_neg */
		{0.85f, 0.30f, 0.05f, 1},   /* di_pos */
	};
	return hylo_mode_valid(mode) ? c[mode] : c[0];
}

/* An alternative's colour: its mode's, a little lighter, so that it reads
 * as secondary to the path (its width tells them apart) while keeping
 * the mode and its contrast with the terrain. */
static rgba_color alt_color(int mode)
{
	rgba_color c = mode_color(mode);

	c.r += 0.15f * (1 - c.r);
	c.g += 0.15f * (1 - c.g);
	c.b += 0.15f * (1 - c.b);
	return c;
}

static rgba_color with_alpha(rgba_color c, float a)
{
	c.a = a;
	return c;
}

static void color(rgba_color c) { glColor4f(c.r, c.g, c.b, c.a); }

/* ---- 2-D frame: world (metres, or p/v) to GL pixels (y up) ---------------- */

typedef struct {
	double wx0, wy0, wx1, wy1;   /* world rectangle shown */
	double s, ox, oy;            /* pixel = o + s * (world - w0) */
	int W, H;
} frame;

static void frame_fit(frame *f, int W, int H, double l, double b, double r, double t,
                      double wx0, double wy0, double wx1, double wy1)
{
	double pw = W - l - r, ph = H - b - t;
	double sx = pw / (wx1 - wx0), sy = ph / (wy1 - wy0);

	f->W = W;
	f->H = H;
	f->wx0 = wx0;
	f->wy0 = wy0;
	f->wx1 = wx1;
	f->wy1 = wy1;
	f->s = sx < sy ? sx : sy;
	f->ox = l + 0.5 * (pw - f->s * (wx1 - wx0));
	f->oy = b + 0.5 * (ph - f->s * (wy1 - wy0));
}

static double fx(const frame *f, double x) { return f->ox + f->s * (x - f->wx0); }
static double fy(const frame *f, double y) { return f->oy + f->s * (y - f->wy0); }

static void pixel_projection(int W, int H)
{
	glViewport(0, 0, W, H);
	glMatrixMode(GL_PROJECTION);
	glLoadIdentity();
	glOrtho(0, W, 0, H, -1, 1);
	glMatrixMode(GL_MODELVIEW);
	glLoadIdentity();
	glDisable(GL_DEPTH_TEST);
	glDisable(GL_LIGHTING);
}

static void disk(double x, double y, double r, rgba_color c)
{
	int k;

	color(c);
	glBegin(GL_TRIANGLE_FAN);
	glVertex2d(x, y);
	for (k = 0; k <= 24; k++)
		glVertex2d(x + r * cos(2 * PI * k / 24), y + r * sin(2 * PI * k / 24));
	glEnd();
}

/* A line of width w pixels as a quad with round caps (wide GL lines vary
 * between drivers; this does not). */
static void thick_line(double x0, double y0, double x1, double y1, double w, rgba_color c)
{
	double dx = x1 - x0, dy = y1 - y0, n = sqrt(dx * dx + dy * dy), h = 0.5 * w;

	if (n > 1e-9) {
		double ux = -dy / n * h, uy = dx / n * h;
		color(c);
		glBegin(GL_QUADS);
		glVertex2d(x0 + ux, y0 + uy);
		glVertex2d(x1 + ux, y1 + uy);
		glVertex2d(x1 - ux, y1 - uy);
		glVertex2d(x0 - ux, y0 - uy);
		glEnd();
	}
	disk(x0, y0, h, c);
	disk(x1, y1, h, c);
}

static void rect(double x0, double y0, double x1, double y1, rgba_color c)
{
	color(c);
	glBegin(GL_QUADS);
	glVertex2d(x0, y0);
	glVertex2d(x1, y0);
	glVertex2d(x1, y1);
	glVertex2d(x0, y1);
	glEnd();
}

/* ---- terrain --------------------------------------------------------------- */

static void height_range(const hylo_map_t *m, float *lo, float *hi)
{
	int i;

	*lo = *hi = m->n_cells > 0 ? m->height_m[0] : 0;
	for (i = 1; i < m->n_cells; i++) {
		if (m->height_m[i] < *lo)
			*lo = m->height_m[i];
		if (m->height_m[i] > *hi)
			*hi = m->height_m[i];
	}
}

static rgba_color terrain_color(const hylo_map_t *m, int cell, float lo, float hi)
{
	rgba_color c;
	float t;

	switch (m->terrain[cell]) {
	case 1: c = GROUND; break;
	case 2: c = WATER; break;
	default: return OBSTACLE;
	}
	/* Higher ground is darker, so platforms read at a glance. */
	t = hi > lo ? (m->height_m[cell] - lo) / (hi - lo) : 0;
	c.r *= 1 - 0.30f * t;
	c.g *= 1 - 0.30f * t;
	c.b *= 1 - 0.30f * t;
	return c;
}

/* Draws one cell (ix, iy) of m: its low corner (x0, y0), its terrain colour c. */
typedef void (*cell_fn)(const void *ctx, const hylo_map_t *m, int ix, int iy, double x0, double y0,
                        rgba_color c);

/* The cells of m as GL_QUADS, each drawn by draw (the top and the 3-D view). */
static void terrain_quads(const hylo_map_t *m, cell_fn draw, const void *ctx)
{
	int ix, iy;
	float lo, hi;
	double r = m->resolution_m;

	height_range(m, &lo, &hi);
	glBegin(GL_QUADS);
	for (iy = 0; iy < m->ny; iy++)
		for (ix = 0; ix < m->nx; ix++)
			draw(ctx, m, ix, iy, m->origin_x_m + ix * r, m->origin_y_m + iy * r,
			     terrain_color(m, iy * m->nx + ix, lo, hi));
	glEnd();
}

typedef struct {
	const frame *f;
	int phase_plane;   /* colour by the sign of p, not by terrain */
} top_view;

static void top_cell(const void *ctx, const hylo_map_t *m, int ix, int iy, double x0, double y0,
                     rgba_color c)
{
	const top_view *v = ctx;
	const frame *f = v->f;
	double r = m->resolution_m;

	if (v->phase_plane)
		c = m->terrain[iy * m->nx + ix] == 0 ? OBSTACLE : x0 + 0.5 * r < 0 ? DI_NEG_BG : DI_POS_BG;
	color(c);
	glVertex2d(fx(f, x0), fy(f, y0));
	glVertex2d(fx(f, x0 + r), fy(f, y0));
	glVertex2d(fx(f, x0 + r), fy(f, y0 + r));
	glVertex2d(fx(f, x0), fy(f, y0 + r));
}

static void draw_terrain_top(const frame *f, const hylo_map_t *m, int phase_plane)
{
	top_view v = {f, phase_plane};

	terrain_quads(m, top_cell, &v);
}

/* ---- graph ------------------------------------------------------------------ */

/* Emits position p as a GL vertex in a view's coordinates. */
typedef void (*position_fn)(const void *ctx, const hylo_position *p);

/* Each roadmap edge once, as GL_LINES in its first end's mode colour at
 * alpha (the top and the 3-D view). */
static void roadmap_edges(const hylo_roadmap *rm, float alpha, position_fn vertex, const void *ctx)
{
	uint32_t i, a;

	glLineWidth(1);
	glBegin(GL_LINES);
	for (i = 0; i < rm->n_positions; i++) {
		const hylo_position *p = &rm->pos[i];
		color(with_alpha(mode_color(p->mode), alpha));
		for (a = p->adj_begin; a < p->adj_end; a++)
			if (rm->adjacency[a] > i) {
				vertex(ctx, p);
				vertex(ctx, &rm->pos[rm->adjacency[a]]);
			}
	}
	glEnd();
}

/* ctx: the frame (const frame *). */
static void position_2d(const void *ctx, const hylo_position *p)
{
	const frame *f = ctx;

	glVertex2d(fx(f, p->p.x), fy(f, p->p.y));
}

/* Raised 0.1 m off the surface. */
static void position_3d(const void *ctx, const hylo_position *p)
{
	(void)ctx;
	glVertex3d(p->p.x, p->p.y, p->p.z + 0.1);
}

static void draw_edges_2d(const frame *f, const hylo_roadmap *rm)
{
	roadmap_edges(rm, 0.22f, position_2d, f);
}

static void draw_nodes_2d(const frame *f, const hylo_roadmap *rm)
{
	uint32_t i;

	for (i = 0; i < rm->n_positions; i++) {
		const hylo_position *p = &rm->pos[i];
		disk(fx(f, p->p.x), fy(f, p->p.y), p->kind == HYLO_POS_GUARD ? 2.2 : 1.8,
		     with_alpha(mode_color(p->mode), 0.85f));
	}
}

/* Mode a path segment k -> k+1 travels in (a switch has zero length). */
static int segment_mode(const hylo_plan_t *p, int k)
{
	return p->mode[k] == p->mode[k + 1] ? p->mode[k + 1] : p->mode[k];
}

static int plan_drawable(const hylo_plan_t *p) { return p && p->status == 0 && p->n_waypoints > 0; }

static void draw_path_2d(const frame *f, const hylo_plan_t *p, double w)
{
	int k;

	for (k = 0; k + 1 < p->n_waypoints; k++)
		thick_line(fx(f, p->state[k][0]), fy(f, p->state[k][1]), fx(f, p->state[k + 1][0]),
		           fy(f, p->state[k + 1][1]), w, mode_color(segment_mode(p, k)));
	for (k = 0; k < p->n_waypoints; k++)
		if (p->guard[k] && (k == 0 || !p->guard[k - 1])) {
			disk(fx(f, p->state[k][0]), fy(f, p->state[k][1]), 5.5, INK);
			disk(fx(f, p->state[k][0]), fy(f, p->state[k][1]), 3.5, WHITE);
		}
	disk(fx(f, p->state[0][0]), fy(f, p->state[0][1]), 6, START);
	disk(fx(f, p->state[p->n_waypoints - 1][0]), fy(f, p->state[p->n_waypoints - 1][1]), 6, GOAL);
}

static void draw_traj_2d(const frame *f, const hylo_traj_t *t, double w, rgba_color c)
{
	int k;

	for (k = 0; k + 1 < t->n_samples; k++)
		thick_line(fx(f, t->state[k][0]), fy(f, t->state[k][1]), fx(f, t->state[k + 1][0]),
		           fy(f, t->state[k + 1][1]), w, c);
}

/* Pose at time t of a trajectory (linear between samples): x, y, heading,
 * mode. Heading: theta of ground and marine (state 4), yaw of flight (8). */
static void traj_pose(const hylo_traj_t *t, double time, double *x, double *y, double *z,
                      double *yaw, int *mode)
{
	int k = 0;
	double a = 0;
	const double *s0, *s1;

	while (k + 1 < t->n_samples - 1 && t->t_s[k + 1] <= time)
		k++;
	if (t->n_samples > 1 && t->t_s[k + 1] > t->t_s[k])
		a = (time - t->t_s[k]) / (t->t_s[k + 1] - t->t_s[k]);
	a = a < 0 ? 0 : a > 1 ? 1 : a;
	s0 = t->state[k];
	s1 = t->state[t->n_samples > 1 ? k + 1 : k];
	*mode = t->mode[k];
	*x = s0[0] + a * (s1[0] - s0[0]);
	*y = s0[1] + a * (s1[1] - s0[1]);
	*z = *mode == HYLO_MODE_FLIGHT ? s0[2] + a * (s1[2] - s0[2]) : 0;
	if (*mode == HYLO_MODE_FLIGHT)
		*yaw = s0[8] + a * (s1[8] - s0[8]);
	else if (*mode == HYLO_MODE_GROUND || *mode == HYLO_MODE_MARINE)
		*yaw = s0[4] + a * (s1[4] - s0[4]);
	else
		*yaw = 0;
}

static void draw_outline_2d(const frame *f, double x, double y, double yaw, int mode)
{
	double c = cos(yaw), s = sin(yaw);
	int k;

	if (mode == HYLO_MODE_FLIGHT) {
		for (k = 0; k < 4; k++) {
			double a = yaw + PI / 4 + k * PI / 2;
			thick_line(fx(f, x), fy(f, y), fx(f, x + DRONE_ARM_M * cos(a)),
			           fy(f, y + DRONE_ARM_M * sin(a)), 1.5, INK);
		}
		return;
	}
	{
		const double hl = 0.5 * AMBOT_LENGTH_M, hw = 0.5 * AMBOT_WIDTH_M;
		const double cx[4] = {hl, -hl, -hl, hl}, cy[4] = {hw, hw, -hw, -hw};
		double px[4], py[4];
		for (k = 0; k < 4; k++) {
			px[k] = fx(f, x + c * cx[k] - s * cy[k]);
			py[k] = fy(f, y + s * cx[k] + c * cy[k]);
		}
		for (k = 0; k < 4; k++)
			thick_line(px[k], py[k], px[(k + 1) % 4], py[(k + 1) % 4], 1.5, INK);
		/* the nose: which way it faces */
		disk(fx(f, x + c * hl), fy(f, y + s * hl), 2.0, INK);
	}
}

static void draw_poses_2d(const frame *f, const hylo_traj_t *t, int n)
{
	int i;
	double t0, t1;

	if (!t || t->n_samples < 2 || n < 1)
		return;
	t0 = t->t_s[0];
	t1 = t->t_s[t->n_samples - 1];
	for (i = 0; i < n; i++) {
		double x, y, z, yaw;
		int mode;
		traj_pose(t, n == 1 ? t0 : t0 + (t1 - t0) * i / (n - 1), &x, &y, &z, &yaw, &mode);
		draw_outline_2d(f, x, y, yaw, mode);
	}
}

/* ---- 3-D ---------------------------------------------------------------------- */

static void normalize3(double *v)
{
	double n = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
	if (n > 0) {
		v[0] /= n;
		v[1] /= n;
		v[2] /= n;
	}
}

static void cross3(const double *a, const double *b, double *o)
{
	o[0] = a[1] * b[2] - a[2] * b[1];
	o[1] = a[2] * b[0] - a[0] * b[2];
	o[2] = a[0] * b[1] - a[1] * b[0];
}

/* Column-major perspective and look-at matrices (as gluPerspective and
 * gluLookAt, without linking GLU). */
static void perspective(double fovy_deg, double aspect, double zn, double zf, double *m)
{
	double t = 1.0 / tan(fovy_deg * PI / 360.0);

	memset(m, 0, 16 * sizeof *m);
	m[0] = t / aspect;
	m[5] = t;
	m[10] = (zf + zn) / (zn - zf);
	m[11] = -1;
	m[14] = 2 * zf * zn / (zn - zf);
}

static void look_at(const double *eye, const double *target, double *m)
{
	double fwd[3] = {target[0] - eye[0], target[1] - eye[1], target[2] - eye[2]};
	double up[3] = {0, 0, 1}, side[3], u[3];

	normalize3(fwd);
	cross3(fwd, up, side);
	normalize3(side);
	cross3(side, fwd, u);
	memset(m, 0, 16 * sizeof *m);
	m[0] = side[0]; m[4] = side[1]; m[8] = side[2];
	m[1] = u[0];    m[5] = u[1];    m[9] = u[2];
	m[2] = -fwd[0]; m[6] = -fwd[1]; m[10] = -fwd[2];
	m[12] = -(side[0] * eye[0] + side[1] * eye[1] + side[2] * eye[2]);
	m[13] = -(u[0] * eye[0] + u[1] * eye[1] + u[2] * eye[2]);
	m[14] = fwd[0] * eye[0] + fwd[1] * eye[1] + fwd[2] * eye[2];
	m[15] = 1;
}

static double cell_height(const hylo_map_t *m, int ix, int iy)
{
	if (ix < 0 || iy < 0 || ix >= m->nx || iy >= m->ny)
		return 0;
	return m->height_m[iy * m->nx + ix];
}

static double surface_at(const hylo_map_t *m, double x, double y)
{
	int ix = (int)floor((x - m->origin_x_m) / m->resolution_m);
	int iy = (int)floor((y - m->origin_y_m) / m->resolution_m);
	ix = ix < 0 ? 0 : ix >= m->nx ? m->nx - 1 : ix;
	iy = iy < 0 ? 0 : iy >= m->ny ? m->ny - 1 : iy;
	return cell_height(m, ix, iy);
}

/* A vertical wall between heights za and zb along the cell edge (x0,y0)-(x1,y1). */
static void wall(double x0, double y0, double x1, double y1, double za, double zb, double nx,
                 double ny)
{
	glNormal3d(nx, ny, 0);
	glVertex3d(x0, y0, za);
	glVertex3d(x1, y1, za);
	glVertex3d(x1, y1, zb);
	glVertex3d(x0, y0, zb);
}

/* ctx: the height of the skirts' base (const double *). */
static void cell_3d(const void *ctx, const hylo_map_t *m, int ix, int iy, double x0, double y0,
                    rgba_color c)
{
	double base = *(const double *)ctx, r = m->resolution_m;
	double h = cell_height(m, ix, iy);
	double hx = ix + 1 < m->nx ? cell_height(m, ix + 1, iy) : base;
	double hy = iy + 1 < m->ny ? cell_height(m, ix, iy + 1) : base;

	color(c);
	glNormal3d(0, 0, 1);
	glVertex3d(x0, y0, h);
	glVertex3d(x0 + r, y0, h);
	glVertex3d(x0 + r, y0 + r, h);
	glVertex3d(x0, y0 + r, h);
	/* walls to the +x and +y neighbours, and skirts at the border */
	if (hx != h)
		wall(x0 + r, y0, x0 + r, y0 + r, hx, h, h > hx ? 1 : -1, 0);
	if (hy != h)
		wall(x0, y0 + r, x0 + r, y0 + r, hy, h, 0, h > hy ? 1 : -1);
	if (ix == 0)
		wall(x0, y0, x0, y0 + r, base, h, -1, 0);
	if (iy == 0)
		wall(x0, y0, x0 + r, y0, base, h, 0, -1);
}

static void draw_terrain_3d(const hylo_map_t *m, double base)
{
	terrain_quads(m, cell_3d, &base);
}

static void path_point_3d(const hylo_map_t *m, const hylo_plan_t *p, int k, double *v)
{
	v[0] = p->state[k][0];
	v[1] = p->state[k][1];
	v[2] = p->mode[k] == HYLO_MODE_FLIGHT ? p->state[k][2] : surface_at(m, v[0], v[1]) + 0.15;
}

/* The segments of plan p in 3-D, each in colour_of its mode. */
static void path_lines_3d(const hylo_map_t *m, const hylo_plan_t *p, rgba_color (*colour_of)(int mode))
{
	int k;
	double a[3], b[3];

	glBegin(GL_LINES);
	for (k = 0; k + 1 < p->n_waypoints; k++) {
		path_point_3d(m, p, k, a);
		path_point_3d(m, p, k + 1, b);
		color(colour_of(segment_mode(p, k)));
		glVertex3dv(a);
		glVertex3dv(b);
	}
	glEnd();
}

static void draw_path_3d(const hylo_map_t *m, const hylo_plan_t *p)
{
	int k;
	double a[3];

	glLineWidth(4);
	path_lines_3d(m, p, mode_color);
	glPointSize(9);
	glBegin(GL_POINTS);
	for (k = 0; k < p->n_waypoints; k++) {
		rgba_color c = k == 0 ? START : k == p->n_waypoints - 1 ? GOAL : INK;
		if (!(k == 0 || k == p->n_waypoints - 1 || p->guard[k]))
			continue;
		path_point_3d(m, p, k, a);
		color(c);
		glVertex3dv(a);
	}
	glEnd();
}

/* ---- alternatives ------------------------------------------------------------ */

/* Where each alternative's numbered tag goes, in image pixels (y down). */
typedef struct {
	int index[INPUT_MAX_ALTERNATIVES];
	double x[INPUT_MAX_ALTERNATIVES], y[INPUT_MAX_ALTERNATIVES];
	int n;
} alt_tags;

/* Alternative i is drawn when it is not the plan itself (index 0), has
 * arrived and has a path. */
static const hylo_plan_t *drawn_alternative(const input_set *in, int i)
{
	const hylo_plan_alternative_t *a = i >= 1 && i < in->n_alternatives ? in->alternative[i] : NULL;

	return a && plan_drawable(&a->plan) ? &a->plan : NULL;
}

/* Rows of the alternatives' list: one per alternative, the plan's own
 * included, when there is one to draw (none: the picture of a plan
 * without alternatives, byte for byte). */
static int alternative_rows(const input_set *in, const view_options *o)
{
	int i;

	if (!o->annotations || !plan_drawable(in->plan))
		return 0;
	for (i = 1; i < in->n_alternatives; i++)
		if (drawn_alternative(in, i))
			return in->n_alternatives;
	return 0;
}

/* Waypoint k in the view's world coordinates (metres, or p and v). */
static void view_point(const hylo_map_t *m, const hylo_plan_t *p, int k, int in_3d, double *v)
{
	if (in_3d) {
		path_point_3d(m, p, k, v);
	} else {
		v[0] = p->state[k][0];
		v[1] = p->state[k][1];
		v[2] = 0;
	}
}

static double distance_to_segment(const double *q, const double *a, const double *b)
{
	double d[3], e[3], n2 = 0, t = 0, r2 = 0;
	int j;

	for (j = 0; j < 3; j++) {
		d[j] = b[j] - a[j];
		n2 += d[j] * d[j];
		t += (q[j] - a[j]) * d[j];
	}
	t = n2 > 0 ? t / n2 : 0;
	t = t < 0 ? 0 : t > 1 ? 1 : t;
	for (j = 0; j < 3; j++) {
		e[j] = a[j] + t * d[j] - q[j];
		r2 += e[j] * e[j];
	}
	return sqrt(r2);
}

/* The waypoint of alternative a farthest from the plan's path: its tag
 * marks it where it differs most. */
static int tag_waypoint(const hylo_map_t *m, const hylo_plan_t *plan, const hylo_plan_t *a,
                        int in_3d)
{
	int k, j, best = 0;
	double best_d = -1, q[3], u[3], w[3];

	for (k = 0; k < a->n_waypoints; k++) {
		double d = HUGE_VAL;
		view_point(m, a, k, in_3d, q);
		for (j = 0; j < plan->n_waypoints; j++) {
			view_point(m, plan, j, in_3d, u);
			view_point(m, plan, j + 1 < plan->n_waypoints ? j + 1 : j, in_3d, w);
			d = fmin(d, distance_to_segment(q, u, w));
		}
		if (d > best_d) {
			best_d = d;
			best = k;
		}
	}
	return best;
}

/* Adds a tag, moved right past any it would cover. */
static void add_tag(alt_tags *t, int index, double x, double y)
{
	int j, moved = 1;

	while (moved) {
		moved = 0;
		for (j = 0; j < t->n; j++)
			if (fabs(t->x[j] - x) < TAG_PX + 1 && fabs(t->y[j] - y) < TAG_PX + 1) {
				x = t->x[j] + TAG_PX + 2;
				moved = 1;
			}
	}
	t->index[t->n] = index;
	t->x[t->n] = x;
	t->y[t->n] = y;
	t->n++;
}

/* The alternatives, dearest first so that cheaper ones lie on top. */
static void draw_alternatives_2d(const frame *f, const input_set *in, alt_tags *tags)
{
	int i, k;

	for (i = in->n_alternatives - 1; i >= 1; i--) {
		const hylo_plan_t *p = drawn_alternative(in, i);
		if (!p)
			continue;
		for (k = 0; k + 1 < p->n_waypoints; k++)
			thick_line(fx(f, p->state[k][0]), fy(f, p->state[k][1]), fx(f, p->state[k + 1][0]),
			           fy(f, p->state[k + 1][1]), ALT_WIDTH_PX, alt_color(segment_mode(p, k)));
		k = tag_waypoint(in->map, in->plan, p, 0);
		add_tag(tags, i, fx(f, p->state[k][0]), f->H - fy(f, p->state[k][1]));
	}
}

/* Image pixel (y down) of world point v through the 3-D view's matrices
 * and viewport (x0, y0, w, h) in an image of height H; 0 behind the camera. */
static int project_3d(const double *proj, const double *view, const double *v, int y0, int w,
                      int h, int H, double *px, double *py)
{
	double e[4], c[4];
	int r;

	for (r = 0; r < 4; r++)
		e[r] = view[r] * v[0] + view[4 + r] * v[1] + view[8 + r] * v[2] + view[12 + r];
	for (r = 0; r < 4; r++)
		c[r] = proj[r] * e[0] + proj[4 + r] * e[1] + proj[8 + r] * e[2] + proj[12 + r] * e[3];
	if (c[3] <= 0)
		return 0;
	*px = 0.5 * (c[0] / c[3] + 1) * w;
	*py = H - (y0 + 0.5 * (c[1] / c[3] + 1) * h);
	return 1;
}

static void draw_alternatives_3d(const hylo_map_t *m, const input_set *in, const double *proj,
                                 const double *view, int y0, int w, int h, int H, alt_tags *tags)
{
	int i;
	double a[3], px, py;

	glLineWidth((float)ALT_WIDTH_PX);
	for (i = in->n_alternatives - 1; i >= 1; i--) {
		const hylo_plan_t *p = drawn_alternative(in, i);
		if (!p)
			continue;
		path_lines_3d(m, p, alt_color);
		path_point_3d(m, p, tag_waypoint(m, in->plan, p, 1), a);
		if (project_3d(proj, view, a, y0, w, h, H, &px, &py))
			add_tag(tags, i, px, py);
	}
}

static void draw_traj_3d(const hylo_map_t *m, const hylo_traj_t *t, rgba_color c)
{
	int k;

	glLineWidth(2);
	color(c);
	glBegin(GL_LINE_STRIP);
	for (k = 0; k < t->n_samples; k++) {
		const double *s = t->state[k];
		glVertex3d(s[0], s[1], t->mode[k] == HYLO_MODE_FLIGHT ? s[2] : surface_at(m, s[0], s[1]) + 0.15);
	}
	glEnd();
}

static void draw_drones_3d(const hylo_map_t *m, const hylo_traj_t *t, int n)
{
	int i, k;
	double t0, t1;
	/* drawn larger than life on big maps, so that it stays visible */
	double arm = fmax(2 * DRONE_ARM_M, 0.015 * m->nx * m->resolution_m);

	if (!t || t->n_samples < 2 || n < 1)
		return;
	t0 = t->t_s[0];
	t1 = t->t_s[t->n_samples - 1];
	glLineWidth(2);
	for (i = 0; i < n; i++) {
		double x, y, z, yaw;
		int mode;
		traj_pose(t, n == 1 ? t0 : t0 + (t1 - t0) * i / (n - 1), &x, &y, &z, &yaw, &mode);
		if (mode != HYLO_MODE_FLIGHT)
			z = surface_at(m, x, y) + 0.15;
		color(INK);
		glBegin(GL_LINES);
		for (k = 0; k < 4; k++) {
			double a = yaw + PI / 4 + k * PI / 2;
			glVertex3d(x, y, z);
			glVertex3d(x + arm * cos(a), y + arm * sin(a), z);
		}
		glEnd();
	}
}

static int render_3d(canvas *c, const input_set *in, const hylo_roadmap *rm, const view_options *o,
                     alt_tags *tags)
{
	const hylo_map_t *m = in->map;
	int top = o->annotations ? TITLE_H : 0;
	int bottom = (o->annotations ? LEGEND_H : 0) + alternative_rows(in, o) * ALT_ROW_H;
	int ph = c->height - top - bottom;
	double proj[16], view[16], eye[3], target[3], R, dist;
	double w = m->nx * m->resolution_m, d = m->ny * m->resolution_m;
	float lo, hi;
	const float light_pos[4] = {-0.45f, -0.75f, 0.8f, 0};
	const float ambient[4] = {0.40f, 0.40f, 0.40f, 1}, diffuse[4] = {0.55f, 0.55f, 0.55f, 1};
	double az = o->azimuth_deg * PI / 180, el = o->elevation_deg * PI / 180;
	double base;

	if (ph < 8)
		return -1;
	height_range(m, &lo, &hi);
	base = lo < 0 ? lo : 0;
	target[0] = m->origin_x_m + 0.5 * w;
	target[1] = m->origin_y_m + 0.5 * d;
	target[2] = 0.5 * (base + hi);
	R = 0.5 * sqrt(w * w + d * d + (hi - base) * (hi - base));
	dist = o->distance_m > 0 ? o->distance_m : 0.8 * R / sin(17.5 * PI / 180);
	eye[0] = target[0] + dist * cos(el) * cos(az);
	eye[1] = target[1] + dist * cos(el) * sin(az);
	eye[2] = target[2] + dist * sin(el);

	glViewport(0, bottom, c->width, ph);
	glMatrixMode(GL_PROJECTION);
	perspective(35, (double)c->width / ph, dist * 0.05, dist * 4, proj);
	glLoadMatrixd(proj);
	glMatrixMode(GL_MODELVIEW);
	look_at(eye, target, view);
	glLoadMatrixd(view);
	glEnable(GL_DEPTH_TEST);
	glDepthFunc(GL_LEQUAL);

	glLightfv(GL_LIGHT0, GL_POSITION, light_pos);
	glLightfv(GL_LIGHT0, GL_AMBIENT, ambient);
	glLightfv(GL_LIGHT0, GL_DIFFUSE, diffuse);
	glEnable(GL_LIGHT0);
	glEnable(GL_LIGHTING);
	glEnable(GL_NORMALIZE);
	glEnable(GL_COLOR_MATERIAL);
	glColorMaterial(GL_FRONT_AND_BACK, GL_AMBIENT_AND_DIFFUSE);
	glLightModeli(GL_LIGHT_MODEL_TWO_SIDE, GL_TRUE);
	glEnable(GL_POLYGON_OFFSET_FILL);
	glPolygonOffset(1, 1);
	draw_terrain_3d(m, base);
	glDisable(GL_POLYGON_OFFSET_FILL);
	glDisable(GL_LIGHTING);

	if (rm && (o->nodes || o->edges)) {
		uint32_t i;
		if (o->edges)
			roadmap_edges(rm, 0.18f, position_3d, NULL);
		if (o->nodes) {
			glPointSize(3);
			glBegin(GL_POINTS);
			for (i = 0; i < rm->n_positions; i++) {
				color(with_alpha(mode_color(rm->pos[i].mode), 0.8f));
				position_3d(NULL, &rm->pos[i]);
			}
			glEnd();
		}
	}
	draw_alternatives_3d(m, in, proj, view, bottom, c->width, ph, c->height, tags);
	if (o->path && plan_drawable(in->plan))
		draw_path_3d(m, in->plan);
	if (in->traj) {
		draw_traj_3d(m, in->traj, SMOOTH);
		draw_drones_3d(m, in->traj, o->n_poses);
	}
	return 0;
}

/* ---- annotations (drawn on the resolved image) ---------------------------------- */

typedef struct {
	canvas *c;
	int x, y;   /* pen: left, vertical centre of the legend strip */
} legend_pen;

static void legend_item(legend_pen *lp, rgba_color col, int line, const char *label)
{
	if (line)
		canvas_fill_rect(lp->c, lp->x, lp->y - 2, 18, 4, col);
	else
		canvas_fill_rect(lp->c, lp->x, lp->y - 6, 14, 12, col);
	lp->x += line ? 22 : 18;
	lp->x += canvas_text(lp->c, lp->x, lp->y + 5, FONT_PX - 1, label, INK) + 12;
}

static const char *mode_label(int mode)
{
	return hylo_mode_valid(mode) ? hylo_mode_str((hylo_mode)mode) : "?";
}

static void title(canvas *c, const input_set *in)
{
	char t[512];
	size_t k;
	int i;
	const hylo_plan_t *p = in->plan;

	if (!p) {
		snprintf(t, sizeof t, "%s map %lld", in->map->robot, (long long)in->map->map_id);
	} else if (p->status != 0) {
		snprintf(t, sizeof t, "%s request %lld: no path drawn (%s)", in->map->robot,
		         (long long)p->request_id, p->reason);
	} else {
		snprintf(t, sizeof t, "%s request %lld   predicted E = %.4g J   ", in->map->robot,
		         (long long)p->request_id, p->total_cost_j);
		for (i = 0; i < p->n_modes; i++) {
			k = strlen(t);
			snprintf(t + k, sizeof t - k, "%s%s", i ? " > " : "", mode_label(p->mode_sequence[i]));
		}
		if (in->traj) {
			k = strlen(t);
			snprintf(t + k, sizeof t - k, "   smoothed E = %.4g J, %.3g s", in->traj->energy_j,
			         in->traj->n_samples ? in->traj->t_s[in->traj->n_samples - 1] : 0.0);
		}
	}
	canvas_text(c, 8, 18, FONT_PX, t, INK);
}

/* An alternative's number (index + 1, as hylo-listen counts) in a box
 * centred at (x, y). */
static void tag_box(canvas *c, int x, int y, int index)
{
	char label[16];
	int x0 = x - TAG_PX / 2, y0 = y - TAG_PX / 2;

	snprintf(label, sizeof label, "%d", index + 1);
	canvas_fill_rect(c, x0, y0, TAG_PX, TAG_PX, INK);
	canvas_fill_rect(c, x0 + 1, y0 + 1, TAG_PX - 2, TAG_PX - 2, WHITE);
	canvas_text(c, x - canvas_text_width(c, FONT_PX - 2, label) / 2, y + 4, FONT_PX - 2, label,
	            INK);
}

/* One row per alternative above the legend strip: its number, predicted
 * cost (and how much above the plan's) and mode sequence. */
static void alternatives_list(canvas *c, const input_set *in, int rows)
{
	int i, k, y0 = c->height - LEGEND_H - rows * ALT_ROW_H;
	char t[512];
	size_t n;

	canvas_fill_rect(c, 0, y0, c->width, rows * ALT_ROW_H, BG);
	for (i = 0; i < rows; i++) {
		const hylo_plan_t *p = i == 0 ? in->plan : drawn_alternative(in, i);
		int y = y0 + i * ALT_ROW_H + ALT_ROW_H / 2;
		tag_box(c, 8 + TAG_PX / 2, y, i);
		if (!p) {
			snprintf(t, sizeof t, "%s", in->alternative[i] ? "no path" : "not received");
		} else {
			snprintf(t, sizeof t, "predicted E = %.5g J", p->total_cost_j);
			n = strlen(t);
			if (i == 0)
				snprintf(t + n, sizeof t - n, " (the plan)");
			else if (in->plan->total_cost_j > 0)
				snprintf(t + n, sizeof t - n, " (%+.1f%%)",
				         100 * (p->total_cost_j / in->plan->total_cost_j - 1));
			for (k = 0; k < p->n_modes; k++) {
				n = strlen(t);
				snprintf(t + n, sizeof t - n, "%s%s", k ? " > " : "   ",
				         mode_label(p->mode_sequence[k]));
			}
		}
		canvas_text(c, 8 + TAG_PX + 8, y + 5, FONT_PX - 1, t, INK);
	}
}

static int map_has(const hylo_map_t *m, int cls)
{
	int i;
	for (i = 0; i < m->n_cells; i++)
		if (m->terrain[i] == cls)
			return 1;
	return 0;
}

static void legend(canvas *c, const input_set *in, const hylo_roadmap *rm, const view_options *o,
                   view_kind kind)
{
	legend_pen lp;
	int i, seen[HYLO_MODE_COUNT] = {0};
	char label[64];

	lp.c = c;
	lp.x = 8;
	lp.y = c->height - LEGEND_H / 2;
	if (kind == VIEW_PHASE) {
		legend_item(&lp, DI_NEG_BG, 0, "p <= 0");
		legend_item(&lp, DI_POS_BG, 0, "p >= 0");
	} else {
		if (map_has(in->map, 1))
			legend_item(&lp, GROUND, 0, "ground");
		if (map_has(in->map, 2))
			legend_item(&lp, WATER, 0, "water");
	}
	if (map_has(in->map, 0))
		legend_item(&lp, OBSTACLE, 0, "obstacle");
	if (o->path && plan_drawable(in->plan))
		for (i = 0; i < in->plan->n_modes; i++) {
			int mo = in->plan->mode_sequence[i];
			if (!hylo_mode_valid(mo) || seen[mo])
				continue;
			seen[mo] = 1;
			snprintf(label, sizeof label, "path: %s", mode_label(mo));
			legend_item(&lp, mode_color(mo), 1, label);
		}
	if (rm && o->nodes && kind != VIEW_PHASE)
		for (i = 1; i < HYLO_MODE_COUNT; i++)
			if (rm->n_per_mode[i]) {
				snprintf(label, sizeof label, "%s nodes", mode_label(i));
				legend_item(&lp, with_alpha(mode_color(i), 0.6f), 0, label);
			}
	if (in->traj)
		legend_item(&lp, SMOOTH, 1, "smoothed");
	if (in->baseline && kind == VIEW_PHASE)
		legend_item(&lp, BASELINE, 1, "multi-phase baseline");
}

static void nice_length(double max, double *len)
{
	double e = pow(10, floor(log10(max)));
	*len = max >= 5 * e ? 5 * e : max >= 2 * e ? 2 * e : e;
}

static void scale_bar(canvas *c, const frame *f)
{
	double len;
	int px, x1, y;
	char label[32];

	nice_length((f->wx1 - f->wx0) / 5, &len);
	px = (int)lround(len * f->s);
	x1 = c->width - 10;
	y = c->height - LEGEND_H / 2;
	snprintf(label, sizeof label, "%g m", len);
	canvas_fill_rect(c, x1 - px, y - 2, px, 4, INK);
	canvas_fill_rect(c, x1 - px, y - 6, 2, 12, INK);
	canvas_fill_rect(c, x1 - 2, y - 6, 2, 12, INK);
	canvas_text(c, x1 - px - 8 - canvas_text_width(c, FONT_PX - 1, label), y + 5, FONT_PX - 1,
	            label, INK);
}

static void phase_axes_text(canvas *c, const frame *f)
{
	static const double ticks[5] = {-1, -0.5, 0, 0.5, 1};
	char label[16];
	int i;

	for (i = 0; i < 5; i++) {
		int tw;
		snprintf(label, sizeof label, "%g", ticks[i]);
		tw = canvas_text_width(c, FONT_PX - 2, label);
		if (ticks[i] >= f->wx0 && ticks[i] <= f->wx1)
			canvas_text(c, (int)lround(fx(f, ticks[i])) - tw / 2,
			            c->height - (int)lround(f->oy) + 16, FONT_PX - 2, label, INK);
		if (ticks[i] >= f->wy0 && ticks[i] <= f->wy1)
			canvas_text(c, (int)lround(f->ox) - tw - 8,
			            c->height - (int)lround(fy(f, ticks[i])) + 4, FONT_PX - 2, label, INK);
	}
	canvas_text(c, (int)lround(fx(f, f->wx1)) - 8, c->height - (int)lround(f->oy) + 30, FONT_PX,
	            "p", INK);
	canvas_text(c, (int)lround(f->ox) - 44, c->height - (int)lround(fy(f, f->wy1)) + 4, FONT_PX,
	            "v", INK);
}

static void phase_ticks(const frame *f)
{
	static const double ticks[5] = {-1, -0.5, 0, 0.5, 1};
	int i;

	for (i = 0; i < 5; i++) {
		if (ticks[i] >= f->wx0 && ticks[i] <= f->wx1)
			rect(fx(f, ticks[i]) - 0.75, f->oy - 5, fx(f, ticks[i]) + 0.75, f->oy, INK);
		if (ticks[i] >= f->wy0 && ticks[i] <= f->wy1)
			rect(f->ox - 5, fy(f, ticks[i]) - 0.75, f->ox, fy(f, ticks[i]) + 0.75, INK);
	}
}

/* ---- entry point ---------------------------------------------------------------- */

int view_render(canvas *c, view_kind kind, const input_set *in, const hylo_roadmap *rm,
                const view_options *o, char *err, size_t errlen)
{
	const hylo_map_t *m = in->map;
	frame f;
	int ann = o->annotations, rows = alternative_rows(in, o), i;
	alt_tags tags;

	memset(&f, 0, sizeof f);
	tags.n = 0;
	if (kind == VIEW_3D) {
		if (render_3d(c, in, rm, o, &tags) != 0) {
			snprintf(err, errlen, "image of %dx%d pixels is too small for the 3-D view",
			         c->width, c->height);
			return -1;
		}
	} else {
		int phase = kind == VIEW_PHASE;
		double l = ann && phase ? 48 : 10;
		double b = (ann ? LEGEND_H : 0) + rows * ALT_ROW_H + (ann && phase ? 36 : 0) + 10;
		double t = (ann ? TITLE_H : 0) + 10;
		frame_fit(&f, c->width, c->height, l, b, 10, t, m->origin_x_m, m->origin_y_m,
		          m->origin_x_m + m->nx * m->resolution_m, m->origin_y_m + m->ny * m->resolution_m);
		if (f.s <= 0) {
			snprintf(err, errlen, "image of %dx%d pixels is too small for the map", c->width,
			         c->height);
			return -1;
		}
		pixel_projection(c->width, c->height);
		draw_terrain_top(&f, m, phase);
		if (phase) {
			thick_line(fx(&f, 0), f.oy, fx(&f, 0), fy(&f, f.wy1), 2, INK);   /* the guard p = 0 */
			if (ann)
				phase_ticks(&f);
		}
		if (rm && o->edges)
			draw_edges_2d(&f, rm);
		if (rm && o->nodes)
			draw_nodes_2d(&f, rm);
		if (phase && in->baseline)
			draw_traj_2d(&f, in->baseline, 2.5, BASELINE);
		draw_alternatives_2d(&f, in, &tags);
		if (o->path && plan_drawable(in->plan))
			draw_path_2d(&f, in->plan, phase ? 3.5 : 4.0);
		if (in->traj) {
			draw_traj_2d(&f, in->traj, 1.5, SMOOTH);
			if (!phase)
				draw_poses_2d(&f, in->traj, o->n_poses);
		}
	}
	if (canvas_finish(c, err, errlen) != 0)
		return -1;
	if (ann) {
		canvas_fill_rect(c, 0, 0, c->width, TITLE_H, BG);
		canvas_fill_rect(c, 0, c->height - LEGEND_H, c->width, LEGEND_H, BG);
		title(c, in);
		legend(c, in, rm, o, kind);
		for (i = 0; i < tags.n; i++)
			tag_box(c, (int)lround(tags.x[i]), (int)lround(tags.y[i]), tags.index[i]);
		if (rows)
			alternatives_list(c, in, rows);
		if (kind == VIEW_TOP)
			scale_bar(c, &f);
		if (kind == VIEW_PHASE)
			phase_axes_text(c, &f);
	}
	return 0;
}
