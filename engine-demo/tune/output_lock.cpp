#include "tune/output_lock.h"

#include <fmt/format.h>

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <string>
#include <utility>

namespace spire::tune {

Expected<OutputLock, Failure> OutputLock::acquire(const std::filesystem::path& directory) {
  std::error_code ec;
  std::filesystem::create_directories(directory, ec);
  if (ec) return Failure{fmt::format("cannot create '{}': {}", directory.string(), ec.message())};
  const std::filesystem::path path = directory / ".lock";
  // O_CLOEXEC: the workers are not the run that holds the directory.
  const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) return Failure{fmt::format("cannot open '{}': {}", path.string(), std::strerror(errno))};
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    ::close(fd);
    std::string holder;
    std::getline(std::ifstream(path), holder);
    if (error == EWOULDBLOCK) {
      return Failure{
          fmt::format("'{}' is in use by another spire-tune run{}; wait for it or choose another output "
                      "directory",
                      directory.string(), holder.empty() ? "" : " (process " + holder + ")")};
    }
    return Failure{fmt::format("cannot lock '{}': {}", path.string(), std::strerror(error))};
  }
  // The pid only names the holder in another run's message: the lock holds
  // without it.
  const std::string pid = std::to_string(::getpid()) + "\n";
  const bool named = ::ftruncate(fd, 0) == 0 && ::write(fd, pid.data(), pid.size()) == static_cast<ssize_t>(pid.size());
  static_cast<void>(named);
  return OutputLock(fd);
}

OutputLock::OutputLock(OutputLock&& other) noexcept : fd_(std::exchange(other.fd_, -1)) {}

OutputLock& OutputLock::operator=(OutputLock&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = std::exchange(other.fd_, -1);
  }
  return *this;
}

OutputLock::~OutputLock() {
  if (fd_ >= 0) ::close(fd_);
}

}  // namespace spire::tune
