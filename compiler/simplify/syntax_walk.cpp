#include "simplify/syntax_walk.h"

namespace spire::simplify {
namespace {

bool immutable(const ast::Stmt& s) { return ast::hasAttribute(s.attributes, "Immutable"); }

}  // namespace

void SyntaxWalker::expr(const ast::Expr* e) {
  if (!e) return;
  visit_(*e);
  switch (e->kind) {
    case ast::ExprKind::Unary: expr(ast::cast<ast::UnaryExpr>(*e).operand.get()); break;
    case ast::ExprKind::Binary: binary(ast::cast<ast::BinaryExpr>(*e)); break;
    case ast::ExprKind::Assign: {
      const auto& a = ast::cast<ast::AssignExpr>(*e);
      expr(a.target.get());
      expr(a.value.get());
      break;
    }
    case ast::ExprKind::Ternary: {
      const auto& t = ast::cast<ast::TernaryExpr>(*e);
      expr(t.condition.get());
      expr(t.thenValue.get());
      expr(t.elseValue.get());
      break;
    }
    case ast::ExprKind::Call:
      for (const ast::ExprPtr& arg : ast::cast<ast::CallExpr>(*e).args) expr(arg.get());
      break;
    case ast::ExprKind::Member: expr(ast::cast<ast::MemberExpr>(*e).object.get()); break;
    case ast::ExprKind::Index: {
      const auto& i = ast::cast<ast::IndexExpr>(*e);
      expr(i.object.get());
      expr(i.index.get());
      break;
    }
    default: break;
  }
}

// A left-associative chain is walked in a loop (ast::leftSpine), so that
// recursion only goes as deep as the code is really nested.
void SyntaxWalker::binary(const ast::BinaryExpr& top) {
  const std::vector<const ast::BinaryExpr*> spine = ast::leftSpine(top);
  expr(spine.front()->lhs.get());
  for (size_t i = 0; i < spine.size(); ++i) {
    if (i > 0) visit_(*spine[i - 1]);
    expr(spine[i]->rhs.get());
  }
}

// An [Immutable] statement is not walked unless asked, so no rule sees
// anything in it.
void SyntaxWalker::stmt(const ast::Stmt* s) {
  if (!s || (immutable_ == Immutable::Skip && immutable(*s))) return;
  visitStmt_(*s);
  switch (s->kind) {
    case ast::StmtKind::Block:
      for (const ast::StmtPtr& child : ast::cast<ast::BlockStmt>(*s).statements) stmt(child.get());
      break;
    case ast::StmtKind::VarDecl:
      for (const ast::VarDeclarator& d : ast::cast<ast::VarDeclStmt>(*s).declarators) expr(d.init.get());
      break;
    case ast::StmtKind::Expr: expr(ast::cast<ast::ExprStmt>(*s).expr.get()); break;
    case ast::StmtKind::If: {
      const auto& i = ast::cast<ast::IfStmt>(*s);
      expr(i.condition.get());
      stmt(i.thenBranch.get());
      stmt(i.elseBranch.get());
      break;
    }
    case ast::StmtKind::For: {
      const auto& f = ast::cast<ast::ForStmt>(*s);
      stmt(f.init.get());
      expr(f.condition.get());
      expr(f.step.get());
      stmt(f.body.get());
      break;
    }
    case ast::StmtKind::While: {
      const auto& w = ast::cast<ast::WhileStmt>(*s);
      expr(w.condition.get());
      stmt(w.body.get());
      break;
    }
    case ast::StmtKind::DoWhile: {
      const auto& d = ast::cast<ast::DoWhileStmt>(*s);
      stmt(d.body.get());
      expr(d.condition.get());
      break;
    }
    case ast::StmtKind::Return: expr(ast::cast<ast::ReturnStmt>(*s).value.get()); break;
    default: break;
  }
}

}  // namespace spire::simplify
