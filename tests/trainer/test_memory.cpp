// The start's frame (trainer/frame.hpp) and the memory of solutions
// (trainer/memory.hpp). The memory in tests/trainer/memory (two Ambot marine
// rows of the regeneration, 94 and 97, and their sidecar) gives a turned and
// moved query the same guesses, turned and moved, as the query itself; the
// path of row 94 leads row 58 into the basin 31% below the one its own
// starts reach without the refinement's retry (SolveOptions::refine_retry,
// which finds it too); a
// memory of another robot file, mode or stream, or with a malformed line,
// is refused naming the file and line. trainer --solve --memory on the
// command line: test_solve_memory.sh. Prints TAP.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "tests/tap.hpp"
#include "trainer/collocation.hpp"
#include "trainer/dataset.hpp"   // training_solve_options
#include "trainer/files.hpp"
#include "trainer/frame.hpp"
#include "trainer/memory.hpp"
#include "trainer/numerics.hpp"
#include "trainer/params.hpp"

namespace {

using namespace hylo::trainer;
namespace fs = std::filesystem;

const char *kFixture = "tests/trainer/memory";

// x turned by phi about the origin and moved by (dx, dy): a planar pair's
// sampled coordinates (px, py, vx, theta).
std::vector<double> turned(const double *x, double phi, double dx, double dy)
{
	const double c = std::cos(phi), s = std::sin(phi);
	return {dx + c * x[0] - s * x[1], dy + s * x[0] + c * x[1], x[2], x[3] + phi};
}

double largest_difference(const std::vector<double> &a, const std::vector<double> &b)
{
	double d = a.size() == b.size() ? 0 : INFINITY;
	for (size_t k = 0; k < a.size() && k < b.size(); k++)
		d = std::fmax(d, std::fabs(a[k] - b[k]));
	return d;
}

// The fixture copied into dir, with `edit` applied to file `name`'s text.
std::string edited_copy(const std::string &dir, const std::string &name, const std::string &from,
			const std::string &to)
{
	fs::remove_all(dir);
	fs::create_directories(dir);
	for (const auto &e : fs::directory_iterator(kFixture))
		fs::copy_file(e.path(), dir + "/" + e.path().filename().string());
	std::string text = read_file(dir + "/" + name);
	const size_t at = text.find(from);
	if (at == std::string::npos)
		throw std::logic_error("edited_copy: no '" + from + "' in " + name);
	text.replace(at, from.size(), to);
	std::ofstream(dir + "/" + name, std::ios::binary | std::ios::trunc) << text;
	return dir;
}

}  // namespace

int main(int argc, char **argv)
{
	if (!pin_numerics(argc, argv))
		return 1;
	RobotParams ambot = load_robot("trainer/params/ambot.yaml");

	// ---- the frame --------------------------------------------------------
	{
		const double a[4] = {5, -3, 0.5, 1.0}, b[4] = {7, -1, 0.2, 2.5};
		Frame f = start_frame(HYLO_MODE_GROUND, a);
		std::vector<double> ca(a, a + 4), cb(b, b + 4);
		sampled_into_frame(f, ca.data());
		sampled_into_frame(f, cb.data());
		const double c = std::cos(1.0), s = std::sin(1.0);
		const std::vector<double> want_b = {c * 2 + s * 2, -s * 2 + c * 2, 0.2, 1.5};
		check(largest_difference(ca, {0, 0, 0.5, 0}) == 0 && largest_difference(cb, want_b) < 1e-15,
		      "a planar pair in its start's frame: the start at the origin facing +x, the goal turned by -theta1");
		std::vector<double> out = {1, 2, 0.3, -0.1, 0.7, 0.2};
		full_out_of_frame(f, out);
		const std::vector<double> want_out = {5 + c * 1 - s * 2, -3 + s * 1 + c * 2, 0.3, -0.1, 1.7, 0.2};
		check(largest_difference(out, want_out) < 1e-15,
		      "a planar full state out of the frame: position turned and moved, heading turned, body velocities kept");
		const double fa[6] = {1, 2, 3, 0.5, 0, 0}, fb[6] = {4, 6, 3, 0, 0.5, 0};
		Frame ff = start_frame(HYLO_MODE_FLIGHT, fa);
		std::vector<double> cfb(fb, fb + 6);
		sampled_into_frame(ff, cfb.data());
		Frame fd = start_frame(HYLO_MODE_DI_NEG, b);
		std::vector<double> cd = {-0.5, 0.1};
		sampled_into_frame(fd, cd.data());
		check(largest_difference(cfb, {3, 4, 0, 0, 0.5, 0}) == 0 && largest_difference(cd, {-0.5, 0.1}) == 0,
		      "flight is only moved (its velocities are the world's); the double integrator's plane is absolute");
	}

	// ---- the memory ----------------------------------------------------------
	const double a58[4] = {0, 0, 0.86799138502896156, 0};
	const double b58[4] = {-1.9253079989130777, -3.9534500931621914, 0, -2.6574456804180704};
	try {
		Memory m(ambot, HYLO_MODE_MARINE, kFixture);
		check(m.rows() == 2 && m.sidecar() == std::string(kFixture) + "/marine.solutions.csv",
		      "the fixture's two converged rows are the memory");
		const std::vector<double> ta = turned(a58, 1.0, 5, -3), tb = turned(b58, 1.0, 5, -3);
		std::vector<Guess> g0 = m.guesses(ambot, a58, b58, 1), g1 = m.guesses(ambot, ta.data(), tb.data(), 1);
		const Frame f = start_frame(HYLO_MODE_MARINE, ta.data());
		double d = g0.size() == 1 && g1.size() == 1 && g0[0].path.size() == g1[0].path.size() ? 0 : INFINITY;
		for (size_t p = 0; std::isfinite(d) && p < g1[0].path.size(); p++) {
			std::vector<double> x = g0[0].path[p];
			full_out_of_frame(f, x);
			d = std::fmax(d, largest_difference(x, g1[0].path[p]));
		}
		check(d < 1e-9 && g1[0].T == g0[0].T &&
			      largest_difference(g1[0].path.front(), full_state(HYLO_MODE_MARINE, ambot, ta.data())) == 0 &&
			      largest_difference(g1[0].path.back(), full_state(HYLO_MODE_MARINE, ambot, tb.data())) == 0,
		      "a turned and moved query gets the same nearest row, its path turned and moved, from a to b",
		      "largest difference " + tap_num(d, 3));
		check(m.guesses(ambot, a58, b58, 8).size() == 2 && m.guesses(ambot, a58, b58, 0).empty(),
		      "K beyond the rows gives every row; K = 0 none");
		SolveOptions o = training_solve_options();
		o.refine_retry = false;
		Solution own = solve_bvp(HYLO_MODE_MARINE, ambot, a58, b58, o);
		Solution warm = solve_bvp_guesses(HYLO_MODE_MARINE, ambot, a58, b58, o, m.guesses(ambot, a58, b58, 8), own);
		check(own.converged && warm.converged && warm.cost <= 0.75 * own.cost && improves_on(warm, own),
		      "row 58: a neighbour's path leads into a basin at least 25% below its own starts' (no refinement retry)",
		      tap_num(own.cost, 7) + " J -> " + tap_num(warm.cost, 7) + " J");
	} catch (const std::exception &e) {
		check(false, "the fixture loads", e.what());
	}

	const std::string tmp = (fs::temp_directory_path() / ("hylo_test_memory_" + std::to_string(getpid()))).string();
	auto refused = [&](const std::string &dir, const std::string &needle, const std::string &name) {
		check_throws([&] { Memory m(ambot, HYLO_MODE_MARINE, dir); }, needle, name);
	};
	refused(tmp + "/none", "memory: no " + tmp + "/none/marine.csv.meta", "a missing memory names the file it lacks");
	check_throws([&] { Memory m(ambot, HYLO_MODE_GROUND, kFixture); }, "no tests/trainer/memory/ground.csv.meta",
		     "another mode's memory: the file this mode lacks");
	refused(edited_copy(tmp + "/robot", "marine.csv.meta", "robot: ambot", "robot: drivocopter"),
		"marine.csv.meta has robot 'drivocopter', not this robot file's 'ambot'", "another robot's dataset");
	refused(edited_copy(tmp + "/sha", "marine.solutions.csv.meta", "params_sha256: f", "params_sha256: 0"),
		"marine.solutions.csv.meta has params_sha256", "another robot file's sidecar");
	refused(edited_copy(tmp + "/seed", "marine.solutions.csv.meta", "seed: 1", "seed: 2"), "is not " + tmp + "/seed/marine.csv's stream",
		"a sidecar of another stream");
	refused(edited_copy(tmp + "/line", "marine.solutions.csv", "\n97,", "\n96,"),
		"marine.solutions.csv line 3: not the sidecar row of sample 97", "a sidecar line of another sample: named by line");
	refused(edited_copy(tmp + "/number", "marine.solutions.csv", "\n97,4", "\n97,x4"),
		"marine.solutions.csv line 3: a result or path column is not a number", "a sidecar line with a malformed number");
	refused(edited_copy(tmp + "/row", "marine.csv", "\n97,", "\n97,x,"), "marine.csv line 3: not a row of a marine dataset",
		"a malformed dataset row: named by line");
	refused(edited_copy(tmp + "/header", "marine.csv", "index,", "idx,"), "marine.csv line 1 is not the header",
		"a dataset without the header");
	fs::remove_all(tmp);
	return tap_finish();
}
