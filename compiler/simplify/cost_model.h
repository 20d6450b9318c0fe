// He et al. 2015's performance model (../shared/seeds/000, section 4.4.4),
// the per-definition part: how many scalar instructions a definition costs,
// counted on the typed syntax tree of the semantic model (never on GLSL
// text), with a texture fetch at 100. variant_cost.h adds the definitions of
// a variant up per world into C = 0.3·C_v + 0.7·C_f + 10·N_var.
//
//   - an operation counts its result's scalars, or its widest argument's
//     when that is wider (`vec4 + vec4`: 4; `dot(vec3, vec3)`: 3);
//   - a matrix product counts the result's scalars times the inner
//     dimension (`mat4 * vec4`: 16);
//   - a texture fetch (texture, textureLod, texelFetch, ...) counts 100;
//   - a call of a user function counts its arguments plus its body;
//   - `if` and `?:` count the condition plus the dearer branch;
//   - a `for` loop whose bounds are constant counts its init plus the trip
//     count times one iteration (condition, step and body); any other loop
//     counts one iteration;
//   - literals (negated ones too), names, swizzles, members, indexing,
//     constructors and plain assignment cost nothing: they only name or
//     gather values.
//
// He et al. cost the DAG after constant propagation, dead code elimination
// and common subexpression elimination. This model removes dead locals of
// the definition (a local that nothing reads, however indirectly, costs
// nothing, so `mix(c1, c2, t)` -> `c1` also saves what computes c2). A
// definition alone is costed as written (two equal subexpressions count
// twice: what a rewrite saves is what it removes from the text); the
// definitions of one world of a variant share their values
// (sharedDefinition, value_keys.h): an expression equal to one costed
// before in that world, in the same definition or another, in a function
// called with the same arguments or another function, costs nothing, as
// the kernel's compiler merges them. Branches and loops are costed as
// written: what they compute is not available after them.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <vector>

#include <string>

#include "sema/semantic_model.h"
#include "simplify/value_keys.h"
#include "syntax/ast.h"

namespace spire::simplify {

inline constexpr int64_t kTextureFetchCost = 100;

// Function bodies a shared definition costs call by call (each call binds
// other arguments); past this many, calls are costed as the body alone,
// once per function, so that functions calling others twice, nested, stay
// linear instead of doubling at every level.
inline constexpr int kMaxSharedCalls = 4096;

// One rewrite seen by the model, to cost a definition as it would be after
// the rewrite without writing and compiling it: `target` costs what `parts`
// cost together (a collapse keeps one subexpression; a user rule keeps the
// expressions its metavariables bound), or is an integer constant of value
// `constant` (a loop bound one lower).
struct Substitution {
  const ast::Expr* target = nullptr;
  std::vector<const ast::Expr*> parts;
  std::optional<int64_t> constant;
};

class CostModel {
 public:
  explicit CostModel(const sem::Model& model) : model_(model), keys_(model) {}

  // A component definition: its `= expr` or its body; 0 for an input.
  int64_t definition(const ast::ComponentDecl& decl, const Substitution& substitution = {});
  // The same, counting only the values that no definition costed before
  // with the same `values` computed (one set per world of a variant).
  int64_t sharedDefinition(const ast::ComponentDecl& decl, std::set<std::string>& values);
  int64_t expr(const ast::Expr& e);
  int64_t stmt(const ast::Stmt& s);
  // A user function's body (memoized; 0 for a prototype, and for a function
  // already being costed: GLSL has no recursion, so that is only a guard).
  int64_t function(const sem::Function& f);

 private:
  int64_t binary(const ast::BinaryExpr& top);
  int64_t binaryOp(ast::BinaryOp op, const ast::Expr& lhs, const ast::Expr& rhs, const ast::Expr& result) const;
  int64_t unary(const ast::UnaryExpr& u);
  int64_t assign(const ast::AssignExpr& a);
  int64_t call(const ast::CallExpr& c);
  int64_t loop(const ast::Stmt& s);
  int64_t forLoop(const ast::ForStmt& f);
  std::optional<int64_t> tripCount(const ast::ForStmt& f) const;
  std::optional<int64_t> constantOf(const ast::Expr& e) const;
  std::set<const ast::VarDeclarator*> deadLocals(const ast::ComponentDecl& decl) const;
  int64_t scalarsOf(const ast::Expr& e) const;
  // Whether `e`'s value was computed before in this world (and if not,
  // that it is now); false when values are not shared here.
  bool alreadyComputed(const ast::Expr& e);
  bool sharing() const { return values_ && unshared_ == 0; }
  // After a write of `target` (by `=`, an operator or an `out` argument).
  void wrote(const ast::Expr& target, std::optional<std::string> value);
  int64_t sharedCall(const sem::Function& f, const ast::CallExpr& c);
  int64_t unsharedStmt(const ast::Stmt& s);

  const sem::Model& model_;
  Substitution substitution_;
  std::set<const ast::VarDeclarator*> deadLocals_;  // of the definition being costed
  std::map<const sem::Function*, int64_t> functions_;
  std::set<const sem::Function*> inProgress_;
  ValueKeys keys_;
  std::set<std::string>* values_ = nullptr;  // while costing a shared definition
  int unshared_ = 0;                         // depth of branches and loops being costed
  int sharedCalls_ = 0;                      // function bodies costed call by call in this definition
};

// Scalars in a value of `type`: 1 for a float, 16 for a mat4, the sum of the
// fields for a struct, element scalars times length for an array; 0 for a
// sampler or void.
int64_t scalarCount(const sem::Type* type);

}  // namespace spire::simplify
