// goal_burst: a load client for the planner node over a live LCM provider
// (tests/node/test_load.sh runs it inside a network namespace). Publishes a
// scene's map, then
//   goals: optionally one slow goal (--slow: Dijkstra on a fine roadmap, so
//          that a plan is in progress), then N goals at a rate (0: as fast as
//          it can publish) from K requesters, and waits for the answers;
//   maps:  (--maps N) N maps of HYLO_MAX_CELLS cells, each waiting for its
//          HYLO_STATUS report.
// Prints one JSON object: sent, answered (distinct request ids), duplicate
// and missing answers, answers by status, the node's own counters (its last
// node_status_t), and the latency of the last answer after the last goal
// was sent. Exit 0 when every goal got exactly one answer (or every map was
// taken), 1 otherwise, 2 on usage errors.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include <lcm/lcm.h>

#include "hylo_goal_t.h"
#include "hylo_map_t.h"
#include "hylo_node_status_t.h"
#include "hylo_msg.h"
#include "hylo_plan_t.h"
#include "tools/scene/planner_view.hpp"
#include "tools/scene/scene.hpp"

namespace {

using Clock = std::chrono::steady_clock;

struct Client {
	std::map<int64_t, int> answers;          // request id -> number of answers
	std::map<int, int> by_status;
	hylo_node_status_t last{};               // counters of the last status seen
	bool have_status = false;
	int64_t map_event_id = 0;
	int map_event_status = -1;
	int maps_taken = 0;
	Clock::time_point last_answer;
};

void on_plan(const lcm_recv_buf_t *, const char *, const hylo_plan_t *msg, void *user)
{
	auto *c = static_cast<Client *>(user);
	c->answers[msg->request_id]++;
	c->by_status[msg->status]++;
	c->last_answer = Clock::now();
}

void on_status(const lcm_recv_buf_t *, const char *, const hylo_node_status_t *msg, void *user)
{
	auto *c = static_cast<Client *>(user);
	c->last = *msg;
	c->last.reason = nullptr;
	c->have_status = true;
	if (msg->event == HYLO_NODE_STATUS_T_EVENT_MAP) {
		c->map_event_id = msg->map_id;
		c->map_event_status = msg->map_status;
		if (msg->map_status == HYLO_PLAN_T_STATUS_OK)
			c->maps_taken++;
	}
}

void pump(lcm_t *lcm, int ms)
{
	while (lcm_handle_timeout(lcm, ms) > 0)
		ms = 0;
}

const char *status_name(int s)
{
	static const char *const n[] = {"ok", "no_map", "no_path", "bad_request", "over_capacity",
					"budget_exhausted", "map_replaced", "no_model", "not_proven",
					"superseded", "unknown_map", "queue_full"};
	return s >= 0 && s < 12 ? n[s] : "other";
}

// Waits until pred() or timeout_s; handles messages meanwhile.
template <class P> bool wait_for(lcm_t *lcm, double timeout_s, P pred)
{
	auto end = Clock::now() + std::chrono::duration<double>(timeout_s);
	while (!pred()) {
		if (Clock::now() > end)
			return false;
		pump(lcm, 50);
	}
	return true;
}

}  // namespace

int main(int argc, char **argv)
{
	std::string url = "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304";
	std::string scene_path = "tests/node/synthetic.yaml";
	int n_goals = 100, requesters = 1, n_maps = 0;
	double rate = 0, timeout_s = 60;
	bool slow = false;

	for (int i = 1; i < argc; i++) {
		std::string a = argv[i];
		auto next = [&]() -> const char * {
			if (i + 1 >= argc) {
				std::fprintf(stderr, "goal_burst: %s needs a value\n", a.c_str());
				std::exit(2);
			}
			return argv[++i];
		};
		if (a == "--lcm-url") url = next();
		else if (a == "--scene") scene_path = next();
		else if (a == "--goals") n_goals = std::atoi(next());
		else if (a == "--rate") rate = std::atof(next());
		else if (a == "--requesters") requesters = std::atoi(next());
		else if (a == "--maps") n_maps = std::atoi(next());
		else if (a == "--timeout") timeout_s = std::atof(next());
		else if (a == "--slow") slow = true;
		else {
			std::fprintf(stderr, "goal_burst: unknown option %s\n", a.c_str());
			return 2;
		}
	}
	hylo::scene::Scene sc;
	try {
		sc = hylo::scene::load(scene_path);
	} catch (const std::exception &e) {
		std::fprintf(stderr, "goal_burst: %s\n", e.what());
		return 2;
	}
	lcm_t *lcm = lcm_create(url.c_str());
	if (!lcm) {
		std::fprintf(stderr, "goal_burst: cannot open %s\n", url.c_str());
		return 2;
	}
	Client c;
	auto *ps = hylo_plan_t_subscribe(lcm, "HYLO_PLAN", on_plan, &c);
	auto *ss = hylo_node_status_t_subscribe(lcm, "HYLO_STATUS", on_status, &c);
	hylo_plan_t_subscription_set_queue_capacity(ps, 0);       // a test client: keep all
	hylo_node_status_t_subscription_set_queue_capacity(ss, 0);

	const hylo_map_view view = map_view(sc);
	hylo_map_t map;
	hylo_msg_map(&view, &map);

	if (n_maps > 0) {
		// Maps at capacity: 512 x 512 cells of the scene's first cell's class.
		const int side = 512;
		std::vector<int8_t> terrain(side * side, HYLO_MAP_T_TERRAIN_GROUND);
		std::vector<float> height(side * side, 0.0f);
		for (int k = 0; k < side * side; k++)
			height[k] = 0.001f * static_cast<float>(k % 97);
		map.nx = map.ny = side;
		map.n_cells = side * side;
		map.terrain = terrain.data();
		map.height_m = height.data();
		int taken = 0, lost = 0;
		for (int k = 0; k < n_maps; k++) {
			map.map_id = 5000 + k;
			hylo_map_t_publish(lcm, "HYLO_MAP", &map);
			bool got = wait_for(lcm, 5, [&] { return c.map_event_id == map.map_id; });
			if (got && c.map_event_status == HYLO_PLAN_T_STATUS_OK)
				taken++;
			else
				lost++;
		}
		std::printf("{\"maps_sent\":%d,\"maps_taken\":%d,\"maps_lost_or_refused\":%d,"
			    "\"map_bytes\":%d}\n", n_maps, taken, lost,
			    hylo_map_t_encoded_size(&map));
		lcm_destroy(lcm);
		return taken == n_maps ? 0 : 1;
	}

	hylo_map_t_publish(lcm, "HYLO_MAP", &map);
	if (!wait_for(lcm, 10, [&] { return c.map_event_id == sc.map_id; })) {
		std::fprintf(stderr, "goal_burst: the node did not report map %lld\n",
			     static_cast<long long>(sc.map_id));
		return 1;
	}
	const auto &g = sc.goal;
	hylo_goal request = goal_of(sc);
	request.map_id = sc.map_id;
	hylo_goal_t goal;
	hylo_msg_goal(&request, &goal);

	int sent = 0;
	if (slow) {
		// A new roadmap 25 times denser, searched by Dijkstra: a plan in progress.
		hylo_goal dense = request;
		dense.request_id = 1;
		dense.algorithm = HYLO_DIJKSTRA;
		dense.sampling.spacing = g.spacing_m / 2;
		dense.sampling.guard_spacing = g.guard_spacing_m / 2;
		dense.sampling.connect_radius = g.connect_radius_m / 1.4;
		dense.sampling.seed = 12345;
		hylo_goal_t s;
		hylo_msg_goal(&dense, &s);
		s.requester_id = 999999;
		hylo_goal_t_publish(lcm, "HYLO_GOAL", &s);
		sent++;
		pump(lcm, 20);   // the node has taken it
	}
	auto t0 = Clock::now();
	for (int k = 0; k < n_goals; k++) {
		goal.request_id = 1000 + k;
		goal.requester_id = 1 + k % (requesters > 0 ? requesters : 1);
		goal.start[1] = g.start.x[1] + 0.05 * (k % 20);
		hylo_goal_t_publish(lcm, "HYLO_GOAL", &goal);
		sent++;
		if (rate > 0) {
			auto due = t0 + std::chrono::duration<double>((k + 1) / rate);
			while (Clock::now() < due)
				pump(lcm, 1);
		} else if (k % 64 == 63) {
			pump(lcm, 0);
		}
	}
	auto t_sent = Clock::now();
	double send_s = std::chrono::duration<double>(t_sent - t0).count();
	bool all = wait_for(lcm, timeout_s, [&] { return static_cast<int>(c.answers.size()) >= sent; });
	// The node's counters once it has answered everything it received.
	wait_for(lcm, 3, [&] {
		return c.have_status && c.last.goals_answered == c.last.goals_received &&
		       c.last.goals_received >= static_cast<int64_t>(c.answers.size());
	});
	pump(lcm, 200);
	int duplicates = 0;
	for (const auto &kv : c.answers)
		duplicates += kv.second - 1;
	double last_ms = std::chrono::duration<double, std::milli>(c.last_answer - t_sent).count();
	std::printf("{\"sent\":%d,\"answered\":%zu,\"duplicates\":%d,\"missing\":%d,"
		    "\"send_s\":%.4f,\"send_rate_per_s\":%.0f,\"last_answer_ms\":%.1f,"
		    "\"node_received\":%lld,\"node_answered\":%lld,\"node_planned\":%lld,"
		    "\"node_superseded\":%lld,\"node_refused\":%lld,\"by_status\":{",
		    sent, c.answers.size(), duplicates, sent - static_cast<int>(c.answers.size()),
		    send_s, n_goals / (send_s > 0 ? send_s : 1e-9), last_ms,
		    static_cast<long long>(c.last.goals_received),
		    static_cast<long long>(c.last.goals_answered),
		    static_cast<long long>(c.last.goals_planned),
		    static_cast<long long>(c.last.goals_superseded),
		    static_cast<long long>(c.last.goals_refused));
	bool first = true;
	for (const auto &kv : c.by_status) {
		std::printf("%s\"%s\":%d", first ? "" : ",", status_name(kv.first), kv.second);
		first = false;
	}
	std::printf("}}\n");
	lcm_destroy(lcm);
	return all && duplicates == 0 ? 0 : 1;
}
