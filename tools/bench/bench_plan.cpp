// Plan latency: hylo end to end (roadmap build + lazy A*) against the
// textbook pipeline on the same graph: every edge evaluated with libsvm's
// svm_predict, then Boost Graph Library's dijkstra_shortest_paths.
//
// Scene: a generated 2-D map, 100 m x 60 m of ground with a 10 m water band,
// for a two-mode robot whose ground cost is the synthetic 2,000-SV SVR
// (build/gen/bench/synthetic_ground.h) and whose water cost is the same model
// scaled by 3. Spacing is chosen so the graph has about 2,000 / 8,000 /
// 32,000 nodes. Writes a table to stdout and JSON rows to argv[1].
#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/dijkstra_shortest_paths.hpp>
#include <libsvm/svm.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include "hylo/features.h"
#include "hylo/planner.h"
#include "bench/synthetic_ground.h"
#include "tools/bench/results.hpp"

namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0)
{
	return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

double median(std::vector<double> v)
{
	std::sort(v.begin(), v.end());
	size_t n = v.size();
	return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::vector<BenchRow> rows;

// The water model: the ground model with every cost tripled.
hylo_svr_model water_model()
{
	hylo_svr_model m = hylo_model_synthetic_ground;
	m.name = "synthetic_water";
	m.label_scale *= 3;
	m.label_offset *= 3;
	m.cost_floor_per_m *= 3;
	m.cost_floor_j *= 3;
	return m;
}

struct Scene {
	int32_t nx = 200, ny = 120;
	std::vector<int8_t> terrain;
	std::vector<float> height;
	Scene() : terrain(nx * ny, HYLO_TERRAIN_GROUND), height(nx * ny, 0.0f)
	{
		for (int iy = 0; iy < ny; iy++)
			for (int ix = 90; ix < 110; ix++)
				terrain[iy * nx + ix] = HYLO_TERRAIN_WATER;
	}
	hylo_map_view view() const
	{
		hylo_map_view v;
		std::memset(&v, 0, sizeof v);
		v.map_id = 1;
		v.robot = "bench";
		v.nx = nx;
		v.ny = ny;
		v.resolution = 0.5;
		v.n_cells = nx * ny;
		v.terrain = terrain.data();
		v.height = height.data();
		return v;
	}
};

const hylo_real kSpeeds[] = {0.0, 1.0};
const hylo_real kHeadings[] = {0.0, M_PI / 2, M_PI, -M_PI / 2};

hylo_goal make_goal(double spacing)
{
	hylo_goal g;
	std::memset(&g, 0, sizeof g);
	g.algorithm = HYLO_ASTAR;
	g.start_mode = HYLO_MODE_GROUND;
	g.start[0] = 3;
	g.start[1] = 30;
	g.goal_mode = HYLO_MODE_GROUND;
	g.goal[0] = 97;
	g.goal[1] = 30;
	g.sampling.seed = 1;
	g.sampling.spacing = spacing;
	g.sampling.guard_spacing = spacing;
	g.sampling.connect_radius = std::min(2.2 * spacing, hylo_model_synthetic_ground.max_distance_m);
	g.sampling.n_speeds = std::size(kSpeeds);
	std::copy(std::begin(kSpeeds), std::end(kSpeeds), g.sampling.speeds);
	g.sampling.n_headings = std::size(kHeadings);
	std::copy(std::begin(kHeadings), std::end(kHeadings), g.sampling.headings);
	return g;
}

// The reference: the graph hylo built, every edge evaluated by svm_predict.
struct Reference {
	double ms = 0, cost = 0, eval_ms = 0;
	size_t edges = 0;
};

struct LibsvmModel {
	std::vector<std::vector<svm_node>> sv;
	std::vector<svm_node *> sv_ptr;
	std::vector<double> coef;
	double rho;
	double *coef_rows[1];
	svm_model model;
	explicit LibsvmModel(const hylo_svr_model &m) : sv(m.n_sv), sv_ptr(m.n_sv), coef(m.coef, m.coef + m.n_sv)
	{
		for (uint32_t i = 0; i < m.n_sv; i++) {
			for (uint32_t k = 0; k < m.n_features; k++)
				sv[i].push_back({int(k + 1), m.sv[i * m.n_features + k]});
			sv[i].push_back({-1, 0});
			sv_ptr[i] = sv[i].data();
		}
		rho = m.rho;
		std::memset(&model, 0, sizeof model);
		model.param.svm_type = EPSILON_SVR;
		model.param.kernel_type = RBF;
		model.param.gamma = m.gamma;
		model.nr_class = 2;
		model.l = int(m.n_sv);
		model.SV = sv_ptr.data();
		coef_rows[0] = coef.data();
		model.sv_coef = coef_rows;
		model.rho = &rho;
	}
};

double svm_cost(const svm_model *sm, const hylo_svr_model &m, const double *f, double dist)
{
	svm_node x[HYLO_MAX_FEATURES + 1];
	for (uint32_t k = 0; k < m.n_features; k++)
		x[k] = {int(k + 1), (f[k] - m.feature_offset[k]) / m.feature_scale[k]};
	x[m.n_features] = {-1, 0};
	double y = svm_predict(sm, x) * m.label_scale + m.label_offset;
	double c = m.label_log ? std::exp(y) : y;
	double lo = m.cost_floor_j + m.cost_floor_per_m * dist;
	return c < lo ? lo : c;
}

void node_state(const hylo_planner *pl, uint32_t u, double *xs)
{
	const hylo_roadmap *rm = &pl->roadmap;
	uint32_t i = rm->node_pos[u];
	if (i == pl->start_pos)
		std::memcpy(xs, pl->start_xs, sizeof pl->start_xs);
	else if (i == pl->goal_pos)
		std::memcpy(xs, pl->goal_xs, sizeof pl->goal_xs);
	else
		hylo_roadmap_state(rm, i, u - rm->pos[i].node_base, xs);
}

Reference run_reference(const hylo_planner *pl, const hylo_svr_model *models[2])
{
	using Graph = boost::adjacency_list<boost::vecS, boost::vecS, boost::directedS,
					    boost::no_property,
					    boost::property<boost::edge_weight_t, double>>;
	const hylo_roadmap *rm = &pl->roadmap;
	uint32_t n = rm->n_nodes + 2;
	LibsvmModel ground(*models[0]), water(*models[1]);
	std::vector<std::pair<uint32_t, uint32_t>> edges;
	std::vector<double> weights;
	std::vector<uint32_t> nb;
	Reference ref;

	// Edge structure from the roadmap (not timed: both sides share it).
	struct Pending { uint32_t u, v; double dist; int kind; };
	std::vector<Pending> todo;
	for (uint32_t u = 0; u < n; u++) {
		uint32_t i = rm->node_pos[u], c = u - rm->pos[i].node_base;
		const hylo_position *p = &rm->pos[i];
		if (i == pl->goal_pos)
			continue;
		nb.clear();
		if (i == pl->start_pos) {
			nb.assign(pl->start_adj, pl->start_adj + pl->n_start_adj);
			if (pl->start_goal_linked)
				nb.push_back(pl->goal_pos);
		} else {
			nb.assign(rm->adjacency + p->adj_begin, rm->adjacency + p->adj_end);
			if (pl->links_goal[i])
				nb.push_back(pl->goal_pos);
		}
		for (uint32_t j : nb) {
			const hylo_position *q = &rm->pos[j];
			double dist = hylo_roadmap_distance(p->p, q->p);
			for (uint32_t cc = 0; cc < q->n_combos; cc++)
				todo.push_back({u, q->node_base + cc, dist, p->mode == HYLO_MODE_MARINE ? 1 : 0});
		}
		if (i < rm->n_positions && p->twin != HYLO_NO_POSITION) {
			uint32_t combos[HYLO_MAX_COMBOS];
			uint32_t ns = hylo_roadmap_switch_heads(rm, i, c, combos);
			for (uint32_t k = 0; k < ns; k++)
				todo.push_back({u, rm->pos[p->twin].node_base + combos[k], 0, 2});
		}
	}

	auto t0 = Clock::now();
	edges.reserve(todo.size());
	weights.reserve(todo.size());
	for (const Pending &e : todo) {
		double w = 0;
		if (e.kind < 2) {
			double a[HYLO_XS_DIM], b[HYLO_XS_DIM], f[HYLO_MAX_FEATURES];
			hylo_mode mode = e.kind ? HYLO_MODE_MARINE : HYLO_MODE_GROUND;
			node_state(pl, e.u, a);
			node_state(pl, e.v, b);
			hylo_features(mode, a, b, f);
			w = e.kind ? svm_cost(&water.model, *models[1], f, e.dist)
				   : svm_cost(&ground.model, *models[0], f, e.dist);
		}
		edges.emplace_back(e.u, e.v);
		weights.push_back(w);
	}
	ref.eval_ms = ms_since(t0);
	Graph g(edges.begin(), edges.end(), weights.begin(), n);
	std::vector<double> dist(n);
	boost::dijkstra_shortest_paths(g, rm->n_nodes, boost::distance_map(dist.data()));
	ref.ms = ms_since(t0);
	ref.cost = dist[rm->n_nodes + 1];
	ref.edges = todo.size();
	return ref;
}

}  // namespace

int main(int argc, char **argv)
{
	if (argc != 2 || argv[1][0] == '-') {  // --help is not a file name
		std::fprintf(stderr, "usage: bench_plan RESULTS.json\n");
		return 2;
	}
	static hylo_svr_model water = water_model();
	const hylo_svr_model *models[2] = {&hylo_model_synthetic_ground, &water};
	hylo_robot robot;
	std::memset(&robot, 0, sizeof robot);
	robot.name = "bench";
	robot.n_modes = 2;
	robot.modes[0].mode = HYLO_MODE_GROUND;
	robot.modes[0].model = models[0];
	robot.modes[1].mode = HYLO_MODE_MARINE;
	robot.modes[1].model = models[1];
	hylo_planner_config cfg;
	std::memset(&cfg, 0, sizeof cfg);
	cfg.robots = &robot;
	cfg.n_robots = 1;
	size_t size = hylo_planner_size(&cfg);
	std::vector<double> mem(size / sizeof(double) + 1);
	hylo_planner *pl = reinterpret_cast<hylo_planner *>(mem.data());
	auto plan = std::unique_ptr<hylo_plan>(new hylo_plan);
	Scene scene;
	hylo_map_view view = scene.view();

	std::printf("workspace: %zu bytes (hylo_planner_size at the default capacities)\n", size);
	std::printf("%8s %8s %10s %10s %10s %10s %10s %11s %11s %8s %10s\n", "target", "nodes",
		    "edges", "evaluated", "hylo ms", "reused ms", "ref ms", "ref eval ms",
		    "hylo cost", "speedup", "cost diff");

	const int targets[] = {2000, 8000, 32000};
	for (int target : targets) {
		// Spacing for about `target` nodes: nodes scale with 1/spacing^2.
		double spacing = 3.0;
		for (int it = 0; it < 6; it++) {
			hylo_goal g = make_goal(spacing);
			if (hylo_planner_init(pl, size, &cfg) != HYLO_OK ||
			    hylo_planner_set_map(pl, &view) != HYLO_OK ||
			    hylo_planner_plan(pl, &g, plan.get()) != HYLO_OK) {
				std::fprintf(stderr, "bench_plan: %s\n", hylo_planner_reason(pl));
				return 1;
			}
			spacing *= std::sqrt(double(plan->n_nodes) / target);
		}
		hylo_goal g = make_goal(spacing);
		std::vector<double> times, reused;
		for (int rep = 0; rep < 5; rep++) {
			auto t0 = Clock::now();
			hylo_planner_set_map(pl, &view);
			hylo_planner_plan(pl, &g, plan.get());
			times.push_back(ms_since(t0));
			t0 = Clock::now();
			hylo_planner_plan(pl, &g, plan.get());
			reused.push_back(ms_since(t0));
		}
		if (plan->status != HYLO_OK || plan->outcome != HYLO_FOUND) {
			std::fprintf(stderr, "bench_plan: no plan: %s\n", plan->reason.text);
			return 1;
		}
		int reps = target >= 32000 ? 1 : 3;
		std::vector<double> ref_ms;
		Reference ref;
		for (int rep = 0; rep < reps; rep++) {
			ref = run_reference(pl, models);
			ref_ms.push_back(ref.ms);
		}
		double hylo_ms = median(times), ref_med = median(ref_ms);
		double diff = std::fabs(plan->total_cost - ref.cost) / ref.cost;
		std::printf("%8d %8u %10llu %10llu %10.2f %10.2f %10.1f %11.1f %11.4f %7.1fx %10.2g\n",
			    target, plan->n_nodes, (unsigned long long)plan->n_edges,
			    (unsigned long long)plan->n_edges_evaluated, hylo_ms, median(reused),
			    ref_med, ref.eval_ms, plan->total_cost, ref_med / hylo_ms, diff);
		std::string t = std::to_string(target);
		rows.push_back(bench_compared("plan_ms_" + t + "_nodes", hylo_ms, "ms",
			"BGL dijkstra_shortest_paths + libsvm svm_predict on every edge", ref_med,
			ref_med / hylo_ms));
		rows.push_back(bench_row("plan_ms_reused_roadmap_" + t + "_nodes", median(reused), "ms"));
		rows.push_back(bench_row("nodes_" + t, plan->n_nodes, "count"));
		rows.push_back(bench_row("edges_" + t, double(plan->n_edges), "count"));
		rows.push_back(bench_row("edges_evaluated_" + t, double(plan->n_edges_evaluated), "count"));
		rows.push_back(bench_row("cost_rel_diff_vs_reference_" + t, diff, "relative"));
		if (ref.edges != plan->n_edges)
			std::fprintf(stderr, "warning: reference has %zu edges, hylo %llu\n", ref.edges,
				     (unsigned long long)plan->n_edges);
	}
	if (!write_bench_results(argv[1], rows)) {
		std::fprintf(stderr, "bench_plan: cannot write %s\n", argv[1]);
		return 1;
	}
	return 0;
}
