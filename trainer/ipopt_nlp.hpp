// The NLP adapter for Ipopt (internal to the trainer): phases of the
// transcription (hs_phase.hpp) stacked into one problem, variables and
// constraints in phase order, then the linear rows joining them; solved with
// hylo's Ipopt settings. The solve strategy (solve_strategy.hpp) sees a
// solve's status and solution, never Ipopt's classes.
#ifndef HYLO_TRAINER_IPOPT_NLP_HPP
#define HYLO_TRAINER_IPOPT_NLP_HPP

#include <cstddef>
#include <memory>
#include <utility>
#include <vector>

#include "trainer/hs_phase.hpp"
#include "trainer/solution.hpp"

namespace hylo::trainer::internal {

// A linear row resolved to variable indices of the stacked problem.
struct Row {
	std::vector<std::pair<int, double>> terms;
	double lo = 0, hi = 0;
};

// Ipopt's mumps_permuting_scaling (MUMPS ICNTL(6)): Ipopt's default lets
// MUMPS choose; 0 skips the column permutation and scaling (MC64).
constexpr int kMumpsChoosesPermutingScaling = 7;

// How one Ipopt solve ended. The default is a success of no iterations.
struct NlpStatus {
	int status = 0;       // Ipopt's ApplicationReturnStatus
	int iterations = 0;
	// Solved, or solved to an acceptable level.
	bool succeeded() const;
	// "solved", "infeasible", "maximum iterations", ...
	const char *text() const;
};

// What an Ipopt solve of stacked phases is asked to do beyond the options.
struct NlpSettings {
	bool warm = false;    // the start is near the optimum: a small barrier keeps it there
	int permuting_scaling = kMumpsChoosesPermutingScaling;
};

class StackedNlp {
public:
	StackedNlp(std::vector<std::unique_ptr<PhaseBlock>> phases, std::vector<Row> rows);
	~StackedNlp();
	StackedNlp(const StackedNlp &) = delete;
	StackedNlp &operator=(const StackedNlp &) = delete;

	// Solves with Ipopt under opt's settings, from start (a solution of the
	// same size) or, empty, from the phases' own guesses.
	NlpStatus solve(const SolveOptions &opt, const std::vector<double> &start, const NlpSettings &settings);
	// The variables Ipopt ended at (empty before a solve).
	const std::vector<double> &solution() const { return z_; }
	// Phase k of the solution.
	void fill(size_t k, Solution &s) { ph_[k]->fill(z_.data() + vo_[k], s); }
	// The solution with the phases marked in `which` on meshes of twice the
	// segments, the others as they are.
	std::vector<double> refined(const std::vector<bool> &which) const;

private:
	friend class IpoptTnlp;   // ipopt_nlp.cpp: Ipopt's view of this problem
	std::vector<std::unique_ptr<PhaseBlock>> ph_;
	std::vector<Row> rows_;
	std::vector<int> vo_, co_;   // variable and constraint offsets of the phases
	int nvar_ = 0, ncon_ = 0;
	std::vector<double> z_;
};

}  // namespace hylo::trainer::internal

#endif
