// spire-demo run in-process, as a user runs it: golden diagnostics for scenes
// that do not fit their shaders (tests/golden/demo/NAME.json against
// NAME.expected, the exact stderr; SPIRE_UPDATE_GOLDENS=1 rewrites them), and
// the main job's outputs on a small terrain scene.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <unistd.h>

#include "demo/demo.h"
#include "driver/exit_codes.h"
#include "engine/device_fixture.h"
#include "scene/texture.h"

namespace spire::demo {
namespace {

namespace fs = std::filesystem;

class DemoTest : public vk::testing::DeviceTest {
 protected:
  fs::path outputDir() const {
    const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
    return fs::temp_directory_path() / (std::string("spire_demo_") + info->name() + "_" + std::to_string(::getpid()));
  }
};

std::string readFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The conventions every Spire tool shares (driver/tool_arguments.h); all
// of them hold before any device is needed.
TEST(DemoCommandLine, FollowsTheToolConventions) {
  std::ostringstream out, err;
  EXPECT_EQ(runDemo({"--version"}, out, err), kExitSuccess);
  EXPECT_EQ(out.str().rfind("spire-demo ", 0), 0U) << out.str();
  for (const std::vector<std::string>& args : std::vector<std::vector<std::string>>{
           {"examples/scenes/terrain.json", "-o", ""}, {"examples/scenes/terrain.json", "--no-such-flag"}, {}}) {
    std::ostringstream usageOut, usageErr;
    EXPECT_EQ(runDemo(args, usageOut, usageErr), kExitUsageError) << usageErr.str();
    EXPECT_NE(usageErr.str().find("Run 'spire-demo --help' for usage."), std::string::npos) << usageErr.str();
  }
}

TEST_F(DemoTest, SceneErrorsMatchGoldenDiagnostics) {
  std::vector<fs::path> scenes;
  for (const auto& entry : fs::directory_iterator("tests/golden/demo")) {
    if (entry.path().extension() == ".json") scenes.push_back(entry.path());
  }
  std::sort(scenes.begin(), scenes.end());
  ASSERT_GE(scenes.size(), 5U);
  for (const fs::path& scene : scenes) {
    SCOPED_TRACE(scene.string());
    std::ostringstream out;
    std::ostringstream err;
    const fs::path dir = outputDir();
    EXPECT_EQ(runDemo({scene.string(), "--validation", "-o", dir.string()}, out, err), 1);
    EXPECT_FALSE(fs::exists(dir)) << "a failed run must not write outputs";
    const fs::path expected = fs::path(scene).replace_extension(".expected");
    if (std::getenv("SPIRE_UPDATE_GOLDENS")) {
      std::ofstream(expected, std::ios::binary) << err.str();
      continue;
    }
    EXPECT_EQ(err.str(), readFile(expected));
  }
}

TEST_F(DemoTest, MainJobWritesImagesReportAndTheTrade) {
  const fs::path dir = outputDir();
  std::ostringstream out;
  std::ostringstream err;
  // The terrain scene at a small size: the same variants, worlds and bakes.
  // --keep-alpha: the images keep the alpha Terrain writes (below 1 where
  // its albedo maps are translucent); without it they are opaque (see
  // AFailingVariantIsReportedAndTheOthersAreWritten).
  ASSERT_EQ(runDemo({"examples/scenes/terrain.json", "--validation", "--frames", "2", "--warmup", "1", "--bake-size",
                     "256", "--keep-alpha", "-o", dir.string()},
                    out, err),
            0)
      << err.str();
  for (const char* name : {"full_quality", "baked_albedo", "baked_vertex_normal", "comparison"}) {
    auto image = scene::loadImage(dir / (std::string(name) + ".png"));
    ASSERT_TRUE(image) << name;
    EXPECT_GT(image->width, 0U);
  }
  const auto fullQuality = scene::loadImage(dir / "full_quality.png");
  ASSERT_TRUE(fullQuality);
  size_t translucent = 0;
  for (size_t i = 3; i < fullQuality->bytes.size(); i += 4) translucent += fullQuality->bytes[i] != 255;
  EXPECT_GT(translucent, 0U);
  const std::string report = readFile(dir / "report.md");
  EXPECT_NE(report.find("| baked_vertex_normal |"), std::string::npos) << report;
  // The baked variants no longer read the maps they baked, which the full
  // quality variant reads: that is no reason to warn.
  EXPECT_EQ(err.str().find("W7101"), std::string::npos) << err.str();
  const std::string table = out.str();
  EXPECT_NE(table.find("baked_albedo"), std::string::npos) << table;
  EXPECT_NE(table.find("PrebakeTex"), std::string::npos) << table;
  fs::remove_all(dir);
}

// A variant that fails is named with its decision file and left out; the
// others are measured and written, as a set that replaces the earlier run's
// files, with opaque images; the exit status says something failed.
TEST_F(DemoTest, AFailingVariantIsReportedAndTheOthersAreWritten) {
  const fs::path dir = outputDir();
  fs::create_directories(dir);
  std::ofstream(dir / "stale.png") << "an earlier run's";
  const fs::path broken = fs::path(dir.string() + "_broken.decisions");
  std::ofstream(broken) << "Terrain.albedo = NoSuchWorld\n";
  std::ostringstream out;
  std::ostringstream err;
  EXPECT_EQ(runDemo({"examples/scenes/terrain.json", "--validation", "--frames", "1", "--warmup", "1", "--bake-size",
                     "64", "--variant", "examples/decisions/terrain_full_quality.decisions", "--variant",
                     broken.string(), "-o", dir.string()},
                    out, err),
            kExitInputError);
  const std::string name = broken.stem().string();
  EXPECT_NE(err.str().find(fmt::format("variant '{}' ({}) failed: ", name, broken.string())), std::string::npos)
      << err.str();
  EXPECT_NE(err.str().find("1 of 2 variants failed"), std::string::npos) << err.str();
  EXPECT_FALSE(fs::exists(dir / "stale.png"));
  EXPECT_FALSE(fs::exists(dir / (name + ".png")));
  const auto image = scene::loadImage(dir / "terrain_full_quality.png");
  ASSERT_TRUE(image) << image.error().message;
  size_t translucent = 0;
  for (size_t i = 3; i < image->bytes.size(); i += 4) translucent += image->bytes[i] != 255;
  EXPECT_EQ(translucent, 0U);
  EXPECT_TRUE(fs::exists(dir / "comparison.png"));
  const std::string report = readFile(dir / "report.md");
  EXPECT_NE(report.find("## Failed variants"), std::string::npos) << report;
  EXPECT_NE(report.find("| " + name + " | " + broken.string() + " |"), std::string::npos) << report;
  fs::remove_all(dir);
  fs::remove(broken);
}

}  // namespace
}  // namespace spire::demo
