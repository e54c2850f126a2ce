// How training pairs are drawn (draw_pair, --draws): the committed
// datasets are their draws' streams, pair for pair; draw 2 puts
// each ground and marine speed at rest with probability kRestFraction and
// keeps every pair inside the trained region; draw 3 is draw 2 up to its
// supplement, then cruise pairs; the double integrator's draw 2 is draw 1,
// then short pairs; a dataset records its draw
// (draw 1 of ground and marine without a line, so the committed metas stay
// valid), a run adopts the draw of the dataset in its --out, and a draw a
// mode does not have is refused. No solves. Prints TAP.
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <unistd.h>
#include <vector>

#include "tests/tap.hpp"
#include "trainer/dataset.hpp"
#include "trainer/params.hpp"
#include "trainer/pipeline.hpp"

namespace {

using namespace hylo::trainer;
namespace fs = std::filesystem;
constexpr double kPi = 3.14159265358979323846;

bool refused(hylo_mode mode, int draws)
{
	try {
		draws_for(mode, draws);
	} catch (const std::invalid_argument &) {
		return true;
	}
	return false;
}

bool inside(const TrainedRegion &r, const double *x)
{
	for (unsigned k = 0; k < 6; k++)
		if ((r.bounded >> k & 1u) && (x[k] < r.min[k] || x[k] > r.max[k]))
			return false;
	return true;
}

struct Stream {
	std::string robot, mode;
	const ModeParams *params;
	int draw;
	uint64_t first_row;
};

// How many of the n pairs from first_row of the committed dataset are the
// draw's, to the bit; why names the first that is not.
int same_pairs(const Stream &s, uint64_t n, std::string &why)
{
	std::ifstream f("trainer/datasets/" + s.robot + "/" + s.mode + ".csv");
	std::string line;
	std::getline(f, line);
	const size_t x1 = csv_column(hylo_mode_parse(s.mode.c_str()), "x1_0");
	int same = 0;
	for (uint64_t i = 0; i < s.first_row + n && std::getline(f, line); i++) {
		if (i < s.first_row)
			continue;
		std::vector<std::string> c = csv_fields(line);
		double a[6] = {0}, b[6] = {0};
		draw_pair(*s.params, 1, i, a, b, s.draw);
		bool ok = c.size() > x1 + 7;
		for (int k = 0; ok && k < 4; k++)
			ok = std::strtod(c[x1 + k].c_str(), nullptr) == a[k] &&
			     std::strtod(c[x1 + 4 + k].c_str(), nullptr) == b[k];
		same += ok;
		if (!ok && why.empty())
			why = "row " + std::to_string(i) + ": " + line.substr(0, 120);
	}
	return same;
}

}  // namespace

int main()
{
	const RobotParams ambot = load_robot("trainer/params/ambot.yaml");

	// The committed datasets are their draws, pair for pair: Drivocopter
	// ground is draw 1; Ambot ground and marine are draw 4, checked at the
	// start and inside the cruise block.
	const RobotParams drivocopter = load_robot("trainer/params/drivocopter.yaml");
	const Stream streams[] = {
		{"drivocopter", "ground", &drivocopter.mode("ground"), 1, 0},
		{"ambot", "ground", &ambot.mode("ground"), 4, 0},
		{"ambot", "ground", &ambot.mode("ground"), 4, 5760},
		{"ambot", "marine", &ambot.mode("marine"), 4, 0},
	};
	for (const Stream &s : streams) {
		std::string why;
		const int same = same_pairs(s, 50, why);
		check(same == 50,
		      "draw " + std::to_string(s.draw) + " is the committed " + s.robot + " " + s.mode + " stream (50 pairs from row " +
			      std::to_string(s.first_row) + ", exactly)",
		      why);
	}

	// Draw 2: speeds at rest a fifth of the time, each end on its own; the
	// rest uniform as in draw 1; inside the trained region.
	for (const char *m : {"ground", "marine"}) {
		const ModeParams &p = ambot.mode(m);
		const TrainedRegion region = trained_region(p);
		const int n = 20000;
		int rest1 = 0, rest2 = 0, both = 0, out = 0, rest_d1 = 0;
		double sum = 0;
		int moving = 0;
		for (int i = 0; i < n; i++) {
			double a[6] = {0}, b[6] = {0};
			draw_pair(p, 1, static_cast<uint64_t>(i), a, b, 2);
			rest1 += a[2] == 0;
			rest2 += b[2] == 0;
			both += a[2] == 0 && b[2] == 0;
			out += !inside(region, a) || !inside(region, b) ||
			       std::hypot(b[0], b[1]) > p.sampling.max_distance_m;
			for (double v : {a[2], b[2]})
				if (v != 0)
					sum += v, moving++;
			draw_pair(p, 1, static_cast<uint64_t>(i), a, b, 1);
			rest_d1 += a[2] == 0 || b[2] == 0;
		}
		const double f1 = double(rest1) / n, f2 = double(rest2) / n, fb = double(both) / n;
		const double mean = sum / moving, want = 0.5 * (p.sampling.speed_min_mps + p.sampling.speed_max_mps);
		check(std::fabs(f1 - kRestFraction) < 0.01 && std::fabs(f2 - kRestFraction) < 0.01 &&
			      std::fabs(fb - kRestFraction * kRestFraction) < 0.005 && std::fabs(mean - want) < 0.01 * want,
		      std::string(m) + ", draw 2: each speed at rest with probability 0.2, independently, else uniform",
		      "at rest: start " + std::to_string(f1) + ", goal " + std::to_string(f2) + ", both " +
			      std::to_string(fb) + "; mean moving speed " + std::to_string(mean) + " (want " +
			      std::to_string(want) + ")");
		check(out == 0 && rest_d1 == 0,
		      std::string(m) + ": draw 2's pairs inside the trained region; draw 1 never at rest",
		      std::to_string(out) + " outside, " + std::to_string(rest_d1) + " at rest in draw 1");
	}

	// Draw 3: draw 2's pairs below its supplement, so a draw-2 dataset is
	// its prefix; cruise pairs from there on.
	for (const char *m : {"ground", "marine"}) {
		const ModeParams &p = ambot.mode(m);
		const uint64_t from = supplement(p.id, 3).from;
		const TrainedRegion region = trained_region(p);
		const double reach = p.sampling.max_distance_m, top = p.sampling.speed_max_mps;
		int differ = 0;
		for (uint64_t i = 0; i < 2000; i++) {
			double a2[6] = {0}, b2[6] = {0}, a3[6] = {0}, b3[6] = {0};
			const uint64_t k = from - 2000 + i;
			draw_pair(p, 1, k, a2, b2, 2);
			draw_pair(p, 1, k, a3, b3, 3);
			for (int j = 0; j < 6; j++)
				differ += a2[j] != a3[j] || b2[j] != b3[j];
		}
		const int n = 20000;
		int out = 0, off_arc = 0, on_arc = 0, rest = 0, at_top = 0, moving = 0;
		for (int i = 0; i < n; i++) {
			double a[6] = {0}, b[6] = {0};
			draw_pair(p, 1, from + static_cast<uint64_t>(i), a, b, 3);
			out += !inside(region, a) || !inside(region, b) || std::hypot(b[0], b[1]) > reach ||
			       a[0] != 0 || a[1] != 0 || a[3] != 0;
			const double bearing = std::atan2(b[1], b[0]);
			off_arc += std::fabs(bearing) > kPi / 4 + 1e-12 || std::fabs(b[3] - 2 * bearing) > 0.3 + 1e-12;
			on_arc += std::fabs(b[3] - 2 * bearing) < 1e-12;
			for (double v : {a[2], b[2]}) {
				rest += v == 0;
				at_top += v == top;
				moving += v != 0 && v != top;
			}
		}
		const double fr = rest / (2.0 * n), ft = at_top / (2.0 * n), fa = double(on_arc) / n;
		check(from == 11520 && supplement(p.id, 3).pairs == 2880 && supplement(p.id, 2).pairs == 0 && differ == 0 &&
			      out == 0 && off_arc == 0 && std::fabs(fa - 0.5) < 0.01 && std::fabs(fr - kRestFraction) < 0.01 &&
			      std::fabs(ft - kTopFraction) < 0.01 && moving > 0,
		      std::string(m) + ", draw 3: draw 2's 11,520 pairs, then 2,880 on arcs (bearing within pi/4, "
				       "the turn twice it, half exactly, else within 0.3 rad), speeds at rest 0.2, at the top 0.3",
		      std::to_string(differ) + " coordinates differ from draw 2, " + std::to_string(out) + " outside, " +
			      std::to_string(off_arc) + " off the arcs, " + std::to_string(fa) + " exactly on them; at rest " +
			      std::to_string(fr) + ", at the top " + std::to_string(ft));
	}

	// Draw 4: draw 2's pairs, the same pair for pair, but for a window of
	// cruise pairs (on arcs, as draw 3's, and not draw 2's pairs there).
	for (const char *m : {"ground", "marine"}) {
		const ModeParams &p = ambot.mode(m);
		const Supplement s4 = supplement(p.id, 4);
		int as_draw2 = 0, as_cruise = 0, off_arc = 0;
		auto same = [](const double *a, const double *b, const double *c, const double *d) {
			for (int j = 0; j < 6; j++)
				if (a[j] != c[j] || b[j] != d[j])
					return false;
			return true;
		};
		// Indices below, in and past the window.
		const uint64_t probes[] = {0, 1, 5759, 5760, 5761, 8639, 8640, 8641, 14399};
		for (uint64_t k : probes) {
			double a2[6] = {0}, b2[6] = {0}, a4[6] = {0}, b4[6] = {0};
			draw_pair(p, 1, k, a2, b2, 2);
			draw_pair(p, 1, k, a4, b4, 4);
			const bool inside = k >= 5760 && k < 8640;
			const double bearing = std::atan2(b4[1], b4[0]);
			const bool arc = std::fabs(bearing) <= kPi / 4 + 1e-12 && std::fabs(b4[3] - 2 * bearing) <= 0.3 + 1e-12;
			as_draw2 += !inside && same(a2, b2, a4, b4);
			as_cruise += inside && !same(a2, b2, a4, b4) && arc;
			off_arc += inside && !arc;
		}
		double a3[6] = {0}, b3[6] = {0}, a4[6] = {0}, b4[6] = {0};
		draw_pair(p, 1, 6000, a4, b4, 4);
		draw_pair(p, 1, 6000, a3, b3, 3);   // draw 3 at 6,000 is a draw-2 pair
		check(s4.from == 5760 && s4.pairs == 2880 && s4.closed && as_draw2 == 6 && as_cruise == 3 && off_arc == 0 &&
			      !same(a3, b3, a4, b4) && supplement(p.id, 3).from == 11520 && !supplement(p.id, 3).closed,
		      std::string(m) + ", draw 4: draw 2's pairs, but cruise pairs at rows 5,760-8,639 (default 8,640 rows)",
		      std::to_string(as_draw2) + " of 6 outside the window as draw 2, " + std::to_string(as_cruise) +
			      " of 3 inside on arcs, " + std::to_string(off_arc) + " off the arcs");
	}

	// The double integrator's draw 2: draw 1's 2,000 pairs, then short ones.
	{
		const RobotParams di = load_robot("trainer/params/di.yaml");
		for (const char *m : {"di_neg", "di_pos"}) {
			const ModeParams &p = di.mode(m);
			const TrainedRegion region = trained_region(p);
			const Supplement sup = supplement(p.id, 2);
			int differ = 0, out = 0, longer = 0, n = 20000;
			double sum = 0;
			for (uint64_t i = 0; i < 2000; i++) {
				double a1[6] = {0}, b1[6] = {0}, a2[6] = {0}, b2[6] = {0};
				draw_pair(p, 1, i, a1, b1, 1);
				draw_pair(p, 1, i, a2, b2, 2);
				differ += a1[0] != a2[0] || a1[1] != a2[1] || b1[0] != b2[0] || b1[1] != b2[1];
			}
			for (int i = 0; i < n; i++) {
				double a[6] = {0}, b[6] = {0};
				draw_pair(p, 1, sup.from + static_cast<uint64_t>(i), a, b, 2);
				const double d = std::hypot(b[0] - a[0], b[1] - a[1]);
				out += !inside(region, a) || !inside(region, b);
				longer += d > kShortPairMax;
				sum += d;
			}
			check(sup.from == 2000 && sup.pairs == 2000 && supplement(p.id, 1).pairs == 0 && differ == 0 && out == 0 &&
				      longer == 0 && sum / n < 0.3,
			      std::string(m) + ", draw 2: draw 1's 2,000 pairs, then 2,000 at most 0.5 apart, inside the region",
			      std::to_string(differ) + " differ from draw 1, " + std::to_string(out) + " outside, " +
				      std::to_string(longer) + " longer; mean distance " + std::to_string(sum / n));
		}
	}

	// Which draws a mode has.
	check(draws_for(HYLO_MODE_GROUND, 0) == 4 && draws_for(HYLO_MODE_MARINE, 1) == 1 &&
		      draws_for(HYLO_MODE_MARINE, 2) == 2 && draws_for(HYLO_MODE_MARINE, 3) == 3 &&
		      draws_for(HYLO_MODE_FLIGHT, 0) == 2 && draws_for(HYLO_MODE_DI_NEG, 0) == 2 &&
		      draws_for(HYLO_MODE_DI_POS, 1) == 1 && refused(HYLO_MODE_GROUND, 5) && refused(HYLO_MODE_FLIGHT, 1) &&
		      refused(HYLO_MODE_FLIGHT, 3) && refused(HYLO_MODE_DI_POS, 3),
	      "draws: ground and marine 1 to 4 (newest 4), flight 2, double integrator 1 or 2 (newest 2); others refused");

	// The meta: draw 2 recorded, draw 1 of ground without a line (as the
	// committed metas), flight's line as before.
	GenOptions o;
	o.mode = HYLO_MODE_GROUND;
	o.draws = 2;
	const std::string m2 = internal::meta_text(ambot, o);
	o.draws = 1;
	const std::string m1 = internal::meta_text(ambot, o);
	check(m2.find("\ndraws: 2\n") != std::string::npos && m1.find("draws:") == std::string::npos &&
		      !internal::same_stream(m1, m2),
	      "a ground dataset's meta says 'draws: 2'; draw 1 has no line; the two are other streams");

	// A run adopts the draw of the dataset in --out.
	char tmpl[] = "/tmp/hylo_test_draws_XXXXXX", tmpl2[] = "/tmp/hylo_test_draws_XXXXXX";
	const std::string dir = mkdtemp(tmpl);
	o.out_dir = dir;
	o.draws = 0;
	const int none = existing_draws(o);
	std::ofstream(dir + "/ground.csv.meta") << m1;
	const int one = existing_draws(o);
	std::ofstream(dir + "/ground.csv.meta") << m2;
	const int two = existing_draws(o);
	fs::remove_all(dir);
	check(none == 0 && one == 1 && two == 2,
	      "existing_draws: none without a dataset, 1 for a meta without a line, 2 for 'draws: 2'",
	      std::to_string(none) + " " + std::to_string(one) + " " + std::to_string(two));

	// Without --samples a run takes the draw's count, or the dataset's
	// whole rows when it holds more (an extended dataset is fitted whole).
	o.draws = 4;
	const std::string dir2 = mkdtemp(tmpl2);
	o.out_dir = dir2;
	const uint64_t empty = default_samples(o);
	auto write_rows = [&](uint64_t n) {
		std::ofstream f(dir2 + "/ground.csv");
		f << csv_join(csv_columns(HYLO_MODE_GROUND)) << "\n";
		for (uint64_t i = 0; i < n; i++)
			f << i << ",0\n";
		f << n << ",0";   // a torn row
	};
	write_rows(100);
	const uint64_t fewer = default_samples(o);
	write_rows(9000);
	const uint64_t more = default_samples(o);
	fs::remove_all(dir2);
	check(empty == 8640 && fewer == 8640 && more == 9000,
	      "default samples: the draw's 8,640 without a dataset or with 100 rows, 9,000 with 9,000 whole rows and a torn one",
	      std::to_string(empty) + " " + std::to_string(fewer) + " " + std::to_string(more));
	return tap_finish();
}
