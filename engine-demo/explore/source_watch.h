// The files a shader library was read from, watched for saves: the explorer
// recompiles when one of them changes on disk. Polled, at most every
// `interval`, since editors save in several ways (in place, or by renaming a
// new file over the old) and a poll of a few stat calls sees them all.
#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace spire::explore {

class SourceWatch {
 public:
  explicit SourceWatch(std::chrono::milliseconds interval = std::chrono::milliseconds(250)) : interval_(interval) {}

  // Watches `paths` from now on, as they are now.
  void reset(const std::vector<std::filesystem::path>& paths);
  // The first file whose modification time or size changed (or that
  // appeared or vanished) since the last reset or report; nullopt when none
  // did, or when the last poll was less than the interval ago.
  std::optional<std::filesystem::path> poll();

 private:
  struct Stamp {
    std::filesystem::path path;
    std::optional<std::filesystem::file_time_type> time;
    std::uintmax_t size = 0;
  };
  static Stamp stamp(const std::filesystem::path& path);

  std::chrono::milliseconds interval_;
  std::chrono::steady_clock::time_point last_{};
  std::vector<Stamp> files_;
};

}  // namespace spire::explore
