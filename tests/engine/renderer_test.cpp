// End-to-end tests of the renderer (engine-demo/renderer) on the device the
// loader finds (lavapipe on CI) with validation on: scenes the tests write
// themselves, rendered through every world the engine implements. Each image
// test checks its content independently (a flat color's exact value, a bake
// against the unbaked variant) as well as against a golden PNG, so neither a
// black image nor a drifting golden can pass.
// The fixture is renderer_fixture.h.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <glm/common.hpp>
#include <glm/gtc/packing.hpp>

#include <stb/stb_image_write.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <set>
#include <sstream>

#include "driver/spirec.h"
#include "engine/renderer_fixture.h"
#include "measure/image_metrics.h"
#include "renderer/bake_analysis.h"
#include "renderer/scene_renderer.h"
#include "renderer/view_error.h"
#include "scene/temp_dir.h"
#include "scene/texture.h"
#include "support/diagnostic_renderer.h"

namespace spire::engine {
namespace {

namespace fs = std::filesystem;
using testing::kDataDir;
using testing::planeScene;
using testing::RendererTest;

TEST_F(RendererTest, FlatPlaneHasExactlyItsMaterialColor) {
  const auto rendered =
      render(planeScene("flat_plane.spire", "FlatPlane", R"({"color": [0.2, 0.4, 0.6, 1.0]})"), std::nullopt);
  ASSERT_TRUE(rendered);
  const double fraction = coveredFraction(rendered->capture);
  EXPECT_GT(fraction, 0.3);
  EXPECT_LT(fraction, 0.9);  // the black background is visible around the plane
  const auto mean = coveredMean(rendered->capture);
  EXPECT_NEAR(mean[0], 0.2, 1e-6);
  EXPECT_NEAR(mean[1], 0.4, 1e-6);
  EXPECT_NEAR(mean[2], 0.6, 1e-6);
  EXPECT_NEAR(mean[3], 1.0, 1e-6);
  expectGolden(rendered->capture, "flat_plane");
  EXPECT_TRUE(rendered->prepared.bakes.empty());
}

// Back faces are culled: a plane seen from below is not drawn unless the
// instance is double-sided, and then it shows its one color from below too.
// A closed sphere looks the same either way, so culling dropped only faces
// the depth test would have hidden, and the sphere's winding is right.
TEST_F(RendererTest, BackFacesAreCulledUnlessDoubleSided) {
  const std::string material = R"({"color": [0.2, 0.4, 0.6, 1.0]})";
  const auto fromBelow = [&](const std::string& instanceExtra) {
    std::string json = planeScene("flat_plane.spire", "FlatPlane", material + instanceExtra);
    const std::string above = R"("position": [0, 2.2, 0.01])";
    json.replace(json.find(above), above.size(), R"("position": [0, -2.2, 0.01])");
    return render(json, std::nullopt);
  };
  const auto culled = fromBelow("");
  ASSERT_TRUE(culled);
  EXPECT_EQ(coveredFraction(culled->capture), 0.0);
  const auto drawn = fromBelow(R"(, "doubleSided": true)");
  ASSERT_TRUE(drawn);
  EXPECT_GT(coveredFraction(drawn->capture), 0.3);
  EXPECT_NEAR(coveredMean(drawn->capture)[2], 0.6, 1e-6);

  const auto sphere = [&](const std::string& instanceExtra) {
    std::string json = planeScene("flat_plane.spire", "FlatPlane", material + instanceExtra);
    const std::string plane = R"("mesh": "plane")";
    json.replace(json.find(plane), plane.size(), R"("mesh": "ball")");
    return render(json, std::nullopt);
  };
  const auto closed = sphere("");
  const auto bothSides = sphere(R"(, "doubleSided": true)");
  ASSERT_TRUE(closed && bothSides);
  EXPECT_GT(coveredFraction(closed->capture), 0.3);
  EXPECT_EQ(closed->capture.coverage, bothSides->capture.coverage);
  EXPECT_EQ(closed->capture.color.rgba, bothSides->capture.color.rgba);
}

// The baked texture is sampled where the Fragment variant samples the source
// texture directly, so the two differ by resampling: the error must shrink as
// the bake resolution grows and stay within a bound proportional to the
// bake's texel size.
TEST_F(RendererTest, PrebakeTexMatchesFragmentWithinTexelTolerance) {
  const std::string scene = planeScene("tex_bake.spire", "TexBake", R"({"colorMap": "noise"})");
  const auto reference = render(scene, "tex_bake_fragment.decisions");
  ASSERT_TRUE(reference);
  EXPECT_TRUE(reference->prepared.bakes.empty());
  expectGolden(reference->capture, "tex_bake_fragment");
  double previous = std::numeric_limits<double>::infinity();
  for (const uint32_t size : {16U, 64U, 256U}) {
    TextureBakeOptions options;
    options.defaultSize = size;
    const auto baked = render(scene, "tex_bake_prebake.decisions", options);
    ASSERT_TRUE(baked);
    ASSERT_EQ(baked->prepared.bakes.size(), 1U);
    EXPECT_EQ(baked->prepared.bakes[0].world, "PrebakeTex");
    const measure::ImageError error = compare(reference->capture, baked->capture);
    EXPECT_EQ(error.nanPixels + error.infPixels, 0U);
    // The noise texture has 32 texels; a bake of `size` texels moves each
    // lookup by at most half a bake texel, and the texture's value changes by
    // well under 1 per source texel.
    EXPECT_LT(error.rmse, 8.0 / size) << "bake size " << size;
    EXPECT_LT(error.rmse, previous) << "bake size " << size;
    previous = error.rmse;
  }
}

// What a world is comes from its [Role], not its name: EnginePipeline with
// every world renamed and reordered renders exactly what it renders, baked
// and unbaked.
TEST_F(RendererTest, RenamedWorldsRenderAsTheirRoles) {
  const std::string original = planeScene("tex_bake.spire", "TexBake", R"({"colorMap": "noise"})");
  const std::string renamed = planeScene("renamed_worlds.spire", "TexBakeRenamed", R"({"colorMap": "noise"})");
  for (const auto& [ours, theirs] : {std::pair{"tex_bake_fragment.decisions", "renamed_worlds_fragment.decisions"},
                                     std::pair{"tex_bake_prebake.decisions", "renamed_worlds_prebake.decisions"}}) {
    SCOPED_TRACE(theirs);
    const auto reference = render(original, fs::path(ours));
    ASSERT_TRUE(reference);
    const auto test = render(renamed, fs::path(theirs));
    ASSERT_TRUE(test);
    EXPECT_EQ(test->prepared.bakes.size(), reference->prepared.bakes.size());
    if (!test->prepared.bakes.empty()) {
      EXPECT_EQ(test->prepared.bakes[0].world, "TexelBake");
    }
    EXPECT_GT(coveredFraction(test->capture), 0.2);
    EXPECT_EQ(compare(reference->capture, test->capture).maxError, 0.0);
  }
}

TEST_F(RendererTest, AnUnknownRoleIsAnErrorListingTheRoles) {
  ASSERT_TRUE(loadScene(planeScene("unknown_role.spire", "TexBakeRenamed", R"({"colorMap": "noise"})")));
  renderer_ = std::make_unique<SceneRenderer>(ctx(), *scene_, *diags_);
  const auto programs = renderer_->compile(std::nullopt);
  ASSERT_FALSE(programs);
  const std::string& message = programs.error().message;
  EXPECT_NE(message.find("world 'Pixel' has [Role: \"pixel\"], which this engine does not implement"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("prebakeTexture (rasterized in UV space at load into textures)"), std::string::npos)
      << message;
}

// vert_tangent may be declared vec3 as well as vec4: the engine binds the
// same data with the format the declaration asks for.
TEST_F(RendererTest, TangentsMayBeDeclaredVec3OrVec4) {
  std::string vec4Scene = planeScene("tangent_types.spire", "TangentVec4", "{}");
  std::string vec3Scene = planeScene("tangent_types.spire", "TangentVec3", "{}");
  for (std::string* scene : {&vec4Scene, &vec3Scene}) {
    const size_t at = scene->find(R"({"mesh": "plane")");
    ASSERT_NE(at, std::string::npos);
    scene->replace(at, 16, R"({"mesh": "ball")");
  }
  const auto reference = render(vec4Scene, std::nullopt);
  ASSERT_TRUE(reference);
  const auto test = render(vec3Scene, std::nullopt);
  ASSERT_TRUE(test);
  EXPECT_GT(coveredFraction(test->capture), 0.2);
  EXPECT_EQ(compare(reference->capture, test->capture).maxError, 0.0);
  // The tangents of a sphere vary, so the comparison is not of one colour.
  std::set<std::array<float, 3>> colors;
  for (size_t i = 0; i < test->capture.coverage.size(); ++i) {
    if (!test->capture.coverage[i]) continue;
    const float* rgba = &test->capture.color.rgba[i * 4];
    colors.insert({rgba[0], rgba[1], rgba[2]});
  }
  EXPECT_GT(colors.size(), 50U);
}

// A scene binds any numeric uniform input to a value the engine supplies
// every frame, by the engine value's name: a shader's own names then follow
// the camera like the engine's, from every view.
TEST_F(RendererTest, InputsBoundToEngineValuesFollowTheCamera) {
  const auto twoViews = [](std::string scene) {
    const std::string one = R"("views": [{"position": [0, 2.2, 0.01], "target": [0, 0, 0]}])";
    scene.replace(scene.find(one), one.size(),
                  R"("views": [{"position": [0, 2.2, 0.01], "target": [0, 0, 0]},
                               {"position": [0.6, 3.0, 0.4], "target": [0, 0, 0]}])");
    return scene;
  };
  // Every view of `json`, rendered by one renderer.
  const auto renderViews = [&](const std::string& json) {
    std::vector<Capture> captures;
    const auto rendered = render(json, std::nullopt);
    if (!rendered) return captures;
    for (const scene::CameraView& view : scene_->camera.views) {
      auto capture = renderer_->capture(rendered->prepared, view);
      EXPECT_TRUE(capture) << capture.error().message;
      if (capture) captures.push_back(std::move(capture).value());
    }
    return captures;
  };
  const std::vector<Capture> own = renderViews(twoViews(planeScene(
      "engine_values.spire", "OwnNames",
      R"({"color": [0.2, 0.4, 0.6, 1], "viewProjectionModel": {"engine": "matMVP"}, "eye": {"engine": "cameraPos"}})")));
  const std::vector<Capture> engine =
      renderViews(twoViews(planeScene("flat_plane.spire", "FlatPlane", R"({"color": [0.2, 0.4, 0.6, 1]})")));
  ASSERT_EQ(own.size(), 2U);
  ASSERT_EQ(engine.size(), 2U);
  EXPECT_NE(engine[0].coverage, engine[1].coverage);  // the views differ
  for (size_t v = 0; v < 2; ++v) {
    SCOPED_TRACE(v);
    EXPECT_EQ(own[v].coverage, engine[v].coverage);  // the matrix is the engine's, for this view
    const double factor = std::min((v == 0 ? 2.2 : 3.0) / 4.0, 1.0);
    const auto mean = coveredMean(own[v]);
    EXPECT_NEAR(mean[0], 0.2 * factor, 1e-5);
    EXPECT_NEAR(mean[2], 0.6 * factor, 1e-5);
  }
}

TEST_F(RendererTest, AnUnknownEngineValueIsAnErrorListingTheValues) {
  ASSERT_TRUE(loadScene(
      planeScene("engine_values.spire", "OwnNames",
                 R"({"color": [1, 1, 1, 1], "viewProjectionModel": {"engine": "matVP"}, "eye": {"engine": "time"}})")));
  renderer_ = std::make_unique<SceneRenderer>(ctx(), *scene_, *diags_);
  auto programs = renderer_->compile(std::nullopt);
  ASSERT_TRUE(programs) << programs.error().message;
  EXPECT_FALSE(renderer_->prepare(*programs));
  const std::string text = renderDiagnostics(*sources_, *diags_, DiagnosticFormat::Text);
  EXPECT_NE(text.find("'viewProjectionModel' is bound to the engine value 'matVP', which the engine does not supply; "
                      "it supplies matMVP"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("'eye' is a vec3, but the engine value 'time' is a float"), std::string::npos) << text;
}

// A renderer made from another shares its textures (it sees them before it
// builds any) but bakes with its own options.
TEST_F(RendererTest, ARendererWithOtherBakeOptionsSharesTheScenesTextures) {
  const auto first =
      render(planeScene("tex_bake.spire", "TexBake", R"({"colorMap": "noise"})"), "tex_bake_prebake.decisions");
  ASSERT_TRUE(first);
  ASSERT_EQ(renderer_->textureCount(), 1U);
  TextureBakeOptions options;
  options.defaultSize = 16;
  SceneRenderer sharing(*renderer_, *diags_, options);
  EXPECT_EQ(sharing.textureCount(), 1U);
  auto programs = sharing.compile(kDataDir / "tex_bake_prebake.decisions");
  ASSERT_TRUE(programs) << programs.error().message;
  auto prepared = sharing.prepare(*programs);
  ASSERT_TRUE(prepared) << prepared.error().message;
  auto capture = sharing.capture(*prepared, scene_->camera.views.front());
  ASSERT_TRUE(capture);
  EXPECT_EQ(renderer_->textureCount(), 1U);
  ASSERT_EQ(prepared->bakes.size(), 1U);
  EXPECT_EQ(sharing.bakeCount(), 1U);
  // The coarser bake gives a different image of the same texture.
  const measure::ImageError error = compare(first->capture, *capture);
  EXPECT_GT(error.rmse, 0.0);
  EXPECT_LT(error.rmse, 8.0 / 16);
}

TEST_F(RendererTest, PrebakeUniformEqualsFragmentForAConstantInput) {
  const std::string scene = planeScene("uniform_bake.spire", "UniformBake", R"({"baseColor": [0.3, 0.5, 0.7, 1.0]})");
  const auto fragment = render(scene, "uniform_bake_fragment.decisions");
  ASSERT_TRUE(fragment);
  const auto prebaked = render(scene, "uniform_bake_prebake.decisions");
  ASSERT_TRUE(prebaked);
  ASSERT_EQ(prebaked->prepared.bakes.size(), 1U);
  EXPECT_EQ(prebaked->prepared.bakes[0].world, "PrebakeUniform");
  const measure::ImageError error = compare(fragment->capture, prebaked->capture);
  EXPECT_LT(error.maxError, 1e-6);
  const auto mean = coveredMean(prebaked->capture);
  EXPECT_NEAR(mean[0], 0.3 * 0.5 + 0.25, 1e-6);
  EXPECT_NEAR(mean[1], 0.5 * 0.5 + 0.25, 1e-6);
  EXPECT_NEAR(mean[2], 0.7 * 0.5 + 0.25, 1e-6);
  expectGolden(prebaked->capture, "uniform_bake");
}

// A per-object value stands for the fragments it replaces, which cover the
// surface by area: the uniform bake averages over the surface, not over
// wherever the vertices happen to be.
TEST_F(RendererTest, PrebakeUniformAveragesOverTheSurface) {
  const auto prebaked = render(planeScene("surface_mean.spire", "SurfaceMean", "{}"), "surface_mean_prebake.decisions");
  ASSERT_TRUE(prebaked);
  ASSERT_EQ(prebaked->prepared.bakes.size(), 1U);
  EXPECT_EQ(prebaked->prepared.bakes[0].world, "PrebakeUniform");
  const auto mean = coveredMean(prebaked->capture);
  EXPECT_NEAR(mean[0], 1.0 / 3.0, 0.004);  // the vertex mean would be 0.375
}

// A per-vertex value computed in a compute bake and read back as vertex data
// interpolates exactly like the same value computed in the vertex shader.
TEST_F(RendererTest, PrebakeVertexEqualsVertex) {
  std::string scene = planeScene("vertex_bake.spire", "VertexBake", "{}");
  scene.replace(scene.find("\"mesh\": \"plane\""), 15, "\"mesh\": \"ball\"");
  const auto vertex = render(scene, "vertex_bake_vertex.decisions");
  ASSERT_TRUE(vertex);
  const auto prebaked = render(scene, "vertex_bake_prebake.decisions");
  ASSERT_TRUE(prebaked);
  ASSERT_EQ(prebaked->prepared.bakes.size(), 1U);
  EXPECT_EQ(prebaked->prepared.bakes[0].world, "PrebakeVertex");
  EXPECT_GT(coveredFraction(prebaked->capture), 0.2);
  const measure::ImageError error = compare(vertex->capture, prebaked->capture);
  EXPECT_LT(error.maxError, 1e-5);
  expectGolden(prebaked->capture, "vertex_bake");
}

// Two instances with the same mesh, material and kernel share one bake.
TEST_F(RendererTest, IdenticalBakesRunOnce) {
  const auto rendered = bakeTwoPlanes("checker");
  ASSERT_TRUE(rendered);
  ASSERT_EQ(rendered->prepared.bakes.size(), 2U);
  EXPECT_FALSE(rendered->prepared.bakes[0].reused);
  EXPECT_TRUE(rendered->prepared.bakes[1].reused);
  EXPECT_EQ(renderer_->bakeCount(), 1U);
}

// Bakes of one kernel with different inputs are different results, but
// share one pipeline, so lavapipe compiles the bake kernel once (a terrain
// in tiles bakes the same kernel on every tile's mesh).
TEST_F(RendererTest, BakesOfOneKernelShareItsPipeline) {
  const auto rendered = bakeTwoPlanes("noise");
  ASSERT_TRUE(rendered);
  ASSERT_EQ(rendered->prepared.bakes.size(), 2U);
  EXPECT_FALSE(rendered->prepared.bakes[1].reused);
  EXPECT_EQ(renderer_->bakeCount(), 2U);
  EXPECT_EQ(renderer_->bakePipelineCounts().created, 1U);
  EXPECT_EQ(renderer_->bakePipelineCounts().reused, 1U);
}

// spirec's output directory (the file path) renders exactly what the
// in-process compiler library (the library path) renders.
TEST_F(RendererTest, FilePathMatchesLibraryPath) {
  const fs::path out = fs::temp_directory_path() / ("spire_renderer_file_path_" + std::to_string(::getpid()));
  fs::remove_all(out);
  std::ostringstream spirecOut;
  std::ostringstream spirecErr;
  ASSERT_EQ(runSpirec({(kDataDir / "tex_bake.spire").string(), "--decisions",
                       (kDataDir / "tex_bake_prebake.decisions").string(), "-o", out.string()},
                      spirecOut, spirecErr),
            0)
      << spirecErr.str();
  const std::string material = R"({"colorMap": "noise"})";
  const auto library = render(planeScene("tex_bake.spire", "TexBake", material), "tex_bake_prebake.decisions");
  ASSERT_TRUE(library);
  std::string fileScene = planeScene("tex_bake.spire", "TexBake", material);
  fileScene.replace(fileScene.find(R"("source": "tex_bake.spire", "shader": "TexBake")"),
                    std::string(R"("source": "tex_bake.spire", "shader": "TexBake")").size(),
                    "\"kernels\": \"" + (out / "TexBake").string() + "\"");
  const auto files = render(fileScene, std::nullopt);
  fs::remove_all(out);
  ASSERT_TRUE(files);
  EXPECT_EQ(files->capture.color.rgba, library->capture.color.rgba);
}

TEST_F(RendererTest, NonFiniteOutputIsCountedNotAveraged) {
  const std::string material = R"({"color": [0.2, 0.4, 0.6, 1.0]})";
  const auto reference = render(planeScene("flat_plane.spire", "FlatPlane", material), std::nullopt);
  ASSERT_TRUE(reference);
  const auto hazard = render(planeScene("nan_output.spire", "NanOutput", material), std::nullopt);
  ASSERT_TRUE(hazard);
  const measure::ImageError error = compare(reference->capture, hazard->capture);
  size_t covered = 0;
  for (uint8_t c : hazard->capture.coverage) covered += c;
  EXPECT_EQ(error.nanPixels, covered);
  EXPECT_TRUE(std::isinf(error.rmse));
  EXPECT_TRUE(std::isinf(error.maxError));
  EXPECT_EQ(error.psnr, 0.0);
}

// The tuner's in-memory decisions go through the compiler's one compile
// path: attributes are checked against the catalogue, and decisions that do
// not apply are reported back as skipped rather than refused.
// A prepare beside draws of scenes prepared before (spire-explore's worker)
// keeps the frame's target: kernels that need another number of color
// outputs are refused, fewer as well as more, and the target stays the one
// the earlier draws use. A tool's own prepare (TargetUse::Fit) makes a target
// that fits instead.
TEST_F(RendererTest, KeepingTheTargetRefusesKernelsWithAnotherNumberOfColorOutputs) {
  std::string json = planeScene("flat_plane.spire", "FlatPlane", R"({"color": [0.2, 0.4, 0.6, 1]})");
  json.replace(json.rfind("}]"), 2, R"(}, {"mesh": "plane", "source": "two_outputs.spire", "shader": "TwoColors",
      "material": {"color": [0.9, 0.5, 0.1, 1]}}])");
  ASSERT_TRUE(loadScene(json));
  SceneRenderer renderer(ctx(), *scene_, *diags_);
  auto programs = renderer.compile(std::nullopt);
  ASSERT_TRUE(programs) << programs.error().message << "\n" << programs.error().details;
  // Every draw of a frame writes the target's outputs, so each scene draws
  // one of the shaders, as instance 0: its plane and color suit both.
  const std::vector<VariantProgram> oneOutput{(*programs)[0]};
  const std::vector<VariantProgram> twoOutputs{(*programs)[1]};

  auto one = renderer.prepare(oneOutput);
  ASSERT_TRUE(one) << one.error().message;
  const vk::Image* frame = renderer.colorImage();
  ASSERT_EQ(renderer.target()->formats().colors.size(), 1U);
  auto refused = renderer.prepare(twoOutputs, SceneRenderer::TargetUse::Keep);
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.error().message.find("write 2 color output(s), and the target the scene's other draws use has 1"),
            std::string::npos)
      << refused.error().message;
  EXPECT_EQ(renderer.colorImage(), frame) << "the target the earlier draws use stays";
  EXPECT_TRUE(renderer.renderView(*one, scene_->camera.views.front(), 0.0F));

  auto two = renderer.prepare(twoOutputs, SceneRenderer::TargetUse::Fit);
  ASSERT_TRUE(two) << two.error().message;
  EXPECT_EQ(renderer.target()->formats().colors.size(), 2U);
  auto capture = renderer.capture(*two, scene_->camera.views.front());
  ASSERT_TRUE(capture) << capture.error().message;
  // Exports take their locations in name order: normalOut is color target 0,
  // the one captured and shown.
  EXPECT_NEAR(coveredMean(*capture)[0], 0.5, 1e-3);
  auto fewer = renderer.prepare(oneOutput, SceneRenderer::TargetUse::Keep);
  ASSERT_FALSE(fewer);
  EXPECT_NE(fewer.error().message.find("write 1 color output(s), and the target the scene's other draws use has 2"),
            std::string::npos)
      << fewer.error().message;
  EXPECT_EQ(renderer.target()->formats().colors.size(), 2U);
  EXPECT_TRUE(renderer.renderView(*two, scene_->camera.views.front(), 0.0F));
}

TEST_F(RendererTest, InMemoryDecisionsAreCheckedAndSkippedOnesReported) {
  std::string json = planeScene("normal_bake.spire", "NormalBake", R"({"colorMap": "noise"})");
  ASSERT_TRUE(loadScene(json));
  SceneRenderer renderer(ctx(), *scene_, *diags_);
  const std::map<std::string, std::string> decisions{{"bentNormal", "PrebakeTex"}};
  auto badFormat = renderer.compileVariant(0, decisions, nullptr, {{"bentNormal", {{"Format", "BC7"}}}});
  ASSERT_FALSE(badFormat);
  EXPECT_NE(badFormat.error().details.find("error[E5010]: 'bentNormal': [Format] takes one of"), std::string::npos)
      << badFormat.error().details;
  std::vector<std::string> skipped;
  auto program = renderer.compileVariant(0, {{"bentNormal", "PrebakeTex"}, {"noSuchComponent", "Fragment"}}, &skipped);
  ASSERT_TRUE(program) << program.error().message << program.error().details;
  EXPECT_EQ(skipped, std::vector<std::string>{"noSuchComponent"});
}

// Data-layout selection: a baked unit vector is recognized as one and stored
// as RGB10_A2 with the signed remap, which costs far less than storing it in
// 8 bits without the remap (which clamps every negative component to 0).
TEST_F(RendererTest, BakedUnitVectorsSelectRgb10A2WithSignedRemap) {
  std::string json = planeScene("normal_bake.spire", "NormalBake", R"({"colorMap": "noise"})");
  ASSERT_TRUE(loadScene(json));
  const std::map<std::string, std::string> decisions{{"bentNormal", "PrebakeTex"}};
  const auto renderWith = [&](SceneRenderer& renderer, const ShaderLibrary::Attributes& attributes,
                              const TextureBakeResult** baked) -> std::optional<Capture> {
    auto program = renderer.compileVariant(0, decisions, nullptr, attributes);
    EXPECT_TRUE(program) << program.error().message << program.error().details;
    if (!program) return std::nullopt;
    auto prepared = renderer.prepare({*program});
    EXPECT_TRUE(prepared) << prepared.error().message;
    if (!prepared) return std::nullopt;
    if (baked) *baked = prepared->textureBakes[0];
    auto capture = renderer.capture(*prepared, scene_->camera.views.front());
    EXPECT_TRUE(capture);
    if (!capture) return std::nullopt;
    return std::move(capture).value();
  };

  TextureBakeOptions analysisOptions;
  analysisOptions.defaultSize = 64;
  analysisOptions.forceFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
  SceneRenderer analysis(ctx(), *scene_, *diags_, analysisOptions);
  const TextureBakeResult* baked = nullptr;
  const auto reference = renderWith(analysis, {}, &baked);
  ASSERT_TRUE(reference && baked);
  auto program = analysis.compileVariant(0, decisions);
  ASSERT_TRUE(program);
  auto layouts = selectBakeLayouts(*program->kernel("PrebakeTex"), *baked);
  ASSERT_TRUE(layouts) << layouts.error().message;
  ASSERT_EQ(layouts->size(), 1U);
  EXPECT_EQ((*layouts)[0].component, "bentNormal");
  EXPECT_TRUE((*layouts)[0].unitVectors);
  EXPECT_LT((*layouts)[0].minimum[0], 0.0F);
  EXPECT_EQ((*layouts)[0].format, "RGB10_A2");
  EXPECT_TRUE((*layouts)[0].signedEncoding);

  TextureBakeOptions options;
  options.defaultSize = 64;
  SceneRenderer renderer(ctx(), *scene_, *diags_, options);
  const auto remapped =
      renderWith(renderer, {{"bentNormal", {{"Format", "RGB10_A2"}, {"Encoding", "signed"}}}}, nullptr);
  const auto clamped = renderWith(renderer, {{"bentNormal", {{"Format", "RGBA8"}}}}, nullptr);
  ASSERT_TRUE(remapped && clamped);
  const double remappedError = compare(*reference, *remapped).rmse;
  const double clampedError = compare(*reference, *clamped).rmse;
  EXPECT_LT(remappedError, 0.002);  // 10 bits over [-1, 1], halved again by the shader's * 0.5
  EXPECT_GT(clampedError, 10.0 * remappedError);
}

// Float textures reach the shader as they were stored: each format's texel
// comes back from the RGBA32F target although 8 bits could not hold it (an
// .hdr texel above 1, 0.123456 which is 31.48 8-bit steps), with validation
// on. A solid texture makes every sample that texel, however it is filtered.
TEST_F(RendererTest, FloatTexturesAreSampledAtTheirPrecision) {
  scene::testing::TempDir dir;
  const fs::path hdr = dir.path() / "bright.hdr";
  std::vector<float> texels;
  for (int i = 0; i < 4; ++i) texels.insert(texels.end(), {3.5F, 0.25F, 1.0F});  // exact in RGBE
  ASSERT_NE(stbi_write_hdr(hdr.c_str(), 2, 2, 3, texels.data()), 0);
  const float fine = 0.123456F;
  const auto solid = [](const char* format) {
    return fmt::format(R"({{"type": "solid", "size": 4, "color": [0.123456, 0.5, 0.75, 1], "format": "{}"}})", format);
  };
  const std::string textures =
      fmt::format(R"("textures": {{"sky": {{"type": "file", "file": "{}"}}, )"
                  R"("unorm16": {}, "half": {}, "float": {}, "red": {}, )",
                  hdr.string(), solid("RGBA16"), solid("RGBA16F"), solid("RGBA32F"), solid("R32F"));
  const struct {
    const char* texture;
    glm::vec4 expected;
  } cases[] = {
      {"sky", {3.5F, 0.25F, 1.0F, 1.0F}},
      {"unorm16", glm::round(glm::vec4(fine, 0.5F, 0.75F, 1.0F) * 65535.0F) / 65535.0F},
      {"half", glm::unpackHalf4x16(glm::packHalf4x16(glm::vec4(fine, 0.5F, 0.75F, 1.0F)))},
      {"float", {fine, 0.5F, 0.75F, 1.0F}},
      {"red", {fine, 0.0F, 0.0F, 1.0F}},
  };
  for (const auto& [texture, expected] : cases) {
    SCOPED_TRACE(texture);
    std::string json =
        planeScene("sampled_plane.spire", "SampledPlane", fmt::format(R"({{"colorMap": "{}"}})", texture));
    json.replace(json.find(R"("textures": {)"), std::string_view(R"("textures": {)").size(), textures);
    const auto rendered = render(json, std::nullopt);
    ASSERT_TRUE(rendered);
    EXPECT_GT(coveredFraction(rendered->capture), 0.3);
    const auto mean = coveredMean(rendered->capture);
    for (size_t c = 0; c < 4; ++c) EXPECT_NEAR(mean[c], expected[static_cast<glm::length_t>(c)], 1e-6) << c;
    // Not an 8-bit value: the texture kept more than 8 bits to the shader.
    EXPECT_GT(std::abs(mean[0] * 255.0 - std::round(mean[0] * 255.0)), 0.3);
  }
}

}  // namespace
}  // namespace spire::engine
