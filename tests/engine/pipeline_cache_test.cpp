// The renderer's pipeline cache (renderer/pipeline_cache.h) across
// prepare() calls, as spire-explore prepares the scene after each change:
// instances whose kernels did not change keep their pipelines, and the
// image is exactly the one a renderer preparing the scene afresh draws.
#include <gtest/gtest.h>

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "engine/renderer_fixture.h"
#include "renderer/scene_renderer.h"

namespace spire::engine {
namespace {

using testing::planeScene;
using testing::RendererTest;

class PipelineCacheTest : public RendererTest {
 protected:
  // Three planes side by side: TexBake (its texColor decided per test), TexBake
  // per fragment, and FlatPlane; different kernels, so three pipelines.
  bool loadThreePlanes() {
    std::string scene = planeScene("tex_bake.spire", "TexBake", R"({"colorMap": "checker"})");
    const std::string others = R"(}, {"mesh": "plane", "source": "tex_bake.spire", "shader": "TexBake",
        "transform": {"translate": [0.6, 0.1, 0]}, "material": {"colorMap": "noise"}},
      {"mesh": "plane", "source": "flat_plane.spire", "shader": "FlatPlane",
        "transform": {"translate": [-0.6, 0.2, 0]}, "material": {"color": [0.2, 0.4, 0.6, 1.0]}}])";
    scene.replace(scene.rfind("}]"), 2, others);
    return loadScene(scene);
  }

  // Every instance's variant, instance 0 with texColor in `texColorWorld`.
  std::vector<VariantProgram> programs(SceneRenderer& renderer, const std::string& texColorWorld) {
    const std::map<std::string, std::string> decisions[] = {
        {{"texColor", texColorWorld}}, {{"texColor", "Fragment"}}, {}};
    std::vector<VariantProgram> result;
    for (size_t i = 0; i < 3; ++i) {
      auto program = renderer.compileVariant(i, decisions[i]);
      EXPECT_TRUE(program) << program.error().message << "\n" << program.error().details;
      if (!program) return {};
      result.push_back(std::move(program).value());
    }
    return result;
  }
};

TEST_F(PipelineCacheTest, UnchangedInstancesKeepTheirPipelinesAndTheImageIsAFreshPreparesImage) {
  ASSERT_TRUE(loadThreePlanes());
  SceneRenderer renderer(ctx(), *scene_, *diags_);
  const std::vector<VariantProgram> before = programs(renderer, "Vertex");
  ASSERT_EQ(before.size(), 3U);
  auto prepared = renderer.prepare(before);
  ASSERT_TRUE(prepared) << prepared.error().message;
  std::optional<PreparedScene> first = std::move(prepared).value();
  EXPECT_EQ(first->pipelines.created, 3U);
  EXPECT_EQ(first->pipelines.reused, 0U);

  // Instance 0 changes while the first scene is still alive (on screen).
  const std::vector<VariantProgram> after = programs(renderer, "PrebakeTex");
  ASSERT_EQ(after.size(), 3U);
  auto second = renderer.prepare(after);
  ASSERT_TRUE(second) << second.error().message;
  EXPECT_EQ(second->pipelines.created, 1U);
  EXPECT_EQ(second->pipelines.reused, 2U);
  EXPECT_NE(second->items[0].pipeline->pipeline.get(), first->items[0].pipeline->pipeline.get());
  EXPECT_EQ(second->items[1].pipeline.get(), first->items[1].pipeline.get());
  EXPECT_EQ(second->items[2].pipeline.get(), first->items[2].pipeline.get());
  EXPECT_EQ(renderer.pipelineCounts().created, 4U);
  EXPECT_EQ(renderer.pipelineCounts().reused, 2U);

  // The scene that built the shared pipelines goes first: the new one keeps them.
  first.reset();
  auto reused = renderer.capture(*second, scene_->camera.views.front());
  ASSERT_TRUE(reused) << reused.error().message;

  SceneRenderer fresh(ctx(), *scene_, *diags_);
  auto freshPrepared = fresh.prepare(programs(fresh, "PrebakeTex"));
  ASSERT_TRUE(freshPrepared) << freshPrepared.error().message;
  EXPECT_EQ(freshPrepared->pipelines.reused, 0U);
  auto expected = fresh.capture(*freshPrepared, scene_->camera.views.front());
  ASSERT_TRUE(expected) << expected.error().message;
  EXPECT_GT(coveredFraction(*expected), 0.3);
  EXPECT_EQ(reused->color.rgba, expected->color.rgba);
  EXPECT_EQ(reused->coverage, expected->coverage);
}

// A pipeline no prepared scene holds any more is built again, not kept:
// the cache grows with the pipelines in use.
TEST_F(PipelineCacheTest, PipelinesOfDroppedScenesAreNotKept) {
  ASSERT_TRUE(loadThreePlanes());
  SceneRenderer renderer(ctx(), *scene_, *diags_);
  const std::vector<VariantProgram> variant = programs(renderer, "Vertex");
  ASSERT_EQ(variant.size(), 3U);
  { ASSERT_TRUE(renderer.prepare(variant)); }
  auto again = renderer.prepare(variant);
  ASSERT_TRUE(again) << again.error().message;
  EXPECT_EQ(again->pipelines.created, 3U);
  EXPECT_EQ(again->pipelines.reused, 0U);
}

}  // namespace
}  // namespace spire::engine
