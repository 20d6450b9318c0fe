// spire-explore on a level-of-detail scene, in a real window (under
// xvfb-run; skipped without a display), on the small test scene: a scripted
// policy edit moves instances to another level and changes the image, and
// the saved policy file reads back to the edited policy; an edit the policy
// reader rejects is reported while the last valid policy keeps drawing and
// the script goes on; a member edit makes the levels again, compiled on the
// worker while frames go on drawing the previous levels; undo brings back
// the previous policy and its image, and undo with nothing to undo is E7202.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <string>

#include "common/lod_test_scene.h"
#include "explore/explorer_window_fixture.h"
#include "lod/lod_policy.h"
#include "scene/texture.h"
#include "support/file_io.h"

namespace spire::explore {
namespace {

namespace fs = std::filesystem;

class LodExplorerWindowTest : public testing::ExplorerWindowFixture {
 protected:
  void SetUp() override {
    ExplorerWindowFixture::SetUp();
    if (IsSkipped() || HasFatalFailure()) return;
    // Near enough that the terrain's near edge (6.3 away) is in the first
    // band and the copies spread over all three.
    std::ofstream(dir_ / "lod.json") << spire::testing::lodTestSceneJson(
        {true, R"([{"position": [0, 6, 9], "target": [0, 0, 0]}])", "policy.json"});
    std::ofstream(dir_ / "policy.json") << spire::testing::lodTestPolicyJson(9.0F, 14.0F);
  }
  int exploreLod(const std::string& text) {
    return explore({(dir_ / "lod.json").string(), "--validation", "--bake-size", "64", "--script",
                    script(text).string(), "--log", (dir_ / "log.json").string()});
  }
};

// Bytes that differ between two PNGs of the same size, as a share.
double differing(const fs::path& a, const fs::path& b) {
  auto left = scene::loadImage(a);
  auto right = scene::loadImage(b);
  EXPECT_TRUE(left && right) << a << " " << b;
  if (!left || !right || left->bytes.size() != right->bytes.size()) return 1.0;
  size_t count = 0;
  for (size_t i = 0; i < left->bytes.size(); ++i) count += left->bytes[i] != right->bytes[i] ? 1 : 0;
  return static_cast<double>(count) / static_cast<double>(left->bytes.size());
}

TEST_F(LodExplorerWindowTest, AnEditedBandEdgeMovesInstancesToALowerLevelAndSavesThePolicy) {
  ASSERT_EQ(exploreLod("screenshot before.png\n"
                       "policy until 0 2\n"
                       "policy hysteresis 0.05\n"
                       "screenshot after.png\n"
                       "policy save saved.json\n"
                       "policy save\n"
                       "quit\n"),
            0)
      << err_.str() << out_.str();
  const nlohmann::json log = this->log();
  const auto start = log["start_levels"].get<std::vector<uint32_t>>();
  const nlohmann::json edits = log["policy_edits"];
  ASSERT_EQ(edits.size(), 2U) << out_.str();
  EXPECT_EQ(edits[0]["action"], "policy until 0 2");
  EXPECT_TRUE(edits[0]["ok"]) << edits[0]["error"];
  const auto after = edits[1]["levels"].get<std::vector<uint32_t>>();
  ASSERT_EQ(start.size(), 3U);
  ASSERT_EQ(after.size(), 3U);
  EXPECT_GT(start[0], 0U) << "some instances start at the nearest level";
  EXPECT_LT(after[0], start[0]) << "the nearest band is narrower";
  EXPECT_GT(after[1], start[1]) << "what left it draws at the next level";
  EXPECT_EQ(after[0] + after[1] + after[2], start[0] + start[1] + start[2]);
  EXPECT_GT(differing(dir_ / "before.png", dir_ / "after.png"), 0.001) << "the edit must show";

  // The saved file reads back to the edited policy, and is what formatLodPolicy writes of it.
  SourceManager sources;
  DiagnosticList diags;
  const auto saved = lod::loadLodPolicy(dir_ / "saved.json", sources, diags);
  ASSERT_TRUE(saved) << (diags.all().empty() ? "" : diags.all().front().message);
  ASSERT_EQ(saved->levels.size(), 3U);
  EXPECT_EQ(saved->levels[0].member, "LodHQ");
  EXPECT_EQ(saved->levels[0].until, 2.0F);
  EXPECT_EQ(saved->levels[1].until, 14.0F);
  EXPECT_EQ(saved->levels[2].member, "LodLQ");
  EXPECT_EQ(saved->hysteresis, 0.05F);
  EXPECT_EQ(saved->transitionFrames, 4U);
  EXPECT_EQ(readWholeFile((dir_ / "saved.json").string()), lod::formatLodPolicy(*saved));
  EXPECT_EQ(readWholeFile((dir_ / "policy.json").string()), lod::formatLodPolicy(*saved))
      << "without a file, Save writes the scene's policy file";
}

TEST_F(LodExplorerWindowTest, AnInvalidEditIsReportedAndTheLastValidPolicyKeepsDrawing) {
  ASSERT_EQ(exploreLod("screenshot before.png\n"
                       "policy until 1 5\n"  // before level 0's edge (9): out of order
                       "screenshot invalid.png\n"
                       "policy until 0 4\n"
                       "policy member 2 LodNone\n"
                       "policy member 2 LodMQ\n"
                       "screenshot after.png\n"
                       "quit\n"),
            0)
      << err_.str() << out_.str();
  const nlohmann::json edits = log()["policy_edits"];
  ASSERT_EQ(edits.size(), 4U) << out_.str();
  EXPECT_FALSE(edits[0]["ok"]);
  const std::string error = edits[0]["error"];
  EXPECT_NE(error.find("error[E7004]: level 1 ends at 5, not beyond level 0 (9): bands go from near to far"),
            std::string::npos)
      << error;
  EXPECT_NE(out_.str().find("policy until 1 5: not applied, the last valid policy keeps drawing"), std::string::npos)
      << out_.str();
  EXPECT_EQ(differing(dir_ / "before.png", dir_ / "invalid.png"), 0.0) << "the last valid policy draws";
  EXPECT_TRUE(edits[1]["ok"]) << edits[1]["error"] << "\nthe session goes on once the policy is valid again";
  EXPECT_FALSE(edits[2]["ok"]);
  EXPECT_NE(edits[2]["error"].get<std::string>().find("'LodNone' is not a member that every instance's group offers "
                                                      "(LodHQ, LodMQ, LodLQ)"),
            std::string::npos)
      << edits[2]["error"];
  EXPECT_TRUE(edits[3]["ok"]) << edits[3]["error"] << "\na member edit makes the levels again";
  const auto levels = log()["levels"];
  ASSERT_EQ(levels.size(), 3U);
  EXPECT_EQ(levels[2]["member"], "LodMQ");
  EXPECT_GT(differing(dir_ / "before.png", dir_ / "after.png"), 0.001);
}

TEST_F(LodExplorerWindowTest, AMemberEditCompilesWhileFramesGoOnAndUndoRestoresThePreviousImage) {
  ASSERT_EQ(exploreLod("screenshot before.png\n"
                       "policy until 0 4\n"
                       "screenshot edge.png\n"
                       "policy member 1 LodLQ\n"
                       "screenshot member.png\n"
                       "policy undo\n"
                       "screenshot member-undone.png\n"
                       "policy undo\n"
                       "screenshot undone.png\n"
                       "policy redo\n"
                       "screenshot redone.png\n"
                       "policy undo\n"
                       "policy undo\n"),  // nothing left to undo
            1)
      << err_.str() << out_.str();
  EXPECT_NE(err_.str().find("script.explore:13:1: error[E7202]: there is no policy edit to undo"), std::string::npos)
      << err_.str();
  const nlohmann::json edits = log()["policy_edits"];
  ASSERT_EQ(edits.size(), 6U) << out_.str();
  for (const nlohmann::json& edit : edits) EXPECT_TRUE(edit["ok"]) << edit["action"] << ": " << edit["error"];
  EXPECT_EQ(edits[1]["action"], "policy member 1 LodLQ");
  EXPECT_GT(edits[1]["compile_ms"].get<double>(), 0.0) << "the new member compiled on the worker";
  EXPECT_GT(edits[1]["prepare_ms"].get<double>(), 0.0) << "its bakes and pipelines were made on the worker too";
  EXPECT_GE(edits[1]["frames_while_compiling"].get<uint32_t>(), 1U)
      << "the window presented the previous levels while the new member compiled";
  EXPECT_EQ(edits[0]["compile_ms"].get<double>(), 0.0) << "a new edge compiles nothing";
  EXPECT_GT(differing(dir_ / "edge.png", dir_ / "member.png"), 0.001) << "the new member shows at once";
  EXPECT_EQ(differing(dir_ / "edge.png", dir_ / "member-undone.png"), 0.0) << "undo restores the previous image";
  EXPECT_EQ(differing(dir_ / "before.png", dir_ / "undone.png"), 0.0) << "and the one before that";
  EXPECT_EQ(differing(dir_ / "edge.png", dir_ / "redone.png"), 0.0);
  const auto levels = log()["levels"];
  ASSERT_EQ(levels.size(), 3U);
  EXPECT_EQ(levels[0]["member"], "LodHQ") << "the drawn policy is the original again";
}

TEST_F(LodExplorerWindowTest, ActionsOfOneShadersDecisionsAreErrorsAtTheirLine) {
  EXPECT_EQ(exploreLod("fly-frame 1\nset Barrel.albedo = Fragment\n"), 1) << out_.str();
  EXPECT_NE(err_.str().find("script.explore:2:1: error[E7202]: on a level-of-detail scene a script edits the policy"),
            std::string::npos)
      << err_.str();
}

// A member edit that makes the policy cross-fade into a level whose shader
// does not read lodFade is warned about (W7102) at the level it edits, in
// the console and the log; an edit that takes the switch or its fade away
// clears the warning, and one that brings it back says it again.
TEST_F(LodExplorerWindowTest, AnEditThatMakesASwitchThatCannotFadeIsWarnedAbout) {
  std::ofstream(dir_ / "fades_policy.json") << R"({"levels": [{"member": "Fades", "until": 5},
            {"member": "Fades"}], "transitionFrames": 4})";
  std::ofstream(dir_ / "fades.json") << spire::testing::lodFadesSceneJson("fades_policy.json", 64);
  ASSERT_EQ(explore({(dir_ / "fades.json").string(), "--validation", "--script",
                     script("policy member 1 Opaque\n"
                            "policy transition 0\n"
                            "policy transition 4\n"
                            "policy member 1 Fades\n"
                            "quit\n")
                         .string(),
                     "--log", (dir_ / "log.json").string()}),
            0)
      << err_.str() << out_.str();
  EXPECT_EQ(err_.str().find("W7102"), std::string::npos) << "the scene's own policy fades: " << err_.str();
  const nlohmann::json edits = log()["policy_edits"];
  ASSERT_EQ(edits.size(), 4U) << out_.str();
  for (const nlohmann::json& edit : edits) EXPECT_TRUE(edit["ok"]) << edit["action"] << ": " << edit["error"];
  const std::string warning =
      "fades_policy.json:2:13: warning[W7102]: 'Thing<Opaque>' at level 1 (Opaque) does not "
      "read lodFade";
  EXPECT_NE(edits[0]["warnings"].get<std::string>().find(warning), std::string::npos) << edits[0]["warnings"];
  EXPECT_EQ(edits[1]["warnings"], "") << "without transition frames nothing cross-fades";
  EXPECT_NE(edits[2]["warnings"].get<std::string>().find(warning), std::string::npos) << edits[2]["warnings"];
  EXPECT_EQ(edits[3]["warnings"], "");
  const std::string out = out_.str();
  const size_t first = out.find(warning);
  ASSERT_NE(first, std::string::npos) << out;
  EXPECT_NE(out.find(warning, first + 1), std::string::npos) << "said again when an edit brings it back:\n" << out;
}

// The scene's own policy cross-fades into a level that cannot: the
// explorer says so once when it opens, not again with each render.
TEST_F(LodExplorerWindowTest, TheScenesOwnSwitchThatCannotFadeIsWarnedAboutOnce) {
  std::ofstream(dir_ / "opaque_policy.json") << R"({"levels": [{"member": "Fades", "until": 5},
            {"member": "Opaque"}], "transitionFrames": 4})";
  std::ofstream(dir_ / "opaque.json") << spire::testing::lodFadesSceneJson("opaque_policy.json", 64);
  ASSERT_EQ(explore({(dir_ / "opaque.json").string(), "--validation", "--script", script("quit\n").string()}), 0)
      << err_.str() << out_.str();
  const std::string all = err_.str() + out_.str();
  const std::string warning = "warning[W7102]: 'Thing<Opaque>' at level 1 (Opaque) does not read lodFade";
  const size_t first = all.find(warning);
  ASSERT_NE(first, std::string::npos) << all;
  EXPECT_EQ(all.find(warning, first + 1), std::string::npos) << "said twice:\n" << all;
}

}  // namespace
}  // namespace spire::explore
