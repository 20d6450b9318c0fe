// spire-simplify --search on a scene the test writes: a shader whose `color`
// is the max of three blurs (24 texture reads each, the third a quarter as
// bright), so that every rewrite the rules propose drops a blur and saves a
// third or more of the frame. The search runs in process with validation on,
// as a user runs it; the chain it writes is checked with spirec.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "driver/exit_codes.h"
#include "engine/device_fixture.h"
#include "lod/lod_policy.h"
#include "scene/texture.h"
#include "search/search_tool.h"
#include "tune/tune_cli.h"

namespace spire::search {
namespace {

namespace fs = std::filesystem;

constexpr const char* kShader = R"(using "pipelines/engine.spire";

shader Blurred using EnginePipeline {
    @MaterialUniform sampler2D colorMap;
    @FrameUniform mat4 matMVP;

    @Fragment vec4 wide {
        vec4 sum = vec4(0.0);
        for (int i = 0; i < 24; i++) { sum += texture(colorMap, vert_uv + vec2(float(i) * 0.004, 0.0)); }
        return sum / 24.0;
    }
    @Fragment vec4 tall {
        vec4 sum = vec4(0.0);
        for (int i = 0; i < 24; i++) { sum += texture(colorMap, vert_uv + vec2(0.0, float(i) * 0.004)); }
        return sum / 24.0;
    }
    @Fragment vec4 faint {
        vec4 sum = vec4(0.0);
        for (int i = 0; i < 24; i++) { sum += texture(colorMap, vert_uv + vec2(float(i) * 0.003)); }
        return sum / 96.0;
    }
    @Fragment vec4 color = max(max(wide, tall), faint);

    vec4 projPos = matMVP * vec4(vert_pos, 1.0);
    vec4 output = color;
}
)";

std::string sceneJson() {
  return fmt::format(R"({{"resolution": [160, 120], "frames": 2, "warmupFrames": 1, "clearColor": [0, 0, 0, 1],
  "includePaths": ["{}"],
  "camera": {{"fovY": 60, "views": [{{"position": [0, 1.2, 0.01], "target": [0, 0, 0]}}]}},
  "meshes": {{"plane": {{"type": "plane", "size": 2, "resolution": 4}}}},
  "textures": {{"noise": {{"type": "noise", "size": 64, "seed": 9, "octaves": 3}}}},
  "instances": [{{"mesh": "plane", "source": "blurred.spire", "shader": "Blurred",
                  "material": {{"colorMap": "noise"}}}}]}}
)",
                     SPIRE_SOURCE_DIR);
}

std::string readText(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::vector<std::vector<std::string>> csvRows(const fs::path& path) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream lines(readText(path));
  std::string line;
  std::getline(lines, line);  // the header
  while (std::getline(lines, line)) {
    std::vector<std::string> fields;
    std::istringstream cells(line);
    // The fields this test reads come before any quoted one.
    for (std::string cell; std::getline(cells, cell, ',');) fields.push_back(cell);
    rows.push_back(fields);
  }
  return rows;
}

class SearchRun : public vk::testing::DeviceTest {
 protected:
  void SetUp() override {
    DeviceTest::SetUp();
    dir_ = fs::temp_directory_path() / fmt::format("spire_search_{}_{}", ::getpid(),
                                                   ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    std::ofstream(dir_ / "blurred.spire") << kShader;
    std::ofstream(dir_ / "scene.json") << sceneJson();
  }
  void TearDown() override {
    DeviceTest::TearDown();
    if (!HasFailure()) fs::remove_all(dir_);
  }
  // The search of `color` on the test's scene into out/, with validation,
  // and `extra` options. Nine pairs of frames per candidate: a median the
  // timing noise of a busy machine does not move.
  std::vector<std::string> searchArgs(const std::vector<std::string>& extra) const {
    std::vector<std::string> args{"--search",
                                  "--scene",
                                  (dir_ / "scene.json").string(),
                                  "--shader",
                                  "Blurred",
                                  "--component",
                                  "color",
                                  "--k1",
                                  "4",
                                  "--frames",
                                  "9",
                                  "--validation",
                                  "-o",
                                  (dir_ / "out").string()};
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
  }
  // ramp.json: the test's scene with its instance drawn by the Ramp shader
  // of ramp.spire (which the test writes).
  void writeRampScene() const {
    std::string scene = sceneJson();
    const std::string blurred = "\"blurred.spire\", \"shader\": \"Blurred\"";
    scene.replace(scene.find(blurred), blurred.size(), "\"ramp.spire\", \"shader\": \"Ramp\"");
    std::ofstream(dir_ / "ramp.json") << scene;
  }
  // The search of `ramp` in the Ramp shader of ramp.json (a test writes
  // both), with validation, into DIR, and `extra` options. Without moves
  // unless `moves`: the tests of the rules would see a ramp moved per
  // vertex, where it is exact, before any rewrite.
  std::vector<std::string> rampArgs(const std::string& dir, const std::vector<std::string>& extra,
                                    bool moves = false) const {
    std::vector<std::string> args{"--search",     "--scene", (dir_ / "ramp.json").string(),
                                  "--shader",     "Ramp",    "--component",
                                  "ramp",         "--k1",    "4",
                                  "--validation", "-o",      (dir_ / dir).string()};
    if (!moves) args.push_back("--no-moves");
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
  }
  // The console of one level of the ramp's search without the average
  // rule, ACSE or moves, into out-without/; it must succeed.
  std::string searchWithoutProbesOrMoves() const {
    std::ostringstream out, err;
    EXPECT_EQ(runSearchTool(rampArgs("out-without", {"--max-levels", "1", "--no-average", "--no-acse"}), out, err),
              kExitSuccess)
        << err.str();
    return out.str();
  }
  // spirec on the written module with level K's decisions: the placement it dumps.
  std::string compileLevel(size_t k) { return compileDecisions(dir_ / fmt::format("out/level{}.decisions", k)); }
  // spirec on the written module with `decisions`, without a warning: the
  // placement it dumps.
  std::string compileDecisions(const fs::path& decisions) {
    const fs::path err = dir_ / "spirec.err";
    const fs::path placement = dir_ / "placement.txt";
    const std::string command =
        fmt::format("{} '{}' -I '{}' --shader BlurredSearch --decisions '{}' --dump-placement > '{}' 2> '{}'",
                    SPIRE_SPIREC_EXE, (dir_ / "out/BlurredSearch.spire").string(), SPIRE_SOURCE_DIR, decisions.string(),
                    placement.string(), err.string());
    EXPECT_EQ(std::system(command.c_str()), 0) << command << "\n" << readText(err);
    EXPECT_EQ(readText(err), "") << command;
    return readText(placement);
  }

  // Two images of the same size whose channels differ by at most 1 (of
  // 255): mix(a, b, 1) need not round to b exactly.
  static void expectSameImage(const fs::path& a, const fs::path& b) {
    const auto imageA = scene::loadImage(a);
    const auto imageB = scene::loadImage(b);
    ASSERT_TRUE(imageA && imageB) << a << " " << b;
    ASSERT_EQ(imageA->width, imageB->width);
    ASSERT_EQ(imageA->bytes.size(), imageB->bytes.size());
    int largest = 0;
    for (size_t i = 0; i < imageA->bytes.size(); ++i) {
      largest = std::max(largest, std::abs(int{imageA->bytes[i]} - int{imageB->bytes[i]}));
    }
    EXPECT_LE(largest, 1) << a << " against " << b;
  }

  // lod_policy.json names some of the chain's levels, in the chain's order
  // from near to far, by the decision
  // files beside it; and it is a policy the engine draws: spire-tune
  // --lod-policy measures every level of it on a scene that uses the module.
  void expectAPolicyOfTheChain(size_t levels) {
    SourceManager sources;
    DiagnosticList diags;
    const auto policy = lod::loadLodPolicy(dir_ / "out/lod_policy.json", sources, diags);
    ASSERT_TRUE(policy) << readText(dir_ / "out/lod_policy.json");
    ASSERT_GE(policy->levels.size(), 1U);
    size_t previous = 0;
    for (size_t i = 0; i < policy->levels.size(); ++i) {
      const lod::LodLevel& level = policy->levels[i];
      EXPECT_TRUE(level.member.empty());
      ASSERT_EQ(level.decisions.count("BlurredSearch"), 1U) << readText(dir_ / "out/lod_policy.json");
      const fs::path file = level.decisions.at("BlurredSearch");
      EXPECT_EQ(fs::canonical(file.parent_path()), fs::canonical(dir_ / "out"));
      // A transition's band lies between the two levels it blends.
      EXPECT_EQ(level.blend, file.stem().string().starts_with("transition"));
      if (file.stem().string().starts_with("transition")) {
        ASSERT_TRUE(i > 0 && i + 1 < policy->levels.size()) << readText(dir_ / "out/lod_policy.json");
        EXPECT_EQ(file.filename(),
                  fmt::format("transition{}_{}.decisions",
                              policy->levels[i - 1].decisions.at("BlurredSearch").stem().string().substr(5),
                              policy->levels[i + 1].decisions.at("BlurredSearch").stem().string().substr(5)));
        continue;
      }
      const size_t k = std::stoul(file.stem().string().substr(std::string("level").size()));
      EXPECT_LT(k, levels);
      // The nearest band may skip level 0 where a level's error is 0 (as
      // dropping the faint blur's is).
      EXPECT_TRUE(i == 0 || k > previous) << "levels out of the chain's order";
      previous = k;
    }
    EXPECT_NE(readText(dir_ / "out/report.md").find("## Level-of-detail policy"), std::string::npos);

    std::string scene = sceneJson();
    scene.replace(scene.find("\"blurred.spire\", \"shader\": \"Blurred\""),
                  std::string("\"blurred.spire\", \"shader\": \"Blurred\"").size(),
                  "\"out/BlurredSearch.spire\", \"shader\": \"BlurredSearch\"");
    scene.insert(scene.rfind('}'), ", \"lod\": {\"policy\": \"out/lod_policy.json\"}");
    std::ofstream(dir_ / "lod_scene.json") << scene;
    std::ostringstream out, err;
    ASSERT_EQ(tune::runTune({(dir_ / "lod_scene.json").string(), "--lod-policy", (dir_ / "measured.json").string(),
                             "--distances", "1,4", "--validation"},
                            out, err),
              kExitSuccess)
        << err.str() << out.str();
    EXPECT_NE(readText(dir_ / "measured.json").find("\"BlurredSearch\": \"out/level"), std::string::npos)
        << readText(dir_ / "measured.json");
  }

  fs::path dir_;
};

TEST_F(SearchRun, WritesAMonotoneChainOfAccumulatingRewrites) {
  std::ostringstream out, err;
  const std::vector<std::string> args = searchArgs({"--max-levels", "3"});
  ASSERT_EQ(runSearchTool(args, out, err), kExitSuccess) << err.str() << out.str();
  const auto rows = csvRows(dir_ / "out/chain.csv");
  // Every rewrite drops a blur, so there are two levels at least (then only
  // one blur may be left, which no rule rewrites).
  ASSERT_GE(rows.size(), 3U) << out.str();
  EXPECT_EQ(std::stod(rows[0][1]), 0.0);
  for (size_t k = 1; k < rows.size(); ++k) {
    EXPECT_GE(std::stod(rows[k][1]), std::stod(rows[k - 1][1])) << "error falls at level " << k;
    // He et al.'s cost model C orders the chain: every level is cheaper.
    EXPECT_LT(std::stod(rows[k][4]), std::stod(rows[k - 1][4])) << "C does not fall at level " << k;
    EXPECT_EQ(rows[k][5], "color");
    EXPECT_EQ(rows[k][6], fmt::format("level{}", k));
    // Level k rewrites level k-1's definition: the rewrites accumulate.
    EXPECT_EQ(rows[k][7], k == 1 ? "color" : fmt::format("color:level{}", k - 1));
  }
  EXPECT_GT(std::stod(rows.back()[1]), 0.0);
  const std::string module = readText(dir_ / "out/BlurredSearch.spire");
  EXPECT_NE(module.find("using \"../blurred.spire\";"), std::string::npos) << module;
  EXPECT_NE(module.find("shader BlurredSearch : Blurred {"), std::string::npos) << module;
  for (size_t k = 0; k < rows.size(); ++k) {
    const std::string placement = compileLevel(k);
    const std::string expected = k == 0 ? "color = Fragment\n" : fmt::format("color = Fragment:level{}\n", k);
    EXPECT_NE(placement.find(expected), std::string::npos) << placement;
  }
  EXPECT_FALSE(fs::exists(dir_ / "out" / fmt::format("level{}.decisions", rows.size())));
  EXPECT_TRUE(fs::exists(dir_ / "out/report.md"));
  EXPECT_GT(fs::file_size(dir_ / "out/error_time.png"), 0U);
  for (size_t k = 0; k < rows.size(); ++k) {
    const fs::path image = dir_ / "out" / fmt::format("level{}.png", k);
    ASSERT_TRUE(fs::exists(image)) << image;
    EXPECT_NE(readText(dir_ / "out/report.md").find(fmt::format("](level{}.png)", k)), std::string::npos);
  }
  // The test's shader reads matMVP, so the transition shaders read the eye
  // and the model matrix from its world: they are written, marked
  // [Transition] so that spire-tune does not explore them.
  EXPECT_EQ(readText(dir_ / "out/report.md").find("do not compile"), std::string::npos);
  EXPECT_NE(module.find("[Transition] vec4 color:transition"), std::string::npos) << module;
  EXPECT_TRUE(std::any_of(fs::directory_iterator(dir_ / "out"), fs::directory_iterator(), [](const auto& entry) {
    return entry.path().filename().string().starts_with("transition");
  }));
  // Level 0 is the original, the last level lost at least one blur: the
  // images differ.
  EXPECT_NE(readText(dir_ / "out/level0.png"), readText(dir_ / "out" / fmt::format("level{}.png", rows.size() - 1)));
  expectAPolicyOfTheChain(rows.size());
}

// Dropping the faint blur changes no pixel; dropping either of the others
// costs an RMSE near 0.09 (see the test above), over the budget: the chain
// ends after one level and says why.
TEST_F(SearchRun, StopsAtTheErrorBudget) {
  std::ostringstream out, err;
  const std::vector<std::string> args = searchArgs({"--error-budget", "0.05"});
  ASSERT_EQ(runSearchTool(args, out, err), kExitSuccess) << err.str() << out.str();
  const auto rows = csvRows(dir_ / "out/chain.csv");
  ASSERT_EQ(rows.size(), 2U) << out.str();
  EXPECT_EQ(rows[1][8], "call-to-argument");
  EXPECT_LE(std::stod(rows[1][1]), 0.05);
  EXPECT_NE(readText(dir_ / "out/report.md").find("Stopped: no candidate is within the error budget"),
            std::string::npos)
      << readText(dir_ / "out/report.md");
}

// --resolution replaces the scene's 160 x 120 for the whole search: every
// level is rendered, measured and written at 48 x 36.
TEST_F(SearchRun, RendersAtTheGivenResolution) {
  std::ostringstream out, err;
  const std::vector<std::string> args =
      searchArgs({"--max-levels", "1", "--no-average", "--no-acse", "--resolution", "48x36"});
  ASSERT_EQ(runSearchTool(args, out, err), kExitSuccess) << err.str() << out.str();
  const size_t levels = csvRows(dir_ / "out/chain.csv").size();
  ASSERT_EQ(levels, 2U) << out.str();
  for (size_t k = 0; k < levels; ++k) {
    const auto image = scene::loadImage(dir_ / "out" / fmt::format("level{}.png", k));
    ASSERT_TRUE(image) << k;
    EXPECT_EQ(image->width, 48U) << k;
    EXPECT_EQ(image->height, 36U) << k;
  }
  std::ostringstream badOut, badErr;
  std::vector<std::string> bad = searchArgs({"--resolution", "48x"});
  EXPECT_EQ(runSearchTool(bad, badOut, badErr), kExitUsageError) << badErr.str();
}

// With --reference, errors and times are against that decision file's
// variant, here one whose `wide` is black: level 0 is already off it, every
// level at least as far, and a budget below level 0's error leaves no level.
TEST_F(SearchRun, MeasuresAgainstTheGivenReference) {
  std::string shader = kShader;
  const std::string color = "    @Fragment vec4 color =";
  shader.insert(shader.find(color), "    @Fragment vec4 wide:dark = vec4(0.0);\n");
  std::ofstream(dir_ / "blurred.spire") << shader;
  std::ofstream(dir_ / "dark.decisions") << "Blurred.wide = Fragment:dark\n";
  const std::string reference = (dir_ / "dark.decisions").string();
  std::ostringstream out, err;
  ASSERT_EQ(
      runSearchTool(searchArgs({"--max-levels", "1", "--no-average", "--no-acse", "--reference", reference}), out, err),
      kExitSuccess)
      << err.str() << out.str();
  const auto rows = csvRows(dir_ / "out/chain.csv");
  ASSERT_EQ(rows.size(), 2U) << out.str();
  const double original = std::stod(rows[0][1]);
  EXPECT_GT(original, 0.01) << "level 0 draws the wide blur the reference leaves black";
  EXPECT_GE(std::stod(rows[1][1]), original);
  EXPECT_NE(readText(dir_ / "out/report.md").find("Error is the RMSE against the variant of `" + reference + "`"),
            std::string::npos)
      << readText(dir_ / "out/report.md");
  EXPECT_NE(readText(dir_ / "out/level1.decisions").find("against the variant of `" + reference + "`"),
            std::string::npos);

  fs::remove_all(dir_ / "out");
  std::ostringstream tightOut, tightErr;
  const std::string budget = fmt::format("{}", original / 2);
  ASSERT_EQ(runSearchTool(searchArgs({"--max-levels", "1", "--no-average", "--no-acse", "--reference", reference,
                                      "--error-budget", budget}),
                          tightOut, tightErr),
            kExitSuccess)
      << tightErr.str();
  EXPECT_EQ(csvRows(dir_ / "out/chain.csv").size(), 1U) << tightOut.str();
}

// User rules propose beside the built-in ones, and one whose replacement
// compiles to another type (`sum += <float>` is legal where a vec4 was
// added) is dropped with the reason, as spire-simplify drops it.
TEST_F(SearchRun, OffersUserRulesAndDropsThoseThatChangeTheType) {
  std::ofstream(dir_ / "taps.rules") << "# a texel's coordinate for its colour: not a vec4\n"
                                        "rule tap-u: texture($m, $uv) -> $uv.x\n";
  std::ostringstream out, err;
  const std::vector<std::string> args =
      searchArgs({"--component", "wide", "--rules", (dir_ / "taps.rules").string(), "--max-levels", "1"});
  ASSERT_EQ(runSearchTool(args, out, err), kExitSuccess) << err.str() << out.str();
  const std::string report = readText(dir_ / "out/report.md");
  EXPECT_NE(report.find("dropped wide (tap-u): '((vert_uv + vec2(float(i) * 0.004, 0.0)).x)' has type 'float', "
                        "not 'vec4'"),
            std::string::npos)
      << report;
  EXPECT_EQ(csvRows(dir_ / "out/chain.csv").size(), 2U) << out.str();
}

// A rule file with an error stops the search before it opens a device.
TEST(SearchCommandLine, ReportsRuleFileErrors) {
  const fs::path dir = fs::temp_directory_path() / fmt::format("spire_search_rules_{}", ::getpid());
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "bad.rules") << "rule oops: pow($x, 2.0) -> $y\n";
  std::ostringstream out, err;
  EXPECT_EQ(runSearchTool({"--search", "--scene", "examples/scenes/terrain.json", "--shader", "Terrain", "--rules",
                           (dir / "bad.rules").string(), "-o", (dir / "out").string()},
                          out, err),
            kExitInputError);
  EXPECT_NE(err.str().find("bad.rules:1:28: error[E8001]: '$y' is not a metavariable of the pattern"),
            std::string::npos)
      << err.str();
  EXPECT_FALSE(fs::exists(dir / "out"));
  fs::remove_all(dir);
}

// Ordered by measured frame time instead, the chain's time never rises.
TEST_F(SearchRun, OrdersByMeasuredTimeWhenAsked) {
  std::ostringstream out, err;
  const std::vector<std::string> args = searchArgs({"--max-levels", "2", "--cost", "time"});
  ASSERT_EQ(runSearchTool(args, out, err), kExitSuccess) << err.str() << out.str();
  const auto rows = csvRows(dir_ / "out/chain.csv");
  ASSERT_GE(rows.size(), 2U) << out.str();
  for (size_t k = 1; k < rows.size(); ++k) {
    EXPECT_GE(std::stod(rows[k][1]), std::stod(rows[k - 1][1])) << "error falls at level " << k;
    EXPECT_LT(std::stod(rows[k][2]), std::stod(rows[k - 1][2])) << "time does not fall at level " << k;
  }
  EXPECT_NE(readText(dir_ / "out/report.md").find("the chain ordered by the measured time"), std::string::npos);
}

// Pellacini's average rule: a ramp across the plane, which the camera
// looks straight down on, centred. Its only rewrites are averages, and
// every subtree of it averages to 0.5 in each scalar over the pixels the
// plane covers (its texture coordinate, symmetric about the image's centre);
// the chain's first level puts that constant in its place. Without the rule
// there is nothing to rewrite.
TEST_F(SearchRun, TheAverageRuleReplacesASubtreeByItsAverageOverThePixels) {
  std::ofstream(dir_ / "ramp.spire") << R"(using "pipelines/engine.spire";
shader Ramp using EnginePipeline {
    @FrameUniform mat4 matMVP;
    vec4 projPos = matMVP * vec4(vert_pos, 1.0);
    float ramp = vert_uv.x;
    vec4 output = vec4(vec3(ramp), 1.0);
}
)";
  // The ramp on a plane half as wide, over a light grey one of another
  // shader that fills the rest of the image: only the ramp's pixels count.
  std::string scene = sceneJson();
  scene.replace(scene.find("\"plane\", \"source\": \"blurred.spire\", \"shader\": \"Blurred\""),
                std::string("\"plane\", \"source\": \"blurred.spire\", \"shader\": \"Blurred\"").size(),
                "\"small\", \"source\": \"ramp.spire\", \"shader\": \"Ramp\"");
  scene.replace(scene.find("\"meshes\": {"), std::string("\"meshes\": {").size(),
                R"("meshes": {"small": {"type": "plane", "size": 1, "resolution": 4}, )");
  scene.replace(scene.rfind("}]"), 2,
                fmt::format(R"(}}, {{"mesh": "plane", "source": "{}/tests/data/engine/flat_plane.spire",
      "shader": "FlatPlane", "transform": {{"translate": [0, -0.1, 0]}}, "material": {{"color": [0.9, 0.9, 0.9, 1]}}}}])",
                            SPIRE_SOURCE_DIR));
  std::ofstream(dir_ / "ramp.json") << scene;
  const std::vector<std::string> args = rampArgs("out", {"--max-levels", "1"});
  std::ostringstream out, err;
  ASSERT_EQ(runSearchTool(args, out, err), kExitSuccess) << err.str() << out.str();
  const std::string log = out.str();
  const size_t at = log.find("ramp:level1 = ramp with average: '");
  ASSERT_NE(at, std::string::npos) << log;
  const size_t open = log.find("-> '(", at);
  ASSERT_NE(open, std::string::npos) << log;
  const size_t begin = open + std::string("-> '(").size();
  const std::string constant = log.substr(begin, log.find(")'", begin) - begin);  // "float(0.5)" or "vec2(...)"
  std::istringstream values(constant.substr(constant.find('(') + 1));
  size_t count = 0;
  for (std::string value; std::getline(values, value, ',');) {
    EXPECT_NEAR(std::stod(value), 0.5, 0.01) << constant;
    ++count;
  }
  EXPECT_GE(count, 1U) << constant;
  EXPECT_NE(readText(dir_ / "out/RampSearch.spire").find("float ramp:level1 = (" + constant + ");"), std::string::npos)
      << readText(dir_ / "out/RampSearch.spire");

  std::ostringstream noOut, noErr;
  ASSERT_EQ(runSearchTool(rampArgs("out-without", {"--max-levels", "1", "--no-average"}), noOut, noErr), kExitSuccess)
      << noErr.str() << noOut.str();
  EXPECT_EQ(noOut.str().find("average"), std::string::npos) << noOut.str();
  EXPECT_NE(noOut.str().find("stopped: no rewrite is left"), std::string::npos) << noOut.str();
}

// Pellacini's renormalization: dropping the blend with a texture that adds
// about 0.75 on average (`mix(u, t + 1.0, 0.5)` -> `u`) lowers the ramp's
// average by about half that; renormalized, the level adds it back, and its
// error is what the texture varied by, a fraction of the unrenormalized
// level's.
TEST_F(SearchRun, RenormalizedCandidatesKeepTheComponentsAverage) {
  std::ofstream(dir_ / "ramp.spire") << R"(using "pipelines/engine.spire";
shader Ramp using EnginePipeline {
    @MaterialUniform sampler2D colorMap;
    @FrameUniform mat4 matMVP;
    vec4 projPos = matMVP * vec4(vert_pos, 1.0);
    float ramp = mix(vert_uv.x, texture(colorMap, vert_uv).x + 1.0, 0.5);
    vec4 output = vec4(vec3(ramp), 1.0);
}
)";
  writeRampScene();
  // Level 1's row of chain.csv, of a search with `extra` options. K2 keeps
  // every candidate, so the one that saves the fetch is taken.
  const auto levelOne = [&](const std::string& out, const std::vector<std::string>& extra) {
    std::vector<std::string> args = rampArgs(out, {"--k2", "10", "--max-levels", "1", "--no-average"});
    args.insert(args.end(), extra.begin(), extra.end());
    std::ostringstream log, err;
    EXPECT_EQ(runSearchTool(args, log, err), kExitSuccess) << err.str() << log.str();
    const std::string csv = readText(dir_ / out / "chain.csv");
    const size_t row = csv.find("\n1,");
    EXPECT_NE(row, std::string::npos) << log.str();
    return row == std::string::npos ? std::string() : csv.substr(row + 1);
  };
  const std::string plain = levelOne("plain", {});
  const std::string renormalized = levelOne("renormalized", {"--renormalize"});
  const std::string rewrite = ",\"mix(vert_uv.x, texture(colorMap, vert_uv).x + 1.0, 0.5)\",(vert_uv.x)";
  EXPECT_NE(plain.find(",call-to-argument" + rewrite), std::string::npos) << plain;
  const std::string rule = ",\"call-to-argument, renormalized by float(";
  const size_t at = renormalized.find(rule);
  ASSERT_NE(at, std::string::npos) << renormalized;
  EXPECT_NE(renormalized.find(rewrite), std::string::npos) << "the same rewrite: " << renormalized;
  // The texture adds 0.5 x (its average + 1) to a ramp of average 0.5 halved.
  const double shift = std::stod(renormalized.substr(at + rule.size()));
  EXPECT_GT(shift, 0.3) << renormalized;
  EXPECT_LT(shift, 0.7) << renormalized;
  const auto rmse = [](const std::string& row) { return std::stod(row.substr(row.find(',') + 1)); };
  EXPECT_LT(rmse(renormalized), rmse(plain) / 2) << "the bias is gone from the error:\n" << plain << renormalized;
  EXPECT_NE(readText(dir_ / "renormalized/RampSearch.spire").find("float ramp:level1 = (((vert_uv.x) + float("),
            std::string::npos)
      << readText(dir_ / "renormalized/RampSearch.spire");
}

// He et al.'s approximate common subexpression elimination: the ramp is
// the texture coordinate but for a term too small to see, and `u`, computed
// per vertex and interpolated, is the coordinate itself. Profiled at the
// pixels, the ramp's whole expression is closest to `u`, which replaces it
// across the stages: the fetch and the square root are gone for an error
// far below the other rules' (the average rule is left out here: it would
// average the tiny term away instead).
TEST_F(SearchRun, ApproximateCommonSubexpressionsAreReplacedByTheClosestComponent) {
  std::ofstream(dir_ / "ramp.spire") << R"(using "pipelines/engine.spire";
shader Ramp using EnginePipeline {
    @MaterialUniform sampler2D colorMap;
    @FrameUniform mat4 matMVP;
    vec4 projPos = matMVP * vec4(vert_pos, 1.0);
    @Vertex float u = vert_uv.x;
    float ramp = sqrt(vert_uv.x * vert_uv.x + 0.0001 * texture(colorMap, vert_uv).x);
    vec4 output = vec4(ramp, u, 0.0, 1.0);
}
)";
  writeRampScene();
  std::ostringstream out, err;
  ASSERT_EQ(runSearchTool(rampArgs("out", {"--max-levels", "1", "--no-average"}), out, err), kExitSuccess)
      << err.str() << out.str();
  EXPECT_NE(out.str().find("acse: 'sqrt(vert_uv.x * vert_uv.x + 0.0001 * texture(colorMap, vert_uv).x)' in ramp is "
                           "closest to u"),
            std::string::npos)
      << out.str();
  const auto rows = csvRows(dir_ / "out/chain.csv");
  ASSERT_EQ(rows.size(), 2U) << out.str();
  EXPECT_LT(std::stod(rows[1][1]), 0.001);
  EXPECT_LT(std::stod(rows[1][4]), std::stod(rows[0][4]) / 4) << "C falls by more than the fetch";
  EXPECT_NE(readText(dir_ / "out/RampSearch.spire").find("float ramp:level1 = (u);"), std::string::npos)
      << readText(dir_ / "out/RampSearch.spire");
  EXPECT_NE(readText(dir_ / "out/level1.decisions").find("RampSearch.u = Vertex"), std::string::npos)
      << readText(dir_ / "out/level1.decisions");

  const std::string without = searchWithoutProbesOrMoves();
  EXPECT_EQ(without.find("acse"), std::string::npos) << without;
}

// He et al.'s move to vertex as a step of the chain: the ramp is an affine
// function of the texture coordinate, so per vertex it is exact, and moving
// it there saves its per-pixel cost for no error. The next level rewrites
// the moved definition where the move put it.
TEST_F(SearchRun, AMoveToACheaperWorldIsAStepOfTheChain) {
  std::ofstream(dir_ / "ramp.spire") << R"(using "pipelines/engine.spire";
shader Ramp using EnginePipeline {
    @FrameUniform mat4 matMVP;
    vec4 projPos = matMVP * vec4(vert_pos, 1.0);
    float ramp = vert_uv.x * 0.5 + 0.25;
    vec4 output = vec4(vec3(ramp), 1.0);
}
)";
  writeRampScene();
  std::ostringstream out, err;
  ASSERT_EQ(runSearchTool(rampArgs("out", {"--max-levels", "2", "--no-average", "--no-acse"}, true), out, err),
            kExitSuccess)
      << err.str() << out.str();
  const auto rows = csvRows(dir_ / "out/chain.csv");
  ASSERT_EQ(rows.size(), 3U) << out.str();
  EXPECT_EQ(rows[1][5], "ramp");
  EXPECT_EQ(rows[1][8], "move");
  EXPECT_EQ(rows[1][9], "Fragment");
  EXPECT_EQ(rows[1][10], "Vertex");
  EXPECT_LT(std::stod(rows[1][1]), 0.002) << out.str();
  EXPECT_LT(std::stod(rows[1][4]), std::stod(rows[0][4])) << "C falls";
  EXPECT_NE(out.str().find("level 1: "), std::string::npos);
  EXPECT_NE(out.str().find("ramp moved: 'Fragment' -> 'Vertex'"), std::string::npos) << out.str();
  EXPECT_NE(readText(dir_ / "out/report.md").find("`ramp` moved: `Fragment` → `Vertex`"), std::string::npos)
      << readText(dir_ / "out/report.md");
  EXPECT_NE(readText(dir_ / "out/level1.decisions").find("RampSearch.ramp = Vertex\n"), std::string::npos)
      << readText(dir_ / "out/level1.decisions");
  // Level 2 rewrites the definition level 1 moved, and keeps it per vertex.
  EXPECT_NE(rows[2][8], "move");
  EXPECT_EQ(rows[2][6], "level2");
  EXPECT_EQ(rows[2][7], "ramp");
  EXPECT_NE(readText(dir_ / "out/level2.decisions").find("RampSearch.ramp = Vertex:level2\n"), std::string::npos)
      << readText(dir_ / "out/level2.decisions");
  const std::string module = readText(dir_ / "out/RampSearch.spire");
  EXPECT_EQ(module.find("ramp:level1"), std::string::npos) << module;
  EXPECT_NE(module.find("ramp:level2"), std::string::npos) << module;
  // The transitions blend the per-pixel ramp with the per-vertex one.
  EXPECT_EQ(readText(dir_ / "out/report.md").find("do not compile"), std::string::npos);

  const std::string without = searchWithoutProbesOrMoves();
  EXPECT_EQ(without.find("moved"), std::string::npos) << without;
}

// Two components that are each the other but for a term too small to see:
// ACSE proposes `b` for `a`'s expression and `a` for `b`'s. Each compiles
// alone, together they are a cycle; the step keeps the first and drops the
// second with the compiler's reason, and the search goes on.
TEST_F(SearchRun, AcseCandidatesThatMakeACycleTogetherAreDroppedOneByOne) {
  std::ofstream(dir_ / "ramp.spire") << R"(using "pipelines/engine.spire";
shader Ramp using EnginePipeline {
    @MaterialUniform sampler2D colorMap;
    @FrameUniform mat4 matMVP;
    vec4 projPos = matMVP * vec4(vert_pos, 1.0);
    float a = sqrt(vert_uv.x * vert_uv.x + 0.0001 * texture(colorMap, vert_uv).x);
    float b = sqrt(vert_uv.x * vert_uv.x + 0.0001 * texture(colorMap, vert_uv * 2.0).x);
    float ramp = a + b;
    vec4 output = vec4(vec3(ramp), 1.0);
}
)";
  writeRampScene();
  const std::vector<std::string> args =
      rampArgs("out", {"--max-levels", "1", "--no-average", "--component", "a", "--component", "b"});
  std::ostringstream out, err;
  ASSERT_EQ(runSearchTool(args, out, err), kExitSuccess) << err.str() << out.str();
  EXPECT_NE(out.str().find("in a is closest to b"), std::string::npos) << out.str();
  EXPECT_NE(out.str().find("in b is closest to a"), std::string::npos) << out.str();
  EXPECT_NE(out.str().find("with the step's other candidates: cycle among components"), std::string::npos) << out.str();
  EXPECT_EQ(csvRows(dir_ / "out/chain.csv").size(), 2U) << out.str();
}

// He et al.'s transition shaders: at each switch of the policy, a band
// that blends the two levels by a distance the shader computes. With the
// distance 0 every pixel is before the blend and the transition draws the
// nearer level; with 1e9 every pixel is past it and it draws the farther one.
TEST_F(SearchRun, TransitionShadersBlendTheTwoLevelsOfEachSwitchByDistance) {
  for (const char* distance : {"0.0", "1e9"}) {
    SCOPED_TRACE(distance);
    std::ostringstream out, err;
    ASSERT_EQ(runSearchTool(searchArgs({"--max-levels", "3", "--max-error", "0.5", "--transition-distance", distance}),
                            out, err),
              kExitSuccess)
        << err.str() << out.str();
    const std::string policy = readText(dir_ / "out/lod_policy.json");
    std::vector<std::pair<size_t, size_t>> transitions;
    for (const auto& entry : fs::directory_iterator(dir_ / "out")) {
      size_t from = 0, to = 0;
      if (std::sscanf(entry.path().filename().c_str(), "transition%zu_%zu.decisions", &from, &to) == 2) {
        transitions.emplace_back(from, to);
      }
    }
    ASSERT_FALSE(transitions.empty()) << out.str() << policy;
    for (const auto& [from, to] : transitions) {
      const std::string name = fmt::format("transition{}_{}", from, to);
      EXPECT_NE(policy.find(fmt::format("\"{}.decisions\"", name)), std::string::npos) << policy;
      const std::string placement = compileDecisions(dir_ / "out" / (name + ".decisions"));
      EXPECT_NE(placement.find(fmt::format("color = Fragment:{}\n", name)), std::string::npos) << placement;
      const size_t shown = std::string(distance) == "0.0" ? from : to;
      expectSameImage(dir_ / "out" / (name + ".png"), dir_ / "out" / fmt::format("level{}.png", shown));
      // Each transition is timed: the console and the report give its
      // frame time over level 0's beside its two levels'.
      const std::string console = out.str();
      const size_t line = console.find(fmt::format("  level {} to {}, from ", from, to));
      ASSERT_NE(line, std::string::npos) << console;
      double ratio = 0.0;
      ASSERT_EQ(std::sscanf(console.c_str() + console.find("time ratio ", line), "time ratio %lf", &ratio), 1);
      EXPECT_GT(ratio, 0.0);
      const std::string report = readText(dir_ / "out/report.md");
      const size_t row = report.find(fmt::format("\n| {} | {} | ", from, to));
      ASSERT_NE(row, std::string::npos) << report;
      double near = 0.0, far = 0.0, reported = 0.0;
      EXPECT_EQ(std::sscanf(report.c_str() + row, "\n| %*u | %*u | %lf | %lf | %lf |", &near, &far, &reported), 3)
          << report.substr(row, 200);
      EXPECT_NEAR(reported, ratio, 0.0005);
    }
    expectAPolicyOfTheChain(csvRows(dir_ / "out/chain.csv").size());
  }
}

// The default distance is the policy's, world units: on an instance scaled
// to a hundredth, whose points are 1.2 to 1.6 units from the eye in the
// world and a hundred times that in model space, every transition (its band
// starts beyond 3, the policy measured from 4) draws its nearer level.
TEST_F(SearchRun, TheDefaultTransitionDistanceIsInWorldUnits) {
  std::string scene = sceneJson();
  scene.replace(scene.find("\"size\": 2,"), std::string("\"size\": 2,").size(), "\"size\": 200,");
  scene.replace(scene.find("\"material\""), std::string("\"material\"").size(),
                "\"transform\": {\"scale\": 0.01}, \"material\"");
  std::ofstream(dir_ / "scene.json") << scene;
  std::ostringstream out, err;
  ASSERT_EQ(runSearchTool(searchArgs({"--max-levels", "3", "--max-error", "0.5", "--distances", "4,8,16"}), out, err),
            kExitSuccess)
      << err.str() << out.str();
  size_t written = 0;
  for (const auto& entry : fs::directory_iterator(dir_ / "out")) {
    size_t from = 0, to = 0;
    if (entry.path().extension() != ".png" ||
        std::sscanf(entry.path().filename().c_str(), "transition%zu_%zu", &from, &to) != 2)
      continue;
    ++written;
    expectSameImage(entry.path(), dir_ / "out" / fmt::format("level{}.png", from));
  }
  EXPECT_GT(written, 0U) << out.str();
}

TEST(SearchCommandLine, RefusesWhatItCannotRun) {
  const fs::path dir = fs::temp_directory_path() / fmt::format("spire_search_cli_{}", ::getpid());
  fs::remove_all(dir);
  fs::create_directories(dir / "busy");
  std::ofstream(dir / "busy/keep.txt") << "a user's file";
  const std::vector<std::vector<std::string>> usage{
      {"--search", "--shader", "Terrain", "-o", (dir / "out").string()},
      {"--search", "--scene", "examples/scenes/terrain.json", "--shader", "Terrain", "--k2", "0", "-o",
       (dir / "out").string()},
      {"--search", "--scene", "examples/scenes/terrain.json", "--shader", "Terrain", "--cost", "speed", "-o",
       (dir / "out").string()},
      {"--search", "--scene", "examples/scenes/terrain.json", "--shader", "Terrain", "--distances", "4,2", "-o",
       (dir / "out").string()},
      {"--search", "--scene", "examples/scenes/terrain.json", "--shader", "Terrain", "-o", (dir / "busy").string()}};
  for (const auto& args : usage) {
    std::ostringstream out, err;
    EXPECT_EQ(runSearchTool(args, out, err), kExitUsageError) << err.str();
  }
  EXPECT_TRUE(fs::exists(dir / "busy/keep.txt"));
  EXPECT_FALSE(fs::exists(dir / "out"));
  EXPECT_TRUE(wantsSearch({"x.spire", "--search"}));
  EXPECT_FALSE(wantsSearch({"x.spire", "--shader", "S"}));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace spire::search
