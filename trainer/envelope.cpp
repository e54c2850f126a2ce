#include "trainer/envelope.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

#include <Eigen/Dense>

#include "hylo/envelope.h"
#include "hylo/features.h"
#include "hylo/modes.h"
#include "hylo/svr.h"

// How the table is computed (onboard/models/README.md, "Envelope"):
//
// Ground and marine. M(d, turn cell, v1, v2) is the least predicted cost
// of the edges from (0, 0, v1, heading 0) to (d cos b, d sin b, v2, heading
// dtheta) over the bearing b in [0, pi] and the heading change dtheta in
// [-pi, pi] whose turn hylo_envelope_turn(b, 0, dtheta) (the planner's
// argument) lies in the cell (the features mirror a goal on the right to
// the left, so b in [0, pi] covers every edge; the heading feature jumps at
// dtheta = +-pi, whose other side the mirror images reach, so both ends are
// searched). 16 turn cells over [0, 2 pi], each widened by 1e-9 rad on both
// sides (the features' turn may differ from the argument in the last bits,
// so an edge on a cell boundary counts in both cells). At every cell end d
// = k d_step (the first at 1e-9 m: the limit d -> 0+, whose features include
// those of d = 0) the costs of a 37 x 73 grid of (b, dtheta), 5 degrees
// apart, are computed once; every grid point counts in the turn cell(s) of
// its turn, and each turn cell and speed pair gets its grid minima within
// the cell; from the best of both ends (within 1%, at most 3) a pattern
// search over (d, b, dtheta), d inside the distance cell and every poll
// point moved into the turn cell (into_turn_range), finds the cell's least
// cost. Pattern search because the features turn and arc are kinked: the
// grid was 15 degrees apart and the poll the axes and three diagonals at
// first, and 1 in 10^6 random edges still cost up to 0.7% less than its
// cell (minima in narrow wedges between kinks, and past the seam); now none
// do. Edges that stay in place (d = 0) get turn 0 from hylo_envelope_args,
// so the first distance cell's turn cell 0 also holds their least cost
// (coincident_minimum).
//
// Flight. M(dh, dz, s1, s2) is the least predicted cost from (0, 0, 0) with
// level velocity s1 (cos psi1, sin psi1, 0) to (dh, 0, dz) with s2 (cos
// psi2, sin psi2, 0) over psi1, psi2 (the features are taken in the
// horizontal displacement's heading, so that covers every rotation about z;
// dh = 1e-9 m stands for the first column's dh -> 0+). The kernel
// factorizes over (displacement), (v1), (v2), so at every cell corner the
// costs of a 12 x 12 grid of directions per speed pair are one matrix
// product; Newton's method refines the grid minima (within 1%, at most 3),
// and from the distinct ones of the cell's four corners Newton's method with
// the displacement held in the cell (projected, trust region) finds the
// cell's least cost. Smooth, so Newton: the cost has several minima in the
// directions and interior minima in the displacement (an 8 m/s edge is
// cheapest near 7 m). The search evaluates the decision value itself (the
// same sum, one exponential per support vector, with exact derivatives).
//
// Every value kept comes from hylo_svr_predict_batch on a real edge built
// by hylo_features(): the planner's number. The search only decides where.

namespace hylo::trainer {
namespace {

using Clock = std::chrono::steady_clock;
constexpr double kPi = 3.14159265358979323846;
constexpr double kTinyDistance = 1e-9;  // the first cell's lower end: d -> 0+
constexpr double kPlanarDStep = 0.1, kFlightStep = 0.25;
constexpr int kBearings = 37, kHeadings = 73;  // planar grid: b = j pi / 36, dtheta = -pi + l pi / 36
constexpr double kSeam = 1e-9;                // dtheta's lower end: -pi + this
constexpr uint32_t kTurnCells = 16;           // planar turn cells over [0, 2 pi]
constexpr double kTurnSlack = 1e-9;           // a turn cell also holds turns this close to its ends
constexpr int kDirections = 12;               // flight grid: psi = -pi + l pi / 6
constexpr double kStartTolerance = 0.01;      // refine grid minima within 1% of the best
constexpr size_t kMaxStarts = 3;
// The turn table's cells have more local minima (the band cuts basins):
// more starts, from further up.
constexpr double kTurnStartTolerance = 0.05;
constexpr size_t kTurnStarts = 4;
constexpr size_t kEdgesPerChunk = 4096;

// mode when its models may carry an envelope (their feature layout's,
// hylo/modes.h), else HYLO_MODE_NONE.
hylo_mode envelope_mode(hylo_mode mode)
{
	const hylo_feature_layout *l = hylo_mode_layout(mode);
	return l && l->envelope ? mode : HYLO_MODE_NONE;
}

double seconds_since(Clock::time_point t0)
{
	return std::chrono::duration<double>(Clock::now() - t0).count();
}

// The onboard batch evaluator with a cache of its own (one per thread).
class Evaluator {
public:
	Evaluator(const hylo_svr_model &m, hylo_mode mode)
		: m_(m), mode_(mode), nf_(hylo_feature_count(mode)), cache_(new hylo_svr_cache()),
		  mem_(hylo_svr_cache_size(&m) / sizeof(double) + 1)
	{
		hylo_svr_cache_attach(cache_.get(), mem_.data(), mem_.size() * sizeof(double));
	}
	void clear() { x_.clear(); }
	void add(const double *tail, const double *head)
	{
		x_.resize(x_.size() + nf_);
		hylo_features(mode_, tail, head, &x_[x_.size() - nf_]);
	}
	size_t size() const { return x_.size() / nf_; }
	// The costs of the edges added since clear().
	const std::vector<double> &run()
	{
		cost_.resize(size());
		if (hylo_svr_predict_batch(&m_, cache_.get(), x_.data(), static_cast<uint32_t>(size()),
					   cost_.data()) != HYLO_OK)
			throw std::runtime_error("envelope: the onboard evaluator refused the model");
		return cost_;
	}

private:
	const hylo_svr_model &m_;
	hylo_mode mode_;
	unsigned nf_;
	std::unique_ptr<hylo_svr_cache> cache_;
	std::vector<double> mem_;   // the cache's memory (hylo_svr_cache_size)
	std::vector<double> x_, cost_;
};

// One evaluator per thread.
std::vector<std::unique_ptr<Evaluator>> evaluators(const hylo_svr_model &m, hylo_mode mode, int jobs)
{
	std::vector<std::unique_ptr<Evaluator>> evs(static_cast<size_t>(std::max(1, jobs)));
	for (auto &e : evs)
		e = std::make_unique<Evaluator>(m, mode);
	return evs;
}

// Runs f(i, worker) for i in [0, n) on up to jobs threads, handing out
// indices in order; f writes its results to per-index slots, so they do not
// depend on the scheduling. The first exception is rethrown.
template <class F>
void parallel(size_t n, int jobs, F f)
{
	const size_t workers = std::max<size_t>(1, std::min<size_t>(n, static_cast<size_t>(std::max(1, jobs))));
	std::atomic<size_t> next{0};
	std::exception_ptr error;
	std::mutex mu;
	auto run = [&](size_t w) {
		try {
			for (size_t i; (i = next++) < n;)
				f(i, w);
		} catch (...) {
			std::lock_guard<std::mutex> lock(mu);
			if (!error)
				error = std::current_exception();
			next = n;
		}
	};
	std::vector<std::thread> pool;
	for (size_t w = 1; w < workers; w++)
		pool.emplace_back(run, w);
	run(0);
	for (auto &t : pool)
		t.join();
	if (error)
		std::rethrow_exception(error);
}

double wrap(double a)
{
	return hylo_wrap_angle(a);
}

// Angular distance on the circle.
double angle_apart(double a, double b)
{
	return std::fabs(wrap(a - b));
}

// The table's layout for m (values not yet filled).
struct Geometry {
	EnvelopeExport t;
	bool flight = false;
	double max_d = 0;

	double speed(uint32_t i) const { return t.v_min + i * t.v_step; }
	uint32_t pairs() const { return t.n_v * t.n_v; }
	size_t index(uint32_t k, uint32_t j, uint32_t pair) const
	{
		return (static_cast<size_t>(k) * t.n_z + j) * pairs() + pair;
	}
	// Cell (k, j) holds edges no longer than the training distance.
	bool needed(uint32_t k, uint32_t j) const
	{
		if (!flight)
			return k * t.d_step <= max_d * (1 + 1e-12);
		double z_lo = t.z_min + j * t.z_step, z_hi = z_lo + t.z_step;
		double z = z_lo > 0 ? z_lo : z_hi < 0 ? z_hi : 0;
		return std::hypot(k * t.d_step, z) <= max_d * (1 + 1e-12);
	}
	double d_end(uint32_t q) const { return q == 0 ? kTinyDistance : q * t.d_step; }
	double z_end(uint32_t q) const { return t.z_min + q * t.z_step; }
};

Geometry geometry(const SvrExport &m)
{
	Geometry g;
	const hylo_feature_layout *layout = hylo_mode_layout(m.mode);
	g.flight = layout && layout->kind == HYLO_LAYOUT_SPATIAL;
	g.max_d = m.max_distance_m;
	EnvelopeExport &t = g.t;
	t.d_step = g.flight ? kFlightStep : kPlanarDStep;
	t.n_d = static_cast<uint32_t>(std::floor(g.max_d / t.d_step + 1e-9)) + 1;  // d = max_d included
	if (g.flight) {
		t.z_step = kFlightStep;
		uint32_t below = static_cast<uint32_t>(std::ceil(g.max_d / t.z_step - 1e-9));
		t.z_min = -(below * t.z_step);
		t.n_z = 2 * below + 1;  // climbs [-max_d, max_d] and a little more
	} else {
		t.n_z = kTurnCells;
		t.z_min = 0;
		t.z_step = 2 * kPi / kTurnCells;
	}
	t.v_min = m.speed_min_mps;
	t.v_step = envelope_speed_step(m.speed_min_mps, m.speed_max_mps);
	t.n_v = static_cast<uint32_t>(std::lround((m.speed_max_mps - m.speed_min_mps) / t.v_step)) + 1;
	return g;
}

// Per cell and speed pair: the least cost found, before the margin. Cells
// beyond the training distance stay at 0.
struct Estimate {
	std::vector<double> cost;
};

// ---------------------------------------------------------------- planar

struct PlanarStart {
	double cost, d, b, t;
};

void planar_edge(double d, double b, double t, double v1, double v2, double *tail, double *head)
{
	tail[0] = 0;
	tail[1] = 0;
	tail[2] = v1;
	tail[3] = 0;
	head[0] = d * std::cos(b);
	head[1] = d * std::sin(b);
	head[2] = v2;
	head[3] = t;
}

// The turn of the edge planar_edge(d, b, t) as the planner looks it up
// (hylo_envelope_args: the bearing b, the tail's heading 0).
double planar_turn(double b, double t)
{
	return hylo_envelope_turn(b, 0, t);
}

// Turn cell j's range, widened by kTurnSlack on both sides: the features'
// turn may differ from hylo_envelope_turn's in the last bits, so a cell
// holds the edges on either side of its ends (the last also 2 pi).
double turn_lo(const Geometry &g, uint32_t j) { return j * g.t.z_step - kTurnSlack; }
double turn_hi(const Geometry &g, uint32_t j) { return (j + 1) * g.t.z_step + kTurnSlack; }

// The turn cells [first, last] whose widened range holds turn.
void turn_cells(const Geometry &g, double turn, uint32_t *first, uint32_t *last)
{
	const double top = g.t.n_z - 1;
	*first = static_cast<uint32_t>(std::min(top, std::max(0.0, std::floor((turn - kTurnSlack) / g.t.z_step))));
	*last = static_cast<uint32_t>(std::min(top, std::max(0.0, std::floor((turn + kTurnSlack) / g.t.z_step))));
}

double grid_bearing(int j) { return j * kPi / (kBearings - 1); }
// The heading feature s * dtheta jumps from pi to -pi (the model sees them
// 2 pi apart), so dtheta's grid and search span the closed [-pi, pi], -pi
// standing for the limit from above (the mirror images of edges with
// dtheta = pi reach it).
double grid_heading(int l) { return l == 0 ? -kPi + kSeam : -kPi + l * 2 * kPi / (kHeadings - 1); }

// Per distance end: the starts of each turn cell and speed pair, [j * np + p].
using PlanarStarts = std::vector<std::vector<PlanarStart>>;

// The best grid minima (within kStartTolerance of the best, at most
// kMaxStarts) of every turn cell and speed pair at distance d: every grid
// point counts in the turn cells whose widened range holds its turn, and is
// a minimum of a cell when no neighbour in the same cell costs less.
PlanarStarts planar_grid(const Geometry &g, Evaluator &ev, double d)
{
	const uint32_t np = g.pairs(), nz = g.t.n_z;
	ev.clear();
	double tail[4], head[4];
	for (int j = 0; j < kBearings; j++)
		for (int l = 0; l < kHeadings; l++)
			for (uint32_t p = 0; p < np; p++) {  // tail speed, then head speed: cached rows
				planar_edge(d, grid_bearing(j), grid_heading(l), g.speed(p / g.t.n_v),
					    g.speed(p % g.t.n_v), tail, head);
				ev.add(tail, head);
			}
	const std::vector<double> &c = ev.run();
	std::vector<double> col(static_cast<size_t>(kBearings) * kHeadings);  // one speed pair's costs
	auto at = [&](int j, int l) { return col[static_cast<size_t>(j) * kHeadings + l]; };
	std::vector<std::array<uint32_t, 2>> cells(static_cast<size_t>(kBearings) * kHeadings);
	for (int j = 0; j < kBearings; j++)
		for (int l = 0; l < kHeadings; l++) {
			auto &cl = cells[static_cast<size_t>(j) * kHeadings + l];
			turn_cells(g, planar_turn(grid_bearing(j), grid_heading(l)), &cl[0], &cl[1]);
		}
	auto in_cell = [&](int j, int l, uint32_t z) {
		const auto &cl = cells[static_cast<size_t>(j) * kHeadings + l];
		return cl[0] <= z && z <= cl[1];
	};
	PlanarStarts starts(static_cast<size_t>(nz) * np);
	std::vector<PlanarStart> mins;
	for (uint32_t p = 0; p < np; p++) {
		for (size_t i = 0; i < col.size(); i++)
			col[i] = c[i * np + p];
		for (uint32_t z = 0; z < nz; z++) {
			mins.clear();
			for (int j = 0; j < kBearings; j++)
				for (int l = 0; l < kHeadings; l++) {
					if (!in_cell(j, l, z))
						continue;
					double v = at(j, l);
					bool lowest = true;
					for (int dj = -1; dj <= 1 && lowest; dj++)
						for (int dl = -1; dl <= 1 && lowest; dl++) {
							int jj = j + dj, ll = l + dl;
							if ((dj || dl) && jj >= 0 && jj < kBearings && ll >= 0 && ll < kHeadings &&
							    in_cell(jj, ll, z) && at(jj, ll) < v)
								lowest = false;
						}
					if (lowest)
						mins.push_back({v, d, grid_bearing(j), grid_heading(l)});
				}
			std::stable_sort(mins.begin(), mins.end(),
					 [](const PlanarStart &a, const PlanarStart &b) { return a.cost < b.cost; });
			std::vector<PlanarStart> &out = starts[static_cast<size_t>(z) * np + p];
			for (const PlanarStart &s : mins)
				if (out.size() < kMaxStarts && s.cost <= mins[0].cost * (1 + kStartTolerance))
					out.push_back(s);
		}
	}
	return starts;
}

// (b, t) moved into the turn range [lo, hi], b kept where it can be: the
// turn is b + |wrap(t - b)|, so b is first held in [lo - pi, hi] and then
// the heading change moved along its side of b. t stays in [-pi + kSeam,
// pi] (a turn within kSeam of the range's end may result).
void into_turn_range(double lo, double hi, double &b, double &t)
{
	b = std::min(std::min(kPi, hi), std::max(std::max(0.0, lo - kPi), b));
	const double e = wrap(t - b), side = e < 0 ? -1 : 1, turn = b + std::fabs(e);
	const double want = std::min(std::min(hi, b + kPi), std::max(std::max(lo, b), turn));
	if (want == turn)
		return;
	t = b + side * (want - b);
	if (t > kPi)
		t -= 2 * kPi;
	t = std::min(kPi, std::max(-kPi + kSeam, t));
}

// Pattern search over (d, b, dtheta) from s, d in [d_lo, d_hi], b in [0,
// pi], dtheta in [-pi, pi], the turn in [turn_lo, turn_hi] (each candidate
// moved into it, into_turn_range): polls 20 directions (d up and down; in
// (b, dtheta) 16 evenly spread and the arc valley's +-(1, 2), the turn
// valley's +-(1, 1) being among the 16: the features are kinked, and a poll
// of the axes alone stalls on a kink), halving the step (at first half the
// grid's, and half the cell in d) when none improves, until it is below
// 1e-3 rad.
PlanarStart pattern_search(Evaluator &ev, double v1, double v2, PlanarStart s, double d_lo, double d_hi,
			   double t_lo, double t_hi, std::atomic<size_t> &evaluations)
{
	static const auto dirs = [] {
		std::vector<std::array<double, 3>> u = {{1, 0, 0}, {-1, 0, 0}};
		for (int k = 0; k < 16; k++)
			u.push_back({0, std::cos(k * kPi / 8), std::sin(k * kPi / 8)});
		const double r = 1 / std::sqrt(5.0);
		u.push_back({0, r, 2 * r});
		u.push_back({0, -r, -2 * r});
		return u;
	}();
	const double angle_unit = kPi / (kBearings - 1), d_unit = d_hi - d_lo;
	double h = 0.5;
	double tail[4], head[4];
	std::vector<PlanarStart> cand;
	for (int it = 0; it < 400 && h * angle_unit > 1e-3; it++) {
		cand.clear();
		ev.clear();
		for (const auto &u : dirs) {
			PlanarStart c = s;
			c.d = std::min(d_hi, std::max(d_lo, s.d + h * u[0] * d_unit));
			c.b = std::min(kPi, std::max(0.0, s.b + h * u[1] * angle_unit));
			c.t = std::min(kPi, std::max(-kPi + kSeam, s.t + h * u[2] * angle_unit));
			into_turn_range(t_lo, t_hi, c.b, c.t);
			if (c.d == s.d && c.b == s.b && c.t == s.t)
				continue;
			planar_edge(c.d, c.b, c.t, v1, v2, tail, head);
			ev.add(tail, head);
			cand.push_back(c);
		}
		if (cand.empty()) {
			h *= 0.5;
			continue;
		}
		const std::vector<double> &cost = ev.run();
		evaluations += cand.size();
		size_t best = cand.size();
		for (size_t i = 0; i < cand.size(); i++)
			if (cost[i] < s.cost && (best == cand.size() || cost[i] < cost[best]))
				best = i;
		if (best < cand.size()) {
			s = cand[best];
			s.cost = cost[best];
		} else {
			h *= 0.5;
		}
	}
	return s;
}

// Edges that stay in place (d = 0; hylo_envelope_args gives them turn 0, so
// turn cell 0 of the first distance cell holds them all). Their features
// depend on the tail heading's quadrant through signed zeros: the bearing
// is 0, or pi when the heading's cosine and sine are both negative
// (atan2(+0, -0)), with the turn |dtheta| or pi + |wrap(dtheta - pi)|. Per
// speed pair the least cost over both and every heading change: a grid of
// 0.5 degrees, its best minima refined by a one-dimensional pattern search.
std::vector<double> coincident_minimum(const Geometry &g, Evaluator &ev, std::atomic<size_t> &evaluations)
{
	constexpr int kSteps = 720;
	const double tails[2] = {0.0, -2.0};  // cos, sin >= 0; both < 0
	const uint32_t np = g.pairs();
	auto heading = [](int l) { return l == 0 ? -kPi + kSeam : -kPi + l * 2 * kPi / kSteps; };
	auto edge = [&](double th1, double dth, uint32_t p, double *tail, double *head) {
		tail[0] = tail[1] = head[0] = head[1] = 0;
		tail[2] = g.speed(p / g.t.n_v);
		head[2] = g.speed(p % g.t.n_v);
		tail[3] = th1;
		head[3] = th1 + dth;
	};
	double tail[4], head[4];
	ev.clear();
	for (double th1 : tails)
		for (int l = 0; l <= kSteps; l++)
			for (uint32_t p = 0; p < np; p++) {
				edge(th1, heading(l), p, tail, head);
				ev.add(tail, head);
			}
	const std::vector<double> grid = ev.run();
	evaluations += grid.size();
	std::vector<double> best(np, INFINITY);
	for (uint32_t p = 0; p < np; p++) {
		struct Start {
			double cost, th1, dth;
		};
		std::vector<Start> mins;
		for (int a = 0; a < 2; a++)
			for (int l = 0; l <= kSteps; l++) {
				auto at = [&](int ll) { return grid[(static_cast<size_t>(a) * (kSteps + 1) + ll) * np + p]; };
				double v = at(l);
				if ((l == 0 || at(l - 1) >= v) && (l == kSteps || at(l + 1) >= v))
					mins.push_back({v, tails[a], heading(l)});
			}
		std::stable_sort(mins.begin(), mins.end(), [](const Start &x, const Start &y) { return x.cost < y.cost; });
		for (size_t s = 0; s < mins.size() && s < 2 * kMaxStarts; s++) {
			Start c = mins[s];
			for (double h = kPi / kSteps; h > 1e-7;) {
				ev.clear();
				double cand[2];
				for (int k = 0; k < 2; k++) {
					cand[k] = std::min(kPi, std::max(-kPi + kSeam, c.dth + (k ? h : -h)));
					edge(c.th1, cand[k], p, tail, head);
					ev.add(tail, head);
				}
				const std::vector<double> &cost = ev.run();
				evaluations += 2;
				int k = cost[0] <= cost[1] ? 0 : 1;
				if (cost[k] < c.cost) {
					c.cost = cost[k];
					c.dth = cand[k];
				} else {
					h *= 0.5;
				}
			}
			best[p] = std::min(best[p], c.cost);
		}
	}
	return best;
}

Estimate planar_estimate(const Geometry &g, const hylo_svr_model &m, hylo_mode mode, const EnvelopeOptions &opt)
{
	const int jobs = opt.jobs;
	const uint32_t n_d = g.t.n_d, n_z = g.t.n_z, np = g.pairs();
	std::vector<std::unique_ptr<Evaluator>> evs = evaluators(m, mode, jobs);
	std::vector<PlanarStarts> ends(n_d + 1);
	auto t0 = Clock::now();
	parallel(n_d + 1, jobs, [&](size_t q, size_t w) {
		ends[q] = planar_grid(g, *evs[w], g.d_end(static_cast<uint32_t>(q)));
	});
	if (opt.debug)
		std::fprintf(stderr, "envelope: grids at %u cell ends in %.1f s\n", n_d + 1, seconds_since(t0));
	std::atomic<size_t> searches{0}, evaluations{0};
	t0 = Clock::now();
	Estimate est;
	est.cost.assign(static_cast<size_t>(n_d) * n_z * np, 0.0);
	const size_t per_d = static_cast<size_t>(n_z) * np;
	parallel(static_cast<size_t>(n_d) * per_d, jobs, [&](size_t i, size_t w) {
		const uint32_t k = static_cast<uint32_t>(i / per_d), z = static_cast<uint32_t>(i % per_d / np),
			       p = static_cast<uint32_t>(i % np);
		if (!g.needed(k, z))
			return;
		std::vector<PlanarStart> starts = ends[k][i % per_d];
		starts.insert(starts.end(), ends[k + 1][i % per_d].begin(), ends[k + 1][i % per_d].end());
		if (starts.empty())
			throw std::logic_error("envelope: a turn cell without grid points");
		std::stable_sort(starts.begin(), starts.end(),
				 [](const PlanarStart &a, const PlanarStart &b) { return a.cost < b.cost; });
		std::vector<PlanarStart> distinct;   // a minimum at both ends once, the better one
		for (const PlanarStart &s : starts) {
			bool seen = false;
			for (const PlanarStart &o : distinct)
				seen |= s.b == o.b && s.t == o.t;
			if (!seen && distinct.size() < kMaxStarts && s.cost <= starts[0].cost * (1 + kStartTolerance))
				distinct.push_back(s);
		}
		double best = distinct[0].cost;
		for (const PlanarStart &s : distinct) {
			PlanarStart r = pattern_search(*evs[w], g.speed(p / g.t.n_v), g.speed(p % g.t.n_v), s,
						       g.d_end(k), g.d_end(k + 1), turn_lo(g, z), turn_hi(g, z),
						       evaluations);
			searches++;
			best = std::min(best, r.cost);
		}
		est.cost[g.index(k, z, p)] = best;
	});
	const std::vector<double> still = coincident_minimum(g, *evs[0], evaluations);
	for (uint32_t p = 0; p < np; p++)
		est.cost[g.index(0, 0, p)] = std::min(est.cost[g.index(0, 0, p)], still[p]);
	if (opt.debug)
		std::fprintf(stderr, "envelope: %zu pattern searches, %zu evaluations, %.1f s\n", searches.load(),
			     evaluations.load(), seconds_since(t0));
	return est;
}

// ---------------------------------------------------------------- flight

// Two doubles per operation (GCC vector extension: SSE2 on x86-64), for
// the flight search's sums; a fixed order of operations, so the same bits
// every run.
typedef double V2 __attribute__((vector_size(16)));
typedef int64_t V2i __attribute__((vector_size(16)));

V2 load2(const double *p)
{
	V2 v;
	std::memcpy(&v, p, sizeof v);
	return v;
}

double sum2(V2 v) { return v[0] + v[1]; }

// exp(x) for x <= 0 to about 4e-16 relative, 0 below -700 (the onboard
// evaluator's method, onboard/src/svr.c): x = k ln2 + r, exp(r) by its
// degree-13 Taylor polynomial, times 2^k put into the exponent bits.
V2 exp_nonpositive(V2 x)
{
	const V2 shift = {0x1.8p52, 0x1.8p52}, lowest = {-700.0, -700.0};
	const double ln2_hi = 0x1.62e42feep-1, ln2_lo = 0x1.a39ef35793c76p-33;
	V2i keep = x >= lowest, xb, lb, tb, pb;
	std::memcpy(&xb, &x, sizeof xb);
	std::memcpy(&lb, &lowest, sizeof lb);
	xb = (xb & keep) | (lb & ~keep);
	std::memcpy(&x, &xb, sizeof x);
	V2 t = x * 0x1.71547652b82fep0 + shift, k = t - shift;
	V2 r = (x - k * ln2_hi) - k * ln2_lo, r2 = r * r, r4 = r2 * r2, r8 = r4 * r4;
	V2 p = ((1.0 + r) + (0.5 + r * (1.0 / 6)) * r2) +
	       ((1.0 / 24 + r * (1.0 / 120)) + (1.0 / 720 + r * (1.0 / 5040)) * r2) * r4 +
	       (((1.0 / 40320 + r * (1.0 / 362880)) + (1.0 / 3628800 + r * (1.0 / 39916800)) * r2) +
		(1.0 / 479001600 + r * (1.0 / 6227020800.0)) * r4) * r8;
	std::memcpy(&tb, &t, sizeof tb);
	std::memcpy(&pb, &p, sizeof pb);
	pb = (pb + (tb << 52)) & keep;
	std::memcpy(&p, &pb, sizeof p);
	return p;
}

// The flight decision value plus rho, g = sum_i coef_i exp(-gamma |z - sv_i|^2),
// as a function of x = (dh, dz, psi1, psi2) at speeds s1, s2, with its
// gradient and Hessian; the features are (dh, 0, dz, s1 cos psi1, s1 sin
// psi1, 0, s2 cos psi2, s2 sin psi2, 0), those hylo_features() gives the
// edge (0, 0, 0, v1) -> (dh, 0, dz, v2). The search's own evaluation (the
// values kept come from the onboard evaluator).
class FlightKernel {
public:
	explicit FlightKernel(const hylo_svr_model &m) : n_(m.n_sv), gamma_(m.gamma), m_(m)
	{
		for (int k = 0; k < 9; k++) {
			o_[k] = m.feature_offset[k];
			s_[k] = m.feature_scale[k];
		}
		const size_t padded = n_ + n_ % 2;   // a zero coefficient pads to pairs
		for (int k : {0, 2, 3, 4, 6, 7})
			col_[k].assign(padded, 0.0);
		c_.assign(padded, 0.0);
		const double z1 = z(1, 0), z5 = z(5, 0), z8 = z(8, 0);
		for (size_t i = 0; i < n_; i++) {
			const double *sv = &m.sv[i * 9];
			for (int k : {0, 2, 3, 4, 6, 7})
				col_[k][i] = sv[k];
			double e1 = z1 - sv[1], e5 = z5 - sv[5], e8 = z8 - sv[8];
			c_[i] = m.coef[i] * std::exp(-gamma_ * (e1 * e1 + e5 * e5 + e8 * e8));
		}
	}
	size_t n_sv() const { return n_; }
	double z(int k, double x) const { return (x - o_[k]) / s_[k]; }

	// exp(-gamma |z_v - sv_v|^2) per support vector for the level velocity
	// s (cos psi, sin psi) of the tail (first = 3) or the head (first = 6).
	void velocity_row(int first, double s, double psi, double *row) const
	{
		const double zx = z(first, s * std::cos(psi)), zy = z(first + 1, s * std::sin(psi));
		for (size_t i = 0; i < n_; i++) {
			double ex = zx - col_[first][i], ey = zy - col_[first + 1][i];
			row[i] = std::exp(-gamma_ * (ex * ex + ey * ey));
		}
	}
	// coef_i exp(-gamma |z_rest - sv_rest|^2): the displacement's and the
	// constant features' factor.
	void weights(double dh, double dz, double *w) const
	{
		const double z0 = z(0, dh), z2 = z(2, dz);
		for (size_t i = 0; i < n_; i++) {
			double e0 = z0 - col_[0][i], e2 = z2 - col_[2][i];
			w[i] = c_[i] * std::exp(-gamma_ * (e0 * e0 + e2 * e2));
		}
	}
	// g(x) with its gradient and Hessian; with displacement false, only
	// their angle parts (the rest 0).
	double eval(const double *x, double s1, double s2, bool displacement, double *grad,
		    double (*hess)[4]) const
	{
		return displacement ? eval_t<true>(x, s1, s2, grad, hess) : eval_t<false>(x, s1, s2, grad, hess);
	}
	// The cost of g (the label transform of g - rho).
	double cost(double g) const
	{
		double y = (g - m_.rho) * m_.label_scale + m_.label_offset;
		return m_.label_log ? std::exp(y) : y;
	}

private:
	template <bool kDisplacement>
	double eval_t(const double *x, double s1, double s2, double *grad, double (*hess)[4]) const
	{
		const double c1 = std::cos(x[2]), n1 = std::sin(x[2]), c2 = std::cos(x[3]), n2 = std::sin(x[3]);
		const double k2 = -2 * gamma_;
		// d/dpsi of the velocity features, first (a) and second (b).
		const double z3a = -s1 * n1 / s_[3], z4a = s1 * c1 / s_[4], z3b = -s1 * c1 / s_[3], z4b = -s1 * n1 / s_[4];
		const double z6a = -s2 * n2 / s_[6], z7a = s2 * c2 / s_[7], z6b = -s2 * c2 / s_[6], z7b = -s2 * n2 / s_[7];
		const V2 z0 = {z(0, x[0]), z(0, x[0])}, z2 = {z(2, x[1]), z(2, x[1])};
		const V2 z3 = {z(3, s1 * c1), z(3, s1 * c1)}, z4 = {z(4, s1 * n1), z(4, s1 * n1)};
		const V2 z6 = {z(6, s2 * c2), z(6, s2 * c2)}, z7 = {z(7, s2 * n2), z(7, s2 * n2)};
		const double q0 = k2 / s_[0], q2 = k2 / s_[2];
		V2 g = {0, 0}, g0 = g, g1 = g, g2 = g, g3 = g, h00 = g, h01 = g, h02 = g, h03 = g, h11 = g,
		   h12 = g, h13 = g, h22 = g, h23 = g, h33 = g, p1 = g, p2 = g;
		for (size_t i = 0; i < c_.size(); i += 2) {
			V2 e0 = z0 - load2(&col_[0][i]), e2 = z2 - load2(&col_[2][i]), e3 = z3 - load2(&col_[3][i]),
			   e4 = z4 - load2(&col_[4][i]), e6 = z6 - load2(&col_[6][i]), e7 = z7 - load2(&col_[7][i]);
			V2 E = load2(&c_[i]) * exp_nonpositive(-gamma_ * (((e0 * e0 + e2 * e2) + (e3 * e3 + e4 * e4)) +
									 (e6 * e6 + e7 * e7)));
			V2 d2 = k2 * (e3 * z3a + e4 * z4a), d3 = k2 * (e6 * z6a + e7 * z7a), Ed2 = E * d2, Ed3 = E * d3;
			g += E;
			g2 += Ed2;
			g3 += Ed3;
			h22 += Ed2 * d2;
			h23 += Ed2 * d3;
			h33 += Ed3 * d3;
			p1 += E * (e3 * z3b + e4 * z4b);
			p2 += E * (e6 * z6b + e7 * z7b);
			if (kDisplacement) {
				V2 d0 = q0 * e0, d1 = q2 * e2, Ed0 = E * d0, Ed1 = E * d1;
				g0 += Ed0;
				g1 += Ed1;
				h00 += Ed0 * d0;
				h01 += Ed0 * d1;
				h02 += Ed0 * d2;
				h03 += Ed0 * d3;
				h11 += Ed1 * d1;
				h12 += Ed1 * d2;
				h13 += Ed1 * d3;
			}
		}
		const double G = sum2(g);
		const double h[4][4] = {
			{sum2(h00) + G * q0 / s_[0], sum2(h01), sum2(h02), sum2(h03)},
			{0, sum2(h11) + G * q2 / s_[2], sum2(h12), sum2(h13)},
			{0, 0, sum2(h22) + k2 * (G * (z3a * z3a + z4a * z4a) + sum2(p1)), sum2(h23)},
			{0, 0, 0, sum2(h33) + k2 * (G * (z6a * z6a + z7a * z7a) + sum2(p2))},
		};
		const double gr[4] = {sum2(g0), sum2(g1), sum2(g2), sum2(g3)};
		for (int a = 0; a < 4; a++) {
			grad[a] = kDisplacement || a >= 2 ? gr[a] : 0;
			for (int b = 0; b < 4; b++)
				hess[a][b] = !kDisplacement && (a < 2 || b < 2) ? 0 : a <= b ? h[a][b] : h[b][a];
		}
		return G;
	}

	size_t n_;
	double gamma_;
	const hylo_svr_model &m_;
	double o_[9], s_[9];
	std::vector<double> col_[9], c_;
};

struct FlightPoint {
	double g;
	double x[4];   // dh, dz, psi1, psi2
};

// Minimizes a smooth g over y (four coordinates, scaled by unit) by Newton
// steps on the free set (a coordinate whose bounds (*bounds)(y, lo, hi) are
// equal is fixed; one at a bound whose gradient points out is held),
// Levenberg-damped when the Hessian is not positive definite, within a
// trust region; project puts a trial point back into the domain. eval(y,
// grad, hess) returns g. Returns g at the y it leaves.
template <class Eval, class Bounds, class Project>
double damped_newton(double *y, const double *unit, Eval eval, Bounds bounds, Project project,
		     double tolerance)
{
	double grad[4], hess[4][4];
	double g = eval(y, grad, hess);
	double radius = 0.5;
	for (int it = 0; it < 60; it++) {
		double lo[4], hi[4];
		bounds(y, lo, hi);
		int idx[4], n = 0;
		for (int a = 0; a < 4; a++) {
			bool held = (y[a] <= lo[a] && grad[a] > 0) || (y[a] >= hi[a] && grad[a] < 0);
			if (lo[a] < hi[a] && !held)
				idx[n++] = a;
		}
		if (n == 0)
			break;
		// Scaled variables z_a = y_a / unit_a: H_z = U H U, g_z = U g.
		Eigen::MatrixXd H(n, n);
		Eigen::VectorXd gz(n);
		double diag = 0;
		for (int a = 0; a < n; a++) {
			gz(a) = grad[idx[a]] * unit[idx[a]];
			for (int b = 0; b < n; b++)
				H(a, b) = hess[idx[a]][idx[b]] * unit[idx[a]] * unit[idx[b]];
			diag = std::max(diag, std::fabs(H(a, a)));
		}
		Eigen::VectorXd step;
		for (double lambda = 0;; lambda = lambda == 0 ? 1e-8 * (diag + gz.norm()) + 1e-300 : lambda * 10) {
			Eigen::MatrixXd Hl = H;
			Hl.diagonal().array() += lambda;
			Eigen::LLT<Eigen::MatrixXd> llt(Hl);
			if (llt.info() == Eigen::Success) {
				step = -llt.solve(gz);
				if (step.allFinite())
					break;
			}
			if (lambda > 1e300)
				return g;
		}
		double len = step.cwiseAbs().maxCoeff();
		if (len > radius)
			step *= radius / len;
		double q[4] = {y[0], y[1], y[2], y[3]};
		for (int a = 0; a < n; a++)
			q[idx[a]] += step(a) * unit[idx[a]];
		project(q);
		double qgrad[4], qhess[4][4];
		double qg = eval(q, qgrad, qhess);
		if (qg < g) {
			g = qg;
			std::copy(q, q + 4, y);
			std::copy(qgrad, qgrad + 4, grad);
			for (int a = 0; a < 4; a++)
				std::copy(qhess[a], qhess[a] + 4, hess[a]);
			radius = std::min(1.0, 2 * radius);
			if (std::min(len, radius) < tolerance)
				break;
		} else {
			radius = 0.25 * std::min(len, radius);
			if (radius < tolerance)
				break;
		}
	}
	return g;
}

// Minimizes g over the free coordinates of x, the displacement kept in
// [lo, hi] (coordinates with lo == hi are fixed; a zero speed's direction
// too) and the directions wrapped (damped_newton; the trust region in
// radians, the displacement in cells).
FlightPoint newton(const FlightKernel &K, double s1, double s2, FlightPoint p, const double *lo,
		   const double *hi, double cell, double tolerance)
{
	const bool free_angle[2] = {s1 > 0, s2 > 0};
	const double unit[4] = {cell, cell, 1, 1};
	const bool displacement = lo[0] < hi[0] || lo[1] < hi[1];
	auto eval = [&](const double *x, double *grad, double (*hess)[4]) {
		return K.eval(x, s1, s2, displacement, grad, hess);
	};
	auto bounds = [&](const double *x, double *l, double *h) {
		for (int a = 0; a < 2; a++) {
			l[a] = lo[a];
			h[a] = hi[a];
			l[a + 2] = free_angle[a] ? -INFINITY : x[a + 2];
			h[a + 2] = free_angle[a] ? INFINITY : x[a + 2];
		}
	};
	auto project = [&](double *x) {
		for (int a = 0; a < 2; a++) {
			x[a] = std::min(hi[a], std::max(lo[a], x[a]));
			x[a + 2] = wrap(x[a + 2]);
		}
	};
	p.g = damped_newton(p.x, unit, eval, bounds, project, tolerance);
	return p;
}

// The speed nodes' rows of the direction grid (a zero speed has one row).
struct DirectionGrid {
	std::vector<int> first, count;
	std::vector<double> psi;   // per row
	int rows = 0;
};

// n directions 2 pi / n apart per nonzero speed node (psi = -pi + (l + 1)
// 2 pi / n), and the kernel's velocity factors of every row: A the tail's,
// B the head's (FlightKernel::velocity_row).
DirectionGrid direction_grid(const Geometry &g, const FlightKernel &K, int n, Eigen::MatrixXd &A,
			     Eigen::MatrixXd &B)
{
	DirectionGrid d;
	for (uint32_t i = 0; i < g.t.n_v; i++) {
		int c = g.speed(i) == 0 ? 1 : n;
		d.first.push_back(d.rows);
		d.count.push_back(c);
		for (int l = 0; l < c; l++)
			d.psi.push_back(c == 1 ? 0 : -kPi + (l + 1) * 2 * kPi / n);
		d.rows += c;
	}
	const Eigen::Index nsv = static_cast<Eigen::Index>(K.n_sv());
	A.resize(d.rows, nsv);
	B.resize(d.rows, nsv);
	std::vector<double> row(K.n_sv());
	for (uint32_t i = 0, r = 0; i < g.t.n_v; i++)
		for (int l = 0; l < d.count[i]; l++, r++) {
			K.velocity_row(3, g.speed(i), d.psi[r], row.data());
			A.row(r) = Eigen::Map<const Eigen::RowVectorXd>(row.data(), nsv);
			K.velocity_row(6, g.speed(i), d.psi[r], row.data());
			B.row(r) = Eigen::Map<const Eigen::RowVectorXd>(row.data(), nsv);
		}
	return d;
}

// The distinct minima (at most kMaxStarts, best first) of every speed pair
// at one corner (dh, dz): grid minima within kStartTolerance of the best,
// each refined by Newton over the directions.
std::vector<std::vector<FlightPoint>> flight_corner(const Geometry &g, const FlightKernel &K,
						    const DirectionGrid &dg, const Eigen::MatrixXd &A,
						    const Eigen::MatrixXd &B, double dh, double dz)
{
	Eigen::VectorXd w(static_cast<Eigen::Index>(K.n_sv()));
	K.weights(dh, dz, w.data());
	const Eigen::MatrixXd G = (A * w.asDiagonal()) * B.transpose();
	const double fixed[2] = {dh, dz};
	std::vector<std::vector<FlightPoint>> out(g.pairs());
	for (uint32_t p = 0; p < g.pairs(); p++) {
		const uint32_t i1 = p / g.t.n_v, i2 = p % g.t.n_v;
		const int f1 = dg.first[i1], c1 = dg.count[i1], f2 = dg.first[i2], c2 = dg.count[i2];
		std::vector<FlightPoint> mins;
		for (int a = 0; a < c1; a++)
			for (int b = 0; b < c2; b++) {
				double v = G(f1 + a, f2 + b);
				bool lowest = true;
				for (int da = -1; da <= 1 && lowest; da++)
					for (int db = -1; db <= 1 && lowest; db++)
						if ((da || db) && G(f1 + (a + da + c1) % c1, f2 + (b + db + c2) % c2) < v)
							lowest = false;
				if (lowest)
					mins.push_back({v, {dh, dz, dg.psi[f1 + a], dg.psi[f2 + b]}});
			}
		std::stable_sort(mins.begin(), mins.end(),
				 [](const FlightPoint &a, const FlightPoint &b) { return a.g < b.g; });
		std::vector<FlightPoint> refined;
		for (size_t s = 0; s < mins.size() && s < kMaxStarts; s++) {
			if (K.cost(mins[s].g) > K.cost(mins[0].g) * (1 + kStartTolerance))
				break;
			refined.push_back(newton(K, g.speed(i1), g.speed(i2), mins[s], fixed, fixed, kFlightStep, 1e-5));
		}
		std::stable_sort(refined.begin(), refined.end(),
				 [](const FlightPoint &a, const FlightPoint &b) { return a.g < b.g; });
		for (const FlightPoint &r : refined) {
			bool seen = false;
			for (const FlightPoint &o : out[p])
				seen |= angle_apart(r.x[2], o.x[2]) < 1e-3 && angle_apart(r.x[3], o.x[3]) < 1e-3;
			if (!seen)
				out[p].push_back(r);
		}
	}
	return out;
}

void flight_edge(const double *x, double s1, double s2, double *tail, double *head)
{
	tail[0] = tail[1] = tail[2] = 0;
	tail[3] = s1 * std::cos(x[2]);
	tail[4] = s1 * std::sin(x[2]);
	tail[5] = 0;
	head[0] = x[0];
	head[1] = 0;
	head[2] = x[1];
	head[3] = s2 * std::cos(x[3]);
	head[4] = s2 * std::sin(x[3]);
	head[5] = 0;
}

Estimate flight_estimate(const Geometry &g, const hylo_svr_model &m, const EnvelopeOptions &opt)
{
	const int jobs = opt.jobs;
	const FlightKernel K(m);
	Eigen::MatrixXd A, B;
	const DirectionGrid dg = direction_grid(g, K, kDirections, A, B);
	const uint32_t n_d = g.t.n_d, n_z = g.t.n_z, np = g.pairs();
	auto corner_needed = [&](uint32_t q, uint32_t r) {
		for (uint32_t k = q > 0 ? q - 1 : 0; k <= q && k < n_d; k++)
			for (uint32_t j = r > 0 ? r - 1 : 0; j <= r && j < n_z; j++)
				if (g.needed(k, j))
					return true;
		return false;
	};
	// Corners (q, r): dh = d_end(q), dz = z_end(r).
	const size_t nc = static_cast<size_t>(n_d + 1) * (n_z + 1);
	std::vector<std::vector<std::vector<FlightPoint>>> corners(nc);
	auto t0 = Clock::now();
	parallel(nc, jobs, [&](size_t c, size_t) {
		const uint32_t q = static_cast<uint32_t>(c / (n_z + 1)), r = static_cast<uint32_t>(c % (n_z + 1));
		if (corner_needed(q, r))
			corners[c] = flight_corner(g, K, dg, A, B, g.d_end(q), g.z_end(r));
	});
	if (opt.debug)
		std::fprintf(stderr, "envelope: %zu cell corners in %.1f s\n", nc, seconds_since(t0));
	t0 = Clock::now();
	std::vector<std::unique_ptr<Evaluator>> evs = evaluators(m, HYLO_MODE_FLIGHT, jobs);
	Estimate est;
	est.cost.assign(static_cast<size_t>(n_d) * n_z * np, 0.0);
	parallel(static_cast<size_t>(n_d) * n_z, jobs, [&](size_t cell, size_t w) {
		const uint32_t k = static_cast<uint32_t>(cell / n_z), j = static_cast<uint32_t>(cell % n_z);
		if (!g.needed(k, j))
			return;
		const double lo[2] = {g.d_end(k), g.z_end(j)}, hi[2] = {g.d_end(k + 1), g.z_end(j + 1)};
		Evaluator &ev = *evs[w];
		ev.clear();
		double tail[6], head[6];
		for (uint32_t p = 0; p < np; p++) {
			const double s1 = g.speed(p / g.t.n_v), s2 = g.speed(p % g.t.n_v);
			std::vector<FlightPoint> starts;
			for (uint32_t dq = 0; dq < 2; dq++)
				for (uint32_t dr = 0; dr < 2; dr++) {
					const auto &c = corners[static_cast<size_t>(k + dq) * (n_z + 1) + j + dr];
					if (!c.empty())
						starts.insert(starts.end(), c[p].begin(), c[p].end());
				}
			std::stable_sort(starts.begin(), starts.end(),
					 [](const FlightPoint &a, const FlightPoint &b) { return a.g < b.g; });
			std::vector<FlightPoint> distinct;
			for (const FlightPoint &s : starts) {
				bool seen = false;
				for (const FlightPoint &o : distinct)
					seen |= angle_apart(s.x[2], o.x[2]) < 0.05 && angle_apart(s.x[3], o.x[3]) < 0.05;
				if (!seen && distinct.size() < kMaxStarts &&
				    K.cost(s.g) <= K.cost(starts[0].g) * (1 + kStartTolerance))
					distinct.push_back(s);
			}
			FlightPoint best = distinct.at(0);
			for (const FlightPoint &s : distinct) {
				FlightPoint r = newton(K, s1, s2, s, lo, hi, kFlightStep, 1e-8);
				if (r.g < best.g)
					best = r;
			}
			flight_edge(best.x, s1, s2, tail, head);
			ev.add(tail, head);
		}
		const std::vector<double> &cost = ev.run();
		for (uint32_t p = 0; p < np; p++)
			est.cost[g.index(k, j, p)] = cost[p];
	});
	if (opt.debug)
		std::fprintf(stderr, "envelope: %u cells in %.1f s\n", n_d * n_z, seconds_since(t0));
	return est;
}

// ---------------------------------------------------------------- flight turn table

// The turn table's layout: the climb table's distance cells and speed
// nodes, kTurnCells turn cells over [0, 2 pi] (as a planar table's).
Geometry turn_geometry(const Geometry &g)
{
	Geometry t = g;
	t.t.n_z = kTurnCells;
	t.t.z_min = 0;
	t.t.z_step = 2 * kPi / kTurnCells;
	return t;
}

// The largest climb of distance cell k's edges within the training ball.
double climb_reach(const Geometry &g, uint32_t k)
{
	const double d = k == 0 ? 0 : g.d_end(k);
	return d >= g.max_d ? 0 : std::sqrt(g.max_d * g.max_d - d * d);
}

// The turn hylo_envelope_flight_turn gives the edge flight_edge(x, s1, s2).
double flight_turn(const double *x, double s1, double s2)
{
	return (s1 > 0 ? std::fabs(wrap(x[2])) : 0) + (s2 > 0 ? std::fabs(wrap(x[3])) : 0);
}

// Minimizes g over y = (dh, dz, T, u) from start: the displacement in [lo, hi], the
// turn T in [t_lo, t_hi] and the velocity directions psi1 = sigma1 u, psi2
// = sigma2 (T - u) with u in [max(0, T - pi), min(T, pi)], so both lie in
// [-pi, pi] and their turn is T (one speed zero: the other's direction is
// sigma T and u is not used; both zero: T = 0). The map to (dh, dz, psi1,
// psi2) is linear, so Newton's method on y has the exact gradient and
// Hessian; bounds, damping and trust region as newton()'s (u's bounds move
// with T: u is put back into them after each step). +inf when the band
// holds no turn of these speeds.
FlightPoint newton_on_turn(const FlightKernel &K, double s1, double s2, double sigma1, double sigma2,
			   const FlightPoint &start, const double *lo, const double *hi, double t_lo,
			   double t_hi, double tolerance)
{
	const bool m1 = s1 > 0, m2 = s2 > 0;
	const double top = (m1 ? kPi : 0) + (m2 ? kPi : 0);
	FlightPoint p;
	p.g = INFINITY;
	const double t_min = std::max(0.0, t_lo), t_max = std::min(top, t_hi);
	if (t_min > t_max)
		return p;
	// J: d(dh, dz, psi1, psi2) / d(dh, dz, T, u).
	double J[4][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 0, 0}, {0, 0, 0, 0}};
	if (m1 && m2) {
		J[2][3] = sigma1;
		J[3][2] = sigma2;
		J[3][3] = -sigma2;
	} else if (m1) {
		J[2][2] = sigma1;
	} else if (m2) {
		J[3][2] = sigma2;
	}
	auto to_x = [&](const double *y, double *x) {
		for (int i = 0; i < 4; i++) {
			x[i] = 0;
			for (int a = 0; a < 4; a++)
				x[i] += J[i][a] * y[a];
		}
	};
	auto eval = [&](const double *y, double *gy, double (*hy)[4]) {
		double x[4], gx[4], hx[4][4];
		to_x(y, x);
		const double v = K.eval(x, s1, s2, true, gx, hx);
		for (int a = 0; a < 4; a++) {
			gy[a] = 0;
			for (int i = 0; i < 4; i++)
				gy[a] += J[i][a] * gx[i];
			for (int b = 0; b < 4; b++) {
				hy[a][b] = 0;
				for (int i = 0; i < 4; i++)
					for (int k = 0; k < 4; k++)
						hy[a][b] += J[i][a] * hx[i][k] * J[k][b];
			}
		}
		return v;
	};
	// u's bounds move with T.
	auto bounds = [&](const double *y, double *l, double *h) {
		l[0] = lo[0], h[0] = hi[0], l[1] = lo[1], h[1] = hi[1], l[2] = t_min, h[2] = t_max;
		l[3] = m1 && m2 ? std::max(0.0, y[2] - kPi) : 0;
		h[3] = m1 && m2 ? std::min(y[2], kPi) : 0;
	};
	auto project = [&](double *y) {
		double l[4], h[4];
		for (int a = 0; a < 3; a++) {
			bounds(y, l, h);
			y[a] = std::min(h[a], std::max(l[a], y[a]));
		}
		bounds(y, l, h);
		y[3] = std::min(h[3], std::max(l[3], y[3]));
	};
	const double unit[4] = {kFlightStep, kFlightStep, 1, 1};
	double y[4] = {start.x[0], start.x[1], flight_turn(start.x, s1, s2), std::fabs(wrap(start.x[2]))};
	project(y);
	p.g = damped_newton(y, unit, eval, bounds, project, tolerance);
	to_x(y, p.x);
	return p;
}

// M(k, turn cell j, s1, s2): the least predicted cost over distance cell k,
// every climb within the training ball and every pair of level velocity
// directions whose turn lies in cell j. The same 24 x 24 direction grid at
// every distance end and climb 0.5 m apart gives each cell's grid minima;
// from the best distinct ones (within 5%, at most 4) and from the two
// neighbouring turn cells' minima, newton_on_turn, with each velocity
// turned to either side, finds the cell's least cost. Cells no edge of the speeds reaches (a turn
// beyond pi with one speed zero, any turn but 0 with both) get the least
// value of their distance cell and speeds, a bound of every such edge.
Estimate flight_turn_estimate(const Geometry &g, const Geometry &gt, const hylo_svr_model &m, const EnvelopeOptions &opt)
{
	const int jobs = opt.jobs;
	constexpr int kTurnDirections = 24;
	constexpr double kClimbStep = 0.5;
	const FlightKernel K(m);
	Eigen::MatrixXd A, B;
	const DirectionGrid dg = direction_grid(g, K, kTurnDirections, A, B);
	const Eigen::Index nsv = static_cast<Eigen::Index>(K.n_sv());
	const uint32_t n_d = g.t.n_d, n_t = gt.t.n_z, np = g.pairs();
	const int n_climbs = 2 * static_cast<int>(std::ceil(g.max_d / kClimbStep - 1e-9)) + 1;
	auto climb = [&](int r) { return (r - (n_climbs - 1) / 2) * kClimbStep; };
	// Per grid point (distance end q, climb r): the best grid point of each
	// speed pair and turn cell, [p * n_t + j].
	const size_t n_points = static_cast<size_t>(n_d + 1) * n_climbs;
	std::vector<std::vector<FlightPoint>> grid(n_points);
	auto t0 = Clock::now();
	parallel(n_points, jobs, [&](size_t c, size_t) {
		const uint32_t q = static_cast<uint32_t>(c / n_climbs);
		const double dh = g.d_end(q), dz = climb(static_cast<int>(c % n_climbs));
		if (std::fabs(dz) > climb_reach(g, q > 0 ? q - 1 : 0) + kClimbStep)
			return;
		Eigen::VectorXd w(nsv);
		K.weights(dh, dz, w.data());
		const Eigen::MatrixXd G = (A * w.asDiagonal()) * B.transpose();
		std::vector<FlightPoint> &out = grid[c];
		out.assign(static_cast<size_t>(np) * n_t, FlightPoint{INFINITY, {0, 0, 0, 0}});
		for (uint32_t p = 0; p < np; p++) {
			const uint32_t i1 = p / g.t.n_v, i2 = p % g.t.n_v;
			const double s1 = g.speed(i1), s2 = g.speed(i2);
			for (int a = 0; a < dg.count[i1]; a++)
				for (int b = 0; b < dg.count[i2]; b++) {
					const FlightPoint x{G(dg.first[i1] + a, dg.first[i2] + b),
							    {dh, dz, dg.psi[dg.first[i1] + a], dg.psi[dg.first[i2] + b]}};
					uint32_t first, last;
					turn_cells(gt, flight_turn(x.x, s1, s2), &first, &last);
					for (uint32_t j = first; j <= last; j++)
						if (x.g < out[p * n_t + j].g)
							out[p * n_t + j] = x;
				}
		}
	});
	if (opt.debug)
		std::fprintf(stderr, "envelope: turn table grid, %zu points in %.1f s\n", n_points, seconds_since(t0));
	t0 = Clock::now();
	std::vector<std::unique_ptr<Evaluator>> evs = evaluators(m, HYLO_MODE_FLIGHT, jobs);
	Estimate est;
	est.cost.assign(static_cast<size_t>(n_d) * n_t * np, 0.0);
	parallel(static_cast<size_t>(n_d) * np, jobs, [&](size_t cell, size_t w) {
		const uint32_t k = static_cast<uint32_t>(cell / np), p = static_cast<uint32_t>(cell % np);
		if (!g.needed(k, (g.t.n_z - 1) / 2))   // the climb-0 cell: within the ball
			return;
		const double s1 = g.speed(p / g.t.n_v), s2 = g.speed(p % g.t.n_v);
		const double reach = climb_reach(g, k);
		const double lo[2] = {g.d_end(k), -reach}, hi[2] = {g.d_end(k + 1), reach};
		Evaluator &ev = *evs[w];
		ev.clear();
		std::vector<uint32_t> found;
		double tail[6], head[6];
		// Every side each velocity may turn to (a C or an S): the band's edge
		// cuts the start's basin, so its signs need not be the best.
		auto search = [&](const FlightPoint &s, uint32_t j, FlightPoint &best) {
			for (double sigma1 : {1.0, -1.0})
				for (double sigma2 : {1.0, -1.0}) {
					if ((sigma1 < 0 && s1 == 0) || (sigma2 < 0 && s2 == 0))
						continue;
					FlightPoint r = newton_on_turn(K, s1, s2, sigma1, sigma2, s, lo, hi, turn_lo(gt, j),
								       turn_hi(gt, j), 1e-8);
					if (r.g < best.g)
						best = r;
				}
		};
		std::vector<FlightPoint> best(n_t);
		for (uint32_t j = 0; j < n_t; j++) {
			std::vector<FlightPoint> starts;
			for (uint32_t q = k; q <= k + 1; q++)
				for (int r = 0; r < n_climbs; r++) {
					const auto &pt = grid[static_cast<size_t>(q) * n_climbs + r];
					if (!pt.empty() && std::isfinite(pt[p * n_t + j].g) &&
					    std::fabs(pt[p * n_t + j].x[1]) <= reach + kClimbStep)
						starts.push_back(pt[p * n_t + j]);
				}
			std::stable_sort(starts.begin(), starts.end(),
					 [](const FlightPoint &a, const FlightPoint &b) { return a.g < b.g; });
			std::vector<FlightPoint> distinct;
			for (const FlightPoint &s : starts) {
				bool seen = false;
				for (const FlightPoint &o : distinct)
					seen |= angle_apart(s.x[2], o.x[2]) < 0.05 && angle_apart(s.x[3], o.x[3]) < 0.05 &&
						std::fabs(s.x[1] - o.x[1]) < 1;
				if (!seen && distinct.size() < kTurnStarts &&
				    K.cost(s.g) <= K.cost(starts[0].g) * (1 + kTurnStartTolerance))
					distinct.push_back(s);
			}
			best[j].g = INFINITY;
			for (const FlightPoint &s : distinct)
				search(s, j, best[j]);
		}
		// The neighbouring turn cells' minima as starts too (a basin the
		// grid saw only in the next cell).
		for (uint32_t j = 0; j < n_t; j++) {
			FlightPoint b = best[j];
			for (uint32_t nb : {j - 1, j + 1})
				if (nb < n_t && std::isfinite(best[nb].g))
					search(best[nb], j, b);
			best[j] = b;
		}
		for (uint32_t j = 0; j < n_t; j++) {
			if (!std::isfinite(best[j].g))
				continue;
			flight_edge(best[j].x, s1, s2, tail, head);
			ev.add(tail, head);
			found.push_back(j);
		}
		if (found.empty())
			return;
		const std::vector<double> &cost = ev.run();
		double least = INFINITY;
		for (size_t f = 0; f < found.size(); f++) {
			est.cost[gt.index(k, found[f], p)] = cost[f];
			least = std::min(least, cost[f]);
		}
		for (uint32_t j = 0; j < n_t; j++)
			if (std::find(found.begin(), found.end(), j) == found.end())
				est.cost[gt.index(k, j, p)] = least;
	});
	if (opt.debug)
		std::fprintf(stderr, "envelope: turn table, %u cells in %.1f s\n", n_d * n_t, seconds_since(t0));
	return est;
}

// ---------------------------------------------------------------- random edges

// SplitMix64 from (seed, edge index): an edge does not depend on the others.
class Rng {
public:
	Rng(uint64_t seed, uint64_t index) : s_(seed * 0x9e3779b97f4a7c15ULL ^ (index + 1) * 0xd1b54a32d192ed03ULL) {}
	uint64_t next()
	{
		uint64_t z = (s_ += 0x9e3779b97f4a7c15ULL);
		z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
		z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
		return z ^ (z >> 31);
	}
	double uniform(double lo, double hi) { return lo + (hi - lo) * static_cast<double>(next() >> 11) * 0x1.0p-53; }
	uint32_t below(uint32_t n) { return static_cast<uint32_t>(next() % n); }

private:
	uint64_t s_;
};

// Edge `index` of stream `seed`: a random position and heading(s), the
// distance uniform in [0, max_d] (flight: the horizontal distance and climb
// uniform over the half-disc of radius max_d), every angle uniform, speeds
// on the nodes.
void random_edge(const Geometry &g, hylo_mode mode, uint64_t seed, uint64_t index, double *tail,
		 double *head)
{
	Rng r(seed, index);
	const double s1 = g.speed(r.below(g.t.n_v)), s2 = g.speed(r.below(g.t.n_v));
	if (mode == HYLO_MODE_FLIGHT) {
		double dh, dz;
		do {
			dh = r.uniform(0, g.max_d);
			dz = r.uniform(-g.max_d, g.max_d);
		} while (dh * dh + dz * dz > g.max_d * g.max_d);
		const double phi = r.uniform(-kPi, kPi), a1 = r.uniform(-kPi, kPi), a2 = r.uniform(-kPi, kPi);
		for (int k = 0; k < 3; k++)
			tail[k] = r.uniform(-20, 20);
		tail[3] = s1 * std::cos(a1);
		tail[4] = s1 * std::sin(a1);
		tail[5] = 0;
		head[0] = tail[0] + dh * std::cos(phi);
		head[1] = tail[1] + dh * std::sin(phi);
		head[2] = tail[2] + dz;
		head[3] = s2 * std::cos(a2);
		head[4] = s2 * std::sin(a2);
		head[5] = 0;
		return;
	}
	const double d = r.uniform(0, g.max_d), bearing = r.uniform(-kPi, kPi);
	tail[0] = r.uniform(-20, 20);
	tail[1] = r.uniform(-20, 20);
	tail[2] = s1;
	tail[3] = r.uniform(-kPi, kPi);
	head[0] = tail[0] + d * std::cos(tail[3] + bearing);
	head[1] = tail[1] + d * std::sin(tail[3] + bearing);
	head[2] = s2;
	head[3] = r.uniform(-kPi, kPi);
}

struct Comparison {
	double worst_excess = 0;    // largest (table - cost) / cost
	size_t below = 0;           // edges with cost < table
	double closest = INFINITY;  // least (cost - table) / cost
};

// The bound table gives an edge through the onboard lookup: the envelope's
// (hylo_envelope_of_edge) or the turn table's (hylo_svr_turn_envelope_bound
// at hylo_envelope_flight_turn), on a copy of m carrying only that table.
double table_bound(const hylo_svr_model &with, hylo_mode mode, bool turn_table, const double *tail,
		   const double *head)
{
	if (!turn_table)
		return hylo_envelope_of_edge(&with, mode, tail, head);
	double a[4], turn;
	if (!hylo_envelope_args(mode, tail, head, a) || !hylo_envelope_flight_turn(tail, head, &turn))
		return 0;
	return hylo_svr_turn_envelope_bound(&with, a[0], a[1], turn, a[2], a[3]);
}

// n random edges of stream seed against the table (g's layout; turn_table:
// the flight turn table).
Comparison compare(const Geometry &g, const hylo_svr_model &m, hylo_mode mode, const std::vector<float> &table,
		   bool turn_table, uint64_t seed, size_t n, const EnvelopeOptions &opt)
{
	const int jobs = opt.jobs;
	EnvelopeExport t = g.t;
	hylo_svr_envelope env{t.n_d, t.n_z, t.n_v, t.d_step, t.z_min, t.z_step, t.v_min, t.v_step, table.data()};
	hylo_svr_model with = m;
	with.envelope = turn_table ? nullptr : &env;
	with.turn_envelope = turn_table ? &env : nullptr;
	const size_t chunks = (n + kEdgesPerChunk - 1) / kEdgesPerChunk;
	std::vector<Comparison> part(chunks);
	std::vector<std::unique_ptr<Evaluator>> evs = evaluators(m, mode, jobs);
	parallel(chunks, jobs, [&](size_t c, size_t w) {
		Evaluator &ev = *evs[w];
		ev.clear();
		const size_t begin = c * kEdgesPerChunk, end = std::min(n, begin + kEdgesPerChunk);
		std::vector<double> bound;
		double tail[HYLO_XS_DIM], head[HYLO_XS_DIM];
		for (size_t e = begin; e < end; e++) {
			random_edge(g, mode, seed, e, tail, head);
			ev.add(tail, head);
			bound.push_back(table_bound(with, mode, turn_table, tail, head));
		}
		const std::vector<double> &cost = ev.run();
		Comparison &r = part[c];
		for (size_t e = 0; e < cost.size(); e++) {
			double rel = (cost[e] - bound[e]) / cost[e];
			r.closest = std::min(r.closest, rel);
			if (cost[e] < bound[e]) {
				r.below++;
				r.worst_excess = std::max(r.worst_excess, -rel);
				if (opt.debug) {
					double tail[HYLO_XS_DIM], head[HYLO_XS_DIM], a[4];
					random_edge(g, mode, seed, begin + e, tail, head);
					hylo_envelope_args(mode, tail, head, a);
					std::fprintf(stderr, "envelope: edge %zu of seed %llu: args %.6g %.6g %.6g %.6g, "
						     "cost %.9g below the table's %.9g\n", begin + e,
						     static_cast<unsigned long long>(seed), a[0], a[1], a[2], a[3],
						     cost[e], bound[e]);
				}
			}
		}
	});
	Comparison all;
	for (const Comparison &r : part) {
		all.worst_excess = std::max(all.worst_excess, r.worst_excess);
		all.below += r.below;
		all.closest = std::min(all.closest, r.closest);
	}
	return all;
}

// v as a float no greater than v (and not below 0).
float round_down(double v)
{
	if (!(v > 0))
		return 0;
	float f = static_cast<float>(v);
	if (static_cast<double>(f) > v)
		f = std::nextafter(f, -INFINITY);
	return f;
}

// x rounded up to two significant digits.
double two_digits_up(double x)
{
	double unit = std::pow(10.0, std::floor(std::log10(x)) - 1);
	return std::ceil(x / unit * (1 - 1e-12)) * unit;
}

std::string short_number(double v)
{
	char buf[32];
	std::snprintf(buf, sizeof buf, "%.2g", v);
	return buf;
}

}  // namespace

std::string EnvelopeReport::provenance() const
{
	return std::to_string(table.n_d) + " x " + std::to_string(table.n_z) + " x " + std::to_string(table.n_v) +
	       " cells, margin " + short_number(margin) + ", worst sampled shortfall " +
	       short_number(worst_shortfall) + " (" + std::to_string(shortfall_edges) + " of " +
	       std::to_string(sampled) + " random edges; " + std::to_string(check_violations) + " of " +
	       std::to_string(sampled) + " fresh ones below the table)";
}

bool envelope_applies(const SvrExport &m)
{
	return envelope_mode(m.mode) != HYLO_MODE_NONE && m.max_distance_m > 0 && m.speed_max_mps > m.speed_min_mps;
}

double envelope_speed_step(double lo, double hi)
{
	for (double step : {0.1, 0.25, 0.5, 1.0, 2.5, 5.0}) {
		double n = (hi - lo) / step;
		if (n <= 12 + 1e-9 && std::fabs(n - std::round(n)) < 1e-9 && std::round(n) >= 1)
			return step;
	}
	throw std::invalid_argument("envelope: no speed step of 0.1, 0.25, 0.5, 1, 2.5 or 5 m/s divides [" +
				    format_double(lo) + ", " + format_double(hi) + "] m/s into at most 12 steps");
}

namespace {

// The model compute_envelope and compute_turn_table work on: m without its
// tables, checked.
hylo_svr_model bare_view(const SvrExport &m, SvrExport &bare)
{
	if (!envelope_applies(m))
		throw std::invalid_argument("envelope: the " + m.robot + " " + hylo_mode_str(m.mode) +
					    " model gets none (ground, marine and flight models with a "
					    "training distance and speed range only)");
	bare = m;
	bare.envelope.reset();
	bare.turn_envelope.reset();
	const hylo_svr_model view = model_view(bare, "envelope");
	hylo_reason why;
	if (hylo_svr_check(&view, &why) != HYLO_OK)
		throw std::invalid_argument(std::string("envelope: ") + why.text);
	return view;
}

// The margin measured on opt.check_edges random edges, the table with it,
// and its check on as many fresh ones, into rep (what: the table's name in
// messages).
void finish_table(const Geometry &g, const hylo_svr_model &view, const SvrExport &m, const Estimate &est,
		  bool turn_table, const EnvelopeOptions &opt, const char *what, EnvelopeReport &rep)
{
	const hylo_mode mode = envelope_mode(m.mode);
	rep.sampled = opt.check_edges;
	if (opt.progress)
		std::printf("%s %s %s: %u x %u x %u cells x %u speed pairs in %.1f s\n", what, m.robot.c_str(),
			    hylo_mode_str(m.mode), g.t.n_d, g.t.n_z, g.t.n_v, g.pairs(), rep.table_seconds);
	auto t0 = Clock::now();
	std::vector<float> before(est.cost.size());
	for (size_t i = 0; i < before.size(); i++)
		before[i] = round_down(est.cost[i]);
	const Comparison measured = compare(g, view, mode, before, turn_table, opt.margin_seed, opt.check_edges, opt);
	rep.worst_shortfall = measured.worst_excess;
	rep.shortfall_edges = measured.below;
	rep.margin = two_digits_up(std::max(opt.min_margin, 2 * measured.worst_excess));
	rep.margin_seconds = seconds_since(t0);

	// A fresh sample can still find an edge below the table (a narrow
	// kernel's dips between the cells' estimates): the margin then grows to
	// twice that edge's whole shortfall and is checked on other fresh edges,
	// a few times at most (docs/decisions.md, "The kernel width at full
	// density").
	t0 = Clock::now();
	Comparison check;
	for (int attempt = 0;; attempt++) {
		rep.table = g.t;
		rep.table.value.resize(est.cost.size());
		for (size_t i = 0; i < est.cost.size(); i++)
			rep.table.value[i] = round_down(est.cost[i] * (1 - rep.margin));
		check = compare(g, view, mode, rep.table.value, turn_table, opt.check_seed + static_cast<uint64_t>(attempt),
				opt.check_edges, opt);
		if (check.below == 0 || attempt + 1 >= opt.check_rounds)
			break;
		if (opt.progress)
			std::printf("%s %s %s: %zu of %zu fresh edges below the table with margin %s (by up to %.3g)\n",
				    what, m.robot.c_str(), hylo_mode_str(m.mode), check.below, opt.check_edges,
				    short_number(rep.margin).c_str(), check.worst_excess);
		rep.margin = two_digits_up(2 * (rep.margin + check.worst_excess));
	}
	rep.check_violations = check.below;
	rep.check_closest = check.closest;
	rep.check_seconds = seconds_since(t0);
	if (opt.progress)
		std::printf("%s %s %s: worst shortfall %.3g (%zu of %zu edges) -> margin %s (%.1f s); "
			    "check: %zu of %zu fresh edges below the table, closest %.3g (%.1f s)\n",
			    what, m.robot.c_str(), hylo_mode_str(m.mode), rep.worst_shortfall, rep.shortfall_edges,
			    opt.check_edges, short_number(rep.margin).c_str(), rep.margin_seconds,
			    rep.check_violations, opt.check_edges, rep.check_closest, rep.check_seconds);
	if (rep.check_violations > 0)
		throw std::runtime_error(std::string(what) + ": " + std::to_string(rep.check_violations) + " of " +
					 std::to_string(opt.check_edges) + " fresh random edges cost less than the " +
					 m.robot + " " + hylo_mode_str(m.mode) + " table with margin " + short_number(rep.margin) +
					 " (by up to " + short_number(check.worst_excess) + " relative)");
}

}  // namespace

EnvelopeReport compute_envelope(const SvrExport &m, const EnvelopeOptions &opt)
{
	SvrExport bare;
	const hylo_svr_model view = bare_view(m, bare);
	const Geometry g = geometry(bare);
	EnvelopeReport rep;
	auto t0 = Clock::now();
	const Estimate est = g.flight ? flight_estimate(g, view, opt)
				      : planar_estimate(g, view, envelope_mode(m.mode), opt);
	rep.table_seconds = seconds_since(t0);
	finish_table(g, view, bare, est, false, opt, "envelope", rep);
	return rep;
}

bool turn_table_applies(const SvrExport &m)
{
	const hylo_feature_layout *layout = hylo_mode_layout(m.mode);
	return envelope_applies(m) && layout && layout->kind == HYLO_LAYOUT_SPATIAL;
}

EnvelopeReport compute_turn_table(const SvrExport &m, const EnvelopeOptions &opt)
{
	if (!turn_table_applies(m))
		throw std::invalid_argument("turn table: the " + m.robot + " " + hylo_mode_str(m.mode) +
					    " model gets none (flight models with a training distance and "
					    "speed range only)");
	SvrExport bare;
	const hylo_svr_model view = bare_view(m, bare);
	const Geometry g = geometry(bare), gt = turn_geometry(g);
	EnvelopeReport rep;
	auto t0 = Clock::now();
	const Estimate est = flight_turn_estimate(g, gt, view, opt);
	rep.table_seconds = seconds_since(t0);
	finish_table(gt, view, bare, est, true, opt, "turn table", rep);
	return rep;
}

}  // namespace hylo::trainer
