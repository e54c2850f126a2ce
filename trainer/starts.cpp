#include "trainer/starts.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace hylo::trainer {
namespace internal {
namespace {

constexpr double kPi = 3.14159265358979323846;

double clamp_duration(const Bounds &bd, double T)
{
	return std::min(std::max(T, bd.T_min), bd.T_max);
}

// x equals y component by component to 1e-9 relative (absolute below 1).
bool same_state(const std::vector<double> &x, const std::vector<double> &y)
{
	for (size_t k = 0; k < x.size(); k++)
		if (std::fabs(x[k] - y[k]) > 1e-9 * std::max(1.0, std::fabs(y[k])))
			return false;
	return true;
}

}  // namespace

double duration_guess(const Bounds &bd, double typical_speed, double length)
{
	return std::max(bd.T_min * 2, length / typical_speed);
}

std::vector<Start> line_starts(const Bounds &bd, const std::vector<double> &T_guesses, double duration)
{
	std::vector<double> Ts = T_guesses;
	if (Ts.empty())
		Ts = {duration, 2 * duration, 0.5 * duration + bd.T_min};
	std::vector<Start> starts;
	for (double T : Ts)
		starts.push_back({{clamp_duration(bd, T)}, {}});
	return starts;
}

std::vector<Start> guess_starts(const Bounds &bd, const std::vector<Guess> &guesses)
{
	std::vector<Start> starts;
	for (const Guess &g : guesses)
		starts.push_back({{clamp_duration(bd, g.T)}, g.path});
	return starts;
}

void check_guesses(hylo_mode mode, const std::vector<Guess> &guesses, const std::vector<double> &a,
		   const std::vector<double> &b)
{
	for (size_t g = 0; g < guesses.size(); g++) {
		const auto &path = guesses[g].path;
		std::string where = "guess " + std::to_string(g) + " of a " + hylo_mode_str(mode) + " BVP: ";
		if (path.size() < 2)
			throw std::invalid_argument(where + "its path needs at least two states");
		for (const auto &x : path)
			if (x.size() != a.size())
				throw std::invalid_argument(where + "a state has " + std::to_string(x.size()) +
							    " components, the mode has " + std::to_string(a.size()));
		if (!same_state(path.front(), a) || !same_state(path.back(), b))
			throw std::invalid_argument(where + "its path does not run from the BVP's start to its goal");
		if (!(guesses[g].T > 0) || !std::isfinite(guesses[g].T))
			throw std::invalid_argument(where + "its duration is not positive");
	}
}

std::vector<Start> scaled_starts(const std::vector<Bounds> &bounds, const std::vector<double> &T_guesses,
				 const std::vector<double> &scales)
{
	std::vector<Start> starts;
	for (double f : scales) {
		Start st;
		for (size_t k = 0; k < T_guesses.size(); k++)
			st.T.push_back(clamp_duration(bounds[k], f * T_guesses[k]));
		// Scales that clamp to the same durations are the same start: it
		// would reach the same solution again (a long ground drift clamped
		// to the mode's longest duration at 1x and 2x took 166 s twice).
		if (std::none_of(starts.begin(), starts.end(), [&](const Start &s) { return s.T == st.T; }))
			starts.push_back(st);
	}
	return starts;
}

// From each start Ipopt stays in the basin it starts in, so a basin no start
// leads into is never found:
// - backing up with the start's heading, through the midpoint, and driving
//   forward facing the goal (from the straight line alone, goals behind the
//   robot often ended in a worse local optimum; docs/decisions.md, "Training
//   labels"); durations from the path length;
// - (issue #35) backing up with the start's heading at twice that duration;
//   reversing towards the goal, the rear facing it, through the midpoint;
//   and turning on the spot to that heading, reversing, turning on the spot
//   to the goal's heading. Their headings are wound to the nearest the mean
//   of the start's and the goal's (theta is not wrapped: the goal's is
//   reached as given). Durations add the turns at 2 rad/s (through the
//   midpoint) or 1 rad/s (on the spot). On the first 12 Ambot ground
//   samples these three found basins 25% (sample 0, 131 -> 98 J) and 23%
//   (sample 10, 144 -> 111 J) below every other start's (docs/decisions.md).
// vy = omega = 0 at the points; marine's paddle speeds at their steady value
// for v.
std::vector<Guess> planar_strategy_guesses(
	const std::vector<double> &a, const std::vector<double> &b, const Bounds &bd, double speed,
	const std::function<std::vector<double>(double, double, double, double)> &point)
{
	std::vector<double> mid = a;
	mid[0] = 0.5 * (a[0] + b[0]);
	mid[1] = 0.5 * (a[1] + b[1]);
	mid[3] = mid[5] = 0;
	std::vector<double> back = mid, face = mid;
	back[2] = std::max(-speed, bd.x_lo[2]);
	face[2] = std::min(speed, bd.x_hi[2]);
	double bearing = std::atan2(b[1] - a[1], b[0] - a[0]);
	face[4] = a[4] + std::remainder(bearing - a[4], 2 * kPi);
	const double d = std::hypot(b[0] - a[0], b[1] - a[1]);
	const double T = duration_guess(bd, speed, d);   // of a path through the midpoint (its length is d)
	std::vector<Guess> out = {{T, {a, back, b}}, {T, {a, face, b}}};
	out.push_back({2 * T, {a, back, b}});
	const double mean = 0.5 * (a[4] + b[4]);
	const double h = mean + std::remainder(bearing + kPi - mean, 2 * kPi);
	const double turn = std::fabs(h - a[4]) + std::fabs(b[4] - h);
	const double rev = std::max(-speed, bd.x_lo[2]);
	out.push_back({T + 0.5 * turn, {a, point(mid[0], mid[1], rev, h), b}});
	out.push_back({T + turn,
		       {a, point(a[0], a[1], 0, h), point(mid[0], mid[1], rev, h), point(b[0], b[1], 0, h), b}});
	for (Guess &g : out)
		g.T = std::min(g.T, bd.T_max);
	return out;
}

}  // namespace internal

namespace {

// The trajectory's state component k at time t, linear between its samples
// (clamped to its ends).
double state_at(const Trajectory &traj, double t, size_t k)
{
	const size_t nx = static_cast<size_t>(traj.nx), n = traj.t.size();
	size_t i = static_cast<size_t>(std::upper_bound(traj.t.begin(), traj.t.end(), t) - traj.t.begin());
	i = std::min(std::max<size_t>(i, 1), n - 1);
	double ta = traj.t[i - 1], tb = traj.t[i], w = tb > ta ? (t - ta) / (tb - ta) : 0;
	w = std::min(std::max(w, 0.0), 1.0);
	return traj.x[(i - 1) * nx + k] + w * (traj.x[i * nx + k] - traj.x[(i - 1) * nx + k]);
}

}  // namespace

Guess transplanted_guess(const Trajectory &traj, double T, const std::vector<double> &a,
			 const std::vector<double> &b, int points)
{
	const size_t nx = static_cast<size_t>(traj.nx), n = traj.t.size();
	if (points < 2 || n < 2 || a.size() != nx || b.size() != nx || traj.x.size() != n * nx)
		throw std::invalid_argument("transplanted_guess: a trajectory of " + std::to_string(n) +
					    " times and states of " + std::to_string(traj.nx) + " for boundary states of " +
					    std::to_string(a.size()) + " and " + std::to_string(b.size()) + ", " +
					    std::to_string(points) + " points");
	const double t0 = traj.t.front(), t1 = traj.t.back();
	Guess g;
	g.T = T;
	for (int p = 0; p < points; p++) {
		double s = static_cast<double>(p) / (points - 1);
		std::vector<double> x(nx);
		for (size_t k = 0; k < nx; k++)
			x[k] = state_at(traj, t0 + s * (t1 - t0), k) + (1 - s) * (a[k] - traj.x[k]) +
			       s * (b[k] - traj.x[(n - 1) * nx + k]);
		g.path.push_back(std::move(x));
	}
	g.path.front() = a;   // exactly, not to rounding
	g.path.back() = b;
	return g;
}

}  // namespace hylo::trainer
