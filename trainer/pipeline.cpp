#include "trainer/pipeline.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "hylo/region.h"
#include "trainer/collocation.hpp"
#include "trainer/files.hpp"
#include "trainer/model_table.hpp"
#include "trainer/modes.hpp"
#include "trainer/envelope.hpp"
#include "trainer/gather.hpp"
#include "trainer/repair.hpp"
#include "trainer/sha256.hpp"
#include "trainer/svr_export.hpp"
#include "trainer/switching.hpp"
#include "trainer/svr_fit.hpp"

namespace hylo::trainer {
namespace {

struct Rows {
	std::vector<double> x_conv, cost, x_all;
	std::vector<double> states;   // per row: x1 then x2, the record's xs_dim each
	std::vector<bool> feasible;
	size_t n = 0;
	size_t errors = 0;   // rows whose solve threw: read, never labels
	std::string sha256;   // of the bytes read: the header line and the n rows
};

std::string slurp(const std::string &path)
{
	std::ifstream f(path, std::ios::binary);
	if (!f)
		throw std::invalid_argument("cannot read the dataset " + path + " (run --stage gen first)");
	std::ostringstream ss;
	ss << f.rdbuf();
	return ss.str();
}

// Reads the header and at most max_rows rows: a dataset only grows at its
// end, so a model fitted on its first rows stays reproducible after more are
// generated. Rows store relative coordinates; the features are computed from
// them here, so new features need no new dataset.
Rows read_dataset(const std::string &path, hylo_mode mode, uint64_t max_rows)
{
	std::string text = slurp(path);
	std::istringstream in(text);
	std::string line;
	std::vector<std::string> cols = csv_columns(mode);
	if (!std::getline(in, line))
		throw std::invalid_argument(path + " is empty");
	if (line != csv_join(cols))
		throw std::invalid_argument(path + ":1: not a " + hylo_mode_str(mode) + " dataset (unexpected header)");
	size_t nr = 0;   // relative coordinates, f0, f1, ...
	for (const auto &c : cols)
		nr += c.size() > 1 && c[0] == 'f' && std::isdigit(static_cast<unsigned char>(c[1]));
	const size_t i_cost = csv_column(mode, "cost_j"), i_conv = csv_column(mode, "converged"),
		     i_status = csv_column(mode, "status");
	const size_t i_x1 = csv_column(mode, "x1_0"), dim = static_cast<size_t>(mode_desc(mode).xs_dim);
	Rows r;
	for (size_t lineno = 2; r.n < max_rows && std::getline(in, line); lineno++) {
		std::vector<std::string> f = csv_fields(line);
		if (f.size() != cols.size())
			throw std::invalid_argument(path + ":" + std::to_string(lineno) + ": " +
						    std::to_string(f.size()) + " fields, expected " +
						    std::to_string(cols.size()));
		std::vector<double> rel(nr);
		for (size_t k = 0; k < nr; k++) {
			char *e = nullptr;
			rel[k] = std::strtod(f[1 + k].c_str(), &e);
			if (*e || !std::isfinite(rel[k]))
				throw std::invalid_argument(path + ":" + std::to_string(lineno) + ": bad number '" +
							    f[1 + k] + "'");
		}
		for (size_t k = 0; k < 2 * dim; k++) {
			char *e = nullptr;
			double x = std::strtod(f[i_x1 + k].c_str(), &e);
			if (*e || !std::isfinite(x))
				throw std::invalid_argument(path + ":" + std::to_string(lineno) + ": bad number '" +
							    f[i_x1 + k] + "'");
			r.states.push_back(x);
		}
		r.n++;
		if (is_error_status(f[i_status])) {
			r.errors++;
			continue;
		}
		std::vector<double> feat = features_of_relative(mode, rel);
		bool conv = f[i_conv] == "1";
		double cost = std::strtod(f[i_cost].c_str(), nullptr);
		r.x_all.insert(r.x_all.end(), feat.begin(), feat.end());
		r.feasible.push_back(conv);
		if (conv) {
			r.x_conv.insert(r.x_conv.end(), feat.begin(), feat.end());
			r.cost.push_back(cost);
		}
	}
	std::streamoff end = in.tellg();
	r.sha256 = sha256_hex(end < 0 ? text : text.substr(0, static_cast<size_t>(end)));
	return r;
}

// The draw's trained region (trained_region), checked against the rows:
// every state of every row must lie in it, and every displacement within
// the draw's max_distance_m where the draw bounds it (not the double
// integrator's, whose positions are bounded instead). Throws naming the
// first row and coordinate outside.
TrainedRegion checked_region(const ModeParams &p, const Rows &rows, const std::string &path)
{
	const TrainedRegion region = trained_region(p);
	const hylo_mode mode = p.id;
	const hylo_mode_desc &d = mode_desc(p.id);
	const size_t dim = d.xs_dim;
	hylo_svr_model m{};
	// The phase plane's draw bounds positions, not displacements.
	m.max_distance_m = d.domain == HYLO_DOMAIN_PHASE ? 0 : p.sampling.max_distance_m;
	m.speed_min_mps = p.sampling.speed_min_mps;
	m.speed_max_mps = p.sampling.speed_max_mps;
	m.state_bounded = region.bounded;
	for (size_t k = 0; k < region.min.size(); k++) {
		m.state_min[k] = region.min[k];
		m.state_max[k] = region.max[k];
	}
	for (size_t i = 0; i < rows.n; i++) {
		double a[HYLO_XS_DIM] = {0}, b[HYLO_XS_DIM] = {0};
		std::copy_n(&rows.states[2 * dim * i], dim, a);
		std::copy_n(&rows.states[2 * dim * i + dim], dim, b);
		hylo_region_miss miss;
		if (!hylo_region_edge(&m, mode, a, b, &miss)) {
			char what[200];
			hylo_region_describe(mode, &miss, what, sizeof what);
			throw std::invalid_argument(path + ": row " + std::to_string(i) + " (" +
						    (miss.end ? "x2" : "x1") + "): " + what +
						    " of the draw (trained_region, trainer/dataset.cpp)");
		}
	}
	return region;
}

void set_region(SvrExport &m, const TrainedRegion &r)
{
	m.state_bounded = r.bounded;
	m.state_min = r.min;
	m.state_max = r.max;
}

// The model fit --compare names, read before the fit so that a wrong file
// is an error at once: a header of this robot and mode.
SvrExport compared_model(const std::string &header, const std::string &robot, hylo_mode mode, int nf)
{
	SvrExport other;
	try {
		other = parse_svr_header(slurp(header));
	} catch (const std::exception &e) {
		throw std::invalid_argument("--compare " + header + ": " + e.what());
	}
	if (other.robot != robot || other.mode != mode || other.n_features != nf)
		throw std::invalid_argument("--compare " + header + ": a " + other.robot + " " + hylo_mode_str(other.mode) +
					    " model, not " + robot + " " + hylo_mode_str(mode));
	return other;
}

// other's held-out errors on the rows a fit held out: what a refit is
// compared with (issue #35).
Accuracy held_out_of(const SvrExport &other, int nf, const Rows &rows, const std::vector<size_t> &test)
{
	const hylo_svr_model view = model_view(other, "compared");
	std::vector<double> pred;
	for (size_t r : test)
		pred.push_back(hylo_svr_predict(&view, &rows.x_conv[r * static_cast<size_t>(nf)]));
	return accuracy_of(pred, rows.cost, test);
}

int fit_stage(const RobotParams &robot, const PipelineOptions &opt)
{
	GenOptions g = opt.gen;
	g.shard = g.shards = 1;
	std::string path = dataset_path(g);
	std::string meta = slurp(path + ".meta");
	if (meta.find("params_sha256: " + robot.labels_sha256) == std::string::npos ||
	    meta.find("robot: " + robot.robot + "\n") == std::string::npos)
		throw std::invalid_argument(path + " was generated from another robot file than " + robot.path);
	Rows rows = read_dataset(path, g.mode, g.samples);
	const ModeParams &p = robot.mode(g.mode);
	int nf = feature_count(g.mode);
	std::optional<SvrExport> compared;
	if (!opt.compare.empty())
		compared = compared_model(opt.compare, robot.robot, g.mode, nf);
	FitOptions fo;
	fo.seed = g.seed;
	fo.jobs = g.jobs;
	fo.debug = g.solve.debug;   // trainer --debug: the solver's and the fit's traces
	fo.symmetries = feature_symmetries(g.mode);
	fo.feature_weights = feature_weights(g.mode);
	SvrExport m;
	FitReport rep = fit_cost(nf, rows.x_conv, rows.cost, fo, m);
	m.robot = robot.robot;
	m.mode = g.mode;
	const CostFloor floor = with_model(p, robot.g, [](const auto &model) { return cost_floor(model); });
	m.cost_floor_per_m = floor.per_m;
	m.cost_floor_j = floor.j;
	m.max_distance_m = p.sampling.max_distance_m;
	m.speed_min_mps = p.sampling.speed_min_mps;
	m.speed_max_mps = p.sampling.speed_max_mps;
	set_region(m, checked_region(p, rows, path));
	std::ostringstream acc;
	ClassifierReport crep;
	bool have_classifier = false;
	try {
		ClassifierExport c;
		crep = fit_feasibility(nf, rows.x_all, rows.feasible, fo, c);
		m.feasibility = c;
		have_classifier = true;
	} catch (const std::invalid_argument &e) {
		std::fprintf(stderr, "trainer: no feasibility classifier: %s\n", e.what());
	}
	const std::string held_out = describe(rep.held_out);
	m.provenance = {
		{"robot file", "trainer/params/" + robot.robot + ".yaml"},   // location-independent
		{"robot file sha256", robot.labels_sha256},
		{"dataset sha256", rows.sha256},   // the whole file unless rows were appended since
		{"samples", std::to_string(rows.n) + " (" + std::to_string(rows.cost.size()) + " converged" +
				    (rows.errors ? ", " + std::to_string(rows.errors) + " errors left out" : "") + ")"},
		{"seed", std::to_string(g.seed)},
		{"held-out errors", held_out},
		{"svr", "C " + format_double(rep.C) + ", gamma " + format_double(rep.gamma) + ", epsilon " +
				format_double(rep.epsilon) + ", " + std::to_string(rep.n_sv) + " support vectors"},
		{"feasibility accuracy", have_classifier ? format_double(crep.accuracy) : "none"},
		{"hylo version", kHyloVersion},
	};
	if (!fo.symmetries.empty())
		m.provenance.insert(m.provenance.end() - 1,
				    {"mirror images", std::to_string(fo.symmetries.size()) +
							      " per training pair (feature_symmetries, trainer/dataset.cpp)"});
	if (!fo.feature_weights.empty()) {
		std::string w;
		for (double v : fo.feature_weights)
			w += (w.empty() ? "" : " ") + format_double(v);
		m.provenance.insert(m.provenance.end() - 1, {"feature weights", w + " (feature_weights, trainer/dataset.cpp)"});
	}
	if (mode_desc(g.mode).air) {
		// Takeoff and landing (docs/models.md section 6): hover at h to hover at h+1, and back.
		TakeoffLanding tl = takeoff_landing(robot, g.solve);
		m.constants = {{"TAKEOFF_J", tl.takeoff_j, "ground rest -> hover 1 m above [J]"},
			       {"LANDING_J", tl.landing_j, "hover 1 m above -> ground rest [J]"}};
	}
	std::string header = g.out_dir + "/" + robot.robot + "_" + hylo_mode_str(g.mode) + ".h";
	write_svr_header(m, header);
	std::ostringstream js;
	js << "{\"robot\":\"" << robot.robot << "\",\"mode\":\"" << hylo_mode_str(g.mode) << "\",\"samples\":" << rows.n
	   << ",\"converged\":" << rows.cost.size() << ",\"n_train\":" << rep.n_train
	   << ",\"n_test\":" << rep.n_test << ",\"n_sv\":" << rep.n_sv << ",\"C\":" << format_double(rep.C)
	   << ",\"gamma\":" << format_double(rep.gamma) << ",\"epsilon\":" << format_double(rep.epsilon)
	   << ",\"mae_j\":" << format_double(rep.held_out.mae)
	   << ",\"median_rel_error\":" << format_double(rep.held_out.median)
	   << ",\"p95_rel_error\":" << format_double(rep.held_out.p95)
	   << ",\"fit_s\":" << format_double(rep.fit_seconds)
	   << ",\"feasibility_accuracy\":" << (have_classifier ? format_double(crep.accuracy) : "null")
	   << "}\n";
	write_file_atomically(g.out_dir + "/" + hylo_mode_str(g.mode) + ".fit.json", js.str());
	if (rows.errors)
		std::fprintf(stderr, "trainer: fit %s %s: %zu rows whose solve ended in an error (status 'error: ...') "
				     "left out\n", robot.robot.c_str(), hylo_mode_str(g.mode), rows.errors);
	std::printf("fit %s %s: %zu of %zu samples converged; %zu SVs; held-out %s; feasibility %s; %.1f s\n",
		    robot.robot.c_str(), hylo_mode_str(g.mode), rows.cost.size(), rows.n, rep.n_sv, held_out.c_str(),
		    have_classifier ? format_double(crep.accuracy).c_str() : "none", rep.fit_seconds);
	if (compared) {
		const Accuracy a = held_out_of(*compared, nf, rows, rep.test_rows);
		std::printf("fit %s %s: %s (%zu SVs) on the same %zu held-out rows: %s\n", robot.robot.c_str(),
			    hylo_mode_str(g.mode), opt.compare.c_str(), compared->coef.size(), rep.test_rows.size(),
			    describe(a).c_str());
	}
	return 0;
}

// Reads the model fit wrote (its header is the hand-off), adds the
// envelope where the mode has one (trainer/envelope.hpp; any envelope the
// header has is computed afresh) and writes the header into models_dir.
int export_stage(const RobotParams &robot, const PipelineOptions &opt)
{
	std::string name = robot.robot + "_" + hylo_mode_str(opt.gen.mode) + ".h";
	std::string path = opt.gen.out_dir + "/" + name;
	SvrExport m;
	try {
		m = parse_svr_header(slurp(path));
	} catch (const std::invalid_argument &e) {
		throw std::invalid_argument(path + ": " + e.what());
	}
	if (m.robot != robot.robot || m.mode != opt.gen.mode)
		throw std::invalid_argument(path + " holds the " + m.robot + " " + hylo_mode_str(m.mode) + " model");
	for (const char *key : {"envelope", "turn table"}) {
		auto line = std::find_if(m.provenance.begin(), m.provenance.end(),
					 [&](const auto &p) { return p.first == key; });
		if (line != m.provenance.end())
			m.provenance.erase(line);
	}
	m.envelope.reset();
	m.turn_envelope.reset();
	EnvelopeOptions eo;
	eo.jobs = opt.gen.jobs;
	eo.progress = opt.gen.progress;
	eo.debug = opt.gen.solve.debug;   // trainer --debug
	auto add = [&](const char *key, const EnvelopeReport &rep) {
		// Before the version line, which stays last.
		auto at = !m.provenance.empty() && m.provenance.back().first == "hylo version"
				  ? m.provenance.end() - 1 : m.provenance.end();
		m.provenance.insert(at, {key, rep.provenance()});
		std::printf("%s %s %s: %s; %.1f s (table %.1f s, margin %.1f s, check %.1f s)\n", key,
			    robot.robot.c_str(), hylo_mode_str(opt.gen.mode), rep.provenance().c_str(),
			    rep.table_seconds + rep.margin_seconds + rep.check_seconds, rep.table_seconds,
			    rep.margin_seconds, rep.check_seconds);
	};
	if (envelope_applies(m)) {
		EnvelopeReport rep = compute_envelope(m, eo);
		m.envelope = rep.table;
		add("envelope", rep);
	}
	if (turn_table_applies(m)) {
		EnvelopeReport rep = compute_turn_table(m, eo);
		m.turn_envelope = rep.table;
		add("turn table", rep);
	}
	write_svr_header(m, opt.models_dir + "/" + name);
	std::printf("exported %s/%s\n", opt.models_dir.c_str(), name.c_str());
	return 0;
}

// The value of provenance line `key: value` of a header's leading comment.
std::string provenance_value(const std::string &text, const std::string &key, const std::string &path)
{
	const std::string tag = "\n * " + key + ": ";
	size_t at = text.find(tag);
	if (at == std::string::npos)
		throw std::invalid_argument(path + " has no provenance line '" + key + "'");
	at += tag.size();
	return text.substr(at, text.find('\n', at) - at);
}

// Writes the trained region into the committed header models_dir/<robot>_<mode>.h
// (in this trainer's format) from the dataset rows it was fitted on and the
// draw's definition; nothing else changes: no refit, no new envelope.
int region_stage(const RobotParams &robot, const PipelineOptions &opt)
{
	const hylo_mode mode = opt.gen.mode;
	const std::string header = opt.models_dir + "/" + robot.robot + "_" + hylo_mode_str(mode) + ".h";
	const std::string text = slurp(header);
	GenOptions g = opt.gen;
	g.shard = g.shards = 1;
	const std::string path = dataset_path(g);
	const uint64_t n = std::stoull(provenance_value(text, "samples", header));
	Rows rows = read_dataset(path, mode, n);
	const std::string sha = provenance_value(text, "dataset sha256", header);
	if (rows.n != n || rows.sha256 != sha)
		throw std::invalid_argument(path + ": its first " + std::to_string(n) + " rows are not those " +
					    header + " was fitted on (dataset sha256 " + sha + ")");
	if (provenance_value(text, "robot file sha256", header) != robot.labels_sha256)
		throw std::invalid_argument(header + " was fitted from another robot file than " + robot.path);
	const TrainedRegion r = checked_region(robot.mode(mode), rows, path);
	write_file_atomically(header, header_with_region(text, r.bounded, r.min, r.max));
	std::printf("region %s %s: %zu rows inside; written into %s\n", robot.robot.c_str(), hylo_mode_str(mode),
		    rows.n, header.c_str());
	return 0;
}

}  // namespace

uint64_t default_samples(hylo_mode mode, int draws)
{
	const Supplement sup = supplement(mode, draws);
	return sup.from + sup.pairs;
}

uint64_t default_samples(const GenOptions &opt)
{
	return std::max(default_samples(opt.mode, opt.draws), existing_rows(opt));
}

int run_pipeline(const RobotParams &robot, const PipelineOptions &opt, const std::string &stage)
{
	// A shard is a slice of the stream, not a dataset: fitting it, or a stale
	// unsharded file beside it, would be wrong. The gather step makes the dataset.
	if (opt.gen.shards > 1 && stage != "gen" && stage != "gather")
		throw std::invalid_argument("--shard K/N only generates (--stage gen); gather the N shards with "
					    "--stage gather --shards N, then run --stage " + stage + " without --shard");
	if (stage == "gather") {
		GatherReport r = gather(robot, opt.gen);
		std::printf("gather %s %s: %d shards of %llu samples, seed %llu\n%s", robot.robot.c_str(),
			    hylo_mode_str(opt.gen.mode), opt.gen.shards, static_cast<unsigned long long>(opt.gen.samples),
			    static_cast<unsigned long long>(opt.gen.seed), gather_text(r).c_str());
		if (!r.foreign.empty())
			std::fprintf(stderr, "trainer: gather: %zu shard(s) not of this stream or settings; see above\n",
				     r.foreign.size());
		else if (!r.resubmit.empty())
			std::fprintf(stderr, "trainer: gather: %zu of %d shards to resubmit\n", r.resubmit.size(),
				     opt.gen.shards);
		return !r.foreign.empty() ? 2 : !r.resubmit.empty() ? 1 : 0;
	}
	if (stage == "gen" || stage == "all") {
		RepairOptions ro;
		ro.gen = opt.gen;
		GenSummary s = opt.solutions ? generate_with_solutions(robot, ro) : generate(robot, opt.gen);
		std::printf("gen %s %s: %llu samples in %s (%llu resumed), %llu converged, %llu rejected, %.1f s\n",
			    robot.robot.c_str(), hylo_mode_str(opt.gen.mode),
			    static_cast<unsigned long long>(s.done + s.resumed_from), s.path.c_str(),
			    static_cast<unsigned long long>(s.resumed_from),
			    static_cast<unsigned long long>(s.converged),
			    static_cast<unsigned long long>(s.rejected), s.seconds);
		if (s.errors)
			std::fprintf(stderr, "trainer: gen %s %s: %llu samples ended in an error, not an outcome "
					     "(see above; their rows are not labels)\n",
				     robot.robot.c_str(), hylo_mode_str(opt.gen.mode), static_cast<unsigned long long>(s.errors));
	}
	if (stage == "remesh") {
		RepairOptions ro;
		ro.gen = opt.gen;
		ro.remesh = true;
		RepairSummary s = repair(robot, ro);
		if (s.already)
			std::printf("remesh %s %s: %s records this remesh of its first %llu rows already; nothing to do\n",
				    robot.robot.c_str(), hylo_mode_str(opt.gen.mode), s.path.c_str(),
				    static_cast<unsigned long long>(s.rows));
		else
			std::printf("remesh %s %s: %llu rows of %s (%llu kept from an earlier pass, %llu done now), "
				    "%llu labels from a finer mesh: %llu lower by more than 0.5%% (median %.2f%%, "
				    "largest %.2f%%), %llu higher by more than 0.5%%; CPU %.1f s; %.1f s\n",
				    robot.robot.c_str(), hylo_mode_str(opt.gen.mode), static_cast<unsigned long long>(s.rows),
				    s.path.c_str(), static_cast<unsigned long long>(s.kept),
				    static_cast<unsigned long long>(s.repaired_now),
				    static_cast<unsigned long long>(s.relabelled),
				    static_cast<unsigned long long>(s.lowered), 100 * s.median_drop, 100 * s.max_drop,
				    static_cast<unsigned long long>(s.raised), s.warm_cpu_s, s.seconds);
	}
	if (stage == "repair") {
		RepairOptions ro;
		ro.gen = opt.gen;
		ro.neighbours = opt.neighbours;
		RepairSummary s = repair(robot, ro);
		if (s.already) {
			std::printf("repair %s %s: %s records this repair of its first %llu rows already; nothing to do\n",
				    robot.robot.c_str(), hylo_mode_str(opt.gen.mode), s.path.c_str(),
				    static_cast<unsigned long long>(s.rows));
		} else {
			std::printf("repair %s %s: %llu rows of %s (%llu kept from an earlier pass, %llu solved again, "
				    "%llu repaired now), %llu labels "
				    "lowered by more than 0.5%% (%llu by the solver alone, %llu by a neighbour's "
				    "warm start; median %.2f%%, largest %.2f%%), %llu newly converged, %llu sidecar paths "
				    "replaced by a neighbour's; CPU %.1f s solving again, %.1f s warm-started; %.1f s\n",
				    robot.robot.c_str(), hylo_mode_str(opt.gen.mode), static_cast<unsigned long long>(s.rows),
				    s.path.c_str(), static_cast<unsigned long long>(s.kept),
				    static_cast<unsigned long long>(s.solved_again),
				    static_cast<unsigned long long>(s.repaired_now),
				    static_cast<unsigned long long>(s.lowered),
				    static_cast<unsigned long long>(s.lowered_by_solver),
				    static_cast<unsigned long long>(s.lowered_by_neighbours), 100 * s.median_drop,
				    100 * s.max_drop, static_cast<unsigned long long>(s.newly_converged),
				    static_cast<unsigned long long>(s.solutions_replaced), s.solve_cpu_s,
				    s.warm_cpu_s, s.seconds);
		}
	}
	if (stage == "fit" || stage == "all")
		fit_stage(robot, opt);
	if (stage == "export" || stage == "all")
		export_stage(robot, opt);
	if (stage == "region")
		region_stage(robot, opt);
	return 0;
}

}  // namespace hylo::trainer
