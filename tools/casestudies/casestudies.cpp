// hylo-casestudies: the paper's case studies, measured (issue 6; make casestudies).
//   di     the hybrid double integrator: edges weighted by exact trajectory
//          optimization (the planner's cost callback calling the trainer's
//          collocation), graph path, smoothed path, a two-phase optimization
//          from a naive guess, the swept two-phase optimum; and the
//          convergence of the graph cost over ten Poisson-disc spacings.
//   ambot  river and island crossing: the energy-optimal plan (committed SVR
//          models) against the shortest-distance plan on the same graph.
// Writes OUT/results.json (every number) and OUT/results.md (the tables);
// tools/casestudies/plot.py draws the convergence figure from the JSON.
#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

extern "C" {
#include "hylo/features.h"
#include "hylo/planner.h"
#include "node/registry.h"
}
#include "tools/scene/scene.hpp"
#include "trainer/collocation.hpp"
#include "trainer/params.hpp"
#include "trainer/smoother.hpp"
#include "trainer/switching.hpp"

namespace {

using namespace hylo::trainer;
using hylo::scene::Scene;

const char *kUsage =
	"usage: hylo-casestudies [--study di|ambot|all] [--out DIR] [--jobs N] [--quick]\n"
	"  The paper's case studies (docs/results.md explains each).\n"
	"  --study S   which study to run (default all)\n"
	"  --out DIR   where results.json and results.md go (default docs)\n"
	"  --jobs N    worker processes for exact edge costs (default 2)\n"
	"  --quick     a check: the DI convergence on 3 spacings instead of 10, and\n"
	"              Ambot plans without exact edge costs or smoothing\n";

struct Options {
	std::string study = "all", out = "docs";
	int jobs = 2;
	bool quick = false;
};

double seconds_since(std::chrono::steady_clock::time_point t0)
{
	return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::string num(double v)
{
	if (!std::isfinite(v))
		return "null";
	char b[64];
	std::snprintf(b, sizeof b, "%.10g", v);
	return b;
}

// f(i) for i in [0, n) in `jobs` forked workers (Ipopt is not thread-safe);
// results in index order. A worker that dies makes every value NaN.
std::vector<double> parallel_map(size_t n, int jobs, const std::function<double(size_t)> &f)
{
	std::vector<double> out(n, NAN);
	int w_count = static_cast<int>(std::min<size_t>(static_cast<size_t>(std::max(1, jobs)), n));
	if (w_count <= 1) {
		for (size_t i = 0; i < n; i++)
			out[i] = f(i);
		return out;
	}
	std::vector<pid_t> pids;
	std::vector<int> fds;
	for (int w = 0; w < w_count; w++) {
		int p[2];
		if (pipe(p) != 0)
			throw std::runtime_error(std::string("pipe: ") + std::strerror(errno));
		std::fflush(nullptr);
		pid_t pid = fork();
		if (pid < 0)
			throw std::runtime_error(std::string("fork: ") + std::strerror(errno));
		if (pid == 0) {
			close(p[0]);
			for (size_t i = static_cast<size_t>(w); i < n; i += static_cast<size_t>(w_count)) {
				double v = f(i);
				if (write(p[1], &v, sizeof v) != static_cast<ssize_t>(sizeof v))
					_exit(1);
			}
			_exit(0);
		}
		close(p[1]);
		pids.push_back(pid);
		fds.push_back(p[0]);
	}
	for (int w = 0; w < w_count; w++) {
		for (size_t i = static_cast<size_t>(w); i < n; i += static_cast<size_t>(w_count)) {
			double v;
			ssize_t k;
			do
				k = read(fds[static_cast<size_t>(w)], &v, sizeof v);
			while (k < 0 && errno == EINTR);
			if (k != static_cast<ssize_t>(sizeof v))
				break;
			out[i] = v;
		}
		close(fds[static_cast<size_t>(w)]);
		waitpid(pids[static_cast<size_t>(w)], nullptr, 0);
	}
	return out;
}

// ---- planner set-up from a scene -----------------------------------------

hylo_map_view map_view(const Scene &sc)
{
	hylo_map_view v{};
	v.map_id = sc.map_id;
	v.robot = sc.robot.c_str();
	v.nx = sc.nx;
	v.ny = sc.ny;
	v.resolution = sc.resolution_m;
	v.origin_x = sc.origin_x_m;
	v.origin_y = sc.origin_y_m;
	v.ceiling = sc.ceiling_m;
	v.max_step = sc.max_step_m;
	v.n_cells = sc.nx * sc.ny;
	v.terrain = sc.terrain.data();
	v.height = sc.height_m.data();
	return v;
}

hylo_goal goal_of(const Scene &sc)
{
	const hylo::scene::Goal &g = sc.goal;
	hylo_goal q{};
	q.request_id = 1;
	q.algorithm = g.algorithm;
	q.start_mode = g.start.mode;
	q.goal_mode = g.goal.mode;
	for (int k = 0; k < HYLO_XS_DIM; k++) {
		q.start[k] = g.start.x[static_cast<size_t>(k)];
		q.goal[k] = g.goal.x[static_cast<size_t>(k)];
	}
	q.seed = static_cast<uint64_t>(g.seed);
	q.spacing = g.spacing_m;
	q.air_spacing = g.air_spacing_m;
	q.guard_spacing = g.guard_spacing_m;
	q.connect_radius = g.connect_radius_m;
	q.air_connect_radius = g.air_connect_radius_m;
	q.n_speeds = static_cast<uint32_t>(g.speeds_mps.size());
	q.speeds = g.speeds_mps.data();
	q.n_headings = static_cast<uint32_t>(g.headings_rad.size());
	q.headings = g.headings_rad.data();
	q.n_air_speeds = static_cast<uint32_t>(g.air_speeds_mps.size());
	q.air_speeds = g.air_speeds_mps.data();
	return q;
}

// One planner workspace (tens of MB: allocated once) planning for one robot.
struct Planner {
	std::unique_ptr<hylo_planner> pl{new hylo_planner};
	std::unique_ptr<hylo_plan> plan{new hylo_plan};

	void plan_on(const hylo_robot &robot, const Scene &sc, const hylo_goal &g)
	{
		hylo_planner_config cfg{};
		cfg.robots = &robot;
		cfg.n_robots = 1;
		if (hylo_planner_init(pl.get(), &cfg) != HYLO_OK)
			throw std::runtime_error(std::string("planner: ") + hylo_planner_reason(pl.get()));
		hylo_map_view v = map_view(sc);
		if (hylo_planner_set_map(pl.get(), &v) != HYLO_OK)
			throw std::runtime_error(sc.path + ": " + hylo_planner_reason(pl.get()));
		if (hylo_planner_plan(pl.get(), &g, plan.get()) != HYLO_OK ||
		    plan->outcome != HYLO_FOUND)
			throw std::runtime_error(sc.path + ": no plan: " + std::string(plan->reason.text));
	}
};

std::vector<Waypoint> waypoints(const hylo_plan &p)
{
	std::vector<Waypoint> w(p.n_waypoints);
	for (uint32_t i = 0; i < p.n_waypoints; i++) {
		w[i].mode = p.mode[i];
		w[i].guard = p.guard[i] != 0;
		for (int k = 0; k < 6; k++)
			w[i].state[k] = p.state[i][k];
	}
	return w;
}

std::string sequence(const hylo_plan &p)
{
	std::string s;
	for (uint32_t i = 0; i < p.n_modes; i++)
		s += (i ? " -> " : "") + mode_name(p.mode_sequence[i]);
	return s;
}

TerrainGrid grid_of(const Scene &sc)
{
	TerrainGrid g;
	g.nx = sc.nx;
	g.ny = sc.ny;
	g.resolution_m = sc.resolution_m;
	g.origin_x_m = sc.origin_x_m;
	g.origin_y_m = sc.origin_y_m;
	g.terrain = sc.terrain;
	g.height_m = sc.height_m;
	return g;
}

// ---- study 1: the hybrid double integrator --------------------------------

// Exact edge costs: every edge's BVP solved by the trainer's collocation
// (default options: three T guesses, mesh refinement, CVODE replay). A BVP
// with no converged, replayed solution gets a cost no path will take.
struct ExactCosts {
	const RobotParams *robot = nullptr;
	int jobs = 2;
	double infeasible_cost = 1e6;
	uint64_t solves = 0, failures = 0, skipped = 0;   // skipped: provably infeasible
	double solve_seconds = 0;
};

// True when no trajectory of the mode can join a and b inside its half of
// the phase plane: with |u| <= 1 the state cannot stop before the guard p = 0
// (forward from a), or cannot have come from inside the domain (backward
// from b). di_neg: stopping distance v^2 / 2 both ways. di_pos (v' = u - v):
// forward |v| - ln(1 + |v|) towards p = 0, backward -ln(1 - v) - v away from
// it (v = 1 cannot be reached at all). These edges are skipped without a solve.
bool di_provably_infeasible(hylo_mode mode, const double *a, const double *b)
{
	if (mode == HYLO_MODE_DI_NEG)
		return (a[1] > 0 && a[1] * a[1] / 2 > -a[0] + 1e-9) || (b[1] < 0 && b[1] * b[1] / 2 > -b[0] + 1e-9);
	if (mode == HYLO_MODE_DI_POS) {
		bool fwd = a[1] < 0 && -a[1] - std::log1p(-a[1]) > a[0] + 1e-9;
		bool bwd = b[1] > 0 && (b[1] >= 1 || -std::log1p(-b[1]) - b[1] > b[0] + 1e-9);
		return fwd || bwd;
	}
	return false;
}

hylo_status exact_cost(void *ctx, hylo_mode mode, const hylo_real *tail, const hylo_real (*heads)[HYLO_XS_DIM],
		       uint32_t n, hylo_real *cost, hylo_reason *)
{
	auto *c = static_cast<ExactCosts *>(ctx);
	std::string m = mode_name(mode);
	auto t0 = std::chrono::steady_clock::now();
	std::vector<double> v = parallel_map(n, c->jobs, [&](size_t i) {
		if (di_provably_infeasible(mode, tail, heads[i]))
			return -2.0;
		try {
			Solution s = solve_bvp(m, *c->robot, tail, heads[i], SolveOptions());
			return s.converged ? s.cost : -1.0;
		} catch (const std::exception &) {
			return -1.0;
		}
	});
	c->solve_seconds += seconds_since(t0);
	for (uint32_t i = 0; i < n; i++) {
		if (v[i] == -2.0)
			c->skipped++;
		else
			c->solves++;
		if (v[i] == -1.0 || !(v[i] >= -2.0))
			c->failures++;
		if (!(v[i] >= 0))
			v[i] = c->infeasible_cost;
		cost[i] = v[i];
	}
	return HYLO_OK;
}

hylo_robot di_exact_robot(ExactCosts &costs)
{
	// Lower bound of an edge's cost for the clamp and the A* heuristic:
	// cost >= rho T, and T >= max(|dp|, |dv| / 2) >= distance / sqrt(5) in
	// the phase plane (|v| <= 1, |v'| <= 2).
	double rho = costs.robot->mode("di_neg").at("rho");
	hylo_robot r{};
	r.name = "di";
	r.n_modes = 2;
	const hylo_mode modes[2] = {HYLO_MODE_DI_NEG, HYLO_MODE_DI_POS};
	for (int k = 0; k < 2; k++) {
		r.modes[k].mode = modes[k];
		r.modes[k].cost_fn = exact_cost;
		r.modes[k].cost_ctx = &costs;
		r.modes[k].cost_floor_per_m = rho / std::sqrt(5.0);
	}
	return r;
}

struct DiCase {
	double a[2], b[2];
};

std::string di_study(const Options &opt, std::string &md)
{
	Scene sc = hylo::scene::load("scenes/di.yaml");
	RobotParams di = load_robot(robot_file("di"));
	ExactCosts costs;
	costs.robot = &di;
	costs.jobs = opt.jobs;
	hylo_robot robot = di_exact_robot(costs);
	Planner planner;
	const DiCase cases[2] = {{{0.8, 0.2}, {-0.8, 0.0}}, {{0.7, -0.1}, {-0.5, 0.2}}};
	std::string js = "{\n  \"cases\": [";
	md += "## 1. Hybrid double integrator\n\n"
	      "Edges weighted by exact trajectory optimization: the planner's cost callback solves each "
	      "edge's BVP with the trainer's collocation (three T guesses, mesh refinement, CVODE replay); "
	      "edges that provably cannot stay in their half of the phase plane (the state cannot stop "
	      "before p = 0) are given no cost without a solve. "
	      "Scene `scenes/di.yaml` (spacing " + num(sc.goal.spacing_m) + ", connection radius " +
	      num(sc.goal.connect_radius_m) + "). The reference is the best two-phase cost through a switch "
	      "state `(0, v)`, `v` swept over [-1, 1] every 0.05 and refined by golden-section search.\n\n"
	      "| case | graph path (exact edges) | smoothed | two-phase from naive guess | swept optimum "
	      "(switch v) | smoothed vs swept | edges solved (no solution) |\n|---|---|---|---|---|---|---|\n";
	std::vector<double> swept(2);
	for (int c = 0; c < 2; c++) {
		const DiCase &k = cases[c];
		std::fprintf(stderr, "di case %d: planning with exact edge costs\n", c + 1);
		hylo_goal g = goal_of(sc);
		g.start_mode = k.a[0] > 0 ? HYLO_MODE_DI_POS : HYLO_MODE_DI_NEG;
		g.goal_mode = k.b[0] > 0 ? HYLO_MODE_DI_POS : HYLO_MODE_DI_NEG;
		for (int j = 0; j < 2; j++) {
			g.start[j] = k.a[j];
			g.goal[j] = k.b[j];
		}
		costs.solves = costs.failures = costs.skipped = 0;
		costs.solve_seconds = 0;
		auto t0 = std::chrono::steady_clock::now();
		planner.plan_on(robot, sc, g);
		double plan_s = seconds_since(t0);
		const hylo_plan &p = *planner.plan;
		std::fprintf(stderr, "  graph cost %.6g (%llu edges solved, %.1f s); smoothing\n", p.total_cost,
			     static_cast<unsigned long long>(costs.solves), plan_s);
		MultiPhaseProblem prob = smoothing_problem(di, waypoints(p), grid_of(sc), TakeoffLanding{});
		MultiPhaseSolution sm = solve_multiphase(di, prob, smoothing_solve_options());
		std::fprintf(stderr, "  smoothed %.6g; two-phase from a naive guess and the sweep\n", sm.cost);
		MultiPhaseSolution naive = di_two_phase(di, k.a, k.b, 0.0);   // the naive guess: through (0, 0)
		auto ref = di_swept_optimum(di, k.a, k.b);
		swept[static_cast<size_t>(c)] = ref.first;
		double rel = sm.converged ? (sm.cost - ref.first) / ref.first : NAN;
		char row[512];
		std::snprintf(row, sizeof row,
			      "| (%g, %g) -> (%g, %g) | %.6f | %s | %s | %.6f (%.4f) | %+.3f%% | %llu (%llu) |\n",
			      k.a[0], k.a[1], k.b[0], k.b[1], p.total_cost,
			      sm.converged ? num(sm.cost).c_str() : "failed",
			      naive.converged ? num(naive.cost).c_str() : "failed", ref.first, ref.second,
			      100 * rel, static_cast<unsigned long long>(costs.solves),
			      static_cast<unsigned long long>(costs.failures));
		md += row;
		js += std::string(c ? "," : "") + "\n    {\"start\": [" + num(k.a[0]) + ", " + num(k.a[1]) +
		      "], \"goal\": [" + num(k.b[0]) + ", " + num(k.b[1]) + "], \"spacing\": " +
		      num(sc.goal.spacing_m) + ", \"connect_radius\": " + num(sc.goal.connect_radius_m) +
		      ",\n     \"graph_cost\": " + num(p.total_cost) + ", \"graph_sequence\": \"" + sequence(p) +
		      "\", \"waypoints\": " + std::to_string(p.n_waypoints) + ", \"nodes\": " +
		      std::to_string(p.n_nodes) + ", \"edges_solved\": " + std::to_string(costs.solves) +
		      ", \"edges_failed\": " + std::to_string(costs.failures) + ", \"edges_skipped\": " +
		      std::to_string(costs.skipped) + ", \"plan_s\": " + num(plan_s) +
		      ",\n     \"smoothed_cost\": " + (sm.converged ? num(sm.cost) : "null") +
		      ", \"smoothed_replay_error\": " + num(sm.replay_error) + ", \"smoothed_T\": " + num(sm.T) +
		      ",\n     \"naive_two_phase_cost\": " + (naive.converged ? num(naive.cost) : "null") +
		      ", \"swept_optimum\": " + num(ref.first) + ", \"swept_switch_v\": " + num(ref.second) +
		      ", \"smoothed_vs_swept\": " + num(rel) + "}";
	}
	js += "\n  ],\n";

	// Convergence (the paper's Fig. 10): case 1 on ten spacings. With exact
	// edge costs a longer edge is never worse than a chain through fixed
	// states, so the radius must shrink slower than the spacing for the cost
	// to converge (as PRM*'s does): r = 0.6 sqrt(s / 0.2), at least 0.3.
	std::vector<double> spacings;
	for (int i = 0; i < 10; i++)
		spacings.push_back(0.5 - 0.05 * i);
	if (opt.quick)
		spacings = {0.5, 0.3, 0.2};
	md += "\nConvergence of the graph cost with the sample spacing (case 1, the paper's Fig. 10; "
	      "connection radius max(0.3, 0.6 sqrt(spacing / 0.2)); figure `results/di_convergence.png`):\n\n"
	      "| spacing | graph cost | above swept optimum | nodes | edges solved | seconds |\n"
	      "|---|---|---|---|---|---|\n";
	js += "  \"convergence\": {\"case\": 1, \"swept_optimum\": " + num(swept[0]) + ", \"points\": [";
	for (size_t i = 0; i < spacings.size(); i++) {
		const DiCase &k = cases[0];
		hylo_goal g = goal_of(sc);
		g.start_mode = HYLO_MODE_DI_POS;
		g.goal_mode = HYLO_MODE_DI_NEG;
		for (int j = 0; j < 2; j++) {
			g.start[j] = k.a[j];
			g.goal[j] = k.b[j];
		}
		g.spacing = g.guard_spacing = spacings[i];
		g.connect_radius = std::max(0.3, 0.6 * std::sqrt(spacings[i] / 0.2));
		costs.solves = costs.failures = costs.skipped = 0;
		auto t0 = std::chrono::steady_clock::now();
		planner.plan_on(robot, sc, g);
		double s = seconds_since(t0);
		const hylo_plan &p = *planner.plan;
		std::fprintf(stderr, "di convergence: spacing %.2f: %.6g (%u nodes, %llu edges solved, %.0f s)\n",
			     spacings[i], p.total_cost, p.n_nodes, static_cast<unsigned long long>(costs.solves), s);
		char row[256];
		std::snprintf(row, sizeof row, "| %.2f | %.6f | %+.2f%% | %u | %llu | %.0f |\n", spacings[i],
			      p.total_cost, 100 * (p.total_cost - swept[0]) / swept[0], p.n_nodes,
			      static_cast<unsigned long long>(costs.solves), s);
		md += row;
		js += std::string(i ? "," : "") + "\n    {\"spacing\": " + num(spacings[i]) + ", \"connect_radius\": " +
		      num(g.connect_radius) + ", \"graph_cost\": " + num(p.total_cost) + ", \"nodes\": " +
		      std::to_string(p.n_nodes) + ", \"edges_solved\": " + std::to_string(costs.solves) +
		      ", \"edges_failed\": " + std::to_string(costs.failures) + ", \"edges_skipped\": " +
		      std::to_string(costs.skipped) + ", \"seconds\": " + num(s) + "}";
	}
	js += "\n  ]}\n}";
	return js;
}

// ---- study 2: Ambot, energy-optimal vs shortest-distance -----------------

// Edge length, times 1 + 1% of the headings' misalignment with the edge
// (0 aligned .. 1 opposite, mean of both ends): lengths decide, and among
// equally short paths the one whose nodes face along the path wins, instead
// of one that moves sideways (which no skid-steer trajectory can follow).
hylo_status length_cost(void *, hylo_mode, const hylo_real *tail, const hylo_real (*heads)[HYLO_XS_DIM],
			uint32_t n, hylo_real *cost, hylo_reason *)
{
	for (uint32_t i = 0; i < n; i++) {
		double dx = heads[i][0] - tail[0], dy = heads[i][1] - tail[1], d = std::hypot(dx, dy);
		double dir = std::atan2(dy, dx);
		double mis = d > 0 ? (2 - std::cos(tail[3] - dir) - std::cos(heads[i][3] - dir)) / 4 : 0;
		cost[i] = d * (1 + 0.01 * mis);
	}
	return HYLO_OK;
}

// Length travelled in water: plan edges in marine mode.
double water_length(const hylo_plan &p)
{
	double w = 0;
	for (uint32_t i = 1; i < p.n_waypoints; i++)
		if (p.mode[i] == HYLO_MODE_MARINE && p.mode[i - 1] == HYLO_MODE_MARINE)
			w += std::hypot(p.state[i][0] - p.state[i - 1][0], p.state[i][1] - p.state[i - 1][1]);
	return w;
}

double path_length(const hylo_plan &p)
{
	double w = 0;
	for (uint32_t i = 1; i < p.n_waypoints; i++)
		if (p.mode[i] == p.mode[i - 1])
			w += std::hypot(p.state[i][0] - p.state[i - 1][0], p.state[i][1] - p.state[i - 1][1]);
	return w;
}

// The SVR's prediction of a plan's edges, clamped as the planner clamps them.
double predicted_cost(const hylo_robot &r, const hylo_plan &p)
{
	double total = 0;
	for (uint32_t i = 1; i < p.n_waypoints; i++) {
		if (p.mode[i] != p.mode[i - 1])
			continue;
		const hylo_mode_model *mm = nullptr;
		for (uint32_t k = 0; k < r.n_modes; k++)
			if (r.modes[k].mode == p.mode[i])
				mm = &r.modes[k];
		hylo_mode mode = static_cast<hylo_mode>(p.mode[i]);
		double f[HYLO_MAX_FEATURES];
		hylo_features(mode, p.state[i - 1], p.state[i], f);
		double c = hylo_svr_predict(mm->model, f);
		double d = std::hypot(p.state[i][0] - p.state[i - 1][0], p.state[i][1] - p.state[i - 1][1]);
		total += std::max(c, hylo_svr_cost_floor(mm->model, d));
	}
	return total;
}

struct PlanResult {
	std::string sequence;
	double predicted = 0, exact = 0, smoothed = NAN, smoothed_error = NAN, length = 0, water = 0,
	       smoothed_water = 0;
	uint32_t waypoints = 0;
	std::string path;   // JSON [[mode, x, y, v, theta], ...]
};

// full: also the exact graph-path cost and the smoothed trajectory (minutes).
PlanResult evaluate(const RobotParams &ambot, const hylo_robot &svr_robot, const hylo_plan &p, const Scene &sc,
		    bool full)
{
	PlanResult r;
	r.sequence = sequence(p);
	r.waypoints = p.n_waypoints;
	for (uint32_t i = 0; i < p.n_waypoints; i++)
		r.path += std::string(i ? ", " : "") + "[\"" + mode_name(p.mode[i]) + "\", " + num(p.state[i][0]) +
			  ", " + num(p.state[i][1]) + ", " + num(p.state[i][2]) + ", " + num(p.state[i][3]) + "]";
	r.predicted = predicted_cost(svr_robot, p);
	r.length = path_length(p);
	r.water = water_length(p);
	r.exact = r.smoothed_water = NAN;
	if (!full)
		return r;
	r.smoothed_water = 0;
	std::vector<Waypoint> w = waypoints(p);
	r.exact = graph_path_cost(ambot, w, TakeoffLanding{}, SolveOptions());
	MultiPhaseProblem prob = smoothing_problem(ambot, w, grid_of(sc), TakeoffLanding{});
	MultiPhaseSolution sm = solve_multiphase(ambot, prob, smoothing_solve_options());
	if (sm.converged) {
		r.smoothed = sm.cost;
		r.smoothed_error = sm.replay_error;
		for (size_t k = 0; k < sm.phases.size(); k++) {
			if (sm.modes[k] != "marine")
				continue;
			const Trajectory &t = sm.phases[k].traj;
			size_t nx = static_cast<size_t>(t.nx);
			for (size_t i = 1; i < t.t.size(); i++)
				r.smoothed_water += std::hypot(t.x[i * nx] - t.x[(i - 1) * nx],
							       t.x[i * nx + 1] - t.x[(i - 1) * nx + 1]);
		}
	}
	return r;
}

std::string plan_json(const PlanResult &r)
{
	return "{\"sequence\": \"" + r.sequence + "\", \"waypoints\": " + std::to_string(r.waypoints) +
	       ", \"predicted_j\": " + num(r.predicted) + ", \"graph_path_exact_j\": " + num(r.exact) +
	       ", \"smoothed_j\": " + num(r.smoothed) + ", \"smoothed_replay_error\": " + num(r.smoothed_error) +
	       ", \"length_m\": " + num(r.length) + ", \"water_m\": " + num(r.water) +
	       ", \"smoothed_water_m\": " + num(r.smoothed_water) + ",\n    \"path\": [" + r.path + "]}";
}

std::string ambot_study(const Options &opt, std::string &md)
{
	RobotParams ambot = load_robot(robot_file("ambot"));
	hylo_robot robots[HYLO_MAX_ROBOTS];
	hylo_reason reason;
	uint32_t n = hylo_registry_robots(robots, HYLO_MAX_ROBOTS, &reason);
	const hylo_robot *energy = nullptr;
	for (uint32_t i = 0; i < n; i++)
		if (std::string(robots[i].name) == "ambot")
			energy = &robots[i];
	if (!energy || !energy->modes[0].model || !energy->modes[1].model)
		throw std::runtime_error("ambot: no committed models in onboard/models/");
	// Same roadmap and edges (the feasibility classifiers drop the same
	// edges); each edge weighted by its length instead of its energy.
	// Admissible: cost >= length (floor 1 per metre).
	hylo_robot shortest = *energy;
	for (uint32_t k = 0; k < shortest.n_modes; k++) {
		shortest.modes[k].model = nullptr;
		shortest.modes[k].cost_fn = length_cost;
		shortest.modes[k].cost_ctx = nullptr;
		shortest.modes[k].cost_floor_per_m = 1;
		shortest.modes[k].cost_floor_j = 0;
		shortest.modes[k].max_distance_m = energy->modes[k].model->max_distance_m;
	}
	md += "\n## 2. Ambot: energy-optimal plan vs shortest-distance plan\n\n"
	      "Both plans on the same roadmap (same samples, edges and feasibility classifier); the "
	      "energy plan weights edges by the committed SVR models, the shortest plan by length (ties "
	      "between equally short paths broken, within 1%, towards nodes that face along the path). "
	      "Energies: the SVR's prediction of the plan's edges, the exact cost of the graph path "
	      "(every edge solved on its own by collocation) and the smoothed trajectory of the plan's "
	      "mode sequence (multi-phase collocation, CVODE replay).\n\n"
	      "| scene | plan | sequence | predicted [J] | graph path, exact [J] | smoothed [J] | length [m] | "
	      "water [m] (smoothed) |\n|---|---|---|---|---|---|---|---|\n";
	std::string js = "[";
	const char *scenes[] = {"river_crossing", "island_crossing"};
	for (int s = 0; s < 2; s++) {
		Scene sc = hylo::scene::load(std::string("scenes/") + scenes[s] + ".yaml");
		hylo_goal g = goal_of(sc);
		Planner pe, ps;
		pe.plan_on(*energy, sc, g);
		ps.plan_on(shortest, sc, g);
		std::fprintf(stderr, "ambot %s: evaluating the energy and the shortest plan (exact edges, smoothing)\n",
			     scenes[s]);
		PlanResult e = evaluate(ambot, *energy, *pe.plan, sc, !opt.quick);
		PlanResult d = evaluate(ambot, *energy, *ps.plan, sc, !opt.quick);
		for (int k = 0; k < 2; k++) {
			const PlanResult &r = k ? d : e;
			char row[512];
			std::snprintf(row, sizeof row, "| %s | %s | %s | %.1f | %.1f | %.1f | %.1f | %.1f (%.1f) |\n",
				      k ? "" : scenes[s], k ? "shortest" : "energy", r.sequence.c_str(), r.predicted,
				      r.exact, r.smoothed, r.length, r.water, r.smoothed_water);
			md += row;
		}
		js += std::string(s ? "," : "") + "\n  {\"scene\": \"" + scenes[s] + "\", \"energy_plan\": " +
		      plan_json(e) + ",\n   \"shortest_plan\": " + plan_json(d) + "}";
	}
	return js + "\n]";
}

void write_atomically(const std::string &path, const std::string &text)
{
	std::string tmp = path + ".tmp";
	std::ofstream f(tmp, std::ios::binary);
	f << text;
	f.close();
	if (!f || std::rename(tmp.c_str(), path.c_str()) != 0)
		throw std::runtime_error(path + ": cannot write");
}

int run(int argc, char **argv)
{
	Options opt;
	for (int i = 1; i < argc; i++) {
		std::string a = argv[i];
		auto value = [&]() -> std::string {
			if (i + 1 >= argc)
				throw std::invalid_argument(a + " needs a value");
			return argv[++i];
		};
		if (a == "--help" || a == "-h") {
			std::fputs(kUsage, stdout);
			return 0;
		} else if (a == "--study") {
			opt.study = value();
			if (opt.study != "di" && opt.study != "ambot" && opt.study != "all")
				throw std::invalid_argument("--study: unknown study '" + opt.study + "' (di, ambot, all)");
		} else if (a == "--out") {
			opt.out = value();
		} else if (a == "--jobs") {
			opt.jobs = std::atoi(value().c_str());
			if (opt.jobs < 1)
				throw std::invalid_argument("--jobs: needs a positive integer");
		} else if (a == "--quick") {
			opt.quick = true;
		} else {
			throw std::invalid_argument("unknown argument '" + a + "'");
		}
	}
	// Fail now, not after an hour of solving.
	if (access(opt.out.c_str(), W_OK) != 0)
		throw std::runtime_error(opt.out + ": cannot write there (" + std::strerror(errno) + ")");
	auto t0 = std::chrono::steady_clock::now();
	std::string md = "# hylo: the paper's case studies, measured\n\n"
			 "Written by `make casestudies` (tools/casestudies/); every number is also in "
			 "`results.json`.\n\n";
	std::string js = "{";
	if (opt.study == "di" || opt.study == "all")
		js += "\n\"di\": " + di_study(opt, md);
	if (opt.study == "ambot" || opt.study == "all")
		js += std::string(js.size() > 1 ? "," : "") + "\n\"ambot\": " + ambot_study(opt, md);
	md += "\n## 3. Drivocopter: fixed mode sequences against hylo (the paper's Table I)\n\n"
	      "Not measured yet. Both Drivocopter models are committed and the planner node plans "
	      "every chasm scene (`scenes/chasm_*.yaml`; the README's Case studies section gives "
	      "the plans), but the fixed-sequence baselines and the smoothing of such plans are not"
	      " built: their flight phases run 30-150 m, hundreds of 20 ms collocation segments "
	      "each, and no such multi-phase problem has been solved here yet. The takeoff/landing "
	      "problems they use are in place.\n";
	js += ",\n\"seconds\": " + num(seconds_since(t0)) + "\n}\n";
	write_atomically(opt.out + "/results.json", js);
	write_atomically(opt.out + "/results.md", md);
	std::fprintf(stderr, "wrote %s/results.json and %s/results.md (%.0f s)\n", opt.out.c_str(), opt.out.c_str(),
		     seconds_since(t0));
	return 0;
}

}  // namespace

int main(int argc, char **argv)
{
	try {
		return run(argc, argv);
	} catch (const std::invalid_argument &e) {
		std::fprintf(stderr, "hylo-casestudies: %s\n%s", e.what(), kUsage);
		return 2;
	} catch (const std::exception &e) {
		std::fprintf(stderr, "hylo-casestudies: %s\n", e.what());
		return 1;
	}
}
