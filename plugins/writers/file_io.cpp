#include "file_io.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "talus/error.hpp"

namespace talus::writers {

void fail_io(std::string_view what, const std::string& path, int error_number) {
  // RunError messages are complete lines for the user (the host prints them).
  std::string message = "error: " + std::string(what);
  message += " '" + path + "': ";
  message += error_number != 0 ? std::strerror(error_number) : "unknown error";
  throw RunError(message);
}

std::string join_path(const std::string& directory, const std::string& name) {
  if (directory.empty()) return name;
  if (directory.back() == '/') return directory + name;
  return directory + "/" + name;
}

void check_writable_directory(const std::string& directory) {
  const std::string dir = directory.empty() ? std::string(".") : directory;
  struct stat st {};
  if (::stat(dir.c_str(), &st) != 0) fail_io("output folder", dir, errno);
  if (!S_ISDIR(st.st_mode)) fail_io("output folder", dir, ENOTDIR);
  // access() answers for the real uid and ignores read-only mounts; creating a
  // file is the only reliable test.
  const std::string probe = join_path(dir, ".talus-write-test-" + std::to_string(::getpid()));
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) fail_io("cannot create files in output folder", dir, errno);
  ::close(fd);
  ::unlink(probe.c_str());
}

namespace {
void sync_path(const std::string& path, int flags) {
  const int fd = ::open(path.c_str(), flags | O_CLOEXEC);
  if (fd < 0) return;  // nothing to sync; the rename below reports real problems
  ::fsync(fd);
  ::close(fd);
}

std::string parent_of(const std::string& path) {
  const auto slash = path.find_last_of('/');
  if (slash == std::string::npos) return ".";
  if (slash == 0) return "/";
  return path.substr(0, slash);
}
}  // namespace

void publish(const std::string& tmp, const std::string& final_path, bool sync) {
  if (sync) {
    const int fd = ::open(tmp.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) fail_io("cannot reopen finished file", tmp, errno);
    if (::fsync(fd) != 0 && errno != EINVAL) {
      const int e = errno;
      ::close(fd);
      fail_io("cannot flush to disk", tmp, e);
    }
    ::close(fd);
  }
  if (::rename(tmp.c_str(), final_path.c_str()) != 0) {
    const int e = errno;
    fail_io("cannot rename '" + tmp + "' to", final_path, e);
  }
  if (sync) sync_path(parent_of(final_path), O_RDONLY | O_DIRECTORY);
}

namespace {
// write(2) until everything is out; returns 0 or the errno of the failure.
int write_all(int fd, const char* data, std::size_t n) {
  while (n > 0) {
    const ssize_t w = ::write(fd, data, n);
    if (w < 0) {
      if (errno == EINTR) continue;
      return errno;
    }
    if (w == 0) return EIO;
    data += w;
    n -= static_cast<std::size_t>(w);
  }
  return 0;
}
}  // namespace

void write_whole_file(const std::string& path, std::string_view text) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) fail_io("cannot create", path, errno);
  int e = write_all(fd, text.data(), text.size());
  if (::close(fd) != 0 && e == 0) e = errno;  // NFS reports write-back errors at close
  if (e != 0) {
    ::unlink(path.c_str());
    fail_io("cannot write", path, e);
  }
}

LineFile::~LineFile() { close(); }

void LineFile::open(const std::string& path, std::size_t keep_bytes) {
  close();
  path_ = path;
  const int flags = O_WRONLY | O_CREAT | O_CLOEXEC | (keep_bytes == 0 ? O_TRUNC : 0);
  fd_ = ::open(path.c_str(), flags, 0644);
  if (fd_ < 0) fail_io("cannot create", path, errno);
  size_ = keep_bytes;
  if (keep_bytes > 0) {
    if (::ftruncate(fd_, static_cast<off_t>(keep_bytes)) != 0) fail_io("cannot truncate", path, errno);
  }
  if (::lseek(fd_, static_cast<off_t>(size_), SEEK_SET) < 0) fail_io("cannot seek in", path, errno);
}

void LineFile::append(std::string_view lines) {
  if (fd_ < 0) throw RunError("error: internal: write to a closed file '" + path_ + "'");
  const int e = write_all(fd_, lines.data(), lines.size());
  if (e != 0) {
    // Drop the partial row so the file still ends with a complete line
    // (character devices such as /dev/full cannot be truncated: ignore).
    if (::ftruncate(fd_, static_cast<off_t>(size_)) == 0) ::lseek(fd_, static_cast<off_t>(size_), SEEK_SET);
    fail_io("cannot write", path_, e);
  }
  size_ += lines.size();
}

void LineFile::close() {
  if (fd_ >= 0) {
    ::fsync(fd_);
    ::close(fd_);
  }
  fd_ = -1;
}

}  // namespace talus::writers
