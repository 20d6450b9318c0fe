// The level-of-detail library for instanced drawing (examples/lod_levels.spire,
// the Spire paper's section 7.2) with the four materials of
// examples/lod_materials.spire: the locked levels LodMQ and LodLQ give every
// material the same Vertex and Fragment kernels (equal keys), so an engine
// can batch them; LodHQ gives each material kernels of its own.
#include <gtest/gtest.h>

#include <map>

#include "driver/compiler.h"
#include "driver/shader_library.h"
#include "support/diagnostic_renderer.h"

namespace spire {
namespace {

const std::vector<std::string> kMaterials = {"TerrainLod", "Barrel", "Sofa", "Rock"};
const std::vector<std::string> kLevels = {"LodHQ", "LodMQ", "LodLQ"};

// material -> level -> world -> key.
using Keys = std::map<std::string, std::map<std::string, std::map<std::string, std::string>>>;

Keys compileAll() {
  ShaderLibrary library;
  EXPECT_TRUE(library.addFile(std::string(SPIRE_SOURCE_DIR) + "/examples/lod_materials.spire"));
  EXPECT_TRUE(library.compile()) << renderDiagnostics(library.sources(), library.diagnostics(), DiagnosticFormat::Text);
  Keys keys;
  for (const std::string& material : kMaterials) {
    for (const std::string& level : kLevels) {
      const std::string shader = material + "<" + level + ">";
      // Default options: SPIR-V made and validated.
      const auto compiled = compileVariant(library, shader, Decisions{});
      EXPECT_TRUE(compiled) << shader << ": " << (compiled ? "" : compiled.error().message);
      if (!compiled) continue;
      for (const reflection::Kernel& kernel : (*compiled)->reflection.kernels) {
        keys[material][level][kernel.world] = kernel.key;
      }
    }
  }
  return keys;
}

const Keys& keys() {
  static const Keys all = compileAll();
  return all;
}

TEST(LodLevels, EveryMaterialHasEveryLevel) {
  ShaderLibrary library;
  ASSERT_TRUE(library.addFile(std::string(SPIRE_SOURCE_DIR) + "/examples/lod_materials.spire"));
  ASSERT_TRUE(library.compile());
  // No optional member was left out (W4101).
  const std::vector<std::string> names = library.shaderNames();
  for (const std::string& material : kMaterials) {
    for (const std::string& level : kLevels) {
      const std::string shader = material + "<" + level + ">";
      EXPECT_NE(std::find(names.begin(), names.end(), shader), names.end()) << shader;
    }
  }
}

TEST(LodLevels, LockedLevelsShareVertexAndFragmentKernels) {
  for (const std::string level : {"LodMQ", "LodLQ"}) {
    for (const std::string world : {"Vertex", "Fragment"}) {
      const std::string& first = keys().at(kMaterials[0]).at(level).at(world);
      EXPECT_EQ(first.size(), 16u);
      for (const std::string& material : kMaterials) {
        EXPECT_EQ(keys().at(material).at(level).at(world), first) << material << "<" << level << "> " << world;
      }
    }
  }
  // The two locked levels are different kernels.
  EXPECT_NE(keys().at("Rock").at("LodMQ").at("Fragment"), keys().at("Rock").at("LodLQ").at("Fragment"));
}

TEST(LodLevels, HighDetailKernelsAreEachMaterialsOwn) {
  // The materials' Fragment kernels differ pairwise (their Vertex kernels
  // may coincide: they only pass mesh attributes on).
  for (size_t a = 0; a < kMaterials.size(); ++a) {
    for (size_t b = a + 1; b < kMaterials.size(); ++b) {
      EXPECT_NE(keys().at(kMaterials[a]).at("LodHQ").at("Fragment"),
                keys().at(kMaterials[b]).at("LodHQ").at("Fragment"))
          << kMaterials[a] << " and " << kMaterials[b];
    }
    // Nor is a material's high-detail kernel a locked one.
    EXPECT_NE(keys().at(kMaterials[a]).at("LodHQ").at("Fragment"), keys().at(kMaterials[a]).at("LodMQ").at("Fragment"));
  }
}

}  // namespace
}  // namespace spire
