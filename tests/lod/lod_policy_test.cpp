#include "lod/lod_policy.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "support/diagnostic_renderer.h"

namespace spire::lod {
namespace {

struct Parsed {
  std::optional<LodPolicy> policy;
  std::string diagnostics;
};

Parsed parse(std::string text) {
  SourceManager sources;
  DiagnosticList diags;
  Parsed parsed;
  parsed.policy = parseLodPolicy("policy.json", std::move(text), sources, diags);
  parsed.diagnostics = renderDiagnostics(sources, diags, DiagnosticFormat::Text);
  return parsed;
}

TEST(LodPolicyTest, ReadsLevelsNearestFirst) {
  const Parsed p = parse(R"({"levels": [{"member": "LodHQ", "until": 12}, {"member": "LodMQ", "until": 40},
                                        {"member": "LodLQ"}], "hysteresis": 0.2, "transitionFrames": 4})");
  ASSERT_TRUE(p.policy) << p.diagnostics;
  ASSERT_EQ(p.policy->levels.size(), 3U);
  EXPECT_EQ(p.policy->levels[1].member, "LodMQ");
  EXPECT_FLOAT_EQ(p.policy->levels[1].until, 40.0F);
  EXPECT_TRUE(std::isinf(p.policy->levels[2].until));
  EXPECT_FLOAT_EQ(p.policy->hysteresis, 0.2F);
  EXPECT_EQ(p.policy->transitionFrames, 4U);
}

TEST(LodPolicyTest, FormattedPolicyReadsBackTheSame) {
  const Parsed p = parse(
      R"({"levels": [{"member": "A", "until": 7.5}, {"member": "T", "blend": true, "until": 8}, {"member": "B"}]})");
  ASSERT_TRUE(p.policy) << p.diagnostics;
  const Parsed again = parse(formatLodPolicy(*p.policy));
  ASSERT_TRUE(again.policy) << again.diagnostics;
  EXPECT_EQ(formatLodPolicy(*again.policy), formatLodPolicy(*p.policy));
  EXPECT_FLOAT_EQ(again.policy->levels[0].until, 7.5F);
  EXPECT_FALSE(again.policy->levels[0].blend);
  EXPECT_TRUE(again.policy->levels[1].blend);
  EXPECT_FALSE(again.policy->levels[1].drawsAs(again.policy->levels[0]));
}

// A member name is any bytes a user gave (an explorer script's word): bytes
// that are not UTF-8, which JSON cannot hold, are written as U+FFFD, and the
// file reads back to itself. (Writing them used to throw, and the explorer
// died of it.)
TEST(LodPolicyTest, NamesThatAreNotUtf8AreWrittenAsReplacementCharacters) {
  LodPolicy policy;
  policy.levels = {{"Lo\xff\xfe", 5.0F, {}, {}}, {"LodLQ", std::numeric_limits<float>::infinity(), {}, {}}};
  std::string text;
  ASSERT_NO_THROW(text = formatLodPolicy(policy));
  EXPECT_NE(text.find("\"Lo\xef\xbf\xbd\xef\xbf\xbd\""), std::string::npos) << text;
  const Parsed again = parse(text);
  ASSERT_TRUE(again.policy) << again.diagnostics;
  EXPECT_EQ(formatLodPolicy(*again.policy), text);
}

TEST(LodPolicyTest, BadPoliciesAreReportedAtTheirValues) {
  struct Case {
    const char* text;
    const char* message;
  };
  const Case cases[] = {
      {R"({"levels": [{"member": "A", "until": 20}, {"member": "B", "until": 10}, {"member": "C"}]})",
       "policy.json:1:43: error[E7004]: level 1 ends at 10, not beyond level 0 (20)"},
      {R"({"levels": [{"member": "A"}, {"member": "B"}]})", "a level before the last has no 'until'"},
      {R"({"levels": [{"member": "A", "until": 3}]})", "the last level has no 'until'"},
      {R"({"levels": [{"until": 3}, {"member": "B"}]})", "a level has neither a 'member'"},
      {R"({"levels": [{"decisions": {}}]})", "'decisions' names no shader"},
      {R"({"levels": [{"decisions": ["a.decisions"]}]})", "'decisions'"},
      {R"({"levels": [{"decisions": {"Rock": 3}}]})", "the decisions of 'Rock'"},
      {R"({"levels": [{"decisions": {"Rock": "no/such.decisions"}}]})",
       "policy.json:1:36: error[E1101]: cannot open decision file 'no/such.decisions'"},
      {R"({"levels": [{"member": "A"}], "hysterisis": 0.1})", "did you mean 'hysteresis'?"},
      {R"({"levels": [{"member": "A"}], "hysteresis": 1.5})", "'hysteresis'"},
      {R"({"levels": []})", "'levels'"},
      {R"({"hysteresis": 0.1})", "the policy has no 'levels'"},
      {R"({"levels": [{"member": "A"}],})", "E7001"},
      {R"({"levels": [{"member": "A", "blend": true, "until": 3}, {"member": "B"}]})",
       "policy.json:1:13: error[E7004]: a 'blend' band blends the bands on either side of it"},
      {R"({"levels": [{"member": "A", "until": 3}, {"member": "B", "blend": true}]})",
       "cannot be the first or the last"},
      {R"({"levels": [{"member": "A", "blend": 1, "until": 3}, {"member": "B"}]})", "'blend'"},
  };
  for (const Case& c : cases) {
    const Parsed p = parse(c.text);
    EXPECT_FALSE(p.policy) << c.text;
    EXPECT_NE(p.diagnostics.find(c.message), std::string::npos) << c.text << "\n" << p.diagnostics;
  }
}

// A folder of decision files beside a policy file, removed at the end.
class PolicyFolder : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("spire-policy-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_ / "chain");
    for (const char* name : {"level0.decisions", "level2.decisions"}) std::ofstream(dir_ / "chain" / name) << "\n";
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  Parsed parseIn(std::string text) const {
    SourceManager sources;
    DiagnosticList diags;
    Parsed parsed;
    parsed.policy = parseLodPolicy((dir_ / "policy.json").string(), std::move(text), sources, diags);
    parsed.diagnostics = renderDiagnostics(sources, diags, DiagnosticFormat::Text);
    return parsed;
  }

  std::filesystem::path dir_;
};

TEST_F(PolicyFolder, DecisionFilesAreFoundBesideThePolicy) {
  const Parsed p = parseIn(R"({"levels": [{"decisions": {"TerrainSearch": "chain/level0.decisions"}, "until": 5},
                                          {"member": "LodLQ", "decisions": {"TerrainSearch": "chain/level2.decisions"}}]})");
  ASSERT_TRUE(p.policy) << p.diagnostics;
  const LodLevel& near = p.policy->levels[0];
  EXPECT_TRUE(near.member.empty());
  ASSERT_EQ(near.decisions.count("TerrainSearch"), 1U);
  EXPECT_EQ(near.decisions.at("TerrainSearch"), dir_ / "chain/level0.decisions");
  EXPECT_EQ(levelName(near), "level0");
  EXPECT_EQ(levelName(p.policy->levels[1]), "LodLQ level2");
  EXPECT_FALSE(near.drawsAs(p.policy->levels[1]));
  EXPECT_TRUE(near.drawsAs(near));

  // Written from another folder, the paths are relative to that folder, and
  // the policy reads back the same from there.
  const std::string moved = formatLodPolicy(*p.policy, dir_ / "chain");
  EXPECT_NE(moved.find(R"("TerrainSearch": "level0.decisions")"), std::string::npos) << moved;
  SourceManager sources;
  DiagnosticList diags;
  const auto back = parseLodPolicy((dir_ / "chain" / "moved.json").string(), moved, sources, diags);
  ASSERT_TRUE(back) << renderDiagnostics(sources, diags, DiagnosticFormat::Text);
  EXPECT_TRUE(back->levels[1].drawsAs(p.policy->levels[1]));
}

TEST_F(PolicyFolder, ALevelDrawsItsShadersWithItsDecisionsAndTheOthersAsTheyAre) {
  const Parsed p = parseIn(R"({"levels": [{"member": "LodMQ", "decisions": {"Rock": "chain/level2.decisions"}}]})");
  ASSERT_TRUE(p.policy) << p.diagnostics;
  scene::InstanceDesc rock;
  rock.shader = "Rock";
  rock.decisions = "own.decisions";
  scene::InstanceDesc barrel = rock;
  barrel.shader = "Barrel";
  const LodLevel& level = p.policy->levels[0];
  const scene::InstanceDesc rockDrawn = levelInstance(rock, level);
  EXPECT_EQ(rockDrawn.shader, "Rock<LodMQ>");
  EXPECT_EQ(rockDrawn.decisions, dir_ / "chain/level2.decisions");
  const scene::InstanceDesc barrelDrawn = levelInstance(barrel, level);
  EXPECT_EQ(barrelDrawn.shader, "Barrel<LodMQ>");
  EXPECT_EQ(barrelDrawn.decisions, std::filesystem::path("own.decisions"));
  // A file many shaders draw with is named once; one whose name holds
  // another's is still named.
  LodLevel shared;
  shared.decisions = {{"A", "x/level12.decisions"}, {"B", "x/level1.decisions"}, {"C", "y/level1.decisions"}};
  EXPECT_EQ(levelName(shared), "level12 level1");
  LodLevel plain;
  plain.decisions = level.decisions;
  EXPECT_EQ(levelInstance(barrel, plain).shader, "Barrel") << "no member: the instance's own shader";
}

}  // namespace
}  // namespace spire::lod
