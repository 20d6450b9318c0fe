// spire-demo run in-process, as a user runs it: golden diagnostics for scenes
// that do not fit their shaders (tests/golden/demo/NAME.json against
// NAME.expected, the exact stderr; SPIRE_UPDATE_GOLDENS=1 rewrites them), the
// main job's outputs on a small terrain scene, and the level-of-detail
// configurations on a small LOD scene.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <regex>
#include <sstream>
#include <string>

#include <unistd.h>

#include "common/lod_test_scene.h"
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
  // A folder beside outputDir() for the scene files a test writes, made
  // on first use.
  fs::path sceneFolder() const {
    const fs::path dir(outputDir().string() + "_scene");
    fs::create_directories(dir);
    return dir;
  }
  // Both folders, once a test passed: a failed one's stay to be read.
  void removeOutputs() const {
    fs::remove_all(outputDir());
    fs::remove_all(outputDir().string() + "_scene");
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
  for (const std::vector<std::string>& args :
       std::vector<std::vector<std::string>>{{"examples/scenes/terrain.json", "-o", ""},
                                             {"examples/scenes/terrain.json", "--no-such-flag"},
                                             {"examples/scenes/terrain.json", "--frames", "0"},
                                             {"examples/scenes/terrain.json", "--resolution", "0x64"},
                                             {"examples/scenes/terrain.json", "--resolution", "64x8193"},
                                             {"examples/scenes/terrain.json", "--resolution", "64x"},
                                             {"examples/scenes/terrain.json", "--resolution", "64x48x2"},
                                             {"examples/scenes/terrain.json", "--resolution", "-64x48"},
                                             {}}) {
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
  // The terrain scene at a smaller size (--resolution replaces the scene's
  // 640 x 480): the same variants, worlds and bakes.
  // --keep-alpha: the images keep the alpha Terrain writes (below 1 where
  // its albedo maps are translucent); without it they are opaque (see
  // AFailingVariantIsReportedAndTheOthersAreWritten).
  ASSERT_EQ(runDemo({"examples/scenes/terrain.json", "--validation", "--frames", "2", "--warmup", "1", "--bake-size",
                     "256", "--keep-alpha", "--resolution", "320x200", "-o", dir.string()},
                    out, err),
            0)
      << err.str();
  for (const char* name : {"full_quality", "baked_albedo", "baked_vertex_normal"}) {
    auto image = scene::loadImage(dir / (std::string(name) + ".png"));
    ASSERT_TRUE(image) << name;
    EXPECT_EQ(image->width, 320U) << name;
    EXPECT_EQ(image->height, 200U) << name;
  }
  ASSERT_TRUE(scene::loadImage(dir / "comparison.png"));
  const auto fullQuality = scene::loadImage(dir / "full_quality.png");
  ASSERT_TRUE(fullQuality);
  size_t translucent = 0;
  for (size_t i = 3; i < fullQuality->bytes.size(); i += 4) translucent += fullQuality->bytes[i] != 255;
  EXPECT_GT(translucent, 0U);
  const std::string report = readFile(dir / "report.md");
  EXPECT_NE(report.find("| baked_vertex_normal |"), std::string::npos) << report;
  EXPECT_NE(report.find(", 320x200, "), std::string::npos) << report;
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

// The shared small LOD scene with the policy file `policyFile` (relative to
// the scene file) and two camera views, so that the fly-through moves.
std::string smallLodScene(const std::string& policyFile) {
  spire::testing::LodTestScene options;
  options.views = R"([{"position": [0, 9, 13], "target": [0, 0, 0]}, {"position": [6, 5, 4], "target": [-2, 0, -2]}])";
  options.policy = policyFile;
  return spire::testing::lodTestSceneJson(options);
}

// The numbers of spire-demo's last line on a LOD scene.
struct LodSummary {
  double speedup, batches, fullBatches, rmse, popping, poppingWithout;
};

std::optional<LodSummary> parseLodSummary(const std::string& out) {
  static const std::regex line(
      R"(\nlod: speedup (\S+), batches (\S+) vs full quality (\S+), rmse (\S+), popping (\S+) with transitions vs )"
      R"((\S+) without\n$)");
  std::smatch m;
  if (!std::regex_search(out, m, line)) return std::nullopt;
  return LodSummary{std::stod(m[1]), std::stod(m[2]), std::stod(m[3]),
                    std::stod(m[4]), std::stod(m[5]), std::stod(m[6])};
}

// The three configurations over a moving camera: the four files, a report
// row for each configuration, and a summary line with sane numbers.
// A scene variant is one decision file for every instance; each instance's
// source reads only the lines of its own shaders. A line for a shader that
// another instance's source declares applies there, not here; a shader no
// source declares is still an error.
TEST_F(DemoTest, ASceneVariantNamesTheShadersOfEverySource) {
  const fs::path dir = outputDir();
  fs::remove_all(dir);
  std::ostringstream out;
  std::ostringstream err;
  EXPECT_EQ(
      runDemo({"examples/scenes/terrain_and_couch.json", "--validation", "--frames", "1", "--warmup", "1",
               "--bake-size", "64", "--variant", "examples/decisions/couch/baked_phong.decisions", "-o", dir.string()},
              out, err),
      kExitSuccess)
      << err.str();
  EXPECT_TRUE(fs::exists(dir / "baked_phong.png"));
  const fs::path typo = fs::path(dir.string() + "_typo.decisions");
  std::ofstream(typo) << "Cuoch.specular = Fragment:standardPhong\n";
  std::ostringstream typoOut;
  std::ostringstream typoErr;
  EXPECT_NE(runDemo({"examples/scenes/terrain_and_couch.json", "--validation", "--frames", "1", "--warmup", "1",
                     "--bake-size", "64", "--variant", typo.string(), "-o", dir.string() + "_out"},
                    typoOut, typoErr),
            kExitSuccess);
  EXPECT_NE(typoErr.str().find("unknown shader 'Cuoch'"), std::string::npos) << typoErr.str();
  fs::remove_all(dir);
  fs::remove_all(dir.string() + "_out");
  fs::remove(typo);
}

TEST_F(DemoTest, LodSceneWritesImagesReportAndSummary) {
  const fs::path dir = outputDir();
  const fs::path sceneDir = sceneFolder();
  // LodHQ only within 0.5 units: the cameras are 5 units or more above the
  // ground, so the copies draw LodMQ (up to 8) or LodLQ in lod, and lod
  // differs from full quality wherever a copy is seen.
  std::ofstream(sceneDir / "policy.json")
      << R"({"levels": [{"member": "LodHQ", "until": 0.5}, {"member": "LodMQ", "until": 8}, {"member": "LodLQ"}],
            "transitionFrames": 2})";
  std::ofstream(sceneDir / "scene.json") << smallLodScene("policy.json");
  std::ostringstream out;
  std::ostringstream err;
  ASSERT_EQ(runDemo({(sceneDir / "scene.json").string(), "--validation", "--frames", "3", "--warmup", "1", "-o",
                     dir.string()},
                    out, err),
            0)
      << err.str();
  for (const char* name : {"full_quality", "lod", "comparison"}) {
    auto image = scene::loadImage(dir / (std::string(name) + ".png"));
    ASSERT_TRUE(image) << name << ": " << image.error().message;
    EXPECT_GT(image->width, 0U);
  }
  const std::string report = readFile(dir / "report.md");
  for (const char* row : {"| full_quality |", "| lod |", "| lod_no_transitions |"}) {
    EXPECT_NE(report.find(row), std::string::npos) << row << "\n" << report;
  }
  const std::optional<LodSummary> summary = parseLodSummary(out.str());
  ASSERT_TRUE(summary) << out.str();
  EXPECT_GT(summary->speedup, 0.0);
  // Full quality binds a pipeline per material and block; in lod the three
  // object materials share one draw group at LodMQ and one at LodLQ, so it
  // binds fewer, fades' overlay batches included.
  EXPECT_GE(summary->batches, 1.0);
  EXPECT_LT(summary->batches, summary->fullBatches);
  EXPECT_TRUE(std::isfinite(summary->rmse));
  // The copies are drawn from bakes in lod, per fragment in full quality.
  EXPECT_GT(summary->rmse, 0.0);
  for (double popping : {summary->popping, summary->poppingWithout}) {
    EXPECT_TRUE(std::isfinite(popping) && popping >= 0.0) << popping;
  }
  // Every level of the library writes lodFade: nothing to warn about.
  EXPECT_EQ(err.str().find("W7102"), std::string::npos) << err.str();
  removeOutputs();
}

// A level whose shader does not read lodFade, which the policy cross-fades
// into, is warned about at the policy's level (W7102), and the run goes on.
TEST_F(DemoTest, ASwitchThatCannotCrossFadeIsWarnedAboutAtThePolicysLevel) {
  const fs::path dir = outputDir();
  const fs::path sceneDir = sceneFolder();
  std::ofstream(sceneDir / "policy.json") << R"({"levels": [{"member": "Fades", "until": 5},
            {"member": "Opaque"}], "transitionFrames": 4})";
  std::ofstream(sceneDir / "scene.json") << spire::testing::lodFadesSceneJson("policy.json", 32);
  std::ostringstream out;
  std::ostringstream err;
  ASSERT_EQ(runDemo({(sceneDir / "scene.json").string(), "--validation", "--frames", "2", "--warmup", "1", "-o",
                     dir.string()},
                    out, err),
            0)
      << err.str();
  EXPECT_NE(err.str().find("policy.json:2:13: warning[W7102]: 'Thing<Opaque>' at level 1 (Opaque) does not read "
                           "lodFade"),
            std::string::npos)
      << err.str();
  EXPECT_NE(out.str().find("lod: speedup"), std::string::npos) << out.str();
  removeOutputs();
}

// A policy file that cannot be read fails the run before anything is
// rendered, naming the file, and leaves no output behind.
TEST_F(DemoTest, LodSceneWithoutItsPolicyFileFails) {
  const fs::path dir = outputDir();
  const fs::path sceneDir = sceneFolder();
  std::ofstream(sceneDir / "scene.json") << smallLodScene("no_such_policy.json");
  std::ostringstream out;
  std::ostringstream err;
  EXPECT_EQ(runDemo({(sceneDir / "scene.json").string(), "--validation", "-o", dir.string()}, out, err),
            kExitInputError);
  EXPECT_NE(err.str().find("E1101"), std::string::npos) << err.str();
  EXPECT_NE(err.str().find((sceneDir / "no_such_policy.json").string()), std::string::npos) << err.str();
  EXPECT_FALSE(fs::exists(dir)) << "a failed run must not write outputs";
  fs::remove_all(sceneDir);
}

// A material value that no level of the LOD library reads is reported, as
// for variants (W7101), and the run goes on.
TEST_F(DemoTest, LodSceneWarnsAboutAValueNoLevelReads) {
  const fs::path dir = outputDir();
  const fs::path sceneDir = sceneFolder();
  std::ofstream(sceneDir / "policy.json") << spire::testing::lodTestPolicyJson();
  std::string json = smallLodScene("policy.json");
  const std::string stave = R"("staveCount": 16)";
  ASSERT_NE(json.find(stave), std::string::npos);
  json.replace(json.find(stave), stave.size(), R"("staveCount": 16, "unreadByAnyLevel": 2)");
  std::ofstream(sceneDir / "scene.json") << json;
  std::ostringstream out;
  std::ostringstream err;
  ASSERT_EQ(
      runDemo({(sceneDir / "scene.json").string(), "--validation", "--frames", "1", "-o", dir.string()}, out, err), 0)
      << err.str();
  EXPECT_NE(err.str().find("W7101"), std::string::npos) << err.str();
  EXPECT_NE(err.str().find("unreadByAnyLevel"), std::string::npos) << err.str();
  removeOutputs();
}

}  // namespace
}  // namespace spire::demo
