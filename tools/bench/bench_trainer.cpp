// Trainer solve times: median wall time and Ipopt iterations per mode on a
// fixed set of BVPs (the same starts, tolerance and meshes every run).
// No CasADi reference yet (issue 3 asks for one): rows carry no ratio.
// Writes a table to stdout and JSON rows to argv[1].
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "trainer/collocation.hpp"
#include "trainer/params.hpp"

namespace {

using namespace hylo::trainer;

struct Case {
	const char *robot, *mode;
	std::vector<std::vector<double>> pairs;   // x1s then x2s, flattened
};

double median(std::vector<double> v)
{
	std::sort(v.begin(), v.end());
	size_t n = v.size();
	return n == 0 ? 0 : n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

int main(int argc, char **argv)
{
	if (argc != 2) {
		std::fprintf(stderr, "usage: %s RESULTS.json\n", argv[0]);
		return 2;
	}
	const std::vector<Case> cases = {
		{"di", "di_neg", {{-0.5, 0, -0.3, 0}, {-0.9, 0.3, -0.1, -0.2}, {-0.2, -0.5, -0.8, 0.1}, {-0.6, 0.2, -0.6, -0.2}, {-0.4, 0, -0.1, 0}}},
		{"ambot", "ground", {{0, 0, 1, 0, 3, 0, 1, 0}, {0, 0, 0, 0, 3, 1, 0.5, 0.5}, {0, 0, 0.5, 0, 2, -2, 0.5, -1.5}, {0, 0, 0, 0, -2, 1, 0, 3.1}, {0, 0, 1, 0, 4, 1, 0.8, 0.2}}},
		{"ambot", "marine", {{0, 0, 0.5, 0, 3, 1, 0.5, 0.5}, {0, 0, 0, 0, 2, 0, 0, 0}, {0, 0, 0.8, 0, 4, -1, 0.8, -0.3}, {0, 0, 0.3, 0, -1, 2, 0.3, 2.0}, {0, 0, 0.6, 0, 3, 0, 0.6, 0}}},
		{"drivocopter", "flight", {{0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0}}},
	};
	std::FILE *f = std::fopen(argv[1], "w");
	if (!f)
		return 1;
	std::fprintf(f, "[\n");
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
		std::string name = std::string(c.robot) + " " + c.mode;
		std::printf("  %-20s %6zu %10d %10.3f %10.0f\n", name.c_str(), c.pairs.size(), ok,
			    median(secs), median(its));
		std::fprintf(f, " {\"name\": \"trainer_solve_s_%s_%s\", \"value\": %.6g, \"unit\": \"s\", "
			     "\"reference\": null, \"reference_value\": null, \"ratio\": null},\n",
			     c.robot, c.mode, median(secs));
		std::fprintf(f, " {\"name\": \"trainer_accepted_%s_%s\", \"value\": %d, \"unit\": \"of %zu BVPs\", "
			     "\"reference\": null, \"reference_value\": null, \"ratio\": null}%s\n",
			     c.robot, c.mode, ok, c.pairs.size(), &c == &cases.back() ? "" : ",");
	}
	std::fprintf(f, "]\n");
	std::fclose(f);
	return 0;
}
