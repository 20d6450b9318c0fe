// A small level-of-detail scene for tests that need one on the device: the
// four materials of examples/lod_materials.spire on a 12-unit terrain, the
// terrain itself plus copies of a barrel, a sofa and a rock (scattered, or
// with `scatter` false one of each at a fixed place), drawn at 96 x 64; and
// a box of a group with a member that cannot cross-fade.
#pragma once

#include <fmt/format.h>

#include <filesystem>
#include <string>

namespace spire::testing {

struct LodTestScene {
  bool scatter = true;
  // The camera's views, as the scene file's "views" array holds them.
  std::string views = R"([{"position": [0, 9, 13], "target": [0, 0, 0]}])";
  std::string policy = "unused.json";  // the "lod" policy path, relative to the scene file
};

inline std::string lodTestSceneJson(const LodTestScene& options = {}) {
  const std::string materials =
      (std::filesystem::path(SPIRE_SOURCE_DIR) / "examples/lod_materials.spire").generic_string();
  const auto placed = [&](const char* mesh, const char* shader, int seed, const char* at, const char* material) {
    const std::string where = options.scatter
                                  ? fmt::format(R"("scatter": {{"count": 12, "seed": {}, "on": "hills"}})", seed)
                                  : fmt::format(R"("transform": {{"translate": {}}})", at);
    return fmt::format(R"(, {{"mesh": "{}", "source": "{}", "shader": "{}", {}, "material": {}}})", mesh, materials,
                       shader, where, material);
  };
  return fmt::format(R"({{"resolution": [96, 64], "frames": 2, "warmupFrames": 1, "clearColor": [0, 0, 0, 1],
  "camera": {{"fovY": 60, "far": 100, "views": {}}},
  "lod": {{"policy": "{}", "blocks": {}}},)",
                     options.views, options.policy, options.scatter ? 2 : 1) +
         R"(
  "meshes": {"hills": {"type": "terrain", "size": 12, "resolution": 16, "height": 0.5, "seed": 3},
             "barrel": {"type": "cylinder", "radius": 0.4, "height": 1.0, "segments": 12},
             "sofa": {"type": "box", "size": 0.8, "height": 0.5},
             "rock": {"type": "rock", "radius": 0.5, "rings": 6, "segments": 12, "seed": 4}},
  "textures": {"n": {"type": "noise", "size": 32, "seed": 9, "octaves": 3},
               "c": {"type": "noise", "size": 32, "seed": 2, "color": [0.8, 0.3, 0.1], "color2": [0.1, 0.2, 0.6]},
               "nm": {"type": "normalMap", "size": 32, "seed": 5}},
  "instances": [{"mesh": "hills", "source": ")" +
         materials +
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

// The policy file of the library's three levels.
inline std::string lodTestPolicyJson(float hqUntil = 6.0F, float mqUntil = 14.0F) {
  return fmt::format(R"({{"levels": [{{"member": "LodHQ", "until": {}}}, {{"member": "LodMQ", "until": {}}},
  {{"member": "LodLQ"}}], "hysteresis": 0.1, "transitionFrames": 4}})",
                     hqUntil, mqUntil);
}

// A box drawn by the group of tests/data/engine/lod_fades.spire, whose
// member Fades reads lodFade and Opaque does not, seen from two views at
// `size` x `size`, with the policy file `policy` (relative to the scene).
inline std::string lodFadesSceneJson(const std::string& policy, int size) {
  return fmt::format(
      R"({{"resolution": [{0}, {0}], "frames": 2,
  "camera": {{"views": [{{"position": [0, 3, 3], "target": [0, 0, 0]}}, {{"position": [0, 9, 9], "target": [0, 0, 0]}}]}},
  "lod": {{"policy": "{1}", "blocks": 1}},
  "meshes": {{"box": {{"type": "box", "size": 1}}}},
  "instances": [{{"mesh": "box", "source": "{2}", "shader": "Thing"}}]}})",
      size, policy, (std::filesystem::path(SPIRE_SOURCE_DIR) / "tests/data/engine/lod_fades.spire").generic_string());
}

}  // namespace spire::testing
