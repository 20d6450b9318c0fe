// The level-of-detail scene on the device: batches formed from kernel keys,
// each level's image equal to the same shaders drawn one object at a time
// (so per-instance records and texture-array layers reach the right
// object), levels that follow the policy as the camera moves, and a scene
// made from programs compiled on another thread (SceneRenderer::
// compileShaderIn) that draws exactly as one that compiled them itself.
#include "renderer/lod_scene.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <future>
#include <set>

#include "common/lod_test_scene.h"
#include "engine/renderer_fixture.h"
#include "lod/lod_policy.h"

namespace spire::engine::testing {
namespace {

lod::LodPolicy policy(uint32_t transitionFrames = 0) {
  lod::LodPolicy p;
  p.levels = {
      {"LodHQ", 6.0F, {}, {}}, {"LodMQ", 14.0F, {}, {}}, {"LodLQ", std::numeric_limits<float>::infinity(), {}, {}}};
  p.hysteresis = 0.1F;
  p.transitionFrames = transitionFrames;
  return p;
}

TextureBakeOptions smallBakes() {
  TextureBakeOptions options;
  options.defaultSize = 64;
  return options;
}

class LodSceneTest : public RendererTest {
 protected:
  std::unique_ptr<LodScene> lodScene(const std::string& json, const LodOptions& options,
                                     const lod::LodPolicy& p = policy()) {
    if (!loadScene(json)) return nullptr;
    renderer_ = std::make_unique<SceneRenderer>(ctx(), *scene_, *diags_, smallBakes());
    auto scene = LodScene::create(*renderer_, p, options);
    if (!scene) {
      ADD_FAILURE() << scene.error().message << "\n"
                    << scene.error().details << renderDiagnostics(*sources_, *diags_, DiagnosticFormat::Text);
      return nullptr;
    }
    return std::move(scene).value();
  }
};

TEST_F(LodSceneTest, MaterialsSharingLockedKernelsLandInOneBatch) {
  // blocks: 2 x 2 over the copies' extent; every level of every prototype
  // in view from above.
  for (uint32_t level = 0; level < 3; ++level) {
    auto scene =
        lodScene(spire::testing::lodTestSceneJson({true, R"([{"position": [0, 30, 0.01], "target": [0, 0, 0]}])"}),
                 {.fixedLevel = level});
    ASSERT_TRUE(scene);
    scene->resetLevels(scene_->camera.views.front());
    ASSERT_TRUE(scene->render(scene_->camera.views.front(), 0.0F));
    const LodFrameStats& stats = scene->lastStats();
    EXPECT_EQ(stats.visible, scene->instanceCount());
    // HQ: each material its own kernels, so a batch per material and block
    // it has copies in; MQ and LQ: the locked kernels, one batch per block.
    const lod::DrawGroups& groups = scene->drawGroups();
    EXPECT_EQ(groups.groupCount, level == 0 ? 4U : 1U) << "level " << level;
    // Every level of the library writes lodFade as its alpha: each group's
    // switches cross-fade.
    ASSERT_EQ(groups.fades.size(), groups.groupCount);
    EXPECT_TRUE(std::all_of(groups.fades.begin(), groups.fades.end(), [](uint8_t f) { return f == 1; }));
    if (level > 0) {
      EXPECT_EQ(stats.batches, 4U);  // the four blocks
      EXPECT_GE(stats.drawCalls, 4U + 3U);
    } else {
      EXPECT_GT(stats.batches, 4U);
    }
  }
}

// A level drawn in batches (one instanced draw for the three locked
// materials, their bakes in texture-array layers and per-instance records)
// gives the image of the same shaders drawn one object at a time by the
// scene renderer, as spire-demo draws them: each object's own baked values
// and textures reached it, at its own transform.
TEST_F(LodSceneTest, EachLevelMatchesTheSameShadersDrawnOneObjectAtATime) {
  const std::string members[] = {"LodHQ", "LodMQ", "LodLQ"};
  for (uint32_t level = 0; level < 3; ++level) {
    auto scene = lodScene(spire::testing::lodTestSceneJson({.scatter = false}), {.fixedLevel = level});
    ASSERT_TRUE(scene);
    scene->resetLevels(scene_->camera.views.front());
    ASSERT_TRUE(scene->render(scene_->camera.views.front(), 0.0F));
    auto batched = scene->readColor();
    ASSERT_TRUE(batched) << batched.error().message;
    if (level > 0) {
      EXPECT_EQ(scene->lastStats().batches, 1U) << "level " << level;  // one block, one group
    }

    std::string json = spire::testing::lodTestSceneJson({.scatter = false});
    for (const char* shader : {"TerrainLod", "Barrel", "Sofa", "Rock"}) {
      const std::string from = fmt::format(R"("shader": "{}")", shader);
      json.replace(json.find(from), from.size(), fmt::format(R"("shader": "{}<{}>")", shader, members[level]));
    }
    auto single = render(json, std::nullopt, smallBakes());
    ASSERT_TRUE(single);
    ASSERT_EQ(single->capture.color.rgba.size(), batched->rgba.size());
    double worst = 0.0;
    size_t lit = 0;
    for (size_t i = 0; i < batched->rgba.size(); ++i) {
      worst = std::max(worst, static_cast<double>(std::abs(batched->rgba[i] - single->capture.color.rgba[i])));
      lit += i % 4 == 0 && batched->rgba[i] > 0.02F ? 1 : 0;
    }
    EXPECT_LT(worst, 1e-5) << members[level];
    EXPECT_GT(lit, batched->rgba.size() / 4 / 8) << members[level] << ": the objects should cover the view";
  }
}

// As the camera moves away and back, every copy's level is the one the
// policy gives for its distance, with the hysteresis margin: never farther
// than its band widened by the margin allows.
TEST_F(LodSceneTest, LevelsFollowThePolicyWithHysteresisAsTheCameraMoves) {
  const lod::LodPolicy p = policy();
  auto scene = lodScene(spire::testing::lodTestSceneJson(), {}, p);
  ASSERT_TRUE(scene);
  scene::CameraView view = scene_->camera.views.front();
  scene->resetLevels(view);
  std::set<uint32_t> seen;
  for (int frame = 0; frame < 24; ++frame) {
    view.position = glm::vec3(0.0F, 2.0F, 2.0F + static_cast<float>(frame < 12 ? frame : 24 - frame) * 1.5F);
    view.target = glm::vec3(0.0F, 0.0F, -40.0F);
    ASSERT_TRUE(scene->render(view, static_cast<float>(frame) / 60.0F));
    for (size_t i = 0; i < scene->instanceCount(); ++i) {
      const float d = scene->instance(i).bounds.nearest(view.position);
      const uint32_t level = scene->levelOf(i);
      seen.insert(level);
      const float lo = level == 0 ? 0.0F : p.levels[level - 1].until * (1.0F - p.hysteresis);
      const float hi = p.levels[level].until * (1.0F + p.hysteresis);
      ASSERT_GE(d, lo) << "instance " << i << " frame " << frame;
      ASSERT_LE(d, hi) << "instance " << i << " frame " << frame;
    }
  }
  EXPECT_EQ(seen.size(), 3U);
}

TEST_F(LodSceneTest, LevelsCompiledOnAnotherThreadDrawAsTheSceneCompilesThem) {
  auto compiledHere = lodScene(spire::testing::lodTestSceneJson({.scatter = false}), {});
  ASSERT_TRUE(compiledHere);
  const scene::CameraView& view = scene_->camera.views.front();
  compiledHere->resetLevels(view);
  ASSERT_TRUE(compiledHere->render(view, 0.0F));
  auto expected = compiledHere->readColor();
  ASSERT_TRUE(expected);

  std::vector<ShaderLibrary*> libraries;
  for (size_t p = 0; p < scene_->instances.size(); ++p) libraries.push_back(*renderer_->library(p));
  // As spire-explore's worker: nothing but the libraries, off the renderer's thread.
  auto programs = std::async(std::launch::async, [&]() -> Expected<LodScene::LevelPrograms> {
                    LodScene::LevelPrograms levels;
                    std::string warnings;
                    for (const lod::LodLevel& level : policy().levels) {
                      std::vector<VariantProgram>& row = levels.emplace_back();
                      for (size_t p = 0; p < libraries.size(); ++p) {
                        auto program = renderer_->compileLevelIn(*libraries[p], p, level, warnings);
                        if (!program) return program.error();
                        row.push_back(std::move(program).value());
                      }
                    }
                    return levels;
                  }).get();
  ASSERT_TRUE(programs) << programs.error().message << "\n" << programs.error().details;
  EXPECT_FALSE(LodScene::createCompiled(*renderer_, policy(), LodScene::LevelPrograms(1)))
      << "one level's programs for a policy of three";
  auto compiledElsewhere = LodScene::createCompiled(*renderer_, policy(), std::move(programs).value());
  ASSERT_TRUE(compiledElsewhere) << compiledElsewhere.error().message;
  LodScene& elsewhere = **compiledElsewhere;
  elsewhere.resetLevels(view);
  ASSERT_TRUE(elsewhere.render(view, 0.0F));
  auto color = elsewhere.readColor();
  ASSERT_TRUE(color);
  EXPECT_EQ(color->rgba, expected->rgba);
}

// Two members, one of which writes lodFade into its alpha and one that
// does not: a policy that cross-fades switches into the second is warned
// about (W7102) at that level, unless it does not cross-fade (no
// transitionFrames) or the switch comes from a blend band, which is
// seamless.
TEST_F(LodSceneTest, ASwitchIntoALevelThatCannotFadeIsWarnedAbout) {
  const std::string json = R"({"resolution": [32, 32],
  "camera": {"views": [{"position": [0, 3, 3], "target": [0, 0, 0]}]},
  "lod": {"policy": "unused.json", "blocks": 1},
  "meshes": {"box": {"type": "box", "size": 1}},
  "instances": [{"mesh": "box", "source": "lod_fades.spire", "shader": "Thing"}]})";
  const auto level = [](const char* member, float until) { return lod::LodLevel{member, until, {}, {}}; };
  const float beyond = std::numeric_limits<float>::infinity();
  lod::LodLevel blend = level("Fades", 6.0F);
  blend.blend = true;
  struct Case {
    std::vector<lod::LodLevel> levels;
    uint32_t transitionFrames;
    std::vector<std::string> warned;  // the members warned about
  };
  const std::vector<Case> cases = {
      {{level("Fades", 5.0F), level("Opaque", beyond)}, 4, {"Opaque"}},
      {{level("Opaque", 5.0F), level("Fades", beyond)}, 4, {"Opaque"}},
      {{level("Fades", 5.0F), level("Opaque", beyond)}, 0, {}},
      {{level("Fades", 5.0F), blend, level("Opaque", beyond)}, 4, {}},
  };
  for (const Case& c : cases) {
    lod::LodPolicy p;
    p.levels = c.levels;
    p.transitionFrames = c.transitionFrames;
    auto scene = lodScene(json, {}, p);
    ASSERT_TRUE(scene);
    scene->reportSwitchesThatCannotFade(*diags_);
    std::vector<std::string> warned;
    for (const Diagnostic& d : diags_->all()) {
      if (d.code != DiagCode::W7102) continue;
      EXPECT_NE(d.message.find("does not read lodFade, so switches into this level are drawn at once, not "
                               "cross-faded over the policy's 4 transitionFrames"),
                std::string::npos)
          << d.message;
      warned.push_back(d.message.substr(d.message.find("(") + 1, d.message.find(")") - d.message.find("(") - 1));
    }
    EXPECT_EQ(warned, c.warned) << renderDiagnostics(*sources_, *diags_, DiagnosticFormat::Text);
  }
}

}  // namespace
}  // namespace spire::engine::testing
