// Plan latency on the committed scenes with the committed models: hylo's
// planner (lazy A*, edge-cost cache) against the algorithm it replaced, run
// here on the same roadmap with the same edge weights: A* with the per-metre
// floor heuristic on positions, every successor of an expanded node
// evaluated (no cache). Rows per scene:
//   first goal on a new map (hylo median of 5 against the reference, 1 run),
//   wall time and the thread's CPU time (other jobs do not inflate it),
//   a second goal nearby (the goal moved by one sampling spacing) and the way back (start
//   and goal swapped) on the same map, after the first (median of 5),
//   the plans' costs (hylo's against the reference's: equal to 1e-9),
//   edges evaluated, and the workspace size.
// Writes a table to stdout and JSON rows to argv[1]; the optional further
// arguments name scene files (default: every scene in scenes/).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <queue>
#include <stdexcept>
#include <string>
#include <vector>

#include <time.h>

#include "hylo/planner.h"
#include "tools/bench/results.hpp"
#include "tools/scene/committed.hpp"
#include "tools/scene/planner_view.hpp"
#include "tools/scene/scene.hpp"

namespace {

using Clock = std::chrono::steady_clock;
using hylo::scene::Scene;

double now_ms(void *)
{
	return std::chrono::duration<double, std::milli>(Clock::now().time_since_epoch()).count();
}

// CPU time of this thread [ms]: what a plan costs the core it runs on, and
// what other jobs on a shared machine do not inflate (an idle machine's wall
// time is the same).
double cpu_ms()
{
	timespec t;
	clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
	return t.tv_sec * 1e3 + t.tv_nsec * 1e-6;
}

double median(std::vector<double> v)
{
	std::sort(v.begin(), v.end());
	size_t n = v.size();
	return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::vector<BenchRow> rows;

using hylo::scene::goal_of;
using hylo::scene::map_view;
using hylo::scene::way_back;

struct Bench {
	hylo::scene::CommittedPlanner committed{now_ms};
	hylo_planner *pl_ = committed.get();
	std::unique_ptr<hylo_plan> plan{new hylo_plan};
	size_t size = committed.size();

	void new_map(const Scene &sc)
	{
		hylo_map_view v = map_view(sc);
		if (hylo_planner_set_map(pl_, &v) != HYLO_OK)
			throw std::runtime_error(sc.path + ": " + hylo_planner_reason(pl_));
	}

	double last_cpu_ms = 0;

	// Plans g; the wall time [ms] (the thread's CPU time in last_cpu_ms).
	double plan_goal(const hylo_goal &g, bool must_find = true)
	{
		auto t0 = Clock::now();
		double c0 = cpu_ms();
		hylo_planner_plan(pl_, &g, plan.get());
		last_cpu_ms = cpu_ms() - c0;
		double ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
		if (must_find && (plan->status != HYLO_OK || plan->outcome != HYLO_FOUND))
			throw std::runtime_error(std::string("no plan: ") + plan->reason.text);
		return ms;
	}
};

// The reference: A* with the floor heuristic on positions (a backward
// Dijkstra over positions, each edge weighted by the mode's per-edge and
// per-metre floors, the switch cost), every successor of an expanded node
// evaluated by hylo_planner_edge_costs. Run after hylo planned the same goal,
// so the roadmap and the start and goal links are in place.
struct Reference {
	double cost = INFINITY, ms = 0, cpu = 0;
	uint64_t evaluated = 0, expansions = 0;
};

double floor_of(const hylo_planner *pl, uint32_t i, uint32_t j)
{
	const hylo_roadmap *rm = &pl->roadmap;
	int k = hylo_robot_mode_index(pl->robot, static_cast<hylo_mode>(rm->pos[i].mode));
	const hylo_mode_model &mm = pl->robot->modes[k];
	double fj = mm.model ? mm.model->cost_floor_j : mm.cost_floor_j;
	double fm = mm.model ? mm.model->cost_floor_per_m : mm.cost_floor_per_m;
	return fj + fm * hylo_roadmap_distance(rm->pos[i].p, rm->pos[j].p);
}

double switch_cost(const hylo_planner *pl, uint32_t i)
{
	return pl->robot->switch_cost[pl->roadmap.pos[i].mode == pl->robot->modes[0].mode ? 0 : 1];
}

Reference run_reference(hylo_planner *pl)
{
	using Item = std::pair<double, uint32_t>;
	const hylo_roadmap *rm = &pl->roadmap;
	uint32_t np = rm->n_positions + 2, start = rm->n_nodes, goal = rm->n_nodes + 1;
	Reference ref;
	auto t0 = Clock::now();
	double c0 = cpu_ms();

	// Position heuristic: backward Dijkstra from the goal position.
	std::vector<double> hp(np, INFINITY);
	std::priority_queue<Item, std::vector<Item>, std::greater<Item>> q;
	hp[pl->goal_pos] = 0;
	q.push({0, pl->goal_pos});
	while (!q.empty()) {
		auto [d, j] = q.top();
		q.pop();
		if (d > hp[j])
			continue;
		std::vector<uint32_t> pred;
		if (j == pl->goal_pos)
			pred.assign(pl->goal_adj, pl->goal_adj + pl->n_goal_adj);
		else if (j < rm->n_positions)
			pred.assign(rm->adjacency + rm->pos[j].adj_begin, rm->adjacency + rm->pos[j].adj_end);
		for (uint32_t i : pred) {
			double nd = d + floor_of(pl, i, j);
			if (nd < hp[i]) {
				hp[i] = nd;
				q.push({nd, i});
			}
		}
		if (j < rm->n_positions && rm->pos[j].twin != HYLO_NO_POSITION) {
			uint32_t t = rm->pos[j].twin;
			double nd = d + switch_cost(pl, t);
			if (nd < hp[t]) {
				hp[t] = nd;
				q.push({nd, t});
			}
		}
	}
	double hs = pl->start_goal_linked ? floor_of(pl, pl->start_pos, pl->goal_pos) : INFINITY;
	for (uint32_t k = 0; k < pl->n_start_adj; k++)
		hs = std::min(hs, floor_of(pl, pl->start_pos, pl->start_adj[k]) + hp[pl->start_adj[k]]);
	hp[pl->start_pos] = hs;

	// Node A*, every successor of an expanded node evaluated.
	uint32_t nn = rm->n_nodes + 2;
	std::vector<double> g(nn, INFINITY);
	std::vector<char> closed(nn, 0);
	std::vector<uint32_t> heads(HYLO_MAX_SUCCESSORS);
	std::vector<double> costs(HYLO_MAX_SUCCESSORS);
	auto h = [&](uint32_t v) { return hp[rm->node_pos[v]]; };
	std::priority_queue<Item, std::vector<Item>, std::greater<Item>> open;
	g[start] = 0;
	open.push({h(start), start});
	while (!open.empty()) {
		auto [f, u] = open.top();
		open.pop();
		if (closed[u] || f > g[u] + h(u))
			continue;
		closed[u] = 1;
		ref.expansions++;
		if (u == goal)
			break;
		uint32_t n = 0, m = 0;
		if (hylo_planner_successors(pl, u, heads.data(), &n) != HYLO_OK)
			throw std::runtime_error(hylo_planner_reason(pl));
		for (uint32_t k = 0; k < n; k++)
			if (!closed[heads[k]] && std::isfinite(h(heads[k])))
				heads[m++] = heads[k];
		if (hylo_planner_edge_costs(pl, u, heads.data(), m, costs.data()) != HYLO_OK)
			throw std::runtime_error(hylo_planner_reason(pl));
		ref.evaluated += m;
		for (uint32_t k = 0; k < m; k++) {
			uint32_t v = heads[k];
			if (std::isfinite(costs[k]) && g[u] + costs[k] < g[v]) {
				g[v] = g[u] + costs[k];
				open.push({g[v] + h(v), v});
			}
		}
	}
	ref.ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
	ref.cpu = cpu_ms() - c0;
	ref.cost = g[goal];
	return ref;
}

// A goal near the scene's: moved by one sampling spacing (2 m on the robots'
// scenes; the first direction the planner accepts).
hylo_goal nearby_goal(Bench &b, const hylo_goal &g)
{
	static const double offsets[][2] = {{0, 1}, {0, -1}, {1, 0}, {-1, 0}, {1, 1}, {-1, -1}, {1, -1}, {-1, 1}};
	for (const auto &o : offsets) {
		hylo_goal n = g;
		n.goal[0] += o[0] * g.sampling.spacing;
		n.goal[1] += o[1] * g.sampling.spacing;
		b.plan_goal(n, false);
		if (b.plan->status == HYLO_OK && b.plan->outcome == HYLO_FOUND)
			return n;
	}
	throw std::runtime_error("no nearby goal is valid");
}

void bench_scene(Bench &b, const std::string &path)
{
	Scene sc = hylo::scene::load(path);
	hylo_goal g = goal_of(sc);
	g.alternatives = 1;   // one plan; the alternatives' row asks for them
	const int runs = 5;
	std::vector<double> first, near, back, first_cpu, near_cpu, back_cpu, alt_cpu;
	std::string alternatives;
	double cost = 0, near_cost = 0;
	uint64_t evaluated = 0, near_evaluated = 0;

	b.new_map(sc);
	hylo_goal g2 = nearby_goal(b, g), g3 = way_back(g);
	for (int r = 0; r < runs; r++) {
		b.new_map(sc);
		first.push_back(b.plan_goal(g));
		first_cpu.push_back(b.last_cpu_ms);
		cost = b.plan->total_cost;
		evaluated = b.plan->n_edges_evaluated;
		near.push_back(b.plan_goal(g2));
		near_cpu.push_back(b.last_cpu_ms);
		near_cost = b.plan->total_cost;
		near_evaluated = b.plan->n_edges_evaluated;
		b.new_map(sc);
		b.plan_goal(g);
		back.push_back(b.plan_goal(g3, false));
		back_cpu.push_back(b.last_cpu_ms);
		// The first goal again, with the best paths of three mode sequences.
		hylo_goal gk = g;
		gk.alternatives = 3;
		b.new_map(sc);
		b.plan_goal(gk);
		alt_cpu.push_back(b.last_cpu_ms);
		alternatives.clear();
		for (uint32_t k = 0; k < b.plan->n_alternatives; k++)
			alternatives += (k ? ", " : "") + std::to_string(b.plan->alternative_switches[k]) + " changes " +
					std::to_string(b.plan->alternative_cost[k]) + " J";
	}
	// The reference on the first goal's graph, and on the nearby one's.
	b.new_map(sc);
	b.plan_goal(g);
	Reference ref = run_reference(b.pl_);
	b.plan_goal(g2);
	Reference ref2 = run_reference(b.pl_);
	std::string n = sc.name;
	std::printf("%-16s %6u nodes %8llu edges | first %7.1f ms, cpu %7.1f (ref %8.1f, cpu %8.1f) | "
		    "nearby %6.1f, cpu %6.1f | back %6.1f, cpu %6.1f | cost %.6f (ref %.6f, %.1e) | evaluated %llu (ref %llu)\n",
		    n.c_str(), b.plan->n_nodes, static_cast<unsigned long long>(b.plan->n_edges), median(first),
		    median(first_cpu), ref.ms, ref.cpu, median(near), median(near_cpu), median(back), median(back_cpu),
		    cost, ref.cost, std::fabs(cost - ref.cost) / ref.cost,
		    static_cast<unsigned long long>(evaluated), static_cast<unsigned long long>(ref.evaluated));
	std::printf("%-16s K = 3: cpu %7.1f ms (K = 1: %7.1f), %s\n", n.c_str(), median(alt_cpu),
		    median(first_cpu), alternatives.c_str());
	std::fflush(stdout);
	rows.push_back(bench_compared("plan_first_goal_k3_cpu_ms_" + n, median(alt_cpu), "ms", "hylo, one plan (K = 1)", median(first_cpu)));
	rows.push_back(bench_compared("plan_first_goal_ms_" + n, median(first), "ms", "floor-heuristic A*, every successor evaluated", ref.ms));
	rows.push_back(bench_compared("plan_nearby_goal_ms_" + n, median(near), "ms", "floor-heuristic A*, every successor evaluated", ref2.ms));
	rows.push_back(bench_row("plan_way_back_ms_" + n, median(back), "ms"));
	rows.push_back(bench_compared("plan_first_goal_cpu_ms_" + n, median(first_cpu), "ms", "floor-heuristic A*, every successor evaluated",
		ref.cpu));
	rows.push_back(bench_compared("plan_nearby_goal_cpu_ms_" + n, median(near_cpu), "ms", "floor-heuristic A*, every successor evaluated",
		ref2.cpu));
	rows.push_back(bench_row("plan_way_back_cpu_ms_" + n, median(back_cpu), "ms"));
	rows.push_back(bench_compared("plan_cost_j_" + n, cost, "J", "floor-heuristic A*", ref.cost));
	rows.push_back(bench_compared("plan_nearby_cost_j_" + n, near_cost, "J", "floor-heuristic A*", ref2.cost));
	rows.push_back(bench_compared("plan_edges_evaluated_" + n, double(evaluated), "edges", "floor-heuristic A*", double(ref.evaluated)));
	rows.push_back(bench_compared("plan_nearby_edges_evaluated_" + n, double(near_evaluated), "edges", "floor-heuristic A*",
		double(ref2.evaluated)));
}

}  // namespace

int main(int argc, char **argv)
{
	if (argc < 2 || argv[1][0] == '-') {
		std::fprintf(stderr, "usage: bench_scenes RESULTS.json [SCENE.yaml ...]\n");
		return 2;
	}
	std::vector<std::string> scenes(argv + 2, argv + argc);
	if (scenes.empty())
		scenes = {"scenes/di.yaml", "scenes/river_crossing.yaml", "scenes/island_crossing.yaml",
			  "scenes/chasm_030.yaml", "scenes/chasm_050.yaml", "scenes/chasm_070.yaml",
			  "scenes/chasm_090.yaml", "scenes/chasm_110.yaml"};
	try {
		Bench b;
		std::printf("workspace: %zu bytes (hylo_planner_size, every committed robot)\n", b.size);
		rows.push_back(bench_row("workspace_bytes", double(b.size), "bytes"));
		for (const std::string &s : scenes)
			bench_scene(b, s);
	} catch (const std::exception &e) {
		std::fprintf(stderr, "bench_scenes: %s\n", e.what());
		return 1;
	}
	if (!write_bench_results(argv[1], rows)) {
		std::fprintf(stderr, "bench_scenes: cannot write %s\n", argv[1]);
		return 1;
	}
	return 0;
}
