// Descriptor sets as reflection numbers them (docs/reflection.md, Descriptor
// bindings; docs/engine.md, Descriptor sets): the kernels of one pipeline in
// different sets with overlapping binding numbers, a kernel alone in set 1,
// a slot two stages share, and slots they cannot share. The kernels are
// written here in GLSL with reflection of their own, so the tests do not
// depend on how the compiler numbers bindings. Validation is on: a layout
// that does not match the shaders fails the test.
#include <gtest/gtest.h>

#include <array>
#include <cstring>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "codegen/spirv_compiler.h"
#include "engine/device_fixture.h"
#include "reflection/reflection_json.h"
#include "renderer/draw_item.h"
#include "renderer/gpu_resources.h"
#include "renderer/pipeline_descriptors.h"
#include "renderer/render_target.h"
#include "renderer/texture_bake.h"
#include "support/content_hash.h"

namespace spire::engine {
namespace {

using Json = nlohmann::ordered_json;

struct TestKernel {
  codegen::ShaderStage stage;
  std::string world;
  std::string glsl;
  std::string reflection;  // the kernel's "inputs", "outputs" and "blocks", as JSON members
};

// Names and strategies are bookkeeping the tests do not vary: fill them in
// where a fixture leaves them out. Kinds, slots and types are always written.
void fillNames(Json& list) {
  for (Json& entry : list) {
    if (entry.contains("component") && !entry.contains("glslName")) entry["glslName"] = entry["component"];
    if (!entry.contains("strategy")) entry["strategy"] = "test";
    if (entry.contains("members")) {
      if (!entry.contains("layout")) entry["layout"] = "std140";
      fillNames(entry["members"]);
    }
  }
}

Json reflectionOf(const std::vector<TestKernel>& kernels) {
  Json kernelList = Json::array();
  for (const TestKernel& k : kernels) {
    Json entry = {{"world", k.world},
                  {"stage", k.stage == codegen::ShaderStage::Vertex ? "vertex" : "fragment"},
                  {"entry", "main"},
                  {"glsl", k.world + ".glsl"},
                  {"spirv", k.world + ".spv"},
                  {"hash", spire::contentHash(k.glsl)},
                  {"key", spire::contentHash(k.world + k.glsl)}};
    entry.update(Json::parse("{" + k.reflection + "}"));
    for (const char* list : {"inputs", "outputs", "blocks"}) fillNames(entry[list]);
    kernelList.push_back(std::move(entry));
  }
  // EnginePipeline's worlds, none with a [Role]: the engine knows them by name.
  Json worlds = Json::array();
  for (const char* world : {"FrameUniform", "MaterialUniform", "MeshVertex", "PrebakeTex", "Vertex", "Fragment"}) {
    worlds.push_back({{"name", world}, {"role", ""}});
  }
  return Json{{"format", "spire-reflection"},
              {"version", reflection::kFormatVersion},
              {"shader", "SetsTest"},
              {"pipeline", "EnginePipeline"},
              {"worlds", worlds},
              {"placement", Json::object()},
              {"kernels", kernelList}};
}

// The kernels' SPIR-V, compiled with glslang; empty for one that does not compile.
std::map<std::string, std::vector<uint32_t>> spirvOf(const std::vector<TestKernel>& kernels) {
  std::map<std::string, std::vector<uint32_t>> spirv;
  for (const TestKernel& k : kernels) {
    codegen::SpirvResult result = codegen::compileGlslToSpirv(k.stage, k.glsl, k.world + ".glsl");
    EXPECT_TRUE(result.ok()) << result.log;
    spirv[k.world] = std::move(result.words);
  }
  return spirv;
}

Expected<VariantProgram> programOf(const std::vector<TestKernel>& kernels) {
  return parseReflection(reflectionOf(kernels), spirvOf(kernels));
}

const std::string kVertexBlockReflection = R"(
  "inputs": [
    {"kind": "uniform", "component": "offset", "type": "vec4", "from": "MaterialUniform", "set": 0, "binding": 0,
     "block": "VertexBlock", "offset": 0},
    {"kind": "varying", "component": "vert_pos", "type": "vec3", "from": "MeshVertex", "location": 0}],
  "outputs": [{"kind": "builtin", "builtin": "gl_Position", "expression": "projPos"}],
  "blocks": [{"name": "VertexBlock", "kind": "uniform", "set": 0, "binding": 0, "size": 16,
              "members": [{"component": "offset", "type": "vec4", "offset": 0, "size": 16}]}])";

// Vertex in set 0 and Fragment in set 1, both numbering bindings from 0: what
// the compiler emits when kernels are numbered one by one.
const TestKernel kVertexSet0{codegen::ShaderStage::Vertex, "Vertex", R"(#version 440
layout(set = 0, binding = 0, std140) uniform VertexBlock { vec4 offset; };
layout(location = 0) in vec3 vert_pos;
void main() { gl_Position = vec4(vert_pos.x + offset.x, vert_pos.z + offset.y, 0.5, 1.0); }
)",
                             kVertexBlockReflection};

const TestKernel kFragmentSet1{codegen::ShaderStage::Fragment, "Fragment", R"(#version 440
layout(set = 1, binding = 0) uniform sampler2D tint;
layout(set = 1, binding = 1, std140) uniform FragmentBlock { vec4 scale; };
layout(location = 0) out vec4 color;
void main() { color = texture(tint, vec2(0.5)) * scale; }
)",
                               R"(
  "inputs": [
    {"kind": "sampler", "component": "tint", "type": "sampler2D", "from": "MaterialUniform", "set": 1, "binding": 0},
    {"kind": "uniform", "component": "scale", "type": "vec4", "from": "MaterialUniform", "set": 1, "binding": 1,
     "block": "FragmentBlock", "offset": 0}],
  "outputs": [{"kind": "varying", "component": "color", "type": "vec4", "location": 0}],
  "blocks": [{"name": "FragmentBlock", "kind": "uniform", "set": 1, "binding": 1, "size": 16,
              "members": [{"component": "scale", "type": "vec4", "offset": 0, "size": 16}]}])"};

TEST(RendererReflectionSets, EveryBindingHasItsSet) {
  const Json reflection = reflectionOf({kVertexSet0, kFragmentSet1});
  auto program = parseReflection(reflection, spirvOf({kVertexSet0, kFragmentSet1}));
  ASSERT_TRUE(program) << program.error().message;
  const KernelProgram& fragment = *program->kernel("Fragment");
  EXPECT_EQ(fragment.inputs[0].slot, (DescriptorSlot{1, 0}));
  EXPECT_EQ(fragment.inputs[1].slot, (DescriptorSlot{1, 1}));
  EXPECT_EQ(fragment.blocks[0].slot, (DescriptorSlot{1, 1}));
  EXPECT_EQ(program->kernel("Vertex")->blocks[0].slot, (DescriptorSlot{0, 0}));
  EXPECT_NE(fragment.block({1, 1}), nullptr);
  EXPECT_EQ(fragment.block({0, 1}), nullptr);
}

TEST(RendererReflectionSets, MissingOrNonIntegerSetIsAnError) {
  for (const Json& bad : {Json(), Json("1"), Json(1.5), Json(-1), Json(true)}) {
    Json reflection = reflectionOf({kVertexSet0, kFragmentSet1});
    Json& input = reflection["kernels"][1]["inputs"][0];
    if (bad.is_null()) {
      input.erase("set");
    } else {
      input["set"] = bad;
    }
    auto program = parseReflection(reflection, spirvOf({kVertexSet0, kFragmentSet1}));
    ASSERT_FALSE(program) << "set: " << bad.dump();
    EXPECT_NE(program.error().message.find("kernel 'Fragment', input 'tint'"), std::string::npos)
        << program.error().message;
    EXPECT_NE(program.error().message.find("\"set\""), std::string::npos) << program.error().message;
  }
  Json reflection = reflectionOf({kVertexSet0, kFragmentSet1});
  reflection["kernels"][0]["blocks"][0]["set"] = "zero";
  auto program = parseReflection(reflection, spirvOf({kVertexSet0, kFragmentSet1}));
  ASSERT_FALSE(program);
  EXPECT_NE(program.error().message.find("kernel 'Vertex', block 'VertexBlock': \"set\" must be a whole number"),
            std::string::npos)
      << program.error().message;
}

class RendererDescriptorSetsTest : public vk::testing::DeviceTest {
 protected:
  void SetUp() override {
    DeviceTest::SetUp();
    if (IsSkipped() || HasFailure()) return;
    auto mesh = uploadMesh(ctx(), scene::makePlane(2.0F, 1));
    ASSERT_TRUE(mesh) << mesh.error().message;
    mesh_ = std::move(mesh).value();
    scene::Image image{1, 1, {255, 128, 0, 255}};
    auto texture = uploadTexture(ctx(), image, true);
    ASSERT_TRUE(texture) << texture.error().message;
    texture_ = std::move(texture).value();
    material_["offset"] = {{0, 0, 0, 0}, nullptr, "offset", {}};
    material_["scale"] = {{1, 0.5, 2, 1}, nullptr, "scale", {}};
    material_["tint"] = {{}, texture_.get(), "tint", {}};
  }

  BindingSources sources() const { return {mesh_.get(), &material_, nullptr, nullptr, nullptr}; }

  Expected<DrawItem> drawItem(const VariantProgram& program, const TargetFormats& formats) {
    return createDrawItem(ctx(), {modules_, pipelines_}, program, sources(), DrawPlacement{glm::mat4(1.0F), true},
                          formats);
  }

  // Draws `program` into a 4x4 target; the color of its middle pixel.
  std::optional<std::array<float, 4>> drawMiddle(const VariantProgram& program, DrawItem* kept = nullptr) {
    auto target = RenderTarget::create(ctx(), 4, 4, 1);
    EXPECT_TRUE(target) << target.error().message;
    if (!target) return std::nullopt;
    auto item = drawItem(program, target->formats());
    EXPECT_TRUE(item) << item.error().message;
    if (!item) return std::nullopt;
    const DrawItem* items[] = {&*item};
    auto rendered = target->render(ctx(), items, FrameState{}, glm::vec4(0.0F));
    EXPECT_TRUE(rendered) << rendered.error().message;
    auto color = target->readColor(ctx());
    EXPECT_TRUE(color) << color.error().message;
    if (!rendered || !color) return std::nullopt;
    const size_t middle = (size_t{2} * color->width + 2) * 4;
    if (kept) *kept = std::move(item).value();
    return std::array<float, 4>{color->rgba[middle], color->rgba[middle + 1], color->rgba[middle + 2],
                                color->rgba[middle + 3]};
  }

  ModuleCache modules_;
  PipelineCache pipelines_;
  std::unique_ptr<GpuMesh> mesh_;
  std::unique_ptr<GpuTexture> texture_;
  MaterialValues material_;
};

// The color both test kernels draw: tint (1, 128/255, 0, 1) times scale
// (1, 0.5, 2, 1).
void expectTintTimesScale(const std::array<float, 4>& color) {
  EXPECT_FLOAT_EQ(color[0], 1.0F);
  EXPECT_NEAR(color[1], 0.5F * 128.0F / 255.0F, 1e-6);
  EXPECT_FLOAT_EQ(color[2], 0.0F);
  EXPECT_FLOAT_EQ(color[3], 1.0F);
}

TEST_F(RendererDescriptorSetsTest, VertexInSetZeroAndFragmentInSetOneDraw) {
  auto program = programOf({kVertexSet0, kFragmentSet1});
  ASSERT_TRUE(program) << program.error().message << program.error().details;
  DrawItem item;
  const auto color = drawMiddle(*program, &item);
  ASSERT_TRUE(color);
  expectTintTimesScale(*color);
  ASSERT_EQ(item.descriptors.layouts.size(), 2U);
  ASSERT_EQ(item.descriptors.sets.size(), 2U);

  const BoundKernel* kernels[] = {&item.kernels[0], &item.kernels[1]};
  auto plan = planDescriptorSets(kernels, 4);
  ASSERT_TRUE(plan) << plan.error().message;
  ASSERT_EQ(plan->size(), 2U);
  ASSERT_EQ((*plan)[0].size(), 1U);
  EXPECT_EQ((*plan)[0][0].descriptor.type, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER);
  EXPECT_EQ((*plan)[0][0].stages, VkShaderStageFlags{VK_SHADER_STAGE_VERTEX_BIT});
  ASSERT_EQ((*plan)[1].size(), 2U);
  EXPECT_EQ((*plan)[1][0].descriptor.slot, (DescriptorSlot{1, 0}));
  EXPECT_EQ((*plan)[1][0].descriptor.type, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER);
  EXPECT_EQ((*plan)[1][1].descriptor.slot, (DescriptorSlot{1, 1}));
  EXPECT_EQ((*plan)[1][1].stages, VkShaderStageFlags{VK_SHADER_STAGE_FRAGMENT_BIT});
  // A device with fewer sets than the kernels use is told so.
  auto tooFew = planDescriptorSets(kernels, 1);
  ASSERT_FALSE(tooFew);
  EXPECT_NE(tooFew.error().message.find("descriptor set 1, but the device binds at most 1"), std::string::npos)
      << tooFew.error().message;
}

// Today's numbering: everything in set 0, bindings unique across kernels.
TEST_F(RendererDescriptorSetsTest, OneSetWithBindingsUniqueAcrossKernelsDraws) {
  TestKernel fragment = kFragmentSet1;
  const std::pair<std::string, std::string> renames[] = {{"set = 1, binding = 1", "set = 0, binding = 2"},
                                                         {"set = 1, binding = 0", "set = 0, binding = 1"}};
  for (const auto& [from, to] : renames) {
    fragment.glsl.replace(fragment.glsl.find(from), from.size(), to);
  }
  Json reflection = Json::parse("{" + fragment.reflection + "}");
  reflection["inputs"][0]["set"] = 0;
  reflection["inputs"][0]["binding"] = 1;
  reflection["inputs"][1]["set"] = 0;
  reflection["inputs"][1]["binding"] = 2;
  reflection["blocks"][0]["set"] = 0;
  reflection["blocks"][0]["binding"] = 2;
  fragment.reflection = reflection.dump().substr(1, reflection.dump().size() - 2);
  auto program = programOf({kVertexSet0, fragment});
  ASSERT_TRUE(program) << program.error().message << program.error().details;
  DrawItem item;
  const auto color = drawMiddle(*program, &item);
  ASSERT_TRUE(color);
  expectTintTimesScale(*color);
  EXPECT_EQ(item.descriptors.layouts.size(), 1U);
}

// Both stages sample the same material texture at set 0, binding 0: one
// binding with both stage flags.
TEST_F(RendererDescriptorSetsTest, StagesSharingASlotForOneResourceMergeStageFlags) {
  const TestKernel vertex{codegen::ShaderStage::Vertex, "Vertex", R"(#version 440
layout(set = 0, binding = 0) uniform sampler2D tint;
layout(location = 0) in vec3 vert_pos;
void main() { gl_Position = vec4(vert_pos.x, vert_pos.z, 0.5, textureLod(tint, vec2(0.5), 0.0).a); }
)",
                          R"(
  "inputs": [
    {"kind": "sampler", "component": "tint", "type": "sampler2D", "from": "MaterialUniform", "set": 0, "binding": 0},
    {"kind": "varying", "component": "vert_pos", "type": "vec3", "from": "MeshVertex", "location": 0}],
  "outputs": [{"kind": "builtin", "builtin": "gl_Position", "expression": "projPos"}], "blocks": [])"};
  const TestKernel fragment{codegen::ShaderStage::Fragment, "Fragment", R"(#version 440
layout(set = 0, binding = 0) uniform sampler2D tint;
layout(location = 0) out vec4 color;
void main() { color = texture(tint, vec2(0.5)); }
)",
                            R"(
  "inputs": [{"kind": "sampler", "component": "tint", "type": "sampler2D", "from": "MaterialUniform", "set": 0, "binding": 0}],
  "outputs": [{"kind": "varying", "component": "color", "type": "vec4", "location": 0}], "blocks": [])"};
  auto program = programOf({vertex, fragment});
  ASSERT_TRUE(program) << program.error().message << program.error().details;
  DrawItem item;
  const auto color = drawMiddle(*program, &item);
  ASSERT_TRUE(color);
  EXPECT_FLOAT_EQ((*color)[0], 1.0F);
  EXPECT_NEAR((*color)[1], 128.0F / 255.0F, 1e-6);

  const BoundKernel* kernels[] = {&item.kernels[0], &item.kernels[1]};
  auto plan = planDescriptorSets(kernels, 4);
  ASSERT_TRUE(plan) << plan.error().message;
  ASSERT_EQ(plan->size(), 1U);
  ASSERT_EQ((*plan)[0].size(), 1U);
  EXPECT_EQ((*plan)[0][0].stages, VkShaderStageFlags{VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT});
}

// Set 0, binding 0 is the Vertex kernel's uniform block; a Fragment kernel
// that puts something else there is refused before Vulkan sees it.
TEST_F(RendererDescriptorSetsTest, StagesSharingASlotForDifferentResourcesIsAnError) {
  const std::string fragmentSet0 = R"(#version 440
layout(set = 0, binding = 0) uniform sampler2D tint;
layout(set = 0, binding = 1, std140) uniform FragmentBlock { vec4 scale; };
layout(location = 0) out vec4 color;
void main() { color = texture(tint, vec2(0.5)) * scale; }
)";
  Json reflection = Json::parse("{" + kFragmentSet1.reflection + "}");
  for (Json* entry : {&reflection["inputs"][0], &reflection["inputs"][1], &reflection["blocks"][0]}) {
    (*entry)["set"] = 0;
  }
  const std::string members = reflection.dump().substr(1, reflection.dump().size() - 2);
  auto differentType = programOf({kVertexSet0, {codegen::ShaderStage::Fragment, "Fragment", fragmentSet0, members}});
  ASSERT_TRUE(differentType) << differentType.error().message << differentType.error().details;
  const TargetFormats formats{{VK_FORMAT_R32G32B32A32_SFLOAT}, VK_FORMAT_D32_SFLOAT};
  auto item = drawItem(*differentType, formats);
  ASSERT_FALSE(item);
  EXPECT_EQ(item.error().message,
            "the Vertex and Fragment kernels both use descriptor set 0, binding 0, with different types: uniform "
            "block 'VertexBlock' as a uniform buffer in Vertex, sampler 'tint' as a combined image sampler in "
            "Fragment");

  // The same type for a different resource: two uniform blocks at set 0, binding 0.
  Json sameType = Json::parse("{" + kVertexBlockReflection + "}");
  sameType["inputs"][0]["component"] = "scale";
  sameType["blocks"][0]["members"][0]["component"] = "scale";
  sameType["outputs"] = Json::parse(R"([{"kind": "varying", "component": "color", "type": "vec4", "location": 0}])");
  sameType["inputs"].erase(1);
  auto differentResource = programOf({kVertexSet0,
                                      {codegen::ShaderStage::Fragment, "Fragment", R"(#version 440
layout(set = 0, binding = 0, std140) uniform VertexBlock { vec4 scale; };
layout(location = 0) out vec4 color;
void main() { color = scale; }
)",
                                       sameType.dump().substr(1, sameType.dump().size() - 2)}});
  ASSERT_TRUE(differentResource) << differentResource.error().message << differentResource.error().details;
  auto second = drawItem(*differentResource, formats);
  ASSERT_FALSE(second);
  EXPECT_EQ(second.error().message,
            "the Vertex and Fragment kernels both use descriptor set 0, binding 0 for different resources (uniform "
            "block 'VertexBlock' in Vertex, uniform block 'VertexBlock' in Fragment)");
}

// The texture bake's vertex shader is the engine's and binds nothing: a
// PrebakeTex kernel in set 1 gets an empty set 0 before its own.
TEST_F(RendererDescriptorSetsTest, TextureBakeKernelInSetOne) {
  const TestKernel bake{codegen::ShaderStage::Fragment, "PrebakeTex", R"(#version 440
layout(set = 1, binding = 0, std140) uniform BakeBlock { vec4 scale; };
layout(location = 0) in vec2 vert_uv;
layout(location = 0) out vec4 albedo;
void main() { albedo = scale + vec4(0.0 * vert_uv, 0.0, 0.0); }
)",
                        R"(
  "inputs": [
    {"kind": "uniform", "component": "scale", "type": "vec4", "from": "MaterialUniform", "set": 1, "binding": 0,
     "block": "BakeBlock", "offset": 0},
    {"kind": "varying", "component": "vert_uv", "type": "vec2", "from": "MeshVertex", "location": 0}],
  "outputs": [{"kind": "varying", "component": "albedo", "type": "vec4", "location": 0}],
  "blocks": [{"name": "BakeBlock", "kind": "uniform", "set": 1, "binding": 0, "size": 16,
              "members": [{"component": "scale", "type": "vec4", "offset": 0, "size": 16}]}])"};
  auto program = programOf({bake});
  ASSERT_TRUE(program) << program.error().message << program.error().details;
  TextureBakeOptions options;
  options.defaultSize = 4;
  options.forceFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
  BakeTiming timing;
  auto baked = runTextureBake(ctx(), {modules_, pipelines_}, program->kernels[0], sources(), options, timing);
  ASSERT_TRUE(baked) << baked.error().message;
  const std::vector<std::byte>& texels = baked->textures.at("albedo").texels;
  ASSERT_EQ(texels.size(), size_t{4} * 4 * 16);
  std::array<float, 4> middle{};
  std::memcpy(middle.data(), texels.data() + (size_t{2} * 4 + 2) * 16, sizeof middle);
  EXPECT_EQ(middle, (std::array<float, 4>{1.0F, 0.5F, 2.0F, 1.0F}));
}

}  // namespace
}  // namespace spire::engine
