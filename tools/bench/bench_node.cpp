// Message-to-plan latency of the planner node: the goal_t is published, the
// node decodes it, plans, encodes and publishes the plan_t, and the client
// decodes it. Over memq:// (node in-process) and over UDP multicast between
// processes inside a network namespace this benchmark creates (skipped where
// that is impossible), next to the library call alone on the same request.
// Scene: tests/node/synthetic.yaml (robot "synthetic", the 2,000-SV model);
// the map is sent once, so every goal reuses the roadmap as on a robot.
// Writes a table to stdout and JSON rows to argv[1].
//   bench_node RESULTS.json
//   bench_node --udp-client URL OUT.txt   (internal: the client side in the namespace)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include <lcm/lcm.h>

#include "hylo_msg.h"
#include "node/node.h"
#include "node/registry.h"
#include "tools/bench/results.hpp"
#include "tools/scene/planner_view.hpp"
#include "tools/scene/scene.hpp"

namespace {

using Clock = std::chrono::steady_clock;
constexpr int kRuns = 60;
const char *kScene = "tests/node/synthetic.yaml";

struct Stats {
	double median, p99;
};

Stats stats(std::vector<double> v)
{
	std::sort(v.begin(), v.end());
	size_t n = v.size();
	return {n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]),
		v[std::min(n - 1, static_cast<size_t>(0.99 * static_cast<double>(n)))]};
}

// The scene's map and goal messages; they point into sc and request.
struct Messages {
	hylo::scene::Scene sc;
	hylo_map_view view;
	hylo_goal request;
	hylo_map_t map;
	hylo_goal_t goal;
};

void make_messages(Messages &m)
{
	m.sc = hylo::scene::load(kScene);
	m.view = map_view(m.sc);
	hylo_msg_map(&m.view, &m.map);
	m.request = goal_of(m.sc);
	m.request.map_id = m.sc.map_id;
	hylo_msg_goal(&m.request, &m.goal);
}

// Varies the start between requests so no two are identical.
void vary(hylo_goal_t &g, int k)
{
	g.request_id = 1000 + k;
	g.start[1] = 2.0 + 0.1 * (k % 20);
}

struct Client {
	lcm_t *lcm;
	int64_t waiting_for = -1;
	bool got = false;
	int status = -1;
};

void on_plan(const lcm_recv_buf_t *, const char *, const hylo_plan_t *msg, void *user)
{
	auto *c = static_cast<Client *>(user);
	if (msg->request_id == c->waiting_for) {
		c->got = true;
		c->status = msg->status;
	}
}

// Round trips over lcm (the node is served by serve(), in-process, or by
// another process when serve is null).
std::vector<double> round_trips(lcm_t *lcm, Messages &m, void (*serve)(lcm_t *))
{
	Client c{lcm};
	hylo_plan_t_subscription_t *sub = hylo_plan_t_subscribe(lcm, "HYLO_PLAN", on_plan, &c);
	hylo_map_t_publish(lcm, "HYLO_MAP", &m.map);
	if (serve)
		serve(lcm);
	std::vector<double> ms;
	for (int k = -3; k < kRuns; k++) {
		vary(m.goal, k + 3);
		c.waiting_for = m.goal.request_id;
		c.got = false;
		auto t0 = Clock::now();
		hylo_goal_t_publish(lcm, "HYLO_GOAL", &m.goal);
		while (!c.got) {
			if (serve)
				serve(lcm);
			else if (lcm_handle_timeout(lcm, 5000) <= 0)
				break;
		}
		double dt = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
		if (!c.got || c.status != HYLO_PLAN_T_STATUS_OK) {
			std::fprintf(stderr, "bench_node: request %lld not answered with a plan\n",
				     static_cast<long long>(m.goal.request_id));
			std::exit(1);
		}
		if (k >= 0)   // the first three warm up (map ingestion, roadmap)
			ms.push_back(dt);
	}
	hylo_plan_t_unsubscribe(lcm, sub);
	return ms;
}

hylo_node g_node;   // static: its pending-map slots hold 2 x HYLO_MAX_CELLS cells

// Admission, then the node's work, as hylo-planner --sync does.
void serve_memq(lcm_t *lcm)
{
	bool more = true;
	while (more) {
		while (lcm_handle_timeout(lcm, 0) > 0) {
		}
		more = false;
		while (hylo_node_step(&g_node) >= 0)
			more = true;
	}
}

int udp_client(const char *url, const char *out)
{
	Messages m;
	make_messages(m);
	lcm_t *lcm = lcm_create(url);
	if (!lcm)
		return 1;
	Stats s = stats(round_trips(lcm, m, nullptr));
	std::ofstream(out) << s.median << " " << s.p99 << "\n";
	lcm_destroy(lcm);
	return 0;
}

}  // namespace

int main(int argc, char **argv)
{
	if (argc == 4 && std::strcmp(argv[1], "--udp-client") == 0)
		return udp_client(argv[2], argv[3]);
	if (argc != 2 || argv[1][0] == '-') {  // --help is not a file name
		std::fprintf(stderr, "usage: %s RESULTS.json\n", argv[0]);
		return 2;
	}
	Messages m;
	make_messages(m);

	// The library call alone, on the same requests.
	static hylo_robot robots[HYLO_MAX_ROBOTS];
	hylo_reason reason;
	hylo_planner_config cfg{};
	cfg.robots = robots;
	cfg.n_robots = hylo_registry_robots(robots, HYLO_MAX_ROBOTS, &reason);
	size_t size = hylo_planner_size(&cfg);
	auto *pl = static_cast<hylo_planner *>(std::malloc(size));
	auto *plan = static_cast<hylo_plan *>(std::malloc(sizeof(hylo_plan)));
	auto *buf = static_cast<hylo_plan_msg_buf *>(std::malloc(sizeof(hylo_plan_msg_buf)));
	if (!pl || !plan || !buf || hylo_planner_init(pl, size, &cfg) != HYLO_OK)
		return 1;
	hylo_map_view view;
	hylo_msg_map_view(&m.map, &view);
	hylo_planner_set_map(pl, &view);
	std::vector<double> lib;
	for (int k = -3; k < kRuns; k++) {
		hylo_goal g;
		vary(m.goal, k + 3);
		hylo_msg_goal_view(&m.goal, &g);
		auto t0 = Clock::now();
		hylo_planner_plan(pl, &g, plan);
		if (k >= 0)
			lib.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
	}
	Stats s_lib = stats(lib);

	// memq: the node in-process, on the same LCM instance as the client.
	lcm_t *memq = lcm_create("memq://");
	if (!memq || hylo_node_init(&g_node, memq, memq, "", pl, plan, buf, nullptr, 0) != 0)
		return 1;
	Stats s_memq = stats(round_trips(memq, m, serve_memq));
	hylo_node_destroy(&g_node);
	lcm_destroy(memq);

	// UDP: node and client as separate processes in a private namespace.
	std::string self = argv[0];
	std::string bin = self.substr(0, self.rfind('/'));
	std::string out = std::string(argv[1]) + ".udp";
	std::string cmd =
		"unshare --net sh -c 'ip link set lo up && ip route add 224.0.0.0/4 dev lo && "
		"URL=\"udpm://239.255.76.67:7667?ttl=0\"; "
		"build/test/node/hylo-planner-synthetic --lcm-url \"$URL\" 2>/dev/null & n=$!; sleep 0.5; " +
		self + " --udp-client \"$URL\" " + out + "; r=$?; kill $n; wait $n; exit $r' 2>/dev/null";
	bool udp = std::system(cmd.c_str()) == 0;
	Stats s_udp{0, 0};
	if (udp) {
		std::ifstream f(out);
		udp = static_cast<bool>(f >> s_udp.median >> s_udp.p99);
	}
	std::remove(out.c_str());

	std::printf("message-to-plan latency, %s (%d requests after 3 warm-ups, roadmap reused)\n",
		    kScene, kRuns);
	std::printf("  %-34s %10s %10s\n", "", "median ms", "p99 ms");
	std::printf("  %-34s %10.3f %10.3f\n", "library call alone", s_lib.median, s_lib.p99);
	std::printf("  %-34s %10.3f %10.3f\n", "node over memq://", s_memq.median, s_memq.p99);
	if (udp)
		std::printf("  %-34s %10.3f %10.3f\n", "node over UDP (network namespace)",
			    s_udp.median, s_udp.p99);
	else
		std::printf("  %-34s  skipped: no network namespace here\n", "node over UDP");

	// ratio: the library call over the node; below 1, the node's overhead.
	const std::string call = "library call alone";
	std::vector<BenchRow> rows = {
		bench_compared("node_latency_memq_median_ms", s_memq.median, "ms", call, s_lib.median),
		bench_compared("node_latency_memq_p99_ms", s_memq.p99, "ms", call, s_lib.p99),
	};
	if (udp) {
		rows.push_back(bench_compared("node_latency_udp_median_ms", s_udp.median, "ms", call, s_lib.median));
		rows.push_back(bench_compared("node_latency_udp_p99_ms", s_udp.p99, "ms", call, s_lib.p99));
	}
	return write_bench_results(argv[1], rows) ? 0 : 1;
}
