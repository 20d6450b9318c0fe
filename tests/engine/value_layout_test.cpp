// Host-side pieces of the renderer that need no device: GLSL value types and
// their std140/std430 placement, the values the engine supplies, the world
// table and the choice of bake formats.
#include <gtest/gtest.h>

#include <glm/ext/matrix_transform.hpp>

#include <cstring>

#include "renderer/bake_analysis.h"
#include "renderer/supplied_values.h"
#include "renderer/texture_bake.h"
#include "renderer/value_layout.h"
#include "renderer/world_roles.h"
#include "sema/attribute_catalog.h"

namespace spire::engine {
namespace {

BlockMember member(const char* type, uint32_t offset, uint32_t size, uint32_t arrayStride, uint32_t matrixStride) {
  return {"m", "m", reflection::parseValueType(type), offset, size, arrayStride, matrixStride};
}

// A std140 mat3 has 16-byte columns: the fourth float of each column is padding.
TEST(ValueLayout, WritesMatricesByColumnStride) {
  std::vector<std::byte> memory(64, std::byte{0xff});
  const BlockMember mat3 = member("mat3", 4, 48, 0, 16);
  const std::vector<double> values{1, 2, 3, 4, 5, 6, 7, 8, 9};
  writeValue(memory, mat3, values);
  float column1[4];
  std::memcpy(column1, memory.data() + 4 + 16, sizeof column1);
  EXPECT_EQ(column1[0], 4.0F);
  EXPECT_EQ(column1[2], 6.0F);
  EXPECT_EQ(readValue(memory, mat3), values);
  // Writes past the end are skipped rather than performed.
  const BlockMember outside = member("vec4", 56, 16, 0, 0);
  writeValue(memory, outside, std::vector<double>{1, 2, 3, 4});
  EXPECT_EQ(readValue(memory, outside).size(), 2U);
}

TEST(ValueLayout, WritesIntegersAndArraysWithStride) {
  std::vector<std::byte> memory(64);
  const BlockMember ints = member("int[2]", 0, 32, 16, 0);
  writeValue(memory, ints, std::vector<double>{-3, 7});
  int32_t second = 0;
  std::memcpy(&second, memory.data() + 16, sizeof second);
  EXPECT_EQ(second, 7);
  EXPECT_EQ(readValue(memory, ints), (std::vector<double>{-3, 7}));
}

TEST(SuppliedValues, FrameValuesAreInModelSpace) {
  FrameState frame;
  frame.cameraPosition = {0, 0, 10};
  frame.lightDirection = {0, 1, 0};
  const glm::mat4 model = glm::translate(glm::rotate(glm::mat4(1.0F), glm::radians(90.0F), {0, 0, 1}), {1, 0, 0});
  const auto light = frameValue("lightDir", frame, model);
  ASSERT_TRUE(light);
  EXPECT_EQ(light->type, "vec3");
  // The model rotates +x onto +y, so the world's up is the model's +x.
  EXPECT_NEAR(light->numbers[0], 1.0, 1e-6);
  EXPECT_NEAR(light->numbers[1], 0.0, 1e-6);
  EXPECT_EQ(frameValue("matMVP", frame, model)->numbers.size(), 16U);
  EXPECT_FALSE(frameValue("noSuchValue", frame, model));
  EXPECT_EQ(findMeshAttribute("vert_uv")->components, 2U);
  EXPECT_FALSE(findMeshAttribute("vert_color"));
}

TEST(WorldTable, NamesEveryWorldOfThePipelinesOnce) {
  for (const char* world : {"MeshVertex", "FrameUniform", "MaterialUniform", "PrebakeUniform", "PrebakeVertex",
                            "PrebakeTex", "Vertex", "Fragment"}) {
    EXPECT_NE(findWorldPass(world), nullptr) << world;
  }
  EXPECT_EQ(findWorldPass("ScreenSpace"), nullptr);
  EXPECT_EQ(findWorldPass("PrebakeTex")->stage, codegen::ShaderStage::Fragment);
  EXPECT_FALSE(findWorldPass("MeshVertex")->stage);
  for (const WorldPass& pass : worldPassTable()) EXPECT_EQ(findRole(pass.role), &pass) << pass.role;
}

TEST(WorldTable, RolesComeFromTheWorldsAttributes) {
  const auto renamed = resolveWorldPasses({{"Geometry", "mesh"}, {"Pixel", "fragment"}, {"Vertex", ""}, {"Other", ""}});
  ASSERT_TRUE(renamed) << renamed.error().message;
  EXPECT_EQ(renamed->at("Pixel")->kind, WorldRole::FragmentStage);
  EXPECT_EQ(renamed->at("Geometry")->kind, WorldRole::MeshAttributes);
  EXPECT_EQ(renamed->at("Vertex")->kind, WorldRole::VertexStage);  // known by its name
  EXPECT_FALSE(renamed->contains("Other"));

  const auto unknown = resolveWorldPasses({{"Pixel", "pixel"}});
  ASSERT_FALSE(unknown);
  EXPECT_NE(unknown.error().message.find("world 'Pixel' has [Role: \"pixel\"], which this engine does not implement"),
            std::string::npos)
      << unknown.error().message;
  EXPECT_NE(unknown.error().message.find("fragment (fragment shader of each frame's draw)"), std::string::npos);

  const auto twice = resolveWorldPasses({{"Fragment", ""}, {"Pixel", "fragment"}});
  ASSERT_FALSE(twice);
  EXPECT_NE(twice.error().message.find("worlds 'Fragment' and 'Pixel' both have the role 'fragment'"),
            std::string::npos)
      << twice.error().message;
}

TEST(BakeFormats, HintNamesMapToFormats) {
  EXPECT_EQ(bakeFormat("RGB10_A2"), VK_FORMAT_A2B10G10R10_UNORM_PACK32);
  EXPECT_EQ(bakeFormat("R8"), VK_FORMAT_R8_UNORM);
  EXPECT_FALSE(bakeFormat("BC7"));
  EXPECT_NE(bakeFormatNames().find("RGBA16F"), std::string::npos);
  // Every format the compiler lets a [Format] name, the engine can bake into.
  for (std::string_view name : sem::textureFormatNames()) EXPECT_TRUE(bakeFormat(name)) << name;
}

std::string formatFor(uint32_t channels, const std::vector<float>& rgba, bool* signedEncoding = nullptr) {
  const std::vector<uint8_t> coverage(rgba.size() / 4, 1);
  const BakeLayout layout = analyzeBakedValues("value", channels, rgba, coverage);
  if (signedEncoding) *signedEncoding = layout.signedEncoding;
  return layout.format;
}

TEST(BakeAnalysis, PicksTheSmallestFormatThatHoldsTheValues) {
  EXPECT_EQ(formatFor(1, {0.2F, 0, 0, 1, 0.9F, 0, 0, 1}), "R8");
  EXPECT_EQ(formatFor(2, {0.2F, 0.4F, 0, 1, 0.9F, 1, 0, 1}), "RG8");
  EXPECT_EQ(formatFor(4, {0.2F, 0.4F, 0.1F, 1, 0.9F, 1, 0, 0.5F}), "RGBA8");
  bool encoded = false;
  EXPECT_EQ(formatFor(3, {0, 0, 1, 1, 0.6F, -0.8F, 0, 1}, &encoded), "RGB10_A2");
  EXPECT_TRUE(encoded);
  EXPECT_EQ(formatFor(3, {0, 0, 2, 1, 0.6F, -0.8F, 0, 1}), "RGBA16F");  // signed, not unit
  EXPECT_EQ(formatFor(1, {-5, 0, 0, 1, 1e6F, 0, 0, 1}), "R32F");        // beyond half precision
  // An uncovered texel does not count.
  const std::vector<uint8_t> coverage{1, 0};
  EXPECT_EQ(analyzeBakedValues("v", 1, std::vector<float>{0.5F, 0, 0, 1, -7, 0, 0, 1}, coverage).format, "R8");
}

}  // namespace
}  // namespace spire::engine
