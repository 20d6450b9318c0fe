// libFuzzer target for variants: the input bytes choose a shader and make
// decisions for its choices, and the variant goes through the one compile
// path, spire::compileVariant, as the engine and the tuner use it.
//
// The bytes, in order:
//   1 byte   the shader: one of the examples (fuzz_support.h), or from 240 up
//            a program of tests/gen (generateProgram) whose seed is the next
//            4 bytes, and a byte choosing one of its shaders;
//   1 byte   per choice (ShaderLibrary::choices): below 48 undecided, from
//            250 up an alternative outside the space, else alternative
//            `byte % count`;
//   2 bytes  per attribute, to the end (at most 8): a choice and one of a few
//            attributes, hostile values included.
// Past the end every byte reads as 0. About one input in 64 (by a hash of all
// of it, so that mutating any byte re-rolls it) is compiled with SPIR-V:
// glslang and spirv-val, a hundred times slower than the rest. Variants go
// through a bounded cache (fuzz_support.h): one compiled before is not
// generated or checked again.
//
// Findings: a crash; a kernel glslang or the validator rejects (E6002: the
// compiler generated invalid code); reflection that does not survive its JSON
// writer and reader; SPIR-V that changes the GLSL or the reflection.
//
// Built two ways (see CMakeLists.txt beside this file):
//   spire_variant_fuzzer  clang + -fsanitize=fuzzer,address,undefined (fuzz preset)
//   spire_variant_replay  any compiler, with replay_main.cpp: the CTest
//                         FuzzVariantCorpusRegression over corpus_variants/
#include <fmt/format.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "fuzz/fuzz_support.h"
#include "gen/program_generator.h"
#include "reflection/reflection_json.h"
#include "support/content_hash.h"
#include "support/diagnostic_renderer.h"

namespace {

using namespace spire;

class ByteReader {
 public:
  ByteReader(const uint8_t* data, size_t size) : data_(data), size_(size) {}
  bool done() const { return pos_ >= size_; }
  uint8_t next() { return pos_ < size_ ? data_[pos_++] : 0; }
  uint32_t next32() {
    uint32_t value = 0;
    for (int i = 0; i < 4; ++i) value = value << 8 | next();
    return value;
  }

 private:
  const uint8_t* data_;
  size_t size_;
  size_t pos_ = 0;
};

struct Target {
  std::string shader;
  std::vector<graph::Choice> choices;
};

const std::vector<Target>& exampleTargets() {
  static const std::vector<Target> targets = [] {
    std::vector<Target> out;
    const ShaderLibrary& library = fuzz::exampleLibrary();
    for (const std::string& name : library.shaderNames()) out.push_back({name, library.choices(name)});
    return out;
  }();
  return targets;
}

// Attributes as decision lines carry them; the last values are what a
// hostile decision file can write (invalid UTF-8, quotes, backslashes).
constexpr std::array<std::pair<const char*, const char*>, 10> kAttributes{{
    {"Format", "RGBA8"},
    {"Format", "RGB10_A2"},
    {"Format", "R8"},
    {"TextureSize", "512"},
    {"TextureSize", "0"},
    {"TextureSize", "4294967296"},
    {"Filter", "nearest"},
    {"Format", ""},
    {"Format", "\"\\\n"},
    {"Format", "\xff\xfe"},
}};

std::string componentOf(const graph::Choice& choice) { return choice.key.substr(choice.key.rfind('.') + 1); }

Decisions readDecisions(const std::vector<graph::Choice>& choices, ByteReader& in) {
  Decisions decisions;
  for (const graph::Choice& choice : choices) {
    const uint8_t b = in.next();
    if (b < 48) continue;
    std::string value = choice.names[b % choice.names.size()];
    if (b >= 250) value = b % 2 ? "NoSuchWorld" : value + ":noSuchVariation";
    decisions.placement[componentOf(choice)] = std::move(value);
  }
  for (int i = 0; i < 8 && !choices.empty() && !in.done(); ++i) {
    const graph::Choice& choice = choices[in.next() % choices.size()];
    const auto& [name, value] = kAttributes[in.next() % kAttributes.size()];
    decisions.attributes[componentOf(choice)].emplace_back(name, value);
  }
  return decisions;
}

// About one input in 64, deterministically from all of its bytes.
bool sampledForSpirv(const uint8_t* data, size_t size) {
  const std::string hash = spire::contentHash({reinterpret_cast<const char*>(data), size});
  return std::stoul(hash.substr(hash.size() - 2), nullptr, 16) % 64 == 0;
}

reflection::Variant withoutSpirvHashes(reflection::Variant variant) {
  for (reflection::Kernel& kernel : variant.kernels) kernel.spirvHash.clear();
  return variant;
}

[[noreturn]] void internalError(const ShaderLibrary& library, const CompileError& error) {
  DiagnosticList diags;
  fuzz::reportAll(error.diagnostics, diags);
  std::fputs(renderDiagnostics(library.sources(), diags, DiagnosticFormat::Text).c_str(), stderr);
  fuzz::fail("the compiler generated a kernel that glslang or spirv-val rejects (E6002)");
}

// The variant with SPIR-V must be the GLSL-only variant plus SPIR-V.
void compareWithGlslOnly(ShaderLibrary& library, const std::string& shader, const Decisions& decisions,
                         const CompiledVariant& withSpirv) {
  CompileOptions glslOnly;
  glslOnly.spirv = false;
  const CompileResult result = compileVariant(library, shader, decisions, glslOnly);
  if (!result) fuzz::fail("a variant that compiles with SPIR-V is refused without it");
  const CompiledVariant& plain = **result;
  if (plain.kernels.size() != withSpirv.kernels.size()) fuzz::fail("SPIR-V changes the number of kernels");
  for (size_t i = 0; i < plain.kernels.size(); ++i) {
    if (plain.kernels[i].glsl != withSpirv.kernels[i].glsl) fuzz::fail("SPIR-V changes a kernel's GLSL");
  }
  if (!(withoutSpirvHashes(withSpirv.reflection) == plain.reflection)) fuzz::fail("SPIR-V changes the reflection");
}

void compileAndCheck(ShaderLibrary& library, const std::string& shader, const Decisions& decisions, bool spirv) {
  CompileOptions options;
  options.spirv = spirv;
  bool fresh = false;
  const CompileResult result = fuzz::compileCached(library, shader, decisions, options, fresh);
  if (!result) {
    if (fuzz::hasInternalError(result.error().diagnostics)) internalError(library, result.error());
    if (result.error().message.empty()) fuzz::fail("a refused variant without a message");
    return;
  }
  if (!fresh) return;  // checked when it was compiled
  fuzz::checkCompiled(**result, spirv);
  if (spirv) compareWithGlslOnly(library, shader, decisions, **result);
}

// A program of tests/gen, compiled for this input alone; refused programs
// are the generator's business (bench/generate-and-check), not a finding.
void fuzzGenerated(ByteReader& in, bool spirv) {
  const testgen::GeneratedProgram program = testgen::generateProgram(in.next32());
  FrontEndOptions options;
  options.readFile = [](const std::string&) -> std::optional<std::string> { return std::nullopt; };
  ShaderLibrary library(std::move(options));
  library.addSource("generated.spire", program.text);
  if (!library.compile()) return;
  const std::vector<std::string> shaders = library.shaderNames();
  if (shaders.empty()) return;
  const std::string& shader = shaders[in.next() % shaders.size()];
  compileAndCheck(library, shader, readDecisions(library.choices(shader), in), spirv);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  ByteReader in(data, size);
  const bool spirv = sampledForSpirv(data, size);
  const uint8_t pick = in.next();
  if (pick >= 240) {
    fuzzGenerated(in, spirv);
    return 0;
  }
  ShaderLibrary& library = fuzz::exampleLibrary();
  const Target& target = exampleTargets()[pick % exampleTargets().size()];
  compileAndCheck(library, target.shader, readDecisions(target.choices, in), spirv);
  return 0;
}
