// The operations an instrumented kernel checks inside component and function
// bodies (CompileOptions::instrumentHazards): a component's check says that
// it went NaN or Inf, and these say where in its body. A checked operation
// is written as a call, `probe(a / b, 3u)`, which passes the value through
// and notes the operation's number the first time since the component began
// that a value it makes is not finite.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "reflection/reflection.h"
#include "sema/semantic_model.h"
#include "syntax/ast.h"

namespace spire::codegen {

// Whether `e` is an operation worth checking: one that can turn finite
// operands into NaN or Inf (float +, -, * and /, a built-in such as log,
// sqrt, pow or normalize), a texture lookup (a texel may hold NaN or Inf),
// or a call of a user function, whose body may hide one.
bool isCheckedOperation(const ast::Expr& e, const sem::ExprInfo& info);

class OperationProbe {
 public:
  // `function`: the GLSL function that checks a value (declared by the
  // instrumentation); `noted`: the global it notes the operation in.
  OperationProbe(std::string function, std::string noted) : function_(std::move(function)), noted_(std::move(noted)) {}

  // `text`, the GLSL of operation `e` (which isCheckedOperation accepts),
  // wrapped in the check; `site` describes `e` for the reflection.
  std::string wrap(const ast::Expr& e, const std::string& text, reflection::HazardOperation site);
  // The statement that forgets what earlier components noted.
  std::string reset() const { return noted_ + " = 0u;"; }
  const std::string& function() const { return function_; }
  const std::string& noted() const { return noted_; }
  const std::vector<reflection::HazardOperation>& operations() const { return operations_; }

 private:
  std::string function_;
  std::string noted_;
  std::map<const ast::Expr*, uint32_t> numbers_;  // 1-based index in operations_
  std::vector<reflection::HazardOperation> operations_;
};

}  // namespace spire::codegen
