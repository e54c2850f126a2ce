/*
 * hylo-planner: the planner node. See --help. Exit codes: 0 on a clean stop
 * (SIGINT/SIGTERM, --once answered, end of an input log), 1 on a start-up
 * failure (LCM URL, robots), 2 on a usage error.
 */
#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "node/node.h"
#include "node/registry.h"

static volatile sig_atomic_t stop_requested;

static void on_signal(int sig)
{
	(void)sig;
	stop_requested = 1;
}

static double clock_ms(void *ctx)
{
	struct timespec t;

	(void)ctx;
	clock_gettime(CLOCK_MONOTONIC, &t);
	return 1e3 * (double)t.tv_sec + 1e-6 * (double)t.tv_nsec;
}

static void usage(FILE *f)
{
	fprintf(f,
		"usage: hylo-planner [options]\n"
		"Plans energy-optimal multi-modal paths: subscribes <prefix>HYLO_MAP and\n"
		"<prefix>HYLO_GOAL, answers every goal with one <prefix>HYLO_PLAN.\n"
		"\n"
		"  --lcm-url URL         LCM provider to listen on (default: $LCM_DEFAULT_URL,\n"
		"                        else LCM's default udpm://239.255.76.67:7667?ttl=0)\n"
		"  --out-url URL         LCM provider to publish plans on (default: the same\n"
		"                        as --lcm-url; needed when reading a file:// log)\n"
		"  --channel-prefix P    prefix of the channel names (default: none)\n"
		"  --once                answer one goal, then exit\n"
		"  --verbose             also log maps and start-up details\n"
		"  --list-robots         print the robots and models compiled in, then exit\n"
		"  --help                this text\n"
		"\n"
		"Exit codes: 0 clean stop (signal, --once, end of an input log),\n"
		"1 start-up failure, 2 usage error.\n");
}

static int is_file_url(const char *url)
{
	return url && strncmp(url, "file://", 7) == 0;
}

static void list_robots(const hylo_robot *robots, uint32_t n)
{
	uint32_t k, m;

	for (k = 0; k < n; k++) {
		printf("%s:", robots[k].name);
		for (m = 0; m < robots[k].n_modes; m++)
			printf(" %s (%s)", hylo_mode_str(robots[k].modes[m].mode),
			       robots[k].modes[m].model ? "model" : "no model");
		if (robots[k].switch_cost[0] > 0 || robots[k].switch_cost[1] > 0)
			printf(", switch costs %.6g J / %.6g J", robots[k].switch_cost[0],
			       robots[k].switch_cost[1]);
		printf("\n");
	}
}

int main(int argc, char **argv)
{
	const char *url = NULL, *out_url = NULL, *prefix = "";
	int once = 0, verbose = 0, list = 0, i, rc = 0;
	static hylo_robot robots[HYLO_MAX_ROBOTS];
	hylo_planner_config cfg;
	hylo_reason reason;
	hylo_planner *planner;
	size_t workspace;
	hylo_plan *plan;
	hylo_plan_msg_buf *buf;
	hylo_node node;
	lcm_t *in, *out;
	struct sigaction sa;
	uint32_t n_robots;
	hylo_status st;

	for (i = 1; i < argc; i++) {
		const char *a = argv[i];

		if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
			usage(stdout);
			return 0;
		} else if (strcmp(a, "--once") == 0) {
			once = 1;
		} else if (strcmp(a, "--verbose") == 0) {
			verbose = 1;
		} else if (strcmp(a, "--list-robots") == 0) {
			list = 1;
		} else if ((strcmp(a, "--lcm-url") == 0 || strcmp(a, "--out-url") == 0 ||
			    strcmp(a, "--channel-prefix") == 0) && i + 1 < argc) {
			const char **dst = a[2] == 'l' ? &url : a[2] == 'o' ? &out_url : &prefix;

			*dst = argv[++i];
		} else {
			fprintf(stderr, "hylo-planner: unknown or incomplete option '%s' (see --help)\n", a);
			return 2;
		}
	}

	n_robots = hylo_registry_robots(robots, HYLO_MAX_ROBOTS, &reason);
	if (n_robots == 0) {
		fprintf(stderr, "hylo-planner: %s\n", reason.text);
		return 1;
	}
	if (list) {
		list_robots(robots, n_robots);
		return 0;
	}
	if (is_file_url(url ? url : getenv("LCM_DEFAULT_URL")) && !out_url) {
		fprintf(stderr, "hylo-planner: reading a log (%s): give --out-url for the plans\n",
			url ? url : getenv("LCM_DEFAULT_URL"));
		return 2;
	}

	/* All memory the planner will ever use, allocated once. */
	memset(&cfg, 0, sizeof cfg);
	cfg.robots = robots;
	cfg.n_robots = n_robots;
	cfg.clock = clock_ms;
	workspace = hylo_planner_size(&cfg);
	planner = malloc(workspace);
	plan = malloc(sizeof *plan);
	buf = malloc(sizeof *buf);
	if (!planner || !plan || !buf) {
		fprintf(stderr, "hylo-planner: cannot allocate the %zu-byte workspace\n",
			workspace + sizeof *plan + sizeof *buf);
		return 1;
	}
	st = hylo_planner_init(planner, workspace, &cfg);
	if (st != HYLO_OK) {
		fprintf(stderr, "hylo-planner: %s\n", hylo_planner_reason(planner));
		return 1;
	}

	in = lcm_create(url);
	if (!in) {
		fprintf(stderr, "hylo-planner: cannot open LCM provider '%s'\n",
			url ? url : "(default)");
		return 1;
	}
	out = in;
	if (out_url) {
		out = lcm_create(out_url);
		if (!out) {
			fprintf(stderr, "hylo-planner: cannot open LCM provider '%s'\n", out_url);
			lcm_destroy(in);
			return 1;
		}
	}
	if (hylo_node_init(&node, in, out, prefix, planner, plan, buf, stderr, verbose) != 0) {
		rc = 1;
		goto done;
	}
	node.goal_limit = once ? 1 : 0;
	if (verbose) {
		fprintf(stderr, "hylo-planner: listening on %sHYLO_MAP, %sHYLO_GOAL; workspace %zu bytes\n",
			prefix, prefix, workspace);
		list_robots(robots, n_robots);
	}

	memset(&sa, 0, sizeof sa);
	sa.sa_handler = on_signal;
	sigemptyset(&sa.sa_mask);
	sigaction(SIGINT, &sa, NULL);
	sigaction(SIGTERM, &sa, NULL);

	while (!stop_requested && !(once && node.n_goals > 0)) {
		int r = lcm_handle_timeout(in, 100);

		if (r < 0) {
			/* A file:// log has ended; anything else is an error. */
			if (is_file_url(url ? url : getenv("LCM_DEFAULT_URL")))
				break;
			if (errno == EINTR)
				continue;
			fprintf(stderr, "hylo-planner: LCM receive failed\n");
			rc = 1;
			break;
		}
	}
	if (verbose)
		fprintf(stderr, "hylo-planner: stopping after %llu goals, %llu maps\n",
			(unsigned long long)node.n_goals, (unsigned long long)node.n_maps);
done:
	if (out != in)
		lcm_destroy(out);
	lcm_destroy(in);
	free(buf);
	free(plan);
	free(planner);
	return rc;
}
