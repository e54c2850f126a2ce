// trainer: the offline half of hylo. main() pins the numerics, parses flags
// and calls run(); see --help. Exit codes: 0 done, 1 failure while running
// (I/O, a worker, numerics that cannot be pinned), 2 bad usage or input
// (unknown mode or robot, malformed vector, a state out of bounds, an unusable
// output directory or dataset).
#include <malloc.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "trainer/cli.hpp"
#include "trainer/collocation.hpp"
#include "trainer/dataset.hpp"
#include "trainer/memory.hpp"
#include "trainer/numerics.hpp"
#include "trainer/params.hpp"
#include "trainer/pipeline.hpp"
#include "trainer/switching.hpp"

namespace {

using namespace hylo::trainer;

class Usage : public std::invalid_argument {
public:
	using std::invalid_argument::invalid_argument;
};

std::string joined(const std::vector<std::string> &v)
{
	std::string out;
	for (const std::string &x : v)
		out += (out.empty() ? "" : ", ") + x;
	return out;
}

bool has_mode(const std::vector<std::string> &modes, const std::string &mode)
{
	return std::find(modes.begin(), modes.end(), mode) != modes.end();
}

// The robots of trainer/params/ with their modes, one line each; with mode
// set, only those that have it.
std::string robots_text(const std::string &mode)
{
	std::string out;
	for (const auto &r : list_robots())
		if (mode.empty() || has_mode(r.second, mode))
			out += "\n  " + r.first + " (" + (r.second.empty() ? "does not load" : joined(r.second)) + ")";
	std::string where = robot_dir() + "/" + (mode.empty() ? "" : " with mode " + mode);
	return out.empty() ? "no robot in " + where : "robots in " + where + ":" + out;
}

void usage(FILE *f)
{
	std::fprintf(f,
		"usage: trainer --mode M --robot R [options]\n"
		"       trainer --mode M --robot R --solve X1 X2 [--memory DIR] [--json] [--trajectory]\n"
		"       trainer --mode switch --robot R [--json]\n"
		"Generates training data by trajectory optimization (Hermite-Simpson\n"
		"collocation with Ipopt, checked by a CVODE replay), fits the SVR cost model\n"
		"and exports it as onboard/models/<robot>_<mode>.h, with its envelope (ground,\n"
		"marine, flight: lower bounds of its cost over every heading, per distance,\n"
		"turn or climb, and speeds).\n"
		"\n"
		"  --mode M          di_neg, di_pos, ground, marine or flight (required); switch:\n"
		"                    print the robot's mode switches and their costs (docs/models.md\n"
		"                    section 6; Drivocopter takeoff and landing are solved, ~20 s)\n"
		"  --robot R         robot parameter file trainer/params/R.yaml (required; installed:\n"
		"                    PREFIX/share/hylo/params/R.yaml; $HYLO_PARAMS_DIR/R.yaml first)\n"
		"  --stage S         gen, repair, remesh, fit, export, region, all (gen, fit, export) or\n"
		"                    gather (default: all; gen with --shard); export reads the\n"
		"                    header fit wrote into --out and adds the envelope (minutes).\n"
		"                    region: writes the trained region into the header in\n"
		"                    --models-dir from the dataset in --out it was fitted on,\n"
		"                    changing nothing else. repair: each of the dataset's first\n"
		"                    N rows is solved again and from the solutions of its\n"
		"                    --neighbours nearest rows (kept in <out>/<mode>.solutions.csv,\n"
		"                    resumable); a label is only ever lowered; the dataset is\n"
		"                    replaced atomically when every row is done (resumable, its\n"
		"                    .meta records the repair; docs/decisions.md); after gen has\n"
		"                    extended a repaired dataset, only the rows past the repaired\n"
		"                    ones (same settings). remesh: each of the first N rows\n"
		"                    labelled on a coarser mesh than its mode now accepts (ground\n"
		"                    80 segments, marine 40) is solved again from its own solution\n"
		"                    in the sidecar, and the finer mesh's label replaces it\n"
		"                    (resumable, atomic, recorded in the .meta like repair)\n"
		"  --samples N       training pairs: gen extends the dataset to N rows, repair\n"
		"                    and fit use its first N (default: ground and marine 8640,\n"
		"                    14400 under --draws 3, 11520 under 1 or 2; flight 17016;\n"
		"                    di 4000, 2000 under --draws 1; or the dataset's rows when\n"
		"                    it holds more)\n"
		"  --neighbours K    repair, --solve: warm starts from the K nearest rows' solutions\n"
		"                    (default: 8)\n"
		"  --solutions       gen: also keep each row's solution in <out>/<mode>.solutions.csv\n"
		"                    as it is solved, so that repair need not solve the rows again\n"
		"                    (unsharded runs; default: off)\n"
		"  --refine-within F ground, marine: refine only the starts whose coarse cost is\n"
		"                    within F of the best refined one; inf: refine every start\n"
		"                    (pruning is 1.4-2x faster but loses optima; docs/decisions.md)\n"
		"                    (recorded in a dataset's .meta; default: inf)\n"
		"  --jobs J          worker processes (gen), threads (fit, export) (default:\n"
		"                    number of cores)\n"
		"  --seed S          seed of the sample stream (default: 1)\n"
		"  --out DIR         dataset directory (default: build/datasets/<robot>)\n"
		"  --shard K/N       generate only the K-th of N slices of the stream into\n"
		"                    <out>/<mode>.shard-K-of-N.csv (default: 1/1); gen only\n"
		"  --shards N        gather: check the N shards in --out (same --samples, --seed\n"
		"                    and solver options), name the ones to resubmit (exit 1) or\n"
		"                    move away (exit 2), else merge them into <out>/<mode>.csv,\n"
		"                    byte for byte an unsharded run's (docs/trainer.md)\n"
		"  --draws N         ground, marine: how pairs are drawn: 4, draw 2's pairs\n"
		"                    but 2,880 cruise pairs from row 5,760 on (goal on an arc,\n"
		"                    speeds at rest, at the top speed or between); 3, draw 2's\n"
		"                    first 11,520 pairs, then cruise pairs; 2, speeds at rest\n"
		"                    with probability 0.2 (the planner's starts, goals and\n"
		"                    switch points); 1, uniform speeds only (recorded in a\n"
		"                    dataset's .meta; default: the existing dataset's in --out,\n"
		"                    else 4); di_neg, di_pos: 2, draw 1's 2,000 pairs, then\n"
		"                    2,000 short ones; 1 (docs/trainer.md, \"Draws\")\n"
		"  --segments N      collocation segments of a start's first mesh (default: 20;\n"
		"                    ground labels are accepted on 80 or more, marine on 40)\n"
		"  --ipopt-option NAME=VALUE\n"
		"                    set an Ipopt option on every solve, after hylo's own settings\n"
		"                    (repeatable; recorded in a dataset's .meta; default: none)\n"
		"  --relabel FILE    gen, ground and marine: FILE is this stream's dataset as\n"
		"                    labelled before the backing-up and goal-facing starts\n"
		"                    (its .meta has no 'starts:' line); its results are reused\n"
		"                    and only those starts solved. A run over such a dataset\n"
		"                    in --out relabels it in place (kept as <file>.straight)\n"
		"  --models-dir DIR  where export writes headers (default: onboard/models)\n"
		"  --compare HEADER  fit: also print the held-out errors of HEADER's model (this\n"
		"                    robot and mode, e.g. the committed one) on the same rows\n"
		"  --solve X1 X2     solve one BVP between sampled states (comma-separated,\n"
		"                    docs/models.md section 7 order) and print the result\n"
		"  --memory DIR      --solve: also start from the solutions of the K nearest rows\n"
		"                    of the dataset DIR/<mode>.csv, kept in DIR/<mode>.solutions.csv\n"
		"                    (gen --solutions), moved into the pair's frame: the basins\n"
		"                    its labels reached; none: the pair's own starts only\n"
		"                    (default: trainer/datasets/<robot> if it has the sidecar)\n"
		"  --json            --solve: print JSON\n"
		"  --trajectory      --solve --json: include time, state and input samples\n"
		"  --quiet           no progress output\n"
		"  --debug           trace every Ipopt solve, replay, cross-validation point and\n"
		"                    envelope stage on stderr (default: off)\n"
		"  --version         the version and what labels depend on (BLAS, LAPACK, libm,\n"
		"                    Ipopt, MUMPS), then exit\n"
		"  --help            this text\n"
		"\n"
		"Labels do not depend on the CPU: the reference BLAS and LAPACK are linked, and\n"
		"on x86-64 the trainer re-executes itself once with libm's AVX2/FMA variants\n"
		"masked (GLIBC_TUNABLES glibc.cpu.hwcaps); it refuses to run with another BLAS.\n"
		"\n"
		"Exit codes: 0 done, 1 failure while running, 2 bad usage or input.\n");
	std::fprintf(f, "\n%s\n", robots_text("").c_str());
}

std::vector<double> parse_vector(const std::string &text, int dim, const std::string &what)
{
	std::vector<double> v;
	size_t pos = 0;
	while (pos <= text.size()) {
		size_t end = text.find(',', pos);
		std::string item = text.substr(pos, end == std::string::npos ? std::string::npos : end - pos);
		char *e = nullptr;
		double x = std::strtod(item.c_str(), &e);
		if (item.empty() || !e || *e != '\0' || !std::isfinite(x))
			throw Usage(what + ": '" + item + "' in '" + text + "' is not a finite number");
		v.push_back(x);
		if (end == std::string::npos)
			break;
		pos = end + 1;
	}
	if (static_cast<int>(v.size()) != dim)
		throw Usage(what + ": mode needs " + std::to_string(dim) + " comma-separated numbers, got " +
			    std::to_string(v.size()));
	return v;
}

// memory: the sidecar the memory starts came from ("" without a memory).
void print_solution(const Solution &s, const std::string &mode, const std::string &robot,
		    const std::vector<double> &a, const std::vector<double> &b, bool json, bool traj,
		    const std::string &memory, size_t memory_starts)
{
	auto arr = [](const double *v, size_t n) {
		std::string o = "[";
		for (size_t k = 0; k < n; k++) {
			char buf[32];
			std::snprintf(buf, sizeof buf, "%.17g", v[k]);
			o += (k ? "," : "") + std::string(std::isfinite(v[k]) ? buf : "null");
		}
		return o + "]";
	};
	if (!json) {
		std::printf("%s %s: %s, cost %.6g J, T %.4g s, %d iterations, %d segments, replay error "
			    "%.3g, replay cost %.6g J, %.3f s\n",
			    robot.c_str(), mode.c_str(), s.converged ? "converged" : s.status_text.c_str(),
			    s.cost, s.T, s.iterations, s.segments, s.replay_error, s.replay_cost,
			    s.solve_seconds);
		if (!memory.empty())
			std::printf("  with %zu starts from %s\n", memory_starts, memory.c_str());
		return;
	}
	std::printf("{\"robot\":\"%s\",\"mode\":\"%s\",\"x1\":%s,\"x2\":%s,\"converged\":%s,"
		    "\"status\":\"%s\",\"cost_j\":%.17g,\"T_s\":%.17g,\"iterations\":%d,\"segments\":%d,"
		    "\"starts\":%d,\"converged_starts\":%d,\"refined_starts\":%d,\"replay_error\":%s,\"replay_cost_j\":%s,"
		    "\"solve_s\":%.6f,\"memory\":%s,\"memory_starts\":%zu",
		    robot.c_str(), mode.c_str(), arr(a.data(), a.size()).c_str(),
		    arr(b.data(), b.size()).c_str(), s.converged ? "true" : "false", s.status_text.c_str(),
		    s.cost, s.T, s.iterations, s.segments, s.starts, s.converged_starts, s.refined_starts,
		    arr(&s.replay_error, 1).substr(1, arr(&s.replay_error, 1).size() - 2).c_str(),
		    arr(&s.replay_cost, 1).substr(1, arr(&s.replay_cost, 1).size() - 2).c_str(),
		    s.solve_seconds, memory.empty() ? "null" : ("\"" + memory + "\"").c_str(), memory_starts);
	if (traj && s.converged) {
		const Trajectory &t = s.traj;
		std::printf(",\"trajectory\":{\"t_s\":%s,\"x\":[", arr(t.t.data(), t.t.size()).c_str());
		for (size_t i = 0; i < t.t.size(); i++)
			std::printf("%s%s", i ? "," : "", arr(&t.x[i * static_cast<size_t>(t.nx)], static_cast<size_t>(t.nx)).c_str());
		std::printf("],\"u\":[");
		for (size_t i = 0; i < t.t.size(); i++)
			std::printf("%s%s", i ? "," : "", arr(&t.u[i * static_cast<size_t>(t.nu)], static_cast<size_t>(t.nu)).c_str());
		std::printf("]}");
	}
	std::printf("}\n");
}

// trainer --mode switch: the robot's mode switches (docs/models.md section 6).
int print_switches(const RobotParams &robot, const SolveOptions &opt, bool json)
{
	struct Switch {
		hylo_mode from, to;
		const char *how;
		double cost;
	};
	std::vector<Switch> sw;
	if (robot.has(HYLO_MODE_DI_NEG) && robot.has(HYLO_MODE_DI_POS)) {
		sw.push_back({HYLO_MODE_DI_POS, HYLO_MODE_DI_NEG, "guard p = 0, identity reset", 0});
		sw.push_back({HYLO_MODE_DI_NEG, HYLO_MODE_DI_POS, "guard p = 0, identity reset", 0});
	}
	if (robot.has(HYLO_MODE_GROUND) && robot.has(HYLO_MODE_MARINE)) {
		sw.push_back({HYLO_MODE_GROUND, HYLO_MODE_MARINE, "shoreline, phiL = phiR = phi_n(vx)", 0});
		sw.push_back({HYLO_MODE_MARINE, HYLO_MODE_GROUND, "shoreline, paddle speeds dropped", 0});
	}
	if (robot.has(HYLO_MODE_GROUND) && robot.has(HYLO_MODE_FLIGHT)) {
		TakeoffLanding tl = takeoff_landing(robot, opt);
		sw.push_back({HYLO_MODE_GROUND, HYLO_MODE_FLIGHT, "takeoff: rest at height h -> hover at h + 1", tl.takeoff_j});
		sw.push_back({HYLO_MODE_FLIGHT, HYLO_MODE_GROUND, "landing: hover at h + 1 -> rest at height h", tl.landing_j});
	}
	if (json)
		std::printf("{\"robot\":\"%s\",\"switches\":[", robot.robot.c_str());
	for (size_t i = 0; i < sw.size(); i++) {
		if (json)
			std::printf("%s{\"from\":\"%s\",\"to\":\"%s\",\"cost_j\":%.17g,\"how\":\"%s\"}",
				    i ? "," : "", hylo_mode_str(sw[i].from), hylo_mode_str(sw[i].to), sw[i].cost, sw[i].how);
		else
			std::printf("%s %s -> %s: %.6g J (%s)\n", robot.robot.c_str(), hylo_mode_str(sw[i].from),
				    hylo_mode_str(sw[i].to), sw[i].cost, sw[i].how);
	}
	if (json)
		std::printf("]}\n");
	return 0;
}

// The usage error for a missing --mode or --robot: what exists, and a
// command that would work.
std::string missing_mode_or_robot(const std::string &mode, const std::string &robot)
{
	auto robots = list_robots();
	if (!robot.empty()) {
		for (const auto &r : robots)
			if (r.first == robot && !r.second.empty())
				return "--mode is required (see --help); robot " + robot + " has modes " +
				       joined(r.second) + " (and switch: its mode switches)\ne.g. trainer --mode " +
				       r.second[0] + " --robot " + robot;
		return "--mode is required (see --help); " + robots_text("");
	}
	std::string text = (mode.empty() ? "--mode and --robot are required" : "--robot is required") +
			   std::string(" (see --help); ") + robots_text(mode == "switch" ? "" : mode);
	for (const auto &r : robots)
		if (!r.second.empty() && (mode.empty() || mode == "switch" || has_mode(r.second, mode)))
			return text + "\ne.g. trainer --mode " + (mode.empty() ? r.second[0] : mode) + " --robot " +
			       r.first;
	return text;
}

int run(int argc, char **argv)
{
	PipelineOptions po;
	std::string mode, robot_name, solve1, solve2, stage, memory_dir;
	int gather_shards = 0;
	bool solve = false, json = false, traj = false;
	po.gen.jobs = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
	long long samples = -1;
	for (int i = 1; i < argc; i++) {
		std::string a = argv[i];
		auto val = [&] { return option_value(argc, argv, i); };
		auto integer = [&](long long lo) -> long long {
			std::string v = val();
			char *e = nullptr;
			long long n = std::strtoll(v.c_str(), &e, 10);
			if (v.empty() || *e || n < lo)
				throw Usage(a + " needs an integer >= " + std::to_string(lo) + ", not '" + v + "'");
			return n;
		};
		if (a == "--help" || a == "-h") {
			usage(stdout);
			return 0;
		} else if (a == "--version") {
			std::printf("hylo trainer %s\n%s", kHyloVersion, numerics_description().c_str());
			return 0;
		} else if (a == "--ipopt-option") {
			std::string v = val();
			try {
				po.gen.solve.ipopt_options.push_back(parse_ipopt_option(v));
			} catch (const std::invalid_argument &e) {
				throw Usage("--ipopt-option: " + std::string(e.what()));
			}
		} else if (a == "--debug") {
			po.gen.solve.debug = true;
		} else if (a == "--mode") {
			mode = val();
		} else if (a == "--robot") {
			robot_name = val();
		} else if (a == "--stage") {
			stage = val();
		} else if (a == "--samples") {
			samples = integer(1);
		} else if (a == "--jobs") {
			po.gen.jobs = static_cast<int>(integer(1));
		} else if (a == "--seed") {
			po.gen.seed = static_cast<uint64_t>(integer(0));
		} else if (a == "--out") {
			po.gen.out_dir = val();
		} else if (a == "--refine-within") {
			std::string v = val();
			char *e = nullptr;
			double x = v == "inf" ? std::numeric_limits<double>::infinity() : std::strtod(v.c_str(), &e);
			if (v != "inf" && (v.empty() || *e || !(x >= 0) || !std::isfinite(x)))
				throw Usage("--refine-within needs a fraction >= 0 or inf, not '" + v + "'");
			po.gen.solve.refine_within = x;
		} else if (a == "--neighbours") {
			po.neighbours = static_cast<int>(integer(1));
		} else if (a == "--relabel") {
			po.gen.relabel = val();
		} else if (a == "--models-dir") {
			po.models_dir = val();
		} else if (a == "--compare") {
			po.compare = val();
		} else if (a == "--solutions") {
			po.solutions = true;
		} else if (a == "--draws") {
			po.gen.draws = static_cast<int>(integer(1));
		} else if (a == "--segments") {
			po.gen.solve.segments = static_cast<int>(integer(2));
		} else if (a == "--shards") {
			gather_shards = static_cast<int>(integer(2));
		} else if (a == "--shard") {
			std::string v = val();
			int k = 0, n = 0;
			char extra;
			if (std::sscanf(v.c_str(), "%d/%d%c", &k, &n, &extra) != 2 || n < 1 || k < 1 || k > n)
				throw Usage("--shard needs K/N with 1 <= K <= N, not '" + v + "'");
			po.gen.shard = k;
			po.gen.shards = n;
		} else if (a == "--solve") {
			solve = true;
			solve1 = val();
			solve2 = val();
		} else if (a == "--memory") {
			memory_dir = val();
		} else if (a == "--json") {
			json = true;
		} else if (a == "--trajectory") {
			traj = true;
		} else if (a == "--quiet") {
			po.gen.progress = false;
		} else {
			throw Usage("unknown option '" + a + "' (see --help)");
		}
	}
	if (!mode.empty() && !known_mode(mode) && mode != "switch")
		throw Usage("unknown mode '" + mode + "' (" + mode_list() + ", switch)");
	if (mode.empty() || robot_name.empty())
		throw Usage(missing_mode_or_robot(mode, robot_name));
	RobotParams robot;
	try {
		robot = load_robot(robot_file(robot_name));
	} catch (const ParamError &e) {
		throw Usage(std::string("robot '") + robot_name + "': " + e.what() + "; " + robots_text(mode == "switch" ? "" : mode));
	}
	if (mode == "switch")
		return print_switches(robot, po.gen.solve, json);
	if (!robot.modes.count(mode))
		throw Usage("robot " + robot_name + " has no mode '" + mode + "'; " + robots_text(mode == "switch" ? "" : mode));
	const hylo_mode id = parse_mode(mode);   // inside, the mode travels as hylo_mode
	if (solve) {
		int d = mode_desc(id).xs_dim;
		std::vector<double> a = parse_vector(solve1, d, "--solve X1"), b = parse_vector(solve2, d, "--solve X2");
		Solution s;
		std::string memory;
		size_t memory_starts = 0;
		try {
			const std::unique_ptr<Memory> m = open_memory(memory_dir, robot_name, robot, id);
			if (m)
				memory = m->sidecar();
			s = solve_remembered(id, robot, a.data(), b.data(), po.gen.solve, m.get(), po.neighbours,
					     &memory_starts);
		} catch (const std::invalid_argument &e) {
			throw Usage(e.what());
		}
		print_solution(s, mode, robot_name, a, b, json, traj, memory, memory_starts);
		return 0;
	}
	if (!memory_dir.empty())
		throw Usage("--memory is for --solve (a dataset's stages read no memory)");
	po.gen.mode = id;
	if (po.gen.out_dir.empty())
		po.gen.out_dir = "build/datasets/" + robot_name;
	if (po.gen.draws == 0)
		po.gen.draws = existing_draws(po.gen);
	draws_for(id, po.gen.draws);   // a draw the mode has
	po.gen.samples = samples > 0 ? static_cast<uint64_t>(samples) : default_samples(po.gen);
	if (stage.empty())   // a shard task only generates (the gather step makes the dataset)
		stage = po.gen.shards > 1 ? "gen" : "all";
	if (stage != "gen" && stage != "repair" && stage != "remesh" && stage != "fit" && stage != "export" &&
	    stage != "all" && stage != "gather" && stage != "region")
		throw Usage("unknown stage '" + stage + "' (gen, repair, remesh, fit, export, region, all, gather)");
	if (stage == "gather") {
		if (gather_shards == 0 || po.gen.shards > 1)
			throw Usage("--stage gather needs --shards N (the N of the tasks' --shard K/N), not --shard");
		po.gen.shards = gather_shards;
	} else if (gather_shards != 0) {
		throw Usage("--shards N is for --stage gather; a shard task takes --shard K/N");
	}
	if (!po.compare.empty() && stage != "fit" && stage != "all")
		throw Usage("--compare HEADER is for the fit (--stage fit or all), not --stage " + stage);
	return run_pipeline(robot, po, stage);
}

}  // namespace

int main(int argc, char **argv)
{
	if (!pin_numerics(argc, argv))
		return 1;
	// Keep freed memory in the heap: MUMPS allocates and frees its workspace
	// at every factorization (10% faster, same labels; docs/decisions.md).
	mallopt(M_MMAP_THRESHOLD, 256 << 20);
	mallopt(M_TRIM_THRESHOLD, 512 << 20);
	return run_main("trainer", run, argc, argv);
}
