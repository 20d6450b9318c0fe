// Numerical stability at the extremes, rendered on the device the loader
// finds (lavapipe on CI) with validation on. Every function of stdlib/ runs in
// a probe shader (tests/data/engine/stability/probes.spire) whose arguments
// are material uniforms, set from the scene's bindings to the extremes:
// zero-length, tiny, huge and non-normalized vectors, grazing and back-facing
// light, roughness 0 and 1, uniforms near the float limits. The Terrain
// example runs under its three decision files and two per-vertex lighting
// ones with the camera at a vertex, the light below the horizon, all-black
// and all-white textures and UVs outside [0, 1]. Each case asserts that every
// covered pixel is finite, and equals the function's exact value where that
// is known (so a guard that returns a finite but wrong value fails too), or,
// where the true value does not fit in a float, that the engine counts the
// hazard. A user's own division by a zero uniform, which no library guard can
// prevent, must be counted and named by spire-demo's warning.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include <unistd.h>

#include "demo/demo.h"
#include "engine/device_fixture.h"
#include "measure/image_metrics.h"
#include "renderer/scene_renderer.h"
#include "support/diagnostic_renderer.h"

namespace spire::engine {
namespace {

namespace fs = std::filesystem;

const fs::path kSourceDir = SPIRE_SOURCE_DIR;
const fs::path kDataDir = kSourceDir / "tests/data/engine/stability";

using Rgba = std::array<float, 4>;

// The probes write a scalar result to red, with alpha 1.
Rgba scalar(float value) { return {value, 0.0F, 0.0F, 1.0F}; }
// ... and a vector result to RGB, with alpha 1.
Rgba direction(float x, float y, float z) { return {x, y, z, 1.0F}; }

enum class Outcome {
  Finite,         // every covered pixel finite
  InfEverywhere,  // every covered pixel Inf: the true value overflows a float, and the engine must count it
};

struct ProbeCase {
  std::string_view function;                 // the stdlib function under test
  std::string_view extreme;                  // what is extreme about the inputs
  std::string_view shader;                   // its probe in probes.spire
  std::string_view material;                 // the probe's bindings
  std::optional<Rgba> value = std::nullopt;  // every covered pixel's value, where the exact result is known
  float tolerance = 1e-4F;                   // relative, for `value`
  Outcome outcome = Outcome::Finite;
};

// 1/sqrt(2), 1/sqrt(3): unit vectors along diagonals.
constexpr float kHalfSqrt2 = 0.70710678F;
constexpr float kInvSqrt3 = 0.57735027F;
// ggx at normal = light = view: 0.96 / PI diffuse plus D * F0 / 4 specular
// with D = 1 / (PI * alpha^2), times PI; alpha is clamped to at least 2e-3.
constexpr float kGgxMirrorRough = 0.97F;
constexpr float kGgxMirrorSmooth = 0.96F + 0.01F / (2e-3F * 2e-3F);
// The GGX peak 1 / (PI alpha^2) at the smallest alpha comes out of the
// cancellation 1 + (alpha^2 - 1), good to a few 0.1% in float.
constexpr float kPeakTolerance = 1e-2F;
constexpr float kPi = 3.14159265F;
// D * G / (4 n.l n.v) at n.h = n.l = n.v = 1 is D / 4: 1 / (4 PI alpha^2).
constexpr float kSpecularPeakSmooth = 1.0F / (4.0F * kPi * 2e-3F * 2e-3F);
constexpr float kSpecularPeakRough = 1.0F / (4.0F * kPi);

const std::vector<ProbeCase>& probeCases() {
  // clang-format off
  static const std::vector<ProbeCase> cases = {
      // safeNormalize
      {.function = "safeNormalize", .extreme = "v = (0, 0, 0): zero length gives the +Z fallback",
       .shader = "SafeNormalizeProbe", .material = R"({"v": [0, 0, 0]})", .value = direction(0, 0, 1)},
      {.function = "safeNormalize", .extreme = "v = (0, 3, 4): not normalized", .shader = "SafeNormalizeProbe",
       .material = R"({"v": [0, 3, 4]})", .value = direction(0, 0.6F, 0.8F)},
      {.function = "safeNormalize", .extreme = "v = (0, 1e-20, 0): dot(v, v) underflows",
       .shader = "SafeNormalizeProbe", .material = R"({"v": [0, 1e-20, 0]})", .value = direction(0, 1, 0)},
      {.function = "safeNormalize", .extreme = "v = (-1e-37, 0, 0): near the smallest normal float",
       .shader = "SafeNormalizeProbe", .material = R"({"v": [-1e-37, 0, 0]})", .value = direction(-1, 0, 0)},
      {.function = "safeNormalize", .extreme = "v = (1e-39, 0, 0): subnormal, too short for a direction",
       .shader = "SafeNormalizeProbe", .material = R"({"v": [1e-39, 0, 0]})", .value = direction(0, 0, 1)},
      {.function = "safeNormalize", .extreme = "v = (0, 1e30, 0): dot(v, v) overflows",
       .shader = "SafeNormalizeProbe", .material = R"({"v": [0, 1e30, 0]})", .value = direction(0, 1, 0)},
      {.function = "safeNormalize", .extreme = "v = (3e38, -3e38, 0): near the largest float",
       .shader = "SafeNormalizeProbe", .material = R"({"v": [3e38, -3e38, 0]})",
       .value = direction(kHalfSqrt2, -kHalfSqrt2, 0)},

      // normalizeOr
      {.function = "normalizeOr", .extreme = "v = (0, 0, 0): gives the fallback", .shader = "NormalizeOrProbe",
       .material = R"({"v": [0, 0, 0], "fallback": [0, 1, 0]})", .value = direction(0, 1, 0)},
      {.function = "normalizeOr", .extreme = "v = (0, 0, 0), fallback (0, 0, 0): the degeneracy signal perturbNormal uses",
       .shader = "NormalizeOrProbe", .material = R"({"v": [0, 0, 0], "fallback": [0, 0, 0]})",
       .value = direction(0, 0, 0)},
      {.function = "normalizeOr", .extreme = "v = (0, -1e30, 0): dot(v, v) overflows", .shader = "NormalizeOrProbe",
       .material = R"({"v": [0, -1e30, 0], "fallback": [0, 0, 0]})", .value = direction(0, -1, 0)},
      {.function = "normalizeOr", .extreme = "v = (3e38, 3e38, 3e38): near the largest float",
       .shader = "NormalizeOrProbe", .material = R"({"v": [3e38, 3e38, 3e38], "fallback": [0, 0, 0]})",
       .value = direction(kInvSqrt3, kInvSqrt3, kInvSqrt3)},
      {.function = "normalizeOr", .extreme = "v = (0, 0, 1e-25): dot(v, v) underflows", .shader = "NormalizeOrProbe",
       .material = R"({"v": [0, 0, 1e-25], "fallback": [0, 0, 0]})", .value = direction(0, 0, 1)},

      // pow5
      {.function = "pow5", .extreme = "x = 0", .shader = "Pow5Probe", .material = R"({"x": 0})", .value = scalar(0)},
      {.function = "pow5", .extreme = "x = -2: negative base (pow() would be undefined)", .shader = "Pow5Probe",
       .material = R"({"x": -2})", .value = scalar(-32)},
      {.function = "pow5", .extreme = "x = 1e-38: x^5 underflows", .shader = "Pow5Probe", .material = R"({"x": 1e-38})",
       .value = scalar(0)},
      {.function = "pow5", .extreme = "x = 1e7: x^5 = 1e35, near the largest float", .shader = "Pow5Probe",
       .material = R"({"x": 1e7})", .value = scalar(1e35F)},
      {.function = "pow5", .extreme = "x = 1e8: x^5 = 1e40 does not fit in a float, the engine counts the Inf",
       .shader = "Pow5Probe", .material = R"({"x": 1e8})", .outcome = Outcome::InfEverywhere},

      // luminance
      {.function = "luminance", .extreme = "color = (0, 0, 0)", .shader = "LuminanceProbe",
       .material = R"({"color": [0, 0, 0]})", .value = scalar(0)},
      {.function = "luminance", .extreme = "color = (3e38, 3e38, 3e38): near the largest float",
       .shader = "LuminanceProbe", .material = R"({"color": [3e38, 3e38, 3e38]})", .value = scalar(3e38F)},
      {.function = "luminance", .extreme = "color = (1e-38, 1e-38, 1e-38)", .shader = "LuminanceProbe",
       .material = R"({"color": [1e-38, 1e-38, 1e-38]})", .value = scalar(0)},

      // clamp01
      {.function = "clamp01", .extreme = "x = 3e38", .shader = "Clamp01Probe", .material = R"({"x": 3e38})",
       .value = scalar(1)},
      {.function = "clamp01", .extreme = "x = -3e38", .shader = "Clamp01Probe", .material = R"({"x": -3e38})",
       .value = scalar(0)},
      {.function = "clamp01", .extreme = "x = 1e-38", .shader = "Clamp01Probe", .material = R"({"x": 1e-38})",
       .value = scalar(0)},

      // unpackNormal
      {.function = "unpackNormal", .extreme = "texel = (0.5, 0.5, 0.5): decodes to a zero vector",
       .shader = "UnpackNormalProbe", .material = R"({"texel": [0.5, 0.5, 0.5, 1]})", .value = direction(0, 0, 1)},
      {.function = "unpackNormal", .extreme = "texel = (0, 0, 0, 0): all-black", .shader = "UnpackNormalProbe",
       .material = R"({"texel": [0, 0, 0, 0]})", .value = direction(-kInvSqrt3, -kInvSqrt3, -kInvSqrt3)},
      {.function = "unpackNormal", .extreme = "texel = (1, 1, 1, 1): all-white", .shader = "UnpackNormalProbe",
       .material = R"({"texel": [1, 1, 1, 1]})", .value = direction(kInvSqrt3, kInvSqrt3, kInvSqrt3)},
      {.function = "unpackNormal", .extreme = "texel = (0.5, 1e30, 0.5): the decoded length overflows",
       .shader = "UnpackNormalProbe", .material = R"({"texel": [0.5, 1e30, 0.5, 1]})", .value = direction(0, 1, 0)},
      {.function = "unpackNormal", .extreme = "texel = (3e38, 3e38, 3e38): texel * 2 overflows to Inf",
       .shader = "UnpackNormalProbe", .material = R"({"texel": [3e38, 3e38, 3e38, 1]})",
       .value = direction(kInvSqrt3, kInvSqrt3, kInvSqrt3)},

      // unpackNormalXY
      {.function = "unpackNormalXY", .extreme = "texel = (0.5, 0.5): straight up", .shader = "UnpackNormalXYProbe",
       .material = R"({"texel": [0.5, 0.5]})", .value = direction(0, 0, 1)},
      {.function = "unpackNormalXY", .extreme = "texel = (0, 0): all-black, x and y longer than 1",
       .shader = "UnpackNormalXYProbe", .material = R"({"texel": [0, 0]})",
       .value = direction(-kHalfSqrt2, -kHalfSqrt2, 0)},
      {.function = "unpackNormalXY", .extreme = "texel = (1, 1): all-white", .shader = "UnpackNormalXYProbe",
       .material = R"({"texel": [1, 1]})", .value = direction(kHalfSqrt2, kHalfSqrt2, 0)},
      {.function = "unpackNormalXY", .extreme = "texel = (1, 0.5): x exactly 1, so z is 0",
       .shader = "UnpackNormalXYProbe", .material = R"({"texel": [1, 0.5]})", .value = direction(1, 0, 0)},
      {.function = "unpackNormalXY", .extreme = "texel = (0.5, 1e30): x^2 + y^2 overflows",
       .shader = "UnpackNormalXYProbe", .material = R"({"texel": [0.5, 1e30]})", .value = direction(0, 1, 0)},
      {.function = "unpackNormalXY", .extreme = "texel = (3e38, 3e38): texel * 2 overflows to Inf",
       .shader = "UnpackNormalXYProbe", .material = R"({"texel": [3e38, 3e38]})",
       .value = direction(kHalfSqrt2, kHalfSqrt2, 0)},

      // perturbNormal; normal +Y and tangent +X unless the extreme says otherwise
      {.function = "perturbNormal", .extreme = "tangent = (0, 0, 0): falls back to the normal",
       .shader = "PerturbNormalProbe",
       .material = R"({"tangentNormal": [1, 0, 0], "normal": [0, 1, 0], "tangent": [0, 0, 0, 1]})",
       .value = direction(0, 1, 0)},
      {.function = "perturbNormal", .extreme = "tangent = (0, 5, 0): parallel to the normal",
       .shader = "PerturbNormalProbe",
       .material = R"({"tangentNormal": [1, 0, 0], "normal": [0, 1, 0], "tangent": [0, 5, 0, 1]})",
       .value = direction(0, 1, 0)},
      {.function = "perturbNormal", .extreme = "normal = (0, 0, 0): the +Z fallback, tangent still +X",
       .shader = "PerturbNormalProbe",
       .material = R"({"tangentNormal": [1, 0, 0], "normal": [0, 0, 0], "tangent": [1, 0, 0, 1]})",
       .value = direction(1, 0, 0)},
      {.function = "perturbNormal", .extreme = "tangentNormal = (0, 0, 0): falls back to the normal",
       .shader = "PerturbNormalProbe",
       .material = R"({"tangentNormal": [0, 0, 0], "normal": [0, 1, 0], "tangent": [1, 0, 0, 1]})",
       .value = direction(0, 1, 0)},
      {.function = "perturbNormal", .extreme = "tangentNormal = (0, 0, 1e30): huge", .shader = "PerturbNormalProbe",
       .material = R"({"tangentNormal": [0, 0, 1e30], "normal": [0, 1, 0], "tangent": [1, 0, 0, 1]})",
       .value = direction(0, 1, 0)},
      {.function = "perturbNormal", .extreme = "tangent = (1e30, 0, 0): its squared length overflows",
       .shader = "PerturbNormalProbe",
       .material = R"({"tangentNormal": [1, 0, 0], "normal": [0, 1, 0], "tangent": [1e30, 0, 0, 1]})",
       .value = direction(1, 0, 0)},
      {.function = "perturbNormal", .extreme = "tangent = (3e38, 3e38, 0): near the largest float, half along the normal",
       .shader = "PerturbNormalProbe",
       .material = R"({"tangentNormal": [1, 0, 0], "normal": [0, 1, 0], "tangent": [3e38, 3e38, 0, 1]})",
       .value = direction(1, 0, 0)},
      {.function = "perturbNormal", .extreme = "tangent = (1e-20, 0, 0): its squared length underflows",
       .shader = "PerturbNormalProbe",
       .material = R"({"tangentNormal": [1, 0, 0], "normal": [0, 1, 0], "tangent": [1e-20, 0, 0, 1]})",
       .value = direction(1, 0, 0)},
      {.function = "perturbNormal", .extreme = "tangent.w = 0: no handedness counts as +1",
       .shader = "PerturbNormalProbe",
       .material = R"({"tangentNormal": [0, 1, 0], "normal": [0, 1, 0], "tangent": [1, 0, 0, 0]})",
       .value = direction(0, 0, -1)},
      {.function = "perturbNormal", .extreme = "all-black normal map (through unpackNormal)", .shader = "NormalMapProbe",
       .material = R"({"normalMap": "black", "uvScale": [1, 1], "uvOffset": [0, 0]})"},
      {.function = "perturbNormal", .extreme = "all-white normal map (through unpackNormal)", .shader = "NormalMapProbe",
       .material = R"({"normalMap": "white", "uvScale": [1, 1], "uvOffset": [0, 0]})"},
      {.function = "perturbNormal", .extreme = "UVs scaled by 1e4, repeat addressing", .shader = "NormalMapProbe",
       .material = R"({"normalMap": "normals", "uvScale": [1e4, 1e4], "uvOffset": [0, 0]})"},
      {.function = "perturbNormal", .extreme = "UVs offset by (-1e6, 1e6), repeat addressing",
       .shader = "NormalMapProbe",
       .material = R"({"normalMap": "normals", "uvScale": [1, 1], "uvOffset": [-1e6, 1e6]})"},
      {.function = "perturbNormal", .extreme = "UVs offset by (3e38, -3e38), repeat addressing",
       .shader = "NormalMapProbe",
       .material = R"({"normalMap": "normals", "uvScale": [1, 1], "uvOffset": [3e38, -3e38]})"},
      {.function = "perturbNormal", .extreme = "UVs in [-5e3, 5e3], clamp addressing", .shader = "NormalMapProbe",
       .material = R"({"normalMap": "normalsClamped", "uvScale": [1e4, 1e4], "uvOffset": [-5e3, -5e3]})"},

      // phong; normal +Y
      {.function = "phong", .extreme = "lightDir = (0, 0, 0): zero length", .shader = "PhongProbe",
       .material = R"({"lightDir": [0, 0, 0], "normal": [0, 1, 0], "viewDir": [0, 1, 0], "shininess": 32})",
       .value = scalar(0)},
      {.function = "phong", .extreme = "N.L = -1: back-facing light", .shader = "PhongProbe",
       .material = R"({"lightDir": [0, -1, 0], "normal": [0, 1, 0], "viewDir": [0, 1, 0], "shininess": 32})",
       .value = scalar(0)},
      {.function = "phong", .extreme = "N.L = 1e-7: grazing light", .shader = "PhongProbe",
       .material = R"({"lightDir": [1, 1e-7, 0], "normal": [0, 1, 0], "viewDir": [0, 1, 0], "shininess": 32})",
       .value = scalar(1e-7F)},
      {.function = "phong", .extreme = "viewDir = (0, 0, 0): zero length", .shader = "PhongProbe",
       .material = R"({"lightDir": [0, 1, 0], "normal": [0, 1, 0], "viewDir": [0, 0, 0], "shininess": 32})",
       .value = scalar(1)},
      {.function = "phong", .extreme = "normal = (0, 0, 0): zero length", .shader = "PhongProbe",
       .material = R"({"lightDir": [0, 1, 0], "normal": [0, 0, 0], "viewDir": [0, 1, 0], "shininess": 32})",
       .value = scalar(0)},
      {.function = "phong", .extreme = "shininess = 3e38 on the mirror direction: pow(1, 3e38)",
       .shader = "PhongProbe",
       .material = R"({"lightDir": [0, 1, 0], "normal": [0, 1, 0], "viewDir": [0, 1, 0], "shininess": 3e38})",
       .value = scalar(2)},
      {.function = "phong", .extreme = "shininess = 3e38 off the mirror direction: pow(0.8, 3e38)",
       .shader = "PhongProbe",
       .material = R"({"lightDir": [0, 1, 0], "normal": [0, 1, 0], "viewDir": [0.6, 0.8, 0], "shininess": 3e38})",
       .value = scalar(1)},
      {.function = "phong", .extreme = "shininess = 0: pow(0, 0) if unguarded", .shader = "PhongProbe",
       .material = R"({"lightDir": [0, 1, 0], "normal": [0, 1, 0], "viewDir": [0, 0, 1], "shininess": 0})",
       .value = scalar(1)},
      {.function = "phong", .extreme = "shininess = 1e-38", .shader = "PhongProbe",
       .material = R"({"lightDir": [0, 1, 0], "normal": [0, 1, 0], "viewDir": [0, 1, 0], "shininess": 1e-38})",
       .value = scalar(2)},
      {.function = "phong", .extreme = "shininess = -3e38", .shader = "PhongProbe",
       .material = R"({"lightDir": [0, 1, 0], "normal": [0, 1, 0], "viewDir": [0, 1, 0], "shininess": -3e38})",
       .value = scalar(2)},
      {.function = "phong", .extreme = "non-normalized vectors of lengths 5, 0.1 and 7", .shader = "PhongProbe",
       .material = R"({"lightDir": [0, 5, 0], "normal": [0, 0.1, 0], "viewDir": [0, 7, 0], "shininess": 32})",
       .value = scalar(2)},
      {.function = "phong", .extreme = "vectors of length 1e30", .shader = "PhongProbe",
       .material = R"({"lightDir": [0, 1e30, 0], "normal": [0, 1e30, 0], "viewDir": [0, 1e30, 0], "shininess": 32})",
       .value = scalar(2)},
      {.function = "phong", .extreme = "vectors of length 3e38", .shader = "PhongProbe",
       .material = R"({"lightDir": [0, 3e38, 0], "normal": [0, 3e38, 0], "viewDir": [0, 3e38, 0], "shininess": 32})",
       .value = scalar(2)},
      // N.L = 1/sqrt(2) and R.V = 1/sqrt(2), so phong = 2^-0.5 + 2^-16.
      {.function = "phong", .extreme = "vectors of length 1e-20", .shader = "PhongProbe",
       .material =
           R"({"lightDir": [1e-20, 1e-20, 0], "normal": [0, 1e-20, 0], "viewDir": [0, 1e-20, 0], "shininess": 32})",
       .value = scalar(kHalfSqrt2 + 1.0F / 65536.0F)},

      // ggx; normal +Y
      {.function = "ggx", .extreme = "roughness = 0 on the mirror direction: the sharpest lobe", .shader = "GgxProbe",
       .material = R"({"lightDir": [0, 1, 0], "normal": [0, 1, 0], "viewDir": [0, 1, 0], "roughness": 0})",
       .value = scalar(kGgxMirrorSmooth), .tolerance = kPeakTolerance},
      {.function = "ggx", .extreme = "roughness = 1", .shader = "GgxProbe",
       .material = R"({"lightDir": [0, 1, 0], "normal": [0, 1, 0], "viewDir": [0, 1, 0], "roughness": 1})",
       .value = scalar(kGgxMirrorRough)},
      {.function = "ggx", .extreme = "roughness = 1e-38", .shader = "GgxProbe",
       .material = R"({"lightDir": [0, 1, 0], "normal": [0, 1, 0], "viewDir": [0, 1, 0], "roughness": 1e-38})",
       .value = scalar(kGgxMirrorSmooth), .tolerance = kPeakTolerance},
      {.function = "ggx", .extreme = "roughness = 3e38", .shader = "GgxProbe",
       .material = R"({"lightDir": [0, 1, 0], "normal": [0, 1, 0], "viewDir": [0, 1, 0], "roughness": 3e38})",
       .value = scalar(kGgxMirrorRough)},
      {.function = "ggx", .extreme = "roughness = -3e38", .shader = "GgxProbe",
       .material = R"({"lightDir": [0, 1, 0], "normal": [0, 1, 0], "viewDir": [0, 1, 0], "roughness": -3e38})",
       .value = scalar(kGgxMirrorSmooth), .tolerance = kPeakTolerance},
      {.function = "ggx", .extreme = "roughness = 0, N.L = N.V = 1e-7: grazing mirror, the largest specular",
       .shader = "GgxProbe",
       .material = R"({"lightDir": [1, 1e-7, 0], "normal": [0, 1, 0], "viewDir": [-1, 1e-7, 0], "roughness": 0})"},
      {.function = "ggx", .extreme = "roughness = 0, N.V = 0: view along the surface", .shader = "GgxProbe",
       .material = R"({"lightDir": [0, 1, 0], "normal": [0, 1, 0], "viewDir": [1, 0, 0], "roughness": 0})"},
      {.function = "ggx", .extreme = "N.L = -1: back-facing light", .shader = "GgxProbe",
       .material = R"({"lightDir": [0, -1, 0], "normal": [0, 1, 0], "viewDir": [0, 1, 0], "roughness": 0.5})",
       .value = scalar(0)},
      {.function = "ggx", .extreme = "lightDir = (0, 0, 0): zero length", .shader = "GgxProbe",
       .material = R"({"lightDir": [0, 0, 0], "normal": [0, 1, 0], "viewDir": [0, 1, 0], "roughness": 0.5})",
       .value = scalar(0)},
      {.function = "ggx", .extreme = "viewDir = (0, 0, 0): zero length", .shader = "GgxProbe",
       .material = R"({"lightDir": [0, 1, 0], "normal": [0, 1, 0], "viewDir": [0, 0, 0], "roughness": 0})"},
      {.function = "ggx", .extreme = "viewDir = -lightDir: the half vector is zero", .shader = "GgxProbe",
       .material = R"({"lightDir": [0, 1, 0], "normal": [0, 1, 0], "viewDir": [0, -1, 0], "roughness": 0})"},
      {.function = "ggx", .extreme = "vectors of length 1e30", .shader = "GgxProbe",
       .material = R"({"lightDir": [0, 1e30, 0], "normal": [0, 1e30, 0], "viewDir": [0, 1e30, 0], "roughness": 1})",
       .value = scalar(kGgxMirrorRough)},
      {.function = "ggx", .extreme = "lightDir of length 1e-20", .shader = "GgxProbe",
       .material = R"({"lightDir": [0, 1e-20, 0], "normal": [0, 1, 0], "viewDir": [0, 1, 0], "roughness": 1})",
       .value = scalar(kGgxMirrorRough)},

      // ggxAlpha (pbr.spire)
      {.function = "ggxAlpha", .extreme = "roughness = 0: alpha kept at 2e-3", .shader = "GgxAlphaProbe",
       .material = R"({"roughness": 0})", .value = scalar(2e-3F)},
      {.function = "ggxAlpha", .extreme = "roughness = 1", .shader = "GgxAlphaProbe", .material = R"({"roughness": 1})",
       .value = scalar(1)},
      {.function = "ggxAlpha", .extreme = "roughness = 3e38", .shader = "GgxAlphaProbe",
       .material = R"({"roughness": 3e38})", .value = scalar(1)},
      {.function = "ggxAlpha", .extreme = "roughness = -3e38", .shader = "GgxAlphaProbe",
       .material = R"({"roughness": -3e38})", .value = scalar(2e-3F)},
      {.function = "ggxAlpha", .extreme = "roughness = 1e-38", .shader = "GgxAlphaProbe",
       .material = R"({"roughness": 1e-38})", .value = scalar(2e-3F)},

      // distributionGGX (pbr.spire): D(1, alpha) = 1 / (PI alpha^2), D(0, alpha) = alpha^2 / PI
      {.function = "distributionGGX", .extreme = "alpha = 1", .shader = "DistributionGgxProbe",
       .material = R"({"nDotH": 1, "alpha": 1})", .value = scalar(1.0F / kPi)},
      {.function = "distributionGGX", .extreme = "alpha = 0 at n.h = 1: 0 / 0 unguarded",
       .shader = "DistributionGgxProbe", .material = R"({"nDotH": 1, "alpha": 0})",
       .value = scalar(1.0F / (kPi * 2e-3F * 2e-3F)), .tolerance = kPeakTolerance},
      {.function = "distributionGGX", .extreme = "alpha = 1e-38 at n.h = 1: alpha^2 underflows",
       .shader = "DistributionGgxProbe", .material = R"({"nDotH": 1, "alpha": 1e-38})",
       .value = scalar(1.0F / (kPi * 2e-3F * 2e-3F)), .tolerance = kPeakTolerance},
      {.function = "distributionGGX", .extreme = "alpha = 3e38: alpha^2 overflows", .shader = "DistributionGgxProbe",
       .material = R"({"nDotH": 0.5, "alpha": 3e38})", .value = scalar(1.0F / kPi)},
      {.function = "distributionGGX", .extreme = "n.h = 2 / sqrt(3) > 1 at alpha = 0.5: denom = 0 unguarded",
       .shader = "DistributionGgxProbe", .material = R"({"nDotH": 1.1547005, "alpha": 0.5})",
       .value = scalar(1.0F / (kPi * 0.25F))},
      {.function = "distributionGGX", .extreme = "n.h = -1: back-facing half vector", .shader = "DistributionGgxProbe",
       .material = R"({"nDotH": -1, "alpha": 0.5})", .value = scalar(0.25F / kPi)},

      // visibilitySmithSchlick (pbr.spire): 0.25 at n.l = n.v = 1
      {.function = "visibilitySmithSchlick", .extreme = "n.l = n.v = 1, alpha = 1", .shader = "VisibilityProbe",
       .material = R"({"nDotL": 1, "nDotV": 1, "alpha": 1})", .value = scalar(0.25F)},
      {.function = "visibilitySmithSchlick", .extreme = "n.l = n.v = 0, alpha = 0: grazing, the largest value",
       .shader = "VisibilityProbe", .material = R"({"nDotL": 0, "nDotV": 0, "alpha": 0})"},
      {.function = "visibilitySmithSchlick", .extreme = "n.l = n.v = -1: back-facing", .shader = "VisibilityProbe",
       .material = R"({"nDotL": -1, "nDotV": -1, "alpha": 0.5})"},
      {.function = "visibilitySmithSchlick", .extreme = "alpha = 3e38: l (1 - k) + k cancels to 0 unguarded",
       .shader = "VisibilityProbe", .material = R"({"nDotL": 1, "nDotV": 1, "alpha": 3e38})", .value = scalar(0.25F)},
      {.function = "visibilitySmithSchlick", .extreme = "alpha = -1: a denominator is 0 at n.l = 1/3 unguarded",
       .shader = "VisibilityProbe", .material = R"({"nDotL": 0.33333334, "nDotV": 1, "alpha": -1})"},
      {.function = "visibilitySmithSchlick", .extreme = "n.l = n.v = 3e38", .shader = "VisibilityProbe",
       .material = R"({"nDotL": 3e38, "nDotV": 3e38, "alpha": 0.5})"},

      // fresnelSchlick (pbr.spire)
      {.function = "fresnelSchlick", .extreme = "v.h = 1: F0", .shader = "FresnelSchlickProbe",
       .material = R"({"f0": [0.04, 0.5, 1], "vDotH": 1})", .value = direction(0.04F, 0.5F, 1)},
      {.function = "fresnelSchlick", .extreme = "v.h = -3e38: clamped to grazing, 1", .shader = "FresnelSchlickProbe",
       .material = R"({"f0": [0.04, 0.5, 1], "vDotH": -3e38})", .value = direction(1, 1, 1)},
      {.function = "fresnelSchlick", .extreme = "v.h = 3e38", .shader = "FresnelSchlickProbe",
       .material = R"({"f0": [0.04, 0.5, 1], "vDotH": 3e38})", .value = direction(0.04F, 0.5F, 1)},
      {.function = "fresnelSchlick", .extreme = "F0 = (3e38, 0, -3e38)", .shader = "FresnelSchlickProbe",
       .material = R"({"f0": [3e38, 0, -3e38], "vDotH": 0.5})"},

      // specularBlinnPhong (pbr.spire): (n + 2) / (8 PI) at n.h = 1, n = 2 / alpha^2 - 2
      {.function = "specularBlinnPhong", .extreme = "alpha = 0: an infinite exponent unguarded",
       .shader = "SpecularBlinnPhongProbe", .material = R"({"nDotH": 1, "alpha": 0})",
       .value = scalar(2.0F / (2e-3F * 2e-3F) / (8.0F * kPi)), .tolerance = kPeakTolerance},
      {.function = "specularBlinnPhong", .extreme = "alpha = 1e-38: alpha^2 underflows",
       .shader = "SpecularBlinnPhongProbe", .material = R"({"nDotH": 0.5, "alpha": 1e-38})", .value = scalar(0)},
      {.function = "specularBlinnPhong", .extreme = "alpha = 1: exponent at its floor 1",
       .shader = "SpecularBlinnPhongProbe", .material = R"({"nDotH": 1, "alpha": 1})",
       .value = scalar(3.0F / (8.0F * kPi))},
      {.function = "specularBlinnPhong", .extreme = "alpha = 3e38", .shader = "SpecularBlinnPhongProbe",
       .material = R"({"nDotH": 1, "alpha": 3e38})", .value = scalar(3.0F / (8.0F * kPi))},
      {.function = "specularBlinnPhong", .extreme = "n.h = -1, alpha = 2e-3", .shader = "SpecularBlinnPhongProbe",
       .material = R"({"nDotH": -1, "alpha": 2e-3})", .value = scalar(0)},

      // specularGGX (pbr.spire)
      {.function = "specularGGX", .extreme = "roughness = 0 at n.h = n.l = n.v = 1: the peak",
       .shader = "SpecularGgxProbe", .material = R"({"nDotH": 1, "nDotL": 1, "nDotV": 1, "roughness": 0})",
       .value = scalar(kSpecularPeakSmooth), .tolerance = kPeakTolerance},
      {.function = "specularGGX", .extreme = "roughness = 1", .shader = "SpecularGgxProbe",
       .material = R"({"nDotH": 1, "nDotL": 1, "nDotV": 1, "roughness": 1})", .value = scalar(kSpecularPeakRough)},
      {.function = "specularGGX", .extreme = "roughness = 0, n.l = n.v = 0: grazing peak", .shader = "SpecularGgxProbe",
       .material = R"({"nDotH": 1, "nDotL": 0, "nDotV": 0, "roughness": 0})"},
      {.function = "specularGGX", .extreme = "roughness = -3e38, n.h = 3e38", .shader = "SpecularGgxProbe",
       .material = R"({"nDotH": 3e38, "nDotL": 1, "nDotV": 1, "roughness": -3e38})",
       .value = scalar(kSpecularPeakSmooth), .tolerance = kPeakTolerance},
      {.function = "specularGGX", .extreme = "roughness = 3e38, cosines -1", .shader = "SpecularGgxProbe",
       .material = R"({"nDotH": -1, "nDotL": -1, "nDotV": -1, "roughness": 3e38})"},

      // specularGGXLut (pbr.spire), on the engine's "ggxLut" texture and on all-black and all-white ones
      {.function = "specularGGXLut", .extreme = "roughness = 0 at n.h = n.l = n.v = 1", .shader = "SpecularGgxLutProbe",
       .material = R"({"ggxLut": "ggxLut", "nDotH": 1, "nDotL": 1, "nDotV": 1, "roughness": 0})"},
      {.function = "specularGGXLut", .extreme = "n.h = 3e38, n.l = n.v = 0, roughness = -3e38",
       .shader = "SpecularGgxLutProbe",
       .material = R"({"ggxLut": "ggxLut", "nDotH": 3e38, "nDotL": 0, "nDotV": 0, "roughness": -3e38})"},
      {.function = "specularGGXLut", .extreme = "n.h = -3e38, roughness = 3e38", .shader = "SpecularGgxLutProbe",
       .material = R"({"ggxLut": "ggxLut", "nDotH": -3e38, "nDotL": 1, "nDotV": 1, "roughness": 3e38})"},
      {.function = "specularGGXLut", .extreme = "all-black lookup texture: the shape is 0", .shader = "SpecularGgxLutProbe",
       .material = R"({"ggxLut": "black", "nDotH": 1, "nDotL": 1, "nDotV": 1, "roughness": 1})", .value = scalar(0)},
      {.function = "specularGGXLut", .extreme = "all-white lookup texture: the shape is 1, the peak",
       .shader = "SpecularGgxLutProbe",
       .material = R"({"ggxLut": "white", "nDotH": 1, "nDotL": 1, "nDotV": 1, "roughness": 1})",
       .value = scalar(kSpecularPeakRough)},

      // environmentBRDF (pbr.spire)
      {.function = "environmentBRDF", .extreme = "roughness = 0, n.v = 1", .shader = "EnvironmentBrdfProbe",
       .material = R"({"f0": [0.04, 0.04, 0.04], "roughness": 0, "nDotV": 1})"},
      {.function = "environmentBRDF", .extreme = "roughness = 3e38, n.v = -3e38", .shader = "EnvironmentBrdfProbe",
       .material = R"({"f0": [0, 0.5, 1], "roughness": 3e38, "nDotV": -3e38})"},
      {.function = "environmentBRDF", .extreme = "roughness = -3e38, n.v = 3e38", .shader = "EnvironmentBrdfProbe",
       .material = R"({"f0": [0, 0.5, 1], "roughness": -3e38, "nDotV": 3e38})"},
      {.function = "environmentBRDF", .extreme = "F0 = (1e30, 0, -1e30)", .shader = "EnvironmentBrdfProbe",
       .material = R"({"f0": [1e30, 0, -1e30], "roughness": 0.5, "nDotV": 0.5})"},

      // hemisphereLight (pbr.spire); sky blue, ground red
      {.function = "hemisphereLight", .extreme = "direction = (0, 0, 0): the +Z fallback, the horizon",
       .shader = "HemisphereLightProbe",
       .material = R"({"direction": [0, 0, 0], "skyColor": [0, 0, 1], "groundColor": [1, 0, 0]})",
       .value = direction(0.5F, 0, 0.5F)},
      {.function = "hemisphereLight", .extreme = "direction = (0, 1e30, 0): straight up, its length overflows",
       .shader = "HemisphereLightProbe",
       .material = R"({"direction": [0, 1e30, 0], "skyColor": [0, 0, 1], "groundColor": [1, 0, 0]})",
       .value = direction(0, 0, 1)},
      {.function = "hemisphereLight", .extreme = "direction = (0, -1e-20, 0): straight down, its length underflows",
       .shader = "HemisphereLightProbe",
       .material = R"({"direction": [0, -1e-20, 0], "skyColor": [0, 0, 1], "groundColor": [1, 0, 0]})",
       .value = direction(1, 0, 0)},
      {.function = "hemisphereLight", .extreme = "colors of 1e30", .shader = "HemisphereLightProbe",
       .material = R"({"direction": [0, 1, 1], "skyColor": [1e30, 1e30, 1e30], "groundColor": [-1e30, 1e30, 0]})"},

      // blendTangentNormals (pbr.spire)
      {.function = "blendTangentNormals", .extreme = "flat base and detail", .shader = "BlendTangentNormalsProbe",
       .material = R"({"base": [0, 0, 1], "detail": [0, 0, 1]})", .value = direction(0, 0, 1)},
      {.function = "blendTangentNormals", .extreme = "z = 1e30 each: their product overflows to Inf",
       .shader = "BlendTangentNormalsProbe", .material = R"({"base": [0, 0, 1e30], "detail": [0, 0, 1e30]})",
       .value = direction(0, 0, 1)},
      {.function = "blendTangentNormals", .extreme = "opposite slopes and z = 0: the zero vector",
       .shader = "BlendTangentNormalsProbe", .material = R"({"base": [1, 0, 0], "detail": [-1, 0, 0]})",
       .value = direction(0, 0, 1)},
      {.function = "blendTangentNormals", .extreme = "x = 3e38 each: their sum overflows to Inf",
       .shader = "BlendTangentNormalsProbe", .material = R"({"base": [3e38, 0, 0], "detail": [3e38, 0, 0]})",
       .value = direction(1, 0, 0)},

      // scaleTangentNormal (pbr.spire)
      {.function = "scaleTangentNormal", .extreme = "strength = 0: flat", .shader = "ScaleTangentNormalProbe",
       .material = R"({"n": [0.6, 0, 0.8], "strength": 0})", .value = direction(0, 0, 1)},
      {.function = "scaleTangentNormal", .extreme = "strength = 0 of a normal with z = 0: the zero vector",
       .shader = "ScaleTangentNormalProbe", .material = R"({"n": [1, 0, 0], "strength": 0})",
       .value = direction(0, 0, 1)},
      {.function = "scaleTangentNormal", .extreme = "strength = 3e38", .shader = "ScaleTangentNormalProbe",
       .material = R"({"n": [0.6, 0, 0.8], "strength": 3e38})", .value = direction(1, 0, 0)},
      {.function = "scaleTangentNormal", .extreme = "strength = -3e38", .shader = "ScaleTangentNormalProbe",
       .material = R"({"n": [0.6, 0, 0.8], "strength": -3e38})", .value = direction(-1, 0, 0)},
      {.function = "scaleTangentNormal", .extreme = "strength = 1e-38", .shader = "ScaleTangentNormalProbe",
       .material = R"({"n": [0.6, 0, 0.8], "strength": 1e-38})", .value = direction(0, 0, 1)},
  };
  // clang-format on
  return cases;
}

// An example shader at an extreme. For the Terrain example
// (examples/terrain.spire), `material` replaces the bindings of
// kTerrainMaterial with the same names, or adds bindings of the
// engine-supplied lightDir and cameraPos, which then win.
struct ExampleCase {
  std::string_view extreme;
  std::map<std::string, std::string> material;  // component -> JSON value
  std::string_view mesh = "plane";
  std::optional<Rgba> value = std::nullopt;  // every covered pixel's value, where known
};

const std::map<std::string, std::string> kTerrainMaterial = {{"mixMap", R"("noise")"},
                                                             {"albedoMap1", R"("grass")"},
                                                             {"albedoMap2", R"("rock")"},
                                                             {"normalMap1", R"("normals")"},
                                                             {"normalMap2", R"("normals")"},
                                                             {"shininess", "32"},
                                                             {"roughness", "0.4"}};

// The same JSON value bound to every one of `names`.
std::map<std::string, std::string> sameValue(std::initializer_list<const char*> names, const std::string& value) {
  std::map<std::string, std::string> bindings;
  for (const char* name : names) bindings[name] = value;
  return bindings;
}

// Camera and light extremes that every example shader is tested at. The
// test plane's central vertex is the origin (it has an even number of quads
// per side).
std::vector<ExampleCase> withCameraAndLightCases(std::vector<ExampleCase> cases) {
  const std::vector<ExampleCase> common = {
      {.extreme = "camera exactly at a vertex: cameraPos = (0, 0, 0)", .material = {{"cameraPos", "[0, 0, 0]"}}},
      {.extreme = "eye below the surface: cameraPos = (0, -2, 0)", .material = {{"cameraPos", "[0, -2, 0]"}}},
      {.extreme = "grazing light: lightDir = (1, 1e-7, 0)", .material = {{"lightDir", "[1, 1e-7, 0]"}}},
      {.extreme = "lightDir = (0, 0, 0)", .material = {{"lightDir", "[0, 0, 0]"}}},
      {.extreme = "lightDir and cameraPos of length 1e30 and 3e38",
       .material = {{"lightDir", "[0, 1e30, 0]"}, {"cameraPos", "[0, 3e38, 0]"}}},
      {.extreme = "UVs in [-3.25, 4.25] (uv_outside.gltf), repeat addressing", .material = {}, .mesh = "uvOutside"},
  };
  cases.insert(cases.begin(), common.begin(), common.end());
  return cases;
}

const std::vector<ExampleCase>& terrainCases() {
  static const std::vector<ExampleCase> cases = withCameraAndLightCases({
      {.extreme = "the scene's own values", .material = {}},
      // Normal-mapped normals stay in the upper hemisphere, so no pixel is lit.
      {.extreme = "light below the horizon: lightDir = (0, -1, 0)",
       .material = {{"lightDir", "[0, -1, 0]"}},
       .value = Rgba{0, 0, 0, 0}},
      {.extreme = "shininess = 3e38, roughness = 0", .material = {{"shininess", "3e38"}, {"roughness", "0"}}},
      {.extreme = "shininess = 1e-38, roughness = 1e-38", .material = {{"shininess", "1e-38"}, {"roughness", "1e-38"}}},
      {.extreme = "shininess = -3e38, roughness = 3e38", .material = {{"shininess", "-3e38"}, {"roughness", "3e38"}}},
      {.extreme = "roughness = 1", .material = {{"roughness", "1"}}},
      {.extreme = "all-black textures",
       .material = sameValue({"mixMap", "albedoMap1", "albedoMap2", "normalMap1", "normalMap2"}, R"("black")")},
      {.extreme = "all-white textures",
       .material = sameValue({"mixMap", "albedoMap1", "albedoMap2", "normalMap1", "normalMap2"}, R"("white")")},
      {.extreme = "UVs in [-3.25, 4.25] (uv_outside.gltf), clamp addressing",
       .material = {{"mixMap", R"("noiseClamped")"},
                    {"albedoMap1", R"("grassClamped")"},
                    {"albedoMap2", R"("rockClamped")"},
                    {"normalMap1", R"("normalsClamped")"},
                    {"normalMap2", R"("normalsClamped")"}},
       .mesh = "uvOutside"},
  });
  return cases;
}

// The decision files Terrain runs under: the example's three, and two that
// light per vertex, where `cameraPos - vert_pos` is evaluated exactly at the
// vertices and so is exactly zero in the camera-at-a-vertex case.
const std::vector<fs::path>& terrainDecisions() {
  static const std::vector<fs::path> files = {
      kSourceDir / "examples/decisions/terrain_full_quality.decisions",
      kSourceDir / "examples/decisions/terrain_baked_albedo.decisions",
      kSourceDir / "examples/decisions/terrain_baked_vertex_normal.decisions",
      kDataDir / "terrain_vertex_basic.decisions",
      kDataDir / "terrain_vertex_ggx.decisions",
  };
  return files;
}

// 17x17 pixels straight down onto a 2x2 plane (4x4 quads), which covers the
// whole image; odd, so that the central pixel's centre lies on the view axis,
// right above the plane's central vertex. Textures and meshes are loaded only
// where an instance uses them.
std::string sceneJson(std::string_view mesh, std::string_view source, std::string_view shader,
                      std::string_view material) {
  std::ostringstream json;
  json << R"({
  "resolution": [17, 17], "frames": 1, "warmupFrames": 0,
  "camera": {"fovY": 45, "up": [0, 0, -1], "views": [{"position": [0, 2, 0], "target": [0, 0, 0]}]},
  "light": {"direction": [0.4, 1.0, 0.3]},
  "meshes": {"plane": {"type": "plane", "size": 2, "resolution": 4},
             "uvOutside": {"type": "gltf", "file": "uv_outside.gltf"}},
  "textures": {
    "black": {"type": "solid", "size": 4, "color": [0, 0, 0, 0]},
    "white": {"type": "solid", "size": 4, "color": [1, 1, 1, 1]},
    "noise": {"type": "noise", "size": 32, "seed": 3, "octaves": 3},
    "grass": {"type": "noise", "size": 32, "seed": 11, "octaves": 3, "color": [0.42, 0.62, 0.2], "color2": [0.12, 0.3, 0.08]},
    "rock": {"type": "noise", "size": 32, "seed": 23, "octaves": 3, "color": [0.58, 0.53, 0.48], "color2": [0.3, 0.25, 0.2]},
    "normals": {"type": "normalMap", "size": 32, "seed": 5, "strength": 2.5},
    "noiseClamped": {"type": "noise", "size": 32, "seed": 3, "octaves": 3, "address": "clamp"},
    "grassClamped": {"type": "noise", "size": 32, "seed": 11, "octaves": 3, "color": [0.42, 0.62, 0.2], "color2": [0.12, 0.3, 0.08], "address": "clamp"},
    "rockClamped": {"type": "noise", "size": 32, "seed": 23, "octaves": 3, "color": [0.58, 0.53, 0.48], "color2": [0.3, 0.25, 0.2], "address": "clamp"},
    "normalsClamped": {"type": "normalMap", "size": 32, "seed": 5, "strength": 2.5, "address": "clamp"},
    "surface": {"type": "pack", "channels": ["normals.r", "normals.g", "noise.r", "rock.r"]},
    "ggxLut": {"type": "ggxLut", "size": 64}
  },
  "instances": [{"mesh": ")"
       << mesh << R"(", "source": ")" << source << R"(", "shader": ")" << shader << R"(", "material": )" << material
       << "}]\n}\n";
  return json.str();
}

std::string materialJson(const std::map<std::string, std::string>& bindings) {
  std::string json = "{";
  for (const auto& [name, value] : bindings) {
    if (json.size() > 1) json += ", ";
    json += "\"" + name + "\": " + value;
  }
  return json + "}";
}

size_t coveredPixels(const Capture& capture) {
  size_t covered = 0;
  for (uint8_t c : capture.coverage) covered += c != 0 ? 1 : 0;
  return covered;
}

// The hazards as the engine reports them: spire-demo counts NaN and Inf
// pixels with measure::compareImages.
measure::ImageError hazardsOf(const Capture& capture) {
  auto error = measure::compareImages(capture.color, capture.color, &capture.coverage);
  EXPECT_TRUE(error) << error.error().message;
  return error ? *error : measure::ImageError{};
}

std::string pixelText(const Capture& capture, size_t pixel) {
  const float* p = &capture.color.rgba[pixel * 4];
  return "pixel (" + std::to_string(pixel % capture.color.width) + ", " + std::to_string(pixel / capture.color.width) +
         ") = (" + std::to_string(p[0]) + ", " + std::to_string(p[1]) + ", " + std::to_string(p[2]) + ", " +
         std::to_string(p[3]) + ")";
}

// Every covered pixel finite, and equal to `value` where one is given, to a
// relative `tolerance` (the shaders compute in float, in another order than
// the constants above).
void expectFiniteEverywhere(const Capture& capture, const std::optional<Rgba>& value, float tolerance = 1e-4F) {
  EXPECT_EQ(coveredPixels(capture), capture.coverage.size()) << "the plane must cover the whole image";
  const measure::ImageError hazards = hazardsOf(capture);
  EXPECT_EQ(hazards.nanPixels, 0U);
  EXPECT_EQ(hazards.infPixels, 0U);
  for (size_t i = 0; i < capture.coverage.size(); ++i) {
    if (capture.coverage[i] == 0) continue;
    for (size_t c = 0; c < 4; ++c) {
      const float got = capture.color.rgba[i * 4 + c];
      bool ok = std::isfinite(got);
      if (ok && value) ok = std::abs(got - (*value)[c]) <= 1e-6F + tolerance * std::abs((*value)[c]);
      if (!ok) {
        ADD_FAILURE() << pixelText(capture, i)
                      << (value ? ", expected (" + std::to_string((*value)[0]) + ", " + std::to_string((*value)[1]) +
                                      ", " + std::to_string((*value)[2]) + ", " + std::to_string((*value)[3]) + ")"
                                : std::string(", expected finite"));
        return;  // one pixel tells the story; the others would repeat it
      }
    }
  }
}

class StabilityTest : public vk::testing::DeviceTest {
 protected:
  // Renders view 0 of `json`, a scene as if in tests/data/engine/stability,
  // with `decisions` for every instance; reports the failure and returns
  // nothing when the scene does not load, compile or render.
  static std::optional<Capture> render(const std::string& json, const std::optional<fs::path>& decisions) {
    SourceManager sources;
    DiagnosticList diags;
    const auto scene = scene::parseSceneFile("stability_scene.json", json, kDataDir, sources, diags);
    if (!scene) {
      ADD_FAILURE() << renderDiagnostics(sources, diags, DiagnosticFormat::Text);
      return std::nullopt;
    }
    SceneRenderer renderer(ctx(), *scene, diags);
    auto programs = renderer.compile(decisions);
    if (!programs) {
      ADD_FAILURE() << programs.error().message << "\n" << programs.error().details;
      return std::nullopt;
    }
    auto prepared = renderer.prepare(*programs);
    if (!prepared) {
      ADD_FAILURE() << prepared.error().message << "\n" << renderDiagnostics(sources, diags, DiagnosticFormat::Text);
      return std::nullopt;
    }
    auto capture = renderer.capture(*prepared, scene->camera.views.front());
    if (!capture) {
      ADD_FAILURE() << capture.error().message;
      return std::nullopt;
    }
    return std::move(capture).value();
  }

  // Renders an example shader (`source`, relative to the test data) under
  // `decisions` once per case, its material `base` with the case's bindings
  // over it, and expects every covered pixel finite.
  static void expectFiniteCases(std::string_view shader, std::string_view source,
                                const std::map<std::string, std::string>& base, const std::vector<ExampleCase>& cases,
                                const fs::path& decisions) {
    for (const ExampleCase& example : cases) {
      std::map<std::string, std::string> material = base;
      for (const auto& [name, value] : example.material) material[name] = value;
      const std::string bindings = materialJson(material);
      SCOPED_TRACE(std::string(shader) + ", " + std::string(example.extreme) + ": " + bindings);
      const auto capture = render(sceneJson(example.mesh, source, shader, bindings), decisions);
      if (capture) expectFiniteEverywhere(*capture, example.value);
    }
  }
};

// One test per stdlib function, running every case of the table for it.
class StdlibStabilityTest : public StabilityTest, public ::testing::WithParamInterface<std::string> {};

TEST_P(StdlibStabilityTest, FiniteAtTheExtremes) {
  size_t cases = 0;
  for (const ProbeCase& probe : probeCases()) {
    if (probe.function != GetParam()) continue;
    ++cases;
    SCOPED_TRACE(std::string(probe.function) + ", " + std::string(probe.extreme) + ": " + std::string(probe.shader) +
                 " " + std::string(probe.material));
    const auto capture = render(sceneJson("plane", "probes.spire", probe.shader, probe.material), std::nullopt);
    if (!capture) continue;
    if (probe.outcome == Outcome::Finite) {
      expectFiniteEverywhere(*capture, probe.value, probe.tolerance);
    } else {
      const measure::ImageError hazards = hazardsOf(*capture);
      EXPECT_EQ(hazards.nanPixels, 0U);
      EXPECT_EQ(hazards.infPixels, coveredPixels(*capture));
      EXPECT_GT(hazards.infPixels, 0U);
    }
  }
  EXPECT_GT(cases, 0U);
}

std::vector<std::string> testedFunctions() {
  std::vector<std::string> functions;
  for (const ProbeCase& probe : probeCases()) {
    if (std::find(functions.begin(), functions.end(), probe.function) == functions.end()) {
      functions.emplace_back(probe.function);
    }
  }
  return functions;
}

INSTANTIATE_TEST_SUITE_P(Stdlib, StdlibStabilityTest, ::testing::ValuesIn(testedFunctions()),
                         [](const ::testing::TestParamInfo<std::string>& param) { return param.param; });

// A function added to stdlib/ without cases in the table fails here.
TEST(StabilityTable, CoversEveryStdlibFunction) {
  const std::regex definition(R"(^(?:float|int|uint|bool|[biu]?vec[234]|mat[234])\s+(\w+)\s*\()");
  std::set<std::string> defined;
  for (const auto& entry : fs::directory_iterator(kSourceDir / "stdlib")) {
    if (entry.path().extension() != ".spire") continue;
    std::ifstream in(entry.path());
    for (std::string line; std::getline(in, line);) {
      std::smatch match;
      if (std::regex_search(line, match, definition)) defined.insert(match[1].str());
    }
  }
  ASSERT_TRUE(defined.count("phong") && defined.count("ggx")) << "the scan of stdlib/ no longer sees its functions";
  const std::vector<std::string> tested = testedFunctions();
  for (const std::string& function : defined) {
    EXPECT_TRUE(std::find(tested.begin(), tested.end(), function) != tested.end())
        << function << " (stdlib/) has no cases in probeCases()";
  }
}

// One test per decision file, running every Terrain case under it.
class TerrainStabilityTest : public StabilityTest, public ::testing::WithParamInterface<fs::path> {};

TEST_P(TerrainStabilityTest, FiniteAtTheExtremes) {
  expectFiniteCases("Terrain", "../../../../examples/terrain.spire", kTerrainMaterial, terrainCases(), GetParam());
}

INSTANTIATE_TEST_SUITE_P(Terrain, TerrainStabilityTest, ::testing::ValuesIn(terrainDecisions()),
                         [](const ::testing::TestParamInfo<fs::path>& param) { return param.param.stem().string(); });

// The Couch example (examples/couch.spire) at the extremes, as Terrain
// above: `material` replaces bindings of kCouchMaterial or adds the
// engine-supplied lightDir and cameraPos. Its parameters with a natural range
// (amounts, roughness) are driven to both ends of it; sizes and densities to
// zero and far beyond any sensible value.
const std::map<std::string, std::string> kCouchMaterial = {{"leatherColorMap", R"("rock")"},
                                                           {"grainNormalMap", R"("normals")"},
                                                           {"surfaceMaps", R"("surface")"},
                                                           {"ggxLut", R"("ggxLut")"},
                                                           {"leatherTint", "[1, 1, 1]"},
                                                           {"wornTint", "[0.62, 0.42, 0.27]"},
                                                           {"dirtColor", "[0.07, 0.05, 0.04]"},
                                                           {"threadColor", "[0.7, 0.62, 0.48]"},
                                                           {"studColor", "[0.95, 0.76, 0.42]"},
                                                           {"panelCount", "2"},
                                                           {"grainTiling", "8"},
                                                           {"grainStrength", "0.4"},
                                                           {"wearAmount", "0.4"},
                                                           {"dirtAmount", "0.5"},
                                                           {"seamWidth", "0.02"},
                                                           {"stitchDensity", "24"},
                                                           {"studSize", "0.08"},
                                                           {"leatherRoughness", "0.38"},
                                                           {"wornRoughness", "0.28"},
                                                           {"studRoughness", "0.3"},
                                                           {"occlusionStrength", "0.8"},
                                                           {"sheenColor", "[0.3, 0.24, 0.18]"},
                                                           {"skyColor", "[0.5, 0.55, 0.65]"},
                                                           {"groundColor", "[0.2, 0.17, 0.14]"}};

const std::vector<ExampleCase>& couchCases() {
  static const std::vector<ExampleCase> cases = withCameraAndLightCases({
      {.extreme = "the test's own values", .material = {}},
      {.extreme = "light below the horizon: lightDir = (0, -1, 0)", .material = {{"lightDir", "[0, -1, 0]"}}},
      {.extreme = "every roughness exactly 0",
       .material = sameValue({"leatherRoughness", "wornRoughness", "studRoughness"}, "0")},
      {.extreme = "every roughness exactly 1",
       .material = sameValue({"leatherRoughness", "wornRoughness", "studRoughness"}, "1")},
      {.extreme = "no wear, dirt, occlusion or grain",
       .material = sameValue({"wearAmount", "dirtAmount", "occlusionStrength", "grainStrength"}, "0")},
      {.extreme = "full wear, dirt and occlusion",
       .material = sameValue({"wearAmount", "dirtAmount", "occlusionStrength"}, "1")},
      {.extreme = "no panels, seams, stitches or studs",
       .material = sameValue({"panelCount", "seamWidth", "stitchDensity", "studSize", "grainTiling"}, "0")},
      {.extreme = "panels, stitches and grain repeats of 1e30, seams and studs of 1e-30",
       .material = {{"panelCount", "1e30"},
                    {"stitchDensity", "1e30"},
                    {"grainTiling", "1e30"},
                    {"seamWidth", "1e-30"},
                    {"studSize", "1e-30"}}},
      {.extreme = "seams and studs of 3e38: the whole surface is seam",
       .material = sameValue({"seamWidth", "studSize"}, "3e38")},
      {.extreme = "grain strength 3e38", .material = {{"grainStrength", "3e38"}}},
      {.extreme = "all-black textures",
       .material = sameValue({"leatherColorMap", "grainNormalMap", "surfaceMaps"}, R"("black")")},
      {.extreme = "all-white textures",
       .material = sameValue({"leatherColorMap", "grainNormalMap", "surfaceMaps"}, R"("white")")},
  });
  return cases;
}

class CouchStabilityTest : public StabilityTest, public ::testing::WithParamInterface<fs::path> {};

TEST_P(CouchStabilityTest, FiniteAtTheExtremes) {
  expectFiniteCases("Couch", "../../../../examples/couch.spire", kCouchMaterial, couchCases(), GetParam());
}

// The example's four decision files: every surface component per fragment
// with GGX or the GGX lookup table, per vertex, and baked with Blinn-Phong.
std::vector<fs::path> couchDecisions() {
  std::vector<fs::path> files;
  for (const char* name : {"full_quality", "ggx_lut", "vertex_surface", "baked_phong"}) {
    files.push_back(kSourceDir / "examples/decisions/couch" / (std::string(name) + ".decisions"));
  }
  return files;
}

INSTANTIATE_TEST_SUITE_P(Couch, CouchStabilityTest, ::testing::ValuesIn(couchDecisions()),
                         [](const ::testing::TestParamInfo<fs::path>& param) { return param.param.stem().string(); });

// A user's component divides by a uniform bound to 0 (user_divide.json): no
// library guard can prevent that, so the engine must count every such pixel
// and spire-demo must name the variant and the counts in its warning.
TEST_F(StabilityTest, UsersDivisionByZeroIsCountedAndNamed) {
  const fs::path scenePath = kDataDir / "user_divide.json";
  std::ifstream in(scenePath);
  const std::string json{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  ASSERT_FALSE(json.empty());

  // 0.5 / 0 is Inf and 0 / 0 is NaN, in every covered pixel.
  const auto inf = render(json, kDataDir / "user_divide_fragment.decisions");
  ASSERT_TRUE(inf);
  const measure::ImageError infHazards = hazardsOf(*inf);
  const size_t covered = coveredPixels(*inf);
  ASSERT_GT(covered, 0U);
  EXPECT_EQ(infHazards.infPixels, covered);
  EXPECT_EQ(infHazards.nanPixels, 0U);
  const std::string color = "[0.5, 0.5, 0.5, 1.0]";
  std::string zeroColor = json;
  ASSERT_NE(zeroColor.find(color), std::string::npos);
  zeroColor.replace(zeroColor.find(color), color.size(), "[0.0, 0.0, 0.0, 0.0]");
  const auto nan = render(zeroColor, kDataDir / "user_divide_fragment.decisions");
  ASSERT_TRUE(nan);
  EXPECT_EQ(hazardsOf(*nan).nanPixels, coveredPixels(*nan));

  const fs::path outputDir = fs::temp_directory_path() / ("spire_stability_user_divide_" + std::to_string(::getpid()));
  std::ostringstream out;
  std::ostringstream err;
  ASSERT_EQ(demo::runDemo({scenePath.string(), "--validation", "-o", outputDir.string()}, out, err), 0) << err.str();
  fs::remove_all(outputDir);
  EXPECT_NE(err.str().find("spire-demo: warning: variant 'divide_per_fragment' produced 0 NaN and " +
                           std::to_string(covered) + " Inf pixels; its error is infinite\n"),
            std::string::npos)
      << err.str();
  // Per vertex, the Inf results are interpolated, which may turn some into
  // NaN (Inf - Inf); every covered pixel is still one or the other.
  const std::regex vertexWarning(R"(variant 'divide_per_vertex' produced (\d+) NaN and (\d+) Inf pixels)");
  std::smatch match;
  const std::string errText = err.str();
  ASSERT_TRUE(std::regex_search(errText, match, vertexWarning)) << errText;
  EXPECT_EQ(std::stoul(match[1].str()) + std::stoul(match[2].str()), covered) << errText;
}

// Hazard attribution (tool/hazard_diagnosis.h) in each kind of world: the
// division by a zero uniform placed per fragment, per vertex and in the
// texture bake. Each variant's report names `scaled` in the world that
// computes it, with the divisor's value there; where another world only
// carries the non-finite value on, that is said and listed after the origin.
TEST_F(StabilityTest, HazardsAreTracedToTheComponentAndInputInEveryWorld) {
  const fs::path outputDir = fs::temp_directory_path() / ("spire_stability_attribution_" + std::to_string(::getpid()));
  std::ostringstream out;
  std::ostringstream err;
  std::vector<std::string> args{(kDataDir / "user_divide.json").string(), "--validation", "-o", outputDir.string()};
  for (const char* v : {"user_divide_fragment", "user_divide_vertex", "user_divide_texture"}) {
    args.push_back("--variant");
    args.push_back((kDataDir / (std::string(v) + ".decisions")).string());
  }
  ASSERT_EQ(demo::runDemo(args, out, err), 0) << err.str();
  std::ifstream reportFile(outputDir / "report.md");
  const std::string report{std::istreambuf_iterator<char>(reportFile), std::istreambuf_iterator<char>()};
  fs::remove_all(outputDir);
  const std::string text = err.str();
  const std::string tail =
      " at `color / divisor` (user_divide.spire:18:19); color = (0.5, 0.5, 0.5, 1), divisor = 0 there [instance 0 "
      "(UserDivide), first at ";
  EXPECT_NE(text.find("hazard: variant 'user_divide_fragment', camera view 0: scaled (Fragment) went Inf in 289 px" +
                      tail + "pixel"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("hazard: variant 'user_divide_vertex', camera view 0: scaled (Vertex) went Inf in 25 vertices" +
                      tail + "vertex"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("hazard: variant 'user_divide_texture', camera view 0: scaled (PrebakeTex) went Inf in "),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("texels" + tail + "texel ("), std::string::npos) << text;
  // Per vertex, Fragment's output only carries the interpolated NaN on: after the origin.
  const size_t origin = text.find("'user_divide_vertex', camera view 0: scaled (Vertex)");
  const size_t carried = text.find("'user_divide_vertex', camera view 0: output (Fragment) went NaN");
  ASSERT_NE(carried, std::string::npos) << text;
  EXPECT_LT(origin, carried);
  const std::string carriedLine = text.substr(carried, text.find('\n', carried) - carried);
  EXPECT_NE(carriedLine.find("(it came in with its input)"), std::string::npos) << carriedLine;
  // Nor is the operation the NaN went through named: it did not go wrong there.
  EXPECT_EQ(carriedLine.find(" at `"), std::string::npos) << carriedLine;
  EXPECT_NE(report.find("## Hazards"), std::string::npos) << report;
  EXPECT_NE(report.find("- scaled (Vertex) went Inf in 25 vertices"), std::string::npos) << report;
}

// Inside a component's body, the report names the first operation to go
// non-finite: a division inside the function a component calls (not the
// call), a built-in's domain (log of a negative number) in Vertex, a
// product that overflowed; and a division whose Inf an earlier component
// clamped away is not blamed.
TEST_F(StabilityTest, HazardsNameTheOperationInTheComponentOrFunction) {
  const fs::path outputDir = fs::temp_directory_path() / ("spire_stability_operation_" + std::to_string(::getpid()));
  std::ostringstream out;
  std::ostringstream err;
  ASSERT_EQ(demo::runDemo({(kDataDir / "operation_hazard.json").string(), "--validation", "-o", outputDir.string()},
                          out, err),
            0)
      << err.str();
  fs::remove_all(outputDir);
  const std::string text = err.str();
  // The first pixel to fail is the first the device ran, which lavapipe's
  // threads may change from run to run: any pixel of the image.
  const std::string exponent =
      R"(camera view 0: exponent \(Fragment\) went Inf in 289 px at `2\.0 / k` \(operation_hazard\.spire:23:12\); )"
      R"(roughness = 0, clampedInverse = 100 there \[instance 0 \(OperationHazard\), first at pixel \(\d+, \d+\), )"
      R"(defined at operation_hazard\.spire:33\])";
  EXPECT_TRUE(std::regex_search(text, std::regex("variant 'operation_per_fragment', " + exponent))) << text;
  EXPECT_TRUE(std::regex_search(text, std::regex("variant 'operation_per_vertex', " + exponent))) << text;
  EXPECT_NE(text.find("variant 'operation_per_vertex', camera view 0: logged (Vertex) went NaN in 25 vertices at "
                      "`log(color.r - 1.0)` (operation_hazard.spire:34:20); color = (0.5, 0.5, 0.5, 1) there"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("variant 'operation_overflow', camera view 0: overflowed (Vertex) went Inf in 25 vertices at "
                      "`color.g * 1e30 * 1e30` (operation_hazard.spire:35:24); color = (0.5, 0.5, 0.5, 1) there"),
            std::string::npos)
      << text;
  EXPECT_EQ(text.find("1.0 / roughness"), std::string::npos) << text;
}

// The uniform bake runs over samples of the mesh's surface, and its hazards
// are counted and located in those samples, not in vertices.
TEST_F(StabilityTest, AUniformBakeHazardIsCountedInSurfaceSamples) {
  const fs::path outputDir = fs::temp_directory_path() / ("spire_stability_per_object_" + std::to_string(::getpid()));
  std::ostringstream out;
  std::ostringstream err;
  ASSERT_EQ(
      demo::runDemo({(kDataDir / "user_divide_per_object.json").string(), "--validation", "-o", outputDir.string()},
                    out, err),
      0)
      << err.str();
  fs::remove_all(outputDir);
  const std::string text = err.str();
  EXPECT_NE(text.find("scaled (PrebakeUniform) went Inf in "), std::string::npos) << text;
  // Any sample may be the first to fail: the first the device ran.
  EXPECT_TRUE(std::regex_search(
      text, std::regex(R"( surface samples at `color / divisor` \(user_divide_per_object\.spire:13:19\); color = )"
                       R"(\(0\.5, 0\.5, 0\.5, 1\), divisor = 0 there \[instance 0 \(UserDividePerObject\), )"
                       R"(first at surface sample \d+, )")))
      << text;
}

// A variant that averages the position per object (collapse.json) draws
// every vertex on one point and covers nothing: spire-demo flags its image
// as degenerate (no speedup in the table, the report or the caption) and
// says why, instead of reporting it as the fastest variant.
TEST_F(StabilityTest, ACollapsedImageIsFlaggedNotASpeedup) {
  const fs::path outputDir = fs::temp_directory_path() / ("spire_stability_collapse_" + std::to_string(::getpid()));
  std::ostringstream out;
  std::ostringstream err;
  ASSERT_EQ(demo::runDemo({(kDataDir / "collapse.json").string(), "--validation", "-o", outputDir.string()}, out, err),
            0)
      << err.str();
  EXPECT_NE(err.str().find("spire-demo: warning: variant 'per_object' covers 0% of the pixels 'per_vertex' covers: "
                           "its image is degenerate"),
            std::string::npos)
      << err.str();
  EXPECT_EQ(err.str().find("variant 'per_vertex' covers"), std::string::npos) << err.str();
  const std::regex degenerateRow(R"(per_object +[0-9.]+ +[0-9.]+ +[0-9.]+ +degenerate )");
  const std::string table = out.str();
  EXPECT_TRUE(std::regex_search(table, degenerateRow)) << table;
  std::ifstream report(outputDir / "report.md");
  const std::string reportText{std::istreambuf_iterator<char>(report), std::istreambuf_iterator<char>()};
  EXPECT_NE(reportText.find("| degenerate |"), std::string::npos) << reportText;
  fs::remove_all(outputDir);
}

}  // namespace
}  // namespace spire::engine
