#include "driver/shader_library.h"

#include <gtest/gtest.h>

namespace spire {
namespace {

class ShaderLibraryTest : public testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(library.addFile(std::string(SPIRE_SOURCE_DIR) + "/examples/terrain.spire"));
    ASSERT_TRUE(library.addFile(std::string(SPIRE_SOURCE_DIR) + "/examples/lod_library.spire"));
    ASSERT_TRUE(library.compile());
  }
  ShaderLibrary library;
};

TEST_F(ShaderLibraryTest, ListsConcreteShaders) {
  EXPECT_EQ(library.shaderNames(),
            (std::vector<std::string>{"Terrain", "TerrainLOD<BaseMaterialHQ>", "TerrainLOD<BaseMaterialLQ>"}));
}

TEST_F(ShaderLibraryTest, ChoicesAsData) {
  const std::vector<Choice> choices = library.choices("Terrain");
  ASSERT_EQ(choices.size(), 4u);
  EXPECT_EQ(choices[3].key, "Terrain.lighting");
  EXPECT_EQ(choices[3].names,
            (std::vector<std::string>{"Vertex:basic", "Fragment:basic", "Vertex:ggx", "Fragment:ggx"}));
  EXPECT_TRUE(library.choices("NoSuchShader").empty());
}

TEST_F(ShaderLibraryTest, VariantsFromInMemoryDecisionsWithoutReparsing) {
  const size_t files = library.sources().fileCount();
  const uint32_t exprs = library.frontEnd().program().exprCount;
  std::vector<std::string> skipped;
  const auto baked = library.buildVariant(
      "Terrain", {{"albedo", "PrebakeTex"}, {"lighting", "Vertex:basic"}, {"normal", "Fragment"}, {"bogus", "Vertex"}},
      &skipped);
  ASSERT_TRUE(baked);
  EXPECT_EQ(skipped, (std::vector<std::string>{"bogus", "normal"}));
  const graph::ShaderGraph& g = baked->graph();
  const sem::Pipeline& p = g.pipeline();
  const auto albedo = g.shader().componentByName.at("albedo");
  EXPECT_EQ(p.worlds[baked->worldOf(albedo)].name, "PrebakeTex");
  // The Fragment world samples albedo from the prebake texture.
  bool sampled = false;
  for (const graph::Transfer& t : baked->world(*p.findWorld("Fragment")).inputs) {
    sampled = sampled || (t.component == albedo && p.imports[t.importIndex].strategy.ref->name == "textureImport");
  }
  EXPECT_TRUE(sampled);
  for (int i = 0; i < 10; ++i) ASSERT_TRUE(library.buildVariant("Terrain", {{"lighting", "Fragment:ggx"}}));
  EXPECT_EQ(library.sources().fileCount(), files);
  EXPECT_EQ(library.frontEnd().program().exprCount, exprs);
}

}  // namespace
}  // namespace spire
