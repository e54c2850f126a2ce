#include "trainer/dataset.hpp"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <sys/stat.h>
#include <unistd.h>
#include <fcntl.h>

#include "hylo/features.h"
#include "trainer/mode_config.hpp"
#include "trainer/model_table.hpp"
#include "trainer/modes.hpp"
#include "trainer/numerics.hpp"
#include "trainer/processes.hpp"
#include "trainer/sha256.hpp"
#include "trainer/svr_export.hpp"

namespace hylo::trainer {
namespace {

constexpr double kPi = 3.14159265358979323846;

uint64_t mix(uint64_t z)
{
	z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
	z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
	return z ^ (z >> 31);
}

struct Stream {
	uint64_t s;
	double uniform(double lo, double hi)
	{
		s += 0x9e3779b97f4a7c15ULL;
		return lo + (hi - lo) * static_cast<double>(mix(s) >> 11) * 0x1.0p-53;
	}
};

std::string num(double v) { return format_double(v); }

}  // namespace

namespace internal {


std::string meta_text(const RobotParams &robot, const GenOptions &opt)
{
	std::ostringstream m;
	// An unsharded stream does not depend on its length: a longer run extends
	// a shorter one. Shard boundaries do, so sharded files record it.
	m << "robot: " << robot.robot << "\nmode: " << hylo_mode_str(opt.mode) << "\nseed: " << opt.seed << "\n";
	if (opt.shards > 1)
		m << "samples: " << opt.samples << "\nshard: " << opt.shard << "/" << opt.shards << "\n";
	// Flight pairs have been drawn two ways (v2: with cruise pairs), ground
	// and marine ones four (v2: speeds at rest; v3: then cruise pairs; v4: the
	// cruise pairs from half the paper's count), the
	// double integrator's two (v2: then short pairs); a file of one draw is
	// not extended with another's. Draw 1 has no line.
	if (draws_for(opt.mode, opt.draws) > 1)
		m << "draws: " << draws_for(opt.mode, opt.draws) << "\n";
	// Ground and marine labels have come from straight-line starts alone (no
	// line), with the backing-up and goal-facing ones (starts: 2) and with
	// issue #35's three more (starts: 3; planar_strategy_guesses).
	if (mode_desc(opt.mode).planar && opt.solve.strategy_starts)
		m << "starts: 3\n";
	m << "params_sha256: " << robot.labels_sha256 << "\n";
	// What else a label depends on: the solver's settings and the numerics.
	m << solve_options_text(opt.solve);
	// The mode's mesh a label is accepted on (its solver hints), where it
	// sets one: earlier files have no line.
	if (const int n = internal::mode_info(opt.mode, robot).accept_segments; n > 0)
		m << "accept_segments: " << n << "\n";
	m << numerics_description();
	return m.str();
}

// A meta's lines by key (the text before the first ": "), in order.
std::vector<std::pair<std::string, std::string>> meta_lines(const std::string &meta)
{
	std::vector<std::pair<std::string, std::string>> out;
	std::istringstream in(meta);
	for (std::string line; std::getline(in, line);)
		out.emplace_back(line.substr(0, line.find(": ")), line);
	return out;
}

std::string meta_value(const std::string &meta, const std::string &key)
{
	for (const auto &kv : meta_lines(meta))
		if (kv.first == key)
			return kv.second.substr(std::min(kv.second.size(), key.size() + 2));
	return "";
}

// The lines in which two metas differ: "old vs new; ...", a line one of them
// lacks shown as "key: (not recorded)".
std::string meta_differences(const std::string &old_meta, const std::string &new_meta)
{
	auto a = meta_lines(old_meta), b = meta_lines(new_meta);
	auto line_of = [](const std::vector<std::pair<std::string, std::string>> &v, const std::string &key) {
		for (const auto &kv : v)
			if (kv.first == key)
				return kv.second;
		return key + ": (not recorded)";
	};
	std::string out;
	auto add = [&](const std::string &key) {
		std::string x = line_of(a, key), y = line_of(b, key);
		if (x != y)
			out += (out.empty() ? "" : "; ") + x + " vs " + y;
	};
	for (const auto &kv : b)
		add(kv.first);
	for (const auto &kv : a)   // lines only the old meta has
		if (line_of(b, kv.first) == kv.first + ": (not recorded)")
			add(kv.first);
	return out;
}

// Whether two metas describe the same stream of pairs (robot, mode, seed,
// robot file, draws, shard), whatever labelled them.
bool same_stream(const std::string &a, const std::string &b)
{
	auto stream = [](const std::string &meta) {
		std::string s;
		for (const auto &kv : meta_lines(meta))
			for (const char *key : {"robot", "mode", "seed", "samples", "shard", "draws", "params_sha256"})
				if (kv.first == key)
					s += kv.second + "\n";
		return s;
	};
	return stream(a) == stream(b);
}

std::string generated_lines(const std::string &meta)
{
	std::string out;
	for (const auto &kv : meta_lines(meta)) {
		bool generated = true;
		for (const MetaPass *p : {&kRepairPass, &kRemeshPass})
			generated = generated && kv.first != p->rows_key && kv.first.rfind(p->prefix, 0) != 0;
		if (generated)
			out += kv.second + "\n";
	}
	return out;
}

ResumePoint resume_point(const std::string &existing, const std::string &header)
{
	ResumePoint r;
	size_t end = existing.rfind('\n');
	end = end == std::string::npos ? 0 : end + 1;
	if (end < header.size())
		return r;
	r.keep = end;
	r.rows = static_cast<uint64_t>(std::count(existing.begin() + static_cast<std::ptrdiff_t>(header.size()),
						  existing.begin() + static_cast<std::ptrdiff_t>(end), '\n'));
	return r;
}

void fork_sample_chunks(uint64_t lo, uint64_t hi, int jobs, int chunk,
			const std::function<std::string(uint64_t)> &f, const std::string &doing,
			const std::function<void(uint64_t, uint64_t, std::vector<std::string> &)> &done)
{
	fork_chunks(
		hi - lo, jobs, static_cast<size_t>(std::max(1, chunk)), [&](size_t k) { return f(lo + k); },
		[&](size_t first, std::vector<std::string> &rows) {
			const uint64_t c = lo + first;
			for (size_t k = 0; k < rows.size(); k++)
				if (rows[k].empty())
					throw std::runtime_error("the process " + doing + " sample " + std::to_string(c + k) +
								 " failed");
			done(c, c + rows.size(), rows);
		});
}

}  // namespace internal

namespace {

// The separator of a worker's row and its sink line.
constexpr char kSinkSeparator = '\x1e';

// Sample i's row (and its sink line), in a worker process. A sample with a
// straight-line result in line (--relabel) gets only the other starts.
std::string solve_sample(const RobotParams &robot, const GenOptions &opt, const std::vector<Solution> &line,
			 uint64_t i, const RowSink *also)
{
	double a[6] = {0}, b[6] = {0};
	draw_pair(robot.mode(opt.mode), opt.seed, i, a, b, opt.draws);
	Solution s;
	try {
		s = i < line.size() ? solve_bvp_strategies(opt.mode, robot, a, b, opt.solve, line[i])
				    : solve_bvp(opt.mode, robot, a, b, opt.solve);
	} catch (const std::exception &e) {
		s = Solution();
		s.status_text = kErrorStatus + std::string(e.what());
	}
	return csv_row(opt.mode, i, a, b, s) + (also ? kSinkSeparator + also->line(i, a, b, s) : "");
}

// The workers' results of samples [lo, hi) in the parent: their sink lines
// go to also, the rows stay in rows; counts the converged rows and the
// errors, saying each error.
void take_chunk(const GenOptions &opt, uint64_t lo, std::vector<std::string> &rows, uint64_t &converged,
		uint64_t &errors, RowSink *also)
{
	if (also) {
		std::vector<std::string> lines;
		for (std::string &r : rows) {
			size_t at = r.find(kSinkSeparator);
			if (at == std::string::npos)
				throw std::runtime_error("a worker's row came without its solution");
			lines.push_back(r.substr(at + 1));
			r.resize(at);
		}
		also->append(lo, lines);
	}
	// Count converged rows from their "converged" column; say each error.
	size_t col = csv_column(opt.mode, "converged"), status = csv_column(opt.mode, "status");
	for (size_t k = 0; k < rows.size(); k++) {
		std::vector<std::string> f = csv_fields(rows[k]);
		converged += col < f.size() && f[col] == "1";
		if (status < f.size() && is_error_status(f[status])) {
			errors++;
			std::fprintf(stderr, "trainer: sample %llu: %s (kept as an error row: not a label, fit leaves it out)\n",
				     static_cast<unsigned long long>(lo + k), f[status].c_str());
		}
	}
}

// The straight-line results of --relabel's dataset, by index: its file must
// be this stream's (robot, mode, seed, robot file and segments by its meta)
// made without the other starts, and each row must be the sample drawn here
// with a result that prints back to the same text.
// The meta of a dataset of opt's stream labelled from straight lines alone.
std::string straight_meta_text(const RobotParams &robot, const GenOptions &opt)
{
	GenOptions line_opt = opt;
	line_opt.solve.strategy_starts = false;
	return internal::meta_text(robot, line_opt);
}

std::vector<Solution> line_results(const RobotParams &robot, const GenOptions &opt)
{
	const std::string &path = opt.relabel;
	const std::string meta = read_file(path + ".meta"), want = straight_meta_text(robot, opt);
	if (meta != want)
		throw std::runtime_error("--relabel " + path + ": its " + path + ".meta is not that of a " +
					 robot.robot + " " + hylo_mode_str(opt.mode) + " dataset with seed " +
					 std::to_string(opt.seed) + " from straight-line starts alone under these " +
					 "settings (" + internal::meta_differences(meta, want) + ")");
	std::ifstream f(path);
	std::string text;
	std::vector<std::string> names = csv_columns(opt.mode);
	if (!std::getline(f, text) || csv_fields(text) != names)
		throw std::runtime_error("--relabel " + path + ": line 1 is not the header of a " + hylo_mode_str(opt.mode) + " dataset");
	const hylo_mode m = opt.mode;
	const size_t i_cost = csv_column(m, "cost_j"), i_T = csv_column(m, "T_s"),
		     i_conv = csv_column(m, "converged"), i_status = csv_column(m, "status"),
		     i_iter = csv_column(m, "iterations"), i_seg = csv_column(m, "segments"),
		     i_err = csv_column(m, "replay_error"), i_rcost = csv_column(m, "replay_cost_j");
	std::vector<Solution> out;
	for (uint64_t i = 0; std::getline(f, text); i++) {
		std::string where = "--relabel " + path + " line " + std::to_string(i + 2);
		std::vector<std::string> c = csv_fields(text);
		if (c.size() != names.size())
			throw std::runtime_error(where + ": " + std::to_string(c.size()) + " fields, not " +
						 std::to_string(names.size()));
		Solution s;
		try {
			s.cost = std::stod(c[i_cost]);
			s.T = std::stod(c[i_T]);
			s.converged = c[i_conv] == "1";
			s.status_text = c[i_status];
			s.iterations = std::stoi(c[i_iter]);
			s.segments = std::stoi(c[i_seg]);
			s.replay_error = std::stod(c[i_err]);
			s.replay_cost = std::stod(c[i_rcost]);
		} catch (const std::exception &) {
			throw std::runtime_error(where + ": a result column is not a number");
		}
		double a[6] = {0}, b[6] = {0};
		draw_pair(robot.mode(opt.mode), opt.seed, i, a, b, opt.draws);
		if (csv_row(opt.mode, i, a, b, s) != text)
			throw std::runtime_error(where + ": not sample " + std::to_string(i) + " of this stream");
		out.push_back(s);
	}
	return out;
}

}  // namespace

// The onboard code's, so training and planning cannot disagree.
std::vector<double> relative_coords(hylo_mode mode, const double *a, const double *b)
{
	std::vector<double> r(hylo_relative_count(mode));
	if (r.empty())
		throw std::invalid_argument(std::string("features: no mode ") + hylo_mode_str(mode));
	hylo_relative(mode, a, b, r.data());
	return r;
}

std::vector<double> features_of_relative(hylo_mode mode, const std::vector<double> &r)
{
	if (r.size() != hylo_relative_count(mode) || r.empty())
		throw std::invalid_argument("features: " + std::to_string(r.size()) +
					    " relative coordinates for mode " + hylo_mode_str(mode));
	std::vector<double> f(hylo_feature_count(mode));
	hylo_features_of_relative(mode, r.data(), f.data());
	return f;
}

int feature_count(hylo_mode mode)
{
	unsigned n = hylo_feature_count(mode);
	if (n == 0)
		throw std::invalid_argument(std::string("features: no mode ") + hylo_mode_str(mode));
	return static_cast<int>(n);
}

std::vector<std::vector<double>> feature_symmetries(hylo_mode mode)
{
	if (mode_desc(mode).layout != HYLO_LAYOUT_SPATIAL)
		return {};
	// Features (dx', dy', dz, v1x', v1y', v1z, v2x', v2y', v2z) in the
	// displacement's heading: the reflection across that heading.
	return {{1, -1, 1, 1, -1, 1, 1, -1, 1}};
}

std::vector<double> feature_weights(hylo_mode mode)
{
	if (mode != HYLO_MODE_MARINE)
		return {};
	std::vector<double> w(HYLO_FEATURES_PLANAR, 1.0);
	w[HYLO_FEATURES_PLANAR - 1] = 2;   // (dx', |dy'|, s*dtheta, vx1, vx2, d, turn, arc)
	return w;
}

int draws_for(hylo_mode mode, int requested)
{
	const hylo_mode_desc &d = mode_desc(mode);
	const bool planar = d.planar;
	const bool spatial = d.layout == HYLO_LAYOUT_SPATIAL;
	const int newest = planar ? 4 : 2;
	if (requested == 0)
		return newest;
	if (requested == newest || (!spatial && requested >= 1 && requested <= newest))
		return requested;
	throw std::invalid_argument("--draws " + std::to_string(requested) + ": " + hylo_mode_str(mode) + " pairs are drawn " +
				    (planar ? "as 1, 2, 3 or 4" : spatial ? "as 2 only" : "as 1 or 2"));
}

Supplement supplement(hylo_mode mode, int draws)
{
	const hylo_mode_desc &d = mode_desc(mode);
	const int draw = draws_for(mode, draws);
	const uint64_t paper = with_model_type(mode, [](auto t) { return decltype(t)::type::kDefaultSamples; });
	if (d.planar && draw >= 4)
		return {paper / 2, paper / 4, true};   // 5,760 and 2,880
	if (d.planar && draw == 3)
		return {paper, paper / 4};   // 11,520 and 2,880
	if (d.layout == HYLO_LAYOUT_PHASE && draw >= 2)
		return {paper, paper};       // 2,000 and 2,000
	return {paper, 0};
}

int existing_draws(const GenOptions &opt)
{
	const std::string meta = opt.out_dir + "/" + hylo_mode_str(opt.mode) + ".csv.meta";
	if (!std::filesystem::exists(meta))
		return 0;
	const std::string draws = internal::meta_value(read_file(meta), "draws");
	return draws.empty() ? 1 : std::atoi(draws.c_str());
}

uint64_t existing_rows(const GenOptions &opt)
{
	const std::string path = opt.out_dir + "/" + hylo_mode_str(opt.mode) + ".csv";
	return internal::resume_point(read_file(path), csv_join(csv_columns(opt.mode)) + "\n").rows;
}

void draw_pair(const ModeParams &p, uint64_t seed, uint64_t i, double *a, double *b, int draws)
{
	Stream r{mix(seed * 0x2545f4914f6cdd1dULL + i + 1)};
	const Sampling &s = p.sampling;
	const hylo_mode m = p.id;
	const hylo_mode_desc &d = mode_desc(m);
	if (d.layout == HYLO_LAYOUT_PLANAR) {
		const int draw = draws_for(m, draws);
		const bool rest = draw >= 2 && s.speed_min_mps <= 0 && s.speed_max_mps >= 0;
		auto speed = [&]() {
			return rest && r.uniform(0, 1) < kRestFraction ? 0.0 : r.uniform(s.speed_min_mps, s.speed_max_mps);
		};
		a[0] = 0, a[1] = 0, a[3] = 0;
		const Supplement sup = supplement(m, draw);
		if (sup.holds(i)) {
			// Cruise: the goal on an arc from the start (the turn twice
			// the goal's bearing, as a path of constant curvature), half
			// of them exactly, half within 0.3 rad of it; each speed at
			// rest, at the top speed or between. Energy-optimal paths are
			// made of such edges, and their cost is a narrow valley: an
			// Ambot marine edge 2 m ahead from 1 to 0.5 m/s costs 53 J,
			// 188 J with the goal 0.3 m aside, 65 J on the arc there.
			// Drawn uniformly they are rare, and the model overpriced
			// them by up to 75% (docs/decisions.md, "Cruise pairs").
			auto cruise_speed = [&]() {
				const double u = r.uniform(0, 1);
				return rest && u < kRestFraction ? 0.0
				       : u < kRestFraction + kTopFraction ? s.speed_max_mps
									  : r.uniform(s.speed_min_mps, s.speed_max_mps);
			};
			const double len = s.max_distance_m * r.uniform(0, 1), bearing = r.uniform(-kPi / 4, kPi / 4);
			a[2] = cruise_speed();
			b[0] = len * std::cos(bearing), b[1] = len * std::sin(bearing);
			b[2] = cruise_speed();
			b[3] = 2 * bearing + (r.uniform(0, 1) < 0.5 ? 0.0 : r.uniform(-0.3, 0.3));
			return;
		}
		double rad = s.max_distance_m * std::sqrt(r.uniform(0, 1)), ang = r.uniform(-kPi, kPi);
		a[2] = speed();
		b[0] = rad * std::cos(ang), b[1] = rad * std::sin(ang);
		b[2] = speed();
		// A half turn is the one towards the goal, as the features price it
		// (hylo_relative); no committed row comes within the tie of pi.
		b[3] = hylo_half_turn_towards(r.uniform(-kPi, kPi), b[1]);
	} else if (d.layout == HYLO_LAYOUT_SPATIAL) {
		auto ball = [&](double radius, double *v) {
			double x, y, z;
			do {
				x = r.uniform(-1, 1), y = r.uniform(-1, 1), z = r.uniform(-1, 1);
			} while (x * x + y * y + z * z > 1);
			v[0] = radius * x, v[1] = radius * y, v[2] = radius * z;
		};
		// Velocities level, as the planner's roadmap makes them (hover, or one
		// horizontal velocity per heading, roadmap.c): samples spent on
		// vertical velocities would teach the model edges never asked for. A
		// fifth of them hover (every takeoff and landing is at hover).
		auto level_speed = [&](double *v, double heading) {
			double sp = r.uniform(0, 1) < 0.2 ? 0.0 : r.uniform(0, s.speed_max_mps);
			v[0] = sp == 0 ? 0 : sp * std::cos(heading);
			v[1] = sp == 0 ? 0 : sp * std::sin(heading);
			v[2] = 0;
		};
		a[0] = a[1] = a[2] = 0;
		if (r.uniform(0, 1) < 0.5) {
			// Any level velocities, any displacement.
			level_speed(a + 3, r.uniform(-kPi, kPi));
			ball(s.max_distance_m, b);
			level_speed(b + 3, r.uniform(-kPi, kPi));
		} else {
			// Cruise: both velocities along the horizontal direction of the
			// displacement, which is mostly along it. An energy-optimal path
			// is made of such edges; drawn at random they are rare and the
			// model overpriced them (an 8 m edge at 8 m/s by 3.3x).
			double heading = r.uniform(-kPi, kPi), off[3];
			double along = s.max_distance_m * r.uniform(0, 1);
			do
				ball(0.3 * s.max_distance_m, off);
			while ((along + off[0]) * (along + off[0]) + off[1] * off[1] + off[2] * off[2] >
			       s.max_distance_m * s.max_distance_m);
			double c = std::cos(heading), sn = std::sin(heading);
			b[0] = c * (along + off[0]) - sn * off[1];
			b[1] = sn * (along + off[0]) + c * off[1];
			b[2] = off[2];
			level_speed(a + 3, heading);
			level_speed(b + 3, heading);
		}
	} else {
		// The mode's side of the phase plane: p in [0, 1], [-1, 0] or [-1, 1].
		const double lo = d.side > 0 ? 0.0 : -1.0, hi = d.side < 0 ? 0.0 : 1.0;
		a[0] = r.uniform(lo, hi);
		a[1] = r.uniform(s.speed_min_mps, s.speed_max_mps);
		const Supplement sup = supplement(m, draws);
		if (sup.holds(i)) {
			// Short: the goal within kShortPairMax, inside the side.
			do {
				const double dist = kShortPairMax * r.uniform(0, 1), ang = r.uniform(-kPi, kPi);
				b[0] = a[0] + dist * std::cos(ang);
				b[1] = a[1] + dist * std::sin(ang);
			} while (b[0] < lo || b[0] > hi || b[1] < s.speed_min_mps || b[1] > s.speed_max_mps);
			return;
		}
		b[0] = r.uniform(lo, hi);
		b[1] = r.uniform(s.speed_min_mps, s.speed_max_mps);
	}
}

TrainedRegion trained_region(const ModeParams &p)
{
	const Sampling &s = p.sampling;
	const hylo_mode_desc &d = mode_desc(p.id);
	TrainedRegion r;
	auto bound = [&](unsigned k, double lo, double hi) {
		r.bounded |= 1u << k;
		r.min[k] = lo;
		r.max[k] = hi;
	};
	if (d.layout == HYLO_LAYOUT_PLANAR) {
		bound(2, s.speed_min_mps, s.speed_max_mps);
	} else if (d.layout == HYLO_LAYOUT_SPATIAL) {
		bound(3, -s.speed_max_mps, s.speed_max_mps);
		bound(4, -s.speed_max_mps, s.speed_max_mps);
		bound(5, 0, 0);   // level_speed: vz = 0
	} else {
		bound(0, d.side > 0 ? 0.0 : -1.0, d.side < 0 ? 0.0 : 1.0);
		bound(1, s.speed_min_mps, s.speed_max_mps);
	}
	return r;
}

std::vector<std::string> csv_columns(hylo_mode mode)
{
	std::vector<std::string> c = {"index"};
	unsigned nr = hylo_relative_count(mode);
	if (nr == 0)
		throw std::invalid_argument(std::string("features: no mode ") + hylo_mode_str(mode));
	for (unsigned k = 0; k < nr; k++)
		c.push_back("f" + std::to_string(k));
	int d = mode_desc(mode).xs_dim;
	for (int k = 0; k < d; k++)
		c.push_back("x1_" + std::to_string(k));
	for (int k = 0; k < d; k++)
		c.push_back("x2_" + std::to_string(k));
	for (const char *s : {"cost_j", "T_s", "converged", "status", "iterations", "segments",
			      "replay_error", "replay_cost_j"})
		c.push_back(s);
	return c;
}

size_t csv_column(hylo_mode mode, const std::string &name)
{
	std::vector<std::string> names = csv_columns(mode);
	auto it = std::find(names.begin(), names.end(), name);
	if (it == names.end())
		throw std::invalid_argument(std::string("a ") + hylo_mode_str(mode) + " dataset has no column " + name);
	return static_cast<size_t>(it - names.begin());
}

std::vector<std::string> csv_fields(const std::string &row)
{
	std::vector<std::string> f;
	std::stringstream ss(row);
	std::string c;
	while (std::getline(ss, c, ','))
		f.push_back(c);
	return f;
}

std::string csv_join(const std::vector<std::string> &fields)
{
	std::string row;
	for (size_t k = 0; k < fields.size(); k++)
		row += (k ? "," : "") + fields[k];
	return row;
}

std::string csv_row(hylo_mode mode, uint64_t i, const double *a, const double *b,
		    const Solution &s)
{
	std::string row = std::to_string(i);
	for (double f : relative_coords(mode, a, b))
		row += "," + num(f);
	int d = mode_desc(mode).xs_dim;
	for (int k = 0; k < d; k++)
		row += "," + num(a[k]);
	for (int k = 0; k < d; k++)
		row += "," + num(b[k]);
	std::string status = s.status_text.empty() ? "none" : s.status_text;
	for (char &ch : status)
		if (ch == ',' || ch == '\n')
			ch = ';';
	row += "," + num(s.converged ? s.cost : 0) + "," + num(s.converged ? s.T : 0) + "," +
	       (s.converged ? "1" : "0") + "," + status + "," + std::to_string(s.iterations) + "," +
	       std::to_string(s.segments) + "," +
	       num(std::isfinite(s.replay_error) ? s.replay_error : -1) + "," +
	       num(std::isfinite(s.replay_cost) ? s.replay_cost : -1);
	return row;
}

std::string dataset_path(const GenOptions &opt)
{
	std::string base = opt.out_dir + "/" + hylo_mode_str(opt.mode);
	if (opt.shards > 1)
		return base + ".shard-" + std::to_string(opt.shard) + "-of-" + std::to_string(opt.shards) + ".csv";
	return base + ".csv";
}

namespace {

// ---- generate's steps ---------------------------------------------------

// The options a run relabels under: a dataset of this stream labelled from
// straight lines alone is relabelled in place: it is moved to
// <file>.straight and relabelled from there (resumable), and removed once
// every row of it is done.
GenOptions relabel_in_place(const RobotParams &robot, const GenOptions &opt, const std::string &path,
			    const std::string &meta)
{
	GenOptions ro = opt;
	const std::string straight = path + ".straight", meta_path = path + ".meta";
	if (!ro.relabel.empty() || ro.shards != 1 || !ro.solve.strategy_starts)
		return ro;
	std::string straight_meta = straight_meta_text(robot, opt);
	if (straight_meta != meta && read_file(meta_path) == straight_meta) {
		if (access(straight.c_str(), F_OK) == 0)
			throw std::runtime_error(straight + " exists already; remove it or " + path);
		if (rename(meta_path.c_str(), (straight + ".meta").c_str()) != 0 ||
		    rename(path.c_str(), straight.c_str()) != 0)
			throw std::runtime_error("cannot move " + path + " to " + straight);
		if (opt.progress)
			std::fprintf(stderr, "%s: labelled from straight lines alone; relabelling it (the old rows are in %s)\n",
				     path.c_str(), straight.c_str());
	}
	if (access(straight.c_str(), F_OK) == 0)
		ro.relabel = straight;
	return ro;
}

// The CSV header line, written by the first shard only.
std::string csv_header(const GenOptions &opt)
{
	return opt.shard == 1 ? csv_join(csv_columns(opt.mode)) + "\n" : "";
}

// Resume: the metadata must match (a repaired dataset's but for the
// repair's lines, which stay: they describe its first repaired_rows rows);
// keeps complete rows, drops a torn tail. Returns the index to go on from;
// none when every row asked for is there, labelled under other settings
// (then it may be fitted, not extended). A new dataset gets its metadata.
std::optional<uint64_t> resume(const GenOptions &opt, const std::string &path, const std::string &meta, const std::string &header,
		uint64_t lo, uint64_t hi)
{
	const std::string meta_path = path + ".meta";
	std::string existing = read_file(path);
	if (existing.empty() && access(meta_path.c_str(), F_OK) != 0) {
		write_file_atomically(meta_path, meta);
		return lo;
	}
	internal::ResumePoint r = internal::resume_point(existing, header);
	std::string old_meta = read_file(meta_path);
	if (internal::generated_lines(old_meta) != meta) {
		if (r.rows >= hi - lo && internal::same_stream(old_meta, meta)) {
			if (opt.progress)
				std::fprintf(stderr, "%s: every row asked for is there (labelled under other "
						     "settings, see its .meta); nothing to generate\n",
					     path.c_str());
			return std::nullopt;
		}
		throw std::runtime_error(path + " was made under other settings: " +
					 internal::meta_differences(internal::generated_lines(old_meta), meta) +
					 "; regenerate it into another --out directory");
	}
	if (truncate(path.c_str(), static_cast<off_t>(r.keep)) != 0 && errno != ENOENT)
		throw std::runtime_error("cannot truncate " + path);
	return lo + r.rows;
}

// The progress line on stderr: every chunk on a terminal, else every 10 s
// and at the end.
class Progress {
public:
	// t0: when the run started (its rate counts from there).
	Progress(bool on, std::chrono::steady_clock::time_point t0, uint64_t lo, uint64_t hi)
		: on_(on), lo_(lo), hi_(hi), t0_(t0)
	{
	}
	uint64_t lo() const { return lo_; }

	void chunk_done(const GenSummary &sum, uint64_t e)
	{
		auto now = std::chrono::steady_clock::now();
		double el = std::chrono::duration<double>(now - t0_).count();
		double rate = sum.done / std::max(el, 1e-9);
		double eta = (hi_ - e) / std::max(rate, 1e-9);
		if (!on_ || !(tty_ || std::chrono::duration<double>(now - last_).count() > 10 || e == hi_))
			return;
		last_ = now;
		int width = 30, fill = static_cast<int>(width * static_cast<double>(e - lo_) / std::max<uint64_t>(1, hi_ - lo_));
		std::fprintf(stderr, "%s[%s%s] %llu/%llu samples, %.2f/s, ETA %.0f s, %llu converged, %llu rejected%s",
			     tty_ ? "\r" : "", std::string(static_cast<size_t>(fill), '#').c_str(),
			     std::string(static_cast<size_t>(width - fill), '.').c_str(),
			     static_cast<unsigned long long>(e - lo_), static_cast<unsigned long long>(hi_ - lo_), rate, eta,
			     static_cast<unsigned long long>(sum.converged), static_cast<unsigned long long>(sum.rejected),
			     tty_ ? "" : "\n");
	}

	void end() const
	{
		if (on_ && tty_)
			std::fprintf(stderr, "\n");
	}

private:
	bool on_, tty_ = isatty(STDERR_FILENO);
	uint64_t lo_, hi_;
	std::chrono::steady_clock::time_point t0_, last_ = std::chrono::steady_clock::now();
};

// Solves samples [next, hi) of [progress.lo(), hi) chunk by chunk, appending each chunk's rows to
// the dataset (synced) and counting them into sum.
void solve_rows(const RobotParams &robot, const GenOptions &opt, const std::vector<Solution> &line,
		const std::string &header, Progress progress, uint64_t next, uint64_t hi, GenSummary &sum,
		RowSink *also)
{
	AppendFile out(sum.path);
	if (next == progress.lo() && opt.shard == 1) {
		struct stat fs;
		if (fstat(out.fd(), &fs) == 0 && fs.st_size == 0)
			out.write(header);
	}
	internal::fork_sample_chunks(
		next, hi, opt.jobs, opt.chunk, [&](uint64_t i) { return solve_sample(robot, opt, line, i, also); },
		"solving", [&](uint64_t c, uint64_t e, std::vector<std::string> &rows) {
			uint64_t conv = 0, errs = 0;
			take_chunk(opt, c, rows, conv, errs, also);
			std::string text;
			for (const auto &r : rows)
				text += r + "\n";
			out.write(text);
			out.sync();
			sum.done += e - c;
			sum.converged += conv;
			sum.errors += errs;
			sum.rejected += (e - c) - conv - errs;
			progress.chunk_done(sum, e);
		});
	progress.end();
	out.close();
}

}  // namespace

GenSummary generate(const RobotParams &robot, const GenOptions &opt, RowSink *also)
{
	auto t0 = std::chrono::steady_clock::now();
	if (opt.shard < 1 || opt.shard > opt.shards)
		throw std::invalid_argument("--shard K/N needs 1 <= K <= N");
	make_out_dir(opt.out_dir);
	uint64_t lo = opt.samples * static_cast<uint64_t>(opt.shard - 1) / static_cast<uint64_t>(opt.shards);
	uint64_t hi = opt.samples * static_cast<uint64_t>(opt.shard) / static_cast<uint64_t>(opt.shards);
	GenSummary sum;
	sum.path = dataset_path(opt);
	const std::string meta = internal::meta_text(robot, opt);
	const GenOptions ro = relabel_in_place(robot, opt, sum.path, meta);
	std::vector<Solution> line;
	if (!ro.relabel.empty()) {
		if (ro.shards > 1 || !ro.solve.strategy_starts)
			throw std::invalid_argument("--relabel needs an unsharded run with the other starts");
		line = line_results(robot, ro);
	}
	const std::string header = csv_header(opt);
	const std::optional<uint64_t> next = resume(opt, sum.path, meta, header, lo, hi);
	if (!next) {
		sum.resumed_from = hi - lo;
		return sum;
	}
	sum.resumed_from = *next - lo;
	if (also && !line.empty())
		throw std::invalid_argument("--relabel keeps no solutions (its rows are not solved in full)");
	solve_rows(robot, opt, line, header, Progress(opt.progress, t0, lo, hi), *next, hi, sum, also);
	if (ro.relabel == sum.path + ".straight" && hi >= line.size()) {
		std::remove(ro.relabel.c_str());
		std::remove((ro.relabel + ".meta").c_str());
	}
	sum.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
	return sum;
}

}  // namespace hylo::trainer
