// Expression checking for BodyChecker.
#include <fmt/format.h>

#include <algorithm>
#include <cstdint>

#include "sema/body_checker.h"
#include "sema/operator_rules.h"
#include "support/spelling.h"
#include "syntax/ast_spelling.h"

namespace spire::sem {
namespace {

std::string signatureText(std::string_view name, const std::vector<const Type*>& args) {
  std::string text = fmt::format("{}(", name);
  for (size_t i = 0; i < args.size(); ++i) text += fmt::format("{}{}", i ? ", " : "", args[i]->name());
  return text + ")";
}

std::string_view directionPrefix(ast::ParamDirection d) {
  switch (d) {
    case ast::ParamDirection::Out: return "out ";
    case ast::ParamDirection::InOut: return "inout ";
    case ast::ParamDirection::In: break;
  }
  return "";
}

// One callable candidate, user-defined or built-in, in a uniform shape.
struct Candidate {
  const Function* function = nullptr;
  const BuiltinOverload* builtin = nullptr;
  const Type* result = nullptr;
  std::vector<Param> params;

  std::string describe(std::string_view name) const {
    std::string text = fmt::format("{} {}(", result->name(), name);
    for (size_t i = 0; i < params.size(); ++i) {
      text += fmt::format("{}{}{}", i ? ", " : "", directionPrefix(params[i].direction), params[i].type->name());
    }
    return text + ")";
  }
};

// The user functions and built-in overloads named `name`.
std::vector<Candidate> collectCandidates(const FunctionTable& functions, const BuiltinTable& builtins,
                                         std::string_view name) {
  std::vector<Candidate> candidates;
  if (auto it = functions.find(name); it != functions.end()) {
    for (const Function* f : it->second) candidates.push_back({f, nullptr, f->returnType, f->params});
  }
  if (const auto* overloads = builtins.lookup(name)) {
    for (const BuiltinOverload& o : *overloads) {
      Candidate c{nullptr, &o, o.result, {}};
      for (const BuiltinParam& p : o.params) c.params.push_back({p.type, p.direction});
      candidates.push_back(std::move(c));
    }
  }
  return candidates;
}

// A candidate the arguments can call, with which arguments match exactly.
struct Viable {
  const Candidate* candidate;
  std::vector<bool> exact;
};

std::vector<Viable> viableCandidates(const std::vector<Candidate>& candidates, const std::vector<const Type*>& args) {
  std::vector<Viable> viable;
  for (const Candidate& c : candidates) {
    if (c.params.size() != args.size()) continue;
    Viable v{&c, {}};
    bool ok = true;
    for (size_t i = 0; i < args.size() && ok; ++i) {
      const Param& p = c.params[i];
      const bool exact = args[i] == p.type;
      if (p.direction == ast::ParamDirection::In)
        ok = isImplicitlyConvertible(args[i], p.type);
      else if (p.direction == ast::ParamDirection::Out)
        ok = exact || isImplicitlyConvertible(p.type, args[i]);
      else
        ok = exact;
      v.exact.push_back(exact);
    }
    if (ok) viable.push_back(std::move(v));
  }
  return viable;
}

// GLSL 4.50 section 6.1: an exact match wins; otherwise a unique candidate
// whose conversions are nowhere worse and somewhere better than every other.
const Viable* bestViable(const std::vector<Viable>& viable) {
  auto better = [](const Viable& a, const Viable& b) {
    bool someBetter = false;
    for (size_t i = 0; i < a.exact.size(); ++i) {
      if (b.exact[i] && !a.exact[i]) return false;
      if (a.exact[i] && !b.exact[i]) someBetter = true;
    }
    return someBetter;
  };
  const Viable* best = nullptr;
  for (const Viable& v : viable) {
    if (std::all_of(viable.begin(), viable.end(), [&](const Viable& o) { return &o == &v || better(v, o); })) best = &v;
  }
  return best;
}

// An ambiguous call lists the tied candidates, an unmatched one every
// candidate, at most kMaxNotes of them.
void reportNoBestCandidate(DiagnosticList& diags, const ast::CallExpr& e, const std::vector<const Type*>& args,
                           const std::vector<Candidate>& candidates, const std::vector<Viable>& viable) {
  const bool ambiguous = !viable.empty();
  Diagnostic& d = diags.report(ambiguous ? DiagCode::E3016 : DiagCode::E3007, e.range,
                               fmt::format("{} call to '{}'", ambiguous ? "ambiguous" : "no matching function for",
                                           signatureText(e.callee.name, args)));
  constexpr size_t kMaxNotes = 8;
  size_t shown = 0;
  if (ambiguous) {
    for (const Viable& v : viable) {
      if (shown++ == kMaxNotes) break;
      d.note(v.candidate->function ? v.candidate->function->decl->nameRange : SourceRange{},
             fmt::format("candidate: {}", v.candidate->describe(e.callee.name)));
    }
  } else {
    for (const Candidate& c : candidates) {
      if (shown++ == kMaxNotes) break;
      d.note(c.function ? c.function->decl->nameRange : SourceRange{},
             fmt::format("candidate: {}", c.describe(e.callee.name)));
    }
  }
  if (candidates.size() > kMaxNotes && !ambiguous) {
    d.note({}, fmt::format("and {} more candidates", candidates.size() - kMaxNotes));
  }
}

bool isSwizzleSet(std::string_view member, std::string_view set) {
  return std::all_of(member.begin(), member.end(), [&](char c) { return set.find(c) != std::string_view::npos; });
}

}  // namespace

const Type* BodyChecker::check(const ast::Expr& expr) {
  ExprInfo info;
  return record(expr, info, checkUncached(expr, info));
}

const Type* BodyChecker::record(const ast::Expr& expr, ExprInfo& info, const Type* type) {
  info.type = type;
  if (!type->isError()) foldConstant(expr, info);
  model_.mutableInfo(expr) = info;
  noteType(type);
  return type;
}

void BodyChecker::noteType(const Type* type) {
  while (type->isArray()) type = type->element;
  if (type->isStruct() && std::find(usedStructs_.begin(), usedStructs_.end(), type) == usedStructs_.end()) {
    usedStructs_.push_back(type);
  }
}

const Type* BodyChecker::checkUncached(const ast::Expr& expr, ExprInfo& info) {
  TypeTable& types = model_.types();
  switch (expr.kind) {
    case ast::ExprKind::BoolLiteral: return types.boolType();
    case ast::ExprKind::IntLiteral:
      return ast::cast<ast::IntLiteral>(expr).isUnsigned ? types.uintType() : types.intType();
    case ast::ExprKind::FloatLiteral: return types.floatType();
    case ast::ExprKind::Name: return checkName(ast::cast<ast::NameExpr>(expr), info);
    case ast::ExprKind::Unary: return checkUnary(ast::cast<ast::UnaryExpr>(expr), info);
    case ast::ExprKind::Binary: return checkBinaryChain(ast::cast<ast::BinaryExpr>(expr));
    case ast::ExprKind::Assign: return checkAssign(ast::cast<ast::AssignExpr>(expr));
    case ast::ExprKind::Ternary: return checkTernary(ast::cast<ast::TernaryExpr>(expr));
    case ast::ExprKind::Call: return checkCall(ast::cast<ast::CallExpr>(expr), info);
    case ast::ExprKind::Member: return checkMember(ast::cast<ast::MemberExpr>(expr), info);
    case ast::ExprKind::Index: return checkIndex(ast::cast<ast::IndexExpr>(expr), info);
  }
  return types.error();
}

const Type* BodyChecker::checkName(const ast::NameExpr& e, ExprInfo& info) {
  if (const Local* local = findLocal(e.name)) {
    info.ref = local->param ? RefKind::Parameter : RefKind::Local;
    info.local = local->declarator;
    info.parameter = local->param;
    info.isLValue = !local->isConst;
    info.constant = local->constant;
    return local->type;
  }
  if (components_) {
    if (const Type* type = components_->useComponent(e.name, e.range)) {
      info.ref = RefKind::Component;
      return type;
    }
  }
  if (functions_.count(e.name) || model_.builtins().lookup(e.name)) {
    diags_.report(DiagCode::E3018, e.range, fmt::format("'{}' is a function, not a value", e.name));
    return model_.types().error();
  }
  if (model_.types().lookupBuiltin(e.name) || model_.structs.count(e.name)) {
    diags_.report(DiagCode::E3018, e.range, fmt::format("'{}' is a type, not a value", e.name));
    return model_.types().error();
  }
  const std::vector<std::string_view> candidates = visibleValueNames();
  const auto suggestion = closestSpelling(e.name, candidates);
  if (!suggestion) {
    diags_.report(DiagCode::E3001, e.range, fmt::format("use of undeclared identifier '{}'", e.name));
    return model_.types().error();
  }
  Diagnostic& d =
      diags_.report(DiagCode::E3001, e.range,
                    fmt::format("use of undeclared identifier '{}'; did you mean '{}'?", e.name, *suggestion));
  SourceRange where;
  if (const Local* local = findLocal(*suggestion))
    where = local->declRange;
  else if (components_)
    where = components_->declarationOf(*suggestion);
  if (where.valid()) d.note(where, fmt::format("'{}' declared here", *suggestion));
  return model_.types().error();
}

const Type* BodyChecker::checkUnary(const ast::UnaryExpr& e, ExprInfo&) {
  const Type* operand = check(*e.operand);
  if (operand->isError()) return operand;
  const Type* result = unaryResultType(e.op, operand);
  if (!result) {
    diags_.report(DiagCode::E3006, e.opRange,
                  fmt::format("invalid operand to unary '{}' (have '{}')", ast::spelling(e.op), operand->name()));
    return model_.types().error();
  }
  const bool mutates = e.op == ast::UnaryOp::PreIncrement || e.op == ast::UnaryOp::PreDecrement ||
                       e.op == ast::UnaryOp::PostIncrement || e.op == ast::UnaryOp::PostDecrement;
  if (mutates && !requireLValue(*e.operand, e.opRange, fmt::format("apply '{}' to", ast::spelling(e.op)))) {
    return model_.types().error();
  }
  return result;
}

// Checks the chain's first operand, then each node from the innermost out
// (ast::leftSpine), in the order the recursion would. check() records the
// outermost node, this loop every other one.
const Type* BodyChecker::checkBinaryChain(const ast::BinaryExpr& top) {
  const std::vector<const ast::BinaryExpr*> spine = ast::leftSpine(top);
  const Type* type = check(*spine.front()->lhs);
  for (size_t i = 0;; ++i) {
    type = checkBinary(*spine[i], type);
    if (i + 1 == spine.size()) return type;
    ExprInfo info;
    record(*spine[i], info, type);
  }
}

const Type* BodyChecker::checkBinary(const ast::BinaryExpr& e, const Type* lhs) {
  const Type* rhs = check(*e.rhs);
  if (lhs->isError() || rhs->isError()) return model_.types().error();
  if (e.op == ast::BinaryOp::Comma) return rhs;
  const Type* result = binaryResultType(model_.types(), e.op, lhs, rhs);
  if (!result) {
    diags_
        .report(DiagCode::E3005, e.opRange,
                fmt::format("invalid operands to binary '{}' ('{}' and '{}')", ast::spelling(e.op), lhs->name(),
                            rhs->name()))
        .note(e.lhs->range, fmt::format("left operand has type '{}'", lhs->name()))
        .note(e.rhs->range, fmt::format("right operand has type '{}'", rhs->name()));
    return model_.types().error();
  }
  return result;
}

const Type* BodyChecker::checkAssign(const ast::AssignExpr& e) {
  const Type* target = check(*e.target);
  const Type* value = check(*e.value);
  if (target->isError() || value->isError()) return model_.types().error();
  if (!requireLValue(*e.target, e.opRange, "assign to")) return model_.types().error();
  if (e.op == ast::AssignOp::Assign) {
    if (!isImplicitlyConvertible(value, target)) {
      diags_.report(
          DiagCode::E3004, e.value->range,
          fmt::format("cannot assign a value of type '{}' to a variable of type '{}'", value->name(), target->name()));
      return model_.types().error();
    }
    return target;
  }
  const Type* result = binaryResultType(model_.types(), compoundOperator(e.op), target, value);
  if (!result || result != target) {
    diags_.report(
        DiagCode::E3005, e.opRange,
        fmt::format("invalid operands to '{}' ('{}' and '{}')", ast::spelling(e.op), target->name(), value->name()));
    return model_.types().error();
  }
  return target;
}

const Type* BodyChecker::checkTernary(const ast::TernaryExpr& e) {
  checkCondition(*e.condition, "'?:'");
  const Type* a = check(*e.thenValue);
  const Type* b = check(*e.elseValue);
  if (a->isError() || b->isError()) return model_.types().error();
  const Type* common = commonType(a, b);
  if (!common || common->containsOpaque()) {
    diags_.report(DiagCode::E3004, SourceRange::cover(e.thenValue->range, e.elseValue->range),
                  fmt::format("the branches of '?:' have incompatible types '{}' and '{}'", a->name(), b->name()));
    return model_.types().error();
  }
  return common;
}

const Type* BodyChecker::checkCall(const ast::CallExpr& e, ExprInfo& info) {
  std::vector<const Type*> args;
  bool argError = false;
  for (const ast::ExprPtr& arg : e.args) {
    args.push_back(check(*arg));
    argError |= args.back()->isError();
  }
  // A callee that names a type (or carries array dimensions) is a constructor.
  const bool isArrayConstructor = !e.callee.arraySizes.empty();
  const Type* builtinType = model_.types().lookupBuiltin(e.callee.name);
  auto structIt = model_.structs.find(e.callee.name);
  if (isArrayConstructor || builtinType || structIt != model_.structs.end()) {
    const Type* target = resolveType(e.callee);
    if (target->isError() || argError) return model_.types().error();
    info.ref = target->isStruct() ? RefKind::StructConstructor : RefKind::Constructor;
    return checkConstructorCall(e, target, args);
  }
  if (argError) return model_.types().error();
  return checkFunctionCall(e, info, args);
}

const Type* BodyChecker::checkConstructorCall(const ast::CallExpr& e, const Type* target,
                                              const std::vector<const Type*>& args) {
  if (target->isArray()) {
    if (args.size() != target->arraySize) {
      diags_.report(DiagCode::E3010, e.range,
                    fmt::format("array constructor for '{}' needs {} arguments, got {}", target->name(),
                                target->arraySize, args.size()));
      return model_.types().error();
    }
    for (size_t i = 0; i < args.size(); ++i) {
      if (!isImplicitlyConvertible(args[i], target->element)) {
        diags_.report(
            DiagCode::E3010, e.args[i]->range,
            fmt::format("cannot convert '{}' to array element type '{}'", args[i]->name(), target->element->name()));
        return model_.types().error();
      }
    }
    return target;
  }
  if (target->isStruct()) {
    if (args.size() != target->fields.size()) {
      diags_.report(DiagCode::E3010, e.range,
                    fmt::format("constructor for struct '{}' needs {} arguments, got {}", target->name(),
                                target->fields.size(), args.size()));
      return model_.types().error();
    }
    for (size_t i = 0; i < args.size(); ++i) {
      if (!isImplicitlyConvertible(args[i], target->fields[i].type)) {
        diags_.report(DiagCode::E3010, e.args[i]->range,
                      fmt::format("cannot convert '{}' to '{}' for field '{}' of '{}'", args[i]->name(),
                                  target->fields[i].type->name(), target->fields[i].name, target->name()));
        return model_.types().error();
      }
    }
    return target;
  }
  if (auto constructible = checkConstructor(target, args); !constructible) {
    diags_.report(DiagCode::E3010, e.range, constructible.error().message);
    return model_.types().error();
  }
  return target;
}

const Type* BodyChecker::checkFunctionCall(const ast::CallExpr& e, ExprInfo& info,
                                           const std::vector<const Type*>& args) {
  const std::vector<Candidate> candidates = collectCandidates(functions_, model_.builtins(), e.callee.name);
  if (candidates.empty()) return reportUnknownFunction(e);
  const std::vector<Viable> viable = viableCandidates(candidates, args);
  const Viable* best = bestViable(viable);
  if (!best) {
    reportNoBestCandidate(diags_, e, args, candidates, viable);
    return model_.types().error();
  }
  const Candidate& chosen = *best->candidate;
  for (size_t i = 0; i < args.size(); ++i) {
    if (chosen.params[i].direction != ast::ParamDirection::In &&
        !requireLValue(*e.args[i], e.args[i]->range, "pass as an 'out' argument")) {
      return model_.types().error();
    }
  }
  if (chosen.function) {
    info.ref = RefKind::Function;
    info.function = chosen.function;
    if (std::find(calledFunctions_.begin(), calledFunctions_.end(), chosen.function) == calledFunctions_.end()) {
      calledFunctions_.push_back(chosen.function);
    }
  } else {
    info.ref = RefKind::Builtin;
    info.builtin = chosen.builtin;
  }
  return chosen.result;
}

const Type* BodyChecker::reportUnknownFunction(const ast::CallExpr& e) {
  if (findLocal(e.callee.name) || (components_ && components_->declarationOf(e.callee.name).valid())) {
    diags_.report(DiagCode::E3018, e.callee.nameRange, fmt::format("'{}' is not a function", e.callee.name));
    return model_.types().error();
  }
  std::vector<std::string_view> names = model_.builtins().names();
  for (const auto& [name, overloads] : functions_) names.push_back(name);
  const auto suggestion = closestSpelling(e.callee.name, names);
  Diagnostic& d = diags_.report(
      DiagCode::E3001, e.callee.nameRange,
      suggestion ? fmt::format("use of undeclared function '{}'; did you mean '{}'?", e.callee.name, *suggestion)
                 : fmt::format("use of undeclared function '{}'", e.callee.name));
  if (suggestion) {
    if (auto it = functions_.find(*suggestion); it != functions_.end() && !it->second.empty()) {
      d.note(it->second.front()->decl->nameRange, fmt::format("'{}' declared here", *suggestion));
    }
  }
  return model_.types().error();
}

const Type* BodyChecker::checkMember(const ast::MemberExpr& e, ExprInfo& info) {
  const Type* object = check(*e.object);
  if (object->isError()) return object;
  const ExprInfo& objectInfo = model_.info(*e.object);
  if (object->isStruct()) {
    for (uint32_t i = 0; i < object->fields.size(); ++i) {
      if (object->fields[i].name == e.member) {
        info.ref = RefKind::Field;
        info.fieldIndex = i;
        info.isLValue = objectInfo.isLValue;
        return object->fields[i].type;
      }
    }
    std::vector<std::string_view> names;
    for (const StructField& f : object->fields) names.push_back(f.name);
    const auto suggestion = closestSpelling(e.member, names);
    diags_.report(DiagCode::E3008, e.memberRange,
                  suggestion ? fmt::format("no field '{}' in struct '{}'; did you mean '{}'?", e.member, object->name(),
                                           *suggestion)
                             : fmt::format("no field '{}' in struct '{}'", e.member, object->name()));
    return model_.types().error();
  }
  if (object->isScalar() || object->isVector()) {
    static constexpr std::string_view kSets[] = {"xyzw", "rgba", "stpq"};
    const uint32_t size = object->rows;
    bool valid = !e.member.empty() && e.member.size() <= 4;
    bool inRange = true;
    if (valid) {
      valid = false;
      for (std::string_view set : kSets) {
        if (!isSwizzleSet(e.member, set)) continue;
        valid = true;
        for (char c : e.member) inRange &= set.find(c) < size;
      }
    }
    if (!valid || !inRange) {
      diags_.report(DiagCode::E3008, e.memberRange,
                    !valid ? fmt::format("invalid swizzle '{}' on a value of type '{}'", e.member, object->name())
                           : fmt::format("swizzle '{}' selects a component beyond the {} of '{}'", e.member,
                                         size == 1 ? std::string("one") : std::to_string(size), object->name()));
      return model_.types().error();
    }
    std::string sorted = e.member;
    std::sort(sorted.begin(), sorted.end());
    const bool repeats = std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end();
    info.ref = RefKind::Swizzle;
    info.isLValue = objectInfo.isLValue && !repeats;
    return model_.types().vector(object->scalar, static_cast<uint32_t>(e.member.size()));
  }
  diags_.report(DiagCode::E3008, e.memberRange,
                fmt::format("member access '.{}' on a value of type '{}'", e.member, object->name()));
  return model_.types().error();
}

const Type* BodyChecker::checkIndex(const ast::IndexExpr& e, ExprInfo& info) {
  const Type* object = check(*e.object);
  const Type* index = check(*e.index);
  if (object->isError() || index->isError()) return model_.types().error();
  if (!index->isScalar() || (index->scalar != ScalarKind::Int && index->scalar != ScalarKind::Uint)) {
    diags_.report(DiagCode::E3009, e.index->range,
                  fmt::format("array index must be 'int' or 'uint', not '{}'", index->name()));
    return model_.types().error();
  }
  const Type* element = nullptr;
  uint32_t bound = 0;
  if (object->isArray()) {
    element = object->element;
    bound = object->arraySize;
  } else if (object->isVector()) {
    element = model_.types().scalar(object->scalar);
    bound = object->rows;
  } else if (object->isMatrix()) {
    element = model_.types().vector(ScalarKind::Float, object->rows);
    bound = object->columns;
  } else {
    diags_.report(DiagCode::E3009, e.object->range,
                  fmt::format("a value of type '{}' cannot be indexed", object->name()));
    return model_.types().error();
  }
  if (const auto& constant = model_.info(*e.index).constant; constant && (*constant < 0 || *constant >= bound)) {
    diags_.report(
        DiagCode::E3009, e.index->range,
        fmt::format("index {} is out of bounds for '{}' (valid: 0 to {})", *constant, object->name(), bound - 1));
    return model_.types().error();
  }
  info.isLValue = model_.info(*e.object).isLValue;
  return element;
}

bool BodyChecker::requireLValue(const ast::Expr& target, SourceRange opRange, std::string_view action) {
  const ExprInfo& info = model_.info(target);
  if (info.isLValue) return true;
  // Walk to the root name to explain why it is read-only.
  const ast::Expr* root = &target;
  while (true) {
    if (const auto* m = ast::dyn_cast<ast::MemberExpr>(root))
      root = m->object.get();
    else if (const auto* i = ast::dyn_cast<ast::IndexExpr>(root))
      root = i->object.get();
    else
      break;
  }
  std::string reason = "it is not a variable";
  if (const auto* name = ast::dyn_cast<ast::NameExpr>(root)) {
    const ExprInfo& rootInfo = model_.info(*root);
    if (rootInfo.ref == RefKind::Component) {
      reason = fmt::format("'{}' is a component, and components are immutable values", name->name);
    } else if (rootInfo.ref == RefKind::Local || rootInfo.ref == RefKind::Parameter) {
      reason = rootInfo.isLValue ? "a swizzle with repeated components cannot be written"
                                 : fmt::format("'{}' is declared 'const'", name->name);
    }
  }
  diags_.report(DiagCode::E3012, target.range, fmt::format("cannot {} this expression: {}", action, reason))
      .note(opRange, "the modification is here");
  return false;
}

std::optional<uint32_t> BodyChecker::arraySize(const ast::Expr& size) {
  const Type* type = check(size);
  if (type->isError()) return std::nullopt;
  const auto& constant = model_.info(size).constant;
  if (!type->isIntegerShape() || !type->isScalar() || !constant) {
    diags_.report(DiagCode::E3015, size.range, "array size must be a constant integer expression");
    return std::nullopt;
  }
  if (*constant <= 0 || *constant > (1 << 20)) {
    diags_.report(DiagCode::E3015, size.range,
                  fmt::format("array size must be between 1 and 1048576, not {}", *constant));
    return std::nullopt;
  }
  return static_cast<uint32_t>(*constant);
}

void BodyChecker::foldConstant(const ast::Expr& expr, ExprInfo& info) {
  if (!info.type->isIntegerShape() || !info.type->isScalar()) return;
  auto value = [&](const ast::ExprPtr& e) { return model_.info(*e).constant; };
  // Folding is done in 64 bits and abandoned when a result would leave the
  // 32-bit range, so constants never wrap silently.
  std::optional<int64_t> result;
  switch (expr.kind) {
    case ast::ExprKind::IntLiteral: result = static_cast<int64_t>(ast::cast<ast::IntLiteral>(expr).value); break;
    case ast::ExprKind::Name:
      if (info.ref == RefKind::Local && !info.isLValue) result = info.constant;
      break;
    case ast::ExprKind::Unary: {
      const auto& u = ast::cast<ast::UnaryExpr>(expr);
      const auto v = value(u.operand);
      if (!v) break;
      if (u.op == ast::UnaryOp::Negate)
        result = -*v;
      else if (u.op == ast::UnaryOp::Plus)
        result = *v;
      break;
    }
    case ast::ExprKind::Binary: {
      const auto& b = ast::cast<ast::BinaryExpr>(expr);
      const auto l = value(b.lhs);
      const auto r = value(b.rhs);
      if (!l || !r) break;
      switch (b.op) {
        case ast::BinaryOp::Add: result = *l + *r; break;
        case ast::BinaryOp::Sub: result = *l - *r; break;
        case ast::BinaryOp::Mul: result = *l * *r; break;
        case ast::BinaryOp::Div:
          if (*r != 0) result = *l / *r;
          break;
        case ast::BinaryOp::Mod:
          if (*r != 0) result = *l % *r;
          break;
        default: break;
      }
      break;
    }
    default: break;
  }
  if (result && *result >= INT32_MIN && *result <= UINT32_MAX) info.constant = result;
}

}  // namespace spire::sem
