#include "driver/compiler.h"

#include "driver/spirv_cache.h"

#include <fmt/format.h>

#include <cstring>
#include <filesystem>

#include "codegen/kernel_generator.h"
#include "codegen/spirv_compiler.h"
#include "graph/locked_placement.h"
#include "sema/attribute_catalog.h"
#include "support/content_hash.h"
#include "support/file_io.h"
#include "support/spelling.h"
#include "support/utf8.h"

namespace spire {
namespace {

// Equal keys, equal compiled variants: the shader, every live component's
// placement and attributes, and whether SPIR-V was made.
std::string variantKey(const graph::Variant& variant, const CompileOptions& options) {
  std::string key = fmt::format("{}\n{}", variant.graph().shader().name, variant.placementText());
  for (sem::ComponentId c : variant.live()) {
    for (const auto& [name, value] : variant.attributes(c)) key += fmt::format("{}[{}={}]\n", c, name, value);
  }
  return key + (options.spirv ? "spirv" : "glsl") + (options.instrumentHazards ? "+hazards" : "");
}

std::string spirvBytes(const std::vector<uint32_t>& words) {
  std::string bytes(words.size() * sizeof(uint32_t), '\0');
  std::memcpy(bytes.data(), words.data(), bytes.size());
  return bytes;
}

// Saves a rejected kernel's text and says where (or why not).
std::string saveRejected(const codegen::Kernel& kernel, const std::string& root, const std::string& directory) {
  if (root.empty()) return "run spirec -o DIR on this variant to save the kernel for a bug report";
  const std::filesystem::path path = std::filesystem::path(root) / directory / kernel.reflection.glslFile;
  std::error_code ignored;
  std::filesystem::create_directories(path.parent_path(), ignored);
  if (auto written = writeFileAtomically(path.string(), kernel.glsl); !written) return written.error().message;
  return fmt::format("the kernel is saved as '{}'", path.string());
}

// Compiles and validates one kernel. glslang or the validator rejecting
// generated code is a compiler bug: an internal error against the shader.
bool compileKernel(const codegen::Kernel& generated, const sem::Shader& shader, const CompileOptions& options,
                   const std::string& directory, CompiledKernel& kernel, DiagnosticList& diags) {
  const std::string& name = generated.reflection.glslFile;
  SpirvCache* cache = options.spirvCache;
  if (cache != nullptr) {
    if (auto words = cache->find(generated.stage, name, generated.glsl)) {
      kernel.spirv = std::move(*words);
      return true;
    }
  }
  const codegen::SpirvResult spirv = codegen::compileGlslToSpirv(generated.stage, generated.glsl, name);
  const Expected<void, Failure> valid = spirv.ok() ? codegen::validateSpirv(spirv.words) : Failure{spirv.log};
  if (valid) {
    kernel.spirv = spirv.words;
    if (cache != nullptr) cache->add(generated.stage, name, generated.glsl, spirv.words);
    return true;
  }
  diags
      .report(DiagCode::E6002, shader.decl->nameRange,
              fmt::format("internal error: the generated {} kernel of '{}' was rejected; this is a spirec bug",
                          generated.world, shader.name))
      .note({}, valid.error().message)
      .note({}, saveRejected(generated, options.saveRejectedTo, directory));
  return false;
}

CompileError failure(std::string message, DiagnosticList& diags) {
  return CompileError{std::move(message), diags.takeSince(0)};
}

const graph::ChoiceSpace* findShader(const ShaderLibrary& library, std::string_view shader, CompileError& error) {
  if (const graph::ChoiceSpace* space = library.choiceSpace(shader)) return space;
  const std::vector<std::string> names = library.shaderNames();
  const std::vector<std::string_view> candidates(names.begin(), names.end());
  const auto suggestion = closestSpelling(shader, candidates);
  error.message = fmt::format("there is no concrete shader named '{}'{}", shader,
                              suggestion ? fmt::format("; did you mean '{}'?", *suggestion) : "");
  return nullptr;
}

// The compiled variant, or the failure with every diagnostic reported.
CompileResult finish(ShaderLibrary& library, const std::optional<graph::Variant>& variant,
                     const CompileOptions& options, DiagnosticList& diags, std::string_view shader,
                     std::vector<std::string> skipped = {}) {
  if (!variant || diags.hasErrors())
    return failure(fmt::format("no variant of '{}' for these decisions", shader), diags);
  if (options.strictDecisions && diags.warningCount() > 0) {
    return failure(fmt::format("not every decision for '{}' applies, so this is not the variant asked for", shader),
                   diags);
  }
  CompiledVariantPtr compiled = compileVariant(library, *variant, options, diags);
  if (!compiled) return failure(fmt::format("cannot compile this variant of '{}'", shader), diags);
  if (diags.size() == 0) return compiled;
  auto withWarnings = std::make_shared<CompiledVariant>(*compiled);
  withWarnings->warnings = diags.takeSince(0);
  withWarnings->skippedDecisions = std::move(skipped);
  return CompiledVariantPtr(std::move(withWarnings));
}

// In-memory attributes get the checks a decision file's get when it is
// read: a value that is not UTF-8 text is skipped with a warning (it would
// reach reflection.json, and JSON holds only UTF-8 text); the others are
// checked against the attribute catalogue (E5010, W5011).
ShaderLibrary::Attributes checkedAttributes(const ShaderLibrary::Attributes& attributes, DiagnosticList& diags) {
  ShaderLibrary::Attributes kept;
  for (const auto& [component, list] : attributes) {
    for (const auto& [name, value] : list) {
      if (utf8::firstInvalidByte(value) != std::string::npos) {
        diags.report(DiagCode::W5003, {},
                     fmt::format("the attribute '{}' of '{}' is not applied: its value is not valid UTF-8 text", name,
                                 component));
        continue;
      }
      if (auto problem = sem::checkAttribute(sem::AttributeSite::Decision, name, value)) {
        diags.report(problem->isError ? DiagCode::E5010 : DiagCode::W5011, {},
                     fmt::format("'{}': {}", component, problem->message));
      }
      kept[component].emplace_back(name, value);
    }
  }
  return kept;
}

}  // namespace

CompiledVariantPtr compileVariant(ShaderLibrary& library, const graph::Variant& variant, const CompileOptions& options,
                                  DiagnosticList& diags) {
  auto& cache = library.compiledVariants();
  const std::string key = variantKey(variant, options);
  if (const auto it = cache.find(key); it != cache.end()) return it->second;
  const auto generated =
      codegen::generateKernels(library.model(), library.sources(), variant, codegen::StrategyRegistry::builtin(), diags,
                               {.instrumentHazards = options.instrumentHazards});
  if (!generated) return nullptr;
  auto compiled = std::make_shared<CompiledVariant>();
  compiled->shader = generated->shader;
  compiled->directory = generated->directory;
  compiled->reflection = generated->reflection(variant);
  compiled->placement = variant.placementText();
  bool ok = true;
  for (size_t i = 0; i < generated->kernels.size(); ++i) {
    CompiledKernel& kernel = compiled->kernels.emplace_back();
    kernel.glsl = generated->kernels[i].glsl;
    if (!options.spirv) continue;
    if (!compileKernel(generated->kernels[i], variant.graph().shader(), options, generated->directory, kernel, diags)) {
      ok = false;
      continue;
    }
    compiled->reflection.kernels[i].spirvHash = spire::contentHash(spirvBytes(kernel.spirv));
  }
  if (!ok) return nullptr;
  return cache.emplace(key, std::move(compiled)).first->second;
}

CompileResult compileVariant(ShaderLibrary& library, std::string_view shader, const graph::DecisionFile& decisions,
                             const CompileOptions& options) {
  CompileError error;
  const graph::ChoiceSpace* space = findShader(library, shader, error);
  if (!space) return error;
  DiagnosticList diags;
  const std::optional<graph::Variant> variant = graph::applyDecisions(decisions, *space, diags);
  return finish(library, variant, options, diags, shader);
}

CompileResult compileVariant(ShaderLibrary& library, std::string_view shader, const Decisions& decisions,
                             const CompileOptions& options) {
  CompileError error;
  if (!findShader(library, shader, error)) return error;
  DiagnosticList diags;
  const ShaderLibrary::Attributes attributes = checkedAttributes(decisions.attributes, diags);
  std::vector<std::string> skipped;
  const std::optional<graph::Variant> variant = library.buildVariant(shader, decisions.placement, &skipped, attributes);
  if (!variant) graph::reportLockedMove(*library.choiceSpace(shader), diags);
  for (const std::string& component : skipped) {
    diags.report(
        DiagCode::W5003, {},
        fmt::format("the decision for '{}' is not applied: unknown, or infeasible with the others", component));
  }
  return finish(library, variant, options, diags, shader, std::move(skipped));
}

}  // namespace spire
