// The explorer's watch on its sources: a save, a rename over the file and a
// deletion are each reported once.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <unistd.h>

#include "explore/source_watch.h"

namespace spire::explore {
namespace {

namespace fs = std::filesystem;

void write(const fs::path& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

TEST(SourceWatch, ReportsEachChangeOnce) {
  const fs::path dir = fs::temp_directory_path() / ("spire-watch-" + std::to_string(getpid()));
  fs::create_directories(dir);
  const fs::path a = dir / "a.spire";
  const fs::path b = dir / "b.spire";
  write(a, "one");
  write(b, "two");
  SourceWatch watch(std::chrono::milliseconds(0));
  watch.reset({a, b});
  EXPECT_EQ(watch.poll(), std::nullopt);
  write(b, "two, saved");
  EXPECT_EQ(watch.poll(), b);
  EXPECT_EQ(watch.poll(), std::nullopt);
  write(dir / "new.spire", "replacement");
  fs::rename(dir / "new.spire", a);  // how many editors save
  EXPECT_EQ(watch.poll(), a);
  fs::remove(b);
  EXPECT_EQ(watch.poll(), b);
  EXPECT_EQ(watch.poll(), std::nullopt);
  fs::remove_all(dir);
}

TEST(SourceWatch, PollsNoMoreOftenThanItsInterval) {
  const fs::path file = fs::temp_directory_path() / ("spire-watch-interval-" + std::to_string(getpid()));
  write(file, "x");
  SourceWatch watch(std::chrono::hours(1));
  watch.reset({file});
  write(file, "xy");
  EXPECT_EQ(watch.poll(), std::nullopt);
  fs::remove(file);
}

}  // namespace
}  // namespace spire::explore
