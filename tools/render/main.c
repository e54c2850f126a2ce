/*
 * hylo-render: draws a plan on its map, offscreen (OSMesa), into a PNG.
 * Inputs come from LCM logs (--log, repeatable) or a live bus (--lcm-url).
 * The roadmap's nodes and edges are rebuilt from the goal's sampling
 * options with the onboard library, so they are exactly the planner's.
 * Exit codes: 0 written, 1 rendering or input failure, 2 usage error.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "canvas.h"
#include "hylo/planner.h"
#include "input.h"
#include "hylo_msg.h"
#include "node/registry.h"
#include "views.h"

#define MAX_LOGS 16

static void usage(FILE *f)
{
	fprintf(f,
		"usage: hylo-render (--log FILE... | --lcm-url URL) --out PNG [options]\n"
		"Draws the plan (channel HYLO_PLAN) on its map (HYLO_MAP), with the sampled\n"
		"nodes of its goal (HYLO_GOAL), its alternatives (HYLO_PLAN_ALTERNATIVE: other\n"
		"mode sequences, drawn thin, numbered and listed with their predicted cost), its\n"
		"smoothed trajectory (HYLO_TRAJ) and, in the phase plane, a multi-phase baseline\n"
		"trajectory (HYLO_BASELINE).\n"
		"\n"
		"  --log FILE          LCM log to read; repeat for several (e.g. the scene's log and\n"
		"                      the planner's output log)\n"
		"  --lcm-url URL       listen on a live bus instead until a plan and its map arrive\n"
		"  --timeout S         with --lcm-url: give up after S seconds (default: 10)\n"
		"  --channel-prefix P  prefix of the channel names (default: none)\n"
		"  --out PNG           image to write (required; written atomically)\n"
		"  --request-id N      the plan answering request N (default: the last plan)\n"
		"  --map-only          draw the map alone; no plan needed\n"
		"  --view V            top, phase or 3d (default: phase for di, 3d for\n"
		"                      drivocopter, top otherwise)\n"
		"  --width W           image width in pixels (default: 960)\n"
		"  --height H          image height in pixels (default: 720)\n"
		"  --edges             draw the graph's edges\n"
		"  --no-nodes          do not draw the sampled nodes\n"
		"  --no-path           do not draw the path (its alternatives still are)\n"
		"  --no-alternatives   do not draw or list the plan's alternatives\n"
		"  --no-annotations    no title, legend, scale bar or axes\n"
		"  --poses N           robot outlines along the smoothed trajectory (default: 8)\n"
		"  --camera AZ,EL[,D]  3-D camera azimuth and elevation [deg] and distance [m]\n"
		"                      (default: -60,28 and a distance that fits the map)\n"
		"  --quiet             no summary line\n"
		"  --help              this text\n"
		"Exit codes: 0 written, 1 input or rendering failure, 2 usage error.\n");
}

static int parse_int(const char *s, long lo, long hi, long *out)
{
	char *end;
	long v = strtol(s, &end, 10);

	if (end == s || *end != '\0' || v < lo || v > hi)
		return -1;
	*out = v;
	return 0;
}

static int parse_camera(const char *s, view_options *o)
{
	double v[3] = {0, 0, 0};
	int n = 0;
	const char *p = s;

	while (n < 3) {
		char *end;
		v[n] = strtod(p, &end);
		if (end == p || !isfinite(v[n]))
			return -1;
		n++;
		if (*end == '\0')
			break;
		if (*end != ',')
			return -1;
		p = end + 1;
	}
	if (n < 2 || *p == '\0' || v[1] < -89 || v[1] > 89 || v[2] < 0)
		return -1;
	o->azimuth_deg = v[0];
	o->elevation_deg = v[1];
	o->distance_m = v[2];
	return 0;
}

/* Rebuilds the plan's roadmap with the onboard library. NULL (with a note)
 * when there is no goal or the robot is not one this build knows. */
static const hylo_roadmap *rebuild_roadmap(const input_set *in, int quiet)
{
	static hylo_robot robots[HYLO_MAX_ROBOTS];
	static hylo_planner *pl;
	size_t size;
	static hylo_plan plan;
	hylo_planner_config cfg;
	hylo_map_view view;
	hylo_goal goal;
	hylo_reason reason;
	uint32_t n;
	const hylo_roadmap *rm;

	if (!in->goal) {
		if (!quiet)
			fprintf(stderr, "hylo-render: note: no goal for this plan in the input; "
			        "nodes and edges are not drawn\n");
		return NULL;
	}
	n = hylo_registry_robots(robots, HYLO_MAX_ROBOTS, &reason);
	memset(&cfg, 0, sizeof cfg);
	cfg.robots = robots;
	cfg.n_robots = n;
	size = hylo_planner_size(&cfg);
	if (!pl)
		pl = malloc(size);
	if (n == 0 || !pl || hylo_planner_init(pl, size, &cfg) != HYLO_OK)
		return NULL;
	hylo_msg_map_view(in->map, &view);
	hylo_msg_goal_view(in->goal, &goal);
	if (hylo_planner_set_map(pl, &view) == HYLO_OK)
		hylo_planner_plan(pl, &goal, &plan);
	rm = hylo_planner_roadmap(pl);
	if (!rm && !quiet)
		fprintf(stderr, "hylo-render: note: the roadmap could not be rebuilt (%s); nodes and "
		        "edges are not drawn\n", hylo_planner_reason(pl));
	return rm;
}

static view_kind default_view(const char *robot)
{
	if (strcmp(robot, "di") == 0)
		return VIEW_PHASE;
	if (strcmp(robot, "drivocopter") == 0)
		return VIEW_3D;
	return VIEW_TOP;
}

int main(int argc, char **argv)
{
	const char *logs[MAX_LOGS], *url = NULL, *out = NULL, *view_name = NULL;
	int n_logs = 0, quiet = 0, i, rc = 1;
	long width = 960, height = 720, lv;
	double timeout_s = 10;
	input_options io = {"", -1, 1, 1};
	view_options vo = {1, 0, 1, 1, 8, -60, 28, 0};
	input_set in;
	canvas c;
	char err[1024];
	view_kind kind;
	const hylo_roadmap *rm = NULL;
	static const rgba_color bg = {0.97f, 0.97f, 0.97f, 1};

	for (i = 1; i < argc; i++) {
		const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
		int takes = strcmp(a, "--log") == 0 || strcmp(a, "--lcm-url") == 0 ||
		            strcmp(a, "--timeout") == 0 || strcmp(a, "--channel-prefix") == 0 ||
		            strcmp(a, "--out") == 0 || strcmp(a, "--request-id") == 0 ||
		            strcmp(a, "--view") == 0 || strcmp(a, "--width") == 0 ||
		            strcmp(a, "--height") == 0 || strcmp(a, "--poses") == 0 ||
		            strcmp(a, "--camera") == 0;
		if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
			usage(stdout);
			return 0;
		}
		if (takes && !v) {
			fprintf(stderr, "hylo-render: %s needs a value (see --help)\n", a);
			return 2;
		}
		if (strcmp(a, "--log") == 0) {
			if (n_logs == MAX_LOGS) {
				fprintf(stderr, "hylo-render: at most %d --log files\n", MAX_LOGS);
				return 2;
			}
			logs[n_logs++] = v;
		} else if (strcmp(a, "--lcm-url") == 0) {
			url = v;
		} else if (strcmp(a, "--timeout") == 0) {
			char *end;
			timeout_s = strtod(v, &end);
			if (end == v || *end || !(timeout_s > 0 && timeout_s < 1e6)) {
				fprintf(stderr, "hylo-render: --timeout '%s' is not a positive number of seconds\n", v);
				return 2;
			}
		} else if (strcmp(a, "--channel-prefix") == 0) {
			io.prefix = v;
		} else if (strcmp(a, "--out") == 0) {
			out = v;
		} else if (strcmp(a, "--request-id") == 0) {
			char *end;
			long long id = strtoll(v, &end, 10);
			if (end == v || *end || id < 0) {
				fprintf(stderr, "hylo-render: --request-id '%s' is not a request id\n", v);
				return 2;
			}
			io.request_id = id;
		} else if (strcmp(a, "--map-only") == 0) {
			io.want_plan = 0;
		} else if (strcmp(a, "--view") == 0) {
			if (strcmp(v, "top") && strcmp(v, "phase") && strcmp(v, "3d")) {
				fprintf(stderr, "hylo-render: --view '%s' is not top, phase or 3d\n", v);
				return 2;
			}
			view_name = v;
		} else if (strcmp(a, "--width") == 0 || strcmp(a, "--height") == 0) {
			if (parse_int(v, 16, CANVAS_MAX_SIDE, &lv) != 0) {
				fprintf(stderr, "hylo-render: %s '%s' is not a size from 16 to %d pixels\n", a, v,
				        CANVAS_MAX_SIDE);
				return 2;
			}
			if (a[2] == 'w')
				width = lv;
			else
				height = lv;
		} else if (strcmp(a, "--poses") == 0) {
			if (parse_int(v, 0, 1000, &lv) != 0) {
				fprintf(stderr, "hylo-render: --poses '%s' is not a count from 0 to 1000\n", v);
				return 2;
			}
			vo.n_poses = (int)lv;
		} else if (strcmp(a, "--camera") == 0) {
			if (parse_camera(v, &vo) != 0) {
				fprintf(stderr, "hylo-render: --camera '%s' is not AZ,EL[,DIST] (elevation in "
				        "[-89, 89] deg, distance >= 0 m)\n", v);
				return 2;
			}
		} else if (strcmp(a, "--edges") == 0) {
			vo.edges = 1;
		} else if (strcmp(a, "--no-nodes") == 0) {
			vo.nodes = 0;
		} else if (strcmp(a, "--no-path") == 0) {
			vo.path = 0;
		} else if (strcmp(a, "--no-alternatives") == 0) {
			io.want_alternatives = 0;
		} else if (strcmp(a, "--no-annotations") == 0) {
			vo.annotations = 0;
		} else if (strcmp(a, "--quiet") == 0) {
			quiet = 1;
		} else {
			fprintf(stderr, "hylo-render: unknown argument '%s' (see --help)\n", a);
			return 2;
		}
		if (takes)
			i++;
	}
	if (!out) {
		fprintf(stderr, "hylo-render: --out PNG is required (see --help)\n");
		return 2;
	}
	if ((n_logs == 0) == (url == NULL)) {
		fprintf(stderr, "hylo-render: give either --log FILE or --lcm-url URL (see --help)\n");
		return 2;
	}

	memset(&in, 0, sizeof in);
	for (i = 0; i < n_logs; i++)
		if (input_read_log(&in, &io, logs[i], err, sizeof err) != 0)
			goto fail;
	if (url && input_listen(&in, &io, url, timeout_s, err, sizeof err) != 0)
		goto fail;
	if (in.n_undecodable && !quiet)
		fprintf(stderr, "hylo-render: warning: %d message(s) on hylo channels did not decode "
		        "and were skipped\n", in.n_undecodable);
	if (input_select(&in, &io, err, sizeof err) != 0)
		goto fail;
	if (in.plan && in.plan->status != 0 && !quiet)
		fprintf(stderr, "hylo-render: note: plan %lld has no path (status %d: %s); drawing the "
		        "map\n", (long long)in.plan->request_id, in.plan->status, in.plan->reason);

	kind = view_name ? (view_name[0] == 't' ? VIEW_TOP : view_name[0] == 'p' ? VIEW_PHASE : VIEW_3D)
	                 : default_view(in.map->robot);
	if ((vo.nodes || vo.edges) && io.want_plan)
		rm = rebuild_roadmap(&in, quiet);
	if (canvas_open(&c, (int)width, (int)height, bg, err, sizeof err) != 0) {
		canvas_close(&c);
		goto fail;
	}
	if (view_render(&c, kind, &in, rm, &vo, err, sizeof err) != 0 ||
	    canvas_write_png(&c, out, err, sizeof err) != 0) {
		canvas_close(&c);
		goto fail;
	}
	canvas_close(&c);
	if (!quiet) {
		printf("wrote %s (%ldx%ld, %s view, map %lld%s%s", out, width, height,
		       kind == VIEW_TOP ? "top" : kind == VIEW_PHASE ? "phase" : "3d",
		       (long long)in.map->map_id, in.plan ? ", plan " : "",
		       in.plan ? (in.plan->status == 0 ? "ok" : "without a path") : "");
		if (in.n_alternatives > 1)
			printf(", %d alternatives", in.n_alternatives);
		printf(")\n");
	}
	rc = 0;
	input_free(&in);
	return rc;
fail:
	fprintf(stderr, "hylo-render: %s\n", err);
	input_free(&in);
	return rc;
}
