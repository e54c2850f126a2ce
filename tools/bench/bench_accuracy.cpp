// Accuracy of the committed cost models where the planner asks (issue #43):
// every committed scene is planned there and back with the committed
// models; from the edges the search evaluated (the edge cache's finite
// costs: start and goal links are not cached) and the edges of the plans,
// a seeded sample per model and source is solved exactly with the
// trainer's collocation (training_solve_options: the solver that labelled
// the training rows; ground and marine edges in the tail's frame, as the
// training rows), from the edge's own starts and, as trainer --solve, from
// the paths of the 8 nearest rows of the model's dataset where
// trainer/datasets/<robot> holds its sidecar (--memory DIR another dataset
// directory, --memory none: own starts only), and the model's relative
// error (prediction - exact) / exact is summarized: median and p95 of
// |error| (the p95 with its distribution-free 90% confidence interval:
// 100 edges pin it only to between their 10th and 2nd largest errors),
// the worst |error|, the bias (signed mean) and how many edges are off by
// more than 10%, next to the held-out errors on rows drawn like the
// training rows (each model's provenance string). Edges whose exact solve
// does not converge are counted, not scored.
//
// usage: bench_accuracy RESULTS.json [--edges N] [--seed S] [--jobs J]
//                       [--model NAME ...] [--memory DIR|none] [--csv EDGES.csv]
//                       [SCENE.yaml ...]
//        bench_accuracy --rescore EDGES.csv HEADER.h
// N edges per model and source (default 100); every committed scene and
// every model by default (--model, repeatable: only that model's edges are
// solved, e.g. ambot_marine before and after its refit). Writes a table to
// stdout, JSON rows {name, value, unit, reference, reference_value, ratio}
// to RESULTS.json (ratio = reference / value: above 1, the planner's edges
// are predicted better than held-out rows) and one CSV line per edge
// (default: RESULTS.json with _edges.csv for .json: length, climb, speeds,
// costs, error and both states) for tools/accuracy/plot_accuracy.py.
// --rescore EDGES.csv HEADER.h scores another header of one of the file's
// models on its edges (a regenerated model against the committed one).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "hylo/features.h"
#include "hylo/planner.h"
#include "hylo/region.h"
#include "tools/bench/results.hpp"
#include "tools/scene/committed.hpp"
#include "tools/scene/planner_view.hpp"
#include "trainer/cli.hpp"
#include "trainer/collocation.hpp"
#include "trainer/dataset.hpp"
#include "trainer/memory.hpp"
#include "trainer/params.hpp"
#include "trainer/processes.hpp"
#include "trainer/svr_export.hpp"

namespace {

using namespace hylo::trainer;

const char *const kSources[2] = {"evaluated", "plan"};

struct Edge {
	std::string scene;
	int source = 0;            // index into kSources
	hylo_mode mode = HYLO_MODE_NONE;
	double a[HYLO_XS_DIM] = {0}, b[HYLO_XS_DIM] = {0};
	double predicted = 0;      // hylo_svr_predict, before the planner's floor
	double exact = NAN;        // the trainer's optimum; NaN: did not converge
};

// Edges of one model: [source] -> edges, and what it needs to be solved.
struct ModelEdges {
	std::string robot;         // the parameter file's name
	const hylo_svr_model *model = nullptr;
	std::vector<Edge> pool[2];
};

Edge edge_of(const std::string &scene, int source, hylo_mode mode, const hylo_svr_model *m, const double *a,
	     const double *b)
{
	Edge e;
	e.scene = scene;
	e.source = source;
	e.mode = mode;
	std::copy_n(a, HYLO_XS_DIM, e.a);
	std::copy_n(b, HYLO_XS_DIM, e.b);
	double f[HYLO_MAX_FEATURES];
	hylo_features(mode, a, b, f);
	e.predicted = hylo_svr_predict(m, f);
	return e;
}

const hylo_mode_model *mode_model(const hylo_planner *pl, int mode)
{
	int k = hylo_robot_mode_index(pl->robot, static_cast<hylo_mode>(mode));
	return k < 0 ? nullptr : &pl->robot->modes[k];
}

// The edges the last search evaluated on roadmap nodes (the cache keeps
// every finite cost it computed; +inf marks a classifier's drop).
void evaluated_edges(hylo_planner *pl, const std::string &scene, std::map<std::string, ModelEdges> &out)
{
	const hylo_roadmap *rm = &pl->roadmap;
	for (uint32_t u = 0; u < rm->n_nodes; u++) {
		const uint32_t i = rm->node_pos[u], c = u - rm->pos[i].node_base;
		const hylo_position &p = rm->pos[i];
		const hylo_mode_model *mm = mode_model(pl, p.mode);
		if (!mm || !mm->model)
			continue;
		double a[HYLO_XS_DIM] = {0}, b[HYLO_XS_DIM] = {0};
		hylo_roadmap_state(rm, i, c, a);
		for (uint32_t k = 0; k < p.adj_end - p.adj_begin; k++) {
			const uint32_t j = rm->adjacency[p.adj_begin + k];
			const hylo_real *costs = hylo_edge_cache_group(&pl->cache, rm, u, k, 0);
			if (!costs || rm->pos[j].mode != p.mode)
				continue;
			for (uint32_t c2 = 0; c2 < rm->pos[j].n_combos; c2++)
				if (std::isfinite(costs[c2])) {
					hylo_roadmap_state(rm, j, c2, b);
					out[mm->model->name].pool[0].push_back(
						edge_of(scene, 0, static_cast<hylo_mode>(p.mode), mm->model, a, b));
				}
		}
	}
}

// The plan's edges within one mode (switches are constants, not models).
void plan_edges(const hylo_planner *pl, const hylo_plan &plan, const std::string &scene,
		std::map<std::string, ModelEdges> &out)
{
	for (uint32_t k = 0; k + 1 < plan.n_waypoints; k++) {
		const hylo_mode_model *mm = mode_model(pl, plan.mode[k]);
		if (plan.mode[k] != plan.mode[k + 1] || !mm || !mm->model ||
		    std::equal(plan.state[k], plan.state[k] + HYLO_XS_DIM, plan.state[k + 1]))
			continue;
		out[mm->model->name].pool[1].push_back(edge_of(scene, 1, static_cast<hylo_mode>(plan.mode[k]),
							       mm->model, plan.state[k], plan.state[k + 1]));
	}
}

// n edges of pool drawn without replacement (all of them when fewer), in
// pool order, by a seeded Fisher-Yates.
std::vector<Edge> sample(const std::vector<Edge> &pool, size_t n, uint64_t seed)
{
	std::vector<size_t> idx(pool.size());
	for (size_t i = 0; i < idx.size(); i++)
		idx[i] = i;
	std::mt19937_64 rng(seed);
	n = std::min(n, idx.size());
	for (size_t i = 0; i < n; i++)
		std::swap(idx[i], idx[i + rng() % (idx.size() - i)]);
	idx.resize(n);
	std::sort(idx.begin(), idx.end());
	std::vector<Edge> out;
	for (size_t i : idx)
		out.push_back(pool[i]);
	return out;
}

// The boundary states the model prices: a planar edge in its tail's frame
// (relative coordinates, as the training rows are drawn: the start at the
// origin with heading 0; a half turn towards the goal), others as they are.
void bvp_states(const Edge &e, double *a, double *b)
{
	std::copy_n(e.a, HYLO_XS_DIM, a);
	std::copy_n(e.b, HYLO_XS_DIM, b);
	if (!hylo_mode_describe(e.mode)->planar)
		return;
	double r[HYLO_RELATIVE_PLANAR];
	hylo_relative(e.mode, e.a, e.b, r);
	a[0] = a[1] = a[3] = 0;
	b[0] = r[0], b[1] = r[1], b[3] = r[2];
}

// Solves every edge (one forked process each: trainer/processes.hpp), with
// the memory of its model where it has one (open_memory; null: none).
void solve_all(std::vector<Edge> &edges, const std::map<std::string, RobotParams> &robots,
	       const std::vector<std::string> &robot_of, const std::vector<const Memory *> &memory_of_edge,
	       int jobs)
{
	std::vector<std::string> res = fork_each(edges.size(), jobs, [&](size_t i) {
		double a[HYLO_XS_DIM], b[HYLO_XS_DIM];
		bvp_states(edges[i], a, b);
		Solution s = solve_remembered(edges[i].mode, robots.at(robot_of[i]), a, b, training_solve_options(),
					      memory_of_edge[i], 8);
		char buf[64];
		std::snprintf(buf, sizeof buf, "%d %.17g", s.converged ? 1 : 0, s.cost);
		return std::string(buf);
	});
	for (size_t i = 0; i < edges.size(); i++) {
		int conv = 0;
		double cost = NAN;
		if (std::sscanf(res[i].c_str(), "%d %lf", &conv, &cost) == 2 && conv && cost > 0)
			edges[i].exact = cost;
	}
}

struct Summary {
	size_t n = 0, unsolved = 0, over_10pct = 0;
	double median = NAN, p95 = NAN, worst = NAN, bias = NAN;   // worst: signed
	double p95_low = NAN, p95_high = NAN;   // its 90% confidence interval
};

// The q-quantile of the sorted sample v, interpolated.
double quantile(const std::vector<double> &v, double q)
{
	if (v.empty())
		return NAN;
	double x = q * (v.size() - 1);
	size_t lo = static_cast<size_t>(x);
	return lo + 1 < v.size() ? v[lo] + (x - lo) * (v[lo + 1] - v[lo]) : v[lo];
}

// A distribution-free 90% confidence interval of the q-quantile of the
// sorted sample v: the order statistics v[r-1], v[s-1] (1-based r, s) with
// P(B < r) <= 0.05 and P(B >= s) <= 0.05 for B ~ Binomial(n, q), the number
// of draws below the true quantile. The high end is NAN where the sample is
// too small for it (for the p95: under 59 edges).
void quantile_interval(const std::vector<double> &v, double q, double &low, double &high)
{
	const size_t n = v.size();
	double cdf = 0;   // P(B <= j)
	low = high = NAN;
	for (size_t j = 0; j < n; j++) {
		cdf += std::exp(std::lgamma(n + 1.0) - std::lgamma(j + 1.0) - std::lgamma(n - j + 1.0) +
				j * std::log(q) + (n - j) * std::log1p(-q));
		if (cdf <= 0.05)   // P(B < j + 1): r = j + 1 will do
			low = v[j];
		if (std::isnan(high) && 1 - cdf <= 0.05)   // P(B >= j + 1): s = j + 1
			high = v[j];
	}
}

Summary summarize(const std::vector<Edge> &edges, int source)
{
	Summary s;
	std::vector<double> abs_err;
	double sum = 0;
	for (const Edge &e : edges) {
		if (source >= 0 && e.source != source)
			continue;
		if (!std::isfinite(e.exact)) {
			s.unsolved++;
			continue;
		}
		double r = (e.predicted - e.exact) / e.exact;
		abs_err.push_back(std::fabs(r));
		s.over_10pct += std::fabs(r) > 0.10;
		sum += r;
		if (!(std::fabs(r) <= std::fabs(s.worst)))
			s.worst = r;
		s.n++;
	}
	if (s.n) {
		std::sort(abs_err.begin(), abs_err.end());
		s.median = quantile(abs_err, 0.5);
		s.p95 = quantile(abs_err, 0.95);
		quantile_interval(abs_err, 0.95, s.p95_low, s.p95_high);
		s.bias = sum / s.n;
	}
	return s;
}

// The error columns of both tables: their heading, one summary's values.
const char *const kErrorHeading = "edges unsolv   median      p95 (90% interval)     worst     bias >10%";

std::string error_columns(const Summary &sm)
{
	char buf[160];
	std::snprintf(buf, sizeof buf, "%5zu %6zu %7.2f%% %7.2f%% (%5.2f%%, %5.2f%%) %+8.2f%% %+7.2f%% %4zu", sm.n,
		      sm.unsolved, 100 * sm.median, 100 * sm.p95, 100 * sm.p95_low, 100 * sm.p95_high, 100 * sm.worst,
		      100 * sm.bias, sm.over_10pct);
	return buf;
}

// The held-out errors of a model's provenance: median, p95, max.
bool held_out(const hylo_svr_model *m, double out[3])
{
	const char *p = m->provenance ? std::strstr(m->provenance, "held-out errors: ") : nullptr;
	return p && std::sscanf(p, "held-out errors: median %lf, p95 %lf, max %lf", &out[0], &out[1], &out[2]) == 3;
}


// Edge length and climb angle (flight: of the displacement) for the CSV.
void write_csv(const std::string &path, const std::vector<std::pair<std::string, Edge>> &edges)
{
	std::ofstream out(path);
	out << "model,mode,source,scene,length_m,climb_deg,speed1_mps,speed2_mps,predicted_j,exact_j,rel_error";
	for (const char *end : {"x1_", "x2_"})
		for (int k = 0; k < HYLO_XS_DIM; k++)
			out << "," << end << k;
	out << "\n";
	for (const auto &[name, e] : edges) {
		double len = hylo_edge_distance(e.mode, e.a, e.b), dz = e.mode == HYLO_MODE_FLIGHT ? e.b[2] - e.a[2] : 0;
		double climb = e.mode == HYLO_MODE_FLIGHT ? std::atan2(dz, std::hypot(e.b[0] - e.a[0], e.b[1] - e.a[1])) * 180 / M_PI : 0;
		char buf[400];
		std::snprintf(buf, sizeof buf, "%s,%s,%s,%s,%.6g,%.6g,%.6g,%.6g,%.10g,%.10g,%.6g\n", name.c_str(),
			      hylo_mode_str(e.mode), kSources[e.source], e.scene.c_str(), len, climb,
			      hylo_state_speed(e.mode, e.a), hylo_state_speed(e.mode, e.b), e.predicted, e.exact,
			      std::isfinite(e.exact) ? (e.predicted - e.exact) / e.exact : NAN);
		out << std::string(buf, std::strlen(buf) - 1);   // the states, to solve an edge again
		for (const double *x : {e.a, e.b})
			for (int k = 0; k < HYLO_XS_DIM; k++) {
				std::snprintf(buf, sizeof buf, ",%.17g", x[k]);
				out << buf;
			}
		out << "\n";
	}
	if (!out)
		throw std::runtime_error("cannot write " + path);
}

// --rescore EDGES.csv HEADER.h: the edges of an earlier run (their exact
// costs) predicted by another header of one of their models, e.g. a
// regenerated one, beside the header they were benchmarked with. No solves.
int rescore(const std::string &csv, const std::string &header)
{
	for (const std::string &path : {csv, header})
		if (!std::ifstream(path))
			throw std::invalid_argument("cannot read " + path);
	SvrExport h = parse_svr_header(read_file(header));
	const std::string name = h.robot + "_" + hylo_mode_str(h.mode);
	if (h.n_features != static_cast<int>(hylo_feature_count(h.mode)))
		throw std::invalid_argument(header + ": " + std::to_string(h.n_features) + " features, mode " +
					    hylo_mode_str(h.mode) + " has " + std::to_string(hylo_feature_count(h.mode)));
	const hylo_svr_model m = model_view(h, name.c_str());
	std::ifstream in(csv);
	std::string line;
	if (!std::getline(in, line) || line.rfind("model,mode,source,", 0) != 0)
		throw std::invalid_argument(csv + ": not a bench_accuracy edges file");
	std::vector<Edge> before, after;
	for (size_t no = 2; std::getline(in, line); no++) {
		std::vector<std::string> f;
		for (size_t a = 0, b; a <= line.size(); a = b + 1) {
			b = std::min(line.find(',', a), line.size());
			f.push_back(line.substr(a, b - a));
		}
		if (f.size() != 11 + 2 * HYLO_XS_DIM)
			throw std::invalid_argument(csv + ":" + std::to_string(no) + ": " + std::to_string(f.size()) +
						    " fields, not " + std::to_string(11 + 2 * HYLO_XS_DIM));
		if (f[0] != name)
			continue;
		Edge e;
		e.source = f[2] == kSources[1] ? 1 : 0;
		e.mode = h.mode;
		e.predicted = std::stod(f[8]);
		e.exact = std::stod(f[9]);
		for (int k = 0; k < HYLO_XS_DIM; k++) {
			e.a[k] = std::stod(f[11 + k]);
			e.b[k] = std::stod(f[11 + HYLO_XS_DIM + k]);
		}
		before.push_back(e);
		double x[HYLO_MAX_FEATURES];
		hylo_features(e.mode, e.a, e.b, x);
		e.predicted = hylo_svr_predict(&m, x);
		after.push_back(e);
	}
	if (before.empty())
		throw std::invalid_argument(csv + ": no edges of " + name + " (" + header + ")");
	std::printf("%-9s %-9s %s\n", "header", "source", kErrorHeading);
	for (const auto &[label, edges] : {std::make_pair("as run", &before), std::make_pair("rescored", &after)})
		for (int src = -1; src < 2; src++)
			std::printf("%-9s %-9s %s\n", label, src < 0 ? "all" : kSources[src],
				    error_columns(summarize(*edges, src)).c_str());
	return 0;
}

int run(int argc, char **argv)
{
	if (argc == 4 && std::string(argv[1]) == "--rescore")
		return rescore(argv[2], argv[3]);
	if (argc < 2 || argv[1][0] == '-') {
		std::fprintf(stderr, "usage: bench_accuracy RESULTS.json [--edges N] [--seed S] [--jobs J] "
				     "[--model NAME ...] [--memory DIR|none] [--csv EDGES.csv] [SCENE.yaml ...]\n"
				     "       bench_accuracy --rescore EDGES.csv HEADER.h\n");
		return 2;
	}
	const std::string json = argv[1];
	std::string csv = json.size() > 5 && json.compare(json.size() - 5, 5, ".json") == 0
				  ? json.substr(0, json.size() - 5) + "_edges.csv"
				  : json + "_edges.csv";
	size_t per_source = 100;
	uint64_t seed = 1;
	int jobs = 2;
	std::vector<std::string> scenes, only;
	std::string memory_dir;
	for (int i = 2; i < argc; i++) {
		std::string a = argv[i];
		auto val = [&] { return option_value(argc, argv, i); };
		if (a == "--edges")
			per_source = std::stoul(val());
		else if (a == "--seed")
			seed = std::stoull(val());
		else if (a == "--jobs")
			jobs = std::stoi(val());
		else if (a == "--csv")
			csv = val();
		else if (a == "--model")
			only.push_back(val());
		else if (a == "--memory")
			memory_dir = val();
		else if (!a.empty() && a[0] == '-')
			throw std::invalid_argument("unknown option " + a);
		else
			scenes.push_back(a);
	}
	if (scenes.empty())
		scenes = hylo::scene::committed_scenes();

	hylo::scene::CommittedPlanner committed;
	hylo_planner *pl = committed.get();
	std::unique_ptr<hylo_plan> plan(new hylo_plan);
	std::map<std::string, ModelEdges> models;
	for (const std::string &path : scenes) {
		const hylo::scene::Scene sc = hylo::scene::load(path);
		const hylo_map_view v = hylo::scene::map_view(sc);
		const hylo_goal there = hylo::scene::goal_of(sc), back = hylo::scene::way_back(there);
		for (const hylo_goal *g : {&there, &back}) {
			hylo_planner_set_map(pl, &v);   // a fresh cache: this goal's edges alone
			hylo_planner_plan(pl, g, plan.get());
			if (plan->status != HYLO_OK || plan->outcome != HYLO_FOUND)
				throw std::runtime_error(path + ": no plan: " + plan->reason.text);
			evaluated_edges(pl, sc.name, models);
			plan_edges(pl, *plan, sc.name, models);
		}
		for (auto &[name, me] : models)
			if (me.robot.empty()) {
				me.robot = sc.robot;
				for (uint32_t k = 0; k < pl->robot->n_modes; k++)
					if (pl->robot->modes[k].model && name == pl->robot->modes[k].model->name)
						me.model = pl->robot->modes[k].model;
			}
	}

	for (const std::string &name : only)
		if (!models.count(name))
			throw std::invalid_argument("--model " + name + ": no such model on these scenes' plans");
	if (!only.empty())
		for (auto it = models.begin(); it != models.end();)
			it = std::find(only.begin(), only.end(), it->first) == only.end() ? models.erase(it) : std::next(it);

	std::map<std::string, RobotParams> params;
	std::vector<Edge> todo;
	std::vector<std::string> todo_model, todo_robot;
	std::vector<std::unique_ptr<Memory>> memories;
	std::vector<const Memory *> todo_memory;
	uint64_t stream = 0;
	for (const auto &[name, me] : models) {
		if (!params.count(me.robot))
			params[me.robot] = load_robot(robot_file(me.robot));
		const hylo_mode mode = me.pool[0].empty() ? me.pool[1].front().mode : me.pool[0].front().mode;
		memories.push_back(open_memory(memory_dir, me.robot, params.at(me.robot), mode));
		std::printf("%-20s %7zu edges evaluated, %4zu on plans (%zu scenes, there and back); memory: %s\n",
			    name.c_str(), me.pool[0].size(), me.pool[1].size(), scenes.size(),
			    memories.back() ? memories.back()->sidecar().c_str() : "none");
		for (int s = 0; s < 2; s++)
			for (const Edge &e : sample(me.pool[s], per_source, seed * 1000003 + stream++)) {
				todo.push_back(e);
				todo_model.push_back(name);
				todo_robot.push_back(me.robot);
				todo_memory.push_back(memories.back().get());
			}
	}
	std::printf("solving %zu edges exactly (%zu per model and source at most, seed %llu, %d jobs)\n", todo.size(),
		    per_source, static_cast<unsigned long long>(seed), jobs);
	std::fflush(stdout);
	solve_all(todo, params, todo_robot, todo_memory, jobs);

	std::vector<BenchRow> rows;
	std::vector<std::pair<std::string, Edge>> all;
	for (size_t i = 0; i < todo.size(); i++)
		all.emplace_back(todo_model[i], todo[i]);
	std::printf("%-20s %-9s %s | held-out %6s %6s %6s\n", "model", "source", kErrorHeading, "median", "p95",
		    "max");
	for (const auto &[name, me] : models) {
		std::vector<Edge> mine;
		for (size_t i = 0; i < todo.size(); i++)
			if (todo_model[i] == name)
				mine.push_back(todo[i]);
		double ho[3] = {NAN, NAN, NAN};
		held_out(me.model, ho);
		for (int s = -1; s < 2; s++) {
			const Summary sm = summarize(mine, s);
			const std::string src = s < 0 ? "all" : kSources[s];
			std::printf("%-20s %-9s %s | %5.2f%% %5.2f%% %5.1f%%\n", name.c_str(), src.c_str(),
				    error_columns(sm).c_str(), 100 * ho[0], 100 * ho[1], 100 * ho[2]);
			const std::string base = "accuracy_" + name + "_" + src + "_";
			const std::string ref = "held-out rows drawn like the training rows (model provenance)";
			rows.push_back(bench_compared(base + "median_rel_error", sm.median, "relative", ref, ho[0]));
			rows.push_back(bench_compared(base + "p95_rel_error", sm.p95, "relative", ref, ho[1]));
			rows.push_back(bench_compared(base + "worst_rel_error", std::fabs(sm.worst), "relative", ref, ho[2]));
			rows.push_back(bench_row(base + "p95_rel_error_90ci_low", sm.p95_low, "relative"));
			rows.push_back(bench_row(base + "p95_rel_error_90ci_high", sm.p95_high, "relative"));
			rows.push_back(bench_row(base + "bias", sm.bias, "relative"));
			rows.push_back(bench_row(base + "edges_over_10pct", static_cast<double>(sm.over_10pct), "edges"));
			rows.push_back(bench_row(base + "edges", static_cast<double>(sm.n), "edges"));
			rows.push_back(bench_row(base + "unsolved", static_cast<double>(sm.unsolved), "edges"));
		}
	}
	if (!write_bench_results(json, rows)) {
		std::fprintf(stderr, "bench_accuracy: cannot write %s\n", json.c_str());
		return 1;
	}
	write_csv(csv, all);
	std::printf("%zu rows -> %s; edges -> %s\n", rows.size(), json.c_str(), csv.c_str());
	return 0;
}

}  // namespace

int main(int argc, char **argv)
{
	return run_main("bench_accuracy", run, argc, argv, 1);
}
