// Pellacini 2005's third rule, "simplification by average substitution": a
// subtree of a definition replaced by its average over the shader's inputs,
// estimated by Monte Carlo. Where the rule applies is decided here, on the
// typed syntax tree; the average itself is measured by rendering
// (spire-simplify --search renders a probe of each site over the scene's
// camera views and parameter samples), so each site carries the Spire source
// of a definition that computes the subtree's value where the original
// definition computes it.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "sema/semantic_model.h"
#include "simplify/rewrite_rules.h"
#include "support/source_manager.h"
#include "syntax/ast.h"

namespace spire::simplify {

inline constexpr const char* kAverageRule = "average";

struct AverageSite {
  // Rule "average": the subtree's range, source and type (`float` or a
  // float vector). Its replacement is empty until the average is measured
  // (averageReplacement); its saving is the definition's cost with a
  // constant in place of the subtree.
  Rewrite rewrite;
  size_t scalars = 0;  // of the type: 1 to 4
  // What follows the type and name of a definition that computes the
  // subtree's value: `{ <the statements before the one it is in> return
  // (S); }`, or `= (S);` for a definition `T c = e;`.
  std::string probe;
};

// Every subtree of `decl`'s definition the rule can replace, ranked as
// rankRewrites ranks rewrites: an expression of type float, vec2, vec3 or
// vec4 that is not a constant already, not assigned to, outside loops, ifs
// and [Immutable] statements, in the definition's expression or in a
// declaration, expression or return statement of its body's top level (so
// that the statements before it are all its value depends on).
std::vector<AverageSite> proposeAverageSites(const sem::Model& model, const SourceManager& sources,
                                             const ast::ComponentDecl& decl);

// The scalars of `float`, `vec2`, `vec3` and `vec4`, the types whose values
// can be averaged; nullopt for any other.
std::optional<size_t> floatScalarCount(const std::string& type);

// A constant of `type` (a site's) holding `values`, one per scalar, as Spire
// source that reads back to the same floats: `vec3(0.5, 0.25, 1)`.
std::string averageReplacement(const std::string& type, const std::vector<double>& values);

}  // namespace spire::simplify
