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

// The check functions take float scalars and vectors; other results are
// checked with the component that holds them.
bool isFloatValue(const sem::Type* type) {
  return type && (type->isScalar() || type->isVector()) && type->scalar == sem::ScalarKind::Float;
}

}  // namespace

bool isCheckedOperation(const ast::Expr& e, const sem::ExprInfo& info) {
  if (!isFloatValue(info.type)) return false;
  switch (e.kind) {
    case ast::ExprKind::Binary: return ast::cast<ast::BinaryExpr>(e).op == ast::BinaryOp::Div;
    case ast::ExprKind::Assign: return ast::cast<ast::AssignExpr>(e).op == ast::AssignOp::Div;
    case ast::ExprKind::Call: {
      if (info.ref == sem::RefKind::Function) return true;
      if (info.ref != sem::RefKind::Builtin) return false;
      const std::string& name = ast::cast<ast::CallExpr>(e).callee.name;
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
