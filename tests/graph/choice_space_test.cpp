#include <gtest/gtest.h>

#include "graph/variant.h"
#include "graph_test_util.h"

namespace spire {
namespace {

using testing_util::altNames;
using testing_util::compileShader;
using testing_util::idOf;

const std::string kEngine = std::string(SPIRE_SOURCE_DIR) + "/pipelines/engine.spire";

std::string shader(const std::string& body) {
  return "shader S using EnginePipeline {\n  @FrameUniform mat4 mvp;\n  vec4 projPos = mvp * vec4(vert_pos, 1.0);\n" +
         body + "\n}\n";
}

TEST(ChoiceSpace, PaperExamplePrunesUnusablePlacements) {
  // Section 5.3: x would be implicitly defined everywhere, but y needs it in
  // Vertex, so Fragment is not offered (nor PrebakeTex, which only reaches
  // Fragment in this pipeline).
  auto c = compileShader({kEngine}, shader("float x = 1.0;\n@Vertex float y = x + 2.0;\nvec4 output = vec4(y);"), "S");
  ASSERT_TRUE(c.graph) << c.rendered();
  graph::ChoiceSpace space(*c.graph);
  ASSERT_TRUE(space.consistent());
  EXPECT_EQ(altNames(space, idOf(*c.graph, "x")), "Vertex");
  EXPECT_TRUE(space.isMandatory(idOf(*c.graph, "x")));
  // Without the pruning, all three concrete worlds are alternatives.
  EXPECT_EQ(c.graph->node(idOf(*c.graph, "x")).alternatives.size(), 3u);
}

TEST(ChoiceSpace, VertexExportRequiresProjPosInVertex) {
  auto c = compileShader({kEngine}, R"(
shader S using EnginePipeline {
  @FrameUniform mat4 mvp;
  mat4 m = mvp;
  vec4 projPos = m * vec4(vert_pos, 1.0);
  vec4 output = vec4(1.0);
})",
                         "S");
  ASSERT_TRUE(c.graph) << c.rendered();
  graph::ChoiceSpace space(*c.graph);
  EXPECT_EQ(altNames(space, idOf(*c.graph, "projPos")), "Vertex");
  EXPECT_EQ(altNames(space, idOf(*c.graph, "m")), "Vertex");
}

TEST(ChoiceSpace, TerrainMatchesListingTwo) {
  auto c = compileShader({std::string(SPIRE_SOURCE_DIR) + "/examples/terrain.spire"}, "", "Terrain");
  ASSERT_TRUE(c.graph) << c.rendered();
  graph::ChoiceSpace space(*c.graph);
  EXPECT_EQ(graph::writeChoiceFile(space),
            "Terrain.mixFactor = {PrebakeTex,Vertex,Fragment}\n"
            "Terrain.albedo = {PrebakeTex,Vertex,Fragment}\n"
            "Terrain.normal = {Vertex,Fragment}\n"
            "Terrain.lighting = {Vertex:basic,Fragment:basic,Vertex:ggx,Fragment:ggx}\n");
}

TEST(ChoiceSpace, DefaultPlacementIsLatestWorldFirstVariation) {
  auto c = compileShader({std::string(SPIRE_SOURCE_DIR) + "/examples/terrain.spire"}, "", "Terrain");
  ASSERT_TRUE(c.graph) << c.rendered();
  graph::ChoiceSpace space(*c.graph);
  const auto result = graph::buildVariant(space, {});
  ASSERT_TRUE(result.variant);
  EXPECT_EQ(result.variant->placementText(),
            "Terrain.projPos = Vertex\n"
            "Terrain.mixFactor = Fragment\n"
            "Terrain.normal = Fragment\n"
            "Terrain.lighting = Fragment:basic\n"
            "Terrain.albedo = Fragment\n"
            "Terrain.output = Fragment\n");
}

TEST(ChoiceSpace, DecisionsPropagateAndConflictsAreNamed) {
  auto c = compileShader({std::string(SPIRE_SOURCE_DIR) + "/examples/terrain.spire"}, "", "Terrain");
  ASSERT_TRUE(c.graph) << c.rendered();
  graph::ChoiceSpace space(*c.graph);
  const auto lighting = idOf(*c.graph, "lighting");
  const auto normal = idOf(*c.graph, "normal");
  const auto vertexBasic = *c.graph->findAlternative(c.graph->node(lighting), "Vertex", "basic");
  const auto fragmentNormal = *c.graph->findAlternative(c.graph->node(normal), "Fragment", "");
  const auto result = graph::buildVariant(space, {{lighting, vertexBasic, {}}, {normal, fragmentNormal, {}}});
  ASSERT_TRUE(result.variant);
  EXPECT_EQ(result.outcomes[0].status, graph::DecisionStatus::Applied);
  EXPECT_EQ(result.outcomes[1].status, graph::DecisionStatus::Conflict);
  EXPECT_EQ(result.outcomes[1].conflictsWith, 0u);
  // Lighting per vertex forces the per-vertex normal.
  EXPECT_EQ(c.graph->altName(c.graph->node(normal), *result.variant->choice(normal)), "Vertex");
}

TEST(ChoiceSpace, OnlyLiveComponentsArePlaced) {
  auto c = compileShader({kEngine}, shader("float unused = 2.0;\nvec4 output = vec4(1.0);"), "S");
  ASSERT_TRUE(c.graph) << c.rendered();
  graph::ChoiceSpace space(*c.graph);
  EXPECT_EQ(graph::writeChoiceFile(space), "");
  const auto result = graph::buildVariant(space, {});
  ASSERT_TRUE(result.variant);
  EXPECT_FALSE(result.variant->choice(idOf(*c.graph, "unused")).has_value());
}

TEST(ChoiceSpace, ValuesAreRoutedThroughIntermediateWorlds) {
  auto c = compileShader({kEngine}, shader("vec4 output = vec4(vert_normal, 1.0);"), "S");
  ASSERT_TRUE(c.graph) << c.rendered();
  graph::ChoiceSpace space(*c.graph);
  const auto result = graph::buildVariant(space, {});
  ASSERT_TRUE(result.variant);
  const sem::Pipeline& p = c.graph->pipeline();
  // MeshVertex -> Vertex -> Fragment: Vertex passes the normal through.
  const auto& vertex = result.variant->world(*p.findWorld("Vertex"));
  const auto normal = idOf(*c.graph, "vert_normal");
  auto carries = [&](const std::vector<graph::Transfer>& list) {
    for (const auto& t : list) {
      if (t.component == normal) return true;
    }
    return false;
  };
  EXPECT_TRUE(carries(vertex.inputs));
  EXPECT_TRUE(carries(vertex.outputs));
  EXPECT_TRUE(carries(result.variant->world(*p.findWorld("Fragment")).inputs));
}

TEST(ShaderGraph, ReportsUndefinableComponentsWithTheBlockingDependency) {
  // PrebakeTex cannot see FrameUniform, and Fragment-only data cannot flow back.
  auto c = compileShader({kEngine}, shader(R"(
  @FrameUniform vec3 light;
  @PrebakeTex float baked = vert_uv.x;
  @Fragment float late = light.x;
  float both = baked + late;
  @PrebakeTex float early = light.y;
  vec4 output = vec4(both, early, 0.0, 1.0);)"),
                         "S");
  EXPECT_EQ(c.codes(), (std::vector<std::string>{"E4015"})) << c.rendered();
  EXPECT_NE(c.rendered().find("'light' is not available in world 'PrebakeTex'"), std::string::npos) << c.rendered();
}

TEST(ShaderGraph, ReportsComponentDefinedNowhere) {
  // Two branches that never meet: nothing can combine Left and Right values.
  auto c = compileShader({}, R"(
pipeline Split {
  abstract world In;
  world Left : "GLSL" export standardExport;
  world Right : "GLSL" export standardExport;
  import In->Left using uniformImport;
  import In->Right using uniformImport;
  @In float seed;
  abstract export @Right float result;
}
shader S using Split {
  @Left float a = seed * 2.0;
  @Right float b = seed * 3.0;
  float both = a + b;
  float result = b + both;
})",
                         "S");
  ASSERT_EQ(c.codes(), (std::vector<std::string>{"E4014"})) << c.rendered();
  EXPECT_NE(c.rendered().find("'both' can be defined nowhere"), std::string::npos) << c.rendered();
  EXPECT_NE(c.rendered().find("'a' (Left) and 'b' (Right)"), std::string::npos) << c.rendered();
}

TEST(ShaderGraph, ReportsRequiredComponentLeftUndefined) {
  auto c = compileShader({kEngine}, "shader S using EnginePipeline { vec4 output = vec4(1.0); }", "S");
  ASSERT_EQ(c.codes(), (std::vector<std::string>{"E4013"})) << c.rendered();
  EXPECT_NE(c.rendered().find("does not define 'projPos'"), std::string::npos);
}

TEST(ShaderGraph, InheritedChoicesCarryTheBasePrefixAndSkipLockedWorlds) {
  auto c =
      compileShader({std::string(SPIRE_SOURCE_DIR) + "/examples/lod_library.spire"}, "", "TerrainLOD<BaseMaterialLQ>");
  ASSERT_TRUE(c.graph) << c.rendered();
  graph::ChoiceSpace space(*c.graph);
  EXPECT_EQ(graph::writeChoiceFile(space), "BaseMaterialLQ.nDotL = {Vertex,Fragment}\n");
  // TerrainLOD's own implicit components may not use the locked worlds.
  EXPECT_EQ(altNames(space, idOf(*c.graph, "mixFactor")), "PrebakeTex");
}

}  // namespace
}  // namespace spire
