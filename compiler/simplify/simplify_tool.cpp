#include "simplify/simplify_tool.h"

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include <ostream>

#include "driver/exit_codes.h"
#include "driver/shader_library.h"
#include "driver/tool_arguments.h"
#include "graph/decision_file.h"
#include "simplify/simplification.h"
#include "simplify/user_rules.h"
#include "simplify/variant_cost.h"
#include "support/diagnostic_renderer.h"
#include "support/file_io.h"

namespace spire::simplify {
namespace {

constexpr const char* kTool = "spire-simplify";

struct CliOptions {
  std::vector<std::string> files;
  std::vector<std::string> includeDirs;
  std::vector<std::string> ruleFiles;
  bool costs = false;
  std::string decisionsPath;  // with --costs
  SimplifyOptions simplify;
};

void defineOptions(CLI::App& app, CliOptions& options) {
  addVersionFlag(app);
  app.add_option("files", options.files, "Spire source files")->required()->type_name("FILE...");
  app.add_option("-I", options.includeDirs, "Search DIR for 'using' includes after the including file's folder")
      ->type_name("DIR");
  app.add_option("--shader", options.simplify.shader, "The shader to simplify")->required()->type_name("NAME");
  app.add_option("--component", options.simplify.components,
                 "Simplify only this component (repeatable; default: every one the shader defines)")
      ->type_name("NAME");
  app.add_option("--max-per-component", options.simplify.maxPerComponent,
                 "At most N variations per component (default 4)")
      ->check(CLI::Range(size_t{1}, size_t{1000}))
      ->type_name("N");
  app.add_option("--rules", options.ruleFiles,
                 "Also apply the rules of FILE: one a line, 'rule NAME: PATTERN -> REPLACEMENT' with $metavariables "
                 "(repeatable; docs/simplify.md, \"User rules\")")
      ->type_name("FILE");
  app.add_option("--name", options.simplify.derivedName, "The derived shader's name (default: SHADER + Simplified)")
      ->type_name("NAME");
  CLI::Option* costs = app.add_flag(
      "--costs", options.costs,
      "Print the shader's cost under its default decisions (He et al. 2015: C = 0.3 C_v + 0.7 C_f + 10 N_var) "
      "instead of simplifying");
  app.add_option("--decisions", options.decisionsPath,
                 "With --costs: the variant of the decision file PATH instead of the default decisions")
      ->needs(costs)
      ->type_name("PATH");
  app.add_option("-o,--output", options.simplify.outputPath,
                 "Write the module of simplified variations to FILE (required unless --costs)")
      ->excludes(costs)
      ->type_name("FILE");
}

// The shader's variant for --costs: the decision file's, or the default
// decisions (every component in its latest feasible world, as spirec
// without --decisions). nullopt after printing why not.
std::optional<graph::Variant> costedVariant(ShaderLibrary& library, const CliOptions& options, std::ostream& err) {
  const graph::ChoiceSpace* space = library.choiceSpace(options.simplify.shader);
  if (!space) {
    err << fmt::format("{}: error: no concrete shader named '{}'\n", kTool, options.simplify.shader);
    return std::nullopt;
  }
  graph::DecisionFile decisions;
  if (!options.decisionsPath.empty()) {
    if (const auto id = library.frontEnd().loadAuxiliaryFile(options.decisionsPath)) {
      decisions = graph::parseDecisionFile(library.sources(), *id, library.diagnostics());
    }
  }
  std::optional<graph::Variant> variant;
  if (!library.diagnostics().hasErrors()) variant = graph::applyDecisions(decisions, *space, library.diagnostics());
  // Warnings too: a decision skipped changes what is costed.
  if (!library.diagnostics().all().empty()) {
    err << renderDiagnostics(library.sources(), library.diagnostics(), DiagnosticFormat::Text);
  }
  return library.diagnostics().hasErrors() ? std::nullopt : variant;
}

int printCosts(ShaderLibrary& library, const CliOptions& options, std::ostream& out, std::ostream& err) {
  const std::optional<graph::Variant> variant = costedVariant(library, options, err);
  if (!variant) return kExitInputError;
  const std::string decisions = options.decisionsPath.empty()
                                    ? "its default decisions"
                                    : fmt::format("the decisions of {}", options.decisionsPath);
  out << formatVariantCost(
      variantCost(library.model(), *variant),
      fmt::format("{} under {} (He et al. 2015's cost model, docs/simplify.md):", options.simplify.shader, decisions));
  return kExitSuccess;
}

void printSummary(const Simplified& result, const std::string& path, std::ostream& out) {
  size_t components = 0;
  std::string last;
  for (const Variation& v : result.variations) {
    components += v.component != last ? 1 : 0;
    last = v.component;
  }
  out << fmt::format("{}: wrote {} variation(s) of {} component(s) to {}", kTool, result.variations.size(), components,
                     path);
  out << (result.dropped.empty() ? "\n" : fmt::format("; {} candidate(s) dropped:\n", result.dropped.size()));
  for (const std::string& dropped : result.dropped) out << "  " << dropped << "\n";
  if (!result.lockedOut.empty()) out << fmt::format("{}: left out {} component(s):\n", kTool, result.lockedOut.size());
  for (const std::string& locked : result.lockedOut) out << "  " << locked << "\n";
  for (const std::string& member : result.membersLeftOut) out << fmt::format("{}: {}\n", kTool, member);
}

}  // namespace

int runSimplifyTool(const std::vector<std::string>& args, std::ostream& out, std::ostream& err,
                    const std::string& libraryDir) {
  CLI::App app{"spire-simplify: writes simplified variations of a Spire shader's components (Pellacini 2005)", kTool};
  CliOptions options;
  defineOptions(app, options);
  if (const auto status = parseToolArguments(app, args, out, err)) return *status;
  if (!options.costs && options.simplify.outputPath.empty()) {
    return usageError(kTool, "-o,--output is required (unless --costs)", err);
  }
  UserRules rules;
  if (!readRuleFiles(options.ruleFiles, rules, kTool, err)) return kExitInputError;
  options.simplify.userRules = &rules;
  options.simplify.frontEnd.includeDirs = options.includeDirs;
  if (!libraryDir.empty()) options.simplify.frontEnd.includeDirs.push_back(libraryDir);
  ShaderLibrary library(options.simplify.frontEnd);
  for (const std::string& file : options.files) library.addFile(file);
  if (!library.compile()) {
    err << renderDiagnostics(library.sources(), library.diagnostics(), DiagnosticFormat::Text);
    return kExitInputError;
  }
  if (options.costs) return printCosts(library, options, out, err);
  auto result = simplifyShader(library, options.simplify);
  if (!result) {
    err << fmt::format("{}: error: {}\n", kTool, result.error().message);
    return kExitInputError;
  }
  if (auto written = writeFileAtomically(options.simplify.outputPath, result->module); !written) {
    err << fmt::format("{}: error: {}\n", kTool, written.error().message);
    return kExitInputError;
  }
  printSummary(*result, options.simplify.outputPath, out);
  return kExitSuccess;
}

}  // namespace spire::simplify
