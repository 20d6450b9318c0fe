#include "support/atomic_directory.h"

#include <fcntl.h>
#include <stdio.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <utility>

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
    if (auto written = writeNewFile((staging / name).string(), contents); !written) return written;
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

StagedDirectory::StagedDirectory(fs::path dir, fs::path staging) : dir_(std::move(dir)), staging_(std::move(staging)) {}

StagedDirectory::StagedDirectory(StagedDirectory&& other) noexcept
    : dir_(std::move(other.dir_)), staging_(std::exchange(other.staging_, {})) {}

StagedDirectory& StagedDirectory::operator=(StagedDirectory&& other) noexcept {
  if (this != &other) {
    discard();
    dir_ = std::move(other.dir_);
    staging_ = std::exchange(other.staging_, {});
  }
  return *this;
}

StagedDirectory::~StagedDirectory() { discard(); }

void StagedDirectory::discard() {
  if (staging_.empty()) return;
  std::error_code ignored;
  fs::remove_all(staging_, ignored);
  staging_.clear();
}

Expected<StagedDirectory, Failure> StagedDirectory::stage(const std::string& path, const FileSet& files) {
  fs::path dir = fs::absolute(path).lexically_normal();
  std::error_code ec;
  fs::create_directories(dir.parent_path(), ec);
  if (ec) return Failure{fmt::format("cannot create directory '{}': {}", dir.parent_path().string(), ec.message())};
  fs::path staging = stagingPath(dir, "new");
  if (auto staged = writeStaged(staging, files); !staged) {
    fs::remove_all(staging, ec);
    return staged.error();
  }
  return StagedDirectory(std::move(dir), std::move(staging));
}

Expected<void, Failure> StagedDirectory::commit() {
  // Whether the directory exists is decided now, not when staging: another
  // writer may have made it in between.
  std::error_code ec;
  const fs::file_status status = fs::symlink_status(dir_, ec);
  if (fs::exists(status) && !fs::is_directory(status)) {
    discard();
    return Failure{fmt::format("cannot write '{}': it exists and is not a directory", dir_.string())};
  }
  if (!fs::exists(status)) {
    fs::rename(staging_, dir_, ec);
    if (ec) {
      discard();
      return Failure{fmt::format("cannot create '{}': {}", dir_.string(), ec.message())};
    }
    staging_.clear();
    return {};
  }
  auto old = swapIn(staging_, dir_);
  if (!old) {
    discard();
    return old.error();
  }
  staging_.clear();
  fs::remove_all(*old, ec);
  return {};
}

Expected<void, Failure> replaceDirectoryAtomically(const std::string& dir, const FileSet& files) {
  auto staged = StagedDirectory::stage(dir, files);
  if (!staged) return staged.error();
  return staged.value().commit();
}

}  // namespace spire
