#include "tune/work_queue.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <fmt/format.h>

#include <cerrno>
#include <charconv>
#include <cstring>

#include "support/file_io.h"

namespace spire::tune {

namespace {

// Closes the descriptor, which also drops its lock.
class FileDescriptor {
 public:
  explicit FileDescriptor(int fd) : fd_(fd) {}
  FileDescriptor(const FileDescriptor&) = delete;
  FileDescriptor& operator=(const FileDescriptor&) = delete;
  ~FileDescriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  int get() const { return fd_; }

 private:
  int fd_;
};

}  // namespace

Expected<void, Failure> WorkQueue::create(const std::filesystem::path& path) {
  return writeFileAtomically(path.string(), "0\n");
}

Expected<std::optional<uint64_t>, Failure> WorkQueue::next(uint64_t chunks) {
  const FileDescriptor file(::open(path_.c_str(), O_RDWR | O_CLOEXEC));
  if (file.get() < 0 || ::flock(file.get(), LOCK_EX) != 0) {
    return Failure{fmt::format("cannot use the work queue '{}': {}", path_.string(), std::strerror(errno))};
  }
  char text[32] = {};
  const ssize_t length = ::pread(file.get(), text, sizeof text - 1, 0);
  uint64_t chunk = 0;
  if (length <= 0 || std::from_chars(text, text + length, chunk).ec != std::errc{}) {
    return Failure{fmt::format("the work queue '{}' is corrupt", path_.string())};
  }
  if (chunk >= chunks) return std::optional<uint64_t>();
  const std::string advanced = fmt::format("{}\n", chunk + 1);
  if (::pwrite(file.get(), advanced.data(), advanced.size(), 0) != static_cast<ssize_t>(advanced.size())) {
    return Failure{fmt::format("cannot write the work queue '{}': {}", path_.string(), std::strerror(errno))};
  }
  return std::optional<uint64_t>(chunk);
}

}  // namespace spire::tune
