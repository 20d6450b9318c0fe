// instanceImport and textureArrayImport: the strategies that let an engine
// draw objects with different per-object values (a model matrix, baked
// values, a layer of baked texture arrays) in one instanced draw
// (pipelines/instanced.spire).
#include <gtest/gtest.h>

#include "codegen/kernel_generator.h"
#include "codegen/spirv_compiler.h"
#include "driver/shader_library.h"
#include "reflection/reflection_json.h"
#include "support/diagnostic_renderer.h"

namespace spire::codegen {
namespace {

std::string render(ShaderLibrary& library) {
  return renderDiagnostics(library.sources(), library.diagnostics(), DiagnosticFormat::Text);
}

// Bake renders `baked` per object into one layer of a texture array; Vertex
// reads the instance's matrix and layer at gl_InstanceIndex and passes the
// layer on to Fragment, which samples the array at (uv, layer).
constexpr const char* kInstanced = R"(
pipeline Inst {
  abstract world Frame;
  abstract world Mesh;
  [Role: "instance"] abstract world Instance;
  world Bake : "GLSL" export standardExport;
  world Vertex : "GLSL" export vertexExport(projPos);
  world Fragment : "GLSL" export standardExport;
  import Mesh->Bake using standardImport;
  import Mesh->Vertex using standardImport;
  import Frame->Vertex using uniformImport;
  import Instance->Vertex using instanceImport;
  import Vertex->Fragment using standardImport;
  import Bake->Fragment using textureArrayImport(uv * 2.0, layer);
  @Mesh vec3 pos;
  @Mesh vec2 uv;
  @Instance mat4 model;
  @Instance float layer;
  abstract @Vertex vec4 projPos;
  abstract export @Fragment vec4 color;
}
shader S using Inst {
  @Frame mat4 viewProj;
  vec4 projPos = viewProj * (model * vec4(pos, 1.0));
  @Bake vec4 baked = vec4(uv, 0.0, 1.0);
  @Bake float shade = uv.x;
  vec4 color = baked * shade;
})";

struct Generated {
  ShaderLibrary library;
  std::optional<GeneratedShader> kernels;
  std::optional<graph::Variant> variant;
};

void generate(Generated& out, const std::string& source) {
  out.library.addSource("instanced.spire", source);
  ASSERT_TRUE(out.library.compile()) << render(out.library);
  out.variant = out.library.buildVariant("S", {});
  ASSERT_TRUE(out.variant);
  out.kernels = generateKernels(out.library.model(), out.library.sources(), *out.variant, StrategyRegistry::builtin(),
                                out.library.diagnostics());
}

const Kernel& kernelOf(const Generated& g, const std::string& world) {
  for (const Kernel& k : g.kernels->kernels) {
    if (k.world == world) return k;
  }
  ADD_FAILURE() << "no kernel " << world;
  return g.kernels->kernels.front();
}

const reflection::KernelInput* inputOf(const Kernel& kernel, const std::string& component) {
  for (const reflection::KernelInput& in : kernel.reflection.inputs) {
    if (in.component == component) return &in;
  }
  return nullptr;
}

void expectValidSpirv(const Kernel& kernel) {
  const SpirvResult spirv = compileGlslToSpirv(kernel.stage, kernel.glsl, kernel.world + ".glsl");
  ASSERT_TRUE(spirv.ok()) << spirv.log << "\n" << kernel.glsl;
  const auto valid = validateSpirv(spirv.words);
  EXPECT_TRUE(valid) << valid.error().message << "\n" << kernel.glsl;
}

TEST(InstanceImport, ReadsPerInstanceRecordsAtTheInstanceIndex) {
  Generated g;
  generate(g, kInstanced);
  ASSERT_TRUE(g.kernels) << render(g.library);
  const Kernel& vertex = kernelOf(g, "Vertex");
  EXPECT_NE(vertex.glsl.find("std430) readonly buffer"), std::string::npos) << vertex.glsl;
  EXPECT_NE(vertex.glsl.find("[gl_InstanceIndex]."), std::string::npos) << vertex.glsl;
  for (const char* component : {"model", "layer"}) {
    const reflection::KernelInput* in = inputOf(vertex, component);
    ASSERT_TRUE(in) << component;
    EXPECT_EQ(in->kind, reflection::InputKind::BufferMember);
    EXPECT_EQ(in->strategy, "instanceImport");
    EXPECT_EQ(in->index, "gl_InstanceIndex");
    EXPECT_EQ(in->from, "Instance");
    const reflection::Block* block = vertex.reflection.block(in->slot);
    ASSERT_TRUE(block);
    EXPECT_TRUE(block->storage);
    EXPECT_EQ(block->layout, "std430");
    ASSERT_TRUE(block->member(component));
    EXPECT_EQ(block->member(component)->offset, in->offset);
  }
  expectValidSpirv(vertex);
  // The pipeline's [Role] reaches reflection as it is written.
  const reflection::Variant variant = g.kernels->reflection(*g.variant);
  ASSERT_EQ(variant.worlds.size(), 6u);
  EXPECT_EQ(variant.worlds[2].name, "Instance");
  EXPECT_EQ(variant.worlds[2].role, "instance");
}

TEST(InstanceImport, RefusesAFragmentConsumer) {
  Generated g;
  generate(g, R"(
pipeline Inst {
  abstract world Frame;
  abstract world Mesh;
  abstract world Instance;
  world Vertex : "GLSL" export vertexExport(projPos);
  world Fragment : "GLSL" export standardExport;
  import Mesh->Vertex using standardImport;
  import Frame->Vertex using uniformImport;
  import Instance->Fragment using instanceImport;
  import Vertex->Fragment using standardImport;
  @Mesh vec3 pos;
  abstract @Vertex vec4 projPos;
  abstract export @Fragment vec4 color;
}
shader S using Inst {
  @Frame mat4 mvp;
  @Instance vec4 tint;
  vec4 projPos = mvp * vec4(pos, 1.0);
  vec4 color = tint;
})");
  EXPECT_FALSE(g.kernels);
  EXPECT_NE(render(g.library).find("instanceImport reads one record per instance at gl_InstanceIndex, which only a "
                                   "vertex kernel has, and cannot feed the fragment world 'Fragment'"),
            std::string::npos)
      << render(g.library);
}

TEST(TextureArrayImport, SamplesALayerOfATextureArray) {
  Generated g;
  generate(g, kInstanced);
  ASSERT_TRUE(g.kernels) << render(g.library);
  const Kernel& fragment = kernelOf(g, "Fragment");
  EXPECT_NE(fragment.glsl.find("uniform sampler2DArray"), std::string::npos) << fragment.glsl;
  EXPECT_EQ(fragment.glsl.find("uniform sampler2D "), std::string::npos) << fragment.glsl;
  EXPECT_NE(fragment.glsl.find(", vec3(uv * 2.0, layer)).x;"), std::string::npos) << fragment.glsl;
  const reflection::KernelInput* baked = inputOf(fragment, "baked");
  ASSERT_TRUE(baked);
  EXPECT_EQ(baked->kind, reflection::InputKind::Texture);
  EXPECT_EQ(baked->strategy, "textureArrayImport");
  EXPECT_EQ(baked->uv, "uv * 2.0");
  EXPECT_EQ(baked->layer, "layer");
  EXPECT_EQ(baked->channels, 4u);
  EXPECT_EQ(baked->from, "Bake");
  // The arguments' components reach the consumer: uv from the mesh and the
  // layer from the instance record, both through Vertex.
  for (const char* component : {"uv", "layer"}) {
    const reflection::KernelInput* in = inputOf(fragment, component);
    ASSERT_TRUE(in) << component;
    EXPECT_EQ(in->kind, reflection::InputKind::Varying);
    EXPECT_EQ(in->from, "Vertex");
  }
  expectValidSpirv(fragment);
}

TEST(TextureArrayImport, TheLayerSurvivesTheJsonRoundTrip) {
  Generated g;
  generate(g, kInstanced);
  ASSERT_TRUE(g.kernels) << render(g.library);
  const reflection::Variant variant = g.kernels->reflection(*g.variant);
  const auto json = reflection::toJson(variant);
  EXPECT_NE(json.dump().find("\"layer\":\"layer\""), std::string::npos) << json.dump();
  const auto reread = reflection::fromJson(json);
  ASSERT_TRUE(reread) << reread.error();
  EXPECT_EQ(*reread, variant);
}

TEST(TextureArrayImport, ASampler2DHasNoLayer) {
  // textureImport's entries carry no "layer" in reflection.json.
  std::string source = kInstanced;
  source.replace(source.find("textureArrayImport(uv * 2.0, layer)"), 35, "textureImport(uv)");
  Generated g;
  generate(g, source);
  ASSERT_TRUE(g.kernels) << render(g.library);
  const reflection::KernelInput* baked = inputOf(kernelOf(g, "Fragment"), "baked");
  ASSERT_TRUE(baked);
  EXPECT_EQ(baked->strategy, "textureImport");
  EXPECT_TRUE(baked->layer.empty());
  EXPECT_EQ(reflection::toJson(g.kernels->reflection(*g.variant)).dump().find("\"layer\""), std::string::npos);
}

}  // namespace
}  // namespace spire::codegen
