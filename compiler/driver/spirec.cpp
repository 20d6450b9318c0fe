#include "driver/spirec.h"

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <filesystem>
#include <memory>
#include <ostream>
#include <sstream>

#include "driver/compiler.h"
#include "driver/shader_library.h"
#include "driver/spirec_batch.h"
#include "driver/tool_arguments.h"
#include "graph/decision_file.h"
#include "reflection/reflection_json.h"
#include "sema/group_members.h"
#include "support/atomic_directory.h"
#include "support/depfile.h"
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
  bool instrumentHazards = false;
  std::string shader;
  std::string pipeline;
  uint32_t maxErrors = 20;
  bool warningsAsErrors = false;
  std::vector<std::string> warningFlags;  // `-Werror` is `-W error`
  bool quiet = false;
  bool noServer = false;
  std::string depfile;
  std::string depfileTarget;
  SpirvCache* spirvCache = nullptr;  // SpirecEnvironment's
};

// An empty path or name is a slip (`-o "$OUT"` with OUT unset), never what
// was meant; it would otherwise quietly mean "no output" or "every shader".
const CLI::Validator kNotEmpty(
    [](std::string& value) { return value.empty() ? std::string("must not be empty") : std::string(); }, "");

// One shader's output: DIR/<Shader>/ as a set of files.
struct OutputDirectory {
  std::filesystem::path path;
  FileSet files;
};

// The files of a compiled variant: <World>.glsl and <World>.spv as --emit
// asks, and reflection.json.
OutputDirectory variantFiles(const CompiledVariant& compiled, const Options& options) {
  OutputDirectory out{std::filesystem::path(options.outputDir) / compiled.directory, {}};
  for (size_t i = 0; i < compiled.kernels.size(); ++i) {
    const reflection::Kernel& kernel = compiled.reflection.kernels[i];
    if (options.emit != "spirv") out.files.emplace_back(kernel.glslFile, compiled.kernels[i].glsl);
    const std::vector<uint32_t>& words = compiled.kernels[i].spirv;
    if (options.emit != "glsl") {
      out.files.emplace_back(kernel.spirvFile,
                             std::string(reinterpret_cast<const char*>(words.data()), words.size() * sizeof(uint32_t)));
    }
  }
  out.files.emplace_back("reflection.json", reflection::toJson(compiled.reflection).dump(2) + "\n");
  return out;
}

// Applies the decisions to one shader and adds its placement dump (with
// --dump-placement) and output directory (with -o) to `output` and
// `directories`. An optional group member's instance that fails here is left
// out with W4101 and adds nothing. False when the shader has no variant or
// kernels.
bool buildVariantOutputs(ShaderLibrary& library, const graph::ChoiceSpace& space, const graph::DecisionFile& decisions,
                         const Options& options, DiagnosticList& diags, std::string& output,
                         std::vector<OutputDirectory>& directories) {
  std::string placement;
  std::optional<OutputDirectory> files;
  const sem::Shader& shader = space.graph().shader();
  const bool ok = sem::runMemberStage(shader, diags, [&](DiagnosticList& stageDiags) {
    const auto variant = graph::applyDecisions(decisions, space, stageDiags);
    if (!variant) return false;
    if (options.dumpPlacement) placement = fmt::format("// variant of {}\n{}", shader.name, variant->describe());
    if (options.outputDir.empty()) return true;
    CompileOptions compileOptions;
    compileOptions.spirv = options.emit != "glsl";
    compileOptions.saveRejectedTo = options.outputDir;
    compileOptions.instrumentHazards = options.instrumentHazards;
    compileOptions.spirvCache = options.spirvCache;
    const CompiledVariantPtr compiled = compileVariant(library, *variant, compileOptions, stageDiags);
    if (compiled) files = variantFiles(*compiled, options);
    return compiled != nullptr;
  });
  if (!ok) return false;
  output += placement;
  if (files) directories.push_back(std::move(*files));
  return true;
}

// Writes each shader's files beside its directory, to be put in place as a
// whole, so that a reader never sees kernels beside another variant's
// reflection. Stops at the first failure.
std::vector<StagedDirectory> stageDirectories(const std::vector<OutputDirectory>& directories, DiagnosticList& diags) {
  std::vector<StagedDirectory> staged;
  for (const OutputDirectory& dir : directories) {
    auto stage = StagedDirectory::stage(dir.path.string(), dir.files);
    if (!stage) {
      diags.report(DiagCode::E6003, {}, stage.error().message);
      return {};
    }
    staged.push_back(std::move(stage).value());
  }
  return staged;
}

void commitDirectories(std::vector<StagedDirectory>& staged, DiagnosticList& diags) {
  for (StagedDirectory& dir : staged) {
    if (auto written = dir.commit(); !written) {
      diags.report(DiagCode::E6003, {}, written.error().message);
      return;
    }
  }
}

// Declares spirec's options; returns --choices, whose PATH is optional, so
// that the caller can tell whether it was given.
CLI::Option* addOptions(CLI::App& app, Options& options) {
  addVersionFlag(app);
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
  app.add_flag("--instrument-hazards", options.instrumentHazards,
               "With -o: kernels that record the first component to go NaN or Inf per pixel, vertex or texel "
               "(for diagnosis; docs/engine.md, hazard reports)");
  app.add_option("--shader", options.shader, "Restrict output to one shader")->check(kNotEmpty)->type_name("NAME");
  app.add_option("--pipeline", options.pipeline,
                 "Retarget every shader written 'using' a pipeline to pipeline NAME (declared in one of the files)")
      ->check(kNotEmpty)
      ->type_name("NAME");
  app.add_option("--max-errors", options.maxErrors, "Stop after N errors (0: no limit)")->type_name("N");
  app.add_flag("--warnings-as-errors", options.warningsAsErrors,
               "Fail on any warning, reporting each warning as an error");
  app.add_option("-W", options.warningFlags, "-Werror: the same as --warnings-as-errors")
      ->check(CLI::IsMember({"error"}))
      ->type_name("error")
      ->allow_extra_args(false);
  app.add_flag("-q,--quiet", options.quiet, "Print errors only: no warnings and their notes");
  app.add_flag("--no-server", options.noServer,
               "Compile in this process, not on the compile server that keeps glslang's tables between runs "
               "(also SPIRE_SERVER=off; docs/integration.md)");
  auto* depfile = app.add_option("--depfile", options.depfile,
                                 "Write a Make-syntax depfile to FILE listing every file read: the sources, each "
                                 "'using' file, the decision file")
                      ->check(kNotEmpty)
                      ->type_name("FILE");
  app.add_option("--depfile-target", options.depfileTarget,
                 "The depfile's target (default: the -o DIR, else the --choices PATH)")
      ->check(kNotEmpty)
      ->needs(depfile)
      ->type_name("NAME");
  return choices;
}

// The choice spaces of the shaders --shader selects (every shader without
// it); an instance is selected by its own name or its template's.
std::vector<const graph::ChoiceSpace*> selectShaders(ShaderLibrary& library, const Options& options) {
  std::vector<const graph::ChoiceSpace*> spaces;
  for (const std::string& name : library.shaderNames()) {
    const graph::ChoiceSpace* space = library.choiceSpace(name);
    const sem::Shader& shader = space->graph().shader();
    const bool selected =
        options.shader.empty() || name == options.shader || (shader.derivedFrom && shader.decl->name == options.shader);
    if (selected) spaces.push_back(space);
  }
  return spaces;
}

// What spirec writes once the diagnostics allow it.
struct SpirecOutput {
  std::string choices;                       // the choice file, with --choices
  std::string placements;                    // with --dump-placement
  std::vector<OutputDirectory> directories;  // with -o, until staged
  std::vector<StagedDirectory> staged;       // the directories, written beside their place
};

// Applies --decisions to the selected shaders and builds their placement
// dumps and output directories; a shader without a variant leaves `spaces`.
void buildOutputs(ShaderLibrary& library, const Options& options, DiagnosticList& diags,
                  std::vector<const graph::ChoiceSpace*>& spaces, SpirecOutput& result) {
  graph::DecisionFile decisions;
  if (!options.decisionsPath.empty()) {
    if (const auto id = library.frontEnd().loadAuxiliaryFile(options.decisionsPath)) {
      decisions = graph::parseDecisionFile(library.sources(), *id, diags);
      checkDecisionPrefixes(decisions, library.model(), diags);
    }
  }
  if (diags.hasErrors()) return;
  const std::vector<const graph::ChoiceSpace*> selected = spaces;
  std::erase_if(spaces, [&](const graph::ChoiceSpace* space) {
    return !buildVariantOutputs(library, *space, decisions, options, diags, result.placements, result.directories);
  });
  if (!diags.hasErrors()) graph::checkSomeDecisionApplies(decisions, selected, diags);
}

// The depfile's target when --depfile-target does not name one: the output
// directory, else the choice file; empty when spirec writes neither.
std::string defaultDepfileTarget(const Options& options) {
  if (!options.outputDir.empty()) return options.outputDir;
  if (options.choices && options.choicesPath != "-") return options.choicesPath;
  return {};
}

// Writes --depfile: every file the run read, in the order it read them.
Expected<void, Failure> writeDepfile(const SourceManager& sources, const Options& options) {
  std::vector<std::string> read;
  for (FileId id = 0; id < sources.fileCount(); ++id) read.push_back(sources.file(id).path);
  auto text = makeDepfile(options.depfileTarget, read);
  if (!text) return text.error();
  return writeFileAtomically(options.depfile, text.value());
}

// --quiet: every diagnostic but the errors is dropped. Without
// --warnings-as-errors an error's severity is its code's, so reporting it
// again keeps the counts right.
void keepErrorsOnly(DiagnosticList& diags) {
  for (Diagnostic& d : diags.takeSince(0)) {
    if (d.severity == Severity::Error) diags.report(d.code, d.range, d.message).notes = std::move(d.notes);
  }
}

// Applies --warnings-as-errors or --quiet and, when there are no errors,
// stages the output directories.
void settle(ShaderLibrary& library, const Options& options, SpirecOutput& result) {
  DiagnosticList& diags = library.diagnostics();
  if (options.warningsAsErrors) {
    diags.promoteWarnings("treated as an error (--warnings-as-errors)");
  } else if (options.quiet) {
    keepErrorsOnly(diags);
  }
  if (diags.hasErrors()) return;
  result.staged = stageDirectories(result.directories, diags);
  result.directories.clear();  // their files are on disk now; a batch job may wait a while to commit
}

// Prints the diagnostics and, when there are no errors, puts the outputs in
// place; returns the exit status.
int finish(ShaderLibrary& library, const Options& options, SpirecOutput& result, std::ostream& out, std::ostream& err) {
  DiagnosticList& diags = library.diagnostics();
  const DiagnosticFormat format = options.diagnosticsFormat == "json" ? DiagnosticFormat::Json : DiagnosticFormat::Text;
  if (!diags.hasErrors()) commitDirectories(result.staged, diags);
  const std::string rendered = renderDiagnostics(library.sources(), diags, format);
  if (format == DiagnosticFormat::Json || !rendered.empty()) err << rendered;
  if (diags.hasErrors()) return kExitInputError;
  if (options.choices && !options.choicesPath.empty() && options.choicesPath != "-") {
    if (auto written = writeFileAtomically(options.choicesPath, result.choices); !written) {
      err << "spirec: error: " << written.error().message << "\n";
      return kExitInputError;
    }
  } else {
    out << result.choices;
  }
  if (!options.depfile.empty()) {
    if (auto written = writeDepfile(library.sources(), options); !written) {
      err << "spirec: error: " << written.error().message << "\n";
      return kExitInputError;
    }
  }
  out << result.placements;
  return kExitSuccess;
}

// What a run that stopped before compiling printed, replayed when it
// finishes.
SpirecFinish printed(int status, std::string outText, std::string errText) {
  return [=](std::ostream& out, std::ostream& err) {
    out << outText;
    err << errText;
    return status;
  };
}

// A run's compiled state, kept until it finishes.
struct PreparedRun {
  Options options;
  std::unique_ptr<ShaderLibrary> library;
  SpirecOutput result;
};

// Declares spirec's options and the --batch entry of --help, and parses
// `args`; a status when the run stops there (--help, a usage error), with
// what it printed in `out` and `err`.
std::optional<int> parseSpirecArguments(const std::vector<std::string>& args, const SpirecEnvironment& environment,
                                        Options& options, std::ostream& out, std::ostream& err) {
  CLI::App app{"spirec: the Spire shader compiler", "spirec"};
  CLI::Option* choices = addOptions(app, options);
  // Only here for --help: batch mode is recognised before parsing, since its
  // FILE replaces the otherwise required sources.
  std::string batchFile;
  app.add_option("--batch", batchFile,
                 "Run each line of FILE as a separate spirec run (its arguments; '#' comments, \"...\" and '...' "
                 "quoting, \\ escapes: docs/integration.md) in this one process, -j N runs at a time (default: one "
                 "per hardware thread); takes no other arguments but -j and --no-server")
      ->type_name("FILE");
  if (!environment.libraryDir.empty()) {
    app.footer("'using' files found neither next to their includer nor under -I are searched in the Spire library, " +
               environment.libraryDir + " (stdlib/, pipelines/).");
  }
  if (const auto status = parseToolArguments(app, args, out, err)) return status;
  options.choices = choices->count() > 0;
  options.spirvCache = environment.spirvCache;
  options.warningsAsErrors |= !options.warningFlags.empty();
  if (!options.depfile.empty() && options.depfileTarget.empty()) {
    options.depfileTarget = defaultDepfileTarget(options);
    if (options.depfileTarget.empty()) {
      return usageError(app.get_name(), "--depfile needs a target: -o DIR, --choices PATH or --depfile-target NAME",
                        err);
    }
  }
  return std::nullopt;
}

// Compiles the sources and builds every output the options ask for; a status
// when the run stops early (an unknown --shader).
std::optional<int> compileRun(PreparedRun& run, const SpirecEnvironment& environment, std::ostream& err) {
  const Options& options = run.options;
  FrontEndOptions feOptions;
  feOptions.includeDirs = options.includeDirs;
  if (!environment.libraryDir.empty()) feOptions.includeDirs.push_back(environment.libraryDir);
  feOptions.pipeline = options.pipeline;
  feOptions.errorLimit = options.maxErrors == 0 ? UINT32_MAX : options.maxErrors;
  run.library = std::make_unique<ShaderLibrary>(std::move(feOptions));
  ShaderLibrary& library = *run.library;
  for (const std::string& file : options.files) library.addFile(file);
  library.compile();
  DiagnosticList& diags = library.diagnostics();

  std::vector<const graph::ChoiceSpace*> spaces;
  if (!diags.hasErrors()) {
    spaces = selectShaders(library, options);
    if (!options.shader.empty() && spaces.empty()) {
      err << fmt::format("spirec: error: no concrete shader named '{}'\n", options.shader);
      return kExitUsageError;
    }
  }
  const bool generate = !options.outputDir.empty();
  if (!diags.hasErrors() && (!options.decisionsPath.empty() || options.dumpPlacement || generate)) {
    buildOutputs(library, options, diags, spaces, run.result);
  }
  if (!diags.hasErrors() && options.choices) run.result.choices = graph::writeChoiceFile(spaces);
  return std::nullopt;
}

// One spirec run, a command line or one line of a batch file, compiled; its
// files are written and its output printed when the result is called.
SpirecFinish prepareSpirecJob(const std::vector<std::string>& args, const SpirecEnvironment& environment) {
  auto run = std::make_shared<PreparedRun>();
  std::ostringstream earlyOut, earlyErr;
  std::optional<int> stopped = parseSpirecArguments(args, environment, run->options, earlyOut, earlyErr);
  if (!stopped) stopped = compileRun(*run, environment, earlyErr);
  if (stopped) return printed(*stopped, std::move(earlyOut).str(), std::move(earlyErr).str());
  settle(*run->library, run->options, run->result);
  return [run](std::ostream& out, std::ostream& err) {
    return finish(*run->library, run->options, run->result, out, err);
  };
}

}  // namespace

bool spirecWantsCompileServer(const std::vector<std::string>& args) {
  if (namesBatchMode(args)) return std::ranges::find(args, "--no-server") == args.end();
  Options options;
  std::ostringstream ignored;
  if (parseSpirecArguments(args, {}, options, ignored, ignored)) return false;
  return !options.noServer && !options.outputDir.empty() && options.emit != "glsl";
}

int runSpirec(const std::vector<std::string>& args, std::ostream& out, std::ostream& err,
              const SpirecEnvironment& environment) {
  if (namesBatchMode(args)) return runSpirecBatch(args, prepareSpirecJob, out, err, environment);
  return prepareSpirecJob(args, environment)(out, err);
}

}  // namespace spire
