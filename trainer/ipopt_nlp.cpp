#include "trainer/ipopt_nlp.hpp"

#include <algorithm>
#include <charconv>
#include <stdexcept>
#include <string>

#include <IpIpoptApplication.hpp>
#include <IpSolveStatistics.hpp>
#include <IpTNLP.hpp>

namespace hylo::trainer {
namespace internal {

// Ipopt's view of a StackedNlp for one solve: forwards each callback to the
// phases at their offsets, then evaluates the linear rows. Held by SmartPtr.
class IpoptTnlp : public Ipopt::TNLP {
public:
	IpoptTnlp(StackedNlp &p, const std::vector<double> &start) : p_(p), start_(start) {}

	bool get_nlp_info(Index &n, Index &m, Index &nnz_jac, Index &nnz_h, IndexStyleEnum &style) override
	{
		n = p_.nvar_;
		m = p_.ncon_ + static_cast<int>(p_.rows_.size());
		nnz_jac = 0;
		nnz_h = 0;
		for (const auto &p : p_.ph_) {
			nnz_jac += p->nnz_jac();
			nnz_h += p->nnz_h();
		}
		for (const Row &r : p_.rows_)
			nnz_jac += static_cast<int>(r.terms.size());
		style = TNLP::C_STYLE;
		return true;
	}

	bool get_bounds_info(Index, Number *xl, Number *xu, Index, Number *gl, Number *gu) override
	{
		for (size_t k = 0; k < p_.ph_.size(); k++)
			p_.ph_[k]->bounds(xl + p_.vo_[k], xu + p_.vo_[k], gl + p_.co_[k], gu + p_.co_[k]);
		for (size_t i = 0; i < p_.rows_.size(); i++) {
			gl[p_.ncon_ + static_cast<int>(i)] = p_.rows_[i].lo;
			gu[p_.ncon_ + static_cast<int>(i)] = p_.rows_[i].hi;
		}
		return true;
	}

	bool get_starting_point(Index n, bool, Number *z, bool, Number *, Number *, Index, bool,
				Number *) override
	{
		if (start_.size() == static_cast<size_t>(n)) {
			std::copy(start_.begin(), start_.end(), z);
			return true;
		}
		for (size_t k = 0; k < p_.ph_.size(); k++)
			p_.ph_[k]->start(z + p_.vo_[k]);
		return true;
	}

	bool get_scaling_parameters(Number &obj_scaling, bool &use_x_scaling, Index, Number *x_scaling,
				    bool &use_g_scaling, Index, Number *g_scaling) override
	{
		double T = 0;
		for (const auto &p : p_.ph_)
			T += p->T_guess();
		obj_scaling = 1.0 / std::max(1.0, T * 10.0);
		use_x_scaling = true;
		use_g_scaling = true;
		for (size_t k = 0; k < p_.ph_.size(); k++)
			p_.ph_[k]->scaling(x_scaling + p_.vo_[k], g_scaling + p_.co_[k]);
		for (size_t i = 0; i < p_.rows_.size(); i++)
			g_scaling[p_.ncon_ + static_cast<int>(i)] = 1.0;
		return true;
	}

	bool eval_f(Index, const Number *z, bool new_x, Number &obj) override
	{
		obj = 0;
		for (size_t k = 0; k < p_.ph_.size(); k++)
			obj += p_.ph_[k]->objective(z + p_.vo_[k], new_x);
		return true;
	}

	bool eval_grad_f(Index, const Number *z, bool new_x, Number *g) override
	{
		for (size_t k = 0; k < p_.ph_.size(); k++)
			p_.ph_[k]->gradient(z + p_.vo_[k], new_x, g + p_.vo_[k]);
		return true;
	}

	bool eval_g(Index, const Number *z, bool new_x, Index, Number *g) override
	{
		for (size_t k = 0; k < p_.ph_.size(); k++)
			p_.ph_[k]->constraints(z + p_.vo_[k], new_x, g + p_.co_[k]);
		for (size_t i = 0; i < p_.rows_.size(); i++) {
			double s = 0;
			for (const auto &t : p_.rows_[i].terms)
				s += t.second * z[t.first];
			g[p_.ncon_ + static_cast<int>(i)] = s;
		}
		return true;
	}

	bool eval_jac_g(Index, const Number *z, bool new_x, Index, Index, Index *iRow, Index *jCol,
			Number *v) override
	{
		int e = 0;
		for (size_t k = 0; k < p_.ph_.size(); k++) {
			if (v)
				p_.ph_[k]->jac_values(z + p_.vo_[k], new_x, v + e);
			else
				p_.ph_[k]->jac_structure(iRow + e, jCol + e, p_.vo_[k], p_.co_[k]);
			e += p_.ph_[k]->nnz_jac();
		}
		for (size_t i = 0; i < p_.rows_.size(); i++)
			for (const auto &t : p_.rows_[i].terms) {
				if (v) {
					v[e] = t.second;
				} else {
					iRow[e] = p_.ncon_ + static_cast<int>(i);
					jCol[e] = t.first;
				}
				e++;
			}
		return true;
	}

	// The rows are linear: only the phases contribute to the Hessian.
	bool eval_h(Index, const Number *z, bool, Number sigma, Index, const Number *lambda, bool, Index,
		    Index *iRow, Index *jCol, Number *v) override
	{
		int e = 0;
		for (size_t k = 0; k < p_.ph_.size(); k++) {
			if (v)
				p_.ph_[k]->hess_values(z + p_.vo_[k], sigma, lambda + p_.co_[k], v + e);
			else
				p_.ph_[k]->hess_structure(iRow + e, jCol + e, p_.vo_[k]);
			e += p_.ph_[k]->nnz_h();
		}
		return true;
	}

	void finalize_solution(Ipopt::SolverReturn, Index n, const Number *z, const Number *,
			       const Number *, Index, const Number *, const Number *, Number,
			       const Ipopt::IpoptData *, Ipopt::IpoptCalculatedQuantities *) override
	{
		p_.z_.assign(z, z + n);
	}

private:
	StackedNlp &p_;
	const std::vector<double> &start_;
};

}  // namespace internal

namespace {

using internal::NlpSettings;

// Sets o by the type Ipopt registered for its name; false if there is none,
// the value does not parse as that type, or Ipopt refuses it (silently).
bool set_ipopt_option(Ipopt::IpoptApplication &app, const IpoptOption &o)
{
	Ipopt::SmartPtr<const Ipopt::RegisteredOption> reg = app.RegOptions()->GetOption(o.name);
	if (!Ipopt::IsValid(reg))
		return false;
	Ipopt::SmartPtr<Ipopt::OptionsList> list = app.Options();
	const char *begin = o.value.c_str(), *end = begin + o.value.size();
	switch (reg->Type()) {
	case Ipopt::OT_Number: {
		double v = 0;
		auto r = std::from_chars(begin, end, v);
		return r.ec == std::errc() && r.ptr == end && list->SetNumericValue(o.name, v, true, true);
	}
	case Ipopt::OT_Integer: {
		int v = 0;
		auto r = std::from_chars(begin, end, v);
		return r.ec == std::errc() && r.ptr == end && list->SetIntegerValue(o.name, v, true, true);
	}
	case Ipopt::OT_String:
		return list->SetStringValue(o.name, o.value, true, true);
	default:
		return false;
	}
}

// Ipopt's second-order derivative checker instead of a solve (opt.derivative_test_file).
bool set_derivative_test(Ipopt::OptionsList &o, const SolveOptions &opt)
{
	bool ok = o.SetStringValue("derivative_test", "second-order");
	ok = ok && o.SetNumericValue("derivative_test_perturbation", opt.derivative_test_perturbation);
	ok = ok && o.SetNumericValue("derivative_test_tol", 1e-4);
	ok = ok && o.SetStringValue("output_file", opt.derivative_test_file);
	ok = ok && o.SetIntegerValue("file_print_level", 5);
	ok = ok && o.SetIntegerValue("print_level", 0);
	return ok && o.SetIntegerValue("max_iter", 0);
}

// hylo's settings, then opt's own Ipopt options (which override them).
bool set_options(Ipopt::IpoptApplication &app, const SolveOptions &opt, const NlpSettings &s)
{
	Ipopt::OptionsList &o = *app.Options();
	bool ok = o.SetIntegerValue("print_level", 0);
	ok = ok && o.SetStringValue("sb", "yes");
	ok = ok && o.SetNumericValue("tol", opt.tol);
	ok = ok && o.SetIntegerValue("max_iter", opt.max_iter);
	ok = ok && o.SetStringValue("linear_solver", "mumps");
	ok = ok && o.SetIntegerValue("mumps_permuting_scaling", s.permuting_scaling);
	// AMF ordering, always: MUMPS's automatic choice takes it for small
	// systems (a training BVP's solve is the same bytes) and SCOTCH for
	// larger ones, whose random seed changed smoothed trajectories' last
	// bits from run to run (docs/decisions.md, "Smoothing is repeatable").
	ok = ok && o.SetIntegerValue("mumps_pivot_order", 2);
	ok = ok && o.SetStringValue("nlp_scaling_method", "user-scaling");
	if (opt.objective_scale != 1)
		ok = ok && o.SetNumericValue("obj_scaling_factor", opt.objective_scale);
	// Monotone barrier from a small start: the adaptive strategy hit the
	// iteration limit on stiff friction terms (docs/decisions.md).
	ok = ok && o.SetStringValue("mu_strategy", "monotone");
	// A warm start is already near the optimum: a small barrier keeps it there.
	ok = ok && o.SetNumericValue("mu_init", s.warm ? 1e-5 : 1e-2);
	if (s.warm) {
		ok = ok && o.SetNumericValue("bound_push", 1e-6);
		ok = ok && o.SetNumericValue("bound_frac", 1e-6);
	}
	if (!opt.derivative_test_file.empty())
		ok = ok && set_derivative_test(o, opt);
	for (const IpoptOption &io : opt.ipopt_options)
		ok = ok && set_ipopt_option(app, io);
	return ok;
}

Ipopt::SmartPtr<Ipopt::IpoptApplication> make_app(const SolveOptions &opt, const NlpSettings &s)
{
	Ipopt::SmartPtr<Ipopt::IpoptApplication> app = IpoptApplicationFactory();
	if (!set_options(*app, opt, s))
		throw std::logic_error("an Ipopt option was refused");
	// An empty options file name: never read ./ipopt.opt (docs/deps.md).
	if (app->Initialize("") != Ipopt::Solve_Succeeded)
		throw std::runtime_error("Ipopt failed to initialize");
	return app;
}

}  // namespace

namespace internal {

bool NlpStatus::succeeded() const
{
	return status == Ipopt::Solve_Succeeded || status == Ipopt::Solved_To_Acceptable_Level;
}

const char *NlpStatus::text() const
{
	switch (static_cast<Ipopt::ApplicationReturnStatus>(status)) {
	case Ipopt::Solve_Succeeded: return "solved";
	case Ipopt::Solved_To_Acceptable_Level: return "solved to acceptable level";
	case Ipopt::Infeasible_Problem_Detected: return "infeasible";
	case Ipopt::Maximum_Iterations_Exceeded: return "maximum iterations";
	case Ipopt::Restoration_Failed: return "restoration failed";
	case Ipopt::Error_In_Step_Computation: return "error in step computation";
	case Ipopt::Maximum_CpuTime_Exceeded: return "maximum cpu time";
	case Ipopt::Diverging_Iterates: return "diverging iterates";
	case Ipopt::Invalid_Number_Detected: return "invalid number";
	default: return "failed";
	}
}

StackedNlp::StackedNlp(std::vector<std::unique_ptr<PhaseBlock>> phases, std::vector<Row> rows)
	: ph_(std::move(phases)), rows_(std::move(rows))
{
	for (const auto &p : ph_) {
		vo_.push_back(nvar_);
		co_.push_back(ncon_);
		nvar_ += p->nvar();
		ncon_ += p->ncon();
	}
}

StackedNlp::~StackedNlp() = default;

NlpStatus StackedNlp::solve(const SolveOptions &opt, const std::vector<double> &start, const NlpSettings &settings)
{
	Ipopt::SmartPtr<IpoptTnlp> tnlp = new IpoptTnlp(*this, start);
	auto app = make_app(opt, settings);
	Ipopt::ApplicationReturnStatus st = app->OptimizeTNLP(tnlp);
	int it = Ipopt::IsValid(app->Statistics()) ? app->Statistics()->IterationCount() : 0;
	return {static_cast<int>(st), it};
}

std::vector<double> StackedNlp::refined(const std::vector<bool> &which) const
{
	std::vector<double> out;
	for (size_t k = 0; k < ph_.size(); k++) {
		const Number *z = z_.data() + vo_[k];
		std::vector<double> r = which[k] ? ph_[k]->refine(z) : std::vector<double>(z, z + ph_[k]->nvar());
		out.insert(out.end(), r.begin(), r.end());
	}
	return out;
}

}  // namespace internal

IpoptOption parse_ipopt_option(const std::string &text)
{
	size_t eq = text.find('=');
	if (eq == std::string::npos || eq == 0)
		throw std::invalid_argument("'" + text + "' is not NAME=VALUE");
	IpoptOption o{text.substr(0, eq), text.substr(eq + 1)};
	// No console journal: Ipopt would print the option's documentation.
	Ipopt::SmartPtr<Ipopt::IpoptApplication> app = new Ipopt::IpoptApplication(false);
	if (!Ipopt::IsValid(app->RegOptions()->GetOption(o.name)))
		throw std::invalid_argument("Ipopt has no option '" + o.name + "'");
	if (!set_ipopt_option(*app, o))
		throw std::invalid_argument("Ipopt refuses '" + o.value + "' for " + o.name +
					    " (its type, range or list of values)");
	return o;
}

}  // namespace hylo::trainer
