#include "scene/scene_file.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "support/diagnostic_renderer.h"
#include "support/file_io.h"

namespace spire::scene {
namespace {

namespace fs = std::filesystem;

struct Loaded {
  SourceManager sources;
  DiagnosticList diags{1000};
  std::optional<SceneFile> scene;
  std::string rendered;
};

std::unique_ptr<Loaded> parseScene(std::string text, const fs::path& directory = "scenes") {
  auto loaded = std::make_unique<Loaded>();
  loaded->scene = parseSceneFile("scene.json", std::move(text), directory, loaded->sources, loaded->diags);
  loaded->rendered = renderDiagnostics(loaded->sources, loaded->diags, DiagnosticFormat::Text);
  return loaded;
}

// A valid scene: `extra` top-level members, then a camera, a mesh "ground"
// and one instance of it, each unless the test leaves it out to replace it.
const char* const kCamera = R"("camera": {"views": [{"position": [0, 2, 5]}]})";
const char* const kMeshes = R"("meshes": {"ground": {"type": "plane"}})";
const char* const kInstances = R"("instances": [{"mesh": "ground", "source": "a.spire", "shader": "A"}])";

std::string scene(const std::string& extra, bool camera = true, bool meshes = true, bool instances = true) {
  std::vector<std::string> parts;
  if (!extra.empty()) parts.push_back(extra);
  if (camera) parts.emplace_back(kCamera);
  if (meshes) parts.emplace_back(kMeshes);
  if (instances) parts.emplace_back(kInstances);
  std::string text = "{";
  for (size_t i = 0; i < parts.size(); ++i) text += (i > 0 ? ", " : "") + parts[i];
  return text + "}";
}

std::string withInstance(const std::string& instance) {
  return scene(R"("textures": {"stone": {"type": "solid"}}, "instances": [)" + instance + "]", true, true, false);
}

// The only diagnostic's code and message.
void expectError(const std::string& text, DiagCode code, const std::string& message) {
  const auto loaded = parseScene(text);
  EXPECT_FALSE(loaded->scene.has_value()) << text;
  ASSERT_EQ(loaded->diags.all().size(), 1u) << text << "\n" << loaded->rendered;
  EXPECT_EQ(diagCodeInfo(loaded->diags.all()[0].code).name, diagCodeInfo(code).name) << loaded->rendered;
  EXPECT_EQ(loaded->diags.all()[0].message, message) << text;
}

TEST(SceneFile, TerrainExampleParses) {
  const fs::path examples = fs::path(SPIRE_SOURCE_DIR) / "examples";
  SourceManager sources;
  DiagnosticList diags;
  const std::optional<SceneFile> scene = loadSceneFile(examples / "scenes/terrain.json", sources, diags);
  ASSERT_TRUE(scene.has_value()) << renderDiagnostics(sources, diags, DiagnosticFormat::Text);
  EXPECT_EQ(diags.all().size(), 0u);
  EXPECT_EQ(scene->directory, examples / "scenes");
  EXPECT_EQ(scene->width, 640u);
  EXPECT_EQ(scene->height, 480u);
  EXPECT_EQ(scene->frames, 30u);
  EXPECT_EQ(scene->warmupFrames, 2u);
  ASSERT_EQ(scene->camera.views.size(), 3u);
  for (const CameraView& view : scene->camera.views) {
    EXPECT_GT(view.position.y, view.target.y + 2.0F) << "the views look down at the terrain";
  }
  EXPECT_NEAR(glm::length(scene->light.direction), 1.0F, 1e-6F);

  ASSERT_EQ(scene->meshes.size(), 1u);
  const MeshDesc& terrain = scene->meshes[0];
  EXPECT_EQ(terrain.kind, MeshKind::Terrain);
  EXPECT_EQ(terrain.size, 10.0F);
  EXPECT_EQ(terrain.resolution, 128u);
  EXPECT_EQ(terrain.height, 1.5F);
  EXPECT_EQ(scene->findMesh(terrain.name), &terrain);

  ASSERT_EQ(scene->instances.size(), 1u);
  const InstanceDesc& instance = scene->instances[0];
  EXPECT_EQ(instance.source, examples / "terrain.spire");
  EXPECT_TRUE(fs::exists(instance.source));
  EXPECT_EQ(instance.shader, "Terrain");
  EXPECT_FALSE(instance.kernels.has_value());
  EXPECT_EQ(scene->findMesh(instance.mesh), &terrain);

  std::vector<std::string> samplers;
  for (const MaterialBinding& binding : instance.material) {
    if (binding.texture) {
      samplers.push_back(binding.component);
      EXPECT_NE(scene->findTexture(*binding.texture), nullptr) << *binding.texture;
    } else if (binding.component == "shininess") {
      EXPECT_EQ(binding.numbers, std::vector<double>{32.0});
    } else {
      EXPECT_EQ(binding.component, "roughness");
      EXPECT_EQ(binding.numbers, std::vector<double>{0.4});
    }
  }
  EXPECT_EQ(samplers, (std::vector<std::string>{"mixMap", "albedoMap1", "albedoMap2", "normalMap1", "normalMap2"}));
  EXPECT_EQ(instance.material.size(), 7u);

  ASSERT_EQ(scene->textures.size(), 5u);
  for (const TextureDesc& texture : scene->textures) {
    EXPECT_TRUE(texture.kind == TextureKind::Noise || texture.kind == TextureKind::NormalMap) << texture.name;
  }

  ASSERT_EQ(scene->variants.size(), 3u);
  EXPECT_EQ(scene->variants[0].name, "full_quality");
  for (const VariantDesc& variant : scene->variants) {
    EXPECT_TRUE(fs::exists(variant.decisions)) << variant.decisions;
    EXPECT_EQ(variant.decisions.parent_path(), examples / "decisions");
  }
}

TEST(SceneFile, DefaultsFromTheHeader) {
  const auto loaded = parseScene(scene(""));
  ASSERT_TRUE(loaded->scene) << loaded->rendered;
  const SceneFile& s = *loaded->scene;
  const SceneFile defaults;
  EXPECT_EQ(s.width, defaults.width);
  EXPECT_EQ(s.height, defaults.height);
  EXPECT_EQ(s.frames, defaults.frames);
  EXPECT_EQ(s.warmupFrames, defaults.warmupFrames);
  EXPECT_EQ(s.clearColor, defaults.clearColor);
  EXPECT_EQ(s.camera.fovYDegrees, 45.0F);
  EXPECT_EQ(s.camera.up, glm::vec3(0.0F, 1.0F, 0.0F));
  EXPECT_EQ(s.camera.views[0].target, glm::vec3(0.0F));
  EXPECT_EQ(s.light.direction, glm::normalize(LightDesc{}.direction));
  EXPECT_EQ(s.light.color, glm::vec3(1.0F));
  EXPECT_EQ(s.meshes[0].kind, MeshKind::Plane);
  EXPECT_EQ(s.meshes[0].size, MeshDesc{}.size);
  EXPECT_EQ(s.instances[0].transform, glm::mat4(1.0F));
  EXPECT_FALSE(s.instances[0].decisions.has_value());
  EXPECT_EQ(s.instances[0].materialRange, s.instances[0].range);
  EXPECT_TRUE(s.variants.empty());
  EXPECT_TRUE(s.includePaths.empty());
}

TEST(SceneFile, IntegralNumbersAreIntegersAndColorsTakeAlpha) {
  const auto loaded = parseScene(scene(R"("frames": 10.0, "clearColor": [0.5, 0.25, 0, 0.5],
      "textures": {"tiles": {"type": "checker", "cells": 4, "color": [1, 0, 0], "color2": [0, 0, 1, 0.5]}})"));
  ASSERT_TRUE(loaded->scene) << loaded->rendered;
  EXPECT_EQ(loaded->scene->frames, 10u);
  EXPECT_EQ(loaded->scene->clearColor, glm::vec4(0.5F, 0.25F, 0.0F, 0.5F));
  const TextureDesc* tiles = loaded->scene->findTexture("tiles");
  ASSERT_NE(tiles, nullptr);
  EXPECT_EQ(tiles->color, glm::vec4(1.0F, 0.0F, 0.0F, 1.0F));
  EXPECT_EQ(tiles->color2, glm::vec4(0.0F, 0.0F, 1.0F, 0.5F));
  EXPECT_EQ(loaded->scene->findTexture("missing"), nullptr);
}

TEST(SceneFile, LookupTablesClampByDefault) {
  const auto loaded = parseScene(scene(R"("textures": {"lut": {"type": "ggxLut", "size": 128},
      "wrapped": {"type": "ggxLut", "address": "repeat"}, "tiles": {"type": "checker"}})"));
  ASSERT_TRUE(loaded->scene) << loaded->rendered;
  const TextureDesc* lut = loaded->scene->findTexture("lut");
  ASSERT_NE(lut, nullptr);
  EXPECT_EQ(lut->kind, TextureKind::GgxLut);
  EXPECT_EQ(lut->size, 128u);
  EXPECT_TRUE(lut->clamp);
  EXPECT_FALSE(loaded->scene->findTexture("wrapped")->clamp);
  EXPECT_FALSE(loaded->scene->findTexture("tiles")->clamp);
  expectError(scene(R"("textures": {"lut": {"type": "ggxLut", "seed": 2}})"), DiagCode::E7002,
              "key 'seed' does not apply to a ggxLut texture (its keys are 'type', 'size', 'address' and 'format')");
}

TEST(SceneFile, FormatPicksTheTexelFormatOfEveryTextureType) {
  const auto loaded = parseScene(scene(R"("textures": {"lut": {"type": "ggxLut", "format": "RGBA32F"},
      "sky": {"type": "file", "file": "sky.hdr", "format": "RGBA16F"}, "height": {"type": "noise", "format": "R32F"},
      "mask": {"type": "pack", "channels": ["height.r"], "format": "RGBA16"}, "tiles": {"type": "checker"},
      "plain": {"type": "solid", "format": "RGBA8"}})"));
  ASSERT_TRUE(loaded->scene) << loaded->rendered;
  EXPECT_EQ(loaded->scene->findTexture("lut")->format, PixelFormat::RGBA32F);
  EXPECT_EQ(loaded->scene->findTexture("sky")->format, PixelFormat::RGBA16F);
  EXPECT_EQ(loaded->scene->findTexture("height")->format, PixelFormat::R32F);
  EXPECT_EQ(loaded->scene->findTexture("mask")->format, PixelFormat::RGBA16);
  EXPECT_EQ(loaded->scene->findTexture("plain")->format, PixelFormat::RGBA8);
  // No "format": the source decides (texture.h), so none is recorded.
  EXPECT_FALSE(loaded->scene->findTexture("tiles")->format.has_value());
}

// An unknown format is reported at the value, with the caret under it and
// the nearest name or the list of names.
TEST(SceneFile, AnUnknownFormatIsAnErrorAtItsValue) {
  const std::string line = R"(  "sky": {"type": "file", "file": "sky.hdr", "format": "RGBA16f"})";
  const auto loaded = parseScene(scene("\"textures\": {\n" + line + "\n}"));
  EXPECT_FALSE(loaded->scene.has_value());
  ASSERT_EQ(loaded->diags.all().size(), 1U) << loaded->rendered;
  const size_t column = line.find("\"RGBA16f\"") + 1;
  const std::string expected = fmt::format(
      "scene.json:2:{}: error[E7004]: unknown texture format 'RGBA16f'; did you mean 'RGBA16F'?\n"
      " 2 | {}\n"
      "   | {}^~~~~~~~~\n",
      column, line, std::string(column - 1, ' '));
  EXPECT_EQ(loaded->rendered.substr(0, expected.size()), expected) << loaded->rendered;
  expectError(scene(R"("textures": {"t": {"type": "solid", "format": "XYZ"}})"), DiagCode::E7004,
              "unknown texture format 'XYZ' (expected 'RGBA8', 'RGBA16', 'RGBA16F', 'RGBA32F' or 'R32F')");
  expectError(scene(R"("textures": {"t": {"type": "solid", "format": 8}})"), DiagCode::E7003,
              "texture format must be a string, found a number");
}

TEST(SceneFile, PathsResolveAgainstTheSceneDirectory) {
  const auto loaded = parseScene(
      withInstance(R"({"mesh": "ground", "source": "../shaders/a.spire", "shader": "A", "decisions": "d/x.decisions",
                       "kernels": "/abs/out/A"})"),
      "work/scenes");
  ASSERT_TRUE(loaded->scene) << loaded->rendered;
  const InstanceDesc& instance = loaded->scene->instances[0];
  EXPECT_EQ(instance.source, fs::path("work/shaders/a.spire"));
  EXPECT_EQ(instance.decisions, fs::path("work/scenes/d/x.decisions"));
  EXPECT_EQ(instance.kernels, fs::path("/abs/out/A"));
  EXPECT_EQ(loaded->sources.text(instance.sourceRange), "\"../shaders/a.spire\"");
  EXPECT_EQ(loaded->sources.text(instance.shaderRange), "\"A\"");

  const auto included = parseScene(scene(R"("includePaths": ["lib", "/usr/share/spire"])"), "");
  ASSERT_TRUE(included->scene) << included->rendered;
  EXPECT_EQ(included->scene->includePaths, (std::vector<fs::path>{"lib", "/usr/share/spire"}));
}

TEST(SceneFile, PipelineRetargetsTheInstancesShader) {
  const auto loaded = parseScene(withInstance(
      R"({"mesh": "ground", "source": "a.spire", "shader": "A",
          "pipeline": {"name": "MultiRatePipeline", "source": "../pipelines/multi_rate.spire"}})"));
  ASSERT_TRUE(loaded->scene) << loaded->rendered;
  const InstanceDesc& instance = loaded->scene->instances[0];
  EXPECT_EQ(instance.pipeline, "MultiRatePipeline");
  EXPECT_EQ(instance.pipelineSource, fs::path("pipelines/multi_rate.spire"));
  const auto nameOnly = parseScene(withInstance(
      R"({"mesh": "ground", "source": "a.spire", "shader": "A", "pipeline": {"name": "MultiRatePipeline"}})"));
  ASSERT_TRUE(nameOnly->scene) << nameOnly->rendered;
  EXPECT_FALSE(nameOnly->scene->instances[0].pipelineSource);

  expectError(withInstance(
                  R"({"mesh": "ground", "source": "a.spire", "shader": "A", "pipeline": {"name": "P", "sourc": "p"}})"),
              DiagCode::E7002, "unknown key 'sourc' in 'pipeline'; did you mean 'source'?");
  expectError(withInstance(R"({"mesh": "ground", "source": "a.spire", "shader": "A", "pipeline": {}})"),
              DiagCode::E7005, "'pipeline' needs the 'name' of the pipeline");
  expectError(withInstance(R"({"mesh": "ground", "source": "a.spire", "shader": "A", "pipeline": "P"})"),
              DiagCode::E7003, "'pipeline' must be an object, found a string");
  expectError(withInstance(R"({"mesh": "ground", "kernels": "k", "pipeline": {"name": "P"}})"), DiagCode::E7005,
              "'pipeline' retargets a 'source' and 'shader', which this instance does not have");
}

TEST(SceneFile, StereoIsOptionalWithDefaults) {
  const auto mono = parseScene(withInstance(R"({"mesh": "ground", "kernels": "k"})"));
  ASSERT_TRUE(mono->scene) << mono->rendered;
  EXPECT_FALSE(mono->scene->camera.stereo);
  const auto stereo = parseScene(
      scene(R"("camera": {"stereo": {"shareObjectSpace": false}, "views": [{"position": [0, 2, 5]}]})", false));
  ASSERT_TRUE(stereo->scene) << stereo->rendered;
  ASSERT_TRUE(stereo->scene->camera.stereo);
  EXPECT_FLOAT_EQ(stereo->scene->camera.stereo->eyeSeparation, 0.064F);
  EXPECT_FALSE(stereo->scene->camera.stereo->shareObjectSpace);
  expectError(scene(R"("camera": {"stereo": {"eyeSeparation": 0}, "views": [{"position": [0, 2, 5]}]})", false),
              DiagCode::E7004, "'eyeSeparation' must be greater than 0, found 0");
  expectError(scene(R"("camera": {"stereo": {"separation": 1}, "views": [{"position": [0, 2, 5]}]})", false),
              DiagCode::E7002, "unknown key 'separation' in 'stereo'; did you mean 'eyeSeparation'?");
}

TEST(SceneFile, KernelsAloneNeedNoSource) {
  const auto loaded = parseScene(withInstance(R"({"mesh": "ground", "kernels": "out/Terrain"})"));
  ASSERT_TRUE(loaded->scene) << loaded->rendered;
  EXPECT_EQ(loaded->scene->instances[0].kernels, fs::path("scenes/out/Terrain"));
  EXPECT_TRUE(loaded->scene->instances[0].shader.empty());
}

TEST(SceneFile, TransformScalesThenRotatesXYZThenTranslates) {
  const auto loaded = parseScene(withInstance(
      R"({"mesh": "ground", "kernels": "k", "transform": {"translate": [0, 0, 1], "rotate": [0, 90, 0], "scale": 2}})"));
  ASSERT_TRUE(loaded->scene) << loaded->rendered;
  const glm::vec4 moved = loaded->scene->instances[0].transform * glm::vec4(1.0F, 0.0F, 0.0F, 1.0F);
  EXPECT_NEAR(moved.x, 0.0F, 1e-6F);
  EXPECT_NEAR(moved.y, 0.0F, 1e-6F);
  EXPECT_NEAR(moved.z, -1.0F, 1e-6F);  // (2, 0, 0) turned to (0, 0, -2), then moved by +1 in z

  const auto xThenY = parseScene(
      withInstance(R"({"mesh": "ground", "kernels": "k", "transform": {"rotate": [90, 90, 0], "scale": [1, 2, 3]}})"));
  ASSERT_TRUE(xThenY->scene) << xThenY->rendered;
  // (0, 1, 0) scaled to (0, 2, 0); X by 90 gives (0, 0, 2); then Y by 90 gives (2, 0, 0).
  const glm::vec4 up = xThenY->scene->instances[0].transform * glm::vec4(0.0F, 1.0F, 0.0F, 1.0F);
  EXPECT_NEAR(up.x, 2.0F, 1e-6F);
  EXPECT_NEAR(up.y, 0.0F, 1e-6F);
  EXPECT_NEAR(up.z, 0.0F, 1e-6F);
}

TEST(SceneFile, MaterialValues) {
  const auto loaded = parseScene(withInstance(
      R"({"mesh": "ground", "kernels": "k", "material": {"albedo": "stone", "gloss": 0.5, "tint": [1, 0.5, 0.25],
          "matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1], "eye": {"engine": "cameraPos"}}})"));
  ASSERT_TRUE(loaded->scene) << loaded->rendered;
  const std::vector<MaterialBinding>& material = loaded->scene->instances[0].material;
  ASSERT_EQ(material.size(), 5u);
  EXPECT_EQ(material[4].engineValue, "cameraPos");
  EXPECT_TRUE(material[4].numbers.empty());
  EXPECT_EQ(material[0].texture, "stone");
  EXPECT_TRUE(material[0].numbers.empty());
  EXPECT_EQ(loaded->sources.text(material[0].keyRange), "\"albedo\"");
  EXPECT_EQ(loaded->sources.text(material[0].valueRange), "\"stone\"");
  EXPECT_EQ(material[1].numbers, std::vector<double>{0.5});
  EXPECT_FALSE(material[1].texture.has_value());
  EXPECT_EQ(material[2].numbers, (std::vector<double>{1.0, 0.5, 0.25}));
  EXPECT_EQ(material[3].numbers.size(), 16u);
  EXPECT_NE(loaded->scene->instances[0].materialRange, loaded->scene->instances[0].range);
}

TEST(SceneFile, DoubleSidedIsLeftToTheMeshUnlessGiven) {
  const auto loaded = parseScene(withInstance(R"({"mesh": "ground", "kernels": "k"},
      {"mesh": "ground", "kernels": "k", "doubleSided": true},
      {"mesh": "ground", "kernels": "k", "doubleSided": false})"));
  ASSERT_TRUE(loaded->scene) << loaded->rendered;
  ASSERT_EQ(loaded->scene->instances.size(), 3u);
  EXPECT_EQ(loaded->scene->instances[0].doubleSided, std::nullopt);
  EXPECT_EQ(loaded->scene->instances[1].doubleSided, true);
  EXPECT_EQ(loaded->scene->instances[2].doubleSided, false);
  expectError(withInstance(R"({"mesh": "ground", "kernels": "k", "doubleSided": 1})"), DiagCode::E7003,
              "'doubleSided' must be a boolean, found a number");
}

TEST(SceneFile, PackTakesNamedChannelsOfOtherTextures) {
  const auto loaded = parseScene(scene(
      R"("textures": {"masks": {"type": "pack", "channels": ["my.wear.g", "dirt.a"], "address": "clamp"},
                      "my.wear": {"type": "noise"}, "dirt": {"type": "solid"}})"));
  ASSERT_TRUE(loaded->scene) << loaded->rendered;
  const TextureDesc* masks = loaded->scene->findTexture("masks");
  ASSERT_NE(masks, nullptr);
  EXPECT_EQ(masks->kind, TextureKind::Pack);
  EXPECT_TRUE(masks->clamp);
  ASSERT_EQ(masks->channels.size(), 2u);
  EXPECT_EQ(masks->channels[0].texture, "my.wear");
  EXPECT_EQ(masks->channels[0].channel, 1u);
  EXPECT_EQ(masks->channels[1].texture, "dirt");
  EXPECT_EQ(masks->channels[1].channel, 3u);
  EXPECT_EQ(loaded->sources.text(masks->channels[1].range), "\"dirt.a\"");

  expectError(scene(R"("textures": {"m": {"type": "pack"}})"), DiagCode::E7005, "pack texture 'm' has no 'channels'");
  expectError(scene(R"("textures": {"m": {"type": "pack", "channels": []}})"), DiagCode::E7003,
              "'channels' must be an array of 1 to 4 channels such as \"wear.r\", found an empty array");
  expectError(scene(R"("textures": {"m": {"type": "pack", "channels": ["t.r", "t.g", "t.b", "t.a", "t.r"]},
                                    "t": {"type": "solid"}})"),
              DiagCode::E7003,
              "'channels' must be an array of 1 to 4 channels such as \"wear.r\", found an array of 5 elements");
  expectError(scene(R"("textures": {"m": {"type": "pack", "channels": ["t.x"]}, "t": {"type": "solid"}})"),
              DiagCode::E7004,
              "channel 't.x' must be a texture name, a dot and one of r, g, b or a, such as \"wear.r\"");
  expectError(scene(R"("textures": {"m": {"type": "pack", "channels": ["t"]}, "t": {"type": "solid"}})"),
              DiagCode::E7004, "channel 't' must be a texture name, a dot and one of r, g, b or a, such as \"wear.r\"");
  expectError(scene(R"("textures": {"m": {"type": "pack", "channels": ["tt.r"]}, "t": {"type": "solid"}})"),
              DiagCode::E7006, "unknown texture 'tt'; did you mean 't'?");
  expectError(scene(R"("textures": {"m": {"type": "pack", "channels": ["n.r"]},
                                    "n": {"type": "pack", "channels": ["t.r"]}, "t": {"type": "solid"}})"),
              DiagCode::E7004,
              "pack texture 'm' takes a channel of 'n', another pack; name the textures that one packs instead");
  expectError(scene(R"("textures": {"m": {"type": "pack", "channels": ["t.r"], "size": 4}, "t": {"type": "solid"}})"),
              DiagCode::E7002,
              "key 'size' does not apply to a pack texture (its keys are 'type', 'channels', 'address' and 'format')");
}

TEST(SceneFile, LightDirectionIsNormalized) {
  const auto loaded = parseScene(scene(R"("light": {"direction": [0, 2, 0], "color": [0.5, 0.5, 0.5]})"));
  ASSERT_TRUE(loaded->scene) << loaded->rendered;
  EXPECT_EQ(loaded->scene->light.direction, glm::vec3(0.0F, 1.0F, 0.0F));
  EXPECT_EQ(loaded->scene->light.color, glm::vec3(0.5F));
}

TEST(SceneFile, UnknownKeysE7002) {
  expectError(scene(R"("resolutoin": [1, 1])"), DiagCode::E7002,
              "unknown key 'resolutoin' in the scene; did you mean 'resolution'?");
  expectError(scene(R"("camera": {"fov": 60, "views": [{"position": [0, 2, 5]}]})", false), DiagCode::E7002,
              "unknown key 'fov' in 'camera'; did you mean 'fovY'?");
  expectError(scene(R"("meshes": {"ground": {"type": "sphere", "height": 2}})", true, false), DiagCode::E7002,
              "key 'height' does not apply to a sphere mesh (its keys are 'type', 'radius', 'rings' and 'segments')");
  expectError(withInstance(R"({"mesh": "ground", "kernels": "k", "transform": {"rotation": [0, 0, 0]}})"),
              DiagCode::E7002, "unknown key 'rotation' in 'transform'; did you mean 'rotate'?");
  const auto loaded = parseScene(scene(R"("xyzzy": 1)"));
  ASSERT_EQ(loaded->diags.all().size(), 1u);
  EXPECT_EQ(loaded->diags.all()[0].message, "unknown key 'xyzzy' in the scene");
  ASSERT_EQ(loaded->diags.all()[0].notes.size(), 1u);
  EXPECT_EQ(loaded->diags.all()[0].notes[0].message,
            "expected one of 'resolution', 'frames', 'warmupFrames', 'clearColor', 'includePaths', 'camera', 'light', "
            "'meshes', 'textures', 'instances', 'variants' or 'lod'");
}

TEST(SceneFile, WrongTypesE7003) {
  expectError("[]", DiagCode::E7003, "a scene file must hold a JSON object, found an empty array");
  expectError(scene(R"("frames": 1.5)"), DiagCode::E7003, "'frames' must be an integer, found 1.5");
  expectError(scene(R"("frames": "10")"), DiagCode::E7003, "'frames' must be a number, found a string");
  expectError(scene(R"("resolution": [640])"), DiagCode::E7003,
              "'resolution' must be an array of 2 integers [width, height], found an array of 1 element");
  expectError(scene(R"("light": {"color": [1, 1, 1, 1]})"), DiagCode::E7003,
              "'color' must be an array of 3 numbers [r, g, b], found an array of 4 elements");
  expectError(scene(R"("camera": {"views": [{"position": [0, "2", 5]}]})", false), DiagCode::E7003,
              "each element of 'position' must be a number, found a string");
  expectError(scene(R"("camera": {"views": [[0, 2, 5]]})", false), DiagCode::E7003,
              "each element of 'views' must be an object, found an array of 3 elements");
  expectError(withInstance(R"({"mesh": "ground", "kernels": "k", "material": {"gloss": true}})"), DiagCode::E7003,
              "the material value of 'gloss' must be a texture name, a number, an array of 1 to 16 numbers or "
              "{\"engine\": NAME}, found a boolean");
  expectError(withInstance(R"({"mesh": "ground", "kernels": "k", "material": {"eye": {"engine": 3}}})"),
              DiagCode::E7003,
              "the material value of 'eye' as an object must be {\"engine\": NAME}, naming a value the engine "
              "supplies every frame");
  expectError(withInstance(R"({"mesh": "ground", "kernels": "k", "material": {"eye": {"engin": "cameraPos"}}})"),
              DiagCode::E7003,
              "the material value of 'eye' as an object must be {\"engine\": NAME}, naming a value the engine "
              "supplies every frame");
  expectError(withInstance(R"({"mesh": "ground", "kernels": "k", "material": {"gloss": []}})"), DiagCode::E7003,
              "the material value of 'gloss' must be a texture name, a number, an array of 1 to 16 numbers or "
              "{\"engine\": NAME}, found an empty array");
  expectError(withInstance(R"({"mesh": "ground", "kernels": "k", "material": {"m": [[1, 0], 2]}})"), DiagCode::E7003,
              "each element of the material value of 'm' must be a number, found an array of 2 elements");
  expectError(withInstance(R"({"mesh": "ground", "kernels": "k", "transform": {"scale": "big"}})"), DiagCode::E7003,
              "'scale' must be a number or an array of 3 numbers [x, y, z], found a string");
  expectError(scene(R"("includePaths": "lib")"), DiagCode::E7003, "'includePaths' must be an array, found a string");
}

TEST(SceneFile, OutOfRangeE7004) {
  expectError(scene(R"("resolution": [0, 480])"), DiagCode::E7004,
              "the width in 'resolution' must be between 1 and 8192, found 0");
  expectError(scene(R"("resolution": [640, 8193])"), DiagCode::E7004,
              "the height in 'resolution' must be between 1 and 8192, found 8193");
  expectError(scene(R"("frames": 0)"), DiagCode::E7004, "'frames' must be between 1 and 100000, found 0");
  expectError(scene(R"("warmupFrames": -1)"), DiagCode::E7004, "'warmupFrames' must be between 0 and 100000, found -1");
  expectError(scene(R"("clearColor": [0, 0, 1.5])"), DiagCode::E7004,
              "each element of 'clearColor' must be between 0 and 1, found 1.5");
  expectError(scene(R"("meshes": {"ground": {"type": "plane", "size": -10}})", true, false), DiagCode::E7004,
              "'size' must be greater than 0, found -10");
  expectError(scene(R"("meshes": {"ground": {"type": "sphear"}})", true, false), DiagCode::E7004,
              "unknown mesh type 'sphear'; did you mean 'sphere'?");
  expectError(scene(R"("meshes": {"ground": {"type": "cube"}})", true, false), DiagCode::E7004,
              "unknown mesh type 'cube' (expected 'terrain', 'sphere', 'plane', 'gltf', 'box', 'cylinder' or 'rock')");
  expectError(scene(R"("textures": {"t": {"type": "solid", "address": "wrap"}})"), DiagCode::E7004,
              "unknown address mode 'wrap' (expected 'repeat' or 'clamp')");
  expectError(scene(R"("textures": {"t": {"type": "checker", "size": 4, "cells": 8}})"), DiagCode::E7004,
              "'cells' must be at most the texture's 'size' (4), found 8");
  expectError(scene(R"("textures": {"t": {"type": "noise", "seed": 4294967296}})"), DiagCode::E7004,
              "'seed' must be between 0 and 4294967295, found 4294967296");
  expectError(scene(R"("camera": {"fovY": 180, "views": [{"position": [0, 2, 5]}]})", false), DiagCode::E7004,
              "'fovY' must be greater than 0 and less than 180, found 180");
  expectError(scene(R"("camera": {"near": 1, "far": 0.5, "views": [{"position": [0, 2, 5]}]})", false), DiagCode::E7004,
              "'far' must be greater than 'near' (1), found 0.5");
  expectError(scene(R"("camera": {"views": [{"position": [1, 2, 3], "target": [1, 2, 3]}]})", false), DiagCode::E7004,
              "a view's 'position' and 'target' must differ");
  expectError(scene(R"("camera": {"views": [{"position": [0, 5, 0]}]})", false), DiagCode::E7004,
              "this view looks along the camera's 'up' vector, so its orientation is undefined");
  expectError(scene(R"("camera": {"views": []})", false), DiagCode::E7004, "'views' must contain at least one view");
  expectError(scene(R"("light": {"direction": [0, 0, 0]})"), DiagCode::E7004,
              "'direction' must not be the zero vector");
  expectError(scene(R"("instances": [])", true, true, false), DiagCode::E7004,
              "'instances' must contain at least one instance");
  expectError(scene(R"("textures": {"": {"type": "solid"}})"), DiagCode::E7004,
              "names in 'textures' must not be empty");
  expectError(withInstance(R"({"mesh": "ground", "kernels": ""})"), DiagCode::E7004, "'kernels' must not be empty");
  expectError(withInstance(R"({"mesh": "ground", "kernels": "k", "transform": {"scale": [1, 0, 1]}})"), DiagCode::E7004,
              "each element of 'scale' must be greater than 0, found 0");
  expectError(withInstance(R"({"mesh": "ground", "kernels": "k", "transform": {"translate": [1e39, 0, 0]}})"),
              DiagCode::E7004, "each element of 'translate' must be within the range of a float, found 1e39");
}

TEST(SceneFile, MissingFieldsE7005) {
  expectError(scene("", false), DiagCode::E7005, "the scene has no 'camera' (it needs at least one view)");
  expectError(scene("", true, true, false), DiagCode::E7005, "the scene has no 'instances' (it needs at least one)");
  expectError(scene(R"("camera": {"fovY": 60})", false), DiagCode::E7005,
              "'camera' has no 'views' (it needs at least one)");
  expectError(scene(R"("meshes": {"ground": {"size": 3}})", true, false), DiagCode::E7005,
              "mesh 'ground' has no 'type' (one of 'terrain', 'sphere', 'plane', 'gltf', 'box', 'cylinder' or 'rock')");
  expectError(scene(R"("meshes": {"ground": {"type": "gltf"}})", true, false), DiagCode::E7005,
              "gltf mesh 'ground' has no 'file'");
  expectError(scene(R"("textures": {"t": {"type": "file"}})"), DiagCode::E7005, "file texture 't' has no 'file'");
  expectError(withInstance(R"({"kernels": "k"})"), DiagCode::E7005, "an instance needs a 'mesh'");
  expectError(withInstance(R"({"mesh": "ground"})"), DiagCode::E7005,
              "an instance needs 'source' and 'shader' (compiled in process) or 'kernels' (a spirec output directory)");
  expectError(withInstance(R"({"mesh": "ground", "source": "a.spire"})"), DiagCode::E7005,
              "an instance with a 'source' needs the 'shader' to build from it");
  expectError(withInstance(R"({"mesh": "ground", "shader": "A", "kernels": "k"})"), DiagCode::E7005,
              "an instance with a 'shader' needs the 'source' that defines it");
  expectError(withInstance(R"({"mesh": "ground", "kernels": "k", "decisions": "x.decisions"})"), DiagCode::E7005,
              "'decisions' apply to a 'source' and 'shader', which this instance does not have");
  expectError(scene(R"("variants": [{"name": "v"}])"), DiagCode::E7005,
              "a variant needs 'decisions' (a decision file)");
}

TEST(SceneFile, UnknownNamesE7006) {
  expectError(withInstance(R"({"mesh": "grund", "kernels": "k"})"), DiagCode::E7006,
              "unknown mesh 'grund'; did you mean 'ground'?");
  expectError(withInstance(R"({"mesh": "ground", "kernels": "k", "material": {"albedo": "stones"}})"), DiagCode::E7006,
              "unknown texture 'stones'; did you mean 'stone'?");
  const auto loaded = parseScene(scene(R"("instances": [{"mesh": "g", "kernels": "k"}])", true, true, false));
  ASSERT_EQ(loaded->diags.all().size(), 1u) << loaded->rendered;
  EXPECT_EQ(loaded->diags.all()[0].message, "unknown mesh 'g'");
  const auto noTextures = parseScene(
      scene(R"("instances": [{"mesh": "ground", "kernels": "k", "material": {"a": "brick"}}])", true, true, false));
  ASSERT_EQ(noTextures->diags.all().size(), 1u) << noTextures->rendered;
  EXPECT_EQ(noTextures->diags.all()[0].message, "unknown texture 'brick'");
  ASSERT_EQ(noTextures->diags.all()[0].notes.size(), 1u);
  EXPECT_EQ(noTextures->diags.all()[0].notes[0].message, "the scene has no 'textures'");
}

TEST(SceneFile, InstancesMayNameMeshesDefinedLater) {
  const auto loaded =
      parseScene(R"({"instances": [{"mesh": "late", "kernels": "k"}], )"
                 R"("camera": {"views": [{"position": [0, 2, 5]}]}, "meshes": {"late": {"type": "plane"}}})");
  EXPECT_TRUE(loaded->scene.has_value()) << loaded->rendered;
}

TEST(SceneFile, DuplicateNamesE7007) {
  expectError(scene(R"("meshes": {"ground": {"type": "plane"}, "ground": {"type": "sphere"}})", true, false),
              DiagCode::E7007, "duplicate key 'ground'");
  expectError(
      scene(R"("variants": [{"name": "a", "decisions": "a.decisions"}, {"name": "a", "decisions": "b.decisions"}])"),
      DiagCode::E7007, "duplicate variant name 'a'");
}

TEST(SceneFile, ReportsEveryErrorOfAFileInFileOrder) {
  const auto loaded = parseScene(R"({
  "resolution": [0, 480],
  "frames": 2.5,
  "camera": {"fovY": 200, "views": [{"position": [0, 2, 5]}]},
  "meshes": {"ground": {"type": "plane", "size": -1, "colour": 1}},
  "instances": [{"mesh": "grond", "source": "a.spire"}]
})");
  EXPECT_FALSE(loaded->scene.has_value());
  std::vector<std::string> codes;
  std::vector<uint32_t> lines;
  for (const Diagnostic& d : loaded->diags.all()) {
    codes.emplace_back(diagCodeInfo(d.code).name);
    lines.push_back(loaded->sources.begin(d.range).line);
  }
  EXPECT_EQ(codes, (std::vector<std::string>{"E7004", "E7003", "E7004", "E7004", "E7002", "E7006", "E7005"}))
      << loaded->rendered;
  EXPECT_EQ(lines, (std::vector<uint32_t>{2, 3, 4, 5, 5, 6, 6}));
}

TEST(SceneFile, SyntaxErrorsStopBeforeChecking) {
  const auto loaded = parseScene("{\"frames\": 0,}");
  EXPECT_FALSE(loaded->scene.has_value());
  ASSERT_EQ(loaded->diags.all().size(), 1u);
  EXPECT_EQ(loaded->diags.all()[0].code, DiagCode::E7001);
}

TEST(SceneFile, MissingFileE1101) {
  SourceManager sources;
  DiagnosticList diags;
  EXPECT_FALSE(loadSceneFile("/nonexistent/scene.json", sources, diags).has_value());
  ASSERT_EQ(diags.all().size(), 1u);
  EXPECT_EQ(diags.all()[0].code, DiagCode::E1101);
  EXPECT_EQ(diags.all()[0].message, "cannot open scene file '/nonexistent/scene.json'");
}

// Every prefix of the example is either rejected with a diagnostic or, for
// the whole file, accepted: no input makes the reader crash or loop.
TEST(SceneFile, EveryTruncationOfTheExampleIsRejectedCleanly) {
  const std::optional<std::string> text =
      readWholeFile((fs::path(SPIRE_SOURCE_DIR) / "examples/scenes/terrain.json").string());
  ASSERT_TRUE(text.has_value());
  const std::string trimmed = text->substr(0, text->find_last_not_of(" \n") + 1);
  for (size_t length = 0; length < trimmed.size(); ++length) {
    const auto loaded = parseScene(trimmed.substr(0, length));
    EXPECT_FALSE(loaded->scene.has_value()) << length;
    EXPECT_TRUE(loaded->diags.hasErrors()) << length;
  }
  EXPECT_TRUE(parseScene(trimmed)->scene.has_value());
}

}  // namespace
}  // namespace spire::scene
