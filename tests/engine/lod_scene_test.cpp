// The level-of-detail scene on the device: batches formed from kernel keys,
// each level's image equal to the same shaders drawn one object at a time
// (so per-instance records and texture-array layers reach the right
// object), and levels that follow the policy as the camera moves.
#include "renderer/lod_scene.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <set>

#include "engine/renderer_fixture.h"
#include "lod/lod_policy.h"

namespace spire::engine::testing {
namespace {

const std::string kMaterials = (fs::path(SPIRE_SOURCE_DIR) / "examples/lod_materials.spire").string();

lod::LodPolicy policy(uint32_t transitionFrames = 0) {
  lod::LodPolicy p;
  p.levels = {{"LodHQ", 6.0F, {}}, {"LodMQ", 14.0F, {}}, {"LodLQ", std::numeric_limits<float>::infinity(), {}}};
  p.hysteresis = 0.1F;
  p.transitionFrames = transitionFrames;
  return p;
}

// Four materials on a small terrain: the terrain itself and copies (or, with
// `scatter` false, one of each at a fixed place) of a barrel, a sofa and a
// rock.
std::string lodJson(bool scatter, const std::string& camera = R"([0, 9, 13], "target": [0, 0, 0])") {
  const auto placed = [&](const char* mesh, const char* shader, int seed, const char* at, const char* material) {
    const std::string where = scatter ? fmt::format(R"("scatter": {{"count": 12, "seed": {}, "on": "hills"}})", seed)
                                      : fmt::format(R"("transform": {{"translate": {}}})", at);
    return fmt::format(R"(, {{"mesh": "{}", "source": "{}", "shader": "{}", {}, "material": {}}})", mesh, kMaterials,
                       shader, where, material);
  };
  return R"({"resolution": [96, 64], "frames": 2, "warmupFrames": 1, "clearColor": [0, 0, 0, 1],
  "camera": {"fovY": 60, "views": [{"position": )" +
         camera + R"(}]},
  "lod": {"policy": "unused.json", "blocks": )" +
         std::string(scatter ? "2" : "1") + R"(},
  "meshes": {"hills": {"type": "terrain", "size": 12, "resolution": 16, "height": 0.5, "seed": 3},
             "barrel": {"type": "cylinder", "radius": 0.4, "height": 1.0, "segments": 12},
             "sofa": {"type": "box", "size": 0.8, "height": 0.5},
             "rock": {"type": "rock", "radius": 0.5, "rings": 6, "segments": 12, "seed": 4}},
  "textures": {"n": {"type": "noise", "size": 32, "seed": 9, "octaves": 3},
               "c": {"type": "noise", "size": 32, "seed": 2, "color": [0.8, 0.3, 0.1], "color2": [0.1, 0.2, 0.6]},
               "nm": {"type": "normalMap", "size": 32, "seed": 5}},
  "instances": [{"mesh": "hills", "source": ")" +
         kMaterials +
         R"(", "shader": "TerrainLod", "material": {"mixMap": "n", "albedoMap1": "c", "albedoMap2": "n",
     "normalMap1": "nm", "normalMap2": "nm"}})" +
         placed("barrel", "Barrel", 1, "[-2, 0.3, 1]",
                R"({"woodGrainMap": "c", "woodNormalMap": "nm", "grimeMap": "n", "rustMap": "n", "staveCount": 16,
      "bandWidth": 0.05, "grimeAmount": 0.5, "rustAmount": 0.4, "metalColor": [0.35, 0.35, 0.38],
      "rustColor": [0.45, 0.2, 0.08]})") +
         placed("sofa", "Sofa", 2, "[0, 0.3, 2]",
                R"({"fabricColorMap": "c", "fabricNormalMap": "nm", "wearMap": "n", "fabricColor": [0.55, 0.2, 0.15],
      "pipingColor": [0.9, 0.85, 0.7], "weaveDensity": 120, "panelCount": 3, "wearAmount": 0.4})") +
         placed("rock", "Rock", 3, "[2, 0.3, 0]",
                R"({"rockNoiseMap": "n", "rockDetailMap": "n", "rockNormalMap": "nm", "crackMap": "n",
      "mossMap": "c", "rockColor1": [0.5, 0.48, 0.45], "rockColor2": [0.35, 0.33, 0.3], "mossAmount": 0.5,
      "crackWidth": 0.02})") +
         "]}";
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
    auto scene = lodScene(lodJson(true, R"([0, 30, 0.01], "target": [0, 0, 0])"), {.fixedLevel = level});
    ASSERT_TRUE(scene);
    scene->resetLevels(scene_->camera.views.front());
    ASSERT_TRUE(scene->render(scene_->camera.views.front(), 0.0F));
    const LodFrameStats& stats = scene->lastStats();
    EXPECT_EQ(stats.visible, scene->instanceCount());
    // HQ: each material its own kernels, so a batch per material and block
    // it has copies in; MQ and LQ: the locked kernels, one batch per block.
    const lod::DrawGroups& groups = scene->drawGroups();
    EXPECT_EQ(groups.groupCount, level == 0 ? 4U : 1U) << "level " << level;
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
    auto scene = lodScene(lodJson(false), {.fixedLevel = level});
    ASSERT_TRUE(scene);
    scene->resetLevels(scene_->camera.views.front());
    ASSERT_TRUE(scene->render(scene_->camera.views.front(), 0.0F));
    auto batched = scene->readColor();
    ASSERT_TRUE(batched) << batched.error().message;
    if (level > 0) {
      EXPECT_EQ(scene->lastStats().batches, 1U) << "level " << level;  // one block, one group
    }

    std::string json = lodJson(false);
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
  auto scene = lodScene(lodJson(true), {}, p);
  ASSERT_TRUE(scene);
  scene::CameraView view = scene_->camera.views.front();
  scene->resetLevels(view);
  std::set<uint32_t> seen;
  for (int frame = 0; frame < 24; ++frame) {
    view.position = glm::vec3(0.0F, 2.0F, 2.0F + static_cast<float>(frame < 12 ? frame : 24 - frame) * 1.5F);
    view.target = glm::vec3(0.0F, 0.0F, -40.0F);
    ASSERT_TRUE(scene->render(view, static_cast<float>(frame) / 60.0F));
    for (size_t i = 0; i < scene->instanceCount(); ++i) {
      const float d =
          std::max(0.0F, glm::distance(scene->instance(i).center, view.position) - scene->instance(i).radius);
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

}  // namespace
}  // namespace spire::engine::testing
