#include "graph/decision_file.h"

#include <gtest/gtest.h>

#include "graph_test_util.h"

namespace spire {
namespace {

graph::DecisionFile parse(SourceManager& sources, DiagnosticList& diags, const std::string& text) {
  return graph::parseDecisionFile(sources, sources.addFile("d.decisions", text), diags);
}

TEST(DecisionFile, ParsesCommentsAttributesVariationsAndCrlf) {
  SourceManager sources;
  DiagnosticList diags;
  const auto file = parse(sources, diags,
                          "// header\r\n"
                          "Terrain.lighting = Fragment:ggx   // trailing\r\n"
                          "\r\n"
                          "[Format: \"RGB10_A2\"][TextureSize: \"512\"] Terrain.albedo = PrebakeTex;\r\n"
                          "TerrainLOD<BaseMaterialLQ>.mixFactor = PrebakeTex\n");
  ASSERT_EQ(diags.all().size(), 0u) << renderDiagnostics(sources, diags, DiagnosticFormat::Text);
  ASSERT_EQ(file.lines.size(), 3u);
  EXPECT_EQ(file.lines[0].prefix, "Terrain");
  EXPECT_EQ(file.lines[0].component, "lighting");
  EXPECT_EQ(file.lines[0].world, "Fragment");
  EXPECT_EQ(file.lines[0].variation, "ggx");
  EXPECT_EQ(file.lines[1].attributes,
            (std::vector<std::pair<std::string, std::string>>{{"Format", "RGB10_A2"}, {"TextureSize", "512"}}));
  EXPECT_EQ(file.lines[2].prefix, "TerrainLOD<BaseMaterialLQ>");
  EXPECT_EQ(sources.text(file.lines[0].worldRange), "Fragment");
}

TEST(DecisionFile, MalformedLinesAreErrorsWithLocations) {
  SourceManager sources;
  DiagnosticList diags;
  const auto file = parse(sources, diags, "Terrain.albedo PrebakeTex\nalbedo = Vertex\nTerrain.x = Vertex extra\n[Format RGBA8] T.c = V\n");
  EXPECT_TRUE(file.lines.empty());
  ASSERT_EQ(diags.all().size(), 4u);
  for (const Diagnostic& d : diags.all()) EXPECT_EQ(d.code, DiagCode::E5001);
  EXPECT_EQ(sources.begin(diags.all()[0].range).column, 16u);
  EXPECT_EQ(sources.begin(diags.all()[2].range).column, 20u);
}

TEST(DecisionFile, AttributesReachTheVariant) {
  auto c = testing_util::compileShader({std::string(SPIRE_SOURCE_DIR) + "/examples/terrain.spire"}, "", "Terrain");
  ASSERT_TRUE(c.graph) << c.rendered();
  graph::ChoiceSpace space(*c.graph);
  SourceManager sources;
  DiagnosticList diags;
  const auto file = parse(sources, diags, "[TextureSize: \"512\"] Terrain.albedo = PrebakeTex\n");
  const auto variant = graph::applyDecisions(file, space, diags);
  ASSERT_TRUE(variant);
  EXPECT_EQ(diags.all().size(), 0u);
  const auto albedo = testing_util::idOf(*c.graph, "albedo");
  EXPECT_EQ(variant->attributes(albedo), (std::vector<std::pair<std::string, std::string>>{{"TextureSize", "512"}}));
}

// E5002 only when no decision takes effect: a conflict that leaves one
// decision applied passes, a file of skipped decisions or of none fails or
// passes as it should.
TEST(DecisionFile, AFileThatDecidesNothingIsAnError) {
  auto c = testing_util::compileShader({std::string(SPIRE_SOURCE_DIR) + "/examples/terrain.spire"}, "", "Terrain");
  ASSERT_TRUE(c.graph) << c.rendered();
  graph::ChoiceSpace space(*c.graph);
  const auto codesFor = [&](const std::string& text) {
    SourceManager sources;
    DiagnosticList diags;
    graph::checkSomeDecisionApplies(parse(sources, diags, text), {&space}, diags);
    std::vector<std::string> codes;
    for (const Diagnostic& d : diags.all()) codes.emplace_back(diagCodeInfo(d.code).name);
    return codes;
  };
  using Codes = std::vector<std::string>;
  EXPECT_EQ(codesFor("Terrain.lighting = Vertex:basic\nTerrain.normal = Fragment\n"), Codes{});
  EXPECT_EQ(codesFor("// nothing decided\n"), Codes{});
  EXPECT_EQ(codesFor("Terrain.normal = PrebakeTex\nTerrain.albedoo = Vertex\n"), Codes{"E5002"});
  EXPECT_EQ(codesFor("Couch.albedo = Vertex\n"), Codes{"E5002"});
}

}  // namespace
}  // namespace spire
