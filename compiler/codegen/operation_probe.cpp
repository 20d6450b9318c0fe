#include "codegen/operation_probe.h"

#include <fmt/format.h>

#include <array>
#include <string_view>

namespace spire::codegen {
namespace {

// Built-ins that can make NaN or Inf from finite arguments: outside their
// domain (log, sqrt, asin, ...), at a pole or a zero length (inversesqrt,
// normalize, mod, smoothstep with equal edges), or by overflow (exp, pow,
// sinh, ldexp).
constexpr std::array<std::string_view, 19> kUnsafeBuiltins = {
    "acos", "acosh", "asin", "atan", "atanh", "cosh",       "exp",  "exp2",      "inversesqrt", "ldexp",
    "log",  "log2",  "mod",  "pow",  "sinh",  "smoothstep", "sqrt", "normalize", "tan"};

// A texel may hold NaN or Inf, whatever the coordinates: a fetch is where
// such a value enters the body. (Queries of a texture's size and levels
// read no texel.)
bool isTextureLookup(std::string_view name) {
  return name.starts_with("texelFetch") ||
         (name.starts_with("texture") && !name.starts_with("textureSize") && !name.starts_with("textureQuery"));
}

// Float arithmetic can overflow to Inf (a product, a sum of large values)
// or make NaN (Inf - Inf, 0 * Inf), and a division also at a zero divisor.
bool isArithmetic(ast::BinaryOp op) {
  return op == ast::BinaryOp::Add || op == ast::BinaryOp::Sub || op == ast::BinaryOp::Mul || op == ast::BinaryOp::Div;
}
bool isArithmetic(ast::AssignOp op) {
  return op == ast::AssignOp::Add || op == ast::AssignOp::Sub || op == ast::AssignOp::Mul || op == ast::AssignOp::Div;
}

// The check functions take float scalars and vectors; other results are
// checked with the component that holds them.
bool isFloatValue(const sem::Type* type) {
  return type && (type->isScalar() || type->isVector()) && type->scalar == sem::ScalarKind::Float;
}

}  // namespace

bool isCheckedOperation(const ast::Expr& e, const sem::ExprInfo& info) {
  if (!isFloatValue(info.type)) return false;
  switch (e.kind) {
    case ast::ExprKind::Binary: return isArithmetic(ast::cast<ast::BinaryExpr>(e).op);
    case ast::ExprKind::Assign: return isArithmetic(ast::cast<ast::AssignExpr>(e).op);
    case ast::ExprKind::Call: {
      if (info.ref == sem::RefKind::Function) return true;
      if (info.ref != sem::RefKind::Builtin) return false;
      const std::string& name = ast::cast<ast::CallExpr>(e).callee.name;
      if (isTextureLookup(name)) return true;
      for (std::string_view unsafe : kUnsafeBuiltins) {
        if (name == unsafe) return true;
      }
      return false;
    }
    default: return false;
  }
}

std::string OperationProbe::wrap(const ast::Expr& e, const std::string& text, reflection::HazardOperation site) {
  auto [it, added] = numbers_.try_emplace(&e, static_cast<uint32_t>(operations_.size() + 1));
  if (added) operations_.push_back(std::move(site));
  return fmt::format("{}({}, {}u)", function_, text, it->second);
}

}  // namespace spire::codegen
