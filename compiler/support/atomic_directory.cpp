#include "support/atomic_directory.h"

#include <fcntl.h>
#include <stdio.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>

#include <fmt/format.h>

#include "support/file_io.h"

namespace spire {
namespace fs = std::filesystem;

namespace {

// A fresh name beside `dir` on the same file system, so the exchange is one
// rename; the leading dot keeps it out of casual listings.
fs::path stagingPath(const fs::path& dir, std::string_view purpose) {
  static std::atomic<unsigned> counter{0};
  return dir.parent_path() / fmt::format(".{}.{}-{}-{}", dir.filename().string(), purpose, ::getpid(), counter++);
}

Expected<void, Failure> writeStaged(const fs::path& staging, const FileSet& files) {
  std::error_code ec;
  if (!fs::create_directory(staging, ec) || ec) {
    return Failure{fmt::format("cannot create '{}': {}", staging.string(), ec ? ec.message() : "it already exists")};
  }
  for (const auto& [name, contents] : files) {
    if (auto written = writeFileAtomically((staging / name).string(), contents); !written) return written;
  }
  return {};
}

// Puts `staging` in the place of the existing `dir` and returns where the old
// contents went. RENAME_EXCHANGE swaps the two in one step; where the file
// system lacks it, two renames leave `dir` missing for an instant but never
// mixed, and a failed second rename puts the old contents back.
Expected<fs::path, Failure> swapIn(const fs::path& staging, const fs::path& dir) {
  if (::renameat2(AT_FDCWD, staging.c_str(), AT_FDCWD, dir.c_str(), RENAME_EXCHANGE) == 0) {
    return staging;
  }
  if (errno != EINVAL && errno != ENOSYS) {
    return Failure{fmt::format("cannot replace '{}': {}", dir.string(), std::strerror(errno))};
  }
  const fs::path aside = stagingPath(dir, "old");
  std::error_code ec;
  fs::rename(dir, aside, ec);
  if (ec) return Failure{fmt::format("cannot replace '{}': {}", dir.string(), ec.message())};
  fs::rename(staging, dir, ec);
  if (ec) {
    std::error_code ignored;
    fs::rename(aside, dir, ignored);
    return Failure{fmt::format("cannot replace '{}': {}", dir.string(), ec.message())};
  }
  return aside;
}

}  // namespace

Expected<void, Failure> replaceDirectoryAtomically(const std::string& path, const FileSet& files) {
  const fs::path dir = fs::absolute(path).lexically_normal();
  std::error_code ec;
  fs::create_directories(dir.parent_path(), ec);
  if (ec) return Failure{fmt::format("cannot create directory '{}': {}", dir.parent_path().string(), ec.message())};
  const bool exists = fs::exists(fs::symlink_status(dir, ec));
  if (exists && !fs::is_directory(fs::symlink_status(dir, ec))) {
    return Failure{fmt::format("cannot write '{}': it exists and is not a directory", dir.string())};
  }
  const fs::path staging = stagingPath(dir, "new");
  if (auto staged = writeStaged(staging, files); !staged) {
    fs::remove_all(staging, ec);
    return staged;
  }
  if (!exists) {
    fs::rename(staging, dir, ec);
    if (!ec) return {};
    fs::remove_all(staging, ec);
    return Failure{fmt::format("cannot create '{}': {}", dir.string(), ec.message())};
  }
  auto old = swapIn(staging, dir);
  fs::remove_all(old ? *old : staging, ec);
  if (!old) return old.error();
  return {};
}

}  // namespace spire
