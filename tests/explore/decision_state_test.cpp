// The explorer's decisions: what propagation leaves possible, refusals that
// name the decision in the way, undo, and the decision file it saves. The
// property test walks every example shader's whole choice space at random:
// every alternative the explorer offers as possible must be accepted and
// build a variant with every decision applied, and every one it shows as
// impossible must be refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "driver/shader_library.h"
#include "explore/decision_state.h"

namespace spire::explore {
namespace {

namespace fs = std::filesystem;

std::unique_ptr<ShaderLibrary> loadLibrary(const std::string& path) {
  auto library = std::make_unique<ShaderLibrary>();
  EXPECT_TRUE(library->addFile(path)) << path;
  EXPECT_TRUE(library->compile()) << path;
  return library;
}

const ChoiceRow& rowOf(const std::vector<ChoiceRow>& rows, const std::string& key) {
  const auto it = std::find_if(rows.begin(), rows.end(), [&](const ChoiceRow& r) { return r.key == key; });
  EXPECT_NE(it, rows.end()) << key;
  return *it;
}

bool possible(const ChoiceRow& row, const std::string& placement) {
  for (const Alternative& alt : row.alternatives) {
    if (alt.placement == placement) return alt.possible;
  }
  ADD_FAILURE() << placement << " is not an alternative of " << row.key;
  return false;
}

TEST(DecisionState, PropagationMarksWhatOtherDecisionsRuleOut) {
  auto library = loadLibrary("examples/terrain.spire");
  DecisionState state(*library->choiceSpace("Terrain"));
  EXPECT_TRUE(possible(rowOf(state.rows(), "Terrain.albedo"), "PrebakeTex"));
  ASSERT_TRUE(state.set("Terrain.mixFactor", "Fragment"));
  const std::vector<ChoiceRow> rows = state.rows();
  // albedo reads mixFactor: a bake cannot read a per-fragment value.
  EXPECT_FALSE(possible(rowOf(rows, "Terrain.albedo"), "PrebakeTex"));
  EXPECT_TRUE(possible(rowOf(rows, "Terrain.albedo"), "Fragment"));
  // A decided choice still lists its own alternatives as the others allow.
  EXPECT_TRUE(possible(rowOf(rows, "Terrain.mixFactor"), "PrebakeTex"));
  EXPECT_EQ(rowOf(rows, "Terrain.mixFactor").decided, "Fragment");
}

TEST(DecisionState, RefusalsSayWhyAndNameTheDecisionInTheWay) {
  auto library = loadLibrary("examples/terrain.spire");
  DecisionState state(*library->choiceSpace("Terrain"));
  ASSERT_TRUE(state.set("mixFactor", "Fragment"));
  auto refused = state.set("Terrain.albedo", "PrebakeTex");
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error().message,
            "'Terrain.albedo = PrebakeTex' is impossible with the other decisions; change or unset mixFactor (now "
            "Fragment)");
  auto unknown = state.set("Terrain.albedoo", "Fragment");
  ASSERT_FALSE(unknown);
  EXPECT_EQ(unknown.error().message, "'Terrain.albedoo' is not a choice of this shader");
  auto wrong = state.set("albedo", "Geometry");
  ASSERT_FALSE(wrong);
  EXPECT_EQ(wrong.error().message,
            "'Geometry' is not an alternative of 'Terrain.albedo' (its alternatives: PrebakeTex, Vertex, Fragment)");
  EXPECT_EQ(state.decisions().size(), 1U) << "a refused change changes nothing";
}

TEST(DecisionState, UndoRestoresEachEarlierState) {
  auto library = loadLibrary("examples/terrain.spire");
  DecisionState state(*library->choiceSpace("Terrain"));
  EXPECT_FALSE(state.undo());
  ASSERT_TRUE(state.set("mixFactor", "PrebakeTex"));
  ASSERT_TRUE(state.set("albedo", "PrebakeTex"));
  ASSERT_TRUE(state.unset("mixFactor"));
  EXPECT_EQ(state.decisions().count("mixFactor"), 0U);
  ASSERT_TRUE(state.undo());
  EXPECT_EQ(state.decisions().at("mixFactor"), "PrebakeTex");
  ASSERT_TRUE(state.undo());
  EXPECT_EQ(state.decisions().count("albedo"), 0U);
  ASSERT_TRUE(state.replace({}));
  EXPECT_TRUE(state.decisions().empty());
  ASSERT_TRUE(state.undo());
  EXPECT_EQ(state.decisions().size(), 1U);
}

TEST(DecisionState, SavesADecisionFileTheCompilerReadsBack) {
  auto library = loadLibrary("examples/terrain.spire");
  DecisionState state(*library->choiceSpace("Terrain"));
  ASSERT_TRUE(state.set("mixFactor", "PrebakeTex"));
  ASSERT_TRUE(state.set("Terrain.lighting", "Fragment:basic"));
  EXPECT_EQ(state.decisionFileText("saved"),
            "// saved\nTerrain.mixFactor = PrebakeTex\nTerrain.lighting = Fragment:basic\n");
}

// Every example shader's whole choice space, walked at random.
TEST(DecisionState, EveryPossibleAlternativeBuildsAndEveryImpossibleOneIsRefused) {
  std::mt19937 random(20261203);
  size_t accepted = 0;
  size_t refused = 0;
  for (const auto& entry : fs::directory_iterator("examples")) {
    if (entry.path().extension() != ".spire") continue;
    auto library = loadLibrary(entry.path().string());
    for (const std::string& shader : library->shaderNames()) {
      DecisionState state(*library->choiceSpace(shader));
      if (state.rows().empty()) continue;
      for (int step = 0; step < 40; ++step) {
        const std::vector<ChoiceRow> rows = state.rows();
        const ChoiceRow& row = rows[random() % rows.size()];
        const Alternative& alt = row.alternatives[random() % row.alternatives.size()];
        const auto result = state.set(row.key, alt.placement);
        EXPECT_EQ(static_cast<bool>(result), alt.possible)
            << shader << ": " << row.key << " = " << alt.placement << (result ? "" : ": " + result.error().message);
        if (!result) {
          ++refused;
          continue;
        }
        ++accepted;
        std::vector<std::string> skipped;
        ASSERT_TRUE(library->buildVariant(shader, state.decisions(), &skipped)) << shader;
        EXPECT_TRUE(skipped.empty()) << shader << ": the compiler skipped " << skipped.front();
      }
    }
  }
  EXPECT_GT(accepted, 100U);
  EXPECT_GT(refused, 10U) << "the walk should meet impossible alternatives too";
}

}  // namespace
}  // namespace spire::explore
