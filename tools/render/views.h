/*
 * The three pictures of a plan:
 *   top    2-D top view (Ambot): terrain classes, nodes by mode, optional
 *          edges, the path by mode, guard points, the robot's outline at
 *          equal time steps of the smoothed trajectory, scale bar, legend;
 *   phase  phase plane (double integrator): the two domains, the guard,
 *          edges, graph path, smoothed path and multi-phase baseline;
 *   3d     perspective (Drivocopter): lit terrain mesh, ground and flight
 *          segments of the path, the drone at equal time steps.
 * In each, the plan's alternatives (other mode sequences) are drawn thin
 * under the path, tagged with their number, and listed above the legend.
 */
#ifndef HYLO_RENDER_VIEWS_H
#define HYLO_RENDER_VIEWS_H

#include "canvas.h"
#include "hylo/internal/roadmap.h"
#include "input.h"

typedef enum { VIEW_TOP, VIEW_PHASE, VIEW_3D } view_kind;

typedef struct {
	int nodes;           /* draw sampled nodes (needs the roadmap) */
	int edges;           /* draw graph edges (needs the roadmap) */
	int path;            /* draw the plan's path and guard points */
	int annotations;     /* title, legend, scale bar, axes */
	int n_poses;         /* robot outlines along the smoothed trajectory */
	double azimuth_deg, elevation_deg, distance_m;   /* 3-D camera; distance 0: fit */
} view_options;

/* Draws the picture into c (opened, not yet finished) and finishes it.
 * rm may be NULL (no nodes or edges). Returns 0, or -1 with err set. */
int view_render(canvas *c, view_kind kind, const input_set *in, const hylo_roadmap *rm,
                const view_options *o, char *err, size_t errlen);

#endif
