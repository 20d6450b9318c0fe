// GLSL 4.50 typing rules for operators and constructors (spec sections 5.4 and
// 5.9), independent of any AST so they can be tested on types alone.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "sema/type.h"
#include "support/expected.h"
#include "syntax/ast.h"

namespace spire::sem {

// The result type of `lhs op rhs`, or null when GLSL rejects the operands.
// Implicit conversions (int -> uint -> float) are applied to make the operand
// base types agree. The sequence operator is handled by the caller.
const Type* binaryResultType(const TypeTable& types, ast::BinaryOp op, const Type* lhs, const Type* rhs);

// The result type of a prefix or postfix unary operator, or null.
const Type* unaryResultType(ast::UnaryOp op, const Type* operand);

// The type both branches of `?:` (or both sides of `==`) convert to, or null.
const Type* commonType(const Type* a, const Type* b);

// Checks a built-in type constructor `target(args...)`; an error explaining
// why it is not one ("too few components ...").
Expected<void, Failure> checkConstructor(const Type* target, const std::vector<const Type*>& args);

// The binary operator a compound assignment applies (`+=` -> `+`).
ast::BinaryOp compoundOperator(ast::AssignOp op);

}  // namespace spire::sem
