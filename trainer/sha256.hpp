// SHA-256 (FIPS 180-4) of files and strings, for the provenance that model
// headers carry. Small and dependency-free.
#ifndef HYLO_TRAINER_SHA256_HPP
#define HYLO_TRAINER_SHA256_HPP

#include <string>

namespace hylo::trainer {

// Lower-case hex digest of bytes.
std::string sha256_hex(const std::string &bytes);

// Digest of a file's contents; throws std::runtime_error naming the file.
std::string sha256_file(const std::string &path);

}  // namespace hylo::trainer

#endif
