// The level-of-detail library for instanced drawing (examples/lod_levels.spire,
// the Spire paper's section 7.2) with the four materials of
// examples/lod_materials.spire: the locked levels LodMQ and LodLQ give every
// material the same Vertex and Fragment kernels (equal keys), so an engine
// can batch them; LodHQ gives each material kernels of its own. The locks,
// not world annotations, are what place the materials' components in the
// bakes: the same sources without them give each material kernels of its own.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>

#include "driver/compiler.h"
#include "driver/shader_library.h"
#include "support/diagnostic_renderer.h"

namespace spire {
namespace {

const std::vector<std::string> kMaterials = {"TerrainLod", "Barrel", "Sofa", "Rock"};
const std::vector<std::string> kLevels = {"LodHQ", "LodMQ", "LodLQ"};

// material -> level -> world -> key.
using Keys = std::map<std::string, std::map<std::string, std::map<std::string, std::string>>>;

// material -> level -> component -> world, for the group's components.
using Placements = std::map<std::string, std::map<std::string, std::map<std::string, std::string>>>;

struct Compiled {
  Keys keys;
  Placements placements;
};

Compiled compileAll(const std::string& materialsFile) {
  ShaderLibrary library;
  EXPECT_TRUE(library.addFile(materialsFile));
  EXPECT_TRUE(library.compile()) << renderDiagnostics(library.sources(), library.diagnostics(), DiagnosticFormat::Text);
  Compiled all;
  for (const std::string& material : kMaterials) {
    for (const std::string& level : kLevels) {
      const std::string shader = material + "<" + level + ">";
      // Default options: SPIR-V made and validated.
      const auto compiled = compileVariant(library, shader, Decisions{});
      EXPECT_TRUE(compiled) << shader << ": " << (compiled ? "" : compiled.error().message);
      if (!compiled) continue;
      for (const reflection::Kernel& kernel : (*compiled)->reflection.kernels) {
        all.keys[material][level][kernel.world] = kernel.key;
      }
      for (const auto& [component, world] : (*compiled)->reflection.placement) {
        all.placements[material][level][component] = world;
      }
    }
  }
  return all;
}

const Keys& keys() {
  static const Keys all = compileAll(std::string(SPIRE_SOURCE_DIR) + "/examples/lod_materials.spire").keys;
  return all;
}

// The library's sources copied with their layout (they reach each other by
// relative paths), every `finalizes` clause of lod_levels.spire deleted.
std::filesystem::path unlockedCopy() {
  namespace fs = std::filesystem;
  const fs::path root = fs::temp_directory_path() / ("spire_lod_unlocked_" + std::to_string(::getpid()));
  fs::remove_all(root);
  fs::create_directories(root);
  for (const char* folder : {"examples", "pipelines", "stdlib"}) {
    fs::copy(fs::path(SPIRE_SOURCE_DIR) / folder, root / folder, fs::copy_options::recursive);
  }
  const fs::path levels = root / "examples" / "lod_levels.spire";
  std::stringstream text;
  text << std::ifstream(levels).rdbuf();
  const std::string locked = text.str();
  const std::string unlocked = std::regex_replace(locked, std::regex(R"(\n\s*finalizes [A-Za-z, ]+\n)"), "\n");
  EXPECT_NE(unlocked, locked) << "no lock found to delete";
  std::ofstream(levels, std::ios::binary | std::ios::trunc) << unlocked;
  return root;
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

// What LodMQ reads per vertex (gloss) and everything LodLQ reads is not
// annotated with a world: the compiler places a material's definitions in
// the latest world that is not locked (paper section 6.2), the per-object
// bake. LodMQ's surface texture is the level's own, annotated PrebakeTex.
TEST(LodLevels, TheLocksPlaceTheMaterialsInTheBakes) {
  const Compiled locked = compileAll(std::string(SPIRE_SOURCE_DIR) + "/examples/lod_materials.spire");
  const std::filesystem::path copy = unlockedCopy();
  const Compiled unlocked = compileAll((copy / "examples" / "lod_materials.spire").string());
  std::filesystem::remove_all(copy);
  for (const std::string& material : kMaterials) {
    const auto& mq = locked.placements.at(material).at("LodMQ");
    EXPECT_EQ(mq.at("albedo"), "PrebakeTex");
    EXPECT_EQ(mq.at("specular"), "PrebakeTex");
    EXPECT_EQ(mq.at("gloss"), "PrebakeUniform");
    EXPECT_EQ(unlocked.placements.at(material).at("LodMQ").at("gloss"), "Vertex");
    for (const std::string component : {"albedo", "specular", "gloss"}) {
      EXPECT_EQ(locked.placements.at(material).at("LodLQ").at(component), "PrebakeUniform");
      EXPECT_EQ(unlocked.placements.at(material).at("LodLQ").at(component), "Vertex");
    }
  }
  // Unlocked, every material's lower levels are kernels of its own: the
  // Vertex kernel computes part of the material.
  for (size_t a = 0; a < kMaterials.size(); ++a) {
    for (size_t b = a + 1; b < kMaterials.size(); ++b) {
      for (const std::string level : {"LodMQ", "LodLQ"}) {
        EXPECT_NE(unlocked.keys.at(kMaterials[a]).at(level).at("Vertex"),
                  unlocked.keys.at(kMaterials[b]).at(level).at("Vertex"))
            << kMaterials[a] << " and " << kMaterials[b] << " at " << level;
        EXPECT_EQ(locked.keys.at(kMaterials[a]).at(level).at("Vertex"),
                  locked.keys.at(kMaterials[b]).at(level).at("Vertex"));
      }
    }
  }
}

}  // namespace
}  // namespace spire
