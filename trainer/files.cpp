#include "trainer/files.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <unistd.h>

namespace hylo::trainer {

void write_all(int fd, const std::string &s, const std::string &what)
{
	size_t off = 0;
	while (off < s.size()) {
		ssize_t n = ::write(fd, s.data() + off, s.size() - off);
		if (n < 0 && errno == EINTR)
			continue;
		if (n <= 0)
			throw std::runtime_error("cannot write " + what + ": " + std::strerror(errno));
		off += static_cast<size_t>(n);
	}
}

AppendFile::AppendFile(const std::string &path) : path_(path), fd_(open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644))
{
	if (fd_ < 0)
		throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
}

AppendFile::~AppendFile()
{
	if (fd_ >= 0)
		::close(fd_);
}

void AppendFile::sync()
{
	if (fsync(fd_) != 0)
		throw std::runtime_error("cannot sync " + path_ + ": " + std::strerror(errno));
}

void AppendFile::close()
{
	int fd = fd_;
	fd_ = -1;
	if (::close(fd) != 0)
		throw std::runtime_error("cannot close " + path_ + ": " + std::strerror(errno));
}

std::string read_file(const std::string &path)
{
	std::ifstream f(path, std::ios::binary);
	std::ostringstream ss;
	ss << f.rdbuf();
	return ss.str();
}

std::vector<std::string> complete_lines(const std::string &text)
{
	std::vector<std::string> out;
	size_t pos = 0;
	for (size_t nl; (nl = text.find('\n', pos)) != std::string::npos; pos = nl + 1)
		out.push_back(text.substr(pos, nl - pos));
	return out;
}

void write_file_atomically(const std::string &path, const std::string &text)
{
	const std::string tmp = path + ".tmp";
	if (unlink(tmp.c_str()) != 0 && errno != ENOENT)
		throw std::runtime_error("cannot remove " + tmp + ": " + std::strerror(errno));
	try {
		AppendFile f(tmp);
		f.write(text);
		f.sync();
		f.close();
		if (std::rename(tmp.c_str(), path.c_str()) != 0)
			throw std::runtime_error("cannot rename " + tmp + " to " + path + ": " + std::strerror(errno));
	} catch (...) {
		unlink(tmp.c_str());
		throw;
	}
}

void make_out_dir(const std::string &dir)
{
	std::error_code ec;
	std::filesystem::create_directories(dir, ec);
	if (ec || access(dir.c_str(), W_OK) != 0)
		throw std::runtime_error("cannot create the output directory " + dir + ": " +
					 (ec ? ec.message() : std::string(std::strerror(errno))));
}

}  // namespace hylo::trainer
