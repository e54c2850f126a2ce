#include "trainer/repair.hpp"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <sstream>
#include <stdexcept>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>
#include <vector>

#include "trainer/collocation.hpp"
#include "trainer/files.hpp"
#include "trainer/memory.hpp"
#include "trainer/mode_config.hpp"
#include "trainer/numerics.hpp"
#include "trainer/sha256.hpp"
#include "trainer/svr_export.hpp"

namespace hylo::trainer {
namespace {

// A label lowered by more than this fraction counts as lowered.
constexpr double kLowered = 0.005;

// CPU seconds of the waited-for worker processes so far.
double children_cpu_s()
{
	struct rusage ru;
	if (getrusage(RUSAGE_CHILDREN, &ru) != 0)
		return 0;
	return static_cast<double>(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) +
	       1e-6 * static_cast<double>(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
}

// Sample i's sidecar line: the current solver's result and its path.
std::string sidecar_line(const RobotParams &robot, const RepairOptions &opt, uint64_t i)
{
	const hylo_mode mode = opt.gen.mode;
	double a[6] = {0}, b[6] = {0};
	draw_pair(robot.mode(mode), opt.gen.seed, i, a, b, opt.gen.draws);
	Solution s;
	try {
		s = solve_bvp(mode, robot, a, b, opt.gen.solve);
	} catch (const std::exception &e) {
		s = Solution();
		s.status_text = kErrorStatus + std::string(e.what());
	}
	return solution_line(robot, mode, opt.path_points, i, a, b, s);
}

// Extends the sidecar to the first n rows (resumable, a chunk at a time; a
// torn last row dropped); returns how many rows this call solved, and in
// *held (when given) how many complete rows the sidecar holds now.
uint64_t extend_sidecar(const RobotParams &robot, const RepairOptions &opt, uint64_t n, uint64_t *held = nullptr)
{
	const std::string path = solutions_path(opt.gen), meta_path = path + ".meta";
	const std::string meta =
		internal::meta_text(robot, opt.gen) + "path_points: " + std::to_string(opt.path_points) + "\n";
	const std::string header = csv_join(sidecar_columns(opt.gen.mode, opt.path_points)) + "\n";
	std::string existing = read_file(path);
	uint64_t next = 0;
	if (!existing.empty() || access(meta_path.c_str(), F_OK) == 0) {
		std::string old_meta = read_file(meta_path);
		if (old_meta != meta)
			throw std::runtime_error(path + " was made under other settings: " +
						 internal::meta_differences(old_meta, meta) + "; remove it (it is solved again)");
		internal::ResumePoint r = internal::resume_point(existing, header);
		next = r.rows;
		if (truncate(path.c_str(), static_cast<off_t>(r.keep)) != 0 && errno != ENOENT)
			throw std::runtime_error("cannot truncate " + path);
		if (r.rows >= n) {
			if (held)
				*held = r.rows;
			return 0;
		}
	} else {
		write_file_atomically(meta_path, meta);
	}
	AppendFile out(path);
	struct stat fs;
	if (fstat(out.fd(), &fs) == 0 && fs.st_size == 0)
		out.write(header);
	const uint64_t first = next;
	internal::fork_sample_chunks(
		next, n, opt.gen.jobs, opt.gen.chunk, [&](uint64_t i) { return sidecar_line(robot, opt, i); }, "solving",
		[&](uint64_t, uint64_t e, std::vector<std::string> &rows) {
			std::string text;
			for (const std::string &r : rows)
				text += r + "\n";
			out.write(text);
			out.sync();
			if (opt.gen.progress)
				std::fprintf(stderr, "%s: %llu/%llu rows solved again\n", path.c_str(),
					     static_cast<unsigned long long>(e), static_cast<unsigned long long>(n));
		});
	out.close();
	if (held)
		*held = n;
	return n - first;
}

// Generation's sink for the sidecar: each row's line, appended in step
// with the dataset (the sidecar already holds `have` rows; extend_sidecar
// brought it up to the dataset's first row to be solved).
class SolutionsSink : public RowSink {
public:
	SolutionsSink(const RobotParams &robot, const RepairOptions &opt, uint64_t have)
		: robot_(robot), opt_(opt), have_(have), out_(solutions_path(opt.gen)) {}
	std::string line(uint64_t i, const double *a, const double *b, const Solution &s) const override
	{
		return solution_line(robot_, opt_.gen.mode, opt_.path_points, i, a, b, s);
	}
	void append(uint64_t first, const std::vector<std::string> &lines) override
	{
		if (first > have_)
			throw std::runtime_error(solutions_path(opt_.gen) + " ends at row " + std::to_string(have_) +
						 ", before the chunk at " + std::to_string(first));
		std::string text;
		for (uint64_t k = have_ - first; k < lines.size(); k++)
			text += lines[k] + "\n";
		out_.write(text);
		out_.sync();
		have_ = std::max(have_, first + lines.size());
	}
	void close() { out_.close(); }

private:
	const RobotParams &robot_;
	const RepairOptions &opt_;
	uint64_t have_;
	AppendFile out_;
};

std::vector<StoredSolution> read_sidecar(const RepairOptions &opt, uint64_t n)
{
	const std::string path = solutions_path(opt.gen);
	std::vector<std::string> lines = complete_lines(read_file(path));
	if (lines.size() < n + 1)
		throw std::runtime_error(path + " has " + std::to_string(lines.empty() ? 0 : lines.size() - 1) +
					 " rows, not " + std::to_string(n));
	std::vector<StoredSolution> out;
	for (uint64_t i = 0; i < n; i++)
		out.push_back(parse_solution_line(opt.gen.mode, lines[i + 1], i, opt.path_points,
						 path + " line " + std::to_string(i + 2)));
	return out;
}

// The pass the options ask for.
const internal::MetaPass &pass_of(const RepairOptions &opt)
{
	return opt.remesh ? internal::kRemeshPass : internal::kRepairPass;
}

// The pass's lines of a dataset's .meta (and of the in-progress file's):
// its settings, and the trainer's solver and numerics.
std::string repair_lines(const RobotParams &robot, const RepairOptions &opt)
{
	const internal::MetaPass &P = pass_of(opt);
	std::string out = P.rows_key + ": " + std::to_string(opt.gen.samples) + "\n";
	if (!opt.remesh)
		out += "repair_neighbours: " + std::to_string(opt.neighbours) + "\n";
	out += P.prefix + "path_points: " + std::to_string(opt.path_points) + "\n";
	GenOptions warm = opt.gen;   // the warm starts' settings: the pass's own
	warm.solve = guess_solve_options(opt.gen.solve);
	std::istringstream in(internal::meta_text(robot, warm));
	for (std::string line; std::getline(in, line);) {
		std::string key = line.substr(0, line.find(": "));
		if (key == "robot" || key == "mode" || key == "seed" || key == "draws" || key == "params_sha256")
			continue;   // the stream's, in the dataset's own lines
		out += P.prefix + line + "\n";
	}
	return out;
}

// meta without the lines of an earlier pass of this kind, then this one's.
std::string repaired_meta(const internal::MetaPass &P, const std::string &meta, const std::string &lines)
{
	std::string out;
	std::istringstream in(meta);
	for (std::string line; std::getline(in, line);)
		if (line.rfind(P.rows_key + ": ", 0) != 0 && line.rfind(P.prefix, 0) != 0)
			out += line + "\n";
	return out + lines;
}

// The pass's lines of meta but its row count and passes: its settings.
std::string repair_settings(const internal::MetaPass &P, const std::string &meta)
{
	std::string out;
	std::istringstream in(meta);
	for (std::string line; std::getline(in, line);)
		if (line.rfind(P.prefix, 0) == 0 && line.rfind(P.prefix + "passes: ", 0) != 0)
			out += line + "\n";
	return out;
}

// The rows an earlier pass with these settings did, when generation has
// extended the dataset past them (its .meta's repaired_rows, below n): they
// keep their labels and only the rows past them are repaired, so adding
// rows costs their repair, not every row's again. 0 (repair every row) for
// a dataset never repaired or repaired under other settings.
uint64_t repaired_before(const internal::MetaPass &P, const std::string &meta, const std::string &lines, uint64_t n)
{
	const std::string rows = internal::meta_value(meta, P.rows_key);
	const uint64_t r = rows.empty() ? 0 : std::strtoull(rows.c_str(), nullptr, 10);
	return r < n && repair_settings(P, meta) == repair_settings(P, lines) ? r : 0;
}

bool contains_lines(const std::string &meta, const std::string &lines)
{
	std::istringstream in(lines);
	for (std::string line; std::getline(in, line);)
		if (("\n" + meta).find("\n" + line + "\n") == std::string::npos)
			return false;
	return true;
}

}  // namespace

std::string solutions_path(const GenOptions &opt)
{
	return opt.out_dir + "/" + hylo_mode_str(opt.mode) + ".solutions.csv";
}

GenSummary generate_with_solutions(const RobotParams &robot, const RepairOptions &opt)
{
	if (opt.gen.shards > 1)
		throw std::invalid_argument("--solutions is for an unsharded run (the repair reads one sidecar)");
	if (opt.path_points < 2)
		throw std::invalid_argument("a solution path needs at least two points");
	make_out_dir(opt.gen.out_dir);
	// Up to the row generation resumes at, solved again (none for a new
	// dataset); then in step with it.
	const std::string rows = read_file(dataset_path(opt.gen));
	const uint64_t have =
		rows.empty() ? 0 : internal::resume_point(rows, csv_join(csv_columns(opt.gen.mode)) + "\n").rows;
	uint64_t held = 0;
	extend_sidecar(robot, opt, have, &held);
	SolutionsSink sink(robot, opt, held);
	GenSummary sum = generate(robot, opt.gen, &sink);
	sink.close();
	return sum;
}

RepairSummary repair(const RobotParams &robot, const RepairOptions &ro)
{
	auto t0 = std::chrono::steady_clock::now();
	RepairOptions opt = ro;
	opt.gen.shard = opt.gen.shards = 1;
	const hylo_mode mode = opt.gen.mode;
	const uint64_t n = opt.gen.samples;
	const internal::MetaPass &P = pass_of(opt);
	if ((!opt.remesh && opt.neighbours < 1) || opt.path_points < 2)
		throw std::invalid_argument("repair needs at least one neighbour and two path points");
	// remesh: the mesh the mode's labels are accepted on.
	const int accept = internal::mode_info(mode, robot).accept_segments;
	if (opt.remesh && accept <= 0)
		throw std::invalid_argument(std::string("remesh: mode ") + hylo_mode_str(mode) +
					    "'s solver accepts labels on any mesh; nothing to remesh");
	RepairSummary sum;
	sum.rows = n;
	sum.path = dataset_path(opt.gen);
	const std::string meta_path = sum.path + ".meta";
	const std::string input = read_file(sum.path), input_meta = read_file(meta_path);
	if (input.empty() || input_meta.empty())
		throw std::invalid_argument(P.name + ": no dataset " + sum.path + " with its .meta (run --stage gen first)");
	if (!internal::same_stream(input_meta, internal::meta_text(robot, opt.gen)))
		throw std::invalid_argument(P.name + ": " + sum.path + " is not this stream's (" +
					    internal::meta_differences(input_meta, internal::meta_text(robot, opt.gen)) + ")");
	const std::string settings_lines = repair_lines(robot, opt);
	if (contains_lines(input_meta, settings_lines)) {
		sum.already = true;
		return sum;
	}
	// Rows below `from` keep an earlier pass's labels; the .meta lists the
	// passes' row counts (repair_passes: 8640 17280), a one-pass repair none.
	const uint64_t from = repaired_before(P, input_meta, settings_lines, n);
	std::string passes = internal::meta_value(input_meta, P.prefix + "passes");
	if (passes.empty())
		passes = std::to_string(from);
	const std::string lines_meta =
		settings_lines + (from ? P.prefix + "passes: " + passes + " " + std::to_string(n) + "\n" : "");
	sum.kept = from;
	std::vector<std::string> lines = complete_lines(input);
	const std::string header = csv_join(csv_columns(mode));
	if (lines.empty() || lines[0] != header)
		throw std::invalid_argument(sum.path + ": line 1 is not the header of a " + hylo_mode_str(mode) + " dataset");
	if (lines.size() < n + 1)
		throw std::invalid_argument(P.name + ": " + sum.path + " has " + std::to_string(lines.size() - 1) +
					    " rows, fewer than the " + std::to_string(n) + " asked for");
	// The rows must be this stream's samples.
	const size_t ix = csv_column(mode, "x1_0"), ic = csv_column(mode, "cost_j");
	const int d = mode_desc(mode).xs_dim;
	std::vector<std::vector<double>> coords(n);
	std::vector<Solution> stored(n);
	for (uint64_t i = 0; i < n; i++) {
		std::string where = sum.path + " line " + std::to_string(i + 2);
		std::vector<std::string> f = csv_fields(lines[i + 1]);
		double a[6] = {0}, b[6] = {0};
		draw_pair(robot.mode(mode), opt.gen.seed, i, a, b, opt.gen.draws);
		bool same = f.size() == csv_columns(mode).size() && f[0] == std::to_string(i);
		for (int k = 0; same && k < d; k++)
			same = f[ix + static_cast<size_t>(k)] == format_double(a[k]) &&
			       f[ix + static_cast<size_t>(d + k)] == format_double(b[k]);
		if (!same)
			throw std::invalid_argument(where + ": not sample " + std::to_string(i) + " of this stream");
		coords[i].assign(a, a + d);
		coords[i].insert(coords[i].end(), b, b + d);
		stored[i] = row_result(f, ic, where);
	}
	std::string input_rows;
	for (uint64_t i = 0; i <= n; i++)
		input_rows += lines[i] + "\n";
	const std::string input_sha = sha256_hex(input_rows);

	// The in-progress file: resumed if it is this repair's of these rows.
	const std::string work = sum.path + P.suffix, work_meta_path = work + ".meta";
	// Beside it: the sidecar lines of the rows whose label a neighbour's
	// path lowered (remesh: the finer mesh gave), written before their rows.
	const std::string side_work = solutions_path(opt.gen) + P.suffix;
	const std::string work_meta = "repair_of_sha256: " + input_sha + "\n" + lines_meta;
	std::string existing = read_file(work);
	uint64_t next = 0;
	if (!existing.empty() || access(work_meta_path.c_str(), F_OK) == 0) {
		std::string old = read_file(work_meta_path);
		if (old != work_meta && existing == input_rows && old.find('\n') != std::string::npos &&
		    old.substr(old.find('\n') + 1) == lines_meta) {
			// Interrupted between replacing the dataset and its .meta: finish.
			write_file_atomically(meta_path, repaired_meta(P, input_meta, lines_meta));
			std::remove(work.c_str());
			std::remove(work_meta_path.c_str());
			std::remove(side_work.c_str());
			sum.already = true;
			return sum;
		}
		if (old != work_meta)
			throw std::runtime_error(work + " is a " + P.name + " under other settings or of other rows: " +
						 internal::meta_differences(old, work_meta) + "; remove it");
		internal::ResumePoint r = internal::resume_point(existing, header + "\n");
		next = std::min(r.rows, n);
		if (truncate(work.c_str(), static_cast<off_t>(r.keep)) != 0 && errno != ENOENT)
			throw std::runtime_error("cannot truncate " + work);
	} else {
		write_file_atomically(work_meta_path, work_meta);
	}

	// The sidecar lines of the rows done, each once (a chunk's lines written
	// before an interruption kept its rows out are solved again).
	std::string side_done;
	for (const std::string &l : complete_lines(read_file(side_work))) {
		const uint64_t i = std::strtoull(l.c_str(), nullptr, 10);
		if (i < next)
			side_done += l + "\n";
	}
	write_file_atomically(side_work, side_done);

	double cpu0 = children_cpu_s();
	// remesh: a dataset without a sidecar has its coarse rows solved again
	// in full instead (the training solve), and keeps having none.
	const std::string side_meta = read_file(solutions_path(opt.gen) + ".meta");
	const bool sidecar = !opt.remesh || !side_meta.empty();
	if (!opt.remesh)
		sum.solved_again = extend_sidecar(robot, opt, n);
	else if (sidecar && !internal::same_stream(side_meta, input_meta))
		throw std::invalid_argument("remesh: " + solutions_path(opt.gen) + " is not " + sum.path +
					    "'s stream (its .meta)");
	sum.solve_cpu_s = children_cpu_s() - cpu0;
	cpu0 = children_cpu_s();
	std::vector<StoredSolution> sol = sidecar ? read_sidecar(opt, n) : std::vector<StoredSolution>(n);
	std::vector<std::vector<uint64_t>> near;
	if (!opt.remesh)
		near = nearest_rows(coords, sol, opt.neighbours);
	// Each row's incumbent: the cheaper converged of the stored label and the
	// current solver's (remesh: the stored label), and the row text it
	// stands for (the input's own bytes where the stored label is kept).
	auto incumbent = [&](uint64_t i, std::string &text) {
		const Solution &a = stored[i], &b = sol[i].s;
		if (!opt.remesh && improves_on(b, a)) {
			double x1[6] = {0}, x2[6] = {0};
			draw_pair(robot.mode(mode), opt.gen.seed, i, x1, x2, opt.gen.draws);
			text = csv_row(mode, i, x1, x2, b);
			return b;
		}
		text = lines[i + 1];
		return a;
	};

	AppendFile work_file(work), side_file(side_work);
	if (next == 0) {
		struct stat fs;
		if (fstat(work_file.fd(), &fs) == 0 && fs.st_size == 0)
			work_file.write(header + "\n");
	}
	if (next < from) {   // the earlier pass's rows, its bytes
		std::string text;
		for (uint64_t i = next; i < from; i++)
			text += lines[i + 1] + "\n";
		work_file.write(text);
		work_file.sync();
		next = from;
	}
	auto repair_row = [&](uint64_t i) {
		std::string text;
		Solution inc = incumbent(i, text);
		double x1[6] = {0}, x2[6] = {0};
		draw_pair(robot.mode(mode), opt.gen.seed, i, x1, x2, opt.gen.draws);
		std::vector<double> a = full_state(mode, robot, x1), b = full_state(mode, robot, x2);
		if (opt.remesh) {
			if (!inc.converged || inc.segments >= accept || (sidecar && !sol[i].s.converged))
				return text;
			try {
				Solution s = sidecar ? solve_bvp_guesses(mode, robot, x1, x2, opt.gen.solve,
									 {stored_guess(mode, sol[i], a, b, opt.path_points)},
									 Solution())
						     : solve_bvp(mode, robot, x1, x2, opt.gen.solve);
				if (s.converged && s.segments >= accept)
					return csv_row(mode, i, x1, x2, s) +
					       (sidecar ? "\n" + solution_line(robot, mode, opt.path_points, i, x1, x2, s) : "");
			} catch (const std::exception &) {
				// keep the row
			}
			return text;
		}
		std::vector<Guess> guesses;
		for (uint64_t j : near[i])
			guesses.push_back(stored_guess(mode, sol[j], a, b, opt.path_points));
		try {
			Solution s = solve_bvp_guesses(mode, robot, x1, x2, opt.gen.solve, guesses, inc);
			if (improves_on(s, inc))   // the row's line, then its sidecar line
				return csv_row(mode, i, x1, x2, s) + "\n" +
				       solution_line(robot, mode, opt.path_points, i, x1, x2, s);
		} catch (const std::exception &) {
			// keep the incumbent
		}
		return text;
	};
	const auto rows_t0 = std::chrono::steady_clock::now();   // this run's rate counts from here
	internal::fork_sample_chunks(next, n, opt.gen.jobs, opt.gen.chunk, repair_row,
				     opt.remesh ? "remeshing" : "repairing",
				     [&](uint64_t c, uint64_t e, std::vector<std::string> &rows) {
		std::string text, side;
		for (const std::string &r : rows) {
			const size_t nl = r.find('\n');
			text += r.substr(0, nl) + "\n";
			if (nl != std::string::npos)
				side += r.substr(nl + 1) + "\n";
		}
		side_file.write(side);
		side_file.sync();
		work_file.write(text);
		work_file.sync();
		sum.repaired_now += e - c;
		if (opt.gen.progress) {
			const double el = std::chrono::duration<double>(std::chrono::steady_clock::now() - rows_t0).count();
			const double rate = static_cast<double>(sum.repaired_now) / std::max(el, 1e-9);
			std::fprintf(stderr, "%s: %llu/%llu rows done, %.2f/s, ETA %.0f s\n", work.c_str(),
				     static_cast<unsigned long long>(e), static_cast<unsigned long long>(n), rate,
				     static_cast<double>(n - e) / std::max(rate, 1e-9));
		}
	});
	work_file.close();
	side_file.close();
	sum.warm_cpu_s = children_cpu_s() - cpu0;

	// Done: the repaired rows, then the input's past n, replace the dataset.
	std::vector<std::string> repaired = complete_lines(read_file(work));
	if (repaired.size() != n + 1)
		throw std::runtime_error(work + " has " + std::to_string(repaired.size() - 1) + " rows, not " +
					 std::to_string(n));
	std::string out;
	for (const auto &l : repaired)
		out += l + "\n";
	for (size_t i = n + 1; i < lines.size(); i++)
		out += lines[i] + "\n";
	const size_t conv = csv_column(mode, "converged");
	std::vector<double> drops;
	for (uint64_t i = 0; i < n; i++) {
		std::vector<std::string> f = csv_fields(repaired[i + 1]);
		bool now = f[conv] == "1";
		double cost = std::stod(f[ic]);
		if (now && !stored[i].converged)
			sum.newly_converged++;
		if (repaired[i + 1] != lines[i + 1])
			sum.relabelled++;
		if (now && stored[i].converged && cost > (1 + kLowered) * stored[i].cost)
			sum.raised++;
		if (now && stored[i].converged && cost < (1 - kLowered) * stored[i].cost) {
			drops.push_back(1 - cost / stored[i].cost);
			if (opt.remesh)
				continue;   // no neighbours to credit
			std::string side;
			(void)incumbent(i, side);
			if (side == repaired[i + 1])
				sum.lowered_by_solver++;
			else
				sum.lowered_by_neighbours++;
		}
	}
	sum.lowered = drops.size();
	if (!drops.empty()) {
		std::sort(drops.begin(), drops.end());
		size_t m = drops.size();
		sum.median_drop = m % 2 ? drops[m / 2] : 0.5 * (drops[m / 2 - 1] + drops[m / 2]);
		sum.max_drop = drops.back();
	}
	// The sidecar first: interrupted before the dataset, a re-run finds every
	// row done and writes the same sidecar again.
	const std::vector<std::string> new_lines = complete_lines(read_file(side_work));
	if (!new_lines.empty()) {
		std::vector<std::string> side_lines = complete_lines(read_file(solutions_path(opt.gen)));
		for (const std::string &l : new_lines) {
			const uint64_t i = std::strtoull(l.c_str(), nullptr, 10);
			if (i >= n || i + 1 >= side_lines.size())
				throw std::runtime_error(side_work + ": a line of sample " + std::to_string(i) +
							 ", not one of the " + std::to_string(n) + " rows repaired");
			side_lines[i + 1] = l;
		}
		std::string side;
		for (const auto &l : side_lines)
			side += l + "\n";
		write_file_atomically(solutions_path(opt.gen), side);
		sum.solutions_replaced = new_lines.size();
	}
	write_file_atomically(sum.path, out);   // atomic: a temporary file, fsync'd, renamed
	write_file_atomically(meta_path, repaired_meta(P, input_meta, lines_meta));
	std::remove(work.c_str());
	std::remove(work_meta_path.c_str());
	std::remove(side_work.c_str());
	sum.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
	return sum;
}

}  // namespace hylo::trainer
