#include "trainer/numerics.hpp"

#include <gnu/libc-version.h>
#include <link.h>
#include <unistd.h>
#if defined(__x86_64__)
#include <sys/platform/x86.h>
#endif

#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <initializer_list>
#include <vector>

#include <IpoptConfig.h>
#include <dmumps_c.h>

namespace hylo::trainer {
namespace {

// Set for the re-executed process, so that it happens once.
constexpr const char *kReexecGuard = "HYLO_NUMERICS_REEXEC";
// The CPU features whose libm variants differ from SSE2 in the last bits
// (glibc 2.36: exp, log, pow, sin, cos, tan, atan, atan2, sinh, cosh,
// tanh, ...; FMA4 on AMD CPUs before Zen). Its AVX variants round as SSE2.
constexpr const char *kHwcapsMask = "-AVX2,-FMA,-FMA4";
constexpr const char *kHwcapsKey = "glibc.cpu.hwcaps=";

std::string base_name(const std::string &path)
{
	size_t slash = path.rfind('/');
	return slash == std::string::npos ? path : path.substr(slash + 1);
}

std::string parent_name(const std::string &path)
{
	size_t slash = path.rfind('/');
	return slash == std::string::npos ? "" : base_name(path.substr(0, slash));
}

bool starts_with(const std::string &s, const char *prefix)
{
	return s.compare(0, std::strlen(prefix), prefix) == 0;
}

// Real paths of the shared objects loaded in this process, in load order.
std::vector<std::string> loaded_objects()
{
	std::vector<std::string> out;
	dl_iterate_phdr(
		[](struct dl_phdr_info *info, size_t, void *data) {
			auto *objects = static_cast<std::vector<std::string> *>(data);
			if (info->dlpi_name && info->dlpi_name[0]) {
				char real[PATH_MAX];
				objects->push_back(realpath(info->dlpi_name, real) ? real : info->dlpi_name);
			}
			return 0;
		},
		&out);
	return out;
}

enum class Kind { other, blas, lapack };

// BLAS and LAPACK implementations by file name: Debian's alternatives
// (libblas.so.3, liblapack.so.3) and the libraries behind other choices.
Kind kind_of(const std::string &path)
{
	const std::string b = base_name(path);
	if (starts_with(b, "liblapack."))
		return Kind::lapack;
	for (const char *p : {"libblas.", "libcblas.", "libopenblas", "libblis", "libmkl_", "libatlas", "libsatlas",
			      "libtatlas", "libflexiblas"})
		if (starts_with(b, p))
			return Kind::blas;
	return Kind::other;
}

// Debian's reference libraries live in <libdir>/blas/ and <libdir>/lapack/;
// the other alternatives in openblas-pthread/, blis-openmp/, atlas/, ...
bool is_reference(const std::string &path, Kind k)
{
	const std::string b = base_name(path), dir = parent_name(path);
	if (k == Kind::blas)
		return starts_with(b, "libblas.") && dir == "blas";
	return k == Kind::lapack && starts_with(b, "liblapack.") && dir == "lapack";
}

// "key: path (reference), ..." for every loaded library of kind k.
std::string libraries_line(const char *key, Kind k, const std::vector<std::string> &objects)
{
	std::string list;
	for (const std::string &o : objects)
		if (kind_of(o) == k)
			list += (list.empty() ? "" : ", ") + o +
				(is_reference(o, k) ? " (reference)" : " (not the reference one: CPU-dependent)");
	return std::string(key) + ": " + (list.empty() ? "none loaded" : list) + "\n";
}

// "key: version path" of the first loaded library whose name starts with prefix.
std::string version_line(const char *key, const char *version, const char *prefix,
			 const std::vector<std::string> &objects)
{
	for (const std::string &o : objects)
		if (starts_with(base_name(o), prefix))
			return std::string(key) + ": " + version + " " + o + "\n";
	return std::string(key) + ": " + version + " (not loaded)\n";
}

// True when libm takes the same variants on every CPU of this architecture.
bool libm_pinned()
{
#if defined(__x86_64__)
	return !CPU_FEATURE_ACTIVE(AVX2) && !CPU_FEATURE_ACTIVE(FMA) && !CPU_FEATURE_ACTIVE(FMA4);
#else
	return true;   // aarch64: no CPU-dispatched variants of these functions
#endif
}

std::string libm_line()
{
	std::string line = std::string("libm: glibc ") + gnu_get_libc_version();
#if defined(__x86_64__)
	line += libm_pinned() ? std::string(", hwcaps ") + kHwcapsMask
			      : std::string(", AVX2/FMA variants active (CPU-dependent)");
#endif
	return line + "\n";
}

// GLIBC_TUNABLES with the mask: added to the user's glibc.cpu.hwcaps entries
// (glibc reads only the last one, so a second entry would drop theirs), or
// appended as an entry of its own.
std::string masked_tunables(const char *user)
{
	const std::string in = user ? user : "";
	std::string out;
	bool merged = false;
	for (size_t pos = 0; pos < in.size();) {
		size_t end = in.find(':', pos);
		std::string item = in.substr(pos, end == std::string::npos ? std::string::npos : end - pos);
		if (starts_with(item, kHwcapsKey)) {
			item += (item.size() > std::strlen(kHwcapsKey) ? "," : "") + std::string(kHwcapsMask);
			merged = true;
		}
		out += (out.empty() ? "" : ":") + item;
		pos = end == std::string::npos ? in.size() : end + 1;
	}
	if (!merged)
		out += (out.empty() ? "" : ":") + std::string(kHwcapsKey) + kHwcapsMask;
	return out;
}

// Returns only if the exec failed.
bool reexec_masked(const std::string &prog, char **argv)
{
	const std::string tunables = masked_tunables(std::getenv("GLIBC_TUNABLES"));
	if (setenv("GLIBC_TUNABLES", tunables.c_str(), 1) == 0 && setenv(kReexecGuard, "1", 1) == 0)
		execv("/proc/self/exe", argv);
	std::fprintf(stderr,
		     "%s: cannot re-execute /proc/self/exe with GLIBC_TUNABLES=%s (%s); not running with "
		     "CPU-dependent libm\n",
		     prog.c_str(), tunables.c_str(), std::strerror(errno));
	return false;
}

bool reference_blas_only(const std::string &prog)
{
	std::string other;
	for (const std::string &o : loaded_objects()) {
		Kind k = kind_of(o);
		if (k != Kind::other && !is_reference(o, k))
			other += (other.empty() ? "" : ", ") + o;
	}
	if (other.empty())
		return true;
	std::fprintf(stderr,
		     "%s: a BLAS or LAPACK other than the reference one is loaded (%s): its kernels depend on "
		     "the CPU, and so would every label. Install Debian's libblas3 and liblapack3 (make "
		     "deps) and rebuild: the link's rpath (NUMERICS_LDFLAGS, mk/config.mk) takes them "
		     "from /usr/lib/<multiarch>/blas and lapack; do not LD_PRELOAD another BLAS.\n",
		     prog.c_str(), other.c_str());
	return false;
}

}  // namespace

bool pin_numerics(int argc, char **argv)
{
	const std::string prog = base_name(argc > 0 && argv[0] ? argv[0] : "hylo");
	if (!libm_pinned()) {
		if (!std::getenv(kReexecGuard))
			return reexec_masked(prog, argv);
		const char *t = std::getenv("GLIBC_TUNABLES");
		std::fprintf(stderr,
			     "%s: libm's AVX2/FMA variants are still active after re-executing with "
			     "GLIBC_TUNABLES=%s; labels would depend on the CPU\n",
			     prog.c_str(), t ? t : "(unset)");
		return false;
	}
	unsetenv(kReexecGuard);
	return reference_blas_only(prog);
}

std::string numerics_description()
{
	const std::vector<std::string> objects = loaded_objects();
	return libraries_line("blas", Kind::blas, objects) + libraries_line("lapack", Kind::lapack, objects) +
	       libm_line() + version_line("ipopt", IPOPT_VERSION, "libipopt.", objects) +
	       version_line("mumps", MUMPS_VERSION, "libdmumps", objects);
}

}  // namespace hylo::trainer
