// Golden diagnostics of bad scene files: tests/golden/scene/NAME.json is
// loaded and its rendered diagnostics are compared exactly with NAME.expected.
// After an intended change, run with SPIRE_UPDATE_GOLDENS=1 to rewrite the
// expectations, then review the diff.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "scene/scene_file.h"
#include "support/diagnostic_renderer.h"
#include "support/file_io.h"

namespace spire::scene {
namespace {

namespace fs = std::filesystem;

const fs::path kGoldenDir = "tests/golden/scene";

std::vector<fs::path> goldenScenes() {
  std::vector<fs::path> scenes;
  for (const auto& entry : fs::directory_iterator(fs::path(SPIRE_SOURCE_DIR) / kGoldenDir)) {
    if (entry.path().extension() == ".json") scenes.push_back(kGoldenDir / entry.path().filename());
  }
  std::sort(scenes.begin(), scenes.end());
  return scenes;
}

class SceneGolden : public testing::TestWithParam<fs::path> {};

TEST_P(SceneGolden, DiagnosticsMatchExpected) {
  // Relative paths keep the rendered locations independent of the checkout.
  fs::current_path(SPIRE_SOURCE_DIR);
  const fs::path scene = GetParam();
  const fs::path expected = fs::path(scene).replace_extension(".expected");
  SourceManager sources;
  DiagnosticList diags;
  EXPECT_FALSE(loadSceneFile(scene, sources, diags).has_value());
  const std::string actual = renderDiagnostics(sources, diags, DiagnosticFormat::Text);
  if (std::getenv("SPIRE_UPDATE_GOLDENS")) {
    std::ofstream(expected, std::ios::binary) << actual;
    GTEST_SKIP() << "updated " << expected;
  }
  const std::optional<std::string> golden = readWholeFile(expected.string());
  ASSERT_TRUE(golden.has_value()) << "missing " << expected << "; run with SPIRE_UPDATE_GOLDENS=1";
  EXPECT_EQ(actual, *golden);
}

INSTANTIATE_TEST_SUITE_P(Scene, SceneGolden, testing::ValuesIn(goldenScenes()),
                         [](const testing::TestParamInfo<fs::path>& param) { return param.param.stem().string(); });

}  // namespace
}  // namespace spire::scene
