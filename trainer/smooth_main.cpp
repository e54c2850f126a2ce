// hylo-smooth: the final path smoothing node. Subscribes <prefix>HYLO_MAP,
// <prefix>HYLO_GOAL, <prefix>HYLO_PLAN and <prefix>HYLO_PLAN_ALTERNATIVE,
// smooths every successful plan with one multi-phase collocation problem over
// its mode sequence (trainer/smoother.hpp), replays it with CVODE and
// publishes <prefix>HYLO_TRAJ. When the goal asked for alternatives it
// smooths them too, publishes the cheapest smoothed trajectory and reports
// each on <prefix>HYLO_TRAJ_ALTERNATIVE. Works on a live bus or, with file://
// providers, on logs.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <lcm/lcm-cpp.hpp>

#include "hylo/goal_t.hpp"
#include "hylo/map_t.hpp"
#include "hylo/plan_alternative_t.hpp"
#include "hylo/plan_t.hpp"
#include "hylo/traj_alternative_t.hpp"
#include "hylo/traj_t.hpp"
#include "hylo/clearance.h"
#include "trainer/clearance.hpp"
#include "trainer/numerics.hpp"
#include "trainer/params.hpp"
#include "trainer/fallbacks.hpp"
#include "trainer/smooth_alternatives.hpp"
#include "trainer/terrain_grid.hpp"

namespace {

using namespace hylo::trainer;

volatile std::sig_atomic_t g_stop = 0;
void on_signal(int) { g_stop = 1; }

void usage(FILE *out)
{
	std::fputs(
		"usage: hylo-smooth [options]\n"
		"Smooths plans: subscribes <prefix>HYLO_MAP and <prefix>HYLO_PLAN, solves one\n"
		"multi-phase trajectory optimization over each successful plan's mode sequence\n"
		"(switch points free along their guards, switching costs included), checks it\n"
		"with a CVODE replay and publishes <prefix>HYLO_TRAJ. When the plan's goal\n"
		"(<prefix>HYLO_GOAL) asked for alternatives, it also smooths the alternatives\n"
		"(<prefix>HYLO_PLAN_ALTERNATIVE), cheapest predicted first within the budget\n"
		"below, publishes the cheapest smoothed trajectory and then one\n"
		"<prefix>HYLO_TRAJ_ALTERNATIVE per alternative (its predicted and smoothed cost;\n"
		"docs/smoothing.md, \"Alternatives\"). When an optimization fails or its replay\n"
		"is rejected, a fallback chain gives the trajectory (finer mesh, via points,\n"
		"phase by phase, the graph path; traj_t.method says which,\n"
		"docs/smoothing.md); only a plan that cannot be followed at all fails. A\n"
		"failed plan or one whose map was not seen gets a traj_t whose status says\n"
		"why.\n"
		"\n"
		"  --lcm-url URL         LCM provider to listen on (default: $LCM_DEFAULT_URL,\n"
		"                        else LCM's default udpm://239.255.76.67:7667?ttl=0)\n"
		"  --out-url URL         LCM provider to publish on (default: the same as\n"
		"                        --lcm-url; needed when reading a file:// log)\n"
		"  --channel-prefix P    prefix of the channel names (default: none)\n"
		"  --request-id N        smooth only the plan answering request N, then exit\n"
		"  --once                smooth one plan, then exit\n"
		"  --segments-per-edge N collocation segments per plan edge (default: 6; each\n"
		"                        phase has 10 to 48)\n"
		"  --alternatives N      smooth at most N of a plan's alternatives, the cheapest\n"
		"                        predicted first (1 to 8; default: 8, every one the planner\n"
		"                        sent; 1: the plan alone, the rest reported unsmoothed)\n"
		"  --alternatives-budget S\n"
		"                        start no further alternative once S seconds have passed\n"
		"                        since the first began (default: 0, no limit); the plan\n"
		"                        itself is always smoothed\n"
		"  --alternatives-wait S wait at most S seconds after the plan for its\n"
		"                        alternatives, then smooth those received (default: 2)\n"
		"  --margin M            clearance the trajectory must keep beyond the robot's\n"
		"                        body from every hazard of its mode, in metres: its\n"
		"                        phases' corridors keep it, the check after the solve\n"
		"                        says whether it does (default: 0.1; docs/smoothing.md,\n"
		"                        \"Clearance\"); traj_t.safe\n"
		"  --no-corridors        no corridors: inside a phase only the state bounds\n"
		"                        hold (the smoother before corridors, for comparison)\n"
		"  --compare-graph       also solve every edge of the plan on its own and print\n"
		"                        the exact cost of the graph path (slow)\n"
		"  --ipopt-option NAME=VALUE\n"
		"                        set an Ipopt option on every solve, after hylo's own\n"
		"                        settings (repeatable; default: none)\n"
		"  --full-ipopt-option NAME=VALUE\n"
		"                        the same, on the multi-phase optimization's solves\n"
		"                        only (steps full, straightened, finer mesh), after\n"
		"                        --ipopt-option's: max_iter=1 forces the fallbacks\n"
		"  --quiet               no summary lines\n"
		"  --debug               trace every Ipopt solve and replay on stderr (default: off)\n"
		"  --help                this text\n"
		"\n"
		"Exit codes: 0 clean stop (signal, --once/--request-id done, end of an input\n"
		"log), 1 start-up failure (also numerics that cannot be pinned, as the\n"
		"trainer's), 2 usage error.\n",
		out);
}

struct Options {
	std::string in_url, out_url, prefix;
	long long request_id = -1;
	bool once = false, compare = false, quiet = false;
	// --segments-per-edge, --margin (beyond the body: the corridors keep it,
	// the clearance check verifies it), --no-corridors, the Ipopt options.
	SmoothOptions smooth;
	AlternativesBudget budget;
	double alternatives_wait_s = 2;
};

// The sampled path of a plan_t.
std::vector<Waypoint> waypoints_of(const hylo::plan_t &p)
{
	std::vector<Waypoint> wps;
	for (int i = 0; i < p.n_waypoints; i++) {
		Waypoint w;
		w.mode = static_cast<hylo_mode>(p.mode[static_cast<size_t>(i)]);   // goal_t numbers; smoothing_problem checks them
		for (int k = 0; k < 6; k++)
			w.state[k] = p.state[static_cast<size_t>(i)][static_cast<size_t>(k)];
		w.guard = p.guard[static_cast<size_t>(i)] != 0;
		wps.push_back(w);
	}
	return wps;
}

// "ground -> flight -> ground": a solution's modes, a run cut at walls, via
// points or edges counted once.
std::string sequence_of(const std::vector<std::string> &modes)
{
	std::string seq, last;
	for (const std::string &md : modes)
		if (md != last) {
			seq += (seq.empty() ? "" : " -> ") + md;
			last = md;
		}
	return seq;
}

// Of modes as numbered in goal_t (MODE_*) and onboard (hylo_mode): a plan's
// (int8_t) or a smoothed trajectory's phases.
template <class Mode>
std::string sequence_of(const std::vector<Mode> &modes)
{
	std::vector<std::string> names;
	for (Mode m : modes)
		names.push_back(mode_name(m));
	return sequence_of(names);
}

class Smoother {
public:
	Smoother(const Options &o, lcm::LCM &out) : o_(o), out_(out) {}
	bool done() const { return done_; }

	void on_map(const lcm::ReceiveBuffer *, const std::string &, const hylo::map_t *m)
	{
		if (m->n_cells != m->nx * m->ny || m->nx <= 0 || m->ny <= 0 || !(m->resolution_m > 0)) {
			std::fprintf(stderr, "hylo-smooth: map %lld is malformed (n_cells %d, nx %d, ny %d); ignored\n",
				     static_cast<long long>(m->map_id), m->n_cells, m->nx, m->ny);
			return;
		}
		if (maps_.size() >= 8)   // a few recent maps: plans name theirs
			maps_.erase(maps_.begin());
		maps_[m->map_id] = {m->robot, terrain_grid(*m)};
	}

	// How many alternatives each recent goal asked for: its plan waits for them.
	void on_goal(const lcm::ReceiveBuffer *, const std::string &, const hylo::goal_t *g)
	{
		if (asked_.size() >= 64)
			asked_.erase(asked_.begin());
		asked_[g->request_id] = g->alternatives == 0 ? hylo::goal_t::DEFAULT_ALTERNATIVES : g->alternatives;
	}

	void on_plan(const lcm::ReceiveBuffer *, const std::string &, const hylo::plan_t *p)
	{
		if (pending_)   // a new plan before every alternative of the last one came
			finish_pending();
		if (done_ || (o_.request_id >= 0 && p->request_id != o_.request_id))
			return;
		auto k = asked_.find(p->request_id);
		// The node publishes alternatives only after a plan with status ok.
		if (k != asked_.end() && k->second >= 2 && p->status == hylo::plan_t::STATUS_OK &&
		    maps_.count(p->map_id)) {
			pending_ = std::make_unique<Pending>();
			pending_->plan = *p;
			pending_->deadline = std::chrono::steady_clock::now() +
					     std::chrono::duration_cast<std::chrono::steady_clock::duration>(
						     std::chrono::duration<double>(o_.alternatives_wait_s));
			return;
		}
		hylo::traj_t t = answer(*p);
		t.utime = now_us();
		out_.publish(o_.prefix + "HYLO_TRAJ", &t);
		finished_one();
	}

	void on_alternative(const lcm::ReceiveBuffer *, const std::string &, const hylo::plan_alternative_t *a)
	{
		if (!pending_ || a->request_id != pending_->plan.request_id)
			return;
		if (a->count < 1 || a->index < 0 || a->index >= a->count || a->count > 64) {
			std::fprintf(stderr, "hylo-smooth: request %lld: alternative index %d of count %d ignored\n",
				     static_cast<long long>(a->request_id), a->index, a->count);
			return;
		}
		pending_->planned = a->count;
		pending_->received[a->index] = *a;
	}

	// Smooths a plan waiting for its alternatives once all have come, its
	// wait is over, or the input ended (at_end).
	void poll(bool at_end)
	{
		if (!pending_)
			return;
		const bool all = pending_->planned > 0 && static_cast<int>(pending_->received.size()) >= pending_->planned;
		if (all || at_end || std::chrono::steady_clock::now() >= pending_->deadline)
			finish_pending();
	}

	// Milliseconds until a waiting plan's wait ends (at most cap).
	int wait_ms(int cap) const
	{
		if (!pending_)
			return cap;
		auto left = std::chrono::duration_cast<std::chrono::milliseconds>(pending_->deadline -
										 std::chrono::steady_clock::now());
		return static_cast<int>(std::clamp<long long>(left.count(), 0, cap));
	}

private:
	struct Pending {
		hylo::plan_t plan;
		int planned = 0;   // plan_alternative_t.count (0: none received)
		std::map<int32_t, hylo::plan_alternative_t> received;   // by index
		std::chrono::steady_clock::time_point deadline;
	};

	static int64_t now_us()
	{
		struct timespec ts;
		clock_gettime(CLOCK_REALTIME, &ts);
		return static_cast<int64_t>(ts.tv_sec) * 1000000 + ts.tv_nsec / 1000;
	}

	void finished_one()
	{
		if (o_.once || o_.request_id >= 0)
			done_ = true;
	}

	void fail(hylo::traj_t &t, int8_t status, const std::string &why)
	{
		t.status = status;
		t.reason = why;
		std::fprintf(stderr, "hylo-smooth: request %lld: %s\n", static_cast<long long>(t.request_id), why.c_str());
	}

	// The default solver options with --ipopt-option's.
	SolveOptions solve_options() const
	{
		SolveOptions s;
		s.ipopt_options = o_.smooth.ipopt_options;
		return s;
	}

	const RobotParams &robot(const std::string &name)
	{
		auto it = robots_.find(name);
		if (it == robots_.end())
			it = robots_.emplace(name, load_robot(robot_file(name))).first;
		return it->second;
	}

	TakeoffLanding switch_costs(const std::string &name, const RobotParams &r)
	{
		if (!r.has(HYLO_MODE_FLIGHT))
			return {};
		auto it = costs_.find(name);
		if (it == costs_.end())
			it = costs_.emplace(name, takeoff_landing(r, solve_options())).first;
		return it->second;
	}

	static hylo::traj_t traj_for(const hylo::plan_t &p)
	{
		hylo::traj_t t{};
		t.request_id = p.request_id;
		t.map_id = p.map_id;
		t.robot = p.robot;
		t.status = hylo::plan_t::STATUS_OK;
		return t;
	}

	// Every failed step of a smoothing on stderr; all of them joined.
	static std::string rejections(long long request_id, const SmoothResult &res)
	{
		std::string tried;
		for (const std::string &why : res.rejections) {
			std::fprintf(stderr, "hylo-smooth: request %lld: rejected %s\n", request_id, why.c_str());
			tried += (tried.empty() ? "" : "; ") + why;
		}
		return tried;
	}

	// How far above the optimum: below the cheapest solution of the full
	// problem a step reached (one the replay or the domain check rejected);
	// unknown (NaN) when no step reached one.
	static double gap_of(const SmoothResult &res)
	{
		return res.method == SmoothMethod::Full ? 0.0
		       : std::isfinite(res.lowest_cost) ? std::max(0.0, res.solution.cost - res.lowest_cost)
							 : std::nan("");
	}

	static std::string reason_of(const SmoothResult &res, const std::string &tried)
	{
		return res.method == SmoothMethod::Full ? "smoothed"
							: std::string("fallback ") + method_name(res.method) + " (" + tried + ")";
	}

	// t from a smoothing of p's path (wps): the trajectory, or why there is none.
	void fill(hylo::traj_t &t, const hylo::plan_t &p, const std::vector<Waypoint> &wps, const SmoothResult &res,
		  const std::string &tried, const RobotParams &r, const TakeoffLanding &costs)
	{
		if (!res.ok)
			return fail(t, hylo::plan_t::STATUS_NO_PATH,
				    "the plan cannot be followed: " + res.failure + " (tried " + tried + ")");
		const MultiPhaseSolution &s = res.solution;
		for (const std::string &n : s.notes)
			std::fprintf(stderr, "hylo-smooth: request %lld: %s\n", static_cast<long long>(p.request_id), n.c_str());
		double t0 = 0;
		for (size_t k = 0; k < s.phases.size(); k++) {
			const Solution &ph = s.phases[k];
			int8_t mode = static_cast<int8_t>(s.modes[k]);
			for (size_t i = 0; i < ph.traj.t.size(); i++) {
				std::vector<double> x(16, 0.0), u(4, 0.0);
				for (int j = 0; j < ph.traj.nx; j++)
					x[static_cast<size_t>(j)] = ph.traj.x[i * static_cast<size_t>(ph.traj.nx) + static_cast<size_t>(j)];
				for (int j = 0; j < ph.traj.nu; j++)
					u[static_cast<size_t>(j)] = ph.traj.u[i * static_cast<size_t>(ph.traj.nu) + static_cast<size_t>(j)];
				t.t_s.push_back(t0 + ph.traj.t[i]);
				t.mode.push_back(mode);
				t.state.push_back(x);
				t.input.push_back(u);
			}
			t0 += ph.T;
		}
		t.n_samples = static_cast<int32_t>(t.t_s.size());
		t.energy_j = s.cost;
		t.replay_energy_j = s.replay_cost;
		t.replay_error = s.replay_error;
		t.method = static_cast<int8_t>(res.method);
		t.gap_j = gap_of(res);
		t.reason = reason_of(res, tried);
		const ClearanceCheck c = check_clearance(s, maps_.at(p.map_id).grid, r.body_radius_m, o_.smooth.margin_m);
		t.safe = c.safe;
		t.body_radius_m = c.body_radius_m;
		t.margin_m = c.margin_m;
		t.min_clearance_m = c.min_clearance_m;
		t.clearance_t_s = c.t_s;
		t.clearance_xyz[0] = c.x_m;
		t.clearance_xyz[1] = c.y_m;
		t.clearance_xyz[2] = c.z_m;
		if (!c.safe)
			t.reason += "; " + c.text();
		if (!o_.quiet) {
			std::printf("request %lld: %s; predicted %.6g J, smoothed %.6g J (replay %.6g J, error %.2g), "
				    "T %.4g s, %.2f s to solve, method %s, gap %.4g J; %s\n",
				    static_cast<long long>(p.request_id), sequence_of(s.modes).c_str(), p.total_cost_j, s.cost,
				    s.replay_cost, s.replay_error, s.T, res.seconds, method_name(res.method), t.gap_j,
				    c.text().c_str());
			if (o_.compare)
				std::printf("request %lld: graph path, every edge solved exactly: %.6g J\n",
					    static_cast<long long>(p.request_id), graph_path_cost(r, wps, costs, solve_options()));
			std::fflush(stdout);
		}
	}

	// Why a plan cannot be smoothed at all (empty: it can).
	std::string unsmoothable(const hylo::plan_t &p, int8_t &status) const
	{
		if (p.status != hylo::plan_t::STATUS_OK && p.status != hylo::plan_t::STATUS_NOT_PROVEN) {
			status = p.status;
			return "the plan has no path to smooth (plan status " + std::to_string(p.status) + ": " + p.reason +
			       ")";
		}
		if (!maps_.count(p.map_id)) {
			status = hylo::plan_t::STATUS_NO_MAP;
			return "map " + std::to_string(p.map_id) + " of the plan was not received";
		}
		return "";
	}

	// The answer to a plan without alternatives.
	hylo::traj_t answer(const hylo::plan_t &p)
	{
		hylo::traj_t t = traj_for(p);
		int8_t status = 0;
		std::string why = unsmoothable(p, status);
		if (!why.empty()) {
			fail(t, status, why);
			return t;
		}
		try {
			const RobotParams &r = robot(p.robot);
			TakeoffLanding costs = switch_costs(p.robot, r);
			std::vector<Waypoint> wps = waypoints_of(p);
			SmoothResult res = smooth_with_fallbacks(r, wps, maps_.at(p.map_id).grid, costs, o_.smooth);
			fill(t, p, wps, res, rejections(p.request_id, res), r, costs);
		} catch (const std::exception &e) {
			fail(t, hylo::plan_t::STATUS_BAD_REQUEST, e.what());
		}
		return t;
	}

	// A plan and the alternatives received: each smoothed within the budget,
	// the cheapest trajectory on HYLO_TRAJ, then one HYLO_TRAJ_ALTERNATIVE each.
	void finish_pending()
	{
		std::unique_ptr<Pending> pd = std::move(pending_);
		const hylo::plan_t &p = pd->plan;
		const long long id = static_cast<long long>(p.request_id);
		// Index 0 is the plan's own path: from the plan_t, whether or not its
		// plan_alternative_t arrived.
		std::vector<const hylo::plan_t *> paths{&p};
		std::vector<int32_t> index{0}, changes{0};
		if (pd->received.count(0))
			changes[0] = pd->received.at(0).mode_changes;
		for (const auto &[k, a] : pd->received)
			if (k > 0) {
				paths.push_back(&a.plan);
				index.push_back(k);
				changes.push_back(a.mode_changes);
			}
		if (pd->received.empty()) {   // as a plan without alternatives: no report
			std::fprintf(stderr, "hylo-smooth: request %lld: no alternative arrived within %g s; "
				     "smoothing the plan alone\n", id, o_.alternatives_wait_s);
			hylo::traj_t t = answer(p);
			t.utime = now_us();
			out_.publish(o_.prefix + "HYLO_TRAJ", &t);
			return finished_one();
		}
		const int planned = pd->planned;
		if (planned > static_cast<int>(paths.size()))
			std::fprintf(stderr, "hylo-smooth: request %lld: %d of %d alternatives did not arrive within %g s; "
				     "smoothing the %zu received\n", id, planned - static_cast<int>(paths.size()), planned,
				     o_.alternatives_wait_s, paths.size());
		hylo::traj_t t = traj_for(p);
		std::vector<hylo::traj_alternative_t> reports;
		try {
			const RobotParams &r = robot(p.robot);
			TakeoffLanding costs = switch_costs(p.robot, r);
			std::vector<PlanAlternative> alts;
			for (size_t i = 0; i < paths.size(); i++)
				alts.push_back({index[i], paths[i]->total_cost_j, waypoints_of(*paths[i])});
			AlternativesChoice c =
				smooth_alternatives(r, alts, maps_.at(p.map_id).grid, costs, o_.smooth, o_.budget);
			std::vector<std::string> tried;
			for (const AlternativeOutcome &o : c.outcomes)
				tried.push_back(o.smoothed ? rejections(p.request_id, o.result) : "");
			// Whichever is chosen, the traj_t is built as for a plan alone;
			// none ok: the plan's own failure.
			for (size_t i = 0; i < c.outcomes.size(); i++) {
				const AlternativeOutcome &o = c.outcomes[i];
				hylo::traj_alternative_t a{};
				a.request_id = p.request_id;
				a.map_id = p.map_id;
				a.index = index[i];
				a.count = static_cast<int32_t>(c.outcomes.size());
				a.planned = planned;
				a.mode_changes = changes[i];
				a.mode_sequence = paths[i]->mode_sequence;
				a.n_modes = static_cast<int32_t>(a.mode_sequence.size());
				a.predicted_j = paths[i]->total_cost_j;
				a.chosen = static_cast<int>(i) == c.chosen;
				a.smoothed_j = a.gap_j = std::nan("");
				if (!o.smoothed) {
					a.status = hylo::plan_t::STATUS_BUDGET_EXHAUSTED;
					a.reason = o.skipped;
				} else if (!o.result.ok) {
					a.status = hylo::plan_t::STATUS_NO_PATH;
					a.reason = "cannot be followed: " + o.result.failure + " (tried " + tried[i] + ")";
				} else {
					a.status = hylo::plan_t::STATUS_OK;
					a.reason = reason_of(o.result, tried[i]);
					if (!o.clearance.safe)
						a.reason += "; " + o.clearance.text();
					a.method = static_cast<int8_t>(o.result.method);
					a.smoothed_j = o.result.solution.cost;
					a.gap_j = gap_of(o.result);
				}
				if (!o_.quiet) {
					char what[160];
					if (a.status == hylo::plan_t::STATUS_OK)
						std::snprintf(what, sizeof what, "smoothed %.6g J, method %s, %.2f s to solve%s",
							      a.smoothed_j, method_name(o.result.method), o.result.seconds,
							      o.clearance.safe ? "" : ", not safe");
					else
						std::snprintf(what, sizeof what, "%s",
							      o.smoothed ? "cannot be followed" : o.skipped.c_str());
					std::printf("request %lld: graph rank %d of %d: %s; predicted %.6g J, %s%s\n",
						    id, a.index + 1, planned, sequence_of(a.mode_sequence).c_str(),
						    a.predicted_j, what, a.chosen ? "; chosen" : "");
				}
				reports.push_back(std::move(a));
			}
			const size_t w = c.chosen >= 0 ? static_cast<size_t>(c.chosen) : 0;
			fill(t, *paths[w], alts[w].plan, c.outcomes[w].result, tried[w], r, costs);
		} catch (const std::exception &e) {
			fail(t, hylo::plan_t::STATUS_BAD_REQUEST, e.what());
		}
		const int64_t utime = now_us();
		t.utime = utime;
		out_.publish(o_.prefix + "HYLO_TRAJ", &t);
		for (hylo::traj_alternative_t &a : reports) {
			a.utime = utime;
			out_.publish(o_.prefix + "HYLO_TRAJ_ALTERNATIVE", &a);
		}
		finished_one();
	}

	struct Map {
		std::string robot;
		TerrainGrid grid;
	};
	const Options &o_;
	lcm::LCM &out_;
	std::map<int64_t, Map> maps_;
	std::map<int64_t, int> asked_;   // request_id -> goal_t.alternatives
	std::unique_ptr<Pending> pending_;
	std::map<std::string, RobotParams> robots_;
	std::map<std::string, TakeoffLanding> costs_;
	bool done_ = false;
};

// Fills o from the command line. False: exit with exit_code (--help, a usage error).
bool parse(int argc, char **argv, Options &o, int &exit_code)
{
	exit_code = 2;
	for (int i = 1; i < argc; i++) {
		std::string a = argv[i];
		if (a == "--help") {
			usage(stdout);
			exit_code = 0;
			return false;
		}
		if (a == "--no-corridors") {
			o.smooth.corridors = false;
			continue;
		}
		if (a == "--debug") {
			o.smooth.debug = true;
			continue;
		}
		if (a == "--once" || a == "--compare-graph" || a == "--quiet") {
			(a == "--once" ? o.once : a == "--quiet" ? o.quiet : o.compare) = true;
			continue;
		}
		bool text = a == "--lcm-url" || a == "--out-url" || a == "--channel-prefix" || a == "--ipopt-option" ||
			    a == "--full-ipopt-option";
		bool number = a == "--request-id" || a == "--segments-per-edge" || a == "--alternatives";
		bool seconds = a == "--alternatives-budget" || a == "--alternatives-wait";
		bool metres = a == "--margin";
		if (!text && !number && !seconds && !metres) {
			std::fprintf(stderr, "hylo-smooth: unknown option '%s' (see --help)\n", a.c_str());
			return false;
		}
		if (i + 1 >= argc) {
			std::fprintf(stderr, "hylo-smooth: %s needs a value\n", a.c_str());
			return false;
		}
		const char *v = argv[++i];
		if (a == "--ipopt-option" || a == "--full-ipopt-option") {
			try {
				(a == "--ipopt-option" ? o.smooth.ipopt_options : o.smooth.full_ipopt_options).push_back(parse_ipopt_option(v));
			} catch (const std::invalid_argument &e) {
				std::fprintf(stderr, "hylo-smooth: %s: %s\n", a.c_str(), e.what());
				return false;
			}
			continue;
		}
		if (text) {
			(a == "--lcm-url" ? o.in_url : a == "--out-url" ? o.out_url : o.prefix) = v;
			continue;
		}
		char *end = nullptr;
		if (metres) {
			double x = std::strtod(v, &end);
			if (!*v || *end != '\0' || !std::isfinite(x) || x < 0 || x > 10) {
				std::fprintf(stderr, "hylo-smooth: %s wants metres in [0, 10], not '%s'\n", a.c_str(), v);
				return false;
			}
			o.smooth.margin_m = x;
			continue;
		}
		if (seconds) {
			double x = std::strtod(v, &end);
			if (!*v || *end != '\0' || !std::isfinite(x) || x < 0) {
				std::fprintf(stderr, "hylo-smooth: %s wants a number of seconds >= 0, not '%s'\n", a.c_str(), v);
				return false;
			}
			(a == "--alternatives-budget" ? o.budget.seconds : o.alternatives_wait_s) = x;
			continue;
		}
		long long n = std::strtoll(v, &end, 10);
		bool id = a == "--request-id";
		long long most = a == "--alternatives" ? 8 : 48;
		if (!*v || *end != '\0' || n < (id ? 0 : 1) || (!id && n > most)) {
			std::fprintf(stderr, "hylo-smooth: %s wants %s, not '%s'\n", a.c_str(),
				     id ? "an integer >= 0" : most == 8 ? "an integer in [1, 8]" : "an integer in [1, 48]", v);
			return false;
		}
		if (id)
			o.request_id = n;
		else if (a == "--alternatives")
			o.budget.max_count = static_cast<int>(n);
		else
			o.smooth.segments_per_edge = static_cast<int>(n);
	}
	return true;
}

}  // namespace

int main(int argc, char **argv)
{
	if (!pin_numerics(argc, argv))
		return 1;
	Options o;
	int code = 0;
	if (!parse(argc, argv, o, code))
		return code;
	lcm::LCM in(o.in_url);
	if (!in.good()) {
		std::fprintf(stderr, "hylo-smooth: cannot open LCM provider '%s'\n", o.in_url.c_str());
		return 1;
	}
	std::unique_ptr<lcm::LCM> own_out;
	lcm::LCM *out = &in;
	if (!o.out_url.empty()) {
		own_out = std::make_unique<lcm::LCM>(o.out_url);
		if (!own_out->good()) {
			std::fprintf(stderr, "hylo-smooth: cannot open LCM provider '%s'\n", o.out_url.c_str());
			return 1;
		}
		out = own_out.get();
	}
	Smoother s(o, *out);
	in.subscribe(o.prefix + "HYLO_MAP", &Smoother::on_map, &s);
	in.subscribe(o.prefix + "HYLO_GOAL", &Smoother::on_goal, &s);
	in.subscribe(o.prefix + "HYLO_PLAN", &Smoother::on_plan, &s);
	in.subscribe(o.prefix + "HYLO_PLAN_ALTERNATIVE", &Smoother::on_alternative, &s);
	std::signal(SIGINT, on_signal);
	std::signal(SIGTERM, on_signal);
	while (!g_stop && !s.done()) {
		int r = in.handleTimeout(s.wait_ms(200));
		s.poll(r < 0);
		if (r < 0)   // end of an input log, or the provider failed
			break;
	}
	return 0;
}
