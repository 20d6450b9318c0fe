#include "support/file_io.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fmt/format.h>
#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <filesystem>

namespace spire {
namespace {

// errno as an error code, taken right after the call that failed: any later
// call, even a successful one, may change errno.
std::error_code lastError() { return {errno != 0 ? errno : EIO, std::generic_category()}; }

// Writes a file that must not exist yet; the error that stopped it. A file it
// created and could not finish is removed.
std::error_code createFile(const std::filesystem::path& path, std::string_view contents) {
  std::FILE* file = std::fopen(path.c_str(), "wbx");
  if (!file) return lastError();
  std::error_code error;
  if (std::fwrite(contents.data(), 1, contents.size(), file) != contents.size()) error = lastError();
  if (std::fclose(file) != 0 && !error) error = lastError();
  std::error_code ignored;
  if (error) std::filesystem::remove(path, ignored);
  return error;
}

class FileDescriptor {
 public:
  explicit FileDescriptor(int fd) : fd_(fd) {}
  ~FileDescriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  FileDescriptor(const FileDescriptor&) = delete;
  FileDescriptor& operator=(const FileDescriptor&) = delete;
  int get() const { return fd_; }

 private:
  int fd_;
};

}  // namespace

Expected<std::string, std::error_code> readFileBytes(const std::string& path) {
  const FileDescriptor file(::open(path.c_str(), O_RDONLY | O_CLOEXEC));
  if (file.get() < 0) return lastError();
  struct stat info {};
  if (::fstat(file.get(), &info) != 0) return lastError();
  // Opening a directory succeeds; reading it would fail less clearly.
  if (S_ISDIR(info.st_mode)) return std::make_error_code(std::errc::is_a_directory);
  constexpr size_t kMaxSize = UINT32_MAX;
  std::string text;
  // Reserved once for a regular file, so that a large file is not copied as
  // the string grows; pipes and devices grow it as they go.
  if (S_ISREG(info.st_mode)) text.reserve(std::min<size_t>(static_cast<size_t>(info.st_size), kMaxSize));
  char buffer[1 << 16];
  while (true) {
    const ssize_t count = ::read(file.get(), buffer, sizeof buffer);
    if (count < 0 && errno == EINTR) continue;
    if (count < 0) return lastError();
    if (count == 0) return text;
    if (text.size() + static_cast<size_t>(count) > kMaxSize) return std::make_error_code(std::errc::file_too_large);
    text.append(buffer, static_cast<size_t>(count));
  }
}

std::optional<std::string> readWholeFile(const std::string& path) {
  auto text = readFileBytes(path);
  if (!text) return std::nullopt;
  return std::move(text).value();
}

Expected<std::string, std::error_code> readThrough(const FileReader& reader, const std::string& path) {
  if (!reader) return readFileBytes(path);
  if (std::optional<std::string> text = reader(path)) return std::move(*text);
  return std::make_error_code(std::errc::no_such_file_or_directory);
}

Expected<void, Failure> writeFileAtomically(const std::string& path, std::string_view contents) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  const auto failure = [&](const std::error_code& error) {
    return Failure{fmt::format("cannot write '{}': {}", path, error.message())};
  };
  // The temporary lives in the target's directory so the rename stays on one
  // file system and is atomic; the counter keeps threads of one process that
  // write the same target apart.
  static std::atomic<unsigned> counter{0};
  const fs::path temp =
      target.parent_path() / fmt::format(".{}.tmp{}-{}", target.filename().string(), ::getpid(), counter++);
  std::error_code error = createFile(temp, contents);
  if (error) return failure(error);
  fs::rename(temp, target, error);
  if (!error) return {};
  std::error_code ignored;
  fs::remove(temp, ignored);
  return failure(error);
}

Expected<void, Failure> writeNewFile(const std::string& path, std::string_view contents) {
  if (const std::error_code error = createFile(path, contents)) {
    return Failure{fmt::format("cannot write '{}': {}", path, error.message())};
  }
  return {};
}

}  // namespace spire
