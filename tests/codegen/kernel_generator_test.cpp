// Kernel generation end to end: every variant of the examples' choice spaces
// yields kernels that glslang compiles for Vulkan and spirv-val accepts.
#include "codegen/kernel_generator.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "codegen/spirv_compiler.h"
#include "codegen/strategies/strategy_support.h"
#include "driver/shader_library.h"
#include "driver/spirv_cache.h"
#include "graph/graph_test_util.h"
#include "reflection/reflection_json.h"
#include "support/content_hash.h"
#include "support/diagnostic_renderer.h"

namespace spire::codegen {
namespace {

namespace fs = std::filesystem;

std::string render(ShaderLibrary& library) {
  return renderDiagnostics(library.sources(), library.diagnostics(), DiagnosticFormat::Text);
}

// Generates and checks every kernel of a variant; returns them. With a
// cache, a kernel whose text it holds (one that compiled and validated, the
// same stage and name) is not compiled again: the variants of a choice
// space share most of their kernels.
std::vector<Kernel> compileAndValidate(ShaderLibrary& library, const graph::Variant& variant,
                                       SpirvCache* checked = nullptr,
                                       const StrategyRegistry& registry = StrategyRegistry::builtin()) {
  const auto generated = generateKernels(library.model(), library.sources(), variant, registry, library.diagnostics());
  EXPECT_TRUE(generated.has_value()) << render(library);
  if (!generated) return {};
  for (const Kernel& kernel : generated->kernels) {
    const std::string name = kernel.world + ".glsl";
    if (checked != nullptr && checked->find(kernel.stage, name, kernel.glsl)) continue;
    const SpirvResult spirv = compileGlslToSpirv(kernel.stage, kernel.glsl, name);
    EXPECT_TRUE(spirv.ok()) << variant.placementText() << spirv.log << "\n" << kernel.glsl;
    if (!spirv.ok()) continue;
    const auto valid = validateSpirv(spirv.words);
    EXPECT_TRUE(valid) << valid.error().message << "\n" << kernel.glsl;
    if (valid && checked != nullptr) checked->add(kernel.stage, name, kernel.glsl, spirv.words);
  }
  return generated->kernels;
}

const Kernel* findKernel(const std::vector<Kernel>& kernels, const std::string& world) {
  for (const Kernel& k : kernels) {
    if (k.world == world) return &k;
  }
  return nullptr;
}

// Every variant of every example, in shards that CTest runs side by side
// (under the sanitizers the whole would take ten minutes on one core): shard
// k takes the decision maps whose index over all shaders is k modulo
// kShards. Each shard compiles and validates each distinct kernel once
// (driver/spirv_cache.h, as spirec --batch).
constexpr int kShards = 4;

class EveryExampleVariant : public ::testing::TestWithParam<int> {};

TEST_P(EveryExampleVariant, KernelsCompileAndValidate) {
  ShaderLibrary library;
  for (const auto& entry : fs::directory_iterator(fs::path(SPIRE_SOURCE_DIR) / "examples")) {
    if (entry.path().extension() == ".spire") library.addFile(entry.path().string());
  }
  ASSERT_TRUE(library.compile()) << render(library);
  size_t variants = 0, mine = 0;
  SpirvCache checked;
  for (const std::string& shader : library.shaderNames()) {
    const graph::ChoiceSpace& space = *library.choiceSpace(shader);
    testing_util::forEachDecisionMap(space, [&](const std::vector<graph::DecisionRequest>& requests, size_t) {
      if (static_cast<int>(variants++ % kShards) != GetParam()) return;
      ++mine;
      const auto result = graph::buildVariant(space, requests);
      ASSERT_TRUE(result.variant);
      compileAndValidate(library, *result.variant, &checked);
    });
  }
  EXPECT_GE(variants, 72u);
  EXPECT_GE(mine, variants / kShards);
}

INSTANTIATE_TEST_SUITE_P(Shard, EveryExampleVariant, ::testing::Range(0, kShards));

TEST(KernelGenerator, BakedAlbedoIsWrittenByPrebakeAndSampledByFragment) {
  ShaderLibrary library;
  library.addFile(std::string(SPIRE_SOURCE_DIR) + "/examples/terrain.spire");
  ASSERT_TRUE(library.compile()) << render(library);
  const auto variant = library.buildVariant("Terrain", {{"albedo", "PrebakeTex"}});
  ASSERT_TRUE(variant);
  const std::vector<Kernel> kernels = compileAndValidate(library, *variant);
  const Kernel* prebake = findKernel(kernels, "PrebakeTex");
  const Kernel* fragment = findKernel(kernels, "Fragment");
  ASSERT_TRUE(prebake && fragment);
  EXPECT_EQ(prebake->stage, ShaderStage::Fragment);
  EXPECT_NE(prebake->glsl.find("out vec4 spire_out_albedo;"), std::string::npos) << prebake->glsl;
  EXPECT_NE(fragment->glsl.find("uniform sampler2D spire_tex_albedo;"), std::string::npos) << fragment->glsl;
  EXPECT_NE(fragment->glsl.find("albedo = texture(spire_tex_albedo, vert_uv);"), std::string::npos) << fragment->glsl;
  bool reflected = false;
  for (const reflection::KernelInput& input : fragment->reflection.inputs) {
    reflected = reflected || (input.kind == reflection::InputKind::Texture && input.component == "albedo" &&
                              input.strategy == "textureImport" && input.uv == "vert_uv");
  }
  EXPECT_TRUE(reflected) << reflection::toJson(fragment->reflection).dump(2);
}

TEST(KernelGenerator, GlslReservedNamesAreRenamedAndReflectedBySourceName) {
  ShaderLibrary library;
  library.addSource("reserved.spire", R"(
using ")" + std::string(SPIRE_SOURCE_DIR) +
                                          R"(/pipelines/engine.spire";
struct input { float filter; };
float sample(float texture) { return texture * 2.0; }
shader S using EnginePipeline {
  @FrameUniform mat4 matMVP;
  @MaterialUniform input common;
  vec4 projPos = matMVP * vec4(vert_pos, 1.0);
  float filter = sample(common.filter);
  @Fragment float gl_weight = filter * 0.5;
  @Fragment vec4 output { vec4 output_ = vec4(filter * gl_weight); return output_; }
})");
  ASSERT_TRUE(library.compile()) << render(library);
  const auto variant = library.buildVariant("S", {});
  ASSERT_TRUE(variant);
  const std::vector<Kernel> kernels = compileAndValidate(library, *variant);
  const Kernel* fragment = findKernel(kernels, "Fragment");
  ASSERT_TRUE(fragment);
  EXPECT_NE(fragment->glsl.find("vec4 output_;"), std::string::npos) << fragment->glsl;
  EXPECT_NE(fragment->glsl.find("float glx_weight;"), std::string::npos) << fragment->glsl;
  ASSERT_FALSE(fragment->reflection.outputs.empty());
  EXPECT_EQ(fragment->reflection.outputs[0].component, "output");
}

TEST(KernelGenerator, LocalDeclarationsKeepTheirShapeInGlsl) {
  ShaderLibrary library;
  library.addSource("locals.spire", R"(
using ")" + std::string(SPIRE_SOURCE_DIR) +
                                        R"(/pipelines/engine.spire";
shader S using EnginePipeline {
  @FrameUniform mat4 matMVP;
  vec4 projPos = matMVP * vec4(vert_pos, 1.0);
  vec4 output {
    float sum = 0.0, weights[3] = float[3](0.25, 0.5, 0.25);
    for (int i = 0, last = 2; i <= last; ++i) { sum += weights[i]; }
    return vec4(sum);
  }
})");
  ASSERT_TRUE(library.compile()) << render(library);
  const auto variant = library.buildVariant("S", {});
  ASSERT_TRUE(variant);
  const std::vector<Kernel> kernels = compileAndValidate(library, *variant);
  const Kernel* fragment = findKernel(kernels, "Fragment");
  ASSERT_TRUE(fragment);
  EXPECT_NE(fragment->glsl.find("float sum = 0.0, weights[3] = float[3](0.25, 0.5, 0.25);"), std::string::npos)
      << fragment->glsl;
  EXPECT_NE(fragment->glsl.find("for (int i = 0, last = 2; i <= last; ++i) {"), std::string::npos) << fragment->glsl;
}

TEST(KernelGenerator, OutputIsDeterministicAndHashesFollowContent) {
  auto generate = [] {
    ShaderLibrary library;
    library.addFile(std::string(SPIRE_SOURCE_DIR) + "/examples/terrain.spire");
    EXPECT_TRUE(library.compile());
    const auto variant = library.buildVariant("Terrain", {{"lighting", "Vertex:ggx"}});
    return generateKernels(library.model(), library.sources(), *variant, StrategyRegistry::builtin(),
                           library.diagnostics())
        ->reflection(*variant);
  };
  EXPECT_EQ(generate(), generate());
  EXPECT_EQ(spire::contentHash("abc"), spire::contentHash("abc"));
  EXPECT_NE(spire::contentHash("abc"), spire::contentHash("abd"));
}

// A strategy defined entirely here: push constants instead of a uniform
// block. Registering it is all a new strategy needs.
class PushConstantImport final : public Strategy {
 public:
  const sem::StrategySignature& signature() const override { return signature_; }
  Expected<void, Failure> emitImport(ImportSite& site) const override {
    std::string members;
    uint32_t offset = 0;
    for (const KernelValue& v : site.values) {
      if (v.type->containsOpaque()) return Failure{"push constants cannot hold samplers"};
      members += "    " + site.consumer.declaration(v.type, v.glslName) + ";\n";
      const MemberLayout layout = layoutOf(v.type, BlockLayout::Std430);
      reflection::KernelInput entry = importEntry(site, v, reflection::InputKind::PushConstant, "pushConstantImport");
      entry.offset = offset = alignUp(offset, layout.alignment);
      offset += layout.size;
      site.consumer.reflectInput(std::move(entry));
    }
    site.consumer.declare("layout(push_constant, std430) uniform " + site.consumer.names().generate("push") + " {\n" +
                          members + "};");
    return {};
  }

 private:
  sem::StrategySignature signature_ =
      makeSignature("pushConstantImport", sem::StrategyRole::Import, {}, "push-constant block");
};

TEST(KernelGenerator, StrategiesRegisteredByTheApplicationWork) {
  StrategyRegistry registry = StrategyRegistry::withBuiltins();
  registry.add(std::make_unique<PushConstantImport>());
  FrontEndOptions options;
  options.strategies = &registry.catalog();
  ShaderLibrary library(options);
  library.addSource("push.spire", R"(
pipeline Push {
  abstract world Frame;
  abstract world Mesh;
  world Vertex : "GLSL" export vertexExport(projPos);
  world Fragment : "GLSL" export standardExport;
  import Frame->Vertex using pushConstantImport;
  import Frame->Fragment using uniformImport;
  import Mesh->Vertex using standardImport;
  import Vertex->Fragment using standardImport;
  @Mesh vec3 pos;
  abstract @Vertex vec4 projPos;
  abstract export @Fragment vec4 color;
}
shader S using Push {
  @Frame mat4 mvp;
  @Frame vec4 tint;
  vec4 projPos = mvp * vec4(pos, 1.0);
  vec4 color = tint * 0.5;
})");
  ASSERT_TRUE(library.compile()) << render(library);
  const auto variant = library.buildVariant("S", {});
  ASSERT_TRUE(variant);
  const auto generated = generateKernels(library.model(), library.sources(), *variant, registry, library.diagnostics());
  ASSERT_TRUE(generated) << render(library);
  const Kernel* vertex = findKernel(generated->kernels, "Vertex");
  ASSERT_TRUE(vertex);
  EXPECT_NE(vertex->glsl.find("layout(push_constant, std430) uniform"), std::string::npos) << vertex->glsl;
  ASSERT_EQ(vertex->reflection.inputs.size(), 2u);  // mvp, pos
  EXPECT_EQ(vertex->reflection.inputs[0].kind, reflection::InputKind::PushConstant);
  EXPECT_EQ(vertex->reflection.inputs[0].component, "mvp");
  // The typed record survives the JSON round trip, kind and offset included.
  const auto reread = reflection::fromJson(reflection::toJson(generated->reflection(*variant)));
  ASSERT_TRUE(reread) << reread.error();
  EXPECT_EQ(*reread, generated->reflection(*variant));
  compileAndValidate(library, *variant, nullptr, registry);
}

TEST(KernelGenerator, ComputeWorldsWriteAndReadBuffers) {
  // Compute prebakes in the spirit of the paper's Figure 4: PrebakeVertex
  // writes {displaced, band} per vertex; Smooth reads only `displaced`, the
  // vertex stage only `band`, and both must read the producer's layout.
  ShaderLibrary library;
  library.addSource("buffers.spire", R"(
pipeline Buffers {
  abstract world Material;
  abstract world Mesh;
  world PrebakeVertex : "GLSL" export bufferExport;
  world Smooth : "GLSL" export bufferExport;
  world Vertex : "GLSL" export vertexExport(projPos);
  world Fragment : "GLSL" export standardExport;
  import Material->PrebakeVertex using uniformImport;
  import Mesh->PrebakeVertex using bufferImport;
  import Material->Vertex using uniformImport;
  import Mesh->Vertex using standardImport;
  import PrebakeVertex->Vertex using bufferImport;
  import PrebakeVertex->Smooth using bufferImport;
  import Smooth->Vertex using bufferImport;
  import Vertex->Fragment using standardImport;
  @Mesh vec3 pos;
  @Mesh vec3 nrm;
  abstract @Vertex vec4 projPos;
  abstract export @Fragment vec4 color;
}
shader S using Buffers {
  @Material mat4 mvp;
  @Material float scale;
  @PrebakeVertex vec3 displaced = pos + nrm * scale;
  @PrebakeVertex int band = int(nrm.y * 4.0);
  @Smooth vec3 smoothed = displaced * 0.5;
  @Vertex vec4 projPos = mvp * vec4(smoothed, 1.0);
  @Vertex float shade = float(band) * 0.25;
  @Fragment vec4 color = vec4(shade, 0.0, 0.0, 1.0);
})");
  ASSERT_TRUE(library.compile()) << render(library);
  const auto variant = library.buildVariant("S", {{"color", "Fragment"}});
  ASSERT_TRUE(variant);
  const std::vector<Kernel> kernels = compileAndValidate(library, *variant);
  const Kernel* prebake = findKernel(kernels, "PrebakeVertex");
  const Kernel* vertex = findKernel(kernels, "Vertex");
  ASSERT_TRUE(prebake && vertex);
  EXPECT_EQ(prebake->stage, ShaderStage::Compute);
  // The consumer reads the producer's records with the producer's layout.
  std::map<std::string, uint32_t> written;
  for (const reflection::KernelOutput& out : prebake->reflection.outputs) written[out.component] = out.offset;
  size_t read = 0;
  for (const reflection::KernelInput& in : vertex->reflection.inputs) {
    if (in.kind != reflection::InputKind::BufferMember || in.from != "PrebakeVertex") continue;
    EXPECT_EQ(in.offset, written.at(in.component)) << in.component;
    ++read;
  }
  EXPECT_GE(read, 1u);
  EXPECT_NE(prebake->glsl.find("if (gl_GlobalInvocationID.x >= uint("), std::string::npos) << prebake->glsl;
  EXPECT_NE(vertex->glsl.find("[gl_VertexIndex]"), std::string::npos) << vertex->glsl;
}

TEST(KernelGenerator, StrategyLimitsAreErrors) {
  ShaderLibrary library;
  library.addSource("bad.spire", R"(
using ")" + std::string(SPIRE_SOURCE_DIR) +
                                     R"(/pipelines/engine.spire";
shader S using EnginePipeline {
  @FrameUniform mat4 matMVP;
  vec4 projPos = matMVP * vec4(vert_pos, 1.0);
  @PrebakeTex int cell = int(vert_uv.x * 8.0);
  vec4 output = vec4(float(cell));
})");
  ASSERT_TRUE(library.compile()) << render(library);
  const auto variant = library.buildVariant("S", {});
  ASSERT_TRUE(variant);
  EXPECT_FALSE(generateKernels(library.model(), library.sources(), *variant, StrategyRegistry::builtin(),
                               library.diagnostics()));
  EXPECT_NE(render(library).find("error[E6001]"), std::string::npos) << render(library);
}

}  // namespace
}  // namespace spire::codegen
