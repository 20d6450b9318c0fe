#include "gen/variant_checker.h"

#include <fmt/format.h>

#include <algorithm>
#include <exception>

#include "codegen/kernel_generator.h"
#include "codegen/spirv_compiler.h"
#include "gen/interface_check.h"
#include "graph/decision_file.h"
#include "reflection/reflection_json.h"
#include "support/diagnostic_renderer.h"
#include "support/file_io.h"

namespace spire::testgen {
namespace {

constexpr const char* kDecisionsPath = "generated.decisions";

bool hasInternalError(const DiagnosticList& diags) {
  for (const Diagnostic& d : diags.all()) {
    if (d.code == DiagCode::E6002) return true;
  }
  return false;
}

// What a variant means, independent of binding numbers: the placement, and
// for each kernel input the world and strategy it comes through.
// Inputs are listed in import declaration order, so the lines are sorted.
std::string routesOf(const codegen::GeneratedShader& generated, const graph::Variant& variant) {
  std::vector<std::string> lines;
  for (const codegen::Kernel& k : generated.kernels) {
    for (const reflection::KernelInput& input : k.reflection.inputs) {
      lines.push_back(fmt::format("{} reads {} from {} by {}\n", k.world, input.component, input.from, input.strategy));
    }
  }
  std::sort(lines.begin(), lines.end());
  std::string out = variant.placementText();
  for (const std::string& line : lines) out += line;
  return out;
}

// The topmost shader of `shader`'s base chain that locks `world`: the one
// whose `finalizes` clause names it.
const sem::Shader& lockingBase(const sem::Shader& shader, sem::WorldId world) {
  const sem::Shader* top = &shader;
  for (const sem::Shader* s = shader.base; s; s = s->base) {
    if (std::find(s->finalizedWorlds.begin(), s->finalizedWorlds.end(), world) != s->finalizedWorlds.end()) top = s;
  }
  return *top;
}

std::map<std::string, std::string> lockedKernelsOf(const codegen::GeneratedShader& generated,
                                                   const graph::Variant& variant) {
  std::map<std::string, std::string> out;
  const sem::Shader& shader = variant.graph().shader();
  for (sem::WorldId w : shader.finalizedWorlds) {
    const std::string& world = variant.graph().pipeline().worlds[w].name;
    std::string& text = out[lockingBase(shader, w).name + "/" + world];
    for (const codegen::Kernel& k : generated.kernels) {
      if (k.world == world) text = k.glsl;
    }
  }
  return out;
}

}  // namespace

const char* verdictName(Verdict verdict) {
  switch (verdict) {
    case Verdict::Accepted: return "accepted";
    case Verdict::Refused: return "refused";
    case Verdict::InternalError: return "internal error";
    case Verdict::InvalidKernel: return "invalid kernel";
    case Verdict::InterfaceMismatch: return "interface mismatch";
    case Verdict::OrderDependentRoute: return "order-dependent route";
    case Verdict::LockedKernelNotShared: return "locked kernel not shared";
  }
  return "?";
}

FrontEndOptions ProgramChecker::readingDecisionsFromMemory() {
  FrontEndOptions options;
  options.readFile = [this](const std::string& path) -> std::optional<std::string> {
    return path == kDecisionsPath ? std::optional(decisions_) : readWholeFile(path);
  };
  return options;
}

ProgramChecker::ProgramChecker(std::string source, std::string displayPath, bool compileKernels)
    : compileKernels_(compileKernels), library_(readingDecisionsFromMemory()) {
  library_.addSource(std::move(displayPath), std::move(source));
  try {
    if (!library_.compile()) frontEnd_ = refusal("", library_.diagnostics());
  } catch (const std::exception& e) {
    frontEnd_ = {"", Verdict::InternalError, {}, fmt::format("exception in the front end: {}", e.what()), {}, {}};
  }
}

// A refusal must carry an error that is not E6002; anything else is an
// internal error.
VariantReport ProgramChecker::refusal(std::string shader, const DiagnosticList& diags) const {
  VariantReport r{std::move(shader),
                  Verdict::Refused,
                  {},
                  renderDiagnostics(library_.sources(), diags, DiagnosticFormat::Text),
                  {},
                  {}};
  for (const Diagnostic& d : diags.all()) {
    if (d.severity == Severity::Error) r.codes.emplace_back(diagCodeInfo(d.code).name);
  }
  if (r.codes.empty() || hasInternalError(diags)) {
    r.verdict = Verdict::InternalError;
    if (r.codes.empty()) r.detail += "\n(refused without an error diagnostic)";
  }
  return r;
}

std::vector<VariantReport> ProgramChecker::check(const std::string& decisions) {
  decisions_ = decisions;
  DiagnosticList parseDiags;
  const auto file = library_.frontEnd().loadAuxiliaryFile(kDecisionsPath);
  const graph::DecisionFile parsed =
      file ? graph::parseDecisionFile(library_.sources(), *file, parseDiags) : graph::DecisionFile{};
  if (!file || parseDiags.hasErrors()) return {refusal("", parseDiags)};
  std::vector<VariantReport> reports;
  for (const std::string& name : library_.shaderNames()) {
    DiagnosticList diags;
    try {
      const auto variant = graph::applyDecisions(parsed, *library_.choiceSpace(name), diags);
      reports.push_back(variant ? checkVariant(*variant, diags) : refusal(name, diags));
    } catch (const std::exception& e) {
      reports.push_back({name, Verdict::InternalError, {}, fmt::format("exception: {}", e.what()), {}, {}});
    }
    reports.back().shader = name;
  }
  return reports;
}

VariantReport ProgramChecker::checkVariant(const graph::Variant& variant, DiagnosticList& diags) {
  const auto generated = codegen::generateKernels(library_.model(), library_.sources(), variant,
                                                  codegen::StrategyRegistry::builtin(), diags);
  if (!generated || diags.hasErrors()) return refusal("", diags);
  if (!compileKernels_)
    return {"", Verdict::Accepted, {}, {}, routesOf(*generated, variant), lockedKernelsOf(*generated, variant)};
  for (const codegen::Kernel& kernel : generated->kernels) {
    if (auto problem = kernelProblem(kernel)) {
      return {"", Verdict::InvalidKernel,
              {}, fmt::format("{} kernel: {}\n--- {}.glsl ---\n{}", kernel.world, *problem, kernel.world, kernel.glsl),
              {}, {}};
    }
  }
  const std::vector<std::string> mismatches =
      checkInterfaces(*generated, variant.graph().pipeline(), variant.graph().shader().finalizedWorlds);
  if (!mismatches.empty()) {
    std::string detail;
    for (const std::string& m : mismatches) detail += m + "\n";
    return {"", Verdict::InterfaceMismatch, {}, detail + reflection::toJson(generated->reflection(variant)).dump(2), {},
            {}};
  }
  return {"", Verdict::Accepted, {}, {}, routesOf(*generated, variant), lockedKernelsOf(*generated, variant)};
}

// glslang's log or the validator's message, or nothing for a good kernel.
std::optional<std::string> ProgramChecker::kernelProblem(const codegen::Kernel& kernel) {
  const std::string key = std::string(codegen::stageName(kernel.stage)) + "\n" + kernel.glsl;
  if (const auto it = kernelCache_.find(key); it != kernelCache_.end()) return it->second;
  const codegen::SpirvResult spirv = codegen::compileGlslToSpirv(kernel.stage, kernel.glsl, kernel.world + ".glsl");
  std::optional<std::string> problem;
  if (!spirv.ok())
    problem = "glslang: " + spirv.log;
  else if (auto valid = codegen::validateSpirv(spirv.words); !valid)
    problem = "spirv-val: " + valid.error().message;
  kernelCache_.emplace(key, problem);
  return problem;
}

}  // namespace spire::testgen
