#include "trainer/gather.hpp"

#include <stdexcept>
#include <unistd.h>

namespace hylo::trainer {
namespace {


std::string header_line(hylo_mode mode)
{
	return csv_join(csv_columns(mode)) + "\n";
}

bool exists(const std::string &path) { return access(path.c_str(), F_OK) == 0; }

// Checks shard k of opt; text receives its bytes when it is complete.
ShardCheck check_shard(const RobotParams &robot, GenOptions o, int k, std::string &text)
{
	o.shard = k;
	const uint64_t n = static_cast<uint64_t>(o.shards);
	const uint64_t lo = o.samples * static_cast<uint64_t>(k - 1) / n, hi = o.samples * static_cast<uint64_t>(k) / n;
	ShardCheck c;
	c.shard = k;
	c.path = dataset_path(o);
	c.want = hi - lo;
	const std::string meta_path = c.path + ".meta";
	auto set = [&](ShardCheck::State s, const std::string &why) {
		c.state = s;
		c.detail = why;
		return c;
	};
	if (!exists(c.path) && !exists(meta_path))
		return set(ShardCheck::missing, "no " + c.path);
	if (!exists(meta_path))
		return set(ShardCheck::foreign, "no " + meta_path + " beside it");
	const std::string meta = read_file(meta_path), want_meta = internal::meta_text(robot, o);
	if (meta != want_meta)
		return set(ShardCheck::foreign, "made under other settings (its .meta vs these options): " +
							internal::meta_differences(meta, want_meta));
	text = read_file(c.path);
	// The trainer writes the .meta first, then the header (shard 1) and rows.
	const std::string header = k == 1 ? header_line(o.mode) : "";
	if (text.empty() && c.want > 0)
		return set(ShardCheck::incomplete, "0 of " + std::to_string(c.want) + " rows");
	if (text.compare(0, header.size(), header) != 0) {
		if (text.size() < header.size() && header.compare(0, text.size(), text) == 0)
			return set(ShardCheck::torn, "a torn header (" + std::to_string(text.size()) + " bytes)");
		return set(ShardCheck::foreign, std::string("line 1 is not the header of a ") + hylo_mode_str(o.mode) + " dataset");
	}
	const size_t ncols = csv_columns(o.mode).size();
	size_t pos = header.size();
	for (size_t eol; (eol = text.find('\n', pos)) != std::string::npos; pos = eol + 1) {
		const std::string where = c.path + ":" + std::to_string(c.rows + (k == 1 ? 2 : 1)) + ": ";
		if (c.rows == c.want)
			return set(ShardCheck::foreign, where + "more rows than the " + std::to_string(c.want) +
								" of shard " + std::to_string(k) + "/" +
								std::to_string(o.shards));
		std::vector<std::string> f = csv_fields(text.substr(pos, eol - pos));
		if (f.size() != ncols)
			return set(ShardCheck::foreign, where + std::to_string(f.size()) + " fields, expected " +
								std::to_string(ncols));
		if (f[0] != std::to_string(lo + c.rows))
			return set(ShardCheck::foreign, where + "sample " + f[0] + ", expected sample " +
								std::to_string(lo + c.rows));
		c.rows++;
	}
	const std::string counted = std::to_string(c.rows) + " of " + std::to_string(c.want) + " rows";
	if (pos < text.size())
		return set(ShardCheck::torn, "a torn last row (" + std::to_string(text.size() - pos) +
						     " bytes) after " + counted);
	if (c.rows < c.want)
		return set(ShardCheck::incomplete, counted);
	return c;
}

std::string list(const std::vector<int> &v)
{
	std::string s;
	for (int k : v)
		s += (s.empty() ? "" : ",") + std::to_string(k);
	return s;
}

}  // namespace

GatherReport gather(const RobotParams &robot, const GenOptions &opt)
{
	if (opt.shards < 2)
		throw std::invalid_argument("gather needs N >= 2 shards (an unsharded run writes the dataset itself)");
	GatherReport r;
	GenOptions u = opt;
	u.shard = u.shards = 1;
	r.path = dataset_path(u);
	// The unsharded dataset may be there already (as generation would, one of
	// other settings with every row asked for is taken as it is), and one that
	// the merge could not replace is reported before any shard is generated.
	const std::string meta_path = r.path + ".meta", meta = internal::meta_text(robot, u);
	const std::string old_meta = read_file(meta_path), existing = read_file(r.path);
	if (exists(r.path) || exists(meta_path)) {
		const uint64_t rows = internal::resume_point(existing, header_line(opt.mode)).rows;
		if ((old_meta == meta || internal::same_stream(old_meta, meta)) && rows >= opt.samples) {
			r.merged = r.unchanged = true;
			r.rows = opt.samples;
			return r;
		}
		if (old_meta != meta)
			throw std::invalid_argument(r.path + " exists and was made under other settings (" +
						    internal::meta_differences(old_meta, meta) + "); move it away to gather");
	}
	std::string merged;
	for (int k = 1; k <= opt.shards; k++) {
		std::string text;
		ShardCheck c = check_shard(robot, opt, k, text);
		if (c.state == ShardCheck::foreign)
			r.foreign.push_back(k);
		else if (c.state != ShardCheck::ok)
			r.resubmit.push_back(k);
		else if (r.foreign.empty() && r.resubmit.empty())
			merged += text;
		r.rows += c.rows;
		r.shards.push_back(c);
	}
	if (!r.foreign.empty() || !r.resubmit.empty())
		return r;
	// A shorter unsharded dataset of this stream (an interrupted run) is
	// replaced by the merged one, which starts with its rows.
	if (merged.compare(0, existing.size(), existing) != 0)
		throw std::invalid_argument(r.path + " exists and holds other rows than the shards; move it away to gather");
	// The unsharded stream's .meta (a shard's without its samples and shard
	// lines) first: a dataset without one would not be resumed or fitted.
	write_file_atomically(meta_path, meta);
	write_file_atomically(r.path, merged);
	r.merged = true;
	return r;
}

std::string gather_text(const GatherReport &r)
{
	static const char *names[] = {"ok", "missing", "incomplete", "torn", "not this stream's"};
	std::string out;
	const std::string n = std::to_string(r.shards.size()), rows = std::to_string(r.rows);
	for (const ShardCheck &c : r.shards) {
		out += "shard " + std::to_string(c.shard) + "/" + n + " " + names[c.state] + ": " +
		       (c.state == ShardCheck::ok ? std::to_string(c.rows) + " rows, " + c.path : c.detail) + "\n";
	}
	if (!r.foreign.empty())
		out += "not this dataset's: shards " + list(r.foreign) + "; gather with the options they were made "
		       "with, or move them and their .meta away and resubmit them\n";
	if (!r.resubmit.empty())
		out += "resubmit: --array=" + list(r.resubmit) + "\n";
	if (r.merged)
		out += r.unchanged ? r.path + " already holds the " + rows + " rows of this stream; no shard needed\n"
				   : "merged " + n + " shards, " + rows + " rows, into " + r.path + "\n";
	return out;
}

}  // namespace hylo::trainer
