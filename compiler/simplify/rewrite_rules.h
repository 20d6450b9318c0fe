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
// parameter ranges, needs values measured by rendering: average_sites.h
// finds where it applies, and spire-simplify --search measures the averages.
//
// User rules (user_rules.h) propose rewrites on the same walk, so they reach
// the same expressions and skip what the built-in rules skip.
//
// Each rewrite carries what it saves in He et al. 2015's cost model
// (cost_model.h): the definition's cost before minus after, costed on the
// typed tree with the rewrite substituted. For a built-in rule that is
// exact. A user rule's replacement is only text until it is compiled, so its
// saving here is an estimate that counts the replacement as the expressions
// its metavariables bound, without the rule's own operations (an upper
// bound); simplifyShader reports the exact one, costed on the compiled
// module.
#pragma once

#include <cstdint>
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
  // Scalar operations the rewrite saves in the definition (cost_model.h);
  // negative when it adds some.
  int64_t saving = 0;
};

// Every single rewrite of `decl`'s definition, each to be applied alone,
// ranked by rankRewrites; duplicates (same range and replacement) once.
// `userRules` propose theirs alongside the built-in ones.
std::vector<Rewrite> proposeRewrites(const sem::Model& model, const SourceManager& sources,
                                     const ast::ComponentDecl& decl, const std::vector<UserRule>& userRules = {});

// Whether `e` is a constant as the rules mean it: a literal, a negated one,
// or a constructor of constants (`vec3(0.5, -1.0, 2.0)`).
bool isConstantExpr(const sem::Model& model, const ast::Expr& e);

// The order to offer rewrites of one component's definitions in, as
// indices into `rewrites`: the largest saving first, then those that remove
// the most source, then in the order given (source order).
std::vector<size_t> rankRewrites(const std::vector<Rewrite>& rewrites);

// The widest expression of `decl`'s definition inside `range`: the one a
// rewrite put there, found again in the compiled module to check its type.
const ast::Expr* widestExprWithin(const ast::ComponentDecl& decl, const SourceRange& range);

}  // namespace spire::simplify
