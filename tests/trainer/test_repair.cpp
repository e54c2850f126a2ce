// The repair stage (trainer --stage repair, trainer/repair.hpp) and its warm
// start. A neighbour's solution, transplanted, leads Ambot ground sample 0
// (a goal behind and to the left) into the basin 25% below the one the
// straight-line starts reach. On a small double-integrator dataset with
// labels made dearer, cheaper and removed by hand: the dear label is lowered
// back, the impossibly cheap one is kept byte for byte (a repair never
// raises a label), the removed one converges again, the rows past N are
// untouched, the sidecar line of the row a neighbour's path solved becomes
// that solution; --jobs does not change a byte; a repair killed part-way
// (solving the sidecar, or repairing) and resumed (torn rows appended) gives
// the same bytes; a second repair does nothing; generation extends a
// repaired dataset, and a repair of more rows repairs only the new ones
// (killed and resumed, the same bytes). Warm starts that repeat a coarse optimum already
// refined are not refined again (the repair's refine_repeats: off). The
// remesh pass (the same stage's other use) moves Ambot ground rows labelled
// on 20 segments onto 80 or more and keeps every other byte. Prints TAP.
#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

#include "tests/tap.hpp"
#include "trainer/collocation.hpp"
#include "trainer/dataset.hpp"
#include "trainer/numerics.hpp"
#include "trainer/params.hpp"
#include "trainer/repair.hpp"
#include "trainer/svr_export.hpp"

namespace {

using namespace hylo::trainer;
namespace fs = std::filesystem;

void spit(const std::string &path, const std::string &text)
{
	std::ofstream(path, std::ios::binary | std::ios::trunc) << text;
}

std::vector<std::string> lines_of(const std::string &text)
{
	std::vector<std::string> out;
	std::stringstream ss(text);
	for (std::string l; std::getline(ss, l);)
		out.push_back(l);
	return out;
}

std::string joined(const std::vector<std::string> &lines)
{
	std::string out;
	for (const auto &l : lines)
		out += l + "\n";
	return out;
}

// Row text with field k replaced.
std::string with_field(const std::string &row, size_t k, const std::string &value)
{
	std::vector<std::string> f = csv_fields(row);
	f.at(k) = value;
	std::string out;
	for (size_t i = 0; i < f.size(); i++)
		out += (i ? "," : "") + f[i];
	return out;
}

size_t count_lines(const std::string &path)
{
	std::string t = read_file(path);
	return static_cast<size_t>(std::count(t.begin(), t.end(), '\n'));
}

// Runs work in a child process and kills it (SIGKILL) once file has at
// least `lines` lines, or after 20 s.
template <class Work>
void kill_part_way(Work work, const std::string &file, size_t lines)
{
	pid_t pid = fork();
	if (pid == 0) {
		try {
			work();
		} catch (...) {
		}
		_exit(0);
	}
	for (int k = 0; k < 20000 && count_lines(file) < lines; k++)
		usleep(1000);
	kill(pid, SIGKILL);
	waitpid(pid, nullptr, 0);
}

// The remesh pass on tests/trainer/remesh, the first 20 rows of Ambot
// ground's dataset and its sidecar, rows 7 and 14 as labelled on 20
// segments, the rest remeshed onto 80 (row 18: on 40, where 80 failed;
// row 10 did not converge) by this pass's first run: the first 16
// remeshed from their sidecar paths, then the first 8 of a copy without a
// sidecar, solved again in full.
void remesh_checks(const fs::path &dir)
{
	RobotParams ambot = load_robot("trainer/params/ambot.yaml");
	const std::string src = "tests/trainer/remesh/ground";
	fs::create_directories(dir / "side");
	fs::create_directories(dir / "bare");
	for (const char *d : {"side", "bare"})
		for (const char *f : {".csv", ".csv.meta"})
			fs::copy_file(src + f, dir / d / (std::string("ground") + f));
	for (const char *f : {".solutions.csv", ".solutions.csv.meta"})
		fs::copy_file(src + f, dir / "side" / (std::string("ground") + f));
	const std::vector<std::string> before = lines_of(read_file((dir / "side" / "ground.csv").string())),
				       side_before = lines_of(read_file((dir / "side" / "ground.solutions.csv").string()));
	const std::string meta_before = read_file((dir / "side" / "ground.csv.meta").string());
	const size_t iseg = csv_column(HYLO_MODE_GROUND, "segments"), ic = csv_column(HYLO_MODE_GROUND, "cost_j");
	auto seg = [&](const std::string &row) { return std::stoi(csv_fields(row)[iseg]); };
	check(before.size() == 21 && seg(before[8]) == 20 && seg(before[15]) == 20,
	      "remesh: rows 7 and 14 of the fixture are labelled on 20 segments");
	if (before.size() != 21)
		return;

	RepairOptions r;
	r.remesh = true;
	r.gen.mode = HYLO_MODE_GROUND;
	r.gen.draws = std::stoi(internal::meta_value(meta_before, "draws"));
	r.gen.samples = 16;
	r.gen.jobs = 2;
	r.gen.progress = false;
	r.gen.out_dir = (dir / "side").string();
	RepairSummary s = repair(ambot, r);
	const std::vector<std::string> after = lines_of(read_file((dir / "side" / "ground.csv").string())),
				       side_after = lines_of(read_file((dir / "side" / "ground.solutions.csv").string()));
	bool others_same = after.size() == before.size() && side_after.size() == side_before.size();
	for (size_t i = 0; others_same && i < after.size(); i++)
		if (i != 8 && i != 15)
			others_same = after[i] == before[i] && side_after[i] == side_before[i];
	check(others_same, "remesh: the rows remeshed before, and the rows past N, keep their bytes "
			   "and their sidecar lines");
	bool finer = true;
	for (size_t i : {8, 15}) {
		const std::vector<std::string> f = csv_fields(after[i]);
		finer = finer && seg(after[i]) >= 80 && f[csv_column(HYLO_MODE_GROUND, "converged")] == "1" &&
			side_after[i] != side_before[i] && side_after[i].rfind(f[0] + "," + f[ic] + ",", 0) == 0;
	}
	check(finer && s.relabelled == 2,
	      "remesh: rows 7 and 14 are labelled on 80 or more segments, their sidecar lines their new solutions",
	      std::to_string(s.relabelled) + " relabelled");
	// 20 segments cannot place these edges' turns: the finer labels are
	// lower (56.07 -> 55.79 J, 55.94 -> 54.97 J on this machine).
	check(std::stod(csv_fields(after[8])[ic]) < std::stod(csv_fields(before[8])[ic]) &&
		      std::stod(csv_fields(after[15])[ic]) < 0.995 * std::stod(csv_fields(before[15])[ic]),
	      "remesh: the finer mesh lowers both labels, row 14's by more than 0.5%",
	      csv_fields(before[8])[ic] + " -> " + csv_fields(after[8])[ic] + ", " + csv_fields(before[15])[ic] +
		      " -> " + csv_fields(after[15])[ic]);
	const std::string meta_after = read_file((dir / "side" / "ground.csv.meta").string());
	check(meta_after.rfind(meta_before, 0) == 0 &&
		      meta_after.find("\nremeshed_rows: 16\nremesh_path_points: 21\n") != std::string::npos &&
		      meta_after.find("\nremesh_accept_segments: 80\n") != std::string::npos,
	      "remesh: the .meta keeps the generation's and the repair's lines and adds the remesh's", meta_after);
	check(repair(ambot, r).already, "remesh: a second remesh with the same settings does nothing");
	std::string why;
	try {
		GenOptions g = r.gen;
		g.samples = 24;
		generate(ambot, g);
	} catch (const std::runtime_error &e) {
		why = e.what();
	}
	check(why.find("made under other settings") != std::string::npos &&
		      why.find("accept_segments: 80") != std::string::npos,
	      "generation refuses to extend a dataset labelled on 20 segments with 80-segment labels", why);

	RepairOptions b = r;
	b.gen.out_dir = (dir / "bare").string();
	b.gen.samples = 8;
	RepairSummary sb = repair(ambot, b);
	const std::vector<std::string> bare = lines_of(read_file((dir / "bare" / "ground.csv").string()));
	check(sb.relabelled == 1 && bare.size() == 21 && seg(bare[8]) >= 80 && bare[9] == before[9] &&
		      !fs::exists(dir / "bare" / "ground.solutions.csv"),
	      "remesh without a sidecar: row 7 is solved again in full onto 80 or more segments, and no sidecar "
	      "appears",
	      std::to_string(sb.relabelled) + " relabelled");
}

}  // namespace

int main(int argc, char **argv)
{
	if (!pin_numerics(argc, argv))
		return 1;

	// ---- the warm start: a neighbour's solution, transplanted ----------
	{
		RobotParams ambot = load_robot("trainer/params/ambot.yaml");
		// Ambot ground sample 0; its neighbour has the goal 0.15 m away.
		double a[4] = {0, 0, 0.73451828298622091, 0};
		double b[4] = {-2.0485834379539933, 3.7672478923170489, 0.43868580694182063, -0.2803914970404775};
		double bn[4] = {b[0] + 0.1, b[1] - 0.1, b[2], b[3] + 0.05};
		SolveOptions o = training_solve_options();
		SolveOptions line_opt = o;
		line_opt.strategy_starts = false;
		Solution line = solve_bvp(HYLO_MODE_GROUND, ambot, a, b, line_opt);
		// The neighbour solved from one start reversing towards its goal (its
		// rear facing it), as planar_strategy_guesses makes it.
		std::vector<double> fa = full_state(HYLO_MODE_GROUND, ambot, a), fb = full_state(HYLO_MODE_GROUND, ambot, bn);
		double bearing = std::atan2(bn[1], bn[0]) + 3.14159265358979323846;
		double h = -0.14 + std::remainder(bearing + 0.14, 2 * 3.14159265358979323846);
		double mid[4] = {0.5 * bn[0], 0.5 * bn[1], -0.6, h};
		Solution none, nb = solve_bvp_guesses(HYLO_MODE_GROUND, ambot, a, bn, o, {{6.0, {fa, full_state(HYLO_MODE_GROUND, ambot, mid), fb}}}, none);
		// Transplanted into sample 0 and solved from it alone.
		Guess g = transplanted_guess(nb.traj, nb.T, fa, full_state(HYLO_MODE_GROUND, ambot, b), 21);
		Solution warm = solve_bvp_guesses(HYLO_MODE_GROUND, ambot, a, b, o, {g}, none);
		std::printf("# ambot ground sample 0: straight lines %.4f J, neighbour %.4f J, warm-started %.4f J\n",
			    line.cost, nb.cost, warm.cost);
		// The two basins: about 98 J backing towards the goal, about 131 J
		// driving forward and turning (straight lines, and the committed
		// label 130.2 J).
		check(g.path.size() == 21 && g.path.front() == fa && g.path.back() == full_state(HYLO_MODE_GROUND, ambot, b),
		      "a transplanted path runs exactly from the row's start to its goal");
		check(nb.converged && warm.converged && line.converged && warm.cost < 0.8 * line.cost && warm.cost < 100,
		      "Ambot ground sample 0: a neighbour's solution leads into the basin below 100 J, the straight lines "
		      "end 25% or more above it",
		      std::to_string(warm.cost) + " vs " + std::to_string(line.cost));
		// The same warm start three times: one refinement (the repeats reach
		// the coarse optimum it was refined from), the same result.
		Solution thrice = solve_bvp_guesses(HYLO_MODE_GROUND, ambot, a, b, o, {g, g, g}, none);
		check(thrice.starts == 3 && thrice.refined_starts == 1 && thrice.cost == warm.cost &&
			      warm.refined_starts == 1,
		      "warm starts that repeat a coarse optimum already refined into an accepted solution are not "
		      "refined again",
		      std::to_string(thrice.starts) + " starts, " + std::to_string(thrice.refined_starts) + " refined, " +
			      std::to_string(thrice.cost) + " J");
		bool threw = false;
		try {
			Guess bad = g;
			bad.path.back()[0] += 0.5;
			solve_bvp_guesses(HYLO_MODE_GROUND, ambot, a, b, o, {bad}, none);
		} catch (const std::invalid_argument &e) {
			threw = std::string(e.what()).find("does not run from the BVP's start to its goal") != std::string::npos;
		}
		check(threw, "a guess that does not end at the goal is refused");
	}

	// ---- the stage, on the double integrator ----------------------------
	const fs::path dir = fs::temp_directory_path() / ("hylo_repair_" + std::to_string(getpid()));
	fs::remove_all(dir);
	RobotParams di = load_robot("trainer/params/di.yaml");
	GenOptions g;
	g.mode = HYLO_MODE_DI_NEG;
	g.samples = 16;
	g.jobs = 2;
	g.progress = false;
	g.out_dir = (dir / "gen").string();
	generate(di, g);
	const std::string csv = read_file(g.out_dir + "/di_neg.csv"), meta = read_file(g.out_dir + "/di_neg.csv.meta");
	std::vector<std::string> rows = lines_of(csv);   // rows[i + 1] is sample i
	const size_t ic = csv_column(HYLO_MODE_DI_NEG, "cost_j"), iv = csv_column(HYLO_MODE_DI_NEG, "converged");
	// Three converged rows among the first 12: one made dearer, one cheaper
	// than any solution, one removed (not converged).
	std::vector<size_t> conv;
	for (size_t i = 0; i < 12; i++)
		if (csv_fields(rows[i + 1])[iv] == "1")
			conv.push_back(i);
	check(conv.size() >= 3, "the double-integrator dataset has three converged rows among its first 12",
	      std::to_string(conv.size()));
	if (conv.size() < 3)
		return tap_finish();
	const size_t dear = conv[0], cheap = conv[1], gone = conv[2];
	auto cost_of = [&](const std::string &row) { return std::stod(csv_fields(row)[ic]); };
	const double true_dear = cost_of(rows[dear + 1]), true_gone = cost_of(rows[gone + 1]);
	std::vector<std::string> edited = rows;
	edited[dear + 1] = with_field(rows[dear + 1], ic, format_double(1.3 * true_dear));
	edited[cheap + 1] = with_field(rows[cheap + 1], ic, format_double(0.7 * cost_of(rows[cheap + 1])));
	edited[gone + 1] = with_field(with_field(rows[gone + 1], ic, "0"), iv, "0");
	auto setup = [&](const std::string &name) {
		fs::create_directories(dir / name);
		spit((dir / name / "di_neg.csv").string(), joined(edited));
		spit((dir / name / "di_neg.csv.meta").string(), meta);
		RepairOptions r;
		r.gen = g;
		r.gen.out_dir = (dir / name).string();
		r.gen.samples = 12;
		r.gen.chunk = 2;
		return r;
	};

	RepairOptions r1 = setup("one");
	r1.gen.jobs = 1;
	RepairSummary s1 = repair(di, r1);
	const std::string out1 = read_file(r1.gen.out_dir + "/di_neg.csv");
	const std::string side1 = read_file(solutions_path(r1.gen));
	std::vector<std::string> got = lines_of(out1);
	bool never_raised = got.size() == edited.size();
	for (size_t i = 0; never_raised && i < 12; i++) {
		std::vector<std::string> was = csv_fields(edited[i + 1]), now = csv_fields(got[i + 1]);
		if (was[iv] == "1")
			never_raised = now[iv] == "1" && std::stod(now[ic]) <= std::stod(was[ic]);
	}
	check(never_raised, "repair never raises a label nor loses a converged row");
	check(got.size() > cheap + 1 && got[cheap + 1] == edited[cheap + 1],
	      "a label cheaper than any solution is kept byte for byte");
	check(got.size() > dear + 1 && std::fabs(cost_of(got[dear + 1]) - true_dear) <= 1e-5 * true_dear,
	      "a label made 30% dearer is lowered back to the optimum",
	      got.size() > dear + 1 ? got[dear + 1] : "");
	check(got.size() > gone + 1 && csv_fields(got[gone + 1])[iv] == "1" &&
		      std::fabs(cost_of(got[gone + 1]) - true_gone) <= 1e-5 * true_gone,
	      "a row without a label gets the optimum again");
	bool tail = got.size() == edited.size();
	for (size_t i = 13; tail && i < edited.size(); i++)
		tail = got[i] == edited[i];
	check(tail, "rows past N are the input's bytes");
	// Newly converged: the row whose label was removed, and one its own
	// straight lines never solved, reached from one of its 8 neighbours.
	check(s1.lowered == 1 && s1.newly_converged == 2 && s1.rows == 12 && s1.solved_again == 12,
	      "the summary counts one label lowered by more than 0.5% and two newly converged",
	      std::to_string(s1.lowered) + " lowered, " + std::to_string(s1.newly_converged) + " newly converged");
	const std::string meta1 = read_file(r1.gen.out_dir + "/di_neg.csv.meta");
	check(meta1.rfind(meta, 0) == 0 && meta1.find("repaired_rows: 12\nrepair_neighbours: 8\n") != std::string::npos &&
		      meta1.find("repair_blas: ") != std::string::npos &&
		      meta1.find("\nrepair_refine_repeats: off\n") != std::string::npos &&
		      meta.find("refine_repeats") == std::string::npos &&
		      !fs::exists(r1.gen.out_dir + "/di_neg.csv.repair") &&
		      !fs::exists(r1.gen.out_dir + "/di_neg.csv.repair.meta"),
	      "the .meta keeps the input's lines and records the repair; no in-progress file is left");
	// The row a neighbour's path solved: its sidecar line is that solution
	// (the dataset row's result columns and a path), so the memory holds it.
	{
		std::vector<std::string> side_lines = lines_of(side1);
		bool same = side_lines.size() == 13 && !fs::exists(solutions_path(r1.gen) + ".repair");
		size_t replaced = 0;   // rows solved now that neither label nor sidecar had
		for (size_t i = 0; same && i < 12; i++) {
			std::vector<std::string> row = csv_fields(got[i + 1]), line = csv_fields(side_lines[i + 1]);
			if (i == gone || csv_fields(edited[i + 1])[iv] == "1" || row[iv] != "1")
				continue;
			replaced++;
			same = line.size() > 9 && std::equal(row.end() - 8, row.end(), line.begin() + 1);
		}
		check(same && s1.solutions_replaced == 1 && replaced == 1,
		      "the sidecar line of the row only a neighbour's path solved is now that solution; no in-progress file is left",
		      std::to_string(s1.solutions_replaced) + " replaced, " + std::to_string(replaced) + " found");
	}

	RepairOptions r2 = setup("two");
	r2.gen.jobs = 2;
	repair(di, r2);
	check(read_file(r2.gen.out_dir + "/di_neg.csv") == out1 &&
		      read_file(r2.gen.out_dir + "/di_neg.csv.meta") == meta1 && read_file(solutions_path(r2.gen)) == side1,
	      "--jobs 1 and 2: the same bytes (dataset, .meta, sidecar)");

	// Killed part-way (a child process running the repair, SIGKILL once the
	// sidecar has rows), a torn row appended, resumed.
	RepairOptions r3 = setup("killed");
	r3.gen.jobs = 1;
	const std::string side = solutions_path(r3.gen), work = r3.gen.out_dir + "/di_neg.csv.repair";
	kill_part_way([&] { repair(di, r3); }, side, 6);
	size_t side_rows = count_lines(side), work_rows = count_lines(work);
	bool partial = side_rows < 13 || work_rows < 13;
	std::ofstream(side, std::ios::app) << "7,0.1";   // torn
	if (fs::exists(work))
		std::ofstream(work, std::ios::app) << "3,-0.2";
	RepairSummary s3 = repair(di, r3);
	check(partial && read_file(r3.gen.out_dir + "/di_neg.csv") == out1 &&
		      read_file(r3.gen.out_dir + "/di_neg.csv.meta") == meta1 && read_file(side) == side1,
	      "a repair killed while solving the sidecar and resumed (torn rows appended) gives the same bytes",
	      "killed with " + std::to_string(side_rows) + " sidecar and " + std::to_string(work_rows) +
		      " repair lines; resumed " + std::to_string(s3.solved_again) + " solves");
	// Killed while repairing (the work file has rows), torn lines appended
	// to the work file and to the new sidecar lines' file, resumed.
	RepairOptions r5 = setup("killed_repairing");
	r5.gen.jobs = 1;
	const std::string work5 = r5.gen.out_dir + "/di_neg.csv.repair", side5 = solutions_path(r5.gen) + ".repair";
	kill_part_way([&] { repair(di, r5); }, work5, 6);
	const size_t work5_rows = count_lines(work5);
	std::ofstream(work5, std::ios::app) << "9,-0.2";
	std::ofstream(side5, std::ios::app) << "11,0.5";
	RepairSummary s5 = repair(di, r5);
	check(work5_rows >= 6 && work5_rows < 13 && read_file(dataset_path(r5.gen)) == out1 &&
		      read_file(solutions_path(r5.gen)) == side1 && s5.repaired_now < 12 && !fs::exists(side5),
	      "a repair killed while repairing and resumed (torn lines appended) gives the same bytes",
	      "killed with " + std::to_string(work5_rows) + " repair lines; resumed " + std::to_string(s5.repaired_now) +
		      " rows");

	// Generation that keeps each row's solution (--solutions) writes the
	// sidecar a repair would solve again, byte for byte, so the repair
	// solves nothing again; killed part-way with torn rows in both files
	// and resumed, the same bytes. The sidecar of "one" was solved again by
	// its repair (from the edited rows' pairs: the same solves).
	{
		RepairOptions w;
		w.gen = g;
		w.gen.out_dir = (dir / "with").string();
		w.gen.samples = 12;
		w.gen.chunk = 2;
		generate_with_solutions(di, w);
		const std::string side_with = read_file(solutions_path(w.gen)), data_with = read_file(dataset_path(w.gen));
		std::vector<std::string> lw = lines_of(side_with), l1 = lines_of(side1);
		size_t differ = lw.size() == l1.size() ? 0 : lw.size();
		for (size_t i = 0; i < lw.size() && i < l1.size(); i++)
			differ += lw[i] != l1[i];
		check(differ == s1.solutions_replaced &&
			      read_file(solutions_path(w.gen) + ".meta") == read_file(solutions_path(r1.gen) + ".meta"),
		      "gen --solutions writes the sidecar the repair solves again, byte for byte but the line the repair replaced",
		      std::to_string(differ) + " lines differ");
		RepairSummary sw = repair(di, w);
		check(sw.solved_again == 0 && sw.rows == 12 && read_file(solutions_path(w.gen)) == side1,
		      "then the repair solves no row again, and replaces the same line",
		      std::to_string(sw.solved_again) + " solved again");
		RepairOptions k = w;
		k.gen.out_dir = (dir / "with_killed").string();
		k.gen.jobs = 1;
		const std::string kside = solutions_path(k.gen), kdata = dataset_path(k.gen);
		kill_part_way([&] { generate_with_solutions(di, k); }, kdata, 5);
		const size_t got_rows = count_lines(kdata);
		std::ofstream(kside, std::ios::app) << "9,0.3";   // torn
		std::ofstream(kdata, std::ios::app) << "8,-0.4";
		generate_with_solutions(di, k);
		check(got_rows < 13 && read_file(kside) == side_with && read_file(kdata) == data_with,
		      "gen --solutions killed part-way (torn rows in both files) and resumed: the same bytes",
		      "killed at " + std::to_string(got_rows) + " lines");
		// A dataset made without solutions, extended with them: the
		// sidecar is first solved up to its rows.
		RepairOptions late = w;
		late.gen.out_dir = (dir / "late").string();
		late.gen.samples = 6;
		generate(di, late.gen);
		late.gen.samples = 12;
		generate_with_solutions(di, late);
		check(read_file(solutions_path(late.gen)) == side_with,
		      "gen --solutions over a dataset made without: the sidecar solved up to it, then kept in step");
	}

	RepairSummary again = repair(di, r1);
	check(again.already && read_file(r1.gen.out_dir + "/di_neg.csv") == out1,
	      "a second repair with the same settings does nothing");

	// Extended: generation appends rows to a repaired dataset, then a repair
	// of all of them repairs only the new ones, from neighbours among all.
	// Killed part-way (while writing the kept rows or repairing) and
	// resumed: the same bytes.
	{
		auto extend = [&](const std::string &name) {
			fs::create_directories(dir / name);
			for (const char *f : {"di_neg.csv", "di_neg.csv.meta", "di_neg.solutions.csv", "di_neg.solutions.csv.meta"})
				fs::copy_file(fs::path(r1.gen.out_dir) / f, dir / name / f);
			RepairOptions e = r1;
			e.gen.out_dir = (dir / name).string();
			e.gen.samples = 20;
			GenSummary gs = generate(di, e.gen);
			return std::make_pair(e, gs);
		};
		auto [e1, gen1] = extend("extended");
		const std::string grown = read_file(dataset_path(e1.gen));
		std::vector<std::string> gl = lines_of(grown), ol = lines_of(out1);
		check(gen1.resumed_from == 16 && gl.size() == 21 && std::equal(ol.begin(), ol.end(), gl.begin()) &&
			      read_file(dataset_path(e1.gen) + ".meta") == meta1,
		      "generation extends a repaired dataset: its rows and its .meta (the repair's lines) unchanged, rows appended",
		      std::to_string(gen1.resumed_from) + " rows there, " + std::to_string(gl.size()) + " lines now");
		RepairSummary se = repair(di, e1);
		const std::string rep = read_file(dataset_path(e1.gen)), rep_meta = read_file(dataset_path(e1.gen) + ".meta");
		std::vector<std::string> rl = lines_of(rep);
		bool kept = rl.size() == 21 && std::equal(gl.begin(), gl.begin() + 13, rl.begin()), lowered_only = kept;
		for (size_t i = 13; lowered_only && i < 21; i++) {
			std::vector<std::string> was = csv_fields(gl[i]), now = csv_fields(rl[i]);
			if (was[iv] == "1")
				lowered_only = now[iv] == "1" && std::stod(now[ic]) <= std::stod(was[ic]);
		}
		check(kept && lowered_only && se.kept == 12 && se.repaired_now == 8 && se.solved_again == 8 && se.rows == 20,
		      "a repair of the extended dataset keeps the 12 repaired rows' bytes and repairs only the 8 new ones, "
		      "never raising a label",
		      std::to_string(se.kept) + " kept, " + std::to_string(se.repaired_now) + " repaired now, " +
			      std::to_string(se.solved_again) + " solved again");
		check(internal::generated_lines(rep_meta) == meta && rep_meta.find("\nrepaired_rows: 20\n") != std::string::npos &&
			      rep_meta.find("\nrepair_passes: 12 20\n") != std::string::npos &&
			      repair(di, e1).already && read_file(dataset_path(e1.gen)) == rep,
		      "its .meta records both passes (repaired_rows: 20, repair_passes: 12 20); a second repair does nothing",
		      rep_meta);
		for (const char *what : {"kept", "repaired"}) {
			const bool in_kept = std::string(what) == "kept";
			RepairOptions e2 = extend(std::string("extended_killed_") + what).first;
			const std::string w2 = dataset_path(e2.gen) + ".repair";
			e2.gen.jobs = 1;
			kill_part_way([&] { repair(di, e2); }, w2, in_kept ? 1 : 15);
			const size_t at = count_lines(w2);
			if (in_kept)   // torn in the kept rows
				spit(w2, joined(std::vector<std::string>(gl.begin(), gl.begin() + 5)) + "4,-0.4");
			else
				std::ofstream(w2, std::ios::app) << "14,-0.2";
			RepairSummary s2 = repair(di, e2);
			check(read_file(dataset_path(e2.gen)) == rep && read_file(dataset_path(e2.gen) + ".meta") == rep_meta &&
				      read_file(solutions_path(e2.gen)) == read_file(solutions_path(e1.gen)) && s2.kept == 12 &&
				      !s2.already && s2.repaired_now > 0,
			      std::string("an extended dataset's repair killed part-way (") + what +
				      ", a torn line appended) and resumed: the same bytes",
			      "killed at " + std::to_string(at) + " lines");
		}
		// Under other settings every row is repaired again, in one pass.
		RepairOptions e3 = extend("extended_other").first;
		e3.neighbours = 4;
		RepairSummary s3o = repair(di, e3);
		const std::string m3 = read_file(dataset_path(e3.gen) + ".meta");
		check(s3o.kept == 0 && s3o.repaired_now == 20 && m3.find("repair_passes") == std::string::npos &&
			      m3.find("\nrepaired_rows: 20\nrepair_neighbours: 4\n") != std::string::npos,
		      "an extended dataset repaired under other settings (4 neighbours): every row again, one pass",
		      std::to_string(s3o.kept) + " kept, " + std::to_string(s3o.repaired_now) + " repaired now");
	}
	std::string why;

	// Another stream's dataset is refused.
	RepairOptions r4 = setup("seed");
	r4.gen.seed = 2;
	why.clear();
	try {
		repair(di, r4);
	} catch (const std::invalid_argument &e) {
		why = e.what();
	}
	check(why.find("not this stream's") != std::string::npos && why.find("seed: 1 vs seed: 2") != std::string::npos,
	      "a dataset of another seed is refused", why);
	why.clear();
	try {
		RepairOptions r5 = setup("remesh_di");
		r5.remesh = true;
		repair(di, r5);
	} catch (const std::invalid_argument &e) {
		why = e.what();
	}
	check(why.find("accepts labels on any mesh") != std::string::npos,
	      "remesh: a mode without a mesh to accept labels on (the double integrator) is refused", why);
	remesh_checks(dir / "remesh");
	fs::remove_all(dir);
	return tap_finish();
}
