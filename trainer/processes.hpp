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
// time, and hands their results to done(first, results) a chunk at a time,
// items [first, first + chunk) in index order, as soon as the chunk and every
// one before it have finished. The workers go on with the next chunk
// meanwhile (at most one chunk ahead), so a slow item does not leave the
// other workers idle at a chunk's end. An item whose process died, or whose
// result is longer than max_bytes, comes back empty. If done throws, the
// running children are killed and the exception propagates.
void fork_chunks(size_t n, int jobs, size_t chunk, const std::function<std::string(size_t)> &f,
		 const std::function<void(size_t, std::vector<std::string> &)> &done, size_t max_bytes = 16384);

// fork_chunks with one chunk: every result, in index order.
std::vector<std::string> fork_each(size_t n, int jobs, const std::function<std::string(size_t)> &f,
				   size_t max_bytes = 16384);

}  // namespace hylo::trainer
