// Semantic analysis: name resolution, type checking, pipelines, shaders,
// inheritance, groups and component dependencies.
#pragma once

#include <memory>
#include <string>

#include "sema/semantic_model.h"
#include "sema/strategy_catalog.h"
#include "support/diagnostic.h"
#include "syntax/ast.h"

namespace spire::sem {

struct AnalysisOptions {
  // Retargeting (paper section 7.3): when set, every shader written `using`
  // a pipeline is analysed against this pipeline instead, so that the same
  // component code gets the choices of another engine's worlds. Shaders
  // derived from a base follow their base.
  std::string pipeline;
};

// Analyses every module of `program`. Always returns a model; entities that
// failed are marked invalid (Pipeline::valid, Shader::valid) and errors go to
// `diags`. The model points into `program`, which must outlive it.
std::unique_ptr<Model> analyze(const ast::Program& program, DiagnosticList& diags, const StrategyCatalog& strategies,
                               const AnalysisOptions& options = {});

}  // namespace spire::sem
