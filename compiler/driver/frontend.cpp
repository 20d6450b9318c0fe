#include "driver/frontend.h"

#include <fmt/format.h>

#include "codegen/strategy_registry.h"
#include "sema/analyzer.h"
#include "support/file_io.h"
#include "syntax/module_loader.h"

namespace spire {

FrontEnd::FrontEnd(FrontEndOptions options) : options_(std::move(options)), diags_(options_.errorLimit) {
  LoadOptions load;
  load.includeDirs = options_.includeDirs;
  load.readFile = options_.readFile;
  loader_ = std::make_unique<ModuleLoader>(sources_, diags_, std::move(load));
}

FrontEnd::~FrontEnd() = default;

bool FrontEnd::addFile(const std::string& path) { return loader_->loadFile(path, program_); }

void FrontEnd::addSource(std::string displayPath, std::string text) {
  loader_->loadSource(std::move(displayPath), std::move(text), program_);
}

std::optional<FileId> FrontEnd::loadAuxiliaryFile(const std::string& path) {
  auto text = readThrough(options_.readFile, path);
  if (!text) {
    diags_.report(DiagCode::E1101, {}, fmt::format("cannot open file '{}': {}", path, text.error().message()));
    return std::nullopt;
  }
  return sources_.addFile(path, std::move(text).value());
}

const sem::Model& FrontEnd::analyze() {
  // Semantic errors in code the parser had to skip or guess at are mostly
  // echoes of the syntax error, so a program that does not parse stops here:
  // every syntax error is reported, and nothing that only follows from one.
  if (diags_.hasErrors()) {
    model_ = std::make_unique<sem::Model>();
    model_->reserveExprs(program_.exprCount);
    return *model_;
  }
  const sem::StrategyCatalog& strategies =
      options_.strategies ? *options_.strategies : codegen::StrategyRegistry::builtin().catalog();
  model_ = sem::analyze(program_, diags_, strategies, sem::AnalysisOptions{options_.pipeline});
  return *model_;
}

}  // namespace spire
