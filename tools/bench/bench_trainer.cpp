// Trainer solve times: median wall time and Ipopt iterations per mode on a
// fixed set of BVPs (the same starts, tolerance and meshes every run), and
// the same BVPs as single Ipopt solves of the bare transcription (one T guess,
// no continuation, no refinement, no replay) for tools/bench/casadi_hs.py to
// solve with CasADi side by side: those go to argv[2] as JSON.
// Writes a table to stdout and JSON rows to argv[1].
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "tools/bench/results.hpp"
#include "trainer/collocation.hpp"
#include "trainer/numerics.hpp"
#include "trainer/params.hpp"

namespace {

using namespace hylo::trainer;

struct Case {
	const char *robot;
	hylo_mode mode;
	std::vector<std::vector<double>> pairs;   // x1s then x2s, flattened
};

double median(std::vector<double> v)
{
	std::sort(v.begin(), v.end());
	size_t n = v.size();
	return n == 0 ? 0 : n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// Bare single solves (median time of 5) of every DI, ground and marine BVP,
// with what the CasADi side needs to pose the same problem.
int bare_solves(const std::vector<Case> &cases, const char *path)
{
	std::FILE *f = std::fopen(path, "w");
	if (!f)
		return 1;
	std::fprintf(f, "[\n");
	bool first = true;
	for (const Case &c : cases) {
		if (c.mode == HYLO_MODE_FLIGHT)
			continue;
		RobotParams r = load_robot(robot_file(c.robot));
		for (const auto &p : c.pairs) {
			size_t d = p.size() / 2;
			SolveOptions o;
			o.continuation = false;
			o.refinements = 0;
			o.replay = false;
			o.T_guesses = {std::max(0.2, std::hypot(p[d] - p[0], p[d + 1] - p[1]) / 0.5)};
			std::vector<double> secs;
			Solution s;
			for (int rep = 0; rep < 5; rep++) {
				s = solve_bvp(c.mode, r, p.data(), p.data() + d, o);
				secs.push_back(s.solve_seconds);
			}
			std::fprintf(f, "%s {\"robot\": \"%s\", \"mode\": \"%s\", \"x1s\": [", first ? "" : ",\n",
				     c.robot, hylo_mode_str(c.mode));
			for (size_t k = 0; k < d; k++)
				std::fprintf(f, "%s%.17g", k ? ", " : "", p[k]);
			std::fprintf(f, "], \"x2s\": [");
			for (size_t k = 0; k < d; k++)
				std::fprintf(f, "%s%.17g", k ? ", " : "", p[d + k]);
			std::fprintf(f, "], \"T_guess\": %.17g, \"segments\": %d, \"tol\": %.17g, "
				     "\"hylo\": {\"converged\": %s, \"seconds\": %.9g, \"iterations\": %d, "
				     "\"cost\": %.17g, \"T\": %.17g}}",
				     o.T_guesses[0], o.segments, o.tol, s.converged ? "true" : "false", median(secs),
				     s.iterations, s.cost, s.T);
			first = false;
		}
	}
	std::fprintf(f, "\n]\n");
	std::fclose(f);
	return 0;
}

}  // namespace

int main(int argc, char **argv)
{
	if (!pin_numerics(argc, argv))
		return 1;
	if (argc < 2 || argc > 3) {
		std::fprintf(stderr, "usage: %s RESULTS.json [BARE_SOLVES.json]\n", argv[0]);
		return 2;
	}
	const std::vector<Case> cases = {
		{"di", HYLO_MODE_DI_NEG, {{-0.5, 0, -0.3, 0}, {-0.9, 0.3, -0.1, -0.2}, {-0.2, -0.5, -0.8, 0.1}, {-0.6, 0.2, -0.6, -0.2}, {-0.4, 0, -0.1, 0}}},
		{"ambot", HYLO_MODE_GROUND, {{0, 0, 1, 0, 3, 0, 1, 0}, {0, 0, 0, 0, 3, 1, 0.5, 0.5}, {0, 0, 0.5, 0, 2, -2, 0.5, -1.5}, {0, 0, 0, 0, -2, 1, 0, 3.1}, {0, 0, 1, 0, 4, 1, 0.8, 0.2}}},
		{"ambot", HYLO_MODE_MARINE, {{0, 0, 0.5, 0, 3, 1, 0.5, 0.5}, {0, 0, 0, 0, 2, 0, 0, 0}, {0, 0, 0.8, 0, 4, -1, 0.8, -0.3}, {0, 0, 0.3, 0, -1, 2, 0.3, 2.0}, {0, 0, 0.6, 0, 3, 0, 0.6, 0}}},
		{"drivocopter", HYLO_MODE_FLIGHT, {{0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0}, {0, 0, 1, 0, 0, 0, 3, 1, 1.5, 0, 0, 0}, {0, 0, 1, 2, 0, 0, 6, 2, 0, 4, 1, -1}, {0, 0, 1, 5, -1, 0, -2, 4, 3, 0, 0, 0}, {0, 0, 0, 6, 0, 0, 8, 0, 0, 6, 0, 0}}},
	};
	std::vector<BenchRow> rows;
	std::printf("trainer solve time per BVP (all starts, continuation and refinement), median\n");
	std::printf("  %-20s %6s %10s %10s %10s\n", "mode", "BVPs", "accepted", "median s", "median it");
	for (const Case &c : cases) {
		RobotParams r = load_robot(robot_file(c.robot));
		std::vector<double> secs, its;
		int ok = 0;
		for (const auto &p : c.pairs) {
			size_t d = p.size() / 2;
			Solution s = solve_bvp(c.mode, r, p.data(), p.data() + d, SolveOptions());
			secs.push_back(s.solve_seconds);
			if (s.converged) {
				ok++;
				its.push_back(s.iterations);
			}
		}
		std::string name = std::string(c.robot) + " " + hylo_mode_str(c.mode);
		std::printf("  %-20s %6zu %10d %10.3f %10.0f\n", name.c_str(), c.pairs.size(), ok,
			    median(secs), median(its));
		rows.push_back(bench_row("trainer_solve_s_" + std::string(c.robot) + "_" + hylo_mode_str(c.mode), median(secs), "s"));
		rows.push_back(bench_row("trainer_accepted_" + std::string(c.robot) + "_" + hylo_mode_str(c.mode), ok,
					 "of " + std::to_string(c.pairs.size()) + " BVPs"));
	}
	if (!write_bench_results(argv[1], rows))
		return 1;
	if (argc == 3)
		return bare_solves(cases, argv[2]);
	return 0;
}
