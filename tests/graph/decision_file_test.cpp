#include "graph/decision_file.h"

#include <gtest/gtest.h>

#include "common/locked_pipeline.h"
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
  const auto file = parse(
      sources, diags, "Terrain.albedo PrebakeTex\nalbedo = Vertex\nTerrain.x = Vertex extra\n[Format RGBA8] T.c = V\n");
  EXPECT_TRUE(file.lines.empty());
  ASSERT_EQ(diags.all().size(), 4u);
  for (const Diagnostic& d : diags.all()) EXPECT_EQ(d.code, DiagCode::E5001);
  EXPECT_EQ(sources.begin(diags.all()[0].range).column, 16u);
  EXPECT_EQ(sources.begin(diags.all()[2].range).column, 20u);
}

// What the writer writes, the parser reads back, whatever bytes attribute
// values hold: quotes, backslashes, line breaks, '//' and non-ASCII text.
TEST(DecisionFile, WritingThenParsingRoundTrips) {
  graph::DecisionFile written;
  written.lines.push_back(graph::makeDecision("Terrain", "albedo", "PrebakeTex",
                                              {{"Format", "RGBA8"},
                                               {"Quote", "say \"hi\""},
                                               {"Backslash", "C:\\dir\\"},
                                               {"Lines", "one\ntwo\r\nthree"},
                                               {"Comment", "a // b ] c"},
                                               {"Unicode", "\xC3\xA9t\xC3\xA9 \xE6\xBC\xA2 \xF0\x9F\x8C\x84"},
                                               {"Empty", ""}}));
  written.lines.push_back(graph::makeDecision("TerrainLOD<BaseMaterialLQ>", "lighting", "Fragment:ggx"));
  const std::string text = graph::writeDecisionFile(written, "header\nsecond line");
  EXPECT_EQ(text.substr(0, text.find("[")), "// header\n// second line\n");
  EXPECT_NE(text.find("[Quote: \"say \\\"hi\\\"\"]"), std::string::npos) << text;

  SourceManager sources;
  DiagnosticList diags;
  const auto read = parse(sources, diags, text);
  ASSERT_EQ(diags.all().size(), 0u) << renderDiagnostics(sources, diags, DiagnosticFormat::Text) << text;
  ASSERT_EQ(read.lines.size(), written.lines.size()) << text;
  for (size_t i = 0; i < read.lines.size(); ++i) {
    EXPECT_EQ(read.lines[i].prefix, written.lines[i].prefix);
    EXPECT_EQ(read.lines[i].component, written.lines[i].component);
    EXPECT_EQ(read.lines[i].world, written.lines[i].world);
    EXPECT_EQ(read.lines[i].variation, written.lines[i].variation);
    EXPECT_EQ(read.lines[i].attributes, written.lines[i].attributes);
  }
  EXPECT_EQ(read.lines[1].variation, "ggx");
}

// Escapes the parser reads; a backslash before any other character is that
// character.
TEST(DecisionFile, ReadsEscapesInAttributeValues) {
  SourceManager sources;
  DiagnosticList diags;
  const auto file = parse(sources, diags, "[A: \"x\\ny\\rz\\q\\\\\\\"\"] T.c = V\n");
  ASSERT_EQ(diags.all().size(), 0u) << renderDiagnostics(sources, diags, DiagnosticFormat::Text);
  ASSERT_EQ(file.lines.size(), 1u);
  EXPECT_EQ(file.lines[0].attributes.front().second, "x\ny\rzq\\\"");
}

// Found by spire_decisions_fuzzer: the value went into reflection.json, whose
// writer threw on invalid UTF-8, and spirec died of the uncaught exception.
TEST(DecisionFile, AttributeValuesMustBeUtf8) {
  SourceManager sources;
  DiagnosticList diags;
  const auto file =
      parse(sources, diags, "[Format: \"\xff\"] Terrain.albedo = PrebakeTex\n[Label: \"\xc3\xa9\"] T.c = V\n");
  ASSERT_EQ(file.lines.size(), 1u);
  EXPECT_EQ(file.lines[0].attributes[0].second, "\xc3\xa9");
  ASSERT_EQ(diags.all().size(), 1u);
  EXPECT_EQ(diags.all()[0].code, DiagCode::E5001);
  EXPECT_EQ(sources.begin(diags.all()[0].range).column, 10u);
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

// LQ finalizes V0; c0, which V0 cannot compute, is Impl's. Computing it in
// C0 sends it to F0 through V0: as LQ's decision that holds for every
// shader derived from LQ, as Mat's alone it would change Mat's V0 kernel.
const std::string kLockedBase = testing_util::lockedTestPipeline("    import U0->F0 using uniformImport;\n") + R"(
shader Impl using P {
    @U0 sampler2D tex;
    int c0 = int(texture(tex, vec2(0.5)).x * 4.0);
    vec4 clip0 = vec4(m0_pos, 1.0);
    float k:a = 0.5;
    float k:b = 0.25;
    vec4 output = vec4(float(c0) * k);
}
shader LQ : Impl finalizes V0 {
}
shader Mat : LQ {
}
)";

TEST(DecisionFile, ADecisionBelowAFinalizerThatWouldChangeItsKernelsIsSkippedNamingTheFinalizer) {
  auto c = testing_util::compileShader({}, kLockedBase, "Mat");
  ASSERT_TRUE(c.graph) << c.rendered();
  graph::ChoiceSpace space(*c.graph);
  const auto c0 = testing_util::idOf(*c.graph, "c0"), k = testing_util::idOf(*c.graph, "k");
  // Where c0 and k go.
  const auto placeC0 = [&](const std::string& text, std::vector<Diagnostic>& out) {
    SourceManager sources;
    DiagnosticList diags;
    const auto variant = graph::applyDecisions(parse(sources, diags, text), space, diags);
    out = diags.all();
    if (!variant) return std::string("no variant");
    return c.graph->altName(c.graph->node(c0), *variant->choice(c0)) + " " +
           c.graph->altName(c.graph->node(k), *variant->choice(k));
  };
  std::vector<Diagnostic> diags;
  EXPECT_EQ(placeC0("LQ.c0 = C0\n", diags), "C0 V0:a");
  EXPECT_TRUE(diags.empty());
  EXPECT_EQ(placeC0("Mat.c0 = C0\n", diags), "F0 V0:a");
  ASSERT_EQ(diags.size(), 1u);
  EXPECT_EQ(diags[0].code, DiagCode::W5002);
  EXPECT_EQ(diags[0].message,
            "decision 'Mat.c0 = C0' is skipped: it would change, for 'Mat' alone, kernels that every shader derived "
            "from 'LQ' shares; decide 'LQ.c0' to place it for all of them");
  // The decision after it still applies: the builder drops the latest
  // decisions until the shader places, then takes back those that fit.
  EXPECT_EQ(placeC0("Mat.c0 = C0\nLQ.k = V0:b\n", diags), "F0 V0:b");
  ASSERT_EQ(diags.size(), 1u);
  EXPECT_EQ(diags[0].code, DiagCode::W5002);
  EXPECT_NE(diags[0].message.find("decision 'Mat.c0 = C0' is skipped"), std::string::npos);
}

}  // namespace
}  // namespace spire
