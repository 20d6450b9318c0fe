// spire-explore end to end, in a real window (under xvfb-run; skipped
// without a display): a scripted decision change shows a new image, the one
// spire-demo renders from the decision file the explorer saves; an edit that
// breaks a source keeps the window and its last good variant, shows the
// compiler's diagnostic and lets the session go on; bad scripts fail with
// their line and column before anything renders.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include <unistd.h>

#include "demo/demo.h"
#include "explore/explorer_window_fixture.h"
#include "scene/texture.h"
#include "support/file_io.h"

namespace spire::explore {
namespace {

namespace fs = std::filesystem;

using ExplorerWindowTest = testing::ExplorerWindowFixture;

// Largest channel difference and the share of differing bytes.
struct PngDifference {
  int largest = 0;
  double differing = 0.0;
};

PngDifference comparePngs(const fs::path& a, const fs::path& b) {
  auto left = scene::loadImage(a);
  auto right = scene::loadImage(b);
  EXPECT_TRUE(left && right) << a << " " << b;
  if (!left || !right || left->bytes.size() != right->bytes.size()) return {255, 1.0};
  PngDifference d;
  size_t count = 0;
  for (size_t i = 0; i < left->bytes.size(); ++i) {
    const int diff = std::abs(int{left->bytes[i]} - int{right->bytes[i]});
    d.largest = std::max(d.largest, diff);
    count += diff > 0 ? 1 : 0;
  }
  d.differing = static_cast<double>(count) / static_cast<double>(left->bytes.size());
  return d;
}

TEST_F(ExplorerWindowTest, AScriptedChangeShowsWhatSpireDemoRendersOfTheSavedDecisions) {
  const fs::path decisions = fs::absolute("examples/decisions/terrain_baked_albedo.decisions");
  const fs::path path = script(
      "screenshot before.png\n"
      "load " +
      decisions.string() +
      "\n"
      "set Terrain.lighting = Fragment:basic\n"
      "save after.decisions\n"
      "screenshot after.png\n"
      "view split\n"
      "screenshot-window window.png\n"
      "quit\n");
  ASSERT_EQ(explore({"examples/scenes/terrain.json", "--validation", "--bake-size", "256", "--script", path.string(),
                     "--log", (dir_ / "log.json").string()}),
            0)
      << err_.str() << out_.str();
  const nlohmann::json changes = log()["changes"];
  ASSERT_EQ(changes.size(), 2U) << out_.str();
  EXPECT_EQ(changes[1]["action"], "set Terrain.lighting = Fragment:basic");
  EXPECT_TRUE(changes[1]["ok"]);
  EXPECT_GT(changes[1]["total_ms"].get<double>(), changes[1]["compile_ms"].get<double>());
  EXPECT_GT(comparePngs(dir_ / "before.png", dir_ / "after.png").differing, 0.01) << "the change must show";

  // spire-demo renders the file the explorer saved: the same image.
  const fs::path demoDir = dir_ / "demo";
  std::ostringstream demoOut;
  std::ostringstream demoErr;
  ASSERT_EQ(demo::runDemo({"examples/scenes/terrain.json", "--variant", (dir_ / "after.decisions").string(), "--frames",
                           "1", "--warmup", "1", "--bake-size", "256", "-o", demoDir.string()},
                          demoOut, demoErr),
            0)
      << demoErr.str();
  const PngDifference same = comparePngs(dir_ / "after.png", demoDir / "after.png");
  EXPECT_LE(same.largest, 2) << "share of bytes that differ: " << same.differing;
  EXPECT_TRUE(fs::exists(dir_ / "window.png"));
  EXPECT_NE(readWholeFile((dir_ / "after.decisions").string()).value_or("").find("[Format: \"RGBA8\"]"),
            std::string::npos)
      << "the loaded file's attributes are kept";
}

// --resolution replaces the scene's 640 x 480: the explorer renders (and
// its screenshots are) 96 x 72; a malformed size is a usage error.
TEST_F(ExplorerWindowTest, RendersAtTheGivenResolution) {
  const fs::path path = script("screenshot small.png\nquit\n");
  ASSERT_EQ(explore({"examples/scenes/terrain.json", "--validation", "--bake-size", "64", "--resolution", "96x72",
                     "--script", path.string()}),
            0)
      << err_.str() << out_.str();
  const auto image = scene::loadImage(dir_ / "small.png");
  ASSERT_TRUE(image);
  EXPECT_EQ(image->width, 96U);
  EXPECT_EQ(image->height, 72U);
  EXPECT_EQ(explore({"examples/scenes/terrain.json", "--resolution", "96x0", "--script", path.string()}), 2)
      << err_.str();
}

TEST_F(ExplorerWindowTest, ABrokenEditKeepsTheWindowAndTheLastGoodVariant) {
  for (const char* folder : {"examples", "pipelines", "stdlib"}) {
    fs::copy(folder, dir_ / folder, fs::copy_options::recursive);
  }
  const fs::path source = dir_ / "examples/terrain.spire";
  const std::string good = readWholeFile(source.string()).value();
  const fs::path path = script(
      "screenshot before.png\n"
      "save marker.decisions\n"
      "wait-reload\n"
      "screenshot after-error.png\n"
      "set Terrain.lighting = Fragment:basic\n"
      "quit\n");
  // The edit comes from outside, as from an editor, once the script says it
  // is waiting for it.
  std::thread editor([&] {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    while (!fs::exists(dir_ / "marker.decisions") && std::chrono::steady_clock::now() < deadline) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    std::string broken = good;
    broken.replace(broken.find("float mixFactor"), 0, "float typo = lightDr;\n    ");
    std::ofstream(source) << broken;
  });
  const int status = explore({(dir_ / "examples/scenes/terrain.json").string(), "--validation", "--bake-size", "256",
                              "--script", path.string(), "--log", (dir_ / "log.json").string()});
  editor.join();
  ASSERT_EQ(status, 0) << err_.str() << out_.str();
  const nlohmann::json changes = log()["changes"];
  ASSERT_EQ(changes.size(), 2U) << out_.str();
  EXPECT_FALSE(changes[0]["ok"]);
  const std::string error = changes[0]["error"];
  EXPECT_NE(error.find("terrain.spire:37:18: error[E3001]: use of undeclared identifier 'lightDr'"), std::string::npos)
      << error;
  EXPECT_NE(out_.str().find("failed: "), std::string::npos) << "the diagnostic is shown";
  EXPECT_EQ(comparePngs(dir_ / "before.png", dir_ / "after-error.png").largest, 0) << "the last good variant stays";
  EXPECT_TRUE(changes[1]["ok"]) << "the session goes on with the last good sources";
}

// The new variant's scene is prepared on the worker, beside the frame
// loop's draws: a variation that reads a material input the scene does not
// bind fails there, and the scene's diagnostic (its file, line and column)
// reaches the change's error while the previous variant stays on screen.
TEST_F(ExplorerWindowTest, AVariantTheSceneCannotDrawFailsOnTheWorkerWithTheScenesDiagnostic) {
  std::ofstream(dir_ / "tinted.spire") << "using \"" << fs::absolute("pipelines/engine.spire").string() << R"(";
shader Tinted using EnginePipeline {
    @FrameUniform mat4 matMVP;
    @MaterialUniform vec4 color;
    @MaterialUniform vec4 tint;
    vec4 projPos = matMVP * vec4(vert_pos, 1.0);
    vec4 shade = color;
    vec4 shade:tinted = color * tint;
    vec4 output = shade;
}
)";
  std::ofstream(dir_ / "tinted.json") << R"({
  "resolution": [96, 64], "frames": 2, "warmupFrames": 1,
  "camera": {"fovY": 60, "views": [{"position": [0, 2.2, 0.01], "target": [0, 0, 0]}]},
  "meshes": {"plane": {"type": "plane", "size": 2, "resolution": 4}},
  "instances": [{"mesh": "plane", "source": "tinted.spire", "shader": "Tinted",
                 "material": {"color": [0.2, 0.6, 0.9, 1]}}]
}
)";
  const fs::path path = script(
      "screenshot before.png\n"
      "set Tinted.shade = Fragment:tinted\n"
      "screenshot after.png\n"
      "set Tinted.shade = Vertex\n"
      "quit\n");
  ASSERT_EQ(explore({(dir_ / "tinted.json").string(), "--validation", "--script", path.string(), "--log",
                     (dir_ / "log.json").string()}),
            0)
      << err_.str() << out_.str();
  const nlohmann::json changes = log()["changes"];
  ASSERT_EQ(changes.size(), 2U) << out_.str();
  EXPECT_FALSE(changes[0]["ok"]);
  EXPECT_GT(changes[0]["prepare_ms"].get<double>(), 0.0) << "the failure comes from the prepare";
  const std::string error = changes[0]["error"];
  EXPECT_NE(error.find("tinted.json:6:30: error[E7102]: input 'tint' (vec4 from MaterialUniform) of 'Tinted' is "
                       "not bound"),
            std::string::npos)
      << error;
  EXPECT_EQ(comparePngs(dir_ / "before.png", dir_ / "after.png").largest, 0) << "the previous variant stays";
  EXPECT_TRUE(changes[1]["ok"]) << changes[1]["error"];
  EXPECT_GT(changes[1]["prepare_ms"].get<double>(), 0.0);
}

TEST_F(ExplorerWindowTest, ABadScriptFailsWithItsLineAndColumn) {
  const fs::path path = script("set Terrain.albedo = Nowhere\n");
  EXPECT_EQ(explore({"examples/scenes/terrain.json", "--script", path.string()}), 1);
  EXPECT_NE(err_.str().find("script.explore:1:1: error[E7202]: 'Nowhere' is not an alternative of 'Terrain.albedo'"),
            std::string::npos)
      << err_.str();
}

// `instance N` switches the explored instance of a two-instance scene; each
// keeps its decisions and undo history, a change to one keeps the other's
// pipeline, and an instance the scene does not have is E7202.
TEST_F(ExplorerWindowTest, SwitchingInstancesKeepsEachOnesDecisionsAndHistory) {
  const fs::path path = script(
      "set Terrain.lighting = Vertex:ggx\n"
      "instance 1\n"
      "set Couch.specular = Fragment:standardGGX\n"
      "save couch.decisions\n"
      "instance 0\n"
      "save terrain.decisions\n"
      "undo\n"
      "save terrain-undone.decisions\n"
      "instance 1\n"
      "save couch-again.decisions\n"
      "quit\n");
  ASSERT_EQ(explore({"examples/scenes/terrain_and_couch.json", "--validation", "--bake-size", "64", "--script",
                     path.string(), "--log", (dir_ / "log.json").string()}),
            0)
      << err_.str() << out_.str();
  const nlohmann::json changes = log()["changes"];
  ASSERT_EQ(changes.size(), 3U) << out_.str();
  EXPECT_EQ(changes[0]["instance"], 0);
  EXPECT_EQ(changes[1]["action"], "set Couch.specular = Fragment:standardGGX");
  EXPECT_EQ(changes[1]["instance"], 1);
  EXPECT_EQ(changes[2]["action"], "undo");
  EXPECT_EQ(changes[2]["instance"], 0);
  for (const nlohmann::json& change : changes) EXPECT_TRUE(change["ok"]) << change["error"];
  // Each change builds the changed instance's pipeline and reuses the other's,
  // whose kernels did not change. The undo goes back to the terrain's
  // starting kernels, whose pipeline the reference still draws with.
  EXPECT_EQ(changes[0]["pipelines_created"], 1);
  EXPECT_EQ(changes[0]["pipelines_reused"], 1);
  EXPECT_EQ(changes[1]["pipelines_created"], 1);
  EXPECT_EQ(changes[1]["pipelines_reused"], 1);
  EXPECT_EQ(changes[2]["pipelines_created"], 0);
  EXPECT_EQ(changes[2]["pipelines_reused"], 2);
  const auto text = [&](const char* name) { return readWholeFile((dir_ / name).string()).value_or(""); };
  EXPECT_NE(text("couch.decisions").find("Couch.specular = Fragment:standardGGX"), std::string::npos);
  EXPECT_NE(text("terrain.decisions").find("Terrain.lighting = Vertex:ggx"), std::string::npos);
  EXPECT_EQ(text("terrain-undone.decisions").find("Terrain.lighting"), std::string::npos)
      << "undo takes back the instance's own last change, not the other instance's";
  EXPECT_EQ(text("couch-again.decisions"), text("couch.decisions"));

  const fs::path bad = script("instance 2\n");
  EXPECT_EQ(explore({"examples/scenes/terrain_and_couch.json", "--script", bad.string()}), 1);
  EXPECT_NE(err_.str().find("script.explore:1:1: error[E7202]: instance 2: the scene has 2 instance(s), from 0"),
            std::string::npos)
      << err_.str();
}

TEST(ExploreCli, NeedsASceneAndDocumentsItsFlags) {
  std::ostringstream out;
  std::ostringstream err;
  EXPECT_EQ(runExploreTool({}, out, err), 2);
  EXPECT_NE(err.str().find("a scene file is required"), std::string::npos) << err.str();
  std::ostringstream help;
  EXPECT_EQ(runExploreTool({"--help"}, help, err), 0);
  for (const char* flag :
       {"--script", "--log", "--reference", "--decisions", "--instance", "--save-to", "--tune-dir"}) {
    EXPECT_NE(help.str().find(flag), std::string::npos) << flag;
  }
}

// The start-up options: --instance picks the explored instance, --decisions
// its first variant, --reference what the error is measured against, and
// --save-to the file of the Save and Load buttons, which a script's `save`
// and `load` without a file use too.
TEST_F(ExplorerWindowTest, StartOptionsPickTheInstanceDecisionsReferenceAndButtonsFile) {
  const fs::path decisions = fs::absolute("examples/decisions/couch/baked_phong.decisions");
  const fs::path buttons = dir_ / "buttons.decisions";
  const fs::path path = script(
      "save\n"
      "view reference\n"
      "screenshot reference.png\n"
      "view variant\n"
      "screenshot variant.png\n"
      "set Couch.specular = Fragment:standardGGX\n"
      "load\n"
      "save reloaded.decisions\n"
      "quit\n");
  ASSERT_EQ(explore({"examples/scenes/terrain_and_couch.json", "--validation", "--bake-size", "64", "--instance", "1",
                     "--decisions", decisions.string(), "--reference", decisions.string(), "--save-to",
                     buttons.string(), "--script", path.string(), "--log", (dir_ / "log.json").string()}),
            0)
      << err_.str() << out_.str();
  EXPECT_EQ(log()["shader"], "Couch");
  const std::string saved = readWholeFile(buttons.string()).value_or("");
  for (const char* line : {"Couch.albedo = PrebakeTex", "Couch.specular = Fragment:standardPhong"}) {
    EXPECT_NE(saved.find(line), std::string::npos) << line << " in\n" << saved;
  }
  EXPECT_EQ(comparePngs(dir_ / "reference.png", dir_ / "variant.png").largest, 0)
      << "the reference is the starting decisions";
  const nlohmann::json changes = log()["changes"];
  ASSERT_EQ(changes.size(), 3U) << out_.str();  // --decisions, set, load
  EXPECT_EQ(changes[0]["action"], "load " + decisions.string());
  EXPECT_EQ(changes[2]["action"], "load");
  EXPECT_TRUE(changes[2]["ok"]);
  EXPECT_EQ(readWholeFile((dir_ / "reloaded.decisions").string()).value_or("x"), saved)
      << "`load` without a file reads what `save` without a file wrote";
}

}  // namespace
}  // namespace spire::explore
