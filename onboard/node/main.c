/*
 * hylo-planner: the planner node. See --help. Exit codes: 0 on a clean stop
 * (SIGINT/SIGTERM, --once answered, end of an input log), 1 on a start-up
 * failure (LCM URL, robots), 2 on a usage error.
 */
#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <sys/socket.h>
#include <unistd.h>

#include "node/node.h"
#include "node/registry.h"

/* The UDP receive buffer the node asks for (LCM URL option recv_buf_size)
 * unless the URL names one: a map at capacity (HYLO_MAX_CELLS cells, 1.3 MB
 * in about 21 datagrams) and a burst of a few thousand goals fit. */
#ifndef HYLO_NODE_RECV_BUF
#define HYLO_NODE_RECV_BUF 4194304
#endif
#define DEFAULT_URL "udpm://239.255.76.67:7667?ttl=0"

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
		"  --recv-buf BYTES      UDP receive buffer asked for on a udpm:// URL that does\n"
		"                        not set recv_buf_size (default: %d)\n"
		"  --sync                plan in the receiving thread, every goal in order\n"
		"                        (the default for file:// logs); otherwise goals wait\n"
		"                        in the queue of docs/node.md while a plan runs\n"
		"  --once                answer one goal, then exit\n"
		"  --margin M            clearance [m] every plan keeps beyond the robot's body\n"
		"                        from obstacles, walls, terrain and the map's edge\n"
		"                        (finite, >= 0; default %g)\n"
		"  --verbose             also log maps and start-up details\n"
		"  --list-robots         print the robots, their body radii and the models\n"
		"                        compiled in, then exit\n"
		"  --help                this text\n"
		"\n"
		"Exit codes: 0 clean stop (signal, --once, end of an input log),\n"
		"1 start-up failure, 2 usage error.\n", HYLO_NODE_RECV_BUF, HYLO_DEFAULT_MARGIN_M);
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
		printf(", body radius %.6g m%s\n", robots[k].body_radius_m,
		       hylo_registry_body_of(robots[k].name) ? "" : " (no robot file)");
	}
}

/* url with recv_buf_size=bytes added when it is udpm:// without one. */
static const char *with_recv_buf(const char *url, long bytes, char *out, size_t n)
{
	int k;

	if (strncmp(url, "udpm://", 7) != 0 || strstr(url, "recv_buf_size=") || bytes <= 0)
		return url;
	k = snprintf(out, n, "%s%crecv_buf_size=%ld", url, strchr(url, '?') ? '&' : '?', bytes);
	return k > 0 && (size_t)k < n ? out : url;
}

/* The receive buffer the kernel grants a UDP socket asking for bytes (it
 * caps requests at net.core.rmem_max): the node's socket gets the same. */
static long granted_recv_buf(long bytes)
{
	int fd = socket(AF_INET, SOCK_DGRAM, 0), v = (int)bytes;
	socklen_t len = sizeof v;

	if (fd < 0)
		return -1;
	if (setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &v, sizeof v) != 0 ||
	    getsockopt(fd, SOL_SOCKET, SO_RCVBUF, &v, &len) != 0)
		v = -2;
	close(fd);
	return v < 0 ? -1 : v / 2;   /* Linux reports twice the request */
}

static void *worker(void *arg)
{
	hylo_node *node = arg;

	int w;

	while ((w = hylo_node_wait(node, 200)) >= 0)
		if (w > 0)
			hylo_node_step(node);
	return NULL;
}

int main(int argc, char **argv)
{
	const char *url = NULL, *out_url = NULL, *prefix = "";
	int once = 0, verbose = 0, list = 0, sync = 0, threaded, i, rc = 0;
	long recv_buf = HYLO_NODE_RECV_BUF;
	double margin = HYLO_DEFAULT_MARGIN_M;
	static char url_buf[1024];
	static hylo_robot robots[HYLO_MAX_ROBOTS];
	hylo_planner_config cfg;
	hylo_reason reason;
	hylo_planner *planner;
	size_t workspace;
	hylo_plan *plan;
	hylo_plan_msg_buf *buf;
	hylo_node *node;
	lcm_t *in, *out;
	struct sigaction sa;
	uint32_t n_robots;
	hylo_status st;
	pthread_t thread;
	double last_status;

	for (i = 1; i < argc; i++) {
		const char *a = argv[i];

		if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
			usage(stdout);
			return 0;
		} else if (strcmp(a, "--once") == 0) {
			once = 1;
		} else if (strcmp(a, "--sync") == 0) {
			sync = 1;
		} else if (strcmp(a, "--verbose") == 0) {
			verbose = 1;
		} else if (strcmp(a, "--list-robots") == 0) {
			list = 1;
		} else if (strcmp(a, "--recv-buf") == 0 && i + 1 < argc) {
			char *end;

			recv_buf = strtol(argv[++i], &end, 10);
			if (*end || recv_buf < 0 || recv_buf > 1L << 30) {
				fprintf(stderr, "hylo-planner: --recv-buf wants bytes in [0, 2^30]\n");
				return 2;
			}
		} else if (strcmp(a, "--margin") == 0 && i + 1 < argc) {
			char *end;

			margin = strtod(argv[++i], &end);
			if (end == argv[i] || *end || !isfinite(margin) || margin < 0) {
				fprintf(stderr, "hylo-planner: --margin '%s': a clearance in metres, finite and >= 0\n",
					argv[i]);
				return 2;
			}
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
	if (!url)
		url = getenv("LCM_DEFAULT_URL");
	if (!url || !*url)
		url = DEFAULT_URL;
	if (is_file_url(url) && !out_url) {
		fprintf(stderr, "hylo-planner: reading a log (%s): give --out-url for the plans\n", url);
		return 2;
	}
	threaded = !sync && !is_file_url(url);
	url = with_recv_buf(url, recv_buf, url_buf, sizeof url_buf);
	if (url == url_buf) {
		long got = granted_recv_buf(recv_buf);

		if (got >= 0 && got < recv_buf)
			fprintf(stderr, "hylo-planner: the kernel caps the UDP receive buffer at %ld "
				"bytes, not the %ld asked for: large maps and goal bursts may be lost. "
				"Raise net.core.rmem_max (sysctl -w net.core.rmem_max=%ld)\n",
				got, recv_buf, recv_buf);
	}

	/* All memory the node will ever use, allocated once. */
	memset(&cfg, 0, sizeof cfg);
	cfg.robots = robots;
	cfg.n_robots = n_robots;
	cfg.clock = clock_ms;
	cfg.margin_m = margin > 0 ? margin : HYLO_NO_MARGIN;
	workspace = hylo_planner_size(&cfg);
	planner = malloc(workspace);
	plan = malloc(sizeof *plan);
	buf = malloc(sizeof *buf);
	node = malloc(sizeof *node);
	if (!planner || !plan || !buf || !node) {
		fprintf(stderr, "hylo-planner: cannot allocate the %zu-byte workspace\n",
			workspace + sizeof *plan + sizeof *buf + sizeof *node);
		return 1;
	}
	st = hylo_planner_init(planner, workspace, &cfg);
	if (st != HYLO_OK) {
		fprintf(stderr, "hylo-planner: %s\n", hylo_planner_reason(planner));
		return 1;
	}

	in = lcm_create(url);
	if (!in) {
		fprintf(stderr, "hylo-planner: cannot open LCM provider '%s'\n", url);
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
	if (hylo_node_init(node, in, out, prefix, planner, plan, buf, stderr, verbose) != 0) {
		rc = 1;
		goto done;
	}
	if (url == url_buf) {
		long got = granted_recv_buf(recv_buf);

		node->recv_buf_bytes = (int32_t)(got < 0 ? 0 : got);
	}
	node->goal_limit = once ? 1 : 0;
	if (verbose) {
		fprintf(stderr, "hylo-planner: listening on %s (%sHYLO_MAP, %sHYLO_GOAL), %s; "
			"margin %g m; workspace %zu bytes, node %zu bytes\n", url, prefix, prefix,
			threaded ? "planning in a second thread" : "planning in order", margin,
			workspace, sizeof *node);
		list_robots(robots, n_robots);
	}

	memset(&sa, 0, sizeof sa);
	sa.sa_handler = on_signal;
	sigemptyset(&sa.sa_mask);
	sigaction(SIGINT, &sa, NULL);
	sigaction(SIGTERM, &sa, NULL);

	if (threaded && pthread_create(&thread, NULL, worker, node) != 0) {
		fprintf(stderr, "hylo-planner: cannot start the planning thread\n");
		hylo_node_destroy(node);
		rc = 1;
		goto done;
	}
	last_status = clock_ms(NULL);
	for (;;) {
		uint64_t answered;
		int r;

		hylo_node_counts(node, NULL, &answered);
		if (stop_requested || (once && answered > 0))
			break;
		r = lcm_handle_timeout(in, 100);
		if (r < 0) {
			/* A file:// log has ended; anything else is an error. */
			if (is_file_url(url))
				break;
			if (errno == EINTR)
				continue;
			fprintf(stderr, "hylo-planner: LCM receive failed\n");
			rc = 1;
			break;
		}
		if (!threaded)
			while (hylo_node_step(node) >= 0)
				;
		if (clock_ms(NULL) - last_status >= 1000) {
			hylo_node_publish_status(node, HYLO_NODE_STATUS_T_EVENT_PERIODIC);
			last_status = clock_ms(NULL);
		}
	}
	if (threaded) {
		hylo_node_stop(node);
		pthread_join(thread, NULL);
	}
	hylo_node_publish_status(node, HYLO_NODE_STATUS_T_EVENT_STOP);
	if (verbose)
		fprintf(stderr, "hylo-planner: stopping after %llu goals (%llu planned, %llu "
			"superseded, %llu refused), %llu maps\n",
			(unsigned long long)node->n_goals, (unsigned long long)node->n_planned,
			(unsigned long long)node->n_superseded, (unsigned long long)node->n_refused,
			(unsigned long long)node->n_maps);
	hylo_node_destroy(node);
done:
	if (out != in)
		lcm_destroy(out);
	lcm_destroy(in);
	free(node);
	free(buf);
	free(plan);
	free(planner);
	return rc;
}
