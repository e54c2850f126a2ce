/*
 * hylo-cost: the predicted edge cost and feasibility of one pair of sampled
 * states, from the model headers compiled in (onboard/models/), with the
 * onboard evaluator itself: for users checking a model. See --help.
 * Exit codes: 0 printed, 1 no model for that robot and mode, 2 usage error.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hylo/envelope.h"
#include "hylo/features.h"
#include "hylo/region.h"
#include "node/registry.h"

static void usage(FILE *f)
{
	fprintf(f,
		"usage: hylo-cost --robot R --mode M [--json] X1 X2\n"
		"Prints the predicted energy of the edge X1 -> X2 (sampled coordinates of mode M,\n"
		"comma-separated, docs/models.md section 7: ground/marine px,py,vx,theta;\n"
		"flight px,py,pz,vx,vy,vz; di_neg/di_pos p,v) and whether the mode's\n"
		"feasibility classifier, if any, predicts a solution, and the model's envelope:\n"
		"the lower bound of its cost over every heading that the planner's search may\n"
		"use for an edge of this distance, these speeds and (ground, marine) this turn,\n"
		"the least total heading change of a path to X2 (flight: the climb, and the\n"
		"turn table's flight turn, how far both velocities point away from the\n"
		"displacement) (JSON envelope_j, null when there is none; envelope_turn_rad,\n"
		"null for a flight edge without a flight turn). Notes when the displacement,\n"
		"a speed or another coordinate (e.g. a flight vz: the training velocities are\n"
		"level) lies outside the model's trained region, naming it (JSON:\n"
		"beyond_training_range, outside_region: one text per finding, or []).\n"
		"\n"
		"  --robot R    robot (ambot, drivocopter, di, ...; see hylo-planner --list-robots)\n"
		"  --mode M     ground, marine, flight, di_neg or di_pos\n"
		"  --json       print one JSON object\n"
		"  --help       this text\n");
}

static int parse_state(const char *text, unsigned dim, double *x, const char *what)
{
	const char *p = text;
	unsigned k;

	for (k = 0; k < dim; k++) {
		char *end;

		x[k] = strtod(p, &end);
		if (end == p || !isfinite(x[k]) || (k + 1 < dim ? *end != ',' : *end != '\0')) {
			fprintf(stderr, "hylo-cost: %s '%s' is not %u comma-separated finite numbers\n",
				what, text, dim);
			return -1;
		}
		p = end + 1;
	}
	return 0;
}

/* What of the edge x1 -> x2 lies outside m's trained region (hylo/region.h),
 * one text each into notes: the displacement, then what of X1, then of X2.
 * Returns their number. */
static int trained_region_notes(const hylo_svr_model *m, hylo_mode mode, const double *x1,
				const double *x2, double dist, char notes[3][200])
{
	const double *x[2];
	hylo_region_miss miss;
	char what[160];
	int n = 0, k;

	x[0] = x1;
	x[1] = x2;
	if (m->max_distance_m > 0 && dist > m->max_distance_m)
		snprintf(notes[n++], 200, "displacement %.3g m is beyond the training range %.3g m", dist,
			 m->max_distance_m);
	for (k = 0; k < 2; k++)
		if (!hylo_region_state(m, mode, x[k], &miss)) {
			hylo_region_describe(mode, &miss, what, sizeof what);
			snprintf(notes[n++], 200, "X%d's %s", k + 1, what);
		}
	return n;
}

int main(int argc, char **argv)
{
	static hylo_robot robots[HYLO_MAX_ROBOTS];
	const char *robot = NULL, *mode_name = NULL, *xs[2] = { NULL, NULL };
	double x1[HYLO_XS_DIM] = { 0 }, x2[HYLO_XS_DIM] = { 0 }, f[HYLO_MAX_FEATURES];
	int json = 0, n_x = 0, i, mode = 0, m;
	uint32_t n, k;
	hylo_reason reason;
	const hylo_mode_model *mm = NULL;
	double cost, floor_cost, dist, feas = NAN, envelope, args[4];
	int flight_turn;
	int planar;
	char outside[3][200];
	int n_outside;

	for (i = 1; i < argc; i++) {
		if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
			usage(stdout);
			return 0;
		} else if (strcmp(argv[i], "--json") == 0) {
			json = 1;
		} else if (strcmp(argv[i], "--robot") == 0 && i + 1 < argc) {
			robot = argv[++i];
		} else if (strcmp(argv[i], "--mode") == 0 && i + 1 < argc) {
			mode_name = argv[++i];
		} else if (argv[i][0] == '-' && argv[i][1] != '\0' && argv[i][1] != '.' &&
			   !(argv[i][1] >= '0' && argv[i][1] <= '9')) {
			fprintf(stderr, "hylo-cost: unknown or incomplete option '%s' (see --help)\n", argv[i]);
			return 2;
		} else if (n_x < 2) {
			xs[n_x++] = argv[i];
		} else {
			fprintf(stderr, "hylo-cost: more than two states given\n");
			return 2;
		}
	}
	if (!robot || !mode_name || n_x != 2) {
		fprintf(stderr, "hylo-cost: need --robot, --mode and two states (see --help)\n");
		return 2;
	}
	for (m = 1; m < HYLO_MODE_COUNT; m++)
		if (strcmp(mode_name, hylo_mode_str((hylo_mode)m)) == 0)
			mode = m;
	if (!mode) {
		fprintf(stderr, "hylo-cost: unknown mode '%s' (ground, marine, flight, di_neg, di_pos)\n",
			mode_name);
		return 2;
	}
	if (parse_state(xs[0], hylo_mode_dim((hylo_mode)mode), x1, "X1") ||
	    parse_state(xs[1], hylo_mode_dim((hylo_mode)mode), x2, "X2"))
		return 2;
	n = hylo_registry_robots(robots, HYLO_MAX_ROBOTS, &reason);
	for (k = 0; k < n; k++)
		if (strcmp(robots[k].name, robot) == 0) {
			int idx = hylo_robot_mode_index(&robots[k], (hylo_mode)mode);

			if (idx >= 0)
				mm = &robots[k].modes[idx];
		}
	if (!mm || !mm->model) {
		fprintf(stderr, "hylo-cost: no model for robot '%s' in mode %s in this build "
			"(train one: trainer --mode %s --robot %s)\n", robot, mode_name, mode_name, robot);
		return 1;
	}
	hylo_features((hylo_mode)mode, x1, x2, f);
	cost = hylo_svr_predict(mm->model, f);
	envelope = hylo_envelope_of_edge(mm->model, (hylo_mode)mode, x1, x2);
	planar = (mode == HYLO_MODE_GROUND || mode == HYLO_MODE_MARINE) &&
		 hylo_envelope_args((hylo_mode)mode, x1, x2, args);
	flight_turn = mode == HYLO_MODE_FLIGHT && hylo_envelope_flight_turn(x1, x2, &args[1]);
	dist = hylo_edge_distance((hylo_mode)mode, x1, x2);
	floor_cost = hylo_svr_cost_floor(mm->model, dist);
	n_outside = trained_region_notes(mm->model, (hylo_mode)mode, x1, x2, dist, outside);
	if (mm->feasibility)
		feas = hylo_svr_predict(mm->feasibility, f);
	if (json) {
		printf("{\"robot\":\"%s\",\"mode\":\"%s\",\"predicted_cost_j\":%.17g,"
		       "\"planner_cost_j\":%.17g,\"envelope_j\":", robot, mode_name, cost,
		       cost < floor_cost ? floor_cost : cost);
		if (envelope > 0)
			printf("%.17g", envelope);
		else
			printf("null");
		printf(",\"envelope_turn_rad\":");
		if (planar || flight_turn)
			printf("%.17g", args[1]);
		else
			printf("null");
		printf(",\"distance_m\":%.17g,\"feasibility\":", dist);
		if (mm->feasibility)
			printf("{\"decision\":%.17g,\"feasible\":%s}", feas, feas >= 0 ? "true" : "false");
		else
			printf("null");
		printf(",\"beyond_training_range\":%s,\"outside_region\":[",
		       n_outside > 0 ? "true" : "false");
		for (i = 0; i < n_outside; i++)
			printf("%s\"%s\"", i ? "," : "", outside[i]);
		printf("]}\n");
		return 0;
	}
	printf("%s %s: predicted cost %.6g J", robot, mode_name, cost);
	if (cost < floor_cost)
		printf(" (the planner raises it to the floor %.6g J)", floor_cost);
	printf("\n");
	if (envelope > 0 && planar)
		printf("envelope: %.6g J (the least cost over every heading with a turn of %.4g rad, at "
		       "this distance and these speeds)\n", envelope, args[1]);
	else if (envelope > 0 && flight_turn)
		printf("envelope: %.6g J (the larger of the least cost over every velocity direction at "
		       "this distance, climb and these speeds, and over every climb with a flight turn "
		       "of %.4g rad)\n", envelope, args[1]);
	else if (envelope > 0)
		printf("envelope: %.6g J (the least cost over every heading at this distance and these "
		       "speeds)\n", envelope);
	else
		printf("envelope: none for this edge\n");
	if (mm->feasibility)
		printf("feasibility: %s (decision %.4g)\n", feas >= 0 ? "feasible" : "infeasible", feas);
	else
		printf("feasibility: no classifier in this model\n");
	for (i = 0; i < n_outside; i++)
		printf("note: %s\n", outside[i]);
	return 0;
}
