// Semantic analysis: name resolution, type checking, pipelines, shaders,
// inheritance, groups and component dependencies.
#pragma once

#include <memory>

#include "sema/semantic_model.h"
#include "sema/strategy_catalog.h"
#include "support/diagnostic.h"
#include "syntax/ast.h"

namespace spire::sem {

// Analyses every module of `program`. Always returns a model; entities that
// failed are marked invalid (Pipeline::valid, Shader::valid) and errors go to
// `diags`. The model points into `program`, which must outlive it.
std::unique_ptr<Model> analyze(const ast::Program& program, DiagnosticList& diags, const StrategyCatalog& strategies);

}  // namespace spire::sem
