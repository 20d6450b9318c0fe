#include "driver/spirec.h"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <filesystem>
#include <ostream>

#include "driver/shader_library.h"
#include "codegen/kernel_generator.h"
#include "codegen/spirv_compiler.h"
#include "graph/decision_file.h"
#include "sema/group_members.h"
#include "support/diagnostic_renderer.h"
#include "support/file_io.h"

namespace spire {
namespace {

struct Options {
  std::vector<std::string> files;
  std::vector<std::string> includeDirs;
  std::string diagnosticsFormat = "text";
  std::string choicesPath;  // "-" is stdout
  bool choices = false;
  std::string decisionsPath;
  std::string outputDir;
  std::string emit = "both";
  bool dumpPlacement = false;
  std::string shader;
  uint32_t maxErrors = 20;
  bool warningsAsErrors = false;
  std::vector<std::string> warningFlags;  // `-Werror` is `-W error`
};

// An empty path or name is a slip (`-o "$OUT"` with OUT unset), never what
// was meant; it would otherwise quietly mean "no output" or "every shader".
const CLI::Validator kNotEmpty(
    [](std::string& value) { return value.empty() ? std::string("must not be empty") : std::string(); }, "");

struct OutputFile {
  std::filesystem::path path;
  std::string contents;
};

// Generates a variant's kernels as the files DIR/<Shader>/<World>.glsl|.spv
// and reflection.json; they are written only once every shader has
// compiled, so a failing run leaves no partial output. SPIR-V is made (and
// validated) only when asked for: glslang's start-up costs far more than the
// rest of spirec. glslang rejecting generated code is a compiler bug: it is
// reported as an internal error against the shader, and that kernel alone is
// saved at once for inspection.
void generateKernelFiles(ShaderLibrary& library, const graph::Variant& variant, const std::string& outputDir,
                         const std::string& emit, DiagnosticList& diags, std::vector<OutputFile>& files) {
  const auto generated = codegen::generateKernels(library.model(), library.sources(), variant,
                                                  codegen::StrategyRegistry::builtin(), diags);
  if (!generated) return;
  const std::filesystem::path dir = std::filesystem::path(outputDir) / generated->directory;
  const bool wantGlsl = emit != "spirv";
  const bool wantSpirv = emit != "glsl";
  for (const codegen::Kernel& kernel : generated->kernels) {
    const std::filesystem::path glslPath = dir / (kernel.world + ".glsl");
    if (wantGlsl) files.push_back({glslPath, kernel.glsl});
    if (!wantSpirv) continue;
    const codegen::SpirvResult spirv = codegen::compileGlslToSpirv(kernel.stage, kernel.glsl, glslPath.string());
    const std::optional<std::string> invalid = spirv.ok() ? codegen::validateSpirv(spirv.words) : std::nullopt;
    if (!spirv.ok() || invalid) {
      std::error_code ignored;
      std::filesystem::create_directories(dir, ignored);
      const auto saveError = writeFileAtomically(glslPath.string(), kernel.glsl);
      diags.report(DiagCode::E6002, variant.graph().shader().decl->nameRange,
                   fmt::format("internal error: the generated {} kernel of '{}' was rejected; this is a spirec bug",
                               kernel.world, generated->shader))
          .note({}, spirv.ok() ? *invalid : spirv.log)
          .note({}, saveError ? *saveError : fmt::format("the kernel is saved as '{}'", glslPath.string()));
      continue;
    }
    files.push_back({dir / (kernel.world + ".spv"),
                     std::string(reinterpret_cast<const char*>(spirv.words.data()), spirv.words.size() * sizeof(uint32_t))});
  }
  files.push_back({dir / "reflection.json", generated->reflection(variant).dump(2) + "\n"});
}

// Applies the decisions to one shader and adds its placement dump (with
// --dump-placement) and kernel files (with -o) to `output` and `files`. An
// optional group member's instance that fails here is left out with W4101
// and adds nothing. False when the shader has no variant or kernels.
bool buildVariantOutputs(ShaderLibrary& library, const graph::ChoiceSpace& space, const graph::DecisionFile& decisions,
                         const Options& options, DiagnosticList& diags, std::string& output,
                         std::vector<OutputFile>& files) {
  std::string placement;
  std::vector<OutputFile> kernels;
  const sem::Shader& shader = space.graph().shader();
  const bool ok = sem::runMemberStage(shader, diags, [&](DiagnosticList& stageDiags) {
    const auto variant = graph::applyDecisions(decisions, space, stageDiags);
    if (!variant) return false;
    if (options.dumpPlacement) placement = fmt::format("// variant of {}\n{}", shader.name, variant->describe());
    const uint32_t errorsBefore = stageDiags.errorCount();
    if (!options.outputDir.empty()) {
      generateKernelFiles(library, *variant, options.outputDir, options.emit, stageDiags, kernels);
    }
    return stageDiags.errorCount() == errorsBefore;
  });
  if (!ok) return false;
  output += placement;
  files.insert(files.end(), std::make_move_iterator(kernels.begin()), std::make_move_iterator(kernels.end()));
  return true;
}

// Writes each file atomically, creating folders as needed.
void writeFiles(const std::vector<OutputFile>& files, DiagnosticList& diags) {
  for (const OutputFile& file : files) {
    std::error_code ec;
    std::filesystem::create_directories(file.path.parent_path(), ec);
    if (ec) {
      diags.report(DiagCode::E6003, {},
                   fmt::format("cannot create directory '{}': {}", file.path.parent_path().string(), ec.message()));
      return;
    }
    if (auto error = writeFileAtomically(file.path.string(), file.contents)) {
      diags.report(DiagCode::E6003, {}, *error);
      return;
    }
  }
}

}  // namespace

int runSpirec(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  CLI::App app{"spirec: the Spire shader compiler", "spirec"};
  Options options;
  app.set_version_flag("--version", std::string("spirec ") + SPIRE_VERSION);
  app.add_option("files", options.files, "Spire source files")->required()->type_name("FILE...");
  app.add_option("-I", options.includeDirs, "Search DIR for 'using' includes after the including file's folder")
      ->type_name("DIR")
      ->allow_extra_args(false);
  app.add_option("--diagnostics-format", options.diagnosticsFormat, "How diagnostics are printed")
      ->check(CLI::IsMember({"text", "json"}))
      ->type_name("text|json");
  auto* choices = app.add_option("--choices", options.choicesPath,
                                 "Write the choice file to PATH (stdout when PATH is omitted or '-')")
                      ->expected(0, 1)
                      ->type_name("[PATH]");
  app.add_option("--decisions", options.decisionsPath, "Apply the decision file PATH to every shader it names")
      ->check(kNotEmpty)
      ->type_name("PATH");
  app.add_option("-o,--output", options.outputDir, "Write kernels and reflection to DIR/<Shader>/")
      ->check(kNotEmpty)
      ->type_name("DIR");
  app.add_option("--emit", options.emit, "What -o writes besides reflection.json")
      ->check(CLI::IsMember({"glsl", "spirv", "both"}))
      ->type_name("glsl|spirv|both");
  app.add_flag("--dump-placement", options.dumpPlacement,
               "Print each variant's placement (as a decision file) and what each world computes, imports and exports");
  app.add_option("--shader", options.shader, "Restrict output to one shader")->check(kNotEmpty)->type_name("NAME");
  app.add_option("--max-errors", options.maxErrors, "Stop after N errors (0: no limit)")->type_name("N");
  app.add_flag("--warnings-as-errors", options.warningsAsErrors,
               "Fail on any warning, reporting each warning as an error");
  app.add_option("-W", options.warningFlags, "-Werror: the same as --warnings-as-errors")
      ->check(CLI::IsMember({"error"}))
      ->type_name("error")
      ->allow_extra_args(false);

  std::vector<std::string> reversed(args.rbegin(), args.rend());
  try {
    app.parse(reversed);
  } catch (const CLI::Success&) {
    out << (app.get_option("--version")->count() ? std::string("spirec ") + SPIRE_VERSION + "\n" : app.help());
    return kExitSuccess;
  } catch (const CLI::ParseError& e) {
    err << fmt::format("spirec: error: {}\nRun 'spirec --help' for usage.\n", e.what());
    return kExitUsageError;
  }
  options.choices = choices->count() > 0;
  options.warningsAsErrors |= !options.warningFlags.empty();
  const DiagnosticFormat format = options.diagnosticsFormat == "json" ? DiagnosticFormat::Json : DiagnosticFormat::Text;

  FrontEndOptions feOptions;
  feOptions.includeDirs = options.includeDirs;
  feOptions.errorLimit = options.maxErrors == 0 ? UINT32_MAX : options.maxErrors;
  ShaderLibrary library(std::move(feOptions));
  for (const std::string& file : options.files) library.addFile(file);
  library.compile();
  DiagnosticList& diags = library.diagnostics();

  std::vector<const graph::ChoiceSpace*> spaces;
  if (!diags.hasErrors()) {
    for (const std::string& name : library.shaderNames()) {
      const graph::ChoiceSpace* space = library.choiceSpace(name);
      const sem::Shader& shader = space->graph().shader();
      const bool selected = options.shader.empty() || name == options.shader ||
                            (shader.derivedFrom && shader.decl->name == options.shader);
      if (selected) spaces.push_back(space);
    }
    if (!options.shader.empty() && spaces.empty()) {
      err << fmt::format("spirec: error: no concrete shader named '{}'\n", options.shader);
      return kExitUsageError;
    }
  }

  std::string choicesText;
  std::string output;
  std::vector<OutputFile> kernelFiles;
  const bool generate = !options.outputDir.empty();
  if (!diags.hasErrors() && (!options.decisionsPath.empty() || options.dumpPlacement || generate)) {
    graph::DecisionFile decisions;
    if (!options.decisionsPath.empty()) {
      if (const auto id = library.frontEnd().loadAuxiliaryFile(options.decisionsPath)) {
        decisions = graph::parseDecisionFile(library.sources(), *id, diags);
        checkDecisionPrefixes(decisions, library.model(), diags);
      }
    }
    if (!diags.hasErrors()) {
      const std::vector<const graph::ChoiceSpace*> selected = spaces;
      std::erase_if(spaces, [&](const graph::ChoiceSpace* space) {
        return !buildVariantOutputs(library, *space, decisions, options, diags, output, kernelFiles);
      });
      if (!diags.hasErrors()) graph::checkSomeDecisionApplies(decisions, selected, diags);
    }
  }
  if (!diags.hasErrors() && options.choices) {
    choicesText = graph::writeChoiceFile(spaces);
  }

  if (options.warningsAsErrors) diags.promoteWarnings("treated as an error (--warnings-as-errors)");
  if (!diags.hasErrors()) writeFiles(kernelFiles, diags);
  const std::string rendered = renderDiagnostics(library.sources(), diags, format);
  if (format == DiagnosticFormat::Json || !rendered.empty()) err << rendered;
  if (diags.hasErrors()) return kExitInputError;
  if (options.choices && !options.choicesPath.empty() && options.choicesPath != "-") {
    if (auto error = writeFileAtomically(options.choicesPath, choicesText)) {
      err << "spirec: error: " << *error << "\n";
      return kExitInputError;
    }
  } else {
    out << choicesText;
  }
  out << output;
  return kExitSuccess;
}

}  // namespace spire
