// Fitting the edge-cost models (paper section III.B): libsvm epsilon-SVR with
// an RBF kernel (its solver is SMO) on standardized features and the
// standardized log of the cost, hyperparameters (C, gamma, epsilon) chosen by
// k-fold cross-validation on a grid, errors measured on a held-out split that
// no fit ever sees; and the feasibility classifier (C-SVC, RBF) on converged
// vs. infeasible samples. Deterministic: splits and folds come from the seed,
// never from rand().
#ifndef HYLO_TRAINER_SVR_FIT_HPP
#define HYLO_TRAINER_SVR_FIT_HPP

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "trainer/svr_export.hpp"

namespace hylo::trainer {

struct FitOptions {
	int folds = 5;                     // k of the k-fold cross-validation (>= 2)
	double test_fraction = 0.2;        // held out, never fitted
	uint64_t seed = 1;
	std::vector<double> C = {3, 30, 300};
	std::vector<double> gamma = {0.1, 0.3, 1.0};   // standardized feature units
	std::vector<double> epsilon = {0.005, 0.02, 0.05};   // standardized log-cost units
	// Sparsity: of the grid points whose cross-validated median relative
	// error is at most sparse_median and whose mean is within
	// sparse_mean_slack of the best mean, the one with the widest tube
	// (epsilon); if there is none, the best mean. Models fitted on at most
	// sparse_min_train pairs keep their most accurate point. Fewer support
	// vectors, a faster planner, the same p95 (docs/decisions.md, "Large
	// models take the widest tube").
	double sparse_median = 0.015;
	double sparse_mean_slack = 0.1;
	size_t sparse_min_train = 2000;
	size_t cv_max_samples = 2000;      // cross-validate on at most this many training samples;
	                                   // with more, gamma is validated again on all of them
	int jobs = 1;                      // threads for the cross-validation fits
	bool debug = false;                // each grid point's cross-validated errors on stderr
	// Sign flips of the features under which the cost is invariant: every
	// training row is also fitted flipped (held-out and validation rows
	// are not; a fold's flipped copies stay in its fold).
	std::vector<std::vector<double>> symmetries;
	// Per feature, how much faster the kernel varies along it than along a
	// standardized feature: its scale is divided by the weight (exported
	// with it, so the onboard evaluator needs nothing). Empty: all 1.
	std::vector<double> feature_weights;
};

// Relative errors |predicted - cost| / cost, and the mean absolute error [J].
struct Accuracy {
	double mae = 0, median = 0, p95 = 0, max = 0;
};

struct FitReport {
	size_t n_train = 0, n_test = 0, n_sv = 0;
	double C = 0, gamma = 0, epsilon = 0;
	double cv_mean_rel_error = 0;      // of the chosen grid point
	Accuracy held_out;                 // on test_rows
	double fit_seconds = 0;            // cross-validation and final fit
	std::vector<size_t> test_rows;     // the held-out samples (indices into cost)
};

// predicted[r] against cost[rows[r]] (rows not empty, the sizes equal).
Accuracy accuracy_of(const std::vector<double> &predicted, const std::vector<double> &cost,
		     const std::vector<size_t> &rows);

// "median M, p95 P, max X relative; MAE E J", as the fit's report and the
// header's provenance print it.
std::string describe(const Accuracy &a);

struct ClassifierReport {
	size_t n_train = 0, n_test = 0, n_sv = 0, n_feasible = 0;
	double C = 0, gamma = 0;
	double accuracy = 0;               // held out
	double fit_seconds = 0;
};

// Fits the cost model on n samples: x (n x n_features raw features,
// row-major), cost (n values, each > 0). Fills the model fields of out
// (n_features, gamma, rho, sv, coef, feature_offset/scale, label_*); the
// caller sets names, floors and provenance. Throws std::invalid_argument on
// unusable data (too few samples for the folds, non-finite or non-positive
// values), naming the problem.
FitReport fit_cost(int n_features, const std::vector<double> &x, const std::vector<double> &cost,
		   const FitOptions &opt, SvrExport &out);

// Fits the feasibility classifier; feasible[i] says whether sample i's
// trajectory optimization converged (and replayed). Oriented so that a
// decision value >= 0 means feasible. Throws std::invalid_argument when a
// class is missing or the data are unusable.
ClassifierReport fit_feasibility(int n_features, const std::vector<double> &x,
				 const std::vector<bool> &feasible, const FitOptions &opt,
				 ClassifierExport &out);

}  // namespace hylo::trainer

#endif
