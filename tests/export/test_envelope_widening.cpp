// The envelope's widening loop (trainer/envelope.cpp, finish_table): when
// the margin measured on one sample of edges is too small for a fresh
// sample, one check round gives up with a clear error, and more rounds
// widen the margin until a fresh sample has no edge below the table. The
// model is a level cost of 10 J with 200 narrow dips of 3 J: the table's
// estimate finds most dips, and a sample of 1,000 random edges finds the
// odd one it missed. With these seeds the margin's sample (1) finds none
// and the first check's (9) finds one, 11% below the table; the second
// check's (10) finds none. Prints TAP.
#include <cstdio>
#include <stdexcept>
#include <string>

#include "hylo/features.h"
#include "tests/tap.hpp"
#include "trainer/envelope.hpp"
#include "trainer/svr_export.hpp"

using namespace hylo::trainer;

namespace {

SvrExport dips()
{
	constexpr int nf = HYLO_FEATURES_PLANAR;
	SvrExport m;
	m.robot = "testbot";
	m.mode = HYLO_MODE_GROUND;
	m.n_features = nf;
	m.gamma = 100;
	m.rho = -10;   // decision = sum - rho: 10 J away from every dip
	uint64_t s = 7;
	auto u = [&](double lo, double hi) {
		s = s * 6364136223846793005ULL + 1442695040888963407ULL;
		return lo + (hi - lo) * static_cast<double>(s >> 11) * 0x1.0p-53;
	};
	for (int i = 0; i < 200; i++) {
		double rel[HYLO_RELATIVE_PLANAR] = {u(-1, 1), u(-1, 1), u(-3.1, 3.1), u(0, 0.5), u(0, 0.5)};
		double x[nf];
		hylo_features_of_relative(HYLO_MODE_GROUND, rel, x);
		m.sv.insert(m.sv.end(), x, x + nf);
		m.coef.push_back(-3);
	}
	m.feature_offset.assign(nf, 0);
	m.feature_scale.assign(nf, 1);
	m.max_distance_m = 1;
	m.speed_max_mps = 0.5;
	return m;
}

}  // namespace

int main()
{
	const SvrExport m = dips();
	EnvelopeOptions o;
	o.check_edges = 1000;
	o.min_margin = 1e-6;
	o.margin_seed = 1;
	o.check_seed = 9;
	o.progress = false;

	o.check_rounds = 1;
	std::string error;
	try {
		EnvelopeReport r = compute_envelope(m, o);
		error = "no error: margin " + tap_num(r.margin, 3) + ", shortfall " + tap_num(r.worst_shortfall, 3);
	} catch (const std::runtime_error &e) {
		error = e.what();
	}
	check(error.find("1 of 1000 fresh random edges cost less than the testbot ground table with margin 1e-06") !=
		      std::string::npos,
	      "one check round: a margin too small for the fresh edges is an error naming the model, the edges "
	      "and the margin",
	      error);

	o.check_rounds = 3;
	try {
		const EnvelopeReport r = compute_envelope(m, o);
		std::printf("# margin %.3g (measured shortfall %.3g on %zu edges)\n", r.margin, r.worst_shortfall,
			    r.shortfall_edges);
		// The margin's own sample saw no shortfall: the margin is the
		// widened one, twice the first check's whole shortfall.
		check(r.worst_shortfall == 0 && r.margin > 0.2 && r.margin < 0.3 && r.check_violations == 0,
		      "three check rounds: the margin grows to twice the fresh edge's shortfall and the next fresh "
		      "sample has no edge below the table",
		      "margin " + tap_num(r.margin, 3) + ", " + std::to_string(r.check_violations) + " below");
	} catch (const std::exception &e) {
		check(false, "three check rounds: the margin grows to twice the fresh edge's shortfall and the next "
			     "fresh sample has no edge below the table", e.what());
	}
	return tap_finish();
}
