// Trains a small epsilon-SVR (cost) and C-SVC (feasibility) with libsvm on a
// smooth function of the 8 planar features, exports them with the trainer's
// exporter as OUT_DIR/testbot_ground.h, and writes libsvm's own predictions
// on held-out points to OUT_DIR/reference.txt (%.17g), which
// tests/export/test_export.c compares with the onboard evaluator. The
// header carries the model's envelope (trainer/envelope.cpp), computed on
// JOBS threads (default 1; the bytes must not depend on it).
//   make_test_model OUT_DIR [JOBS]
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fstream>
#include <string>
#include <vector>

#include <libsvm/svm.h>

#include "hylo/features.h"
#include "trainer/envelope.hpp"
#include "trainer/svr_export.hpp"

namespace {

constexpr int kF = HYLO_FEATURES_PLANAR, kTrain = 300, kTest = 200;

struct Rng {
	uint64_t s;
	double uniform(double lo, double hi)
	{
		s = s * 6364136223846793005ULL + 1442695040888963407ULL;
		return lo + (hi - lo) * static_cast<double>(s >> 11) * 0x1.0p-53;
	}
};

// The features of random relative coordinates (dx', dy', dtheta, vx1, vx2).
void draw(Rng &r, double *x)
{
	double rel[HYLO_RELATIVE_PLANAR];
	rel[0] = r.uniform(-4, 4);
	rel[1] = r.uniform(-4, 4);
	rel[2] = r.uniform(-3.14, 3.14);
	rel[3] = r.uniform(0, 1);
	rel[4] = r.uniform(0, 1);
	hylo_features_of_relative(HYLO_MODE_GROUND, rel, x);
}

double cost(const double *x)
{
	return 3.0 * std::hypot(x[0], x[1]) * (1 + 0.2 * std::fabs(x[4] - x[3])) +
	       0.5 * x[2] * x[2] + 1.0;
}

bool feasible(const double *x) { return std::fabs(x[2]) < 2.0 || std::hypot(x[0], x[1]) > 1.5; }

const double kOffset[kF] = {0, 2, 0, 0.5, 0.5, 3, 2, 1.6};
const double kScale[kF] = {2.3, 1.2, 1.8, 0.29, 0.29, 1.4, 1.2, 0.9};

void nodes(const double *x, svm_node *n)
{
	for (int k = 0; k < kF; k++)
		n[k] = {k + 1, (x[k] - kOffset[k]) / kScale[k]};
	n[kF] = {-1, 0};
}

svm_model *train(std::vector<double> &xs, std::vector<double> &ys, int type,
		 std::vector<svm_node> &store, svm_problem &prob, std::vector<svm_node *> &rows)
{
	store.resize(static_cast<size_t>(kTrain) * (kF + 1));
	rows.resize(kTrain);
	for (int i = 0; i < kTrain; i++) {
		nodes(&xs[static_cast<size_t>(i) * kF], &store[static_cast<size_t>(i) * (kF + 1)]);
		rows[static_cast<size_t>(i)] = &store[static_cast<size_t>(i) * (kF + 1)];
	}
	prob.l = kTrain;
	prob.y = ys.data();
	prob.x = rows.data();
	svm_parameter p{};
	p.svm_type = type;
	p.kernel_type = RBF;
	p.gamma = 0.5;
	p.C = 10;
	p.p = 0.05;
	p.eps = 1e-4;
	p.cache_size = 20;
	p.shrinking = 1;
	const char *err = svm_check_parameter(&prob, &p);
	if (err)
		throw std::runtime_error(err);
	return svm_train(&prob, &p);
}

void take(const svm_model *m, std::vector<double> &sv, std::vector<double> &coef, double sign)
{
	for (int i = 0; i < m->l; i++) {
		std::vector<double> row(kF, 0.0);
		for (const svm_node *n = m->SV[i]; n->index != -1; n++)
			row[static_cast<size_t>(n->index - 1)] = n->value;
		sv.insert(sv.end(), row.begin(), row.end());
		coef.push_back(sign * m->sv_coef[0][i]);
	}
}

}  // namespace

int main(int argc, char **argv)
{
	if (argc != 2 && argc != 3) {
		std::fprintf(stderr, "usage: %s OUT_DIR [JOBS]\n", argv[0]);
		return 2;
	}
	try {
		svm_set_print_string_function([](const char *) {});
		Rng rng{7};
		std::vector<double> xs(static_cast<size_t>(kTrain) * kF), ys(kTrain), labels(kTrain);
		for (int i = 0; i < kTrain; i++) {
			double *x = &xs[static_cast<size_t>(i) * kF];
			draw(rng, x);
			ys[static_cast<size_t>(i)] = cost(x);
			labels[static_cast<size_t>(i)] = feasible(x) ? 1 : -1;
		}
		std::vector<svm_node> s1, s2;
		std::vector<svm_node *> r1, r2;
		svm_problem p1{}, p2{};
		svm_model *reg = train(xs, ys, EPSILON_SVR, s1, p1, r1);
		svm_model *cls = train(xs, labels, C_SVC, s2, p2, r2);

		hylo::trainer::SvrExport m;
		m.robot = "testbot";
		m.mode = HYLO_MODE_GROUND;
		m.n_features = kF;
		m.gamma = reg->param.gamma;
		m.rho = reg->rho[0];
		take(reg, m.sv, m.coef, 1.0);
		m.feature_offset.assign(kOffset, kOffset + kF);
		m.feature_scale.assign(kScale, kScale + kF);
		m.cost_floor_per_m = 0;
		m.max_distance_m = 6;
		m.speed_min_mps = 0;
		m.speed_max_mps = 0.5;
		m.provenance = {{"kind", "test model (tests/export/make_test_model.cpp)"},
				{"samples", std::to_string(kTrain)}};
		// Orient the classifier: decision >= 0 means feasible (+1).
		double sign = cls->label[0] == 1 ? 1.0 : -1.0;
		hylo::trainer::ClassifierExport f;
		f.gamma = cls->param.gamma;
		f.rho = sign * cls->rho[0];
		take(cls, f.sv, f.coef, sign);
		f.feature_offset = m.feature_offset;
		f.feature_scale = m.feature_scale;
		m.feasibility = f;
		hylo::trainer::EnvelopeOptions eo;
		eo.jobs = argc == 3 ? std::atoi(argv[2]) : 1;
		eo.check_edges = 100000;
		eo.progress = false;
		hylo::trainer::EnvelopeReport env = hylo::trainer::compute_envelope(m, eo);
		m.envelope = env.table;
		m.provenance.push_back({"envelope", env.provenance()});
		std::string dir = argv[1];
		hylo::trainer::write_svr_header(m, dir + "/testbot_ground.h");

		std::ofstream ref(dir + "/reference.txt");
		ref.precision(17);
		for (int i = 0; i < kTest; i++) {
			double x[kF], dec = 0;
			svm_node n[kF + 1];
			draw(rng, x);
			nodes(x, n);
			double y = svm_predict(reg, n);
			svm_predict_values(cls, n, &dec);
			for (double v : x)
				ref << v << " ";
			ref << y << " " << sign * dec << "\n";
		}
		svm_free_and_destroy_model(&reg);
		svm_free_and_destroy_model(&cls);
	} catch (const std::exception &e) {
		std::fprintf(stderr, "make_test_model: %s\n", e.what());
		return 1;
	}
	return 0;
}
