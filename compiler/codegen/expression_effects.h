// Whether evaluating an expression can change anything but its own value.
// The GLSL writer moves the prefixes of long operator chains into
// temporaries declared before the statement, which is only the same program
// when neither the chain nor the statement around it writes anything.
#pragma once

#include "sema/semantic_model.h"
#include "syntax/ast.h"

namespace spire::codegen {

// True when `e` assigns, increments or decrements, or calls a function (user
// or built-in) with an `out` or `inout` parameter. Walks the expression with
// an explicit stack: generated chains are deeper than the call stack allows.
bool hasSideEffects(const sem::Model& model, const ast::Expr& e);

// True when `call` passes any argument to an `out` or `inout` parameter (a
// user function's, or a built-in's such as modf's second).
bool callWrites(const sem::Model& model, const ast::CallExpr& call);

}  // namespace spire::codegen
