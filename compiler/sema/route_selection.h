// Routes between worlds (paper sections 4.2 and 5.1): a value computed in one
// world and read in another travels along a chain of imports. The chain is a
// property of the pipeline, chosen here once for every pair of worlds, so
// that codegen, the placement dump and the engine all see the same one.
#pragma once

#include "sema/semantic_model.h"
#include "support/diagnostic.h"

namespace spire::sem {

// What `import` does to the values it carries: an import from an abstract
// world hands over the engine's values as they are (Exact); otherwise its
// strategy's ValueTransfer.
ValueTransfer transferOf(const Pipeline& pipeline, const Import& import);

// An import's `[Priority: "N"]` attribute, 0 when absent. checkAttributes
// has reported a value that is not an integer in range; it counts as 0.
int importPriority(const ast::ImportDecl& decl);

// Fills pipeline.routes. Routes are compared by, in order:
//  1. the worst change an import on the route makes to the value
//     (exact < interpolated < resampled < aggregated);
//  2. the number of imports that change the value;
//  3. the sum of the imports' priorities, higher first;
//  4. the number of imports.
// A route that passes a world chosen at an earlier step (one whose best
// route has a milder worst change) extends that world's route, so the
// routes from one world form a tree and a value enters each world once.
// Declaration order never decides. Routes still tied go through the
// predecessor world whose name sorts first, with a warning (W4110) at the
// pipeline that names the tie and how to break it.
void selectRoutes(Pipeline& pipeline, DiagnosticList& diags);

}  // namespace spire::sem
