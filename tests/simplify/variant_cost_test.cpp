// He et al. 2015's cost of a variant (variant_cost.h) on a pipeline of its
// own, whose world names say nothing: the rates come from the worlds'
// stages, the pipeline's requirements and its imports. C_v, C_f and N_var
// are worked out by hand in the comments.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "simplify/cost_model.h"
#include "simplify/simplify_tool.h"
#include "simplify/variant_cost.h"
#include "simplify_fixture.h"

namespace spire::simplify {
namespace {

// Bake is a fragment-stage world too (standardExport), but holds none of
// the pipeline's requirements: it is baked into textures that PS samples.
constexpr const char* kPipeline = R"(pipeline P {
    abstract world Uni;
    abstract world Mesh;
    world Bake : "GLSL" export standardExport;
    world VS : "GLSL" export vertexExport(clip);
    world PS : "GLSL" export standardExport;
    import Uni->Bake using uniformImport;
    import Uni->VS using uniformImport;
    import Uni->PS using uniformImport;
    import Mesh->Bake using standardImport;
    import Mesh->VS using standardImport;
    import VS->PS using standardImport;
    import Bake->PS using textureImport(uv);
    @Mesh vec3 pos;
    @Mesh vec2 uv;
    abstract @VS vec4 clip;
    abstract export @PS vec4 color;
}
)";

const std::string kShader = std::string(kPipeline) + R"(shader S using P {
    @Uni mat4 mvp;
    @Uni sampler2D map;
    @Uni vec3 tint;
    vec4 clip = mvp * vec4(pos, 1.0);
    float shade = max(dot(normalize(pos), tint), 0.0);
    vec4 albedo = texture(map, uv) * 2.0;
    vec4 color = albedo * shade;
}
)";

class VariantCostTest : public SimplifyFixture {
 protected:
  VariantCost costOf(const std::map<std::string, std::string>& decisions) {
    const auto variant = library_->buildVariant("S", decisions);
    EXPECT_TRUE(variant);
    return variant ? variantCost(library_->model(), *variant) : VariantCost{};
  }
  static const ComponentCost* row(const VariantCost& cost, const std::string& component) {
    for (const ComponentCost& c : cost.components) {
      if (c.component == component) return &c;
    }
    return nullptr;
  }
};

TEST_F(VariantCostTest, TheRatesComeFromThePipelineNotTheNames) {
  load(kShader);
  const VariantCost cost = costOf({});
  EXPECT_EQ(cost.vertexWorlds, (std::vector<std::string>{"VS"}));
  EXPECT_EQ(cost.fragmentWorlds, (std::vector<std::string>{"PS"}));
}

// By default every component is placed in its latest world, PS, but clip,
// which the pipeline wants in VS.
//   C_v = clip: mat4 * vec4, 16
//   C_f = shade: normalize 3 + dot 3 + max 1; albedo: 100 + 4; color: 4 = 115
//   N_var = pos (3) and uv (2) interpolated from VS into PS = 5
//   C = 0.3 * 16 + 0.7 * 115 + 10 * 5 = 4.8 + 80.5 + 50 = 135.3
TEST_F(VariantCostTest, CountsTheVertexAndFragmentKernelsAndTheVaryings) {
  load(kShader);
  const VariantCost cost = costOf({});
  EXPECT_EQ(cost.vertexOps, 16);
  EXPECT_EQ(cost.fragmentOps, 115);
  EXPECT_EQ(cost.varyings, 5);
  EXPECT_EQ(cost.varyingValues, 2U);
  EXPECT_EQ(cost.totalTenths(), 1353);
  const std::string table = formatVariantCost(cost, "S:");
  EXPECT_NE(table.find("C     = 0.3 * 16 + 0.7 * 115 + 10 * 5 = 135.3\n"), std::string::npos) << table;
}

// shade in VS: its 7 move to C_v, and PS reads shade (1) instead of pos (3).
TEST_F(VariantCostTest, PlacingAComponentInTheVertexWorldMovesItsCost) {
  load(kShader);
  const VariantCost cost = costOf({{"shade", "VS"}});
  EXPECT_EQ(cost.vertexOps, 23);
  EXPECT_EQ(cost.fragmentOps, 108);
  EXPECT_EQ(cost.varyings, 3);
  ASSERT_NE(row(cost, "shade"), nullptr);
  EXPECT_EQ(row(cost, "shade")->rate, WorldRate::Vertex);
  EXPECT_EQ(row(cost, "shade")->ops, 7);
}

// albedo baked in Bake: its 104 are not counted, PS pays one fetch (100);
// uv still reaches PS, where textureImport samples at it.
TEST_F(VariantCostTest, ABakedComponentCostsOneFetchWhereItIsSampled) {
  load(kShader);
  const VariantCost cost = costOf({{"albedo", "Bake"}});
  EXPECT_EQ(cost.vertexOps, 16);
  EXPECT_EQ(cost.fragmentOps, 7 + 100 + 4);
  EXPECT_EQ(cost.varyings, 5);
  const ComponentCost* albedo = row(cost, "albedo");
  ASSERT_NE(albedo, nullptr);
  EXPECT_EQ(albedo->world, "Bake");
  EXPECT_EQ(albedo->rate, WorldRate::Other);
  EXPECT_EQ(albedo->ops, 104);
  EXPECT_EQ(albedo->fetchedIn, (std::vector<std::string>{"PS"}));
}

TEST_F(VariantCostTest, TheToolPrintsTheCostsAndStillWantsAnOutputOtherwise) {
  load(kShader);
  std::ostringstream out;
  std::ostringstream err;
  ASSERT_EQ(runSimplifyTool({source_.string(), "--shader", "S", "--costs"}, out, err), 0) << err.str();
  EXPECT_NE(out.str().find("C_v   = 16 (vertex rate: VS)\n"), std::string::npos) << out.str();
  EXPECT_NE(out.str().find("= 135.3\n"), std::string::npos) << out.str();
  std::ostringstream out2;
  std::ostringstream err2;
  EXPECT_EQ(runSimplifyTool({source_.string(), "--shader", "S"}, out2, err2), 2);
  EXPECT_NE(err2.str().find("-o,--output is required (unless --costs)"), std::string::npos) << err2.str();
  std::ostringstream err3;
  EXPECT_EQ(runSimplifyTool({source_.string(), "--shader", "S", "--decisions", "d", "-o", "m.spire"}, out2, err3), 2);
}

// albedo baked: C_f = 7 + 100 + 4 = 111, so C = 4.8 + 77.7 + 50.
TEST_F(VariantCostTest, TheToolCostsTheVariantOfADecisionFile) {
  load(kShader);
  const std::string decisions = (dir_ / "baked.decisions").string();
  std::ofstream(decisions) << "S.albedo = Bake\n";
  std::ostringstream out;
  std::ostringstream err;
  ASSERT_EQ(runSimplifyTool({source_.string(), "--shader", "S", "--costs", "--decisions", decisions}, out, err), 0)
      << err.str();
  EXPECT_NE(out.str().find("C_f += 100 (a fetch in PS)"), std::string::npos) << out.str();
  EXPECT_NE(out.str().find("C     = 0.3 * 16 + 0.7 * 111 + 10 * 5 = 132.5\n"), std::string::npos) << out.str();
  // A decision the shader cannot take is skipped with a warning.
  std::ofstream(decisions) << "S.color = VS\n";
  std::ostringstream out2;
  std::ostringstream err2;
  ASSERT_EQ(runSimplifyTool({source_.string(), "--shader", "S", "--costs", "--decisions", decisions}, out2, err2), 0);
  EXPECT_NE(err2.str().find("warning"), std::string::npos) << err2.str();
  EXPECT_NE(out2.str().find("= 135.3\n"), std::string::npos) << out2.str();
}

// Two components that compute the same values, as Couch's surface
// components do: equal masks through functions of their own (wear and dirt
// read the same texel, each takes one channel), one called twice with the
// same arguments, and a local that holds a value another component computes
// in one expression. `edge` writes its parameter first, so its texel is
// another one.
const std::string kSharing =
    std::string(kPipeline) + R"(float wear(sampler2D maps, vec2 at) { return texture(maps, at).b * 2.0; }
float dirt(sampler2D maps, vec2 at) { return texture(maps, at).a; }
float edge(sampler2D maps, vec2 at) { at = at * 4.0; return texture(maps, at).a; }
shader S using P {
    @Uni mat4 mvp;
    @Uni sampler2D map;
    vec4 clip = mvp * vec4(pos, 1.0);
    float a {
        float w = wear(map, uv);
        w = w + dirt(map, uv);
        return w;
    }
    float b = wear(map, uv) + dirt(map, uv) + edge(map, uv);
    vec4 color = vec4(a, b, 0.0, 1.0);
}
)";

// Per fragment:
//   a = wear: fetch 100 + `* 2.0` 1; dirt: its fetch is wear's, 0; `+` 1 = 102
//   b = wear + dirt: a's value, 0; edge: `at * 4.0` 2 + fetch 100; `+` 1 = 103
//   color: 0 (a constructor)
// Costed alone, as written, b alone would be 100 + 1 + 100 + 1 + 2 + 100 + 2.
TEST_F(VariantCostTest, AWorldCountsEachValueOnce) {
  load(kSharing);
  const VariantCost cost = costOf({});
  ASSERT_NE(row(cost, "a"), nullptr);
  ASSERT_NE(row(cost, "b"), nullptr);
  EXPECT_EQ(row(cost, "a")->ops + row(cost, "b")->ops, 102 + 103);
  EXPECT_EQ(cost.fragmentOps, 205);
}

// b baked: the Bake kernel computes its own wear and dirt (the model counts
// no Bake world), and PS reads b with a fetch: 100 instead of 103, where
// costing b as written would have made baking it save 303.
TEST_F(VariantCostTest, BakingAComponentThatSharesItsWorkCostsAFetch) {
  load(kSharing);
  const VariantCost shared = costOf({});
  const VariantCost baked = costOf({{"b", "Bake"}});
  EXPECT_EQ(shared.fragmentOps, 102 + 103);
  EXPECT_EQ(baked.fragmentOps, 102 + 100);
}

// Each world counts its own values: a in VS pays for its wear and dirt, and
// b in PS for them again, but only once within b (dirt's texel is wear's):
// 101 + 0 + 1 + (2 + 100) + 1.
TEST_F(VariantCostTest, EachWorldCountsItsOwnValues) {
  load(kSharing);
  const VariantCost cost = costOf({{"a", "VS"}});
  EXPECT_EQ(cost.vertexOps, 16 + 102);
  EXPECT_EQ(row(cost, "b")->ops, 205);
}

// A chain of 20,000 terms, as generated shaders write: its keys stop at
// kMaxValueKey, so no link is shared (they all differ anyway) and keying
// every link stays linear; each `+` counts 1.
TEST_F(VariantCostTest, ALongChainIsCountedWholeWithoutSharing) {
  std::string source = kShader;
  std::string sum = "shade";
  for (int i = 1; i < 20000; ++i) sum += " + shade";
  const std::string line = "    vec4 color = albedo * shade;\n";
  source.replace(source.find(line), line.size(), "    float total = " + sum + ";\n    vec4 color = albedo * total;\n");
  load(source);
  const VariantCost cost = costOf({});
  ASSERT_NE(row(cost, "total"), nullptr);
  EXPECT_EQ(row(cost, "total")->ops, 19999);
}

// Functions that call the one before twice, 40 deep, with arguments that
// never meet (x * 2 * 3 is not x * 3 * 2 to the keys): costed call by
// call, the last would take 2^40 bodies. Past kMaxSharedCalls the calls are
// costed as their bodies alone, once per function, and the cost is finite
// and no more than costed alone.
TEST_F(VariantCostTest, NestedCallsStayLinear) {
  std::string functions = "float f0(float x) { return x * 2.0; }\n";
  for (int i = 1; i <= 40; ++i) {
    functions += fmt::format("float f{}(float x) {{ return f{}(x * 2.0) + f{}(x * 3.0); }}\n", i, i - 1, i - 1);
  }
  std::string source = std::string(kPipeline) + functions + R"(shader S using P {
    @Uni mat4 mvp;
    vec4 clip = mvp * vec4(pos, 1.0);
    float deep = f40(pos.x);
    vec4 color = vec4(deep);
}
)";
  load(source);
  const VariantCost cost = costOf({});
  ASSERT_NE(row(cost, "deep"), nullptr);
  CostModel alone(library_->model());
  const auto variant = library_->buildVariant("S", {});
  ASSERT_TRUE(variant);
  EXPECT_GT(row(cost, "deep")->ops, 0);
  for (sem::ComponentId c : variant->live()) {
    const graph::ComponentNode& node = variant->graph().node(c);
    if (node.component->name != "deep") continue;
    EXPECT_LE(row(cost, "deep")->ops, alone.definition(*node.alternatives[*variant->choice(c)].definition->decl));
  }
}

// A built-in that writes an argument (modf's second) gives the local a new
// value: `ip * 2.0` after it is not the `1.0 * 2.0` that b computes.
//   a = modf 1 + `ip * 2.0` 1 + `+ f` 1 = 3; b = 1.
TEST_F(VariantCostTest, ALocalABuiltinWritesIsANewValue) {
  load(std::string(kPipeline) + R"(shader S using P {
    @Uni mat4 mvp;
    vec4 clip = mvp * vec4(pos, 1.0);
    float a {
        float ip = 1.0;
        float f = modf(pos.x, ip);
        return ip * 2.0 + f;
    }
    float b = 1.0 * 2.0;
    vec4 color = vec4(a, b, 0.0, 1.0);
}
)");
  const VariantCost cost = costOf({});
  ASSERT_NE(row(cost, "a"), nullptr);
  ASSERT_NE(row(cost, "b"), nullptr);
  EXPECT_EQ(row(cost, "a")->ops + row(cost, "b")->ops, 3 + 1);
}

}  // namespace
}  // namespace spire::simplify
