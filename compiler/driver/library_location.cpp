#include "driver/library_location.h"

namespace spire {
namespace fs = std::filesystem;

std::optional<fs::path> runningExecutable() {
  std::error_code error;
  fs::path self = fs::read_symlink("/proc/self/exe", error);
  if (error) return std::nullopt;
  return self;
}

std::optional<fs::path> bundledLibraryDir(const fs::path& executable) {
  const fs::path library = (executable.parent_path() / ".." / "share" / "spire").lexically_normal();
  std::error_code error;
  if (!fs::is_directory(library, error)) return std::nullopt;
  return library;
}

}  // namespace spire
