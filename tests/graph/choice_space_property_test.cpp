// Property tests over whole choice spaces: every decision map drawn from a
// shader's choice file yields a valid variant, and a variant's placement
// applied as a decision file reproduces it.
#include <gtest/gtest.h>

#include <filesystem>

#include "graph/decision_file.h"
#include "graph/variant.h"
#include "graph_test_util.h"

namespace spire {
namespace {

namespace fs = std::filesystem;

// Checks the variant's invariants: every live definition's dependencies are
// live and placed in a world that reaches it, every pipeline requirement is
// met, and each crossing is carried by the world plans.
void expectValid(const graph::Variant& v, const std::string& context) {
  const graph::ShaderGraph& g = v.graph();
  for (sem::ComponentId c : v.live()) {
    const graph::Alternative& alt = g.node(c).alternatives[*v.choice(c)];
    for (sem::ComponentId dep : alt.definition->dependencies) {
      ASSERT_TRUE(v.choice(dep).has_value()) << context << ": dead dependency " << g.node(dep).component->name;
      ASSERT_TRUE(g.reaches(v.worldOf(dep), alt.world))
          << context << ": " << g.node(dep).component->name << " is not available where " << g.node(c).component->name
          << " is computed";
      if (v.worldOf(dep) != alt.world) {
        bool carried = false;
        for (const graph::Transfer& t : v.world(alt.world).inputs) carried = carried || t.component == dep;
        ASSERT_TRUE(carried) << context << ": " << g.node(dep).component->name << " is not imported";
      }
    }
  }
  for (const graph::Sink& sink : g.sinks()) {
    ASSERT_TRUE(v.choice(sink.component).has_value()) << context;
    ASSERT_TRUE(g.reaches(v.worldOf(sink.component), sink.world)) << context;
  }
}

void expectRoundTrip(const graph::Variant& v, const graph::ChoiceSpace& space, const std::string& context) {
  SourceManager sources;
  DiagnosticList diags;
  const FileId file = sources.addFile("placement.decisions", v.placementText());
  const graph::DecisionFile decisions = graph::parseDecisionFile(sources, file, diags);
  const auto again = graph::applyDecisions(decisions, space, diags);
  ASSERT_TRUE(again.has_value()) << context;
  EXPECT_EQ(diags.all().size(), 0u) << context << "\n" << renderDiagnostics(sources, diags, DiagnosticFormat::Text);
  EXPECT_EQ(again->placementText(), v.placementText()) << context;
  for (sem::ComponentId c = 0; c < space.graph().nodes().size(); ++c) {
    EXPECT_EQ(again->choice(c), v.choice(c)) << context;
  }
}

// Checks the decision maps of `space` whose running number (`next`, counted
// over every space walked) is `shard` modulo `shards`.
void walkChoiceSpace(const graph::ChoiceSpace& space, size_t& next, int shard, int shards) {
  testing_util::forEachDecisionMap(space, [&](const std::vector<graph::DecisionRequest>& requests, size_t index) {
    if (static_cast<int>(next++ % static_cast<size_t>(shards)) != shard) return;
    const std::string context = space.graph().shader().name + " decision map #" + std::to_string(index);
    const auto result = graph::buildVariant(space, requests);
    ASSERT_TRUE(result.variant) << context;
    expectValid(*result.variant, context);
    for (size_t r = 0; r < requests.size(); ++r) {
      if (result.outcomes[r].status == graph::DecisionStatus::Applied) {
        const sem::ComponentId c = requests[r].component;
        if (result.variant->choice(c)) {
          EXPECT_EQ(*result.variant->choice(c), requests[r].alternative) << context;
        }
      }
    }
    expectRoundTrip(*result.variant, space, context);
  });
}

// In shards that CTest runs side by side (under the sanitizers the whole
// takes minutes on one core).
constexpr int kShards = 4;

class EveryExampleDecisionMap : public ::testing::TestWithParam<int> {};

TEST_P(EveryExampleDecisionMap, YieldsAValidVariant) {
  size_t shaders = 0, maps = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(SPIRE_SOURCE_DIR) / "examples")) {
    if (entry.path().extension() != ".spire") continue;
    FrontEnd frontEnd;
    frontEnd.addFile(entry.path().string());
    const sem::Model& model = frontEnd.analyze();
    ASSERT_FALSE(frontEnd.diagnostics().hasErrors()) << entry.path();
    for (const sem::Shader* shader : graph::concreteShaders(model)) {
      auto g = graph::ShaderGraph::build(*shader, frontEnd.diagnostics());
      ASSERT_TRUE(g) << shader->name;
      graph::ChoiceSpace space(*g);
      ASSERT_TRUE(space.consistent()) << shader->name;
      walkChoiceSpace(space, maps, GetParam(), kShards);
      ++shaders;
    }
  }
  EXPECT_GE(shaders, 3u);
  EXPECT_GE(maps, static_cast<size_t>(kShards));
}

INSTANTIATE_TEST_SUITE_P(Shard, EveryExampleDecisionMap, ::testing::Range(0, kShards));

}  // namespace
}  // namespace spire
