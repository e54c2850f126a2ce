// A C++ benchmark's figures for BUILD/bench/results.json (tools/bench/run
// merges every benchmark's file): a JSON list of {name, value, unit,
// reference, reference_value, ratio}, nulls where a figure has no reference
// or is not a number.
#ifndef HYLO_BENCH_RESULTS_HPP
#define HYLO_BENCH_RESULTS_HPP

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

struct BenchRow {
	std::string name;
	double value = NAN;
	std::string unit;
	std::string reference;         // empty: none
	double reference_value = NAN;
	// reference_value / value unless given: above 1, hylo does better on a
	// lower-is-better figure (time, energy, edges).
	double ratio = NAN;
};

inline BenchRow bench_row(const std::string &name, double value, const std::string &unit)
{
	return {name, value, unit, "", NAN, NAN};
}

inline BenchRow bench_compared(const std::string &name, double value, const std::string &unit,
			       const std::string &reference, double reference_value, double ratio = NAN)
{
	if (std::isnan(ratio) && value > 0)
		ratio = reference_value / value;
	return {name, value, unit, reference, reference_value, ratio};
}

namespace bench_json {
inline std::string text(const std::string &s)
{
	std::string out = "\"";
	for (char c : s)
		out += c == '"' || c == '\\' ? std::string("\\") + c : std::string(1, c);
	return out + "\"";
}

inline std::string number(double x)
{
	if (!std::isfinite(x))
		return "null";
	char buf[40];
	std::snprintf(buf, sizeof buf, "%.10g", x);
	return buf;
}
}  // namespace bench_json

// Writes rows to path; false when the file cannot be written.
inline bool write_bench_results(const std::string &path, const std::vector<BenchRow> &rows)
{
	using namespace bench_json;
	std::string out = "[\n";
	for (size_t i = 0; i < rows.size(); i++) {
		const BenchRow &r = rows[i];
		const bool ref = !r.reference.empty() && std::isfinite(r.reference_value);
		out += "  {\"name\": " + text(r.name) + ", \"value\": " + number(r.value) + ", \"unit\": " + text(r.unit) +
		       ", \"reference\": " + (ref ? text(r.reference) : "null") +
		       ", \"reference_value\": " + (ref ? number(r.reference_value) : "null") +
		       ", \"ratio\": " + (ref ? number(r.ratio) : "null") + "}" + (i + 1 < rows.size() ? ",\n" : "\n");
	}
	out += "]\n";
	std::FILE *f = std::fopen(path.c_str(), "w");
	if (!f)
		return false;
	const bool ok = std::fwrite(out.data(), 1, out.size(), f) == out.size();
	return std::fclose(f) == 0 && ok;
}

#endif
