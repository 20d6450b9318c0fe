#include "codegen/spirv_compiler.h"

#include <gtest/gtest.h>
#include <spirv-tools/libspirv.hpp>

#include <cstdint>
#include <string>
#include <thread>
#include <vector>

namespace spire::codegen {
namespace {

// Success when `text` contains `part`; the failure message shows the text.
::testing::AssertionResult contains(const std::string& text, const std::string& part) {
  if (text.find(part) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "\"" << part << "\" not found in:\n" << text;
}

constexpr uint32_t kSpirvMagic = 0x07230203u;
constexpr uint32_t kSpirv15 = 0x00010500u;

// What the generator emits for a vertex kernel: a std140 block, attributes,
// varyings, all with explicit locations and bindings.
constexpr const char* kVertexShader = R"(#version 440
#extension GL_GOOGLE_cpp_style_line_directive : require

layout(std140, set = 0, binding = 0) uniform ViewUniforms {
  mat4 viewProjection;
  mat4 model;
  vec4 cameraPosition;
} view;

layout(location = 0) in vec3 vert_pos;
layout(location = 1) in vec3 vert_normal;
layout(location = 2) in vec2 vert_uv;

layout(location = 0) out vec3 fs_normal;
layout(location = 1) out vec2 fs_uv;
layout(location = 2) out float fs_distance;

#line 12 "terrain.spire"
void main() {
  vec4 world = view.model * vec4(vert_pos, 1.0);
  fs_normal = mat3(view.model) * vert_normal;
  fs_uv = vert_uv;
  fs_distance = length(world.xyz - view.cameraPosition.xyz);
  gl_Position = view.viewProjection * world;
}
)";

constexpr const char* kFragmentShader = R"(#version 440
#extension GL_GOOGLE_cpp_style_line_directive : require

layout(set = 0, binding = 1) uniform sampler2D albedoTex;
layout(set = 0, binding = 2) uniform sampler2D normalTex;
layout(std140, set = 0, binding = 3) uniform Material {
  vec4 tint;
  float roughness;
} material;

layout(location = 0) in vec3 fs_normal;
layout(location = 1) in vec2 fs_uv;

layout(location = 0) out vec4 outColor;

#line 30 "terrain.spire"
void main() {
  vec3 n = normalize(fs_normal + texture(normalTex, fs_uv).xyz * 2.0 - 1.0);
  vec4 albedo = texture(albedoTex, fs_uv) * material.tint;
  float lambert = max(dot(n, normalize(vec3(0.3, 1.0, 0.2))), 0.0);
  outColor = vec4(albedo.rgb * mix(lambert, 1.0, material.roughness), albedo.a);
}
)";

constexpr const char* kComputeShader = R"(#version 440
#extension GL_GOOGLE_cpp_style_line_directive : require

layout(local_size_x = 64) in;

layout(std140, set = 0, binding = 0) uniform Params {
  uint count;
  float scale;
} params;

layout(std430, set = 0, binding = 1) readonly buffer Heights {
  float heights[];
};

layout(std430, set = 0, binding = 2) writeonly buffer Result {
  vec4 result[];
};

#line 7 "terrain.spire"
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= params.count) return;
  result[i] = vec4(heights[i] * params.scale, 0.0, 0.0, 1.0);
}
)";

void expectValidModule(const SpirvResult& r) {
  ASSERT_TRUE(r.ok()) << r.log;
  EXPECT_EQ(r.log, "");
  ASSERT_GE(r.words.size(), 5u);
  EXPECT_EQ(r.words[0], kSpirvMagic);
  EXPECT_EQ(r.words[1], kSpirv15);
  const auto problem = validateSpirv(r.words);
  EXPECT_TRUE(problem) << problem.error().message;
}

TEST(SpirvCompilerTest, StageNames) {
  EXPECT_EQ(stageName(ShaderStage::Vertex), "vertex");
  EXPECT_EQ(stageName(ShaderStage::Fragment), "fragment");
  EXPECT_EQ(stageName(ShaderStage::Compute), "compute");
}

TEST(SpirvCompilerTest, VertexShaderCompilesAndValidates) {
  expectValidModule(compileGlslToSpirv(ShaderStage::Vertex, kVertexShader, "terrain.vert"));
}

TEST(SpirvCompilerTest, FragmentShaderCompilesAndValidates) {
  expectValidModule(compileGlslToSpirv(ShaderStage::Fragment, kFragmentShader, "terrain.frag"));
}

TEST(SpirvCompilerTest, ComputeShaderCompilesAndValidates) {
  expectValidModule(compileGlslToSpirv(ShaderStage::Compute, kComputeShader, "terrain.comp"));
}

TEST(SpirvCompilerTest, ErrorNamesSpireFileAndLineFromLineDirective) {
  const std::string glsl = R"(#version 440
#extension GL_GOOGLE_cpp_style_line_directive : require
layout(local_size_x = 64) in;
layout(std430, set = 0, binding = 0) buffer Out { float values[]; };
#line 42 "terrain.spire"
void main() {
  values[gl_GlobalInvocationID.x] = undeclaredHeight;
}
)";
  const SpirvResult r = compileGlslToSpirv(ShaderStage::Compute, glsl, "terrain.comp");
  EXPECT_FALSE(r.ok());
  EXPECT_TRUE(r.words.empty());
  // `void main() {` is line 42, so the error is on line 43.
  EXPECT_TRUE(contains(r.log, "terrain.spire:43"));
  EXPECT_TRUE(contains(r.log, "undeclaredHeight"));
  EXPECT_TRUE(contains(r.log, "ERROR"));
}

TEST(SpirvCompilerTest, ErrorOnTheLineDirectiveLineItself) {
  const std::string glsl = R"(#version 440
#extension GL_GOOGLE_cpp_style_line_directive : require
layout(location = 0) out vec4 outColor;
#line 42 "terrain.spire"
void main() { outColor = vec4(missingComponent); }
)";
  const SpirvResult r = compileGlslToSpirv(ShaderStage::Fragment, glsl, "terrain.frag");
  EXPECT_FALSE(r.ok());
  EXPECT_TRUE(contains(r.log, "terrain.spire:42"));
  EXPECT_TRUE(contains(r.log, "missingComponent"));
  // Once a #line names a file, the kernel's own name is not used for it.
  EXPECT_FALSE(contains(r.log, "terrain.frag:"));
}

TEST(SpirvCompilerTest, ErrorBeforeAnyLineDirectiveNamesTheKernel) {
  const std::string glsl = "#version 440\nvoid main() { int x = ; }\n";
  const SpirvResult r = compileGlslToSpirv(ShaderStage::Vertex, glsl, "Terrain_vs");
  EXPECT_FALSE(r.ok());
  EXPECT_TRUE(contains(r.log, "Terrain_vs:2"));
}

TEST(SpirvCompilerTest, LinkErrorIsReported) {
  // Parses, but a shader without main() fails at link time.
  const std::string glsl = "#version 440\nvoid helper() {}\n";
  const SpirvResult r = compileGlslToSpirv(ShaderStage::Vertex, glsl, "no_main");
  EXPECT_FALSE(r.ok());
  EXPECT_TRUE(contains(r.log, "Missing entry point"));
}

TEST(SpirvCompilerTest, WrongStageIsAnError) {
  // gl_Position is not writable from a compute shader.
  const std::string glsl = "#version 440\nlayout(local_size_x = 64) in;\nvoid main() { gl_Position = vec4(0.0); }\n";
  const SpirvResult r = compileGlslToSpirv(ShaderStage::Compute, glsl, "wrong_stage");
  EXPECT_FALSE(r.ok());
  EXPECT_TRUE(contains(r.log, "gl_Position"));
}

TEST(SpirvCompilerTest, OutputIsDeterministic) {
  const SpirvResult a = compileGlslToSpirv(ShaderStage::Fragment, kFragmentShader, "terrain.frag");
  const SpirvResult b = compileGlslToSpirv(ShaderStage::Fragment, kFragmentShader, "terrain.frag");
  ASSERT_TRUE(a.ok()) << a.log;
  EXPECT_EQ(a.words, b.words);
  const SpirvResult c = compileGlslToSpirv(ShaderStage::Compute, kComputeShader, "terrain.comp");
  const SpirvResult d = compileGlslToSpirv(ShaderStage::Compute, kComputeShader, "terrain.comp");
  ASSERT_TRUE(c.ok()) << c.log;
  EXPECT_EQ(c.words, d.words);
}

TEST(SpirvCompilerTest, ConcurrentCompilesMatchSerialOnes) {
  const std::vector<uint32_t> vertex = compileGlslToSpirv(ShaderStage::Vertex, kVertexShader, "v").words;
  const std::vector<uint32_t> fragment = compileGlslToSpirv(ShaderStage::Fragment, kFragmentShader, "f").words;
  const std::vector<uint32_t> compute = compileGlslToSpirv(ShaderStage::Compute, kComputeShader, "c").words;
  ASSERT_FALSE(vertex.empty());
  ASSERT_FALSE(fragment.empty());
  ASSERT_FALSE(compute.empty());

  constexpr int kThreads = 4;
  constexpr int kRounds = 5;
  std::vector<int> mismatches(kThreads, 0);
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&, t] {
      for (int round = 0; round < kRounds; ++round) {
        if (compileGlslToSpirv(ShaderStage::Vertex, kVertexShader, "v").words != vertex) ++mismatches[t];
        if (compileGlslToSpirv(ShaderStage::Fragment, kFragmentShader, "f").words != fragment) ++mismatches[t];
        if (compileGlslToSpirv(ShaderStage::Compute, kComputeShader, "c").words != compute) ++mismatches[t];
        if (compileGlslToSpirv(ShaderStage::Compute, "#version 440\nvoid main() { x; }\n", "bad").ok()) {
          ++mismatches[t];
        }
      }
    });
  }
  for (std::thread& thread : threads) thread.join();
  for (int t = 0; t < kThreads; ++t) EXPECT_EQ(mismatches[t], 0) << "thread " << t;
}

TEST(SpirvCompilerTest, ValidatorRejectsTruncatedModule) {
  const SpirvResult r = compileGlslToSpirv(ShaderStage::Compute, kComputeShader, "terrain.comp");
  ASSERT_TRUE(r.ok()) << r.log;
  std::vector<uint32_t> truncated(r.words.begin(), r.words.begin() + static_cast<std::ptrdiff_t>(r.words.size() / 2));
  const auto problem = validateSpirv(truncated);
  ASSERT_FALSE(problem);
  EXPECT_FALSE(problem.error().message.empty());
}

TEST(SpirvCompilerTest, ValidatorRejectsGarbage) {
  const auto problem = validateSpirv({0xdeadbeefu, 1u, 2u, 3u, 4u, 5u});
  ASSERT_FALSE(problem);
  EXPECT_TRUE(contains(problem.error().message, "error"));
}

TEST(SpirvCompilerTest, ValidatorRejectsEmptyModule) {
  const auto problem = validateSpirv({});
  ASSERT_FALSE(problem);
  EXPECT_FALSE(problem.error().message.empty());
}

TEST(SpirvCompilerTest, ValidatorRejectsStructurallyInvalidModule) {
  // A valid header followed by an instruction whose word count runs past the end.
  const SpirvResult r = compileGlslToSpirv(ShaderStage::Vertex, kVertexShader, "terrain.vert");
  ASSERT_TRUE(r.ok()) << r.log;
  std::vector<uint32_t> broken(r.words.begin(), r.words.begin() + 5);
  broken.push_back((50u << 16) | 17u);  // OpCapability claiming 50 words
  broken.push_back(1u);                 // Shader
  const auto problem = validateSpirv(broken);
  ASSERT_FALSE(problem);
  EXPECT_FALSE(problem.error().message.empty());
}

// Validation runs without friendly names first (they cost most of a valid
// module's validation); a module that fails is named in its message all the
// same.
TEST(SpirvCompilerTest, ValidatorNamesTheIdsOfAFailingModule) {
  const char* text = R"(
    OpCapability Shader
    OpMemoryModel Logical GLSL450
    OpEntryPoint Fragment %main "main"
    OpExecutionMode %main OriginUpperLeft
    OpName %main "main"
    OpName %ghost "ghost"
    %void = OpTypeVoid
    %fn = OpTypeFunction %void
    %float = OpTypeFloat 32
    %main = OpFunction %void None %fn
    %entry = OpLabel
    %sum = OpFAdd %float %ghost %ghost
    OpReturn
    OpFunctionEnd
  )";
  std::vector<uint32_t> words;
  ASSERT_TRUE(spvtools::SpirvTools(SPV_ENV_VULKAN_1_2).Assemble(text, &words));
  const auto problem = validateSpirv(words);
  ASSERT_FALSE(problem);
  // The message's own text, not only the disassembled instruction under it.
  EXPECT_TRUE(contains(problem.error().message, "ID '2[%ghost]' has not been defined")) << problem.error().message;
}

}  // namespace
}  // namespace spire::codegen
