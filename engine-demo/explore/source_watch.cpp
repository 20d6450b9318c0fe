#include "explore/source_watch.h"

#include <system_error>

namespace spire::explore {

SourceWatch::Stamp SourceWatch::stamp(const std::filesystem::path& path) {
  Stamp s{path, std::nullopt, 0};
  std::error_code ec;
  const auto time = std::filesystem::last_write_time(path, ec);
  if (ec) return s;
  s.time = time;
  s.size = std::filesystem::file_size(path, ec);
  if (ec) s.size = 0;
  return s;
}

void SourceWatch::reset(const std::vector<std::filesystem::path>& paths) {
  files_.clear();
  for (const std::filesystem::path& path : paths) files_.push_back(stamp(path));
  last_ = std::chrono::steady_clock::now();
}

std::optional<std::filesystem::path> SourceWatch::poll() {
  const auto now = std::chrono::steady_clock::now();
  if (now - last_ < interval_) return std::nullopt;
  last_ = now;
  std::optional<std::filesystem::path> changed;
  for (Stamp& file : files_) {
    Stamp current = stamp(file.path);
    if (current.time != file.time || current.size != file.size) {
      if (!changed) changed = file.path;
      file = std::move(current);
    }
  }
  return changed;
}

}  // namespace spire::explore
