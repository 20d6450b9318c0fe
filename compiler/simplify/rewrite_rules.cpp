#include "simplify/rewrite_rules.h"

#include <algorithm>

#include "simplify/cost_model.h"
#include "simplify/rule_matching.h"
#include "simplify/syntax_walk.h"

namespace spire::simplify {
namespace {

class RuleSet {
 public:
  RuleSet(const sem::Model& model, const SourceManager& sources, const ast::ComponentDecl& decl,
          const std::vector<UserRule>& userRules)
      : model_(model), sources_(sources), decl_(decl), userRules_(userRules), costs_(model) {
    cost_ = costs_.definition(decl);
  }

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
  bool isConstant(const ast::Expr& e) const { return isConstantExpr(model_, e); }
  // `e` replaced by `kept` (parenthesized: the context's precedence is kept
  // whatever `kept` is), when both have the same type.
  void collapse(const char* rule, const ast::Expr& e, const ast::Expr& kept) {
    const std::string type = typeName(e);
    if (type.empty() || typeName(kept) != type) return;
    add({rule, e.range, "(" + text(kept) + ")", text(e), ""}, {&e, {&kept}, std::nullopt});
  }
  // `r`, with its saving: the definition's cost with `substitution` in
  // place of what `r` replaces.
  void add(Rewrite r, const Substitution& substitution) {
    for (const Rewrite& other : rewrites_) {
      if (other.range == r.range && other.replacement == r.replacement) return;
    }
    r.saving = cost_ - costs_.definition(decl_, substitution);
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
    if (auto match = applyUserRule(rule, e, sources_)) {
      add({rule.name, e.range, match->replacement, text(e), type}, {&e, match->holes, std::nullopt});
    }
  }

  const sem::Model& model_;
  const SourceManager& sources_;
  const ast::ComponentDecl& decl_;
  const std::vector<UserRule>& userRules_;
  CostModel costs_;
  int64_t cost_ = 0;  // the definition's, as written
  std::vector<Rewrite> rewrites_;
};

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
  const auto fewer = static_cast<int64_t>(bound->value - 1);
  add({"loop-iteration", bound->range, std::to_string(fewer), text(*bound), ""}, {bound, {}, fewer});
}

}  // namespace

bool isConstantExpr(const sem::Model& model, const ast::Expr& e) {
  switch (e.kind) {
    case ast::ExprKind::BoolLiteral:
    case ast::ExprKind::IntLiteral:
    case ast::ExprKind::FloatLiteral: return true;
    case ast::ExprKind::Unary: {
      const auto& u = ast::cast<ast::UnaryExpr>(e);
      return (u.op == ast::UnaryOp::Negate || u.op == ast::UnaryOp::Plus) && isConstantExpr(model, *u.operand);
    }
    case ast::ExprKind::Call: {
      const auto& call = ast::cast<ast::CallExpr>(e);
      const sem::Type* type = model.typeOf(call);
      return type && call.callee.name == type->name() &&
             std::all_of(call.args.begin(), call.args.end(),
                         [&](const ast::ExprPtr& a) { return isConstantExpr(model, *a); });
    }
    default: return false;
  }
}

std::vector<Rewrite> proposeRewrites(const sem::Model& model, const SourceManager& sources,
                                     const ast::ComponentDecl& decl, const std::vector<UserRule>& userRules) {
  RuleSet rules(model, sources, decl, userRules);
  SyntaxWalker walker([&](const ast::Expr& e) { rules.propose(e); }, [&](const ast::Stmt& s) { rules.loop(s); });
  walker.expr(decl.init.get());
  walker.stmt(decl.body.get());
  std::vector<Rewrite> rewrites = rules.take();
  std::stable_sort(rewrites.begin(), rewrites.end(),
                   [](const Rewrite& a, const Rewrite& b) { return a.range.begin < b.range.begin; });
  std::vector<Rewrite> ranked;
  for (size_t i : rankRewrites(rewrites)) ranked.push_back(std::move(rewrites[i]));
  return ranked;
}

std::vector<size_t> rankRewrites(const std::vector<Rewrite>& rewrites) {
  const auto removed = [](const Rewrite& r) {
    return static_cast<int64_t>(r.before.size()) - static_cast<int64_t>(r.replacement.size());
  };
  std::vector<size_t> order(rewrites.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  // Stable: rewrites equal in both keys keep the order they come in.
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    const Rewrite& x = rewrites[a];
    const Rewrite& y = rewrites[b];
    return x.saving != y.saving ? x.saving > y.saving : removed(x) > removed(y);
  });
  return order;
}

const ast::Expr* widestExprWithin(const ast::ComponentDecl& decl, const SourceRange& range) {
  const ast::Expr* widest = nullptr;
  const auto within = [&](const ast::Expr& e) {
    return e.range.file == range.file && e.range.begin >= range.begin && e.range.end <= range.end;
  };
  SyntaxWalker walker(
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
