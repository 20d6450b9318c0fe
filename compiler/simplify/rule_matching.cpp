#include "simplify/rule_matching.h"

#include <utility>
#include <vector>

namespace spire::simplify {
namespace {

class Matcher {
 public:
  explicit Matcher(const UserRule& rule) : rule_(rule) {}

  // Whether `target` is `pattern`'s tree. A repeated metavariable compares
  // two trees of the shader with the same function: neither side is a
  // metavariable node there.
  bool match(const ast::Expr& pattern, const ast::Expr& target) {
    if (const auto meta = rule_.metavariables.find(&pattern); meta != rule_.metavariables.end()) {
      const auto [bound, first] = bindings_.emplace(meta->second, &target);
      return first || match(*bound->second, target);
    }
    if (pattern.kind != target.kind) return false;
    switch (pattern.kind) {
      case ast::ExprKind::BoolLiteral:
        return ast::cast<ast::BoolLiteral>(pattern).value == ast::cast<ast::BoolLiteral>(target).value;
      case ast::ExprKind::IntLiteral: {
        const auto& p = ast::cast<ast::IntLiteral>(pattern);
        const auto& t = ast::cast<ast::IntLiteral>(target);
        return p.value == t.value && p.isUnsigned == t.isUnsigned;
      }
      case ast::ExprKind::FloatLiteral:
        return ast::cast<ast::FloatLiteral>(pattern).value == ast::cast<ast::FloatLiteral>(target).value;
      case ast::ExprKind::Name: return ast::cast<ast::NameExpr>(pattern).name == ast::cast<ast::NameExpr>(target).name;
      case ast::ExprKind::Unary: {
        const auto& p = ast::cast<ast::UnaryExpr>(pattern);
        const auto& t = ast::cast<ast::UnaryExpr>(target);
        return p.op == t.op && match(*p.operand, *t.operand);
      }
      case ast::ExprKind::Binary: return binary(pattern, target);
      default: return compound(pattern, target);
    }
  }

  const ast::Expr* bound(const std::string& name) const { return bindings_.at(name); }

 private:
  // Down both left spines in a loop: a bound operand compared with another
  // can be a generated chain thousands of terms long (ast::leftSpine).
  bool binary(const ast::Expr& pattern, const ast::Expr& target) {
    std::vector<std::pair<const ast::Expr*, const ast::Expr*>> rhs;
    const ast::Expr* p = &pattern;
    const ast::Expr* t = &target;
    while (p->kind == ast::ExprKind::Binary && rule_.metavariables.count(p) == 0) {
      if (t->kind != ast::ExprKind::Binary) return false;
      const auto& pb = ast::cast<ast::BinaryExpr>(*p);
      const auto& tb = ast::cast<ast::BinaryExpr>(*t);
      if (pb.op != tb.op) return false;
      rhs.emplace_back(pb.rhs.get(), tb.rhs.get());
      p = pb.lhs.get();
      t = tb.lhs.get();
    }
    if (!match(*p, *t)) return false;
    for (const auto& [pr, tr] : rhs) {
      if (!match(*pr, *tr)) return false;
    }
    return true;
  }

  bool all(const std::vector<std::pair<const ast::ExprPtr*, const ast::ExprPtr*>>& pairs) {
    for (const auto& [p, t] : pairs) {
      if (!match(**p, **t)) return false;
    }
    return true;
  }

  bool compound(const ast::Expr& pattern, const ast::Expr& target);

  const UserRule& rule_;
  std::map<std::string, const ast::Expr*> bindings_;
};

// Assignments, ?:, calls, members and indexing.
bool Matcher::compound(const ast::Expr& pattern, const ast::Expr& target) {
  switch (pattern.kind) {
    case ast::ExprKind::Assign: {
      const auto& p = ast::cast<ast::AssignExpr>(pattern);
      const auto& t = ast::cast<ast::AssignExpr>(target);
      return p.op == t.op && all({{&p.target, &t.target}, {&p.value, &t.value}});
    }
    case ast::ExprKind::Ternary: {
      const auto& p = ast::cast<ast::TernaryExpr>(pattern);
      const auto& t = ast::cast<ast::TernaryExpr>(target);
      return all({{&p.condition, &t.condition}, {&p.thenValue, &t.thenValue}, {&p.elseValue, &t.elseValue}});
    }
    case ast::ExprKind::Call: {
      const auto& p = ast::cast<ast::CallExpr>(pattern);
      const auto& t = ast::cast<ast::CallExpr>(target);
      // Array constructors (`float[3](...)`) are left alone: their sizes
      // are part of the callee.
      if (p.callee.name != t.callee.name || p.args.size() != t.args.size() || !p.callee.arraySizes.empty() ||
          !t.callee.arraySizes.empty()) {
        return false;
      }
      for (size_t i = 0; i < p.args.size(); ++i) {
        if (!match(*p.args[i], *t.args[i])) return false;
      }
      return true;
    }
    case ast::ExprKind::Member: {
      const auto& p = ast::cast<ast::MemberExpr>(pattern);
      const auto& t = ast::cast<ast::MemberExpr>(target);
      return p.member == t.member && match(*p.object, *t.object);
    }
    case ast::ExprKind::Index: {
      const auto& p = ast::cast<ast::IndexExpr>(pattern);
      const auto& t = ast::cast<ast::IndexExpr>(target);
      return all({{&p.object, &t.object}, {&p.index, &t.index}});
    }
    default: return false;
  }
}

}  // namespace

std::optional<UserRuleMatch> applyUserRule(const UserRule& rule, const ast::Expr& e, const SourceManager& sources) {
  Matcher matcher(rule);
  if (!matcher.match(*rule.pattern, e)) return std::nullopt;
  UserRuleMatch result{"(", {}};
  size_t copied = 0;
  for (const MetavariableUse& hole : rule.holes) {
    const ast::Expr* bound = matcher.bound(hole.name);
    result.replacement.append(rule.replacement, copied, hole.offset - copied);
    result.replacement += "(" + std::string(sources.text(bound->range)) + ")";
    result.holes.push_back(bound);
    copied = hole.offset + hole.length;
  }
  result.replacement.append(rule.replacement, copied);
  result.replacement += ")";
  return result;
}

}  // namespace spire::simplify
