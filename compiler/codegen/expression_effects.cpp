#include "codegen/expression_effects.h"

#include <array>
#include <string_view>
#include <vector>

namespace spire::codegen {
namespace {

// The GLSL built-ins that write through an `out` parameter.
bool writesOutParameter(std::string_view builtin) {
  static constexpr std::array<std::string_view, 6> kWriting = {"modf",       "frexp",        "uaddCarry",
                                                               "usubBorrow", "umulExtended", "imulExtended"};
  for (std::string_view name : kWriting) {
    if (name == builtin) return true;
  }
  return false;
}

}  // namespace

bool callWrites(const sem::Model& model, const ast::CallExpr& call) {
  const sem::ExprInfo& info = model.info(call);
  if (info.ref == sem::RefKind::Builtin) return writesOutParameter(call.callee.name);
  if (info.ref != sem::RefKind::Function || info.function == nullptr) return false;
  for (const sem::Param& p : info.function->params) {
    if (p.direction != ast::ParamDirection::In) return true;
  }
  return false;
}

bool hasSideEffects(const sem::Model& model, const ast::Expr& root) {
  std::vector<const ast::Expr*> pending{&root};
  const auto push = [&](const ast::ExprPtr& child) {
    if (child) pending.push_back(child.get());
  };
  while (!pending.empty()) {
    const ast::Expr& e = *pending.back();
    pending.pop_back();
    switch (e.kind) {
      case ast::ExprKind::BoolLiteral:
      case ast::ExprKind::IntLiteral:
      case ast::ExprKind::FloatLiteral:
      case ast::ExprKind::Name: break;
      case ast::ExprKind::Assign: return true;
      case ast::ExprKind::Unary: {
        const auto& u = ast::cast<ast::UnaryExpr>(e);
        switch (u.op) {
          case ast::UnaryOp::PreIncrement:
          case ast::UnaryOp::PreDecrement:
          case ast::UnaryOp::PostIncrement:
          case ast::UnaryOp::PostDecrement: return true;
          default: push(u.operand);
        }
        break;
      }
      case ast::ExprKind::Binary: {
        const auto& b = ast::cast<ast::BinaryExpr>(e);
        push(b.lhs);
        push(b.rhs);
        break;
      }
      case ast::ExprKind::Ternary: {
        const auto& t = ast::cast<ast::TernaryExpr>(e);
        push(t.condition);
        push(t.thenValue);
        push(t.elseValue);
        break;
      }
      case ast::ExprKind::Call: {
        const auto& c = ast::cast<ast::CallExpr>(e);
        if (callWrites(model, c)) return true;
        for (const ast::ExprPtr& arg : c.args) push(arg);
        break;
      }
      case ast::ExprKind::Member: push(ast::cast<ast::MemberExpr>(e).object); break;
      case ast::ExprKind::Index: {
        const auto& i = ast::cast<ast::IndexExpr>(e);
        push(i.object);
        push(i.index);
        break;
      }
    }
  }
  return false;
}

}  // namespace spire::codegen
