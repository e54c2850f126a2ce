// Files the trainer writes so that an interruption loses nothing: rows
// appended and synced, whole files replaced atomically.
#ifndef HYLO_TRAINER_FILES_HPP
#define HYLO_TRAINER_FILES_HPP

#include <string>
#include <vector>

namespace hylo::trainer {

// The file's bytes ("" if it cannot be read).
std::string read_file(const std::string &path);

// The complete lines of text, without their newlines (a torn last line,
// one without its newline, dropped).
std::vector<std::string> complete_lines(const std::string &text);

// Writes all of s to fd; throws std::runtime_error naming what.
void write_all(int fd, const std::string &s, const std::string &what);

// A file opened for appending rows (O_APPEND, created 0644), closed when it
// goes out of scope, so that a write that throws does not leak it; sync()
// and close() throw naming the file.
class AppendFile {
public:
	explicit AppendFile(const std::string &path);
	~AppendFile();
	AppendFile(const AppendFile &) = delete;
	AppendFile &operator=(const AppendFile &) = delete;
	int fd() const { return fd_; }
	void write(const std::string &s) { write_all(fd_, s, path_); }
	void sync();
	void close();

private:
	std::string path_;
	int fd_;
};

// Replaces path with text atomically: a temporary file beside it, fsync'd,
// renamed over it (removed if anything fails). Throws std::runtime_error
// naming the file.
void write_file_atomically(const std::string &path, const std::string &text);

// Creates dir and its parents; throws std::runtime_error naming it when it
// cannot, or cannot be written.
void make_out_dir(const std::string &dir);

}  // namespace hylo::trainer

#endif
