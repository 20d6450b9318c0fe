// The transition shaders of a chain (search/transitions.h) on a module the
// test writes: where they blend, what they define and place, and the bands
// they add to the policy. SearchRun draws them.
#include "search/transitions.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <utility>

#include "search/candidates.h"
#include "search/search_outputs.h"

namespace spire::search {
namespace {

// Level 1 rewrites `tint` (a float vector) and `steps` (an int).
constexpr const char* kModule = R"(using "pipelines/engine.spire";

shader Ramp using EnginePipeline {
    @FrameUniform mat4 matMVP;
    @FrameUniform vec3 cameraPos;
    vec3 tint = vec3(vert_uv, 1.0);
    int steps = 4;
    vec4 projPos = matMVP * vec4(vert_pos, 1.0);
    vec4 output = vec4(tint * float(steps) * 0.25, 1.0);
}

shader RampSearch : Ramp {
    vec3 tint:level1 = vec3(0.5);
    int steps:level1 = 2;
}
)";

lod::LodLevel band(size_t level, float until) {
  lod::LodLevel b;
  b.until = until;
  b.decisions.emplace("RampSearch", fmt::format("out/level{}.decisions", level));
  return b;
}

class TransitionsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    compile_.frontEnd.includeDirs.push_back(SPIRE_SOURCE_DIR);
    auto compiled = compileModule(compile_, "ramp_search.spire", kModule, "RampSearch");
    ASSERT_TRUE(compiled) << compiled.error().message;
    module_ = std::move(compiled).value();
    chain_.levels.resize(2);
    chain_.levels[0].placement = {{"tint", "Fragment"}, {"steps", "Fragment"}, {"output", "Fragment"}};
    chain_.levels[1].placement = {{"tint", "Fragment:level1"}, {"steps", "Fragment:level1"}, {"output", "Fragment"}};
  }

  ModuleCompile compile_;
  Chain chain_;
  std::unique_ptr<ShaderLibrary> module_;
};

TEST_F(TransitionsTest, BlendEachComponentThatDiffersOverTheLastPartOfTheNearerBand) {
  lod::LodPolicy policy;
  policy.levels = {band(0, 10.0F), band(0, 20.0F), band(1, std::numeric_limits<float>::infinity())};
  const TransitionShape shape{0.25, {"length(cameraPos - vert_pos)", {}}};
  auto transitions = chainTransitions(chain_, policy, *module_, "RampSearch", shape);
  ASSERT_TRUE(transitions) << transitions.error().message;
  // Bands 0 and 1 draw the same level: one switch, at 20.
  ASSERT_EQ(transitions->list.size(), 1U);
  const Transition& t = transitions->list.front();
  EXPECT_EQ(t.from, 0U);
  EXPECT_EQ(t.to, 1U);
  EXPECT_EQ(t.band, 1U);
  EXPECT_DOUBLE_EQ(t.farDistance, 20.0);
  EXPECT_DOUBLE_EQ(t.nearDistance, 17.5);  // the last quarter of 10..20
  EXPECT_NE(transitions->shared.find("float spireTransitionDistance = length(cameraPos - vert_pos);"),
            std::string::npos)
      << transitions->shared;
  EXPECT_NE(t.definitions.find("clamp((spireTransitionDistance - 17.5) / 2.5, 0.0, 1.0)"), std::string::npos)
      << t.definitions;
  // Both definitions copied, blended by mix where mix applies and switched
  // halfway where it does not.
  EXPECT_NE(t.definitions.find("vec3 spireTransition0_1_tint_near = vec3(vert_uv, 1.0);"), std::string::npos)
      << t.definitions;
  EXPECT_NE(t.definitions.find("vec3 spireTransition0_1_tint_far = vec3(0.5);"), std::string::npos);
  EXPECT_NE(t.definitions.find("vec3 tint:transition0_1 = mix(spireTransition0_1_tint_near, "
                               "spireTransition0_1_tint_far, spireTransitionFade0_1);"),
            std::string::npos);
  EXPECT_NE(t.definitions.find("int steps:transition0_1 = spireTransitionFade0_1 < 0.5 ? "
                               "spireTransition0_1_steps_near : spireTransition0_1_steps_far;"),
            std::string::npos)
      << t.definitions;
  const Placement expected{{"tint", "Fragment:transition0_1"},
                           {"steps", "Fragment:transition0_1"},
                           {"output", "Fragment"},
                           {"spireTransition0_1_tint_near", "Fragment"},
                           {"spireTransition0_1_tint_far", "Fragment"},
                           {"spireTransition0_1_steps_near", "Fragment"},
                           {"spireTransition0_1_steps_far", "Fragment"}};
  EXPECT_EQ(t.placement, expected);

  // The definitions compile in the derived shader, and the decision file
  // places them.
  std::string text = kModule;
  text.insert(text.rfind('}'), transitionDefinitions(*transitions));
  auto compiled = compileModule(compile_, "ramp_search.spire", text, "RampSearch");
  EXPECT_TRUE(compiled) << (compiled ? "" : compiled.error().message) << text;
  EXPECT_NE(transitionDecisionText(t, {"ramp.spire", "Ramp", "RampSearch"})
                .find("RampSearch.tint = Fragment:transition0_1\n"),
            std::string::npos);
}

TEST_F(TransitionsTest, ThePolicyGetsABandForEachTransitionBetweenTheLevelsItBlends) {
  // Level 2 keeps level 1's tint and takes back the original steps.
  chain_.levels.push_back(chain_.levels[1]);
  chain_.levels[2].placement[1].second = "Fragment";
  lod::LodPolicy policy;
  policy.levels = {band(0, 10.0F), band(1, 30.0F), band(2, std::numeric_limits<float>::infinity())};
  auto transitions = chainTransitions(chain_, policy, *module_, "RampSearch", {0.2, {"0.0", {}}});
  ASSERT_TRUE(transitions) << transitions.error().message;
  ASSERT_EQ(transitions->list.size(), 2U);
  const lod::LodPolicy with = withTransitions(policy, transitions->list, "RampSearch", "out");
  ASSERT_EQ(with.levels.size(), 5U);
  const float ends[] = {8.0F, 10.0F, 26.0F, 30.0F};
  const char* files[] = {"out/level0.decisions", "out/transition0_1.decisions", "out/level1.decisions",
                         "out/transition1_2.decisions", "out/level2.decisions"};
  for (size_t i = 0; i < with.levels.size(); ++i) {
    EXPECT_EQ(with.levels[i].decisions.at("RampSearch"), files[i]) << i;
    EXPECT_EQ(with.levels[i].blend, i % 2 == 1) << i;
    if (i < 4) {
      EXPECT_FLOAT_EQ(with.levels[i].until, ends[i]) << i;
    }
  }
  EXPECT_TRUE(std::isinf(with.levels[4].until));
  // Only steps differs between levels 1 and 2.
  EXPECT_EQ(transitions->list.back().placement[0], (std::pair<std::string, std::string>{"tint", "Fragment:level1"}));
  EXPECT_EQ(transitions->list.back().placement[1],
            (std::pair<std::string, std::string>{"steps", "Fragment:transition1_2"}));

  // A switch between two levels that place alike blends nothing: no band.
  chain_.levels[2] = chain_.levels[1];
  auto none = chainTransitions(chain_, policy, *module_, "RampSearch", {0.2, {"0.0", {}}});
  ASSERT_TRUE(none) << none.error().message;
  EXPECT_EQ(none->list.size(), 1U);
  EXPECT_EQ(transitionDefinitions(Transitions{"shared", {}}), "");
}

// A move carries what its component reads into its world: level 1 moves
// `tint` to Vertex with `shade`, which it reads. Both are blended, and each
// copy reads its own side's copy of `shade`: the far copy of `tint`, in
// Vertex, could not read `shade`'s blend, which is in Fragment.
TEST_F(TransitionsTest, EachCopyReadsItsSidesCopiesOfWhatAMoveCarries) {
  constexpr const char* kShade = R"(using "pipelines/engine.spire";

shader Shade using EnginePipeline {
    @FrameUniform mat4 matMVP;
    @FrameUniform vec3 cameraPos;
    vec3 shade = vec3(vert_uv, 1.0);
    vec3 tint { vec3 half = shade * 0.5; return half + shade.zyx * 0.25; }
    vec4 projPos = matMVP * vec4(vert_pos, 1.0);
    vec4 output = vec4(tint, 1.0);
}

shader ShadeSearch : Shade {
}
)";
  auto shade = compileModule(compile_, "shade.spire", kShade, "ShadeSearch");
  ASSERT_TRUE(shade) << shade.error().message;
  Chain chain;
  chain.levels.resize(2);
  chain.levels[0].placement = {{"shade", "Fragment"}, {"tint", "Fragment"}, {"output", "Fragment"}};
  chain.levels[1].placement = {{"shade", "Vertex"}, {"tint", "Vertex"}, {"output", "Fragment"}};
  lod::LodPolicy policy;
  policy.levels = {band(0, 10.0F), band(1, std::numeric_limits<float>::infinity())};
  for (auto& level : policy.levels) level.decisions = {{"ShadeSearch", level.decisions.at("RampSearch")}};
  const TransitionShape shape{0.25, {"length(cameraPos - vert_pos)", {}}};
  auto transitions = chainTransitions(chain, policy, **shade, "ShadeSearch", shape);
  ASSERT_TRUE(transitions) << transitions.error().message;
  ASSERT_EQ(transitions->list.size(), 1U);
  const std::string& text = transitions->list[0].definitions;
  for (const char* side : {"near", "far"}) {
    EXPECT_NE(text.find(fmt::format("vec3 spireTransition0_1_tint_{0} {{ vec3 half = spireTransition0_1_shade_{0} "
                                    "* 0.5; return half + spireTransition0_1_shade_{0}.zyx * 0.25; }}",
                                    side)),
              std::string::npos)
        << text;
  }
  std::string module = kShade;
  module.insert(module.rfind('}'), transitionDefinitions(*transitions));
  auto compiled = compileModule(compile_, "shade.spire", module, "ShadeSearch");
  ASSERT_TRUE(compiled) << compiled.error().message << module;
  const Placement& placement = transitions->list[0].placement;
  std::vector<std::string> skipped;
  EXPECT_TRUE((*compiled)->buildVariant("ShadeSearch", {placement.begin(), placement.end()}, &skipped));
  EXPECT_TRUE(skipped.empty()) << skipped.front();

  // A local that hides a blended component cannot be told from it.
  std::string hiding = kShade;
  hiding.replace(hiding.find("vec3 half"), 9, "vec3 shade");
  hiding.replace(hiding.find("return half"), 11, "return shade");
  auto hidden = compileModule(compile_, "shade.spire", hiding, "ShadeSearch");
  ASSERT_TRUE(hidden) << hidden.error().message;
  auto refused = chainTransitions(chain, policy, **hidden, "ShadeSearch", shape);
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.error().message.find("declares a local 'shade'"), std::string::npos) << refused.error().message;
}

// The default distance is the policy's: world units, from the engine's
// world-space eye and model matrix, declared where the shader reads the
// engine's other per-frame values when it does not read them.
TEST_F(TransitionsTest, TheDefaultDistanceIsTheEyesInWorldUnits) {
  const sem::Shader* ramp = module_->model().findShader("RampSearch");
  ASSERT_NE(ramp, nullptr);
  auto distance = eyeDistanceInWorld(*ramp);
  ASSERT_TRUE(distance) << distance.error().message;
  EXPECT_EQ(distance->expression, "length(cameraPosWorld - (matModel * vec4(vert_pos, 1.0)).xyz)");
  EXPECT_EQ(distance->declarations, "    @FrameUniform vec3 cameraPosWorld;\n    @FrameUniform mat4 matModel;\n");

  // With transitions, the module compiles.
  lod::LodPolicy policy;
  policy.levels = {band(0, 10.0F), band(1, std::numeric_limits<float>::infinity())};
  auto transitions = chainTransitions(chain_, policy, *module_, "RampSearch", {0.2, *distance});
  ASSERT_TRUE(transitions) << transitions.error().message;
  std::string text = kModule;
  text.insert(text.rfind('}'), transitionDefinitions(*transitions));
  auto compiled = compileModule(compile_, "ramp_search.spire", text, "RampSearch");
  EXPECT_TRUE(compiled) << (compiled ? "" : compiled.error().message) << text;
}

TEST_F(TransitionsTest, TheDefaultDistanceReadsWhatThePipelineAndShaderSupply) {
  // The instanced pipeline supplies matModel per instance, and the shader
  // reads the eye already: nothing to declare.
  constexpr const char* kInstanced = R"(using "pipelines/instanced.spire";

shader Lamp using InstancedPipeline {
    @FrameUniform mat4 matViewProj;
    @FrameUniform vec3 cameraPosWorld;
    vec4 projPos = matViewProj * (matModel * vec4(vert_pos, 1.0));
    vec4 output = vec4(1.0);
}

shader LampSearch : Lamp {
    vec4 output:level1 = vec4(0.5);
}
)";
  auto lamp = compileModule(compile_, "lamp.spire", kInstanced, "LampSearch");
  ASSERT_TRUE(lamp) << lamp.error().message;
  auto distance = eyeDistanceInWorld(*(*lamp)->model().findShader("LampSearch"));
  ASSERT_TRUE(distance) << distance.error().message;
  EXPECT_EQ(distance->declarations, "");
  // matModel reaches only the Vertex world there: the distance is computed
  // per vertex, and the module with its transitions compiles.
  Chain chain;
  chain.levels.resize(2);
  chain.levels[0].placement = {{"output", "Fragment"}};
  chain.levels[1].placement = {{"output", "Fragment:level1"}};
  lod::LodPolicy policy;
  policy.levels = {band(0, 10.0F), band(1, std::numeric_limits<float>::infinity())};
  for (auto& level : policy.levels) level.decisions = {{"LampSearch", level.decisions.at("RampSearch")}};
  auto transitions = chainTransitions(chain, policy, **lamp, "LampSearch", {0.2, *distance});
  ASSERT_TRUE(transitions) << transitions.error().message;
  ASSERT_EQ(transitions->list.size(), 1U);
  std::string text = kInstanced;
  text.insert(text.rfind('}'), transitionDefinitions(*transitions));
  auto compiled = compileModule(compile_, "lamp.spire", text, "LampSearch");
  ASSERT_TRUE(compiled) << compiled.error().message << text;
  std::map<std::string, std::string> decisions(transitions->list[0].placement.begin(),
                                               transitions->list[0].placement.end());
  std::vector<std::string> skipped;
  EXPECT_TRUE((*compiled)->buildVariant("LampSearch", decisions, &skipped));
  EXPECT_TRUE(skipped.empty()) << skipped.front();

  // A shader that reads no engine value per frame has no world to read the
  // eye from; one that reads the eye under another type is not the engine's.
  constexpr const char* kUnlit = R"(using "pipelines/engine.spire";

shader Unlit using EnginePipeline {
    @MaterialUniform mat4 placed;
    vec4 projPos = placed * vec4(vert_pos, 1.0);
    vec4 output = vec4(1.0);
}

shader Odd using EnginePipeline {
    @FrameUniform vec4 cameraPosWorld;
    vec4 projPos = vec4(vert_pos, 1.0) + cameraPosWorld;
    vec4 output = vec4(1.0);
}
)";
  for (const char* name : {"Unlit", "Odd"}) {
    auto unlit = compileModule(compile_, "unlit.spire", kUnlit, name);
    ASSERT_TRUE(unlit) << unlit.error().message;
    auto none = eyeDistanceInWorld(*(*unlit)->model().findShader(name));
    ASSERT_FALSE(none) << name;
    EXPECT_NE(none.error().message.find(name == std::string("Unlit") ? "reads no per-frame engine value"
                                                                     : "as a vec4, not the engine's vec3"),
              std::string::npos)
        << none.error().message;
  }
}

}  // namespace
}  // namespace spire::search
