// The front end as a library: load sources, parse and analyse them. The CLI,
// the tests, the fuzzer and the benchmarks all go through this one entry.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "sema/semantic_model.h"
#include "sema/strategy_catalog.h"
#include "support/diagnostic.h"
#include "support/file_io.h"
#include "support/source_manager.h"
#include "syntax/ast.h"

namespace spire {

class ModuleLoader;

struct FrontEndOptions {
  std::vector<std::string> includeDirs;
  uint32_t errorLimit = 20;
  // See LoadOptions::readFile; the default reads the file system.
  FileReader readFile;
  // Strategies pipelines may name; null means those of
  // codegen::StrategyRegistry::builtin().
  const sem::StrategyCatalog* strategies = nullptr;
  // Retargets every `using` shader to this pipeline (sem::AnalysisOptions).
  std::string pipeline;
};

class FrontEnd {
 public:
  explicit FrontEnd(FrontEndOptions options = {});
  ~FrontEnd();
  FrontEnd(const FrontEnd&) = delete;
  FrontEnd& operator=(const FrontEnd&) = delete;

  // Loads a file named by the user (and its includes). False if unreadable.
  bool addFile(const std::string& path);
  // Loads in-memory source; includes resolve relative to displayPath.
  void addSource(std::string displayPath, std::string text);

  // Loads a non-Spire input (a decision file) so that its diagnostics render
  // like any source's. Reports E1101 and returns nullopt if unreadable.
  std::optional<FileId> loadAuxiliaryFile(const std::string& path);

  // Runs semantic analysis over everything loaded. After errors in loading
  // or parsing the model is empty; after semantic errors it holds what was
  // understood, with failed entities marked. Check diagnostics().hasErrors().
  const sem::Model& analyze();

  const SourceManager& sources() const { return sources_; }
  const DiagnosticList& diagnostics() const { return diags_; }
  DiagnosticList& diagnostics() { return diags_; }
  const ast::Program& program() const { return program_; }

 private:
  FrontEndOptions options_;
  SourceManager sources_;
  DiagnosticList diags_;
  ast::Program program_;
  std::unique_ptr<ModuleLoader> loader_;
  std::unique_ptr<sem::Model> model_;
};

}  // namespace spire
