#include "trainer/processes.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <csignal>
#include <cstring>
#include <map>
#include <stdexcept>
#include <sys/mman.h>
#ifdef __linux__
#include <sys/prctl.h>
#endif
#include <sys/wait.h>
#include <unistd.h>

namespace hylo::trainer {

namespace {

// Results go to shared memory, one slot per item of a ring: a length, then
// bytes.
class Slots {
public:
	Slots(size_t count, size_t max_bytes) : max_(max_bytes), slot_(sizeof(uint64_t) + max_bytes), bytes_(count * slot_)
	{
		void *mem = mmap(nullptr, bytes_, PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0);
		if (mem == MAP_FAILED)
			throw std::runtime_error(std::string("mmap: ") + std::strerror(errno));
		base_ = static_cast<char *>(mem);
	}
	~Slots() { munmap(base_, bytes_); }
	Slots(const Slots &) = delete;
	Slots &operator=(const Slots &) = delete;

	// Empty until a child puts a result there.
	void clear(size_t k) { std::memset(base_ + k * slot_, 0, sizeof(uint64_t)); }
	bool put(size_t k, const std::string &r)
	{
		if (r.size() > max_)
			return false;
		uint64_t len = r.size();
		std::memcpy(base_ + k * slot_ + sizeof len, r.data(), r.size());
		std::memcpy(base_ + k * slot_, &len, sizeof len);
		return true;
	}
	std::string get(size_t k) const
	{
		uint64_t len = 0;
		std::memcpy(&len, base_ + k * slot_, sizeof len);
		return std::string(base_ + k * slot_ + sizeof len, static_cast<size_t>(std::min<uint64_t>(len, max_)));
	}

private:
	size_t max_, slot_, bytes_;
	char *base_ = nullptr;
};

}  // namespace

void fork_chunks(size_t n, int jobs, size_t chunk, const std::function<std::string(size_t)> &f,
		 const std::function<void(size_t, std::vector<std::string> &)> &done, size_t max_bytes)
{
	if (n == 0)
		return;
	chunk = std::clamp<size_t>(chunk, 1, n);
	const size_t ring = std::min(n, 2 * chunk);   // the chunk being gathered and the next
	const size_t limit = static_cast<size_t>(std::max(1, jobs));
	Slots slots(ring, max_bytes);
	std::map<pid_t, size_t> running;              // child -> item
	std::vector<bool> finished(n, false);
	size_t next = 0, first = 0;
	auto kill_children = [&] {
		for (const auto &[pid, item] : running) {
			kill(pid, SIGKILL);
			waitpid(pid, nullptr, 0);
		}
		running.clear();
	};
	try {
		while (first < n) {
			const size_t end = std::min(n, first + chunk);
			if (std::all_of(finished.begin() + first, finished.begin() + end, [](bool f) { return f; })) {
				const size_t at = first;
				std::vector<std::string> out;
				for (size_t i = at; i < end; i++)
					out.push_back(slots.get(i % ring));
				first = end;
				done(at, out);
				continue;
			}
			if (next < std::min(n, first + ring) && running.size() < limit) {
				slots.clear(next % ring);
				std::fflush(nullptr);
				const pid_t parent = getpid();
				pid_t pid = fork();
				if (pid < 0)
					throw std::runtime_error(std::string("fork: ") + std::strerror(errno));
				if (pid == 0) {
#ifdef __linux__
					// A worker dies with the process that forked it
					// (killed by a job scheduler or a test), instead of
					// solving on for no one.
					if (prctl(PR_SET_PDEATHSIG, SIGKILL) != 0 || getppid() != parent)
						_exit(1);
#else
					(void)parent;
#endif
					int code = 1;
					try {
						code = slots.put(next % ring, f(next)) ? 0 : 1;
					} catch (...) {
					}
					_exit(code);
				}
				running[pid] = next++;
				continue;
			}
			pid_t pid = waitpid(-1, nullptr, 0);
			if (pid < 0) {
				if (errno == EINTR)
					continue;
				throw std::runtime_error(std::string("waitpid: ") + std::strerror(errno));
			}
			auto it = running.find(pid);
			if (it == running.end())
				continue;   // not one of ours
			finished[it->second] = true;
			running.erase(it);
		}
	} catch (...) {
		kill_children();
		throw;
	}
}

std::vector<std::string> fork_each(size_t n, int jobs, const std::function<std::string(size_t)> &f,
				   size_t max_bytes)
{
	std::vector<std::string> out;
	fork_chunks(n, jobs, n, f, [&out](size_t, std::vector<std::string> &r) { out = std::move(r); }, max_bytes);
	return out;
}

}  // namespace hylo::trainer
