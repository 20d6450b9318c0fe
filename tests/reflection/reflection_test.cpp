// The typed reflection records and their one JSON form: every kernel the
// examples can produce survives the round trip unchanged, value types are
// read from their GLSL spelling once, and malformed documents are errors
// that name what is wrong.
#include "reflection/reflection_json.h"

#include <gtest/gtest.h>

#include <string>

#include "driver/compiler.h"
#include "driver/shader_library.h"

namespace spire::reflection {
namespace {

TEST(ReflectionValueType, ParsesNumericTypes) {
  const ValueType mat = parseValueType("mat3x4");
  ASSERT_TRUE(mat.isNumeric());
  EXPECT_EQ(mat.columns, 3U);
  EXPECT_EQ(mat.rows, 4U);
  EXPECT_EQ(mat.componentCount(), 12U);
  EXPECT_EQ(parseValueType("vec2[3]").componentCount(), 6U);
  EXPECT_EQ(parseValueType("uvec3").scalar, ValueType::Scalar::Uint);
  EXPECT_EQ(parseValueType("sampler2D").kind, ValueType::Kind::Sampler);
  for (const char* other : {"vec5", "float[0]", "float[2][2]", "Light", ""}) {
    EXPECT_EQ(parseValueType(other).kind, ValueType::Kind::Other) << other;
    EXPECT_EQ(parseValueType(other).name, other);
  }
}

// Every variant that differs from the default in one decision, for every
// shader of the examples: each is a different mix of strategies and kinds.
TEST(ReflectionJson, EveryKernelOfTheExamplesSurvivesTheRoundTrip) {
  size_t variants = 0;
  for (const char* file : {"terrain.spire", "couch.spire", "terrain_five_world.spire", "lod_library.spire"}) {
    ShaderLibrary library;
    library.addFile(std::string(SPIRE_SOURCE_DIR) + "/examples/" + file);
    ASSERT_TRUE(library.compile()) << file;
    CompileOptions glslOnly;
    glslOnly.spirv = false;
    for (const std::string& shader : library.shaderNames()) {
      std::vector<Decisions> all{{}};
      for (const graph::Choice& choice : library.choices(shader)) {
        const std::string component = choice.key.substr(choice.key.find('.') + 1);
        for (const std::string& name : choice.names) all.push_back({{{component, name}}, {}});
      }
      for (const Decisions& decisions : all) {
        const auto compiled = compileVariant(library, shader, decisions, glslOnly);
        if (!compiled) continue;  // an alternative only feasible with other decisions
        const Variant& variant = (*compiled)->reflection;
        const auto json = toJson(variant);
        const auto reread = fromJson(json);
        ASSERT_TRUE(reread) << shader << ": " << reread.error();
        EXPECT_EQ(*reread, variant) << shader << "\n" << json.dump(2);
        EXPECT_EQ(toJson(*reread).dump(), json.dump());
        ++variants;
      }
    }
  }
  EXPECT_GT(variants, 40U);
}

// Instrumented kernels (CompileOptions::instrumentHazards) of every single
// decision of the examples compile to validated SPIR-V, bind every resource
// where the plain kernel does, add their record at a slot of their own, give
// each checked value a code in evaluation order, and survive the JSON round
// trip with their hazard records.
TEST(ReflectionJson, InstrumentedKernelsKeepTheirInterfaceAndRecordHazards) {
  size_t kernels = 0;
  for (const char* file : {"couch.spire", "terrain_five_world.spire"}) {
    ShaderLibrary library;
    library.addFile(std::string(SPIRE_SOURCE_DIR) + "/examples/" + file);
    ASSERT_TRUE(library.compile()) << file;
    CompileOptions instrumented;
    instrumented.instrumentHazards = true;
    for (const std::string& shader : library.shaderNames()) {
      std::vector<Decisions> all{{}};
      for (const graph::Choice& choice : library.choices(shader)) {
        const std::string component = choice.key.substr(choice.key.find('.') + 1);
        all.push_back({{{component, choice.names.front()}}, {}});
      }
      for (const Decisions& decisions : all) {
        const auto plain = compileVariant(library, shader, decisions);
        const auto checked = compileVariant(library, shader, decisions, instrumented);
        ASSERT_TRUE(plain && checked) << shader;
        const reflection::Variant& a = (*plain)->reflection;
        const reflection::Variant& b = (*checked)->reflection;
        ASSERT_EQ(a.kernels.size(), b.kernels.size());
        for (size_t k = 0; k < a.kernels.size(); ++k) {
          const reflection::Kernel& p = a.kernels[k];
          const reflection::Kernel& q = b.kernels[k];
          EXPECT_FALSE(p.hazards);
          ASSERT_TRUE(q.hazards) << q.world;
          EXPECT_EQ(p.inputs, q.inputs);
          EXPECT_EQ(p.outputs, q.outputs);
          EXPECT_EQ(p.blocks, q.blocks);
          for (const reflection::Block& block : q.blocks) EXPECT_NE(block.slot, q.hazards->slot);
          for (const reflection::KernelInput& input : q.inputs) {
            if (input.kind != reflection::InputKind::Varying && input.kind != reflection::InputKind::PushConstant) {
              EXPECT_NE(input.slot, q.hazards->slot);
            }
          }
          uint32_t code = 0;
          for (const reflection::HazardValue& v : q.hazards->values) {
            if (v.code == 0) continue;
            EXPECT_EQ(v.code, ++code) << v.component;
            EXPECT_FALSE(v.source.empty());
          }
          EXPECT_EQ(std::max(code, 1U), q.hazards->slots);
          EXPECT_FALSE((*checked)->kernels[k].spirv.empty());
          ++kernels;
        }
        const auto json = toJson(b);
        const auto reread = fromJson(json);
        ASSERT_TRUE(reread) << reread.error();
        EXPECT_EQ(*reread, b);
      }
    }
  }
  EXPECT_GT(kernels, 30U);
}

nlohmann::ordered_json terrainReflection() {
  ShaderLibrary library;
  library.addFile(std::string(SPIRE_SOURCE_DIR) + "/examples/terrain.spire");
  EXPECT_TRUE(library.compile());
  CompileOptions glslOnly;
  glslOnly.spirv = false;
  const auto compiled = compileVariant(library, "Terrain", Decisions{}, glslOnly);
  EXPECT_TRUE(compiled);
  return compiled ? toJson((*compiled)->reflection) : nlohmann::ordered_json{};
}

// Found by spire_variant_fuzzer: an attribute value that is not UTF-8 went
// into the kernel key's JSON, whose writer threw during code generation.
TEST(ReflectionJson, AttributeValuesThatAreNotUtf8AreSkipped) {
  ShaderLibrary library;
  library.addFile(std::string(SPIRE_SOURCE_DIR) + "/examples/terrain.spire");
  ASSERT_TRUE(library.compile());
  CompileOptions glslOnly;
  glslOnly.spirv = false;
  const Decisions decisions{{{"albedo", "PrebakeTex"}}, {{"albedo", {{"Format", "\xff"}, {"TextureSize", "512"}}}}};
  const auto compiled = compileVariant(library, "Terrain", decisions, glslOnly);
  ASSERT_TRUE(compiled);
  ASSERT_EQ((*compiled)->warnings.size(), 1u);
  EXPECT_EQ((*compiled)->warnings[0].code, DiagCode::W5003);
  const std::string json = toJson((*compiled)->reflection).dump();
  EXPECT_NE(json.find("TextureSize"), std::string::npos);
  EXPECT_EQ(json.find("Format"), std::string::npos);
}

std::string errorOf(const nlohmann::ordered_json& document) {
  const auto variant = fromJson(document);
  return variant ? std::string("(accepted)") : variant.error();
}

TEST(ReflectionJson, MalformedDocumentsAreErrorsNamingTheEntry) {
  const nlohmann::ordered_json good = terrainReflection();
  ASSERT_TRUE(fromJson(good));
  auto wrongKind = good;
  wrongKind["kernels"][1]["inputs"][0]["kind"] = "telepathy";
  EXPECT_NE(errorOf(wrongKind).find("kernel 'Fragment', input"), std::string::npos) << errorOf(wrongKind);
  auto missing = good;
  missing["kernels"][0]["inputs"][0].erase("strategy");
  EXPECT_NE(errorOf(missing).find("kernel 'Vertex'"), std::string::npos) << errorOf(missing);
  auto oldVersion = good;
  oldVersion["version"] = 1;
  EXPECT_NE(errorOf(oldVersion).find("compile the shader again"), std::string::npos);
  EXPECT_NE(parseReflection("{\"format\": ").error().find("not valid JSON"), std::string::npos);
  auto badStage = good;
  badStage["kernels"][0]["stage"] = "geometry";
  EXPECT_NE(errorOf(badStage).find("unknown stage"), std::string::npos);
}

}  // namespace
}  // namespace spire::reflection
