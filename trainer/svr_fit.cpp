#include "trainer/svr_fit.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>
#include <thread>
#include <cstdlib>
#include <cstdio>

#include <libsvm/svm.h>

namespace hylo::trainer {
namespace {

using Clock = std::chrono::steady_clock;

// Deterministic permutation of 0..n-1 (Fisher-Yates on SplitMix64).
std::vector<size_t> permutation(size_t n, uint64_t seed)
{
	std::vector<size_t> p(n);
	std::iota(p.begin(), p.end(), size_t{0});
	uint64_t s = seed ^ 0x5851f42d4c957f2dULL;
	for (size_t i = n; i > 1; i--) {
		uint64_t z = (s += 0x9e3779b97f4a7c15ULL);
		z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
		z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
		z ^= z >> 31;
		std::swap(p[i - 1], p[static_cast<size_t>(z % i)]);
	}
	return p;
}

// Standardized rows of a libsvm problem (dense: every feature has a node).
struct Problem {
	int nf = 0;
	std::vector<svm_node> nodes;
	std::vector<svm_node *> rows;
	std::vector<double> y;
	svm_problem prob{};

	Problem(int n_features, const std::vector<double> &x, const std::vector<size_t> &idx,
		const std::vector<double> &target, const std::vector<double> &offset,
		const std::vector<double> &scale)
		: nf(n_features), nodes(idx.size() * static_cast<size_t>(n_features + 1)),
		  rows(idx.size()), y(idx.size())
	{
		for (size_t r = 0; r < idx.size(); r++) {
			svm_node *n = &nodes[r * static_cast<size_t>(nf + 1)];
			for (int k = 0; k < nf; k++)
				n[k] = {k + 1, (x[idx[r] * static_cast<size_t>(nf) + static_cast<size_t>(k)] -
						offset[static_cast<size_t>(k)]) / scale[static_cast<size_t>(k)]};
			n[nf] = {-1, 0};
			rows[r] = n;
			y[r] = target[idx[r]];
		}
		prob.l = static_cast<int>(idx.size());
		prob.y = y.data();
		prob.x = rows.data();
	}
	Problem(const Problem &) = delete;
	Problem &operator=(const Problem &) = delete;
};

svm_parameter params(int type, double C, double gamma, double epsilon)
{
	svm_parameter p{};
	p.svm_type = type;
	p.kernel_type = RBF;
	p.gamma = gamma;
	p.C = C;
	p.p = epsilon;
	p.eps = 1e-3;
	p.cache_size = 200;
	p.shrinking = 1;
	return p;
}

void silence() { svm_set_print_string_function([](const char *) {}); }

void check_data(int nf, const std::vector<double> &x, size_t n, size_t min_n, int folds)
{
	if (nf <= 0)
		throw std::invalid_argument("fit: the number of features must be positive");
	if (x.size() != n * static_cast<size_t>(nf))
		throw std::invalid_argument("fit: " + std::to_string(x.size()) +
					    " feature values for " + std::to_string(n) + " samples of " +
					    std::to_string(nf) + " features");
	if (folds < 2)
		throw std::invalid_argument("fit: cross-validation needs at least 2 folds");
	if (n < min_n)
		throw std::invalid_argument("fit: " + std::to_string(n) + " samples are too few for " +
					    std::to_string(folds) + "-fold cross-validation and a held-out "
					    "split (need at least " + std::to_string(min_n) + ")");
	for (size_t i = 0; i < x.size(); i++)
		if (!std::isfinite(x[i]))
			throw std::invalid_argument("fit: feature " + std::to_string(i % nf) +
						    " of sample " + std::to_string(i / nf) +
						    " is not finite");
}

// Feature standardization from the training rows only, each scale divided
// by its feature's weight (none: 1).
void standardization(int nf, const std::vector<double> &x, const std::vector<size_t> &train,
		     const std::vector<double> &weights, std::vector<double> &offset, std::vector<double> &scale)
{
	if (!weights.empty() && weights.size() != static_cast<size_t>(nf))
		throw std::invalid_argument("fit: " + std::to_string(weights.size()) + " feature weights for " +
					    std::to_string(nf) + " features");
	for (double w : weights)
		if (!(w > 0) || !std::isfinite(w))
			throw std::invalid_argument("fit: a feature weight is not finite and > 0");
	offset.assign(static_cast<size_t>(nf), 0.0);
	scale.assign(static_cast<size_t>(nf), 1.0);
	for (int k = 0; k < nf; k++) {
		double mean = 0, var = 0;
		for (size_t i : train)
			mean += x[i * static_cast<size_t>(nf) + static_cast<size_t>(k)];
		mean /= static_cast<double>(train.size());
		for (size_t i : train) {
			double d = x[i * static_cast<size_t>(nf) + static_cast<size_t>(k)] - mean;
			var += d * d;
		}
		var /= static_cast<double>(train.size());
		offset[static_cast<size_t>(k)] = mean;
		scale[static_cast<size_t>(k)] = (var > 1e-24 ? std::sqrt(var) : 1.0) /
						 (weights.empty() ? 1.0 : weights[static_cast<size_t>(k)]);
	}
}

// Dense support vectors and coefficients (times sign) of a trained model.
void take(const svm_model *m, int nf, double sign, std::vector<double> &sv,
	  std::vector<double> &coef)
{
	sv.clear();
	coef.clear();
	for (int i = 0; i < m->l; i++) {
		std::vector<double> row(static_cast<size_t>(nf), 0.0);
		for (const svm_node *n = m->SV[i]; n->index != -1; n++)
			row[static_cast<size_t>(n->index - 1)] = n->value;
		sv.insert(sv.end(), row.begin(), row.end());
		coef.push_back(sign * m->sv_coef[0][i]);
	}
}

// Runs f(i) for i in [0, n) on up to jobs threads; results must go to
// per-index slots, so the outcome does not depend on scheduling.
template <class F>
void parallel_for(size_t n, int jobs, F f)
{
	size_t workers = std::max<size_t>(1, std::min<size_t>(n, static_cast<size_t>(jobs)));
	std::vector<std::thread> pool;
	for (size_t w = 0; w < workers; w++)
		pool.emplace_back([&, w] {
			for (size_t i = w; i < n; i += workers)
				f(i);
		});
	for (auto &t : pool)
		t.join();
}

double quantile(std::vector<double> v, double q)
{
	std::sort(v.begin(), v.end());
	double pos = q * static_cast<double>(v.size() - 1);
	size_t lo = static_cast<size_t>(std::floor(pos));
	size_t hi = std::min(lo + 1, v.size() - 1);
	return v[lo] + (pos - static_cast<double>(lo)) * (v[hi] - v[lo]);
}

// ---- the cost model's steps (fit_cost) ----------------------------------

void check_costs(const std::vector<double> &cost, const FitOptions &opt)
{
	for (size_t i = 0; i < cost.size(); i++)
		if (!std::isfinite(cost[i]) || !(cost[i] > 0))
			throw std::invalid_argument("fit: cost of sample " + std::to_string(i) + " is " +
						    std::to_string(cost[i]) + ", not a positive number");
	if (opt.C.empty() || opt.gamma.empty() || opt.epsilon.empty())
		throw std::invalid_argument("fit: empty hyperparameter grid");
}

// The held-out rows and the training rows, from the seed.
struct Split {
	std::vector<size_t> test, train;
};

Split split(size_t n, uint64_t seed, const FitOptions &opt)
{
	std::vector<size_t> perm = permutation(n, seed);
	size_t n_test = std::max<size_t>(1, static_cast<size_t>(opt.test_fraction * static_cast<double>(n)));
	return {std::vector<size_t>(perm.begin(), perm.begin() + static_cast<long>(n_test)),
		std::vector<size_t>(perm.begin() + static_cast<long>(n_test), perm.end())};
}

// Labels: standardized log cost (relative errors matter; costs span decades),
// with the training rows' mean and scale.
struct LogLabels {
	double mean = 0, scale = 1;
	std::vector<double> target;   // per row (and per mirror image, with_symmetries)
	double cost(double label) const { return std::exp(label * scale + mean); }
};

LogLabels log_labels(const std::vector<double> &cost, const std::vector<size_t> &train)
{
	const size_t n = cost.size();
	std::vector<double> logc(n);
	for (size_t i = 0; i < n; i++)
		logc[i] = std::log(cost[i]);
	double mean = 0, var = 0;
	for (size_t i : train)
		mean += logc[i];
	mean /= static_cast<double>(train.size());
	for (size_t i : train)
		var += (logc[i] - mean) * (logc[i] - mean);
	double lscale = std::sqrt(var / static_cast<double>(train.size()));
	if (!(lscale > 1e-12))
		lscale = 1;
	LogLabels l{mean, lscale, std::vector<double>(n)};
	for (size_t i = 0; i < n; i++)
		l.target[i] = (logc[i] - mean) / lscale;
	return l;
}

// The mirror images: rows n*(s+1) + i of the returned features are row i
// flipped by symmetry s; labels repeat.
std::vector<double> with_symmetries(int nf, const std::vector<double> &x, size_t n,
				    const std::vector<std::vector<double>> &symmetries, std::vector<double> &target)
{
	std::vector<double> xa = x;
	for (const std::vector<double> &sg : symmetries) {
		if (sg.size() != static_cast<size_t>(nf))
			throw std::invalid_argument("fit: a symmetry has " + std::to_string(sg.size()) +
						    " signs for " + std::to_string(nf) + " features");
		for (size_t i = 0; i < n; i++)
			for (size_t k = 0; k < sg.size(); k++)
				xa.push_back(sg[k] * x[i * sg.size() + k]);
	}
	for (size_t s = 0; s < symmetries.size(); s++)
		target.insert(target.end(), target.begin(), target.begin() + static_cast<long>(n));
	return xa;
}

// Rows idx and their mirror images (with_symmetries).
std::vector<size_t> with_images(const std::vector<size_t> &idx, size_t n, size_t symmetries)
{
	std::vector<size_t> all = idx;
	for (size_t s = 1; s <= symmetries; s++)
		for (size_t i : idx)
			all.push_back(s * n + i);
	return all;
}

// The rows with their images, standardized, as the fits see them.
struct CostData {
	int nf = 0;
	size_t n = 0, symmetries = 0;
	std::vector<double> xa;           // features with the mirror images
	LogLabels labels;
	std::vector<double> offset, scale;   // feature standardization
	const std::vector<double> *cost = nullptr;
};

// A grid point and its cross-validated relative errors.
struct Point { double C, gamma, eps, err, median, p95; };

std::vector<Point> grid_of(const FitOptions &opt)
{
	std::vector<Point> grid;
	for (double C : opt.C)
		for (double g : opt.gamma)
			for (double e : opt.epsilon)
				grid.push_back({C, g, e, 0, 0, 0});
	return grid;
}

// Cross-validation's rows: a deterministic subset of the training split.
std::vector<size_t> cv_rows(const std::vector<size_t> &train, const FitOptions &opt)
{
	return std::vector<size_t>(train.begin(),
				   train.begin() + static_cast<long>(std::min(train.size(), opt.cv_max_samples)));
}

// Fold f of k of the cross-validation rows: every k-th row validates, the rest fit.
void fold(const std::vector<size_t> &cv, size_t f, size_t k, std::vector<size_t> &fit_idx,
	  std::vector<size_t> &val_idx)
{
	for (size_t i = 0; i < cv.size(); i++)
		(i % k == f ? val_idx : fit_idx).push_back(cv[i]);
}

// The median and p95 of a point's relative errors rel.
void set_quantiles(Point &pt, const std::vector<double> &rel)
{
	pt.median = quantile(rel, 0.5);
	pt.p95 = quantile(rel, 0.95);
}

// A point's errors on stderr (--debug); stage: where they were measured.
void trace(const char *stage, const Point &pt)
{
	std::fprintf(stderr, "%s: C %g gamma %g epsilon %g: relative error mean %.5f, median %.5f, p95 %.5f\n", stage,
		     pt.C, pt.gamma, pt.eps, pt.err, pt.median, pt.p95);
}

// One fold's fit at a grid point: the relative errors of its validation rows.
std::vector<double> fold_errors(const CostData &d, const std::vector<size_t> &cv, const Point &pt, size_t f,
				size_t k)
{
	std::vector<size_t> fit_idx, val_idx;
	fold(cv, f, k, fit_idx, val_idx);
	Problem p(d.nf, d.xa, with_images(fit_idx, d.n, d.symmetries), d.labels.target, d.offset, d.scale);
	svm_parameter par = params(EPSILON_SVR, pt.C, pt.gamma, pt.eps);
	svm_model *m = svm_train(&p.prob, &par);
	Problem v(d.nf, d.xa, val_idx, d.labels.target, d.offset, d.scale);
	std::vector<double> rel;
	for (size_t r = 0; r < val_idx.size(); r++) {
		double pred = d.labels.cost(svm_predict(m, v.rows[r]));
		rel.push_back(std::fabs(pred - (*d.cost)[val_idx[r]]) / (*d.cost)[val_idx[r]]);
	}
	svm_free_and_destroy_model(&m);
	return rel;
}

// Cross-validation of every grid point on cv (k folds): their mean and
// median relative errors. Returns the best mean's index.
size_t cross_validate(const CostData &d, const std::vector<size_t> &cv, std::vector<Point> &grid,
		      const FitOptions &opt)
{
	size_t k = static_cast<size_t>(opt.folds);
	std::vector<std::vector<double>> fold_rel(grid.size() * k);   // per validation sample
	parallel_for(grid.size() * k, opt.jobs,
		     [&](size_t job) { fold_rel[job] = fold_errors(d, cv, grid[job / k], job % k, k); });
	size_t best = 0;
	for (size_t g = 0; g < grid.size(); g++) {
		std::vector<double> all;
		for (size_t f = 0; f < k; f++) {
			const std::vector<double> &rel = fold_rel[g * k + f];
			double sum = 0;
			for (double e : rel)
				sum += e;
			grid[g].err += sum / static_cast<double>(rel.size()) / static_cast<double>(k);
			all.insert(all.end(), rel.begin(), rel.end());
		}
		set_quantiles(grid[g], all);
		if (grid[g].err < grid[best].err)
			best = g;
	}
	if (opt.debug)
		for (const Point &pt : grid)
			trace("cv", pt);
	return best;
}

// The sparse choice (large models only): the widest tube whose median error
// is within the budget and whose mean error is near the best; else the best.
size_t sparse_choice(const std::vector<Point> &grid, size_t best, size_t n_train, const FitOptions &opt)
{
	size_t chosen = best;
	for (size_t g = 0; n_train > opt.sparse_min_train && g < grid.size(); g++)
		if (grid[g].median <= opt.sparse_median && grid[g].err <= grid[best].err * (1 + opt.sparse_mean_slack) &&
		    (grid[g].eps > grid[chosen].eps ||
		     (grid[g].eps == grid[chosen].eps && grid[g].err < grid[chosen].err)))
			chosen = g;
	return chosen;
}

// The kernel width at full density: the grid's cross-validation sees at most
// cv_max_samples training rows, and a sparser sample favours a wider kernel.
// With more rows than that, each of the grid's gammas at the chosen C and
// epsilon is fitted on the whole training split less every folds-th row and
// validated on those rows; the lowest mean relative error wins.
Point width_at_full_density(const CostData &d, const std::vector<size_t> &train, const Point &chosen,
			    const FitOptions &opt)
{
	if (train.size() <= opt.cv_max_samples)
		return chosen;
	std::vector<Point> widths;
	for (double g : opt.gamma)
		widths.push_back({chosen.C, g, chosen.eps, 0, 0, 0});
	const size_t k = static_cast<size_t>(opt.folds);
	std::vector<std::vector<double>> rel(widths.size());
	parallel_for(widths.size(), opt.jobs, [&](size_t i) { rel[i] = fold_errors(d, train, widths[i], 0, k); });
	size_t best = 0;
	for (size_t i = 0; i < widths.size(); i++) {
		widths[i].err = std::accumulate(rel[i].begin(), rel[i].end(), 0.0) / static_cast<double>(rel[i].size());
		set_quantiles(widths[i], rel[i]);
		if (opt.debug)
			trace("full density", widths[i]);
		if (widths[i].err < widths[best].err)
			best = i;
	}
	Point pt = widths[best];
	pt.err = chosen.err;   // the report's cross-validated mean stays the grid's
	return pt;
}

// The held-out errors of model m.
void test_errors(const svm_model *m, const CostData &d, const std::vector<double> &x,
		 const std::vector<size_t> &test, FitReport &rep)
{
	Problem t(d.nf, x, test, d.labels.target, d.offset, d.scale);
	std::vector<double> pred;
	for (size_t r = 0; r < test.size(); r++)
		pred.push_back(d.labels.cost(svm_predict(m, t.rows[r])));
	rep.held_out = accuracy_of(pred, *d.cost, test);
	rep.test_rows = test;
}

// Model m with d's standardization as an export's model fields.
void export_model(const svm_model *m, const CostData &d, SvrExport &out)
{
	out.n_features = d.nf;
	out.gamma = m->param.gamma;
	out.rho = m->rho[0];
	take(m, d.nf, 1.0, out.sv, out.coef);
	out.feature_offset = d.offset;
	out.feature_scale = d.scale;
	out.label_offset = d.labels.mean;
	out.label_scale = d.labels.scale;
	out.label_log = true;
}

}  // namespace

Accuracy accuracy_of(const std::vector<double> &predicted, const std::vector<double> &cost,
		     const std::vector<size_t> &rows)
{
	if (rows.empty() || predicted.size() != rows.size())
		throw std::invalid_argument("accuracy: " + std::to_string(predicted.size()) + " predictions for " +
					    std::to_string(rows.size()) + " rows");
	Accuracy a;
	std::vector<double> rel;
	for (size_t r = 0; r < rows.size(); r++) {
		const double c = cost.at(rows[r]);
		a.mae += std::fabs(predicted[r] - c) / static_cast<double>(rows.size());
		rel.push_back(std::fabs(predicted[r] - c) / c);
	}
	a.median = quantile(rel, 0.5);
	a.p95 = quantile(rel, 0.95);
	a.max = *std::max_element(rel.begin(), rel.end());
	return a;
}

std::string describe(const Accuracy &a)
{
	char buf[160];
	std::snprintf(buf, sizeof buf, "median %.4f, p95 %.4f, max %.4f relative; MAE %.4g J", a.median, a.p95, a.max,
		      a.mae);
	return buf;
}

FitReport fit_cost(int nf, const std::vector<double> &x, const std::vector<double> &cost,
		   const FitOptions &opt, SvrExport &out)
{
	auto t0 = Clock::now();
	const size_t n = cost.size();
	check_data(nf, x, n, static_cast<size_t>(std::max(10, 2 * opt.folds)), opt.folds);
	check_costs(cost, opt);
	silence();
	const Split sp = split(n, opt.seed, opt);
	CostData d;
	d.nf = nf;
	d.n = n;
	d.symmetries = opt.symmetries.size();
	d.cost = &cost;
	d.labels = log_labels(cost, sp.train);
	d.xa = with_symmetries(nf, x, n, opt.symmetries, d.labels.target);
	const std::vector<size_t> train_all = with_images(sp.train, n, d.symmetries);
	standardization(nf, d.xa, train_all, opt.feature_weights, d.offset, d.scale);

	std::vector<Point> grid = grid_of(opt);
	const size_t best = cross_validate(d, cv_rows(sp.train, opt), grid, opt);
	const Point pt = width_at_full_density(d, sp.train, grid[sparse_choice(grid, best, sp.train.size(), opt)], opt);

	// The final fit on the whole training split.
	Problem p(nf, d.xa, train_all, d.labels.target, d.offset, d.scale);
	svm_parameter par = params(EPSILON_SVR, pt.C, pt.gamma, pt.eps);
	svm_model *m = svm_train(&p.prob, &par);
	FitReport rep;
	rep.n_train = sp.train.size();
	rep.n_test = sp.test.size();
	rep.n_sv = static_cast<size_t>(m->l);
	rep.C = pt.C;
	rep.gamma = pt.gamma;
	rep.epsilon = pt.eps;
	rep.cv_mean_rel_error = pt.err;
	test_errors(m, d, x, sp.test, rep);
	export_model(m, d, out);
	svm_free_and_destroy_model(&m);
	rep.fit_seconds = std::chrono::duration<double>(Clock::now() - t0).count();
	return rep;
}

namespace {

// ---- the feasibility classifier's steps (fit_feasibility) ---------------

// The classifier's data: +1 feasible, -1 not; standardized on the training rows.
struct ClassData {
	int nf = 0;
	const std::vector<double> *x = nullptr;
	std::vector<double> label;
	std::vector<double> offset, scale;
};

// A grid point of the classifier and its cross-validated accuracy.
struct ClassPoint { double C, gamma, acc; };

bool one_class(const Problem &p)
{
	return std::all_of(p.y.begin(), p.y.end(), [&](double v) { return v == p.y[0]; });
}

// The share of rows idx that m classifies right.
double accuracy(const svm_model *m, const ClassData &d, const std::vector<size_t> &idx)
{
	Problem v(d.nf, *d.x, idx, d.label, d.offset, d.scale);
	size_t hits = 0;
	for (size_t r = 0; r < idx.size(); r++)
		hits += svm_predict(m, v.rows[r]) == d.label[idx[r]];
	return static_cast<double>(hits) / static_cast<double>(idx.size());
}

// The share of rows idx of class c.
double share_of_class(double c, const ClassData &d, const std::vector<size_t> &idx)
{
	size_t hits = 0;
	for (size_t i : idx)
		hits += d.label[i] == c;
	return static_cast<double>(hits) / static_cast<double>(idx.size());
}

// One fold's fit at a grid point: its validation accuracy. A fold of one
// class predicts that class.
double fold_accuracy(const ClassData &d, const std::vector<size_t> &cv, const ClassPoint &pt, size_t f, size_t k)
{
	std::vector<size_t> fit_idx, val_idx;
	fold(cv, f, k, fit_idx, val_idx);
	Problem p(d.nf, *d.x, fit_idx, d.label, d.offset, d.scale);
	if (one_class(p))
		return share_of_class(p.y[0], d, val_idx);
	svm_parameter par = params(C_SVC, pt.C, pt.gamma, 0);
	svm_model *m = svm_train(&p.prob, &par);
	double acc = accuracy(m, d, val_idx);
	svm_free_and_destroy_model(&m);
	return acc;
}

// Cross-validation of every (C, gamma) on cv: the most accurate point's index.
size_t cross_validate(const ClassData &d, const std::vector<size_t> &cv, std::vector<ClassPoint> &grid,
		      const FitOptions &opt)
{
	size_t k = static_cast<size_t>(opt.folds);
	std::vector<double> fold_acc(grid.size() * k, 0.0);
	parallel_for(grid.size() * k, opt.jobs,
		     [&](size_t job) { fold_acc[job] = fold_accuracy(d, cv, grid[job / k], job % k, k); });
	size_t best = 0;
	for (size_t g = 0; g < grid.size(); g++) {
		for (size_t f = 0; f < k; f++)
			grid[g].acc += fold_acc[g * k + f] / static_cast<double>(k);
		if (grid[g].acc > grid[best].acc)
			best = g;
	}
	return best;
}

}  // namespace

ClassifierReport fit_feasibility(int nf, const std::vector<double> &x,
				 const std::vector<bool> &feasible, const FitOptions &opt,
				 ClassifierExport &out)
{
	auto t0 = Clock::now();
	size_t n = feasible.size();
	check_data(nf, x, n, static_cast<size_t>(std::max(10, 2 * opt.folds)), opt.folds);
	size_t n_feasible = static_cast<size_t>(std::count(feasible.begin(), feasible.end(), true));
	if (n_feasible == 0 || n_feasible == n)
		throw std::invalid_argument("fit: the feasibility classifier needs both feasible and "
					    "infeasible samples (" + std::to_string(n_feasible) +
					    " of " + std::to_string(n) + " are feasible)");
	silence();
	const Split sp = split(n, opt.seed + 1, opt);
	ClassData d;
	d.nf = nf;
	d.x = &x;
	for (size_t i = 0; i < n; i++)
		d.label.push_back(feasible[i] ? 1 : -1);
	standardization(nf, x, sp.train, {}, d.offset, d.scale);
	std::vector<ClassPoint> grid;
	for (double C : opt.C)
		for (double g : opt.gamma)
			grid.push_back({C, g, 0});
	const ClassPoint &pt = grid[cross_validate(d, cv_rows(sp.train, opt), grid, opt)];

	Problem p(nf, x, sp.train, d.label, d.offset, d.scale);
	if (one_class(p))
		throw std::invalid_argument("fit: the training split of the feasibility data has one class only");
	svm_parameter par = params(C_SVC, pt.C, pt.gamma, 0);
	svm_model *m = svm_train(&p.prob, &par);
	// libsvm's decision value is positive for label[0]: orient it to "feasible".
	double sign = m->label[0] == 1 ? 1.0 : -1.0;
	ClassifierReport rep;
	rep.n_train = sp.train.size();
	rep.n_test = sp.test.size();
	rep.n_sv = static_cast<size_t>(m->l);
	rep.n_feasible = n_feasible;
	rep.C = pt.C;
	rep.gamma = pt.gamma;
	rep.accuracy = accuracy(m, d, sp.test);
	out.gamma = m->param.gamma;
	out.rho = sign * m->rho[0];
	take(m, nf, sign, out.sv, out.coef);
	out.feature_offset = d.offset;
	out.feature_scale = d.scale;
	svm_free_and_destroy_model(&m);
	rep.fit_seconds = std::chrono::duration<double>(Clock::now() - t0).count();
	return rep;
}

}  // namespace hylo::trainer
