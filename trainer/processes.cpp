#include "trainer/processes.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <sys/mman.h>
#include <sys/wait.h>
#include <unistd.h>

namespace hylo::trainer {

std::vector<std::string> fork_each(size_t n, int jobs, const std::function<std::string(size_t)> &f,
				   size_t max_bytes)
{
	std::vector<std::string> out(n);
	if (n == 0)
		return out;
	// Results go to shared memory, one slot per item: a length, then bytes.
	const size_t slot = sizeof(uint64_t) + max_bytes;
	const size_t bytes = n * slot;
	void *mem = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0);
	if (mem == MAP_FAILED)
		throw std::runtime_error(std::string("mmap: ") + std::strerror(errno));
	auto *base = static_cast<char *>(mem);
	size_t next = 0, running = 0;
	const size_t limit = static_cast<size_t>(std::max(1, jobs));
	while (next < n || running > 0) {
		if (next < n && running < limit) {
			std::fflush(nullptr);
			pid_t pid = fork();
			if (pid < 0) {
				munmap(mem, bytes);
				throw std::runtime_error(std::string("fork: ") + std::strerror(errno));
			}
			if (pid == 0) {
				int code = 1;
				try {
					std::string r = f(next);
					if (r.size() <= max_bytes) {
						uint64_t len = r.size();
						std::memcpy(base + next * slot, &len, sizeof len);
						std::memcpy(base + next * slot + sizeof len, r.data(), r.size());
						code = 0;
					}
				} catch (...) {
				}
				_exit(code);
			}
			next++;
			running++;
			continue;
		}
		if (waitpid(-1, nullptr, 0) > 0)
			running--;
		else if (errno != EINTR) {
			munmap(mem, bytes);
			throw std::runtime_error(std::string("waitpid: ") + std::strerror(errno));
		}
	}
	for (size_t i = 0; i < n; i++) {
		uint64_t len = 0;
		std::memcpy(&len, base + i * slot, sizeof len);
		out[i].assign(base + i * slot + sizeof len, static_cast<size_t>(std::min<uint64_t>(len, max_bytes)));
	}
	munmap(mem, bytes);
	return out;
}

}  // namespace hylo::trainer
