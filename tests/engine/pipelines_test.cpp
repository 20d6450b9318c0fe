// The engine on pipelines other than the ones it ships: the paper's Figure 4
// pipeline as drawn, where PrebakeVertex feeds Vertex and PrebakeTex through
// standardImport (tests/data/engine/figure4.spire). Every world choice of its
// shader renders, with validation on, and each image is checked against what
// its placement must give: per-vertex, per-texel and per-fragment placements
// of a value linear in the attributes give the reference image, and a
// PrebakeUniform placement makes the value constant over the mesh.
#include <gtest/gtest.h>

#include <fmt/format.h>
#include <algorithm>

#include <fstream>

#include "driver/shader_library.h"
#include "engine/renderer_fixture.h"
#include "renderer/frame_pass.h"

namespace spire::engine {
namespace {

namespace fs = std::filesystem;
using testing::kDataDir;
using testing::planeScene;

std::string figure4Scene() {
  std::string scene = planeScene("figure4.spire", "Figure4Shade", R"({"tint": [0.9, 0.5, 0.2]})");
  scene.replace(scene.find("\"mesh\": \"plane\""), 15, "\"mesh\": \"ball\"");
  return scene;
}

// The largest difference of channel `c` between covered pixels.
double channelSpread(const Capture& capture, size_t c) {
  float low = 1e30F;
  float high = -1e30F;
  for (size_t i = 0; i < capture.coverage.size(); ++i) {
    if (!capture.coverage[i]) continue;
    low = std::min(low, capture.color.rgba[i * 4 + c]);
    high = std::max(high, capture.color.rgba[i * 4 + c]);
  }
  return high - low;
}

// Whether a kernel of `program` reads an input from `producer` as a varying:
// the standardImport edge the test is about.
bool readsVaryingFrom(const VariantProgram& program, std::string_view consumer, std::string_view producer) {
  const KernelProgram* kernel = program.kernel(consumer);
  if (!kernel) return false;
  return std::any_of(kernel->inputs.begin(), kernel->inputs.end(), [&](const KernelInput& input) {
    return input.kind == InputKind::Varying && input.from == producer;
  });
}

class Figure4Test : public testing::RendererTest {
 protected:
  void SetUp() override {
    RendererTest::SetUp();
    if (IsSkipped() || HasFatalFailure()) return;
    reference_ = render(figure4Scene(), std::nullopt);
    ASSERT_TRUE(reference_);
    ASSERT_GT(coveredFraction(reference_->capture), 0.2);
  }

  // Renders Figure4Shade with `decisions` ("Figure4Shade.shade = Vertex" lines).
  std::optional<Rendered> renderFigure4(const std::string& name, const std::string& decisions) {
    return renderWith(figure4Scene(), "figure4_" + name, decisions);
  }

  std::optional<Rendered> reference_;
};

TEST_F(Figure4Test, EveryWorldChoiceRendersWhatItsPlacementMeans) {
  ShaderLibrary library;
  ASSERT_TRUE(library.addFile((kDataDir / "figure4.spire").string()));
  ASSERT_TRUE(library.compile());
  const std::vector<Choice> choices = library.choices("Figure4Shade");
  ASSERT_EQ(choices.size(), 3U);
  size_t rendered = 0;
  for (const Choice& choice : choices) {
    const std::string component = choice.key.substr(choice.key.find('.') + 1);
    ASSERT_EQ(choice.names.size(), 5U) << choice.key;
    for (const std::string& world : choice.names) {
      SCOPED_TRACE(choice.key + " = " + world);
      const auto variant = renderFigure4(component + "_" + world, fmt::format("{} = {}\n", choice.key, world));
      ASSERT_TRUE(variant);
      ++rendered;
      EXPECT_EQ(variant->capture.coverage, reference_->capture.coverage);
      const measure::ImageError error = compare(reference_->capture, variant->capture);
      EXPECT_EQ(error.nanPixels + error.infPixels, 0U);
      if (world != "PrebakeUniform" || component == "tinted") {
        // Texture bakes resample (RGBA16F, bilinear, seams of the sphere's UVs).
        EXPECT_LT(error.rmse, world == "PrebakeTex" ? 5e-3 : 1e-5);
        continue;
      }
      // An average over the vertices is constant: all of ramp, and the blue
      // channel of the output when shade is averaged (ramp.b = shade.b / 2 + 0.125).
      EXPECT_LT(channelSpread(variant->capture, 2), 1e-6);
      if (component == "ramp") {
        EXPECT_LT(channelSpread(variant->capture, 0), 1e-6);
      }
      EXPECT_GT(error.rmse, 1e-3) << "an average should differ from the per-pixel value";
    }
  }
  EXPECT_EQ(rendered, 15U);
}

// PrebakeVertex's records reach Vertex and PrebakeTex as vertex attributes
// (standardImport), and values computed from them match the reference.
TEST_F(Figure4Test, VertexBakeRecordsAreVertexAttributesOfVertexAndPrebakeTex) {
  const auto intoVertex =
      renderFigure4("into_vertex", "Figure4Shade.shade = PrebakeVertex\nFigure4Shade.ramp = Vertex\n");
  ASSERT_TRUE(intoVertex);
  ASSERT_EQ(intoVertex->programs.size(), 1U);
  EXPECT_TRUE(readsVaryingFrom(intoVertex->programs[0], "Vertex", "PrebakeVertex"));
  EXPECT_LT(compare(reference_->capture, intoVertex->capture).maxError, 1e-5);

  const auto intoTexture =
      renderFigure4("into_texture", "Figure4Shade.shade = PrebakeVertex\nFigure4Shade.ramp = PrebakeTex\n");
  ASSERT_TRUE(intoTexture);
  EXPECT_TRUE(readsVaryingFrom(intoTexture->programs[0], "PrebakeTex", "PrebakeVertex"));
  std::vector<std::string> bakes;
  for (const BakeRecord& bake : intoTexture->prepared.bakes) bakes.push_back(bake.world);
  EXPECT_EQ(bakes, (std::vector<std::string>{"PrebakeVertex", "PrebakeTex"}));
  EXPECT_LT(compare(reference_->capture, intoTexture->capture).rmse, 5e-3);
  expectGolden(intoTexture->capture, "figure4_vertex_bake_into_texture");
}

// An edge the pipeline declares but the engine cannot run (a per-frame value
// into a bake that runs once) is refused when the variant is loaded, naming
// the kernel, the input and the edges the engine implements out of that role.
class EdgeTest : public testing::RendererTest {};

TEST_F(EdgeTest, AnEdgeTheEngineDoesNotImplementIsRefusedListingTheEdgesItDoes) {
  const fs::path decisions = writeDecisions("frame_into_bake", "FrameIntoBake.pulse = PrebakeTex\n");
  ASSERT_TRUE(loadScene(planeScene("frame_into_bake.spire", "FrameIntoBake", "{}")));
  renderer_ = std::make_unique<SceneRenderer>(ctx(), *scene_, *diags_);
  const auto programs = renderer_->compile(decisions);
  ASSERT_FALSE(programs);
  const std::string& message = programs.error().message;
  EXPECT_NE(message.find("the PrebakeTex kernel (prebakeTexture) reads 'time' from world 'FrameUniform' (frame) as a "
                         "uniform input (uniformImport), an edge this engine does not implement"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("out of frame it implements: uniform into vertex, fragment"), std::string::npos) << message;

  // Placed where the engine runs frame values, the same shader renders.
  EXPECT_TRUE(render(planeScene("frame_into_bake.spire", "FrameIntoBake", "{}"), std::nullopt));
}

// A scene retargets an instance's shader (written for EnginePipeline) to
// FiveWorldPipeline, whose extra worlds then take decisions: the same image
// with texColor computed per vertex at load (PrebakeVertex) as computed by
// the Vertex kernel.
TEST_F(EdgeTest, AnInstanceRetargetedToAnotherPipelineRendersItsWorlds) {
  const std::string retarget =
      R"("pipeline": {"name": "FiveWorldPipeline", "source": "../../../pipelines/five_world.spire"}, )";
  std::string scene = planeScene("tex_bake.spire", "TexBake", R"({"colorMap": "checker"})");
  scene.replace(scene.find(R"("mesh": "plane")"), 0, retarget);
  const auto perVertex = renderWith(scene, "retarget_vertex", "TexBake.texColor = Vertex\n");
  ASSERT_TRUE(perVertex);
  EXPECT_EQ(perVertex->programs.at(0).pipeline, "FiveWorldPipeline");
  const auto baked = renderWith(scene, "retarget_prebake", "TexBake.texColor = PrebakeVertex\n");
  ASSERT_TRUE(baked);
  ASSERT_EQ(baked->prepared.bakes.size(), 1U);
  EXPECT_EQ(baked->prepared.bakes[0].world, "PrebakeVertex");
  EXPECT_GT(coveredFraction(baked->capture), 0.2);
  EXPECT_LT(compare(perVertex->capture, baked->capture).maxError, 1e-5);

  // Without retargeting the world does not exist: the decision is skipped.
  const auto original = render(planeScene("tex_bake.spire", "TexBake", R"({"colorMap": "checker"})"), std::nullopt);
  ASSERT_TRUE(original);
  EXPECT_EQ(original->programs.at(0).pipeline, "EnginePipeline");
}

// A retargeting pipeline that no file declares is an error at the instance's
// "pipeline", with the compiler's diagnostic.
TEST_F(EdgeTest, AnUnknownRetargetingPipelineIsAnErrorAtTheSceneLine) {
  std::string scene = planeScene("tex_bake.spire", "TexBake", R"({"colorMap": "checker"})");
  scene.replace(scene.find(R"("mesh": "plane")"), 0, R"("pipeline": {"name": "FiveWorldPipelin"}, )");
  ASSERT_TRUE(loadScene(scene));
  renderer_ = std::make_unique<SceneRenderer>(ctx(), *scene_, *diags_);
  const auto programs = renderer_->compile(std::nullopt);
  ASSERT_FALSE(programs);
  EXPECT_NE(programs.error().message.find("does not compile against pipeline 'FiveWorldPipelin'"), std::string::npos)
      << programs.error().message;
  EXPECT_NE(programs.error().details.find("cannot retarget 'TexBake' to pipeline 'FiveWorldPipelin'"),
            std::string::npos)
      << programs.error().details;
}

// A kernel that writes more textures than the device has color attachments
// is refused with the kernel and the limit; it used to crash the driver.
TEST_F(EdgeTest, MoreTexturesThanColorAttachmentsIsAnError) {
  std::string decisions;
  for (int i = 0; i < 9; ++i) decisions += fmt::format("ManyOutputs.c{} = PrebakeTex\n", i);
  const fs::path path = writeDecisions("many_outputs", decisions);
  ASSERT_TRUE(loadScene(planeScene("many_outputs.spire", "ManyOutputs", "{}")));
  renderer_ = std::make_unique<SceneRenderer>(ctx(), *scene_, *diags_);
  auto programs = renderer_->compile(path);
  ASSERT_TRUE(programs) << programs.error().message;
  const auto prepared = renderer_->prepare(*programs);
  ASSERT_FALSE(prepared);
  EXPECT_NE(prepared.error().message.find("the PrebakeTex kernel writes 9 textures, but this device renders at most"),
            std::string::npos)
      << prepared.error().message;
}

// The frame-pass scene: FramePasses retargeted to `pipeline`.
std::string framePassScene(const std::string& pipeline, const std::string& file) {
  std::string scene = planeScene("frame_passes.spire", "FramePasses", R"({"tint": [0.9, 0.5, 0.2]})");
  scene.replace(scene.find(R"("mesh": "plane")"), 0,
                fmt::format(R"("pipeline": {{"name": "{}", "source": "../../../pipelines/{}"}}, )", pipeline, file));
  return scene;
}

// The fraction of pixels covered in both images whose RGB differ by at most `tolerance`.
double matchingFraction(const Capture& a, const Capture& b, float tolerance) {
  size_t both = 0;
  size_t matching = 0;
  for (size_t i = 0; i < a.coverage.size(); ++i) {
    if (!a.coverage[i] || !b.coverage[i]) continue;
    ++both;
    bool same = true;
    for (size_t c = 0; c < 3; ++c)
      same = same && std::abs(a.color.rgba[i * 4 + c] - b.color.rgba[i * 4 + c]) <= tolerance;
    matching += same ? 1 : 0;
  }
  return both == 0 ? 0.0 : static_cast<double>(matching) / static_cast<double>(both);
}

class FramePassTest : public testing::RendererTest {};

// Multi-rate shading: LowResFragment runs at half the width and height, and
// Fragment reads its results by screen position. A constant is the same
// everywhere but at the silhouette; a UV ramp is close everywhere.
TEST_F(FramePassTest, LowResFragmentShadesAQuarterOfThePixelsAndFragmentReadsThem) {
  const std::string scene = framePassScene("MultiRatePipeline", "multi_rate.spire");
  const auto reference = renderWith(scene, "multirate_reference", "");
  ASSERT_TRUE(reference);
  EXPECT_TRUE(reference->prepared.items.at(0).passes.empty()) << "no LowResFragment kernel, no pass";

  const auto constant = renderWith(scene, "multirate_tinted", "FramePasses.tinted = LowResFragment\n");
  ASSERT_TRUE(constant);
  ASSERT_EQ(constant->prepared.items.at(0).passes.size(), 1U);
  const FramePass& pass = *constant->prepared.items[0].passes[0];
  EXPECT_EQ(pass.world(), "LowResFragment");
  EXPECT_EQ(pass.extent().width, 48U);
  EXPECT_EQ(pass.extent().height, 32U);
  EXPECT_EQ(constant->capture.coverage, reference->capture.coverage);
  // RGBA16F holds 0.72 to within 2.5e-4; the silhouette blends with the clear color.
  EXPECT_GT(matchingFraction(reference->capture, constant->capture, 1e-3F), 0.8);

  const auto ramp = renderWith(scene, "multirate_ramp", "FramePasses.ramp = LowResFragment\n");
  ASSERT_TRUE(ramp);
  const measure::ImageError error = compare(reference->capture, ramp->capture);
  EXPECT_LT(error.rmse, 0.02);
  EXPECT_GT(error.rmse, 1e-6) << "resampled at half resolution, the ramp cannot be exact";
  expectGolden(ramp->capture, "frame_pass_multirate");

  // A vertex bake's records reach the low-resolution pass as they reach Vertex.
  const auto fromBake = renderWith(scene, "multirate_from_bake",
                                   "FramePasses.tinted = PrebakeVertex\nFramePasses.ramp = LowResFragment\n");
  ASSERT_TRUE(fromBake);
  EXPECT_TRUE(readsVaryingFrom(fromBake->programs.at(0), "LowResFragment", "LowResVertex"));
  const KernelProgram* lowResVertex = fromBake->programs[0].kernel("LowResVertex");
  ASSERT_NE(lowResVertex, nullptr);
  EXPECT_TRUE(std::any_of(lowResVertex->inputs.begin(), lowResVertex->inputs.end(), [](const KernelInput& input) {
    return input.kind == InputKind::BufferMember && input.from == "PrebakeVertex";
  }));
  EXPECT_LT(compare(ramp->capture, fromBake->capture).maxError, 1e-3);
}

// Object-space shading: ObjSpaceFrag renders the mesh in UV space each
// frame, and Fragment samples it at vert_uv, as it would a texture bake.
TEST_F(FramePassTest, ObjSpaceFragRendersInUvSpaceEachFrameAndFragmentSamplesIt) {
  const std::string scene = framePassScene("ObjectSpacePipeline", "object_space.spire");
  const auto reference = renderWith(scene, "objspace_reference", "");
  ASSERT_TRUE(reference);
  const auto ramp = renderWith(scene, "objspace_ramp", "FramePasses.ramp = ObjSpaceFrag\n");
  ASSERT_TRUE(ramp);
  ASSERT_EQ(ramp->prepared.items.at(0).passes.size(), 1U);
  EXPECT_EQ(ramp->prepared.items[0].passes[0]->world(), "ObjSpaceFrag");
  EXPECT_EQ(ramp->prepared.items[0].passes[0]->extent().width, 512U);
  EXPECT_TRUE(ramp->prepared.bakes.empty()) << "an object-space pass is not a load-time bake";
  EXPECT_EQ(ramp->capture.coverage, reference->capture.coverage);
  EXPECT_LT(compare(reference->capture, ramp->capture).rmse, 5e-3);
  expectGolden(ramp->capture, "frame_pass_objspace");
}

// The object-space pass runs every frame with that frame's values: a
// component of the camera position shaded in ObjSpaceFrag follows the camera
// exactly as it does shaded per fragment.
TEST_F(FramePassTest, ObjSpaceFragSeesEachFramesCamera) {
  std::string scene = framePassScene("ObjectSpacePipeline", "object_space.spire");
  scene.replace(scene.find(R"("FramePasses")"), 13, R"("FramePassesEye")");
  std::string moved = scene;
  moved.replace(moved.find("[0, 2.2, 0.01]"), 14, "[0.3, 2.1, 0.2]");
  std::vector<std::array<double, 4>> means;
  for (const std::string* s : {&scene, &moved}) {
    const auto perFragment = renderWith(*s, "eye_fragment", "FramePassesEye.eye = Fragment\n");
    const auto objectSpace = renderWith(*s, "eye_objspace", "FramePassesEye.eye = ObjSpaceFrag\n");
    ASSERT_TRUE(perFragment && objectSpace);
    ASSERT_EQ(objectSpace->prepared.items.at(0).passes.size(), 1U);
    EXPECT_LT(compare(perFragment->capture, objectSpace->capture).maxError, 1e-3);
    means.push_back(coveredMean(objectSpace->capture));
  }
  EXPECT_GT(std::abs(means[0][0] - means[1][0]) + std::abs(means[0][2] - means[1][2]), 0.05)
      << "the two cameras should give different colors";
}

// Stereo: `scene` with both eyes (0.4 apart) side by side.
std::string stereoScene(std::string scene, bool shareObjectSpace) {
  scene.replace(scene.find(R"("camera": {)") + 11, 0,
                fmt::format(R"("stereo": {{"eyeSeparation": 0.4, "shareObjectSpace": {}}}, )", shareObjectSpace));
  return scene;
}

// `scene` seen from one eye: the camera above the plane moved along x (its
// right vector) by `dx`, target included.
std::string monoEye(std::string scene, float dx) {
  const auto replace = [&](const std::string& from, const std::string& to) {
    scene.replace(scene.find(from), from.size(), to);
  };
  replace("[0, 2.2, 0.01]", fmt::format("[{}, 2.2, 0.01]", dx));
  replace(R"("target": [0, 0, 0])", fmt::format(R"("target": [{}, 0, 0])", dx));
  return scene;
}

// The left (0) or right (1) half of a side-by-side capture.
Capture half(const Capture& stereo, int eye) {
  Capture out;
  const uint32_t width = stereo.color.width / 2;
  out.color.width = width;
  out.color.height = stereo.color.height;
  for (uint32_t y = 0; y < stereo.color.height; ++y) {
    const size_t row = size_t{y} * stereo.color.width + size_t{width} * static_cast<size_t>(eye);
    out.color.rgba.insert(out.color.rgba.end(), stereo.color.rgba.begin() + static_cast<std::ptrdiff_t>(row * 4),
                          stereo.color.rgba.begin() + static_cast<std::ptrdiff_t>((row + width) * 4));
    out.coverage.insert(out.coverage.end(), stereo.coverage.begin() + static_cast<std::ptrdiff_t>(row),
                        stereo.coverage.begin() + static_cast<std::ptrdiff_t>(row + width));
  }
  return out;
}

// Each half of a stereo image is that eye's own frame, and the object-space
// pass runs once for both eyes (from the centre camera) or once per eye.
TEST_F(FramePassTest, StereoDrawsEachEyeAndSharesObjectSpaceWork) {
  std::string scene = framePassScene("ObjectSpacePipeline", "object_space.spire");
  scene.replace(scene.find(R"("FramePasses")"), 13, R"("FramePassesEye")");
  const std::string decisions = "FramePassesEye.eye = ObjSpaceFrag\n";
  const auto left = renderWith(monoEye(scene, -0.2F), "stereo_left", decisions);
  const auto right = renderWith(monoEye(scene, 0.2F), "stereo_right", decisions);
  const auto centre = renderWith(scene, "stereo_centre", decisions);
  const auto perEye = renderWith(stereoScene(scene, false), "stereo_per_eye", decisions);
  const auto shared = renderWith(stereoScene(scene, true), "stereo_shared", decisions);
  ASSERT_TRUE(left && right && centre && perEye && shared);
  ASSERT_EQ(perEye->capture.color.width, 192U);
  ASSERT_EQ(perEye->capture.coverage.size(), 192U * 64U);
  // Per eye, each half is exactly that eye's frame.
  EXPECT_LT(compare(left->capture, half(perEye->capture, 0)).maxError, 1e-6);
  EXPECT_LT(compare(right->capture, half(perEye->capture, 1)).maxError, 1e-6);
  EXPECT_NE(left->capture.coverage, right->capture.coverage) << "the eyes should see the plane from two places";
  // Shared, the eyes keep their own geometry but sample the centre camera's
  // object-space result.
  EXPECT_EQ(half(shared->capture, 0).coverage, left->capture.coverage);
  const auto centreColor = coveredMean(centre->capture);
  for (int eye = 0; eye < 2; ++eye) {
    const auto mean = coveredMean(half(shared->capture, eye));
    for (size_t c = 0; c < 3; ++c) EXPECT_NEAR(mean[c], centreColor[c], 1e-3) << "eye " << eye << " channel " << c;
  }
  EXPECT_GT(compare(left->capture, half(shared->capture, 0)).maxError, 1e-2);
  expectGolden(shared->capture, "frame_pass_stereo_shared");
}

}  // namespace
}  // namespace spire::engine
