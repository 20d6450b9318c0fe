// Value numbering for the cost model (cost_model.h): a key per expression,
// equal for two expressions that compute the same value in one world, so
// that the model can count a value once, as He et al. 2015 count the program
// after common subexpression elimination. A driver's compiler merges the
// same texture read or the same arithmetic in two components computed in one
// kernel; counting it twice made baking a component that shares all its work
// with another look like a saving when it adds a texture read.
//
// A key spells the expression with its names resolved: a component is its
// name, a parameter of a user function the key of the argument it was called
// with, a local the key of the value it holds at that point of the
// straight-line code. Literals are their values. An expression with effects
// (an assignment, `++`, a call with `out` parameters), one that reads a value
// of unknown key, or one whose key would be longer than kMaxValueKey has
// none and is never shared.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "sema/semantic_model.h"
#include "syntax/ast.h"

namespace spire::simplify {

// Longer keys are of expressions that no other expression repeats in
// practice; the bound keeps a chain of thousands of terms linear.
inline constexpr size_t kMaxValueKey = 4096;

class ValueKeys {
 public:
  explicit ValueKeys(const sem::Model& model) : model_(model) {}

  // A fresh frame for a component definition: no locals, no parameters.
  void beginDefinition();
  // The body of `f`, called with arguments of these keys (nullopt: unknown).
  void enterFunction(const ast::FunctionDecl& f, const std::vector<std::optional<std::string>>& arguments);
  void leaveFunction();

  // The key of `e` in the innermost frame.
  std::optional<std::string> key(const ast::Expr& e);
  // `local` holds a value of key `value` from here on; nullopt: a value
  // unlike any other (assigned in a branch or a loop, or by an `out`).
  void setLocal(const ast::VarDeclarator* local, std::optional<std::string> value);
  // After a write of `target`: a local or parameter assigned whole holds
  // `value` from here on, one written in part (a member, an element) a
  // value unlike any other.
  void wrote(const ast::Expr& target, std::optional<std::string> value);

 private:
  struct Frame {
    std::map<const ast::Param*, std::optional<std::string>> params;
    std::map<const ast::VarDeclarator*, std::string> locals;
    std::map<const ast::Expr*, std::optional<std::string>> known;  // keys computed in this frame
  };

  std::optional<std::string> compute(const ast::Expr& e);
  std::optional<std::string> name(const ast::Expr& e);
  std::optional<std::string> call(const ast::CallExpr& c);
  std::optional<std::string> binary(const ast::BinaryExpr& top);
  std::optional<std::string> joined(std::string head, const std::vector<const ast::Expr*>& parts);
  std::string opaque() { return "~" + std::to_string(opaque_++); }

  const sem::Model& model_;
  std::vector<Frame> frames_{1};
  uint64_t opaque_ = 0;
};

}  // namespace spire::simplify
