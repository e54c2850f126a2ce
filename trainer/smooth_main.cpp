// hylo-smooth: the final path smoothing node. Subscribes <prefix>HYLO_MAP and
// <prefix>HYLO_PLAN, smooths every successful plan with one multi-phase
// collocation problem over its mode sequence (trainer/smoother.hpp), replays
// it with CVODE and publishes <prefix>HYLO_TRAJ. Works on a live bus or, with
// file:// providers, on logs.
#include <algorithm>
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

#include "hylo/map_t.hpp"
#include "hylo/plan_t.hpp"
#include "hylo/traj_t.hpp"
#include "trainer/numerics.hpp"
#include "trainer/params.hpp"
#include "trainer/smoother.hpp"

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
		"with a CVODE replay and publishes <prefix>HYLO_TRAJ. A plan that drives\n"
		"between two flights is also smoothed with that drive flown over, and the\n"
		"cheaper trajectory is published. When that optimization fails or its replay\n"
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
	int segments_per_edge = 6;
	std::vector<IpoptOption> ipopt_options, full_ipopt_options;
};

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
		TerrainGrid g;
		g.nx = m->nx;
		g.ny = m->ny;
		g.resolution_m = m->resolution_m;
		g.origin_x_m = m->origin_x_m;
		g.origin_y_m = m->origin_y_m;
		g.terrain = m->terrain;
		g.height_m = m->height_m;
		g.max_step_m = m->max_step_m;
		if (maps_.size() >= 8)   // a few recent maps: plans name theirs
			maps_.erase(maps_.begin());
		maps_[m->map_id] = {m->robot, std::move(g)};
	}

	void on_plan(const lcm::ReceiveBuffer *, const std::string &, const hylo::plan_t *p)
	{
		if (done_ || (o_.request_id >= 0 && p->request_id != o_.request_id))
			return;
		hylo::traj_t t{};
		t.request_id = p->request_id;
		t.map_id = p->map_id;
		t.robot = p->robot;
		t.status = hylo::plan_t::STATUS_OK;
		smooth(*p, t);
		t.utime = now_us();
		t.n_samples = static_cast<int32_t>(t.t_s.size());
		out_.publish(o_.prefix + "HYLO_TRAJ", &t);
		if (o_.once || o_.request_id >= 0)
			done_ = true;
	}

private:
	static int64_t now_us()
	{
		struct timespec ts;
		clock_gettime(CLOCK_REALTIME, &ts);
		return static_cast<int64_t>(ts.tv_sec) * 1000000 + ts.tv_nsec / 1000;
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
		s.ipopt_options = o_.ipopt_options;
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
		if (!r.modes.count("flight"))
			return {};
		auto it = costs_.find(name);
		if (it == costs_.end())
			it = costs_.emplace(name, takeoff_landing(r, solve_options())).first;
		return it->second;
	}

	void smooth(const hylo::plan_t &p, hylo::traj_t &t)
	{
		if (p.status != hylo::plan_t::STATUS_OK && p.status != hylo::plan_t::STATUS_NOT_PROVEN)
			return fail(t, p.status, "the plan has no path to smooth (plan status " +
							 std::to_string(p.status) + ": " + p.reason + ")");
		auto m = maps_.find(p.map_id);
		if (m == maps_.end())
			return fail(t, hylo::plan_t::STATUS_NO_MAP,
				    "map " + std::to_string(p.map_id) + " of the plan was not received");
		try {
			const RobotParams &r = robot(p.robot);
			TakeoffLanding costs = switch_costs(p.robot, r);
			std::vector<Waypoint> wps;
			for (int i = 0; i < p.n_waypoints; i++) {
				Waypoint w;
				w.mode = p.mode[static_cast<size_t>(i)];
				for (int k = 0; k < 6; k++)
					w.state[k] = p.state[static_cast<size_t>(i)][static_cast<size_t>(k)];
				w.guard = p.guard[static_cast<size_t>(i)] != 0;
				wps.push_back(w);
			}
			SmoothOptions so;
			so.segments_per_edge = o_.segments_per_edge;
			so.ipopt_options = o_.ipopt_options;
			so.full_ipopt_options = o_.full_ipopt_options;
			SmoothResult res = smooth_with_fallbacks(r, wps, m->second.grid, costs, so);
			std::string tried;
			for (const std::string &why : res.rejections) {
				std::fprintf(stderr, "hylo-smooth: request %lld: rejected %s\n",
					     static_cast<long long>(p.request_id), why.c_str());
				tried += (tried.empty() ? "" : "; ") + why;
			}
			if (!res.ok)
				return fail(t, hylo::plan_t::STATUS_NO_PATH,
					    "the plan cannot be followed: " + res.failure + " (tried " + tried + ")");
			const MultiPhaseSolution &s = res.solution;
			double t0 = 0;
			for (size_t k = 0; k < s.phases.size(); k++) {
				const Solution &ph = s.phases[k];
				int8_t mode = static_cast<int8_t>(mode_number(s.modes[k]));
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
			t.energy_j = s.cost;
			t.replay_energy_j = s.replay_cost;
			t.replay_error = s.replay_error;
			t.method = static_cast<int8_t>(res.method);
			// How far above the optimum: below the cheapest solution of the full
			// problem a step reached (one the replay or the domain check
			// rejected); unknown (NaN) when no step reached one.
			t.gap_j = res.method == SmoothMethod::Full ? 0.0
				  : std::isfinite(res.lowest_cost) ? std::max(0.0, s.cost - res.lowest_cost)
								    : std::nan("");
			t.reason = res.method == SmoothMethod::Full
					   ? "smoothed"
					   : std::string("fallback ") + method_name(res.method) + " (" + tried + ")";
			if (!o_.quiet) {
				std::string seq, last;
				for (const std::string &md : s.modes)
					if (md != last) {   // a run cut at walls, via points or edges is one mode
						seq += (seq.empty() ? "" : " -> ") + md;
						last = md;
					}
				std::printf("request %lld: %s; predicted %.6g J, smoothed %.6g J (replay %.6g J, error %.2g), "
					    "T %.4g s, %.2f s to solve, method %s, gap %.4g J\n",
					    static_cast<long long>(p.request_id), seq.c_str(), p.total_cost_j, s.cost,
					    s.replay_cost, s.replay_error, s.T, res.seconds, method_name(res.method), t.gap_j);
				if (o_.compare)
					std::printf("request %lld: graph path, every edge solved exactly: %.6g J\n",
						    static_cast<long long>(p.request_id),
						    graph_path_cost(r, wps, costs, solve_options()));
				std::fflush(stdout);
			}
		} catch (const std::exception &e) {
			fail(t, hylo::plan_t::STATUS_BAD_REQUEST, e.what());
		}
	}

	struct Map {
		std::string robot;
		TerrainGrid grid;
	};
	const Options &o_;
	lcm::LCM &out_;
	std::map<int64_t, Map> maps_;
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
		if (a == "--once" || a == "--compare-graph" || a == "--quiet") {
			(a == "--once" ? o.once : a == "--quiet" ? o.quiet : o.compare) = true;
			continue;
		}
		bool text = a == "--lcm-url" || a == "--out-url" || a == "--channel-prefix" || a == "--ipopt-option" ||
			    a == "--full-ipopt-option";
		bool number = a == "--request-id" || a == "--segments-per-edge";
		if (!text && !number) {
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
				(a == "--ipopt-option" ? o.ipopt_options : o.full_ipopt_options).push_back(parse_ipopt_option(v));
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
		long long n = std::strtoll(v, &end, 10);
		bool id = a == "--request-id";
		if (!*v || *end != '\0' || n < (id ? 0 : 1) || (!id && n > 48)) {
			std::fprintf(stderr, "hylo-smooth: %s wants %s, not '%s'\n", a.c_str(),
				     id ? "an integer >= 0" : "an integer in [1, 48]", v);
			return false;
		}
		if (id)
			o.request_id = n;
		else
			o.segments_per_edge = static_cast<int>(n);
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
	in.subscribe(o.prefix + "HYLO_PLAN", &Smoother::on_plan, &s);
	std::signal(SIGINT, on_signal);
	std::signal(SIGTERM, on_signal);
	while (!g_stop && !s.done()) {
		int r = in.handleTimeout(200);
		if (r < 0)   // end of an input log, or the provider failed
			break;
	}
	return 0;
}
