// spire-explore --tune-dir end to end, in a real window (under xvfb-run;
// skipped without a display): a real spire-tune run on Terrain (two
// components, a few frames), whose first front point the script applies as
// one change and saves; and the same run refused when the explored instance
// has another shader.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>

#include <unistd.h>

#include "common/have_display.h"
#include "explore/explorer_window_fixture.h"
#include "graph/decision_file.h"
#include "support/diagnostic.h"
#include "support/file_io.h"
#include "support/source_manager.h"
#include "tune/results_csv.h"
#include "tune/tune_cli.h"

namespace spire::explore {
namespace {

namespace fs = std::filesystem;

class ParetoWindowTest : public testing::ExplorerWindowFixture {
 protected:
  // One tuning run for the suite: it takes most of the time.
  static void SetUpTestSuite() {
    DeviceTest::SetUpTestSuite();
    if (!spire::testing::haveDisplay()) return;
    tuneDir_ = new fs::path(fs::temp_directory_path() / ("spire-explore-tune-" + std::to_string(getpid())));
    fs::remove_all(*tuneDir_);
    std::ostringstream out;
    std::ostringstream err;
    tuneStatus_ =
        tune::runTune({"examples/scenes/terrain.json", "--shader", "Terrain", "--components", "albedo,lighting",
                       "--jobs", "1", "--bake-size", "64", "--max-frames", "3", "-o", tuneDir_->string()},
                      out, err);
    if (tuneStatus_ != 0) std::cerr << err.str();
  }
  static void TearDownTestSuite() {
    if (tuneDir_ != nullptr) fs::remove_all(*tuneDir_);
    delete tuneDir_;
    tuneDir_ = nullptr;
    DeviceTest::TearDownTestSuite();
  }
  void SetUp() override {
    ExplorerWindowFixture::SetUp();
    if (IsSkipped() || HasFatalFailure()) return;
    ASSERT_EQ(tuneStatus_, 0) << "spire-tune failed";
  }

  static fs::path* tuneDir_;
  static int tuneStatus_;
};

fs::path* ParetoWindowTest::tuneDir_ = nullptr;
int ParetoWindowTest::tuneStatus_ = -1;

// component -> placement of a decision file's lines for `shader`.
std::map<std::string, std::string> decisionsIn(const fs::path& path, const std::string& shader) {
  SourceManager sources;
  DiagnosticList diags;
  const FileId file = sources.addFile(path.string(), readWholeFile(path.string()).value_or(""));
  std::map<std::string, std::string> decisions;
  for (const graph::DecisionLine& line : graph::parseDecisionFile(sources, file, diags).lines) {
    if (line.prefix == shader)
      decisions[line.component] = line.variation.empty() ? line.world : line.world + ":" + line.variation;
  }
  EXPECT_FALSE(diags.hasErrors()) << path;
  return decisions;
}

TEST_F(ParetoWindowTest, ApplyingAFrontPointIsOneChangeToItsDecisions) {
  const fs::path path = script("apply-front 0\nsave x.decisions\nquit\n");
  ASSERT_EQ(runExploreTool({"examples/scenes/terrain.json", "--bake-size", "64", "--tune-dir", tuneDir_->string(),
                            "--script", path.string(), "--log", (dir_ / "log.json").string()},
                           out_, err_),
            0)
      << err_.str() << out_.str();
  EXPECT_NE(out_.str().find("tuned variants"), std::string::npos) << out_.str();
  const nlohmann::json changes =
      nlohmann::json::parse(readWholeFile((dir_ / "log.json").string()).value_or("null"))["changes"];
  ASSERT_EQ(changes.size(), 1U) << out_.str();
  EXPECT_EQ(changes[0]["action"], "apply-front 0");
  EXPECT_TRUE(changes[0]["ok"]) << changes[0]["error"];
  EXPECT_TRUE(changes[0]["skipped"].empty()) << changes[0]["skipped"];

  // The tuner's own reading of its front: point 0 is pareto.csv's first row.
  auto components = tune::readComponents(*tuneDir_ / "pareto.csv");
  ASSERT_TRUE(components) << components.error().message;
  auto front = tune::readResults(*tuneDir_ / "pareto.csv", *components);
  ASSERT_TRUE(front && !front->empty());
  std::map<std::string, std::string> expected;
  for (size_t i = 0; i < components->size(); ++i) expected[(*components)[i]] = front->front().placements[i];
  EXPECT_EQ(decisionsIn(dir_ / "x.decisions", "Terrain"), expected);
}

TEST_F(ParetoWindowTest, AnotherShadersTuningIsRefused) {
  EXPECT_EQ(
      runExploreTool({"tests/data/engine/stability/guarded_divide.json", "--tune-dir", tuneDir_->string()}, out_, err_),
      1);
  EXPECT_NE(err_.str().find("is spire-tune's output for shader 'Terrain', but the explored instance's shader is "
                            "'GuardedDivide'"),
            std::string::npos)
      << err_.str();
}

}  // namespace
}  // namespace spire::explore
