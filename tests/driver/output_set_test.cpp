// spirec's output directory is written as a set: a fault part-way through
// (here a file-size limit, as a full disk would give) leaves the previous
// kernels and reflection exactly as they were, with nothing left beside
// them, and a successful run replaces the whole directory, so no kernel of
// an earlier variant survives next to the new reflection.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "driver/spirec.h"
#include "support/file_io.h"

namespace spire {
namespace {

namespace fs = std::filesystem;

const std::string kExamples = std::string(SPIRE_SOURCE_DIR) + "/examples/";

std::vector<std::string> terrainArgs(const std::string& decisions, const fs::path& out) {
  return {kExamples + "terrain.spire",
          "--decisions",
          kExamples + "decisions/" + decisions,
          "-o",
          out.string(),
          "--emit",
          "both"};
}

int spirec(const std::vector<std::string>& args) {
  std::ostringstream sink;
  return runSpirec(args, sink, sink);
}

// spirec in a child process whose files may not grow past `limit` bytes;
// its exit code, or -1 when it did not exit normally.
int spirecWithFileSizeLimit(const std::vector<std::string>& args, rlim_t limit) {
  const pid_t child = ::fork();
  if (child == 0) {
    ::signal(SIGXFSZ, SIG_IGN);  // a write past the limit fails with EFBIG instead of killing
    const rlimit small{limit, limit};
    ::setrlimit(RLIMIT_FSIZE, &small);
    ::_exit(spirec(args));
  }
  int status = 0;
  ::waitpid(child, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::map<std::string, std::string> contentsOf(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    if (entry.is_regular_file())
      files[fs::relative(entry.path(), dir).string()] = *readWholeFile(entry.path().string());
  }
  return files;
}

class SpirecOutputSet : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::path(::testing::TempDir()) / ("spirec_output_set_" + std::to_string(::getpid()));
    fs::remove_all(root_);
    ASSERT_EQ(spirec(terrainArgs("terrain_baked_albedo.decisions", root_)), kExitSuccess);
    before_ = contentsOf(root_);
    ASSERT_TRUE(before_.contains("Terrain/PrebakeTex.spv"));
  }
  void TearDown() override { fs::remove_all(root_); }

  fs::path root_;
  std::map<std::string, std::string> before_;
};

TEST_F(SpirecOutputSet, AFaultPartWayLeavesTheOldSetWhole) {
  // Large enough for the first kernels, too small for all of them.
  const int code = spirecWithFileSizeLimit(terrainArgs("terrain_full_quality.decisions", root_), 4096);
  EXPECT_EQ(code, kExitInputError);
  EXPECT_EQ(contentsOf(root_), before_) << "the old kernels and reflection changed";
  for (const auto& entry : fs::directory_iterator(root_)) {
    EXPECT_EQ(entry.path().filename(), "Terrain") << "left beside the output: " << entry.path();
  }
}

TEST_F(SpirecOutputSet, ASuccessfulRunReplacesTheWholeDirectory) {
  ASSERT_EQ(spirec(terrainArgs("terrain_full_quality.decisions", root_)), kExitSuccess);
  const auto after = contentsOf(root_);
  EXPECT_FALSE(after.contains("Terrain/PrebakeTex.spv")) << "a kernel of the earlier variant survived";
  EXPECT_NE(after.at("Terrain/reflection.json"), before_.at("Terrain/reflection.json"));
  for (const auto& entry : fs::directory_iterator(root_)) {
    EXPECT_EQ(entry.path().filename(), "Terrain") << "left beside the output: " << entry.path();
  }
}

}  // namespace
}  // namespace spire
