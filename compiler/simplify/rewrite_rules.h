// Pellacini 2005's simplification rules ("User-Configurable Automatic Shader
// Simplification", ../shared/seeds/004) as rewrites of one component
// definition, chosen on the typed syntax tree: each rewrite replaces one
// piece of the definition's source with a simpler expression of the same
// type, so the result still type-checks, and keeps everything else of the
// author's text (layout and comments) for the person who reads or edits it.
//
//   constant-operand   a binary +, -, *, / with a constant operand collapses
//                      to its other operand (`c * 0.5` -> `c`)
//   call-to-argument   a built-in call collapses to an argument of its own
//                      type (`mix(a, b, t)` -> `a`, `normalize(n)` -> `n`)
//   loop-iteration     a loop `i < N` with a constant N drops its last
//                      iteration (`i < 4` -> `i < 3`)
//
// Pellacini's third rule, a subtree replaced by its average over the
// parameter ranges, needs values measured by rendering and is not here.
//
// User rules (user_rules.h) propose rewrites on the same walk, so they reach
// the same expressions and skip what the built-in rules skip.
#pragma once

#include <string>
#include <vector>

#include "sema/semantic_model.h"
#include "simplify/user_rules.h"
#include "support/source_manager.h"
#include "syntax/ast.h"

namespace spire::simplify {

struct Rewrite {
  std::string rule;         // "constant-operand", "call-to-argument", "loop-iteration", a user rule's name
  SourceRange range;        // the source replaced
  std::string replacement;  // the Spire source put in its place
  std::string before;       // the replaced source, for the reader
  // The type the replacement must have, where the rule cannot promise it
  // (a user rule): simplifyShader checks it on the compiled module. Empty
  // for the built-in rules, which only keep expressions of the same type.
  std::string type;
};

// Every single rewrite of `decl`'s definition, each to be applied alone:
// those that remove the most source first, then in source order; duplicates
// (same range and replacement) once.
// `userRules` propose theirs alongside the built-in ones.
std::vector<Rewrite> proposeRewrites(const sem::Model& model, const SourceManager& sources,
                                     const ast::ComponentDecl& decl, const std::vector<UserRule>& userRules = {});

// The widest expression of `decl`'s definition inside `range`: the one a
// rewrite put there, found again in the compiled module to check its type.
const ast::Expr* widestExprWithin(const ast::ComponentDecl& decl, const SourceRange& range);

}  // namespace spire::simplify
