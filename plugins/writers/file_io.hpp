// Small POSIX helpers shared by the writers: publishing a finished file under
// its final name atomically, appending whole lines, and error messages that
// name the path and the system's reason (DESIGN.md principle 7).
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace talus::writers {

// Throws RunError "error: WHAT 'PATH': <strerror>", e.g.
// "error: cannot write 'out/a.vtu.tmp': No space left on device".
[[noreturn]] void fail_io(std::string_view what, const std::string& path, int error_number);

// Throws RunError (naming the folder and the reason) unless `directory` exists
// and a file can be created in it. Called from open() so that an unwritable
// folder fails before the first step, not after an hour of simulation.
void check_writable_directory(const std::string& directory);

// Makes `tmp` durable (fsync) and renames it over `final_path` (atomic on
// POSIX), then syncs the folder so the rename survives a power loss. When
// `sync` is false only the rename is done (the data may still sit in the page
// cache, but a reader never sees a half-written file under the final name).
void publish(const std::string& tmp, const std::string& final_path, bool sync);

// Writes all bytes of `text` to a new file `path` (truncating), checking every
// call; on failure removes the partial file and throws RunError.
void write_whole_file(const std::string& path, std::string_view text);

// An append-only text file written line by line: each line goes out in one
// write(2); if a write fails the file is truncated back to its last complete
// line, so it never ends in a partial row, and RunError names the path.
class LineFile {
 public:
  LineFile() = default;
  ~LineFile();
  LineFile(const LineFile&) = delete;
  LineFile& operator=(const LineFile&) = delete;

  // Opens (creating or truncating) the file; `keep_bytes` > 0 keeps that many
  // leading bytes of an existing file instead (restart).
  void open(const std::string& path, std::size_t keep_bytes = 0);
  void append(std::string_view lines);  // one or more complete '\n'-terminated lines
  void close();
  const std::string& path() const { return path_; }
  bool is_open() const { return fd_ >= 0; }

 private:
  std::string path_;
  int fd_ = -1;
  std::size_t size_ = 0;  // bytes of complete lines on disk
};

// Path join that tolerates a trailing slash.
std::string join_path(const std::string& directory, const std::string& name);

}  // namespace talus::writers
