// hylo-casestudies: the paper's case studies, measured (issue 6; make casestudies).
//   di     the hybrid double integrator: edges weighted by exact trajectory
//          optimization (the planner's cost callback calling the trainer's
//          collocation), graph path, smoothed path, a two-phase optimization
//          from a naive guess, the swept two-phase optimum; and the
//          convergence of the graph cost over ten Poisson-disc spacings.
//   ambot  river and island crossing: the energy-optimal plan (committed SVR
//          models) against the shortest-distance plan on the same graph.
//   drivocopter  the paper's Table I: on each chasm scene the fixed mode
//          sequences F ... DFDFD, each one multi-phase optimization (the
//          smoother's, on a plan of that sequence), against hylo's plan, its
//          predicted cost and its smoothed cost. With --two-chasms, scenes
//          nobody tuned on: the 30 m chasm made into two, every route
//          (where it lands and drives) against hylo's alternatives.
// Each study writes OUT/results/<study>.{md,json}; OUT/results.json (every
// number) and OUT/results.md (the tables) are put together from those parts.
// tools/casestudies/plot.py draws the convergence figure from the JSON.
#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <sys/stat.h>
#include <unistd.h>
#include <vector>

#include "hylo/features.h"
#include "hylo/clearance.h"
#include "hylo/planner.h"
#include "node/registry.h"
#include "tools/casestudies/chasm.hpp"
#include "tools/scene/planner_view.hpp"
#include "tools/scene/scene.hpp"
#include "trainer/clearance.hpp"
#include "trainer/cli.hpp"
#include "trainer/collocation.hpp"
#include "trainer/files.hpp"
#include "trainer/numerics.hpp"
#include "trainer/params.hpp"
#include "trainer/processes.hpp"
#include "trainer/sha256.hpp"
#include "trainer/fallbacks.hpp"
#include "trainer/smooth_alternatives.hpp"
#include "trainer/smoother.hpp"
#include "trainer/svr_export.hpp"
#include "trainer/switching.hpp"

namespace {

using namespace hylo::trainer;
using hylo::casestudies::chasms;
using hylo::casestudies::letters;
using hylo::casestudies::Profile;
using hylo::casestudies::profile_of;
using hylo::casestudies::route_name;
using hylo::casestudies::route_of_plan;
using hylo::casestudies::sequence_plan;
using hylo::casestudies::widened;
using hylo::scene::Scene;

const char *kUsage =
	"usage: hylo-casestudies [--study di|ambot|drivocopter|all] [--out DIR] [--jobs N] [--quick]\n"
	"                        [--widths W,... | --two-chasms W1,P,W2 ...]\n"
	"  The paper's case studies (docs/results.md explains each).\n"
	"  --study S   which study to run (default all); the others' last results\n"
	"              (DIR/results/<study>.{md,json}) are kept in the combined files\n"
	"  --out DIR   where results.json and results.md go (default docs)\n"
	"  --jobs N    worker processes for exact edge costs and solves (default 2)\n"
	"  --quick     a check: the DI convergence on 3 spacings instead of 10, Ambot\n"
	"              plans without exact edge costs or smoothing, the Drivocopter\n"
	"              sequences on the 30 m chasm from one switch placement, no crossover\n"
	"  --widths W,... the Drivocopter study on these chasm widths [m, >= 30] instead of\n"
	"              30-110: a committed scene where there is one, else the 30 m chasm\n"
	"              widened (floor inserted at its middle); no crossover. For scenes\n"
	"              nobody tuned on: write them to another --out\n"
	"  --two-chasms W1,P,W2  the Drivocopter study on two chasms instead: the 30 m chasm\n"
	"              made into a floor W1 m wide [5-400], a middle platform P m long [2-400]\n"
	"              and a floor W2 m wide [5-400] (whole metres); repeat the option for\n"
	"              more scenes. Every route that drives on the start and goal platforms\n"
	"              (landing on any of floor 1, the middle platform, floor 2: 8 routes)\n"
	"              against hylo's alternatives; needs an --out other than docs\n"
	"  The Drivocopter study ends by locating the crossover from flying over to driving\n"
	"  through to the metre (the two sequences solved on chasms widened in between).\n"
	"  It logs each finished solve to DIR/results/drivocopter.solves\n"
	"  and a rerun takes them from there (an interrupted run resumes) when they were\n"
	"  made by the same sources (a hash of the trainer, the library, the models and\n"
	"  the study is part of each record's key); others are solved again and dropped\n"
	"  from the log.\n"
	"  --sources-sha  print that hash and exit\n";

struct Options {
	std::string study = "all", out = "docs";
	int jobs = 2;
	bool quick = false;
	std::vector<int> widths;   // the Drivocopter study's chasms; empty: the committed 30-110 m
	std::vector<std::vector<int>> two_chasms;   // --two-chasms: {W1, P, W2} per scene [m]
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

// f(0) ... f(n-1), each in a fresh process forked from this one, `jobs` at a
// time (processes.hpp says why). Records in index order; an item whose process
// died stays NaN.
std::vector<std::vector<double>> parallel_records(size_t n, size_t width, int jobs,
						  const std::function<std::vector<double>(size_t)> &f)
{
	std::vector<std::string> raw = fork_each(n, jobs, [&](size_t i) {
		std::vector<double> v = f(i);
		v.resize(width, NAN);
		return std::string(reinterpret_cast<const char *>(v.data()), width * sizeof(double));
	}, width * sizeof(double));
	std::vector<std::vector<double>> out(n, std::vector<double>(width, NAN));
	for (size_t i = 0; i < n; i++)
		if (raw[i].size() == width * sizeof(double))
			std::memcpy(out[i].data(), raw[i].data(), raw[i].size());
	return out;
}

std::vector<double> parallel_map(size_t n, int jobs, const std::function<double(size_t)> &f)
{
	auto rec = parallel_records(n, 1, jobs, [&](size_t i) { return std::vector<double>{f(i)}; });
	std::vector<double> out(n);
	for (size_t i = 0; i < n; i++)
		out[i] = rec[i][0];
	return out;
}

// ---- planner set-up from a scene -----------------------------------------

using hylo::scene::goal_of;
using hylo::scene::map_view;

// One planner workspace (allocated for the robot it plans for) planning for one robot.
struct Planner {
	std::vector<double> mem;   // hylo_planner_size bytes, aligned for double
	std::unique_ptr<hylo_plan> plan{new hylo_plan};

	hylo_planner *pl() { return reinterpret_cast<hylo_planner *>(mem.data()); }

	void plan_on(const hylo_robot &robot, const Scene &sc, const hylo_goal &g)
	{
		hylo_planner_config cfg{};
		cfg.robots = &robot;
		cfg.n_robots = 1;
		size_t size = hylo_planner_size(&cfg);
		mem.assign(size / sizeof(double) + 1, 0.0);
		if (hylo_planner_init(pl(), size, &cfg) != HYLO_OK)
			throw std::runtime_error(std::string("planner: ") + hylo_planner_reason(pl()));
		hylo_map_view v = map_view(sc);
		if (hylo_planner_set_map(pl(), &v) != HYLO_OK)
			throw std::runtime_error(sc.path + ": " + hylo_planner_reason(pl()));
		if (hylo_planner_plan(pl(), &g, plan.get()) != HYLO_OK ||
		    plan->outcome != HYLO_FOUND)
			throw std::runtime_error(sc.path + ": no plan: " + std::string(plan->reason.text));
	}
};

// One alternative of a plan: the best graph path of one mode sequence.
struct Alternative {
	std::vector<Waypoint> path;
	std::string letters;   // "DFD" (Drivocopter) or the sequence's mode names
	double predicted = 0;
	std::unique_ptr<hylo_plan> plan;
};

std::vector<Waypoint> waypoints(const hylo_plan &p);
std::string letters(const hylo_plan &p);

// The planner's alternatives after plan_on with goal.alternatives = K, graph
// rank order (the first is the plan).
std::vector<Alternative> alternatives_of(Planner &pl)
{
	std::vector<Alternative> out;
	for (uint32_t k = 0; k < pl.plan->n_alternatives; k++) {
		Alternative a;
		a.plan.reset(new hylo_plan(*pl.plan));
		if (hylo_planner_alternative(pl.pl(), k, a.plan.get()) != HYLO_OK)
			throw std::runtime_error(std::string("alternative: ") + hylo_planner_reason(pl.pl()));
		a.path = waypoints(*a.plan);
		a.letters = letters(*a.plan);
		a.predicted = a.plan->total_cost;
		out.push_back(std::move(a));
	}
	return out;
}

std::vector<Waypoint> waypoints(const hylo_plan &p)
{
	std::vector<Waypoint> w(p.n_waypoints);
	for (uint32_t i = 0; i < p.n_waypoints; i++) {
		w[i].mode = static_cast<hylo_mode>(p.mode[i]);
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
	auto t0 = std::chrono::steady_clock::now();
	std::vector<double> v = parallel_map(n, c->jobs, [&](size_t i) {
		if (di_provably_infeasible(mode, tail, heads[i]))
			return -2.0;
		try {
			// The turn the model would price (a half turn towards the goal),
			// not the headings' difference, which may go the long way round.
			double head[HYLO_XS_DIM];
			std::copy_n(heads[i], HYLO_XS_DIM, head);
			if (hylo_mode_describe(mode)->planar)
				head[3] = tail[3] + priced_turn(mode, tail, heads[i]);
			Solution s = solve_bvp(mode, *c->robot, tail, head, SolveOptions());
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
	double rho = costs.robot->mode(HYLO_MODE_DI_NEG).at("rho");
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
		g.alternatives = 1;
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
		MultiPhaseProblem prob = smoothing_problem(di, waypoints(p), terrain_grid(sc), TakeoffLanding{});
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
		g.alternatives = 1;
		g.start_mode = HYLO_MODE_DI_POS;
		g.goal_mode = HYLO_MODE_DI_NEG;
		for (int j = 0; j < 2; j++) {
			g.start[j] = k.a[j];
			g.goal[j] = k.b[j];
		}
		g.sampling.spacing = g.sampling.guard_spacing = spacings[i];
		g.sampling.connect_radius = std::max(0.3, 0.6 * std::sqrt(spacings[i] / 0.2));
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
		      num(g.sampling.connect_radius) + ", \"graph_cost\": " + num(p.total_cost) + ", \"nodes\": " +
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

// A smoothed trajectory's clearance by the check hylo-smooth publishes
// (trainer/clearance.hpp), with the default margin: its safe rule chooses
// among alternatives.
ClearanceCheck least_clearance(const MultiPhaseSolution &s, const Scene &sc, const RobotParams &robot)
{
	return check_clearance(s, terrain_grid(sc), robot.body_radius_m, HYLO_DEFAULT_MARGIN_M);
}

// Its least clearance beyond the robot's body as the tables print it;
// -infinity when a point leaves its mode's domain.
double clearance_m(const ClearanceCheck &c)
{
	return c.outside_phase >= 0 ? -INFINITY : c.min_clearance_m;
}

// What the fixed sequences' switch points keep from the walls' edges: what
// the smoother's corridors keep (the body, the default margin and the pad),
// so the sequences are solved under the margins hylo's plans keep.
double switch_clearance(const RobotParams &robot)
{
	return robot.body_radius_m + HYLO_DEFAULT_MARGIN_M + SmoothOptions().corridor_pad_m;
}

struct PlanResult {
	std::string sequence;
	double predicted = 0, exact = 0, smoothed = NAN, smoothed_error = NAN, length = 0, water = 0,
	       smoothed_water = 0;
	std::optional<ClearanceCheck> clearance;   // of the smoothed trajectory, when there is one
	uint32_t waypoints = 0;
	std::string path;   // JSON [[mode, x, y, v, theta], ...]

	// The least clearance beyond the body [m]; NaN when not smoothed.
	double least_clearance_m() const { return clearance ? clearance_m(*clearance) : NAN; }
	bool safe() const { return clearance && clearance->safe; }
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
	MultiPhaseProblem prob = smoothing_problem(ambot, w, terrain_grid(sc), TakeoffLanding{});
	MultiPhaseSolution sm = solve_multiphase(ambot, prob, smoothing_solve_options());
	if (sm.converged) {
		r.smoothed = sm.cost;
		r.smoothed_error = sm.replay_error;
		r.clearance = least_clearance(sm, sc, ambot);
		for (size_t k = 0; k < sm.phases.size(); k++) {
			if (sm.modes[k] != HYLO_MODE_MARINE)
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
	       ", \"smoothed_water_m\": " + num(r.smoothed_water) + ", \"smoothed_min_clearance_m\": " +
	       num(r.least_clearance_m()) + ",\n    \"path\": [" + r.path + "]}";
}

// The robot with its two committed models (onboard/models/, the registry).
hylo_robot committed_robot(const std::string &name)
{
	hylo_robot robots[HYLO_MAX_ROBOTS];
	hylo_reason reason;
	uint32_t n = hylo_registry_robots(robots, HYLO_MAX_ROBOTS, &reason);
	for (uint32_t i = 0; i < n; i++)
		if (robots[i].name == name && robots[i].modes[0].model && robots[i].modes[1].model)
			return robots[i];
	throw std::runtime_error(name + ": no committed models in onboard/models/");
}

// The energy plan's alternatives on the Ambot scenes.
constexpr uint32_t kAmbotAlternatives = 3;

std::string ambot_study(const Options &opt, std::string &md)
{
	RobotParams ambot = load_robot(robot_file("ambot"));
	const hylo_robot energy_robot = committed_robot("ambot");
	const hylo_robot *energy = &energy_robot;
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
	      "mode sequence (multi-phase collocation, CVODE replay). Below them the energy plan's "
	      "alternatives (goal.alternatives = " + std::to_string(kAmbotAlternatives) + ": the best graph "
	      "path of each of the next cheapest distinct mode sequences within 1.25 times the plan's "
	      "prediction), smoothed as `hylo-smooth` does (its fallback chain; the step named when not the "
	      "full optimization), without the exact graph-path cost; hylo's result is the cheapest smoothed "
	      "of the energy plan and its alternatives.\n\n"
	      "Least clearance: the smoothed trajectory's smallest distance between Ambot's body (0.35 m) and "
	      "a hazard (docs/smoothing.md, \"Clearance\"; margin " + num(HYLO_DEFAULT_MARGIN_M) + " m, at most 2.1 "
	      "reported), -inf where it leaves its domain.\n\n"
	      "| scene | plan | sequence | predicted [J] | graph path, exact [J] | smoothed [J] | length [m] | "
	      "water [m] (smoothed) | least clearance [m] |\n|---|---|---|---|---|---|---|---|---|\n";
	std::string js = "[";
	const char *scenes[] = {"river_crossing", "island_crossing"};
	for (int s = 0; s < 2; s++) {
		Scene sc = hylo::scene::load(std::string("scenes/") + scenes[s] + ".yaml");
		hylo_goal g = goal_of(sc);
		Planner pe, ps;
		g.alternatives = 1;
		ps.plan_on(shortest, sc, g);
		g.alternatives = kAmbotAlternatives;
		pe.plan_on(*energy, sc, g);
		const std::vector<Alternative> alts = alternatives_of(pe);
		std::fprintf(stderr, "ambot %s: evaluating the energy and the shortest plan (exact edges, smoothing)\n",
			     scenes[s]);
		PlanResult e = evaluate(ambot, *energy, *pe.plan, sc, !opt.quick);
		PlanResult d = evaluate(ambot, *energy, *ps.plan, sc, !opt.quick);
		for (int k = 0; k < 2; k++) {
			const PlanResult &r = k ? d : e;
			char row[512];
			std::snprintf(row, sizeof row, "| %s | %s | %s | %.1f | %.1f | %.1f | %.1f | %.1f (%.1f) | %.2f |\n",
				      k ? "" : scenes[s], k ? "shortest" : "energy", r.sequence.c_str(), r.predicted,
				      r.exact, r.smoothed, r.length, r.water, r.smoothed_water, r.least_clearance_m());
			md += row;
		}
		// The energy plan's alternatives, smoothed as hylo-smooth does.
		std::string aj;
		// hylo's result as hylo-smooth chooses it (choose_alternative): the
		// cheapest safe trajectory of the plan and its alternatives.
		std::vector<AlternativeOutcome> candidates(1);
		candidates[0].result.ok = std::isfinite(e.smoothed);
		candidates[0].result.solution.cost = e.smoothed;
		candidates[0].clearance.safe = e.safe();
		for (size_t k = 1; k < alts.size(); k++) {
			PlanResult a = evaluate(ambot, *energy, *alts[k].plan, sc, false);
			std::string how = "";
			if (!opt.quick) {
				SmoothResult sm = smooth_with_fallbacks(ambot, alts[k].path, terrain_grid(sc), TakeoffLanding{},
									SmoothOptions());
				if (sm.ok) {
					a.smoothed = sm.solution.cost;
					a.smoothed_error = sm.solution.replay_error;
					a.clearance = least_clearance(sm.solution, sc, ambot);
					if (sm.method != SmoothMethod::Full)
						how = std::string(" (") + method_name(sm.method) + ")";
				}
			}
			AlternativeOutcome o;
			o.result.ok = std::isfinite(a.smoothed);
			o.result.solution.cost = a.smoothed;
			o.clearance.safe = a.safe();
			candidates.push_back(std::move(o));
			char row[512];
			std::snprintf(row, sizeof row, "| | alternative %zu | %s | %.1f | | %.1f%s | %.1f | %.1f | %.2f |\n",
				      k + 1, a.sequence.c_str(), a.predicted, a.smoothed, how.c_str(), a.length, a.water,
				      a.least_clearance_m());
			md += row;
			aj += std::string(k > 1 ? ", " : "") + "{\"rank\": " + std::to_string(k + 1) +
			      ", \"sequence\": \"" + a.sequence + "\", \"predicted_j\": " + num(a.predicted) +
			      ", \"smoothed_j\": " + num(a.smoothed) + ", \"method\": \"" +
			      (how.empty() ? "full" : how.substr(2, how.size() - 3)) + "\", \"length_m\": " +
			      num(a.length) + ", \"water_m\": " + num(a.water) + ", \"min_clearance_m\": " +
			      num(a.least_clearance_m()) + "}";
		}
		const int chosen = choose_alternative(candidates);
		const size_t best = chosen > 0 ? static_cast<size_t>(chosen) : 0;   // graph rank - 1 of hylo's result
		const double best_j = candidates[best].result.solution.cost;
		if (!opt.quick) {
			char row[256];
			std::snprintf(row, sizeof row, "| | **hylo** | %s | | | **%.1f** (rank %zu) | | | |\n",
				      sequence(best ? *alts[best].plan : *pe.plan).c_str(), best_j, best + 1);
			md += row;
		}
		js += std::string(s ? "," : "") + "\n  {\"scene\": \"" + scenes[s] + "\", \"energy_plan\": " +
		      plan_json(e) + ",\n   \"shortest_plan\": " + plan_json(d) + ",\n   \"alternatives\": [" + aj +
		      "],\n   \"result_rank\": " + std::to_string(best + 1) + ", \"result_j\": " + num(best_j) + "}";
	}
	return js + "\n]";
}

// ---- study 3: Drivocopter, fixed mode sequences (the paper's Table I) -----

// "DFDFD" from a plan's mode sequence.
std::string letters(const hylo_plan &p)
{
	std::string s;
	for (uint32_t i = 0; i < p.n_modes; i++)
		s += p.mode_sequence[i] == HYLO_MODE_FLIGHT ? 'F' : 'D';
	return s;
}

// One smoothing solve of a plan: {cost, T, replay error, least clearance, seconds,
// switch-point x...}; cost NaN when it failed.
std::vector<double> smooth_record(const RobotParams &robot, const std::vector<Waypoint> &plan, const Scene &sc,
				  const TakeoffLanding &tl)
{
	std::vector<double> r(5, NAN);
	try {
		SmoothOptions so;
		so.guard_half_length_m = 1e3;   // the whole platform or floor
		MultiPhaseSolution s = smooth_plan(robot, plan, terrain_grid(sc), tl, so, {1.0});
		r[4] = s.solve_seconds;
		if (!s.converged)
			return r;
		r[0] = s.cost;
		r[1] = s.T;
		r[2] = s.replay_error;
		r[3] = clearance_m(least_clearance(s, sc, robot));
		for (size_t k = 0; k + 1 < s.phases.size(); k++)
			if (s.modes[k] != s.modes[k + 1]) {
				const Trajectory &t = s.phases[k].traj;
				r.push_back(t.x[(t.t.size() - 1) * static_cast<size_t>(t.nx)]);
			}
	} catch (const std::exception &e) {
		std::fprintf(stderr, "  smoothing failed: %s\n", e.what());
	}
	return r;
}

// The hash of the sources this build's solves depend on (mk/casestudies.mk).
#ifndef HYLO_SOURCES_SHA
#define HYLO_SOURCES_SHA "unknown"
#endif

// Finished solves survive an interruption: each appends a line "<key>\t<record>"
// to a log (OUT/results/drivocopter.solves) and a rerun takes its records from
// there. Keys name the robot file's hash, the hash of the sources
// (HYLO_SOURCES_SHA: a record made by other code is solved again), the scene
// (chasm_030; two chasms chasm_030_020_030), the sequence (hylo's plan by its
// predicted cost) and the placement.
class SolveLog {
public:
	explicit SolveLog(std::string path) : path_(std::move(path))
	{
		// A build without the hash knows no sources: it takes no record and
		// drops nothing.
		const bool keyed = sources().size() == 16;
		size_t other = 0;
		std::string kept;   // the lines of these sources, in order
		std::ifstream f(path_);
		std::string line;
		while (std::getline(f, line)) {
			size_t tab = line.find('\t');
			if (tab == std::string::npos)
				continue;
			std::vector<double> r;
			std::istringstream in(line.substr(tab + 1));
			std::string v;
			while (in >> v)
				r.push_back(std::strtod(v.c_str(), nullptr));
			const std::string key = line.substr(0, tab);
			if (r.size() < 5)
				continue;
			if (keyed && made_by(key, sources())) {
				done_[key] = r;
				kept += line + "\n";
			} else {
				other++;
			}
		}
		// A record of other code is never taken again: the log keeps only
		// these sources' (the committed one, the committed tables' solves).
		if (other) {
			std::fprintf(stderr, "  %s: %zu solves made by other code (sources %s now): solving them again%s\n",
				     path_.c_str(), other, sources().c_str(), keyed ? ", dropped from the log" : "");
			f.close();
			if (keyed)
				write_file_atomically(path_, kept);
		}
	}
	const std::vector<double> *find(const std::string &key) const
	{
		auto it = done_.find(key);
		return it == done_.end() ? nullptr : &it->second;
	}
	// One write() with O_APPEND: lines from concurrent processes do not mix.
	void add(const std::string &key, const std::vector<double> &r) const
	{
		std::string line = key + "\t";
		for (double v : r)
			line += " " + format_double(v);
		line += "\n";
		int fd = open(path_.c_str(), O_WRONLY | O_APPEND | O_CREAT, 0644);
		if (fd < 0 || write(fd, line.data(), line.size()) != static_cast<ssize_t>(line.size()))
			std::fprintf(stderr, "  %s: cannot append (%s)\n", path_.c_str(), std::strerror(errno));
		if (fd >= 0)
			close(fd);
	}

	// The record of one solve, "what" on the scene `scene` (chasm_030) from
	// placement lambda: from the log, else solve() and logged.
	std::vector<double> solve(const std::string &robot_sha, const std::string &scene, const std::string &what,
				  double lambda, const std::function<std::vector<double>()> &solve) const
	{
		char placement[32];
		std::snprintf(placement, sizeof placement, " placement %.3f", lambda);
		const std::string key = robot_sha.substr(0, 16) + " " + sources() + " " + scene + " " + what + placement;
		if (const std::vector<double> *old = find(key)) {
			std::fprintf(stderr, "  %s: from %s\n", key.c_str(), path_.c_str());
			return *old;
		}
		std::vector<double> v = solve();
		std::fprintf(stderr, "  %s %s (placement %.1f): %.1f J, %.0f s\n", scene.c_str(), what.c_str(), lambda,
			     v[0], v[4]);
		add(key, v);
		return v;
	}

private:
	// 16 hex digits; a build without them ("unknown") reuses nothing.
	static std::string sources() { return HYLO_SOURCES_SHA; }
	// Whether a key's second word (after the robot's hash) is sha: a
	// malformed line's short key is simply not.
	static bool made_by(const std::string &key, const std::string &sha)
	{
		const size_t a = key.find(' ');
		return a != std::string::npos && key.compare(a + 1, sha.size() + 1, sha + " ") == 0;
	}

	std::string path_;
	std::map<std::string, std::vector<double>> done_;
};

struct ChasmItem {
	size_t chasm;
	int seq;   // index into the sequences; -1: hylo's alternative `rank`
	double lambda;
	int rank = 0;   // hylo: the planner's alternative of this graph rank (0: its plan)
};

// The planner's alternatives per chasm (hylo-smooth smooths them all and
// publishes the cheapest).
constexpr uint32_t kChasmAlternatives = 3;

// One scene of the Drivocopter study, and the planner's alternatives on it.
struct ChasmScene {
	std::string key;     // its name in the solves log: chasm_030, chasm_030_020_030
	std::string label;   // the table's first column: "30", "30, 20, 30"
	std::string json;    // its fields in the JSON: "scene": "chasm_30", "width_m": 30
	Scene scene;
	Profile profile;
	std::vector<Alternative> alts;   // graph rank order, each named by its route
	double plan_s = 0;               // planning with the alternatives [s]
};

// Plans on the scene with kChasmAlternatives alternatives; the fixed
// sequences' switch points keep clearance_m from the walls. On one chasm an
// alternative is named by its letters (DFDFD), on more by its route
// (DFD(floor1)FD).
ChasmScene chasm_scene(const hylo_robot &svr, double clearance_m, Scene sc, std::string key, std::string label,
		       std::string json)
{
	ChasmScene s;
	s.profile = profile_of(sc, clearance_m);
	s.scene = std::move(sc);
	s.key = std::move(key);
	s.label = std::move(label);
	s.json = std::move(json);
	Planner pl;
	hylo_goal g = goal_of(s.scene);
	g.alternatives = kChasmAlternatives;
	auto t0 = std::chrono::steady_clock::now();
	pl.plan_on(svr, s.scene, g);
	s.plan_s = seconds_since(t0);
	s.alts = alternatives_of(pl);
	for (size_t k = 0; k < s.alts.size(); k++) {
		if (s.profile.walls.size() > 2)
			s.alts[k].letters = route_name(s.profile, route_of_plan(s.profile, s.alts[k].path));
		std::fprintf(stderr, "drivocopter %s: hylo's alternative %zu: %s, %.1f J predicted\n", s.scene.path.c_str(),
			     k + 1, s.alts[k].letters.c_str(), s.alts[k].predicted);
	}
	std::fprintf(stderr, "drivocopter %s: planned in %.2f s\n", s.scene.path.c_str(), s.plan_s);
	return s;
}

// The table's text above it: its heading and what it compares.
std::string table_one_intro(size_t placements, const TakeoffLanding &tl);
std::string two_chasms_intro(const TakeoffLanding &tl);

std::string table_one(const std::vector<ChasmScene> &scenes, size_t done, const std::vector<std::string> &seqs,
		      const std::vector<ChasmItem> &items, const std::vector<std::vector<double>> &rec,
		      const std::string &intro, const std::string &first_column, bool crossover_line, std::string &md);

// Per fixed sequence of chasm c, its cheapest converged record (empty: none).
std::vector<std::vector<double>> best_fixed(const std::vector<ChasmItem> &items,
					    const std::vector<std::vector<double>> &rec, size_t c, size_t n_seqs)
{
	std::vector<std::vector<double>> best(n_seqs);
	for (size_t i = 0; i < items.size(); i++) {
		if (items[i].chasm != c || items[i].seq < 0 || !std::isfinite(rec[i][0]))
			continue;
		std::vector<double> &b = best[static_cast<size_t>(items[i].seq)];
		if (b.empty() || rec[i][0] < b[0])
			b = rec[i];
	}
	return best;
}

double cost_of(const std::vector<double> &r) { return r.empty() ? NAN : r[0]; }

// Index of the cheapest finite cost (0 if none is).
size_t cheapest(const std::vector<double> &costs)
{
	size_t qb = 0;
	for (size_t q = 0; q < costs.size(); q++)
		if (std::isfinite(costs[q]) && !(costs[q] >= costs[qb]))
			qb = q;
	return qb;
}

// The first chasm whose best sequence drives on the floor after one whose
// best flies over it; best_seq.size() if none.
size_t first_drive_change(const std::vector<std::string> &best_seq)
{
	auto drives = [&](size_t k) { return best_seq[k].find("FDF") != std::string::npos; };
	size_t c = 1;
	while (c < best_seq.size() && !(drives(c) && !drives(c - 1)))
		c++;
	return c;
}

// Where the best fixed sequence changes from flying over the chasm (A) to
// driving through it (B), to the metre: between the two table widths that
// bracket it, both sequences solved on widened chasms, each width by
// false position on cost(A) - cost(B) (while the upper end has no value, the
// secant through the two points below; else bisection).
// Appends its section to md; returns its JSON (null: no change in the table).
std::string crossover(const Options &opt, const RobotParams &robot, const TakeoffLanding &tl,
		      const std::vector<int> &widths, const std::vector<ChasmScene> &scenes,
		      const std::vector<std::string> &seqs, const std::vector<ChasmItem> &items,
		      const std::vector<std::vector<double>> &rec, const SolveLog &log, const std::string &robot_sha,
		      std::string &md)
{
	std::vector<size_t> best;
	std::vector<std::string> best_seq;
	std::vector<std::vector<std::vector<double>>> fixed;
	for (size_t c = 0; c < widths.size(); c++) {
		fixed.push_back(best_fixed(items, rec, c, seqs.size()));
		std::vector<double> costs;
		for (const std::vector<double> &r : fixed.back())
			costs.push_back(cost_of(r));
		best.push_back(cheapest(costs));
		best_seq.push_back(seqs[best.back()]);
	}
	const size_t c = first_drive_change(best_seq);
	if (c == widths.size())
		return "null";
	const size_t qa = best[c - 1], qb = best[c];
	const std::string &A = seqs[qa], &B = seqs[qb];
	int lo = widths[c - 1], hi = widths[c];
	double dlo = cost_of(fixed[c - 1][qa]) - cost_of(fixed[c - 1][qb]);
	double dhi = cost_of(fixed[c][qa]) - cost_of(fixed[c][qb]);
	// Below the bracket: the secant's second point while hi has no value
	// (a long flight's solve may fail there).
	int w2 = c >= 2 ? widths[c - 2] : 0;
	double d2 = c >= 2 ? cost_of(fixed[c - 2][qa]) - cost_of(fixed[c - 2][qb]) : NAN;
	std::string rows, js = "{\"from\": \"" + A + "\", \"to\": \"" + B + "\", \"solved\": [";
	bool failed = false;
	for (int round = 0; hi - lo > 1 && !failed; round++) {
		double guess = 0.5 * (lo + hi);
		if (std::isfinite(dlo) && std::isfinite(dhi))
			guess = lo - dlo * (hi - lo) / (dhi - dlo);
		else if (std::isfinite(dlo) && std::isfinite(d2) && dlo > d2)
			guess = lo - dlo * (lo - w2) / (dlo - d2);
		int w = std::clamp(static_cast<int>(std::lround(guess)), lo + 1, hi - 1);
		Scene sc = widened(scenes[c - 1].scene, scenes[c - 1].profile, w - widths[c - 1]);
		Profile ch = profile_of(sc, switch_clearance(robot));
		auto r = parallel_records(2, 9, opt.jobs, [&](size_t j) {
			const std::string &seq = j ? B : A;
			return log.solve(robot_sha, sc.name, seq, 0.0,
					 [&] { return smooth_record(robot, sequence_plan(ch, seq, 0.0), sc, tl); });
		});
		const double d = r[0][0] - r[1][0];
		char row[160];
		std::snprintf(row, sizeof row, "| %d | %.1f | %.1f | %+.1f |\n", w, r[0][0], r[1][0], d);
		rows += row;
		js += std::string(round ? ", " : "") + "{\"width_m\": " + std::to_string(w) + ", \"" + A +
		      "\": " + num(r[0][0]) + ", \"" + B + "\": " + num(r[1][0]) + "}";
		if (!std::isfinite(d))
			failed = true;
		else if (d < 0)
			w2 = lo, d2 = dlo, lo = w, dlo = d;
		else
			hi = w, dhi = d;
	}
	md += "\nThe crossover to the metre: " + A + " and " + B + " solved on chasms widened between " +
	      std::to_string(widths[c - 1]) + " and " + std::to_string(widths[c]) +
	      " m (floor columns inserted at the middle; each width chosen by false position, or by the "
	      "secant through the widths below, on the cost difference):\n\n| width [m] | " + A + " | " + B + " | " + A + " - " + B + " |\n|---|---|---|---|\n" +
	      rows + "\n" +
	      (failed ? "A solve failed; the crossover lies between " : "So the crossover lies between ") +
	      std::to_string(lo) + " m (" + A + " cheaper) and " + std::to_string(hi) + " m (" + B + " cheaper)";
	const double at = std::isfinite(dlo) && std::isfinite(dhi) ? lo - dlo * (hi - lo) / (dhi - dlo) : NAN;
	if (std::isfinite(at)) {
		char lin[96];
		std::snprintf(lin, sizeof lin, ", at %.1f m by linear interpolation", at);
		md += lin;
	}
	md += ".\n";
	return js + "], \"between_m\": [" + std::to_string(lo) + ", " + std::to_string(hi) +
	       "], \"interpolated_m\": " + num(at) + "}";
}

// checkpoint(md, json) is called after each chasm with the results so far.
// On the committed chasms (or --widths) the fixed sequences F ... DFDFD; on
// --two-chasms scenes every route that drives on both ends (8).
std::string drivocopter_study(const Options &opt, std::string &md,
			      const std::function<void(const std::string &, const std::string &)> &checkpoint)
{
	RobotParams robot = load_robot(robot_file("drivocopter"));
	const hylo_robot svr_robot = committed_robot("drivocopter");
	std::fprintf(stderr, "drivocopter: takeoff and landing costs\n");
	const TakeoffLanding tl = takeoff_landing(robot, SolveOptions());
	std::vector<std::string> seqs = {"F", "DF", "DFD", "FDF", "DFDF", "DFDFD"};
	// Switch points start at the walls. A second placement half way to the
	// legs' far ends, tried on the 30 m chasm, failed its cold start in 3 of
	// 5 sequences (at 400 Ipopt iterations; DF still at 1,000) and ended
	// within 0.02% of this one where it converged (DF, DFD).
	const std::vector<double> lambdas = {0.0};
	std::vector<int> widths = {30, 50, 70, 90, 110};
	if (opt.quick)
		widths = {30};
	if (!opt.widths.empty())
		widths = opt.widths;
	using Item = ChasmItem;
	std::vector<ChasmScene> scenes;
	if (opt.two_chasms.empty()) {
		for (int width : widths) {
			char path[64];
			std::snprintf(path, sizeof path, "scenes/chasm_%03d.yaml", width);
			Scene sc;
			if (access(path, R_OK) == 0) {
				sc = hylo::scene::load(path);
			} else {
				// Not committed: the 30 m chasm widened (--widths).
				Scene base = hylo::scene::load("scenes/chasm_030.yaml");
				sc = widened(base, profile_of(base, 0), width - 30.0);
			}
			char key[32];
			std::snprintf(key, sizeof key, "chasm_%03d", width);
			scenes.push_back(chasm_scene(svr_robot, switch_clearance(robot), std::move(sc), key, std::to_string(width),
						     "\"scene\": \"chasm_" + std::to_string(width) + "\", \"width_m\": " +
							     std::to_string(width)));
		}
	} else {
		// Scenes nobody tuned on: the 30 m chasm made into two (--two-chasms).
		const Scene base = hylo::scene::load("scenes/chasm_030.yaml");
		for (const std::vector<int> &l : opt.two_chasms) {
			Scene sc = chasms(base, profile_of(base, 0), {double(l[0]), double(l[1]), double(l[2])});
			const std::string lengths = std::to_string(l[0]) + ", " + std::to_string(l[1]) + ", " + std::to_string(l[2]);
			const std::string key = sc.name;
			scenes.push_back(chasm_scene(svr_robot, switch_clearance(robot), std::move(sc), key, lengths,
						     "\"scene\": \"" + key + "\", \"lengths_m\": [" + lengths + "]"));
		}
		seqs.clear();
		for (const hylo::casestudies::Route &r : hylo::casestudies::routes(scenes[0].profile))
			seqs.push_back(route_name(scenes[0].profile, r));
	}
	std::vector<Item> items;
	for (size_t c = 0; c < scenes.size(); c++) {
		for (size_t k = 0; k < scenes[c].alts.size(); k++)
			items.push_back({c, -1, 0, static_cast<int>(k)});
		for (size_t q = 0; q < seqs.size(); q++)
			for (double l : lambdas) {
				items.push_back({c, static_cast<int>(q), l});
				if (seqs[q] == "F")
					break;   // no switch point to place
			}
	}
	const std::string log_path = opt.out + "/results/drivocopter.solves", robot_sha = sha256_file(robot.path);
	const SolveLog log(log_path);
	std::fprintf(stderr, "drivocopter: %zu multi-phase solves on %d workers (sources %s)\n", items.size(), opt.jobs,
		     HYLO_SOURCES_SHA);
	const bool two = !opt.two_chasms.empty();
	const std::string intro = two ? two_chasms_intro(tl) : table_one_intro(lambdas.size(), tl);
	// One chasm at a time, its results written as they come (hours in all).
	std::vector<std::vector<double>> rec(items.size());
	std::string head_md = md, js;
	for (size_t done = 1; done <= scenes.size(); done++) {
		std::vector<size_t> mine;
		for (size_t i = 0; i < items.size(); i++)
			if (items[i].chasm == done - 1)
				mine.push_back(i);
		auto r = parallel_records(mine.size(), 9, opt.jobs, [&](size_t j) {
			const Item &it = items[mine[j]];
			const ChasmScene &sc = scenes[it.chasm];
			// hylo's plan keeps its key of before (the alternatives' first).
			const Alternative *a = it.seq >= 0 ? nullptr : &sc.alts[static_cast<size_t>(it.rank)];
			std::string what = a ? "hylo " + std::string(it.rank ? "alternative " + std::to_string(it.rank) + " " : "") +
						       a->letters + " " + num(a->predicted)
					     : seqs[static_cast<size_t>(it.seq)];
			return log.solve(robot_sha, sc.key, what, it.lambda, [&] {
				std::vector<Waypoint> w =
					a ? a->path : sequence_plan(sc.profile, seqs[static_cast<size_t>(it.seq)], it.lambda);
				return smooth_record(robot, w, sc.scene, tl);
			});
		});
		for (size_t j = 0; j < mine.size(); j++)
			rec[mine[j]] = r[j];
		md = head_md;
		js = std::string(two ? "{\"two_chasms\": " : "{\"chasms\": ") +
		     table_one(scenes, done, seqs, items, rec, intro, two ? "chasm, platform, chasm [m]" : "width [m]",
			       !two, md);
		checkpoint(md, js + (two ? "}" : ", \"crossover\": null}"));
	}
	if (two)
		return js + "}";
	if (!opt.quick && opt.widths.empty())
		js += ", \"crossover\": " + crossover(opt, robot, tl, widths, scenes, seqs, items, rec, log, robot_sha, md);
	return js + "}";
}

std::string table_one_intro(size_t placements, const TakeoffLanding &tl)
{
	return "\n## 3. Drivocopter: fixed mode sequences against hylo (the paper's Table I)\n\n"
	       "Each chasm scene (`scenes/chasm_*.yaml`: platforms 6 m high, start and goal on them 10 m "
	       "back from the walls; the width is the floor between the walls). Fixed sequences "
	       "(D drive, F fly): one multi-phase collocation each, from ground rest at the start to "
	       "ground rest at the goal, takeoff (" + num(tl.takeoff_j) + " J) and landing (" +
	       num(tl.landing_j) + " J) included, every switch point free on its whole platform or floor, "
	       "flights cut at each wall into phases that meet 0.5 m above its top (the planner's flight "
	       "clearance), every phase in a corridor that keeps the body (0.32 m) plus " +
	       num(HYLO_DEFAULT_MARGIN_M) + " m clear of the terrain (docs/smoothing.md, \"Clearance\"); "
	       "switch points placed at the walls initially (" + std::to_string(placements) +
	       " placement). hylo: the planner's alternatives with the committed "
	       "SVR models (goal.alternatives = " + std::to_string(kChasmAlternatives) + ": the best graph path "
	       "of each of the cheapest distinct mode sequences predicted within 1.25 times the best; sequence "
	       "and predicted cost), each smoothed by the same multi-phase solver from its path; the cheapest "
	       "smoothed one is hylo's result, as `hylo-smooth` publishes it, and rank is the graph's rank of "
	       "its sequence (1: the plan). Smoothing options: flight segments of at most 40 ms, replay "
	       "tolerance 0.05 (knot to knot for flight), up to 1,000 Ipopt iterations per solve. Costs in J, "
	       "each with its trajectory's least clearance beyond the body in m (the check hylo-smooth "
	       "publishes; -inf: it leaves its domain); best fixed sequence in bold.\n\n";
}

std::string two_chasms_intro(const TakeoffLanding &tl)
{
	return "\n## 3. Drivocopter on two chasms (scenes nobody tuned on)\n\n"
	       "`scenes/chasm_030.yaml` made into two chasms (`hylo-casestudies --two-chasms W1,P,W2`): its "
	       "start platform, a floor W1 m wide, a middle platform P m long and 6 m high, a floor W2 m "
	       "wide, its goal platform; start and goal 10 m back from the outer walls. Each route (D drive, "
	       "F fly) drives on the start and goal platforms and on the segments named: D(floor1) on the "
	       "first floor, D(mid1) on the middle platform, D(floor2) on the second floor; a flight may "
	       "cross several walls. Every route is one multi-phase collocation, as in Table I: ground rest "
	       "to ground rest, takeoff (" + num(tl.takeoff_j) + " J) and landing (" + num(tl.landing_j) +
	       " J) included, every switch point free on its whole platform or floor, flights cut at each "
	       "wall into phases that meet 0.5 m above its top, corridors keeping the body (0.32 m) plus " +
	       num(HYLO_DEFAULT_MARGIN_M) + " m clear; switch points placed the body, the margin and a "
	       "cell from the walls initially, flights 1 m above the highest wall top they pass. hylo: the "
	       "planner's alternatives (goal.alternatives = " + std::to_string(kChasmAlternatives) +
	       "), each named by its route and smoothed from its path; "
	       "the cheapest smoothed one is hylo's result, rank its graph rank (1: the plan). Costs in J, "
	       "each with its trajectory's least clearance beyond the body in m; best route in bold.\n\n";
}

// The table of study 3 for the first `done` scenes, below `intro`, one
// column per fixed sequence (route); with the crossover's line if
// crossover_line. Returns its JSON.
std::string table_one(const std::vector<ChasmScene> &scenes, size_t done, const std::vector<std::string> &seqs,
		      const std::vector<ChasmItem> &items, const std::vector<std::vector<double>> &rec,
		      const std::string &intro, const std::string &first_column, bool crossover_line, std::string &md)
{
	md += intro + "| " + first_column + " |";
	for (const std::string &q : seqs)
		md += " " + q + " |";
	md += " hylo plan (predicted) | plan smoothed | other alternatives (predicted) smoothed | hylo | rank | vs best |\n|";
	for (size_t k = 0; k < seqs.size() + 7; k++)
		md += "---|";
	md += "\n";
	std::string js = "[";
	std::vector<std::string> best_seq(done);
	for (size_t c = 0; c < done; c++) {
		const std::vector<Alternative> &alts = scenes[c].alts;
		const std::vector<std::vector<double>> best_rec = best_fixed(items, rec, c, seqs.size());
		std::vector<double> best;
		for (const std::vector<double> &r : best_rec)
			best.push_back(cost_of(r));
		std::vector<const std::vector<double> *> smoothed(alts.size());   // each alternative smoothed, by rank
		for (size_t i = 0; i < items.size(); i++)
			if (items[i].chasm == c && items[i].seq < 0)
				smoothed[static_cast<size_t>(items[i].rank)] = &rec[i];
		const std::vector<double> *hylo = smoothed[0];   // the plan smoothed
		const std::string &plan_seq = alts[0].letters;
		const size_t qb = cheapest(best);
		best_seq[c] = seqs[qb];
		// hylo's result: the cheapest converged alternative (the earlier on a tie).
		size_t rank = 0;
		for (size_t k = 1; k < smoothed.size(); k++)
			if (std::isfinite((*smoothed[k])[0]) && !((*smoothed[k])[0] >= (*smoothed[rank])[0]))
				rank = k;
		const std::vector<double> *res = smoothed[rank];
		const std::string &res_seq = alts[rank].letters;
		const double hs = (*res)[0];
		auto own = std::find(seqs.begin(), seqs.end(), plan_seq);
		double seq_best = own == seqs.end() ? NAN : best[static_cast<size_t>(own - seqs.begin())];
		double rel = (hs - best[qb]) / best[qb], seq_rel = (seq_best - best[qb]) / best[qb];
		auto cost = [](double v) { return std::isfinite(v) ? num(std::round(v * 10) / 10) : std::string("failed"); };
		auto clearance = [](double v) {
			char b[32];
			std::snprintf(b, sizeof b, "%.2f", v);
			return std::string(b);
		};
		md += "| " + scenes[c].label + " |";
		for (size_t q = 0; q < seqs.size(); q++) {
			char cell[96];
			std::snprintf(cell, sizeof cell, q == qb ? " **%.1f** (%.2f) |" : " %.1f (%.2f) |", best[q],
				      best_rec[q].size() > 3 ? best_rec[q][3] : NAN);
			md += std::isfinite(best[q]) ? cell : " failed |";
		}
		std::string others;
		for (size_t k = 1; k < smoothed.size(); k++) {
			char pred[32];
			std::snprintf(pred, sizeof pred, " (%.1f) ", alts[k].predicted);
			others += std::string(k > 1 ? ", " : "") + alts[k].letters + pred + cost((*smoothed[k])[0]);
		}
		char pct[32] = "", tail[512];
		if (std::isfinite(hs))   // "0.00%" rather than "-0.00%" for a rounding-level difference
			std::snprintf(pct, sizeof pct, "%+.2f%%", std::fabs(rel) < 5e-5 ? 0.0 : 100 * rel);
		std::snprintf(tail, sizeof tail, " %s (%.1f) | %s | %s | %s | %zu | %s |\n", plan_seq.c_str(),
			      alts[0].predicted, cost((*hylo)[0]).c_str(), others.empty() ? "none" : others.c_str(),
			      std::isfinite(hs) ? (res_seq + " " + cost(hs) + " (" + clearance((*res)[3]) + ")").c_str()
						: "failed",
			      rank + 1, pct);
		md += tail;
		js += std::string(c ? "," : "") + "\n  {" + scenes[c].json + ", \"fixed\": {";
		for (size_t q = 0; q < seqs.size(); q++) {
			const std::vector<double> &r = best_rec[q];
			js += std::string(q ? ", " : "") + "\"" + seqs[q] + "\": ";
			if (r.empty()) {
				js += "null";
				continue;
			}
			js += "{\"cost_j\": " + num(r[0]) + ", \"T_s\": " + num(r[1]) + ", \"replay_error\": " +
			      num(r[2]) + ", \"min_clearance_m\": " + num(r[3]) + ", \"switch_x_m\": [";
			for (size_t k = 5; k < r.size() && std::isfinite(r[k]); k++)
				js += std::string(k > 5 ? ", " : "") + num(r[k]);
			js += "]}";
		}
		std::string aj;
		for (size_t k = 0; k < smoothed.size(); k++)
			aj += std::string(k ? ", " : "") + "{\"rank\": " + std::to_string(k + 1) + ", \"sequence\": \"" +
			      alts[k].letters + "\", \"predicted_j\": " + num(alts[k].predicted) +
			      ", \"smoothed_j\": " + num((*smoothed[k])[0]) + "}";
		js += "},\n   \"best_fixed\": \"" + seqs[qb] + "\", \"hylo\": {\"sequence\": \"" + plan_seq +
		      "\", \"predicted_j\": " + num(alts[0].predicted) + ", \"plan_s\": " + num(scenes[c].plan_s) +
		      ", \"smoothed_j\": " + num((*hylo)[0]) + ", \"sequence_fixed_j\": " + num(seq_best) +
		      ", \"sequence_vs_best\": " + num(seq_rel) + ", \"alternatives\": [" + aj +
		      "], \"result_rank\": " + std::to_string(rank + 1) + ", \"result_sequence\": \"" + res_seq +
		      "\", \"result_j\": " + num(hs) + ", \"T_s\": " +
		      num((*res)[1]) + ", \"replay_error\": " + num((*res)[2]) + ", \"min_clearance_m\": " +
		      num((*res)[3]) + ", \"result_vs_best\": " + num(rel) + "}}";
	}
	// The crossover: the first width whose best sequence drives on the floor.
	std::string cross = "none between " + scenes.front().label + " and " + scenes[done - 1].label + " m";
	if (size_t c = first_drive_change(best_seq); c < done)
		cross = "between " + scenes[c - 1].label + " m (" + best_seq[c - 1] + ") and " + scenes[c].label + " m (" +
			best_seq[c] + ")";
	if (crossover_line)
		md += "\nCrossover from flying over the chasm to driving through it: " + cross + ".\n";
	double solver_s = 0;
	size_t n_solves = 0;
	for (size_t i = 0; i < items.size(); i++)
		if (items[i].chasm < done && std::isfinite(rec[i][4]))
			solver_s += rec[i][4], n_solves++;
	char took[128];
	std::snprintf(took, sizeof took, "\n%zu solves, %.1f h of solver time (each solve's own time, from the log).\n",
		      n_solves, solver_s / 3600);
	md += took;
	if (done < scenes.size())
		md += "\n(Partial: " + std::to_string(done) + " of " + std::to_string(scenes.size()) + " chasms so far.)\n";
	return js + "\n]";
}

const char *const kStudies[] = {"di", "ambot", "drivocopter"};

// results.md and results.json from every study's part in OUT/results/.
void write_results(const std::string &out)
{
	std::string md = "# hylo: the paper's case studies, measured\n\n"
			 "Written by `make casestudies` (tools/casestudies/); every number is also in "
			 "`results.json`.\n\n";
	std::string js = "{";
	for (const char *name : kStudies) {
		std::ifstream fm(out + "/results/" + name + ".md"), fj(out + "/results/" + name + ".json");
		if (!fm || !fj)
			continue;
		std::stringstream m, j;
		m << fm.rdbuf();
		j << fj.rdbuf();
		md += m.str();
		js += std::string(js.size() > 1 ? "," : "") + "\n\"" + name + "\": " + j.str();
	}
	write_file_atomically(out + "/results.json", js + "\n}\n");
	write_file_atomically(out + "/results.md", md);
}

int run(int argc, char **argv)
{
	Options opt;
	for (int i = 1; i < argc; i++) {
		std::string a = argv[i];
		auto value = [&] { return option_value(argc, argv, i); };
		if (a == "--help" || a == "-h") {
			std::fputs(kUsage, stdout);
			return 0;
		} else if (a == "--sources-sha") {
			std::puts(HYLO_SOURCES_SHA);
			return 0;
		} else if (a == "--study") {
			opt.study = value();
			if (opt.study != "di" && opt.study != "ambot" && opt.study != "drivocopter" && opt.study != "all")
				throw std::invalid_argument("--study: unknown study '" + opt.study +
							    "' (di, ambot, drivocopter, all)");
		} else if (a == "--out") {
			opt.out = value();
		} else if (a == "--jobs") {
			opt.jobs = std::atoi(value().c_str());
			if (opt.jobs < 1)
				throw std::invalid_argument("--jobs: needs a positive integer");
		} else if (a == "--quick") {
			opt.quick = true;
		} else if (a == "--widths") {
			std::stringstream in(value());
			for (std::string w; std::getline(in, w, ',');) {
				char *end = nullptr;
				long v = std::strtol(w.c_str(), &end, 10);
				if (w.empty() || *end || v < 30 || v > 400)
					throw std::invalid_argument("--widths: '" + w + "' is not a whole number of metres in 30..400");
				opt.widths.push_back(static_cast<int>(v));
			}
		} else if (a == "--two-chasms") {
			const std::string text = value();
			std::vector<std::string> parts;
			std::stringstream in(text);
			for (std::string w; std::getline(in, w, ',');)
				parts.push_back(w);
			if (parts.size() != 3 || text.back() == ',')
				throw std::invalid_argument("--two-chasms: '" + text +
							    "' is not W1,P,W2 (chasm, middle platform, chasm in m)");
			std::vector<int> l;
			for (const std::string &w : parts) {
				const bool platform = l.size() == 1;
				const long lo = platform ? 2 : 5;
				char *end = nullptr;
				long v = std::strtol(w.c_str(), &end, 10);
				if (w.empty() || *end || v < lo || v > 400)
					throw std::invalid_argument("--two-chasms: '" + w + "' is not a whole number of metres in " +
								    std::to_string(lo) + "..400 (" +
								    (platform ? "the middle platform's length" : "a chasm's width") + ")");
				l.push_back(static_cast<int>(v));
			}
			opt.two_chasms.push_back(l);
		} else {
			throw std::invalid_argument("unknown argument '" + a + "'");
		}
	}
	if (!opt.two_chasms.empty() && !opt.widths.empty())
		throw std::invalid_argument("--two-chasms and --widths: one or the other (different tables)");
	// Fail now, not after an hour of solving.
	if (access(opt.out.c_str(), W_OK) != 0)
		throw std::runtime_error(opt.out + ": cannot write there (" + std::strerror(errno) + ")");
	if (!opt.two_chasms.empty()) {   // it writes the Drivocopter part: not over the committed Table I
		char *out = realpath(opt.out.c_str(), nullptr), *docs = realpath("docs", nullptr);
		const bool same = out && docs && std::string(out) == docs;
		std::free(out);
		std::free(docs);
		if (same)
			throw std::invalid_argument("--two-chasms: give an --out other than docs (it would replace "
						    "docs/results/drivocopter.md, the committed Table I)");
	}
	// Each study writes its part (OUT/results/<study>.{md,json}); results.md
	// and results.json are put together from every part there, so one study
	// can be re-run without the others (the DI study takes half an hour).
	const std::string parts = opt.out + "/results";
	if (mkdir(parts.c_str(), 0755) != 0 && errno != EEXIST)
		throw std::runtime_error(parts + ": cannot create (" + std::strerror(errno) + ")");
	for (const char *name : kStudies) {
		if (opt.study != name && opt.study != "all")
			continue;
		auto t0 = std::chrono::steady_clock::now();
		auto save = [&](const std::string &md, const std::string &js) {
			char took[96];
			std::snprintf(took, sizeof took, "\n(%s%.0f s on %d worker%s.)\n", opt.quick ? "--quick, " : "",
				      seconds_since(t0), opt.jobs, opt.jobs == 1 ? "" : "s");
			write_file_atomically(parts + "/" + name + ".md", md + took);
			write_file_atomically(parts + "/" + name + ".json", js);
			write_results(opt.out);
		};
		std::string md, js;
		if (std::string(name) == "di")
			js = di_study(opt, md);
		else if (std::string(name) == "ambot")
			js = ambot_study(opt, md);
		else
			js = drivocopter_study(opt, md, save);
		save(md, js);
	}
	std::fprintf(stderr, "wrote %s/results.json and %s/results.md\n", opt.out.c_str(), opt.out.c_str());
	return 0;
}

}  // namespace

int main(int argc, char **argv)
{
	if (!pin_numerics(argc, argv))
		return 1;
	return run_main("hylo-casestudies", run, argc, argv, 2, kUsage);
}
