#include "trainer/memory.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "trainer/collocation.hpp"
#include "trainer/dataset.hpp"
#include "trainer/files.hpp"
#include "trainer/frame.hpp"
#include "trainer/svr_export.hpp"

namespace hylo::trainer {
namespace {

// Each coordinate's 1 / range over the rows (0 where it has none).
std::vector<double> inverse_ranges(const std::vector<std::vector<double>> &coords)
{
	const size_t d = coords.empty() ? 0 : coords[0].size();
	std::vector<double> scale(d, 0);
	for (size_t c = 0; c < d; c++) {
		double lo = coords[0][c], hi = coords[0][c];
		for (const auto &x : coords) {
			lo = std::min(lo, x[c]);
			hi = std::max(hi, x[c]);
		}
		scale[c] = hi > lo ? 1.0 / (hi - lo) : 0.0;
	}
	return scale;
}

double scaled_distance2(const std::vector<double> &a, const std::vector<double> &b, const std::vector<double> &scale)
{
	double s = 0;
	for (size_t c = 0; c < scale.size(); c++) {
		double v = (a[c] - b[c]) * scale[c];
		s += v * v;
	}
	return s;
}

}  // namespace

bool improves_on(const Solution &b, const Solution &a)
{
	return b.converged && (!a.converged || b.cost < (1 - 1e-6) * a.cost);
}

std::vector<std::string> sidecar_columns(hylo_mode mode, int points)
{
	std::vector<std::string> c = {"index", "cost_j", "T_s", "converged", "status", "iterations",
				      "segments", "replay_error", "replay_cost_j"};
	for (int p = 0; p < points; p++)
		for (int k = 0; k < mode_desc(mode).nx; k++)
			c.push_back("p" + std::to_string(p) + "_x" + std::to_string(k));
	return c;
}

std::string solution_line(const RobotParams &robot, hylo_mode mode, int points, uint64_t i, const double *a,
			  const double *b, const Solution &s)
{
	std::vector<std::string> f = csv_fields(csv_row(mode, i, a, b, s));
	std::string out = std::to_string(i);
	for (auto it = f.end() - 8; it != f.end(); ++it)
		out += "," + *it;
	const size_t nx = static_cast<size_t>(mode_desc(mode).nx);
	std::vector<std::vector<double>> path;
	if (s.converged)
		path = transplanted_guess(s.traj, s.T, full_state(mode, robot, a), full_state(mode, robot, b), points).path;
	for (int p = 0; p < points; p++)
		for (size_t k = 0; k < nx; k++)
			out += "," + (s.converged ? format_double(path[static_cast<size_t>(p)][k]) : std::string("0"));
	return out;
}

Solution row_result(const std::vector<std::string> &f, size_t first, const std::string &where)
{
	Solution s;
	try {
		s.cost = std::stod(f.at(first));
		s.T = std::stod(f.at(first + 1));
		s.converged = f.at(first + 2) == "1";
		s.status_text = f.at(first + 3);
		s.iterations = std::stoi(f.at(first + 4));
		s.segments = std::stoi(f.at(first + 5));
		s.replay_error = std::stod(f.at(first + 6));
		s.replay_cost = std::stod(f.at(first + 7));
	} catch (const std::exception &) {
		throw std::invalid_argument(where + ": a result column is missing or not a number");
	}
	return s;
}

StoredSolution parse_solution_line(hylo_mode mode, const std::string &line, uint64_t i, int points,
				   const std::string &where)
{
	std::vector<std::string> f = csv_fields(line);
	const size_t nx = static_cast<size_t>(mode_desc(mode).nx);
	if (f.size() != 9 + nx * static_cast<size_t>(points) || f[0] != std::to_string(i))
		throw std::runtime_error(where + ": not the sidecar row of sample " + std::to_string(i));
	StoredSolution st;
	try {
		st.s = row_result(f, 1, where);
		if (st.s.converged)
			for (int p = 0; p < points; p++) {
				std::vector<double> x(nx);
				for (size_t k = 0; k < nx; k++)
					x[k] = std::stod(f[9 + static_cast<size_t>(p) * nx + k]);
				st.path.push_back(std::move(x));
			}
	} catch (const std::invalid_argument &) {   // row_result's, or stod's
		throw std::runtime_error(where + ": a result or path column is not a number");
	} catch (const std::out_of_range &) {
		throw std::runtime_error(where + ": a result or path column is out of range");
	}
	return st;
}

Guess stored_guess(hylo_mode mode, const StoredSolution &stored, const std::vector<double> &a,
		   const std::vector<double> &b, int points)
{
	Trajectory tr;
	tr.nx = mode_desc(mode).nx;
	const auto &path = stored.path;
	for (size_t p = 0; p < path.size(); p++) {
		tr.t.push_back(stored.s.T * static_cast<double>(p) / static_cast<double>(path.size() - 1));
		tr.x.insert(tr.x.end(), path[p].begin(), path[p].end());
	}
	return transplanted_guess(tr, stored.s.T, a, b, points);
}

std::vector<std::vector<uint64_t>> nearest_rows(const std::vector<std::vector<double>> &coords,
						const std::vector<StoredSolution> &sol, int k)
{
	const size_t n = coords.size();
	const std::vector<double> scale = inverse_ranges(coords);
	std::vector<std::vector<uint64_t>> out(n);
	std::vector<std::pair<double, uint64_t>> cand;
	for (size_t i = 0; i < n; i++) {
		cand.clear();
		for (size_t j = 0; j < n; j++)
			if (j != i && sol[j].s.converged)
				cand.emplace_back(scaled_distance2(coords[i], coords[j], scale), j);
		size_t m = std::min(cand.size(), static_cast<size_t>(std::max(0, k)));
		std::partial_sort(cand.begin(), cand.begin() + static_cast<std::ptrdiff_t>(m), cand.end());
		for (size_t q = 0; q < m; q++)
			out[i].push_back(cand[q].second);
	}
	return out;
}

Memory::Memory(const RobotParams &robot, hylo_mode mode, const std::string &dir) : mode_(mode)
{
	const std::string name = hylo_mode_str(mode), data = dir + "/" + name + ".csv";
	sidecar_ = dir + "/" + name + ".solutions.csv";
	const std::string hint = " (a memory is a dataset and its solutions: trainer --stage gen --solutions)";
	auto file = [&](const std::string &path) {
		std::string text = read_file(path);
		if (text.empty())
			throw std::invalid_argument("memory: no " + path + hint);
		return text;
	};
	const std::string data_meta = file(data + ".meta"), side_meta = file(sidecar_ + ".meta");
	for (const auto &m : {std::make_pair(data, data_meta), std::make_pair(sidecar_, side_meta)}) {
		const std::pair<const char *, std::string> want[] = {
			{"robot", robot.robot}, {"mode", name}, {"params_sha256", robot.labels_sha256}};
		for (const auto &w : want)
			if (internal::meta_value(m.second, w.first) != w.second)
				throw std::invalid_argument("memory: " + m.first + ".meta has " + w.first + " '" +
							    internal::meta_value(m.second, w.first) + "', not this robot file's '" +
							    w.second + "'");
	}
	if (!internal::same_stream(data_meta, side_meta))
		throw std::invalid_argument("memory: " + sidecar_ + " is not " + data + "'s stream (" +
					    internal::meta_differences(data_meta, side_meta) + ")");
	points_ = std::atoi(internal::meta_value(side_meta, "path_points").c_str());
	if (points_ < 2)
		throw std::invalid_argument("memory: " + sidecar_ + ".meta has no path_points of at least 2");

	const std::vector<std::string> rows = complete_lines(file(data)), sides = complete_lines(file(sidecar_));
	if (rows.empty() || rows[0] != csv_join(csv_columns(mode)))
		throw std::invalid_argument("memory: " + data + " line 1 is not the header of a " + name + " dataset");
	if (sides.empty() || sides[0] != csv_join(sidecar_columns(mode, points_)))
		throw std::invalid_argument("memory: " + sidecar_ + " line 1 is not the header of " +
					    std::to_string(points_) + "-point " + name + " solutions");
	const size_t ix = csv_column(mode, "x1_0"), d = mode_desc(mode).xs_dim;
	const size_t n = std::min(rows.size(), sides.size()) - 1;
	for (size_t r = 1; r <= n; r++) {
		const std::string where = data + " line " + std::to_string(r + 1);
		std::vector<std::string> f = csv_fields(rows[r]);
		std::vector<double> x(2 * d);
		uint64_t i = 0;
		try {
			if (f.size() != csv_columns(mode).size())
				throw std::invalid_argument("");
			i = std::stoull(f[0]);
			for (size_t k = 0; k < 2 * d; k++)
				x[k] = std::stod(f[ix + k]);
		} catch (const std::exception &) {
			throw std::invalid_argument("memory: " + where + ": not a row of a " + name + " dataset");
		}
		StoredSolution st;
		try {
			st = parse_solution_line(mode, sides[r], i, points_, sidecar_ + " line " + std::to_string(r + 1));
		} catch (const std::runtime_error &e) {
			throw std::invalid_argument("memory: " + std::string(e.what()));
		}
		if (!st.s.converged)
			continue;
		coords_.push_back(std::move(x));
		sol_.push_back(std::move(st));
	}
	scale_ = inverse_ranges(coords_);
}

std::vector<Guess> Memory::guesses(const RobotParams &robot, const double *x1s, const double *x2s, int k) const
{
	const size_t d = mode_desc(mode_).xs_dim;
	const Frame f = start_frame(mode_, x1s);
	std::vector<double> q(x1s, x1s + d);
	q.insert(q.end(), x2s, x2s + d);
	sampled_into_frame(f, q.data());
	sampled_into_frame(f, q.data() + d);
	std::vector<std::pair<double, size_t>> cand;
	for (size_t j = 0; j < coords_.size(); j++)
		cand.emplace_back(scaled_distance2(q, coords_[j], scale_), j);
	const size_t m = std::min(cand.size(), static_cast<size_t>(std::max(0, k)));
	std::partial_sort(cand.begin(), cand.begin() + static_cast<std::ptrdiff_t>(m), cand.end());
	const std::vector<double> a = full_state(mode_, robot, x1s), b = full_state(mode_, robot, x2s);
	std::vector<Guess> out;
	for (size_t c = 0; c < m; c++) {
		StoredSolution moved = sol_[cand[c].second];
		for (auto &x : moved.path)
			full_out_of_frame(f, x);
		out.push_back(stored_guess(mode_, moved, a, b, points_));
	}
	return out;
}

std::unique_ptr<Memory> open_memory(const std::string &dir, const std::string &robot_name, const RobotParams &robot,
				    hylo_mode mode)
{
	std::string d = dir;
	if (d.empty()) {
		d = "trainer/datasets/" + robot_name;
		if (access((d + "/" + hylo_mode_str(mode) + ".solutions.csv").c_str(), F_OK) != 0)
			return nullptr;
	}
	return d == "none" ? nullptr : std::make_unique<Memory>(robot, mode, d);
}

Solution solve_remembered(hylo_mode mode, const RobotParams &robot, const double *x1s, const double *x2s,
			  const SolveOptions &opt, const Memory *memory, int k, size_t *memory_starts)
{
	std::vector<Guess> guesses;
	if (memory)
		guesses = memory->guesses(robot, x1s, x2s, k);
	if (memory_starts)
		*memory_starts = guesses.size();
	Solution s = solve_bvp(mode, robot, x1s, x2s, opt);
	if (guesses.empty())
		return s;
	Solution m = solve_bvp_guesses(mode, robot, x1s, x2s, opt, guesses, s);
	if (improves_on(m, s))
		return m;
	// A tie keeps the pair's own solution, as the repair keeps a label; the
	// starts and seconds add up either way.
	s.starts = m.starts;
	s.converged_starts = m.converged_starts;
	s.refined_starts = m.refined_starts;
	s.solve_seconds = m.solve_seconds;
	return s;
}

}  // namespace hylo::trainer
