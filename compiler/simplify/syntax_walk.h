// A walk over a component definition's syntax tree, for the rules that
// propose rewrites (rewrite_rules.h) and for the cost model's dead-code
// pass (cost_model.h): every expression and statement, outermost first.
#pragma once

#include <functional>

#include "syntax/ast.h"

namespace spire::simplify {

class SyntaxWalker {
 public:
  // Whether statements marked [Immutable], and everything inside them, are
  // visited: rules must not see them, the cost model must.
  enum class Immutable { Skip, Visit };

  SyntaxWalker(std::function<void(const ast::Expr&)> visit, std::function<void(const ast::Stmt&)> visitStmt,
               Immutable immutable = Immutable::Skip)
      : visit_(std::move(visit)), visitStmt_(std::move(visitStmt)), immutable_(immutable) {}

  void expr(const ast::Expr* e);
  void stmt(const ast::Stmt* s);

 private:
  void binary(const ast::BinaryExpr& top);

  std::function<void(const ast::Expr&)> visit_;
  std::function<void(const ast::Stmt&)> visitStmt_;
  Immutable immutable_;
};

}  // namespace spire::simplify
