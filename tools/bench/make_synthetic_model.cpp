// Writes the synthetic ground model used by the benchmarks: an RBF model with
// 2,000 support vectors over the 8 planar features, in the exported-header
// format, so that the benchmarks exercise the exact code path of a trained
// model without a long libsvm fit at build time.
//
// The model is a regularized kernel interpolation of a plausible energy
// function (cost grows with distance, turning and speed change):
//   c = 3 J/m * d * (1 + 0.3 |dtheta| / pi + 0.2 |vx2 - vx1|) + 0.5 J
// at 2,000 random relative coordinates (their features are the support
// vectors, hylo_features_of_relative), coefficients from
// (K + 1e-2 I) a = standardized c. Deterministic: fixed seed, own RNG.
//
// Usage: make_synthetic_model OUT.h
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <vector>

#include <Eigen/Dense>

#include "hylo/features.h"
#include "trainer/svr_export.hpp"

namespace {

constexpr int kSv = 2000, kR = HYLO_RELATIVE_PLANAR, kF = HYLO_FEATURES_PLANAR;
constexpr double kRadius = 10.0, kGamma = 0.3, kPi = 3.14159265358979323846;

struct SplitMix {
	uint64_t s;
	double uniform(double lo, double hi)
	{
		uint64_t z = (s += 0x9e3779b97f4a7c15ULL);
		z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
		z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
		z ^= z >> 31;
		return lo + (hi - lo) * static_cast<double>(z >> 11) * 0x1.0p-53;
	}
};

double true_cost(const double *f)
{
	double d = std::hypot(f[0], f[1]);
	return 3.0 * d * (1 + 0.3 * std::fabs(f[2]) / kPi + 0.2 * std::fabs(f[4] - f[3])) + 0.5;
}

}  // namespace

int main(int argc, char **argv)
{
	if (argc != 2 || argv[1][0] == '-') {  // --help is not a file name
		std::fprintf(stderr, "usage: %s OUT.h\n", argv[0]);
		return 2;
	}
	try {
		// Relative coordinates: displacement in a disc of kRadius, heading
		// change, speeds in [0, 1]; features standardized by their sample
		// mean and deviation.
		const double lo[kR] = {-kRadius, -kRadius, -kPi, 0, 0};
		const double hi[kR] = {kRadius, kRadius, kPi, 1, 1};
		hylo::trainer::SvrExport m;
		m.robot = "synthetic";
		m.mode = HYLO_MODE_GROUND;
		m.n_features = kF;
		SplitMix rng{20261122};
		std::vector<double> raw(kSv * kF), cost(kSv);
		for (int i = 0; i < kSv; i++) {
			double r[kR];
			do {
				for (int k = 0; k < kR; k++)
					r[k] = rng.uniform(lo[k], hi[k]);
			} while (std::hypot(r[0], r[1]) > kRadius);
			cost[i] = true_cost(r);
			hylo_features_of_relative(HYLO_MODE_GROUND, r, &raw[i * kF]);
		}
		for (int k = 0; k < kF; k++) {
			double mu = 0, v = 0;
			for (int i = 0; i < kSv; i++)
				mu += raw[i * kF + k] / kSv;
			for (int i = 0; i < kSv; i++)
				v += (raw[i * kF + k] - mu) * (raw[i * kF + k] - mu) / kSv;
			m.feature_offset.push_back(mu);
			m.feature_scale.push_back(std::sqrt(v));
		}
		for (int i = 0; i < kSv; i++)
			for (int k = 0; k < kF; k++)
				m.sv.push_back((raw[i * kF + k] - m.feature_offset[k]) / m.feature_scale[k]);
		double mean = 0, var = 0;
		for (double c : cost)
			mean += c / kSv;
		for (double c : cost)
			var += (c - mean) * (c - mean) / kSv;
		Eigen::MatrixXd K(kSv, kSv);
		Eigen::VectorXd t(kSv);
		for (int i = 0; i < kSv; i++) {
			t[i] = (cost[i] - mean) / std::sqrt(var);
			for (int j = 0; j < kSv; j++) {
				double d2 = 0;
				for (int k = 0; k < kF; k++) {
					double d = m.sv[i * kF + k] - m.sv[j * kF + k];
					d2 += d * d;
				}
				K(i, j) = std::exp(-kGamma * d2) + (i == j ? 1e-2 : 0.0);
			}
		}
		Eigen::VectorXd a = K.ldlt().solve(t);
		m.coef.assign(a.data(), a.data() + kSv);
		m.gamma = kGamma;
		m.rho = 0;
		m.label_offset = mean;
		m.label_scale = std::sqrt(var);
		m.cost_floor_per_m = 3.0;  // the true function never costs less than
		m.cost_floor_j = 0.5;      // 3 J/m * d + 0.5 J
		m.max_distance_m = kRadius;
		m.provenance = {{"kind", "synthetic benchmark model (tools/bench/make_synthetic_model.cpp)"},
				{"support vectors", std::to_string(kSv)},
				{"seed", "20261122"}};
		hylo::trainer::write_svr_header(m, argv[1]);
	} catch (const std::exception &e) {
		std::fprintf(stderr, "make_synthetic_model: %s\n", e.what());
		return 1;
	}
	return 0;
}
