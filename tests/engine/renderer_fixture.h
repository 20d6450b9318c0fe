// The renderer test fixture: scenes the tests write themselves, rendered on
// the device the loader finds (lavapipe on CI) with validation on, and the
// checks the image tests share (coverage, means, errors, golden PNGs).
//
// Goldens live in tests/golden/images; after an intended change run with
// SPIRE_UPDATE_GOLDENS=1 and review the new PNGs.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <string>

#include "engine/device_fixture.h"
#include "measure/image_metrics.h"
#include "renderer/scene_renderer.h"
#include "renderer/view_error.h"
#include "scene/texture.h"
#include "support/diagnostic_renderer.h"

namespace spire::engine::testing {

namespace fs = std::filesystem;

inline const fs::path kDataDir = fs::path(SPIRE_SOURCE_DIR) / "tests/data/engine";

// A 96x64 view straight down onto a 2x2 plane at the origin, which then
// covers the middle of the image.
inline std::string planeScene(const std::string& source, const std::string& shader, const std::string& material,
                              const std::string& extra = "") {
  return R"({
  "resolution": [96, 64], "frames": 2, "warmupFrames": 1,
  "clearColor": [0, 0, 0, 1],
  "camera": {"fovY": 60, "views": [{"position": [0, 2.2, 0.01], "target": [0, 0, 0]}]},
  "meshes": {"plane": {"type": "plane", "size": 2, "resolution": 4},
             "ball": {"type": "sphere", "radius": 0.9, "rings": 12, "segments": 24}},
  "textures": {"noise": {"type": "noise", "size": 32, "seed": 9, "octaves": 3},
               "checker": {"type": "checker", "size": 64, "cells": 4, "color": [0.9, 0.2, 0.1], "color2": [0.1, 0.3, 0.8]}},
  "instances": [{"mesh": "plane", "source": ")" +
         source + R"(", "shader": ")" + shader + R"(", "material": )" + material + "}]" + extra + "\n}\n";
}

class RendererTest : public vk::testing::DeviceTest {
 protected:
  struct Rendered {
    Capture capture;
    PreparedScene prepared;
    std::string diagnostics;
    std::vector<VariantProgram> programs;  // per instance
  };

  // Loads `json` into scene_ as if it were a file in tests/data/engine, with
  // fresh sources and diagnostics; false (and a test failure) when it does
  // not parse.
  bool loadScene(const std::string& json) {
    sources_ = std::make_unique<SourceManager>();
    diags_ = std::make_unique<DiagnosticList>();
    scene_ = scene::parseSceneFile("test_scene.json", json, kDataDir, *sources_, *diags_);
    if (!scene_) ADD_FAILURE() << renderDiagnostics(*sources_, *diags_, DiagnosticFormat::Text);
    return scene_.has_value();
  }

  // `text` as the decision file NAME.decisions in the test's temporary folder.
  static fs::path writeDecisions(const std::string& name, const std::string& text) {
    const fs::path path = fs::path(::testing::TempDir()) / (name + ".decisions");
    std::ofstream(path) << text;
    return path;
  }

  // render() with the decision file `decisions` written as NAME.decisions.
  std::optional<Rendered> renderWith(const std::string& json, const std::string& name, const std::string& decisions) {
    return render(json, writeDecisions(name, decisions));
  }

  // Loads `json` (loadScene) and renders view 0 with `decisions` applied to
  // every instance.
  std::optional<Rendered> render(const std::string& json, const std::optional<fs::path>& decisions,
                                 TextureBakeOptions bakeOptions = {}) {
    if (!loadScene(json)) return std::nullopt;
    renderer_ = std::make_unique<SceneRenderer>(ctx(), *scene_, *diags_, bakeOptions);
    auto programs = renderer_->compile(decisions ? std::optional(kDataDir / *decisions) : std::nullopt);
    if (!programs) {
      ADD_FAILURE() << programs.error().message << "\n" << programs.error().details;
      return std::nullopt;
    }
    auto prepared = renderer_->prepare(*programs);
    const std::string diagnostics = renderDiagnostics(*sources_, *diags_, DiagnosticFormat::Text);
    if (!prepared) {
      ADD_FAILURE() << prepared.error().message << "\n" << diagnostics;
      return std::nullopt;
    }
    auto capture = renderer_->capture(*prepared, scene_->camera.views.front());
    if (!capture) {
      ADD_FAILURE() << capture.error().message;
      return std::nullopt;
    }
    return Rendered{std::move(capture).value(), std::move(prepared).value(), diagnostics, *programs};
  }

  // Two planes of tex_bake.spire's TexBake with its texture bake (64
  // texels), the first with colorMap "checker", the second with `second`.
  std::optional<Rendered> bakeTwoPlanes(const std::string& second) {
    std::string scene = planeScene("tex_bake.spire", "TexBake", R"({"colorMap": "checker"})");
    const std::string instance = R"({"mesh": "plane", "source": "tex_bake.spire", "shader": "TexBake",
    "transform": {"translate": [0.5, 0, 0]}, "material": {"colorMap": ")" +
                                 second + R"("}})";
    scene.replace(scene.rfind("}]"), 2, "}, " + instance + "]");
    TextureBakeOptions options;
    options.defaultSize = 64;
    return render(scene, "tex_bake_prebake.decisions", options);
  }

  // The error of `test` against `reference` over pixels either covers.
  static measure::ImageError compare(const Capture& reference, const Capture& test) {
    auto error = engine::viewError(reference, test);
    EXPECT_TRUE(error) << error.error().message;
    return error ? *error : measure::ImageError{};
  }

  static double coveredFraction(const Capture& capture) {
    size_t covered = 0;
    for (uint8_t c : capture.coverage) covered += c;
    return static_cast<double>(covered) / static_cast<double>(capture.coverage.size());
  }

  // Mean RGBA over covered pixels.
  static std::array<double, 4> coveredMean(const Capture& capture) {
    std::array<double, 4> sum{};
    size_t count = 0;
    for (size_t i = 0; i < capture.coverage.size(); ++i) {
      if (!capture.coverage[i]) continue;
      for (size_t c = 0; c < 4; ++c) sum[c] += capture.color.rgba[i * 4 + c];
      ++count;
    }
    for (double& s : sum) s /= static_cast<double>(std::max<size_t>(count, 1));
    return sum;
  }

  // Compares the 8-bit rendering with tests/golden/images/NAME.png, allowing
  // `tolerance` (in 8-bit steps) per channel for rasterizer differences.
  static void expectGolden(const Capture& capture, const std::string& name, int tolerance = 2) {
    const scene::Image image = measure::toRgba8(capture.color);
    const fs::path golden = fs::path(SPIRE_SOURCE_DIR) / "tests/golden/images" / (name + ".png");
    if (std::getenv("SPIRE_UPDATE_GOLDENS")) {
      ASSERT_TRUE(scene::writePng(golden, image));
      return;
    }
    auto expected = scene::loadImage(golden);
    ASSERT_TRUE(expected) << expected.error().message << "; run with SPIRE_UPDATE_GOLDENS=1";
    ASSERT_EQ(expected->width, image.width);
    ASSERT_EQ(expected->height, image.height);
    size_t differing = 0;
    for (size_t i = 0; i < image.bytes.size(); ++i) {
      if (std::abs(int{image.bytes[i]} - int{expected->bytes[i]}) > tolerance) ++differing;
    }
    EXPECT_EQ(differing, 0U) << name << ": " << differing << " channels differ by more than " << tolerance;
  }

  std::unique_ptr<SourceManager> sources_;
  std::unique_ptr<DiagnosticList> diags_;
  std::optional<scene::SceneFile> scene_;
  std::unique_ptr<SceneRenderer> renderer_;
};

}  // namespace spire::engine::testing
