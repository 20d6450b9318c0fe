#include "simplify/value_keys.h"

#include <fmt/format.h>

#include "codegen/expression_effects.h"

namespace spire::simplify {

void ValueKeys::beginDefinition() { frames_.assign(1, Frame{}); }

void ValueKeys::enterFunction(const ast::FunctionDecl& f, const std::vector<std::optional<std::string>>& arguments) {
  Frame frame;
  for (size_t i = 0; i < f.params.size(); ++i) {
    frame.params[&f.params[i]] = i < arguments.size() ? arguments[i] : std::nullopt;
  }
  frames_.push_back(std::move(frame));
}

void ValueKeys::leaveFunction() {
  if (frames_.size() > 1) frames_.pop_back();
}

void ValueKeys::setLocal(const ast::VarDeclarator* local, std::optional<std::string> value) {
  if (local) frames_.back().locals[local] = value ? std::move(*value) : opaque();
}

void ValueKeys::wrote(const ast::Expr& target, std::optional<std::string> value) {
  const ast::Expr* e = &target;
  while (e && e->kind != ast::ExprKind::Name) {
    if (const auto* m = ast::dyn_cast<ast::MemberExpr>(e)) {
      e = m->object.get();
    } else if (const auto* i = ast::dyn_cast<ast::IndexExpr>(e)) {
      e = i->object.get();
    } else {
      return;
    }
  }
  if (!e) return;
  if (e != &target) value.reset();
  const sem::ExprInfo& info = model_.info(*e);
  Frame& frame = frames_.back();
  if (info.ref == sem::RefKind::Local) setLocal(info.local, std::move(value));
  if (info.ref == sem::RefKind::Parameter) frame.params[info.parameter] = value ? std::move(value) : opaque();
}

std::optional<std::string> ValueKeys::key(const ast::Expr& e) {
  Frame& frame = frames_.back();
  if (const auto found = frame.known.find(&e); found != frame.known.end()) return found->second;
  std::optional<std::string> k = compute(e);
  if (k && k->size() > kMaxValueKey) k.reset();
  frames_.back().known[&e] = k;
  return k;
}

std::optional<std::string> ValueKeys::joined(std::string head, const std::vector<const ast::Expr*>& parts) {
  head += '(';
  for (const ast::Expr* part : parts) {
    const std::optional<std::string> k = part ? key(*part) : std::nullopt;
    if (!k) return std::nullopt;
    head += *k;
    head += ',';
    if (head.size() > kMaxValueKey) return std::nullopt;
  }
  head += ')';
  return head;
}

std::optional<std::string> ValueKeys::compute(const ast::Expr& e) {
  switch (e.kind) {
    case ast::ExprKind::BoolLiteral: return ast::cast<ast::BoolLiteral>(e).value ? "true" : "false";
    case ast::ExprKind::IntLiteral: {
      const auto& i = ast::cast<ast::IntLiteral>(e);
      return fmt::format("{}{}", i.value, i.isUnsigned ? "u" : "i");
    }
    case ast::ExprKind::FloatLiteral: return fmt::format("{}f", ast::cast<ast::FloatLiteral>(e).value);
    case ast::ExprKind::Name: return name(e);
    case ast::ExprKind::Unary: {
      const auto& u = ast::cast<ast::UnaryExpr>(e);
      if (u.op != ast::UnaryOp::Plus && u.op != ast::UnaryOp::Negate && u.op != ast::UnaryOp::LogicalNot &&
          u.op != ast::UnaryOp::BitNot) {
        return std::nullopt;
      }
      return joined(fmt::format("u{}", static_cast<int>(u.op)), {u.operand.get()});
    }
    case ast::ExprKind::Binary: return binary(ast::cast<ast::BinaryExpr>(e));
    case ast::ExprKind::Ternary: {
      const auto& t = ast::cast<ast::TernaryExpr>(e);
      return joined("?", {t.condition.get(), t.thenValue.get(), t.elseValue.get()});
    }
    case ast::ExprKind::Call: return call(ast::cast<ast::CallExpr>(e));
    case ast::ExprKind::Member: {
      const auto& m = ast::cast<ast::MemberExpr>(e);
      return joined("." + m.member, {m.object.get()});
    }
    case ast::ExprKind::Index: {
      const auto& i = ast::cast<ast::IndexExpr>(e);
      return joined("[]", {i.object.get(), i.index.get()});
    }
    default: return std::nullopt;  // assignments
  }
}

std::optional<std::string> ValueKeys::name(const ast::Expr& e) {
  const sem::ExprInfo& info = model_.info(e);
  const Frame& frame = frames_.back();
  switch (info.ref) {
    case sem::RefKind::Component: return "@" + ast::cast<ast::NameExpr>(e).name;
    case sem::RefKind::Local: {
      const auto found = frame.locals.find(info.local);
      return found != frame.locals.end() ? std::optional<std::string>(found->second) : std::nullopt;
    }
    case sem::RefKind::Parameter: {
      const auto found = frame.params.find(info.parameter);
      return found != frame.params.end() ? found->second : std::nullopt;
    }
    default: return std::nullopt;
  }
}

// A chain is keyed in a loop, innermost link first (see ast::leftSpine).
std::optional<std::string> ValueKeys::binary(const ast::BinaryExpr& top) {
  if (top.op == ast::BinaryOp::Comma) return std::nullopt;
  const std::vector<const ast::BinaryExpr*> spine = ast::leftSpine(top);
  std::optional<std::string> k = key(*spine.front()->lhs);
  for (const ast::BinaryExpr* b : spine) {
    // Once a link has no key, none above it has: each is remembered, so
    // that asking for every link of a long chain stays linear.
    if (k) {
      const std::optional<std::string> rhs = key(*b->rhs);
      k = rhs && b->op != ast::BinaryOp::Comma
              ? std::optional<std::string>(fmt::format("b{}({},{})", static_cast<int>(b->op), *k, *rhs))
              : std::nullopt;
      if (k && k->size() > kMaxValueKey) k.reset();
    }
    if (b != &top) frames_.back().known[b] = k;
  }
  return k;
}

std::optional<std::string> ValueKeys::call(const ast::CallExpr& c) {
  if (codegen::callWrites(model_, c)) return std::nullopt;
  const sem::ExprInfo& info = model_.info(c);
  std::vector<const ast::Expr*> args;
  for (const ast::ExprPtr& arg : c.args) args.push_back(arg.get());
  if (info.ref == sem::RefKind::Function) {
    // Overloads share a name: the function itself tells them apart.
    if (!info.function) return std::nullopt;
    return joined(fmt::format("f{}", static_cast<const void*>(info.function)), args);
  }
  return joined(c.callee.name, args);
}

}  // namespace spire::simplify
