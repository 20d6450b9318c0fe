#include "simplify/rewrite_rules.h"

#include <algorithm>
#include <functional>

#include "simplify/rule_matching.h"

namespace spire::simplify {
namespace {

// Calls the visitors on every expression and statement of a definition,
// outermost first, except those inside [Immutable] statements.
class ExprWalker {
 public:
  ExprWalker(std::function<void(const ast::Expr&)> visit, std::function<void(const ast::Stmt&)> visitStmt)
      : visit_(std::move(visit)), visitStmt_(std::move(visitStmt)) {}

  void expr(const ast::Expr* e) {
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

  void stmt(const ast::Stmt* s);

 private:
  // A left-associative chain is walked in a loop (ast::leftSpine), so that
  // recursion only goes as deep as the code is really nested.
  void binary(const ast::BinaryExpr& top) {
    const std::vector<const ast::BinaryExpr*> spine = ast::leftSpine(top);
    expr(spine.front()->lhs.get());
    for (size_t i = 0; i < spine.size(); ++i) {
      if (i > 0) visit_(*spine[i - 1]);
      expr(spine[i]->rhs.get());
    }
  }

  std::function<void(const ast::Expr&)> visit_;
  std::function<void(const ast::Stmt&)> visitStmt_;
};

bool immutable(const ast::Stmt& s) {
  return std::any_of(s.attributes.begin(), s.attributes.end(),
                     [](const ast::Attribute& a) { return a.name == "Immutable"; });
}

// An [Immutable] statement is not walked, so no rule sees anything in it.
void ExprWalker::stmt(const ast::Stmt* s) {
  if (!s || immutable(*s)) return;
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

class RuleSet {
 public:
  RuleSet(const sem::Model& model, const SourceManager& sources, const std::vector<UserRule>& userRules)
      : model_(model), sources_(sources), userRules_(userRules) {}

  void propose(const ast::Expr& e) {
    if (const auto* b = ast::dyn_cast<ast::BinaryExpr>(&e)) constantOperand(*b);
    if (const auto* c = ast::dyn_cast<ast::CallExpr>(&e)) callToArgument(*c);
    for (const UserRule& rule : userRules_) userRule(rule, e);
  }
  void loop(const ast::Stmt& s);
  std::vector<Rewrite> take() { return std::move(rewrites_); }

 private:
  std::string typeName(const ast::Expr& e) const {
    const sem::Type* type = model_.typeOf(e);
    return type ? type->name() : "";
  }
  std::string text(const ast::Expr& e) const { return std::string(sources_.text(e.range)); }
  bool isConstructor(const ast::CallExpr& call) const { return call.callee.name == typeName(call); }
  bool isConstant(const ast::Expr& e) const;
  // `e` replaced by `kept` (parenthesized: the context's precedence is kept
  // whatever `kept` is), when both have the same type.
  void collapse(const char* rule, const ast::Expr& e, const ast::Expr& kept) {
    const std::string type = typeName(e);
    if (type.empty() || typeName(kept) != type) return;
    add({rule, e.range, "(" + text(kept) + ")", text(e), ""});
  }
  void add(Rewrite r) {
    for (const Rewrite& other : rewrites_) {
      if (other.range == r.range && other.replacement == r.replacement) return;
    }
    rewrites_.push_back(std::move(r));
  }
  void constantOperand(const ast::BinaryExpr& b) {
    if (b.op != ast::BinaryOp::Add && b.op != ast::BinaryOp::Sub && b.op != ast::BinaryOp::Mul &&
        b.op != ast::BinaryOp::Div) {
      return;
    }
    if (isConstant(*b.rhs)) collapse("constant-operand", b, *b.lhs);
    if (isConstant(*b.lhs)) collapse("constant-operand", b, *b.rhs);
  }
  // User functions are left alone: their arguments need not relate to what
  // they return.
  void callToArgument(const ast::CallExpr& call) {
    if (isConstructor(call) || model_.builtins().lookup(call.callee.name) == nullptr) return;
    for (const ast::ExprPtr& arg : call.args) {
      if (!isConstant(*arg)) collapse("call-to-argument", call, *arg);
    }
  }

  // Whatever the replacement's type, it is checked when compiled (the
  // Rewrite's `type`): only an expression with a type is rewritten.
  void userRule(const UserRule& rule, const ast::Expr& e) {
    const std::string type = typeName(e);
    if (type.empty()) return;
    if (auto replacement = applyUserRule(rule, e, sources_)) add({rule.name, e.range, *replacement, text(e), type});
  }

  const sem::Model& model_;
  const SourceManager& sources_;
  const std::vector<UserRule>& userRules_;
  std::vector<Rewrite> rewrites_;
};

bool RuleSet::isConstant(const ast::Expr& e) const {
  switch (e.kind) {
    case ast::ExprKind::BoolLiteral:
    case ast::ExprKind::IntLiteral:
    case ast::ExprKind::FloatLiteral: return true;
    case ast::ExprKind::Unary: {
      const auto& u = ast::cast<ast::UnaryExpr>(e);
      return (u.op == ast::UnaryOp::Negate || u.op == ast::UnaryOp::Plus) && isConstant(*u.operand);
    }
    case ast::ExprKind::Call: {
      const auto& call = ast::cast<ast::CallExpr>(e);
      return isConstructor(call) &&
             std::all_of(call.args.begin(), call.args.end(), [&](const ast::ExprPtr& a) { return isConstant(*a); });
    }
    default: return false;
  }
}

// `for (...; i < N; ...)` or `i <= N` with an integer literal N: one
// iteration fewer.
void RuleSet::loop(const ast::Stmt& s) {
  const auto* f = ast::dyn_cast<ast::ForStmt>(&s);
  if (!f) return;
  const auto* condition = ast::dyn_cast<ast::BinaryExpr>(f->condition.get());
  if (!condition || (condition->op != ast::BinaryOp::Less && condition->op != ast::BinaryOp::LessEqual)) return;
  const auto* bound = ast::dyn_cast<ast::IntLiteral>(condition->rhs.get());
  const uint64_t lowest = condition->op == ast::BinaryOp::Less ? 2 : 1;
  if (!bound || bound->value < lowest) return;
  add({"loop-iteration", bound->range, std::to_string(bound->value - 1), text(*bound), ""});
}

}  // namespace

std::vector<Rewrite> proposeRewrites(const sem::Model& model, const SourceManager& sources,
                                     const ast::ComponentDecl& decl, const std::vector<UserRule>& userRules) {
  RuleSet rules(model, sources, userRules);
  ExprWalker walker([&](const ast::Expr& e) { rules.propose(e); }, [&](const ast::Stmt& s) { rules.loop(s); });
  walker.expr(decl.init.get());
  walker.stmt(decl.body.get());
  std::vector<Rewrite> rewrites = rules.take();
  // The rewrites that remove the most source first (a rough stand-in for
  // the work they save), then in source order.
  const auto removed = [](const Rewrite& r) {
    return static_cast<long>(r.before.size()) - static_cast<long>(r.replacement.size());
  };
  std::stable_sort(rewrites.begin(), rewrites.end(), [&](const Rewrite& a, const Rewrite& b) {
    return removed(a) != removed(b) ? removed(a) > removed(b) : a.range.begin < b.range.begin;
  });
  return rewrites;
}

const ast::Expr* widestExprWithin(const ast::ComponentDecl& decl, const SourceRange& range) {
  const ast::Expr* widest = nullptr;
  const auto within = [&](const ast::Expr& e) {
    return e.range.file == range.file && e.range.begin >= range.begin && e.range.end <= range.end;
  };
  ExprWalker walker(
      [&](const ast::Expr& e) {
        if (within(e) && (!widest || e.range.end - e.range.begin > widest->range.end - widest->range.begin)) {
          widest = &e;
        }
      },
      [](const ast::Stmt&) {});
  walker.expr(decl.init.get());
  walker.stmt(decl.body.get());
  return widest;
}

}  // namespace spire::simplify
