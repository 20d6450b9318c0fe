#include "driver/spirec.h"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <ostream>

#include "driver/definition_listing.h"
#include "driver/frontend.h"
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
  std::string shader;
  uint32_t maxErrors = 20;
};

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
  app.add_option("--shader", options.shader, "Restrict output to one shader")->type_name("NAME");
  app.add_option("--max-errors", options.maxErrors, "Stop after N errors (0: no limit)")->type_name("N");

  std::vector<std::string> reversed(args.rbegin(), args.rend());
  try {
    app.parse(reversed);
  } catch (const CLI::Success&) {
    out << (app.get_option("--version")->count() ? std::string("spirec ") + SPIRE_VERSION + "\n" : app.help());
    return kExitSuccess;
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) {
      out << app.help();
      return kExitSuccess;
    }
    err << fmt::format("spirec: error: {}\nRun 'spirec --help' for usage.\n", e.what());
    return kExitUsageError;
  }
  options.choices = choices->count() > 0;
  const DiagnosticFormat format = options.diagnosticsFormat == "json" ? DiagnosticFormat::Json : DiagnosticFormat::Text;

  FrontEndOptions feOptions;
  feOptions.includeDirs = options.includeDirs;
  feOptions.errorLimit = options.maxErrors == 0 ? UINT32_MAX : options.maxErrors;
  FrontEnd frontEnd(std::move(feOptions));
  for (const std::string& file : options.files) frontEnd.addFile(file);
  const sem::Model& model = frontEnd.analyze();

  if (!options.shader.empty() && !frontEnd.diagnostics().hasErrors() && !model.findShader(options.shader)) {
    err << fmt::format("spirec: error: no shader named '{}'\n", options.shader);
    return kExitUsageError;
  }
  const std::string rendered = renderDiagnostics(frontEnd.sources(), frontEnd.diagnostics(), format);
  if (format == DiagnosticFormat::Json || !rendered.empty()) err << rendered;
  if (frontEnd.diagnostics().hasErrors()) return kExitInputError;

  if (options.choices) {
    const std::string listing = listDeclaredDefinitions(model, options.shader);
    if (options.choicesPath.empty() || options.choicesPath == "-") {
      out << listing;
    } else if (auto error = writeFileAtomically(options.choicesPath, listing)) {
      err << "spirec: error: " << *error << "\n";
      return kExitInputError;
    }
  }
  return kExitSuccess;
}

}  // namespace spire
