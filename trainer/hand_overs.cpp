#include "trainer/hand_overs.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace hylo::trainer::internal {
namespace {

// A piece's least duration: the mode's least duration bounds the whole
// phase, and a piece of a short phase lasts less.
constexpr double kPieceTMinS = 1e-3;
// A piece spans at least this many of the phase's segments: a shorter one
// stays in its neighbour's piece, whose boxes keep their windows. Pieces of
// any length made a generated Drivocopter scene 4.7 times slower
// (continuation steps of 45-1,000 Ipopt iterations instead of 11-13;
// docs/decisions.md, "Free hand-overs").
constexpr double kLeastSegments = 4;

// The normalized times of s's guess states (uniform when it has none).
std::vector<double> guess_times(const PhaseSetup &s)
{
	if (!s.guess_at.empty())
		return s.guess_at;
	const size_t n = s.guess.size();
	std::vector<double> at(n);
	for (size_t i = 0; i < n; i++)
		at[i] = static_cast<double>(i) / static_cast<double>(n - 1);
	return at;
}

// The guess state at normalized time t, linear between the states around it.
std::vector<double> guess_state(const PhaseSetup &s, const std::vector<double> &at, double t)
{
	size_t w = 0;
	while (w + 2 < at.size() && at[w + 1] <= t)
		w++;
	const double span = at[w + 1] - at[w];
	const double f = span > 0 ? std::clamp((t - at[w]) / span, 0.0, 1.0) : 0.0;
	std::vector<double> x(s.guess[w].size());
	for (size_t k = 0; k < x.size(); k++)
		x[k] = s.guess[w][k] + f * (s.guess[w + 1][k] - s.guess[w][k]);
	return x;
}

// The hand-over times: in the middle of the overlap of each two consecutive
// boxes' windows, kept increasing and inside (0, 1); box index after which
// each comes.
std::vector<std::pair<double, size_t>> hand_overs(const std::vector<CorridorBox> &boxes, int segments)
{
	const double least = kLeastSegments / std::max(1, segments);
	std::vector<std::pair<double, size_t>> cuts;
	for (size_t j = 0; j + 1 < boxes.size(); j++) {
		const CorridorBox &a = boxes[j], &b = boxes[j + 1];
		if (a.tau1 < b.tau0)
			continue;   // a stretch without either box: no knot to hand over at
		const double c = 0.5 * (b.tau0 + a.tau1);
		const double after = cuts.empty() ? 0.0 : cuts.back().first;
		if (c >= after + least && c <= 1 - least)
			cuts.push_back({c, j});
	}
	return cuts;
}

// The piece of s over normalized times [a, b] with boxes first..last.
PhaseSetup piece(const PhaseSetup &s, const ModeInfo &info, const std::vector<double> &at, double a, double b,
		 size_t first, size_t last)
{
	PhaseSetup p = s;
	const double share = b - a;
	p.guess = {guess_state(s, at, a)};
	p.guess_at = {0.0};
	for (size_t i = 0; i < at.size(); i++)
		if (at[i] > a && at[i] < b) {
			p.guess.push_back(s.guess[i]);
			p.guess_at.push_back((at[i] - a) / share);
		}
	p.guess.push_back(guess_state(s, at, b));
	p.guess_at.push_back(1.0);
	p.T_guess = s.T_guess * share;
	p.T_min = kPieceTMinS;
	p.segments = std::max(1, static_cast<int>(std::lround(s.segments * share)));
	p.mesh_share = s.mesh_share * share;
	p.corridor.assign(s.corridor.begin() + static_cast<std::ptrdiff_t>(first),
			  s.corridor.begin() + static_cast<std::ptrdiff_t>(last) + 1);
	for (CorridorBox &box : p.corridor) {
		box.tau0 = std::clamp((box.tau0 - a) / share, 0.0, 1.0);
		box.tau1 = std::clamp((box.tau1 - a) / share, 0.0, 1.0);
	}
	if (a > 0) {
		p.first_lo = info.bounds.x_lo;
		p.first_hi = info.bounds.x_hi;
		p.inset_first = true;
	}
	if (b < 1) {
		p.last_lo = info.bounds.x_lo;
		p.last_hi = info.bounds.x_hi;
		p.inset_last = true;
	}
	return p;
}

void append(Trajectory &to, const Trajectory &from, double t0)
{
	const size_t nx = static_cast<size_t>(from.nx), nu = static_cast<size_t>(from.nu);
	for (size_t i = to.t.empty() ? 0 : 1; i < from.t.size(); i++) {   // the shared knot once
		to.t.push_back(t0 + from.t[i]);
		to.x.insert(to.x.end(), from.x.begin() + static_cast<std::ptrdiff_t>(i * nx),
			    from.x.begin() + static_cast<std::ptrdiff_t>((i + 1) * nx));
		to.u.insert(to.u.end(), from.u.begin() + static_cast<std::ptrdiff_t>(i * nu),
			    from.u.begin() + static_cast<std::ptrdiff_t>((i + 1) * nu));
	}
}

}  // namespace

std::vector<PhaseSetup> hand_over_pieces(const PhaseSetup &s, const ModeInfo &info)
{
	const std::vector<std::pair<double, size_t>> cuts = s.T_fixed > 0 ? decltype(cuts){} : hand_overs(s.corridor, s.segments);
	if (cuts.empty())
		return {s};
	const std::vector<double> at = guess_times(s);
	std::vector<PhaseSetup> pieces;
	double a = 0;
	size_t first = 0;
	for (const auto &[c, j] : cuts) {
		pieces.push_back(piece(s, info, at, a, c, first, j));
		a = c;
		first = j + 1;
	}
	pieces.push_back(piece(s, info, at, a, 1.0, first, s.corridor.size() - 1));
	return pieces;
}

MultiPhaseSolution joined_pieces(MultiPhaseSolution pieces, const std::vector<size_t> &owner)
{
	if (owner.empty() || owner.back() + 1 == owner.size())
		return pieces;   // one piece per phase
	MultiPhaseSolution out = std::move(pieces);
	std::vector<Solution> phases;
	std::vector<hylo_mode> modes;
	for (size_t k = 0; k < out.phases.size() && k < owner.size(); k++) {
		Solution &p = out.phases[k];
		if (k == 0 || owner[k] != owner[k - 1]) {
			phases.push_back(std::move(p));
			modes.push_back(out.modes[k]);
			continue;
		}
		Solution &ph = phases.back();
		append(ph.traj, p.traj, ph.T);
		ph.T += p.T;
		ph.cost += p.cost;
		ph.segments += p.segments;
		ph.replay_cost += p.replay_cost;
		ph.replayed = ph.replayed && p.replayed;
		if (ph.replay_ok && !p.replay_ok)
			ph.replay_check = p.replay_check;
		ph.replay_ok = ph.replay_ok && p.replay_ok;
		ph.replay_error = std::max(ph.replay_error, p.replay_error);
	}
	out.phases = std::move(phases);
	out.modes = std::move(modes);
	return out;
}

}  // namespace hylo::trainer::internal
