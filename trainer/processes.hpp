// One forked process per work item, a few at a time.
//
// Ipopt is not thread-safe, and a solve must not depend on what ran before it:
// OpenBLAS's kernels sum in an order that depends on the alignment of their
// buffers, so a long-lived worker's iterates (and whether a solve converged)
// changed with the solves it had done before. A fresh fork per item makes each
// result a function of its inputs only, whatever --jobs is.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace hylo::trainer {

// Runs f(0) ... f(n-1), each in its own child process, at most `jobs` at a
// time, and returns their results in index order. An item whose process died,
// or whose result is longer than max_bytes, comes back empty.
std::vector<std::string> fork_each(size_t n, int jobs, const std::function<std::string(size_t)> &f,
				   size_t max_bytes = 16384);

}  // namespace hylo::trainer
