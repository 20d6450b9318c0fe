// Statement checking, scopes and type resolution for BodyChecker.
#include <fmt/format.h>

#include "sema/attribute_catalog.h"
#include "sema/body_checker.h"
#include "support/spelling.h"

namespace spire::sem {

BodyChecker::BodyChecker(Model& model, DiagnosticList& diags, const FunctionTable& functions,
                         ComponentResolver* components)
    : model_(model), diags_(diags), functions_(functions), components_(components) {
  pushScope();
}

const Type* BodyChecker::resolveType(const ast::TypeSyntax& syntax, const std::vector<ast::ExprPtr>& declaratorDims) {
  const Type* type = model_.types().lookupBuiltin(syntax.name);
  if (!type) {
    if (auto it = model_.structs.find(syntax.name); it != model_.structs.end()) type = it->second;
  }
  if (!type) {
    std::vector<std::string_view> names = model_.types().builtinNames();
    for (const auto& [name, t] : model_.structs) names.push_back(name);
    const auto suggestion = closestSpelling(syntax.name, names);
    diags_.report(DiagCode::E3002, syntax.nameRange,
                  suggestion ? fmt::format("unknown type '{}'; did you mean '{}'?", syntax.name, *suggestion)
                             : fmt::format("unknown type '{}'", syntax.name));
    return model_.types().error();
  }
  // `float[2] a[3]` is an array of 3 arrays of 2 floats: declarator
  // dimensions are outermost, so apply the type's dimensions first.
  std::vector<const ast::Expr*> dims;
  for (const ast::ExprPtr& d : declaratorDims) dims.push_back(d.get());
  for (const ast::ExprPtr& d : syntax.arraySizes) dims.push_back(d.get());
  for (auto it = dims.rbegin(); it != dims.rend(); ++it) {
    const auto size = arraySize(**it);
    if (!size) return model_.types().error();
    if (type->isVoid()) {
      diags_.report(DiagCode::E3015, syntax.range, "arrays of 'void' are not allowed");
      return model_.types().error();
    }
    type = model_.types().array(type, *size);
  }
  noteType(type);
  return type;
}

const BodyChecker::Local* BodyChecker::findLocal(std::string_view name) const {
  for (auto scope = scopes_.rbegin(); scope != scopes_.rend(); ++scope) {
    if (auto it = scope->find(name); it != scope->end()) return &it->second;
  }
  return nullptr;
}

void BodyChecker::declareLocal(std::string_view name, Local local) {
  auto& scope = scopes_.back();
  if (auto it = scope.find(name); it != scope.end()) {
    diags_.report(DiagCode::E3003, local.declRange, fmt::format("redefinition of '{}'", name))
        .note(it->second.declRange, "previous definition is here");
    return;
  }
  scope.emplace(std::string(name), local);
}

std::vector<std::string_view> BodyChecker::visibleValueNames() const {
  std::vector<std::string_view> names;
  for (const auto& scope : scopes_) {
    for (const auto& [name, local] : scope) names.push_back(name);
  }
  if (components_) components_->appendNames(names);
  return names;
}

void BodyChecker::declareParameter(const ast::Param& param, const Type* type) {
  noteType(type);
  if (param.name.empty()) return;
  Local local;
  local.type = type;
  local.isConst = param.isConst;
  local.declRange = param.nameRange;
  local.param = &param;
  declareLocal(param.name, local);
}

void BodyChecker::checkConversion(const ast::Expr& value, const Type* target, std::string_view what) {
  const Type* type = check(value);
  if (type->isError() || target->isError()) return;
  if (!isImplicitlyConvertible(type, target)) {
    diags_.report(
        DiagCode::E3004, value.range,
        fmt::format("cannot initialize {} of type '{}' with a value of type '{}'", what, target->name(), type->name()));
  }
}

void BodyChecker::checkCondition(const ast::Expr& condition, std::string_view construct) {
  const Type* type = check(condition);
  if (!type->isError() && type != model_.types().boolType()) {
    diags_.report(DiagCode::E3011, condition.range,
                  fmt::format("the condition of {} must be a 'bool', not '{}'", construct, type->name()));
  }
}

void BodyChecker::checkBody(const ast::BlockStmt& body, const Type* returnType, std::string_view owner) {
  returnType_ = returnType;
  owner_ = std::string(owner);
  checkStmt(body);
  if (!returnType->isVoid() && !returnType->isError() && !alwaysReturns(body)) {
    diags_.report(DiagCode::E3014, SourceRange{body.range.file, body.range.end - 1, body.range.end},
                  fmt::format("{} does not return a value on every path", owner));
  }
}

void BodyChecker::checkVarDecl(const ast::VarDeclStmt& decl) {
  for (const ast::VarDeclarator& d : decl.declarators) {
    const Type* type = resolveType(decl.type, d.arraySizes);
    if (type->isVoid()) {
      diags_.report(DiagCode::E3004, decl.type.range, fmt::format("variable '{}' cannot have type 'void'", d.name));
      type = model_.types().error();
    } else if (type->containsOpaque()) {
      diags_.report(DiagCode::E3004, decl.type.range,
                    fmt::format("variable '{}' cannot have opaque type '{}'; read the sampler component directly",
                                d.name, type->name()));
      type = model_.types().error();
    }
    Local local;
    local.type = type;
    local.isConst = decl.isConst;
    local.declRange = d.nameRange;
    local.declarator = &d;
    if (d.init) {
      checkConversion(*d.init, type, fmt::format("variable '{}'", d.name));
      if (decl.isConst) local.constant = model_.info(*d.init).constant;
    } else if (decl.isConst) {
      diags_.report(DiagCode::E3004, d.nameRange, fmt::format("'const' variable '{}' needs an initializer", d.name));
    }
    model_.localTypes[&d] = type;
    // Declared after its initializer is checked: `float x = x;` reads an outer x.
    declareLocal(d.name, local);
  }
}

void BodyChecker::checkStmt(const ast::Stmt& stmt) {
  checkAttributes(stmt.attributes, AttributeSite::Statement, diags_);
  switch (stmt.kind) {
    case ast::StmtKind::Block: checkBlock(ast::cast<ast::BlockStmt>(stmt)); return;
    case ast::StmtKind::VarDecl: checkVarDecl(ast::cast<ast::VarDeclStmt>(stmt)); return;
    case ast::StmtKind::Expr: check(*ast::cast<ast::ExprStmt>(stmt).expr); return;
    case ast::StmtKind::If: checkIf(ast::cast<ast::IfStmt>(stmt)); return;
    case ast::StmtKind::For: checkFor(ast::cast<ast::ForStmt>(stmt)); return;
    case ast::StmtKind::While: checkWhile(ast::cast<ast::WhileStmt>(stmt)); return;
    case ast::StmtKind::DoWhile: checkDoWhile(ast::cast<ast::DoWhileStmt>(stmt)); return;
    case ast::StmtKind::Break:
    case ast::StmtKind::Continue:
      if (loopDepth_ == 0) {
        diags_.report(DiagCode::E3013, stmt.range,
                      fmt::format("'{}' outside of a loop", stmt.kind == ast::StmtKind::Break ? "break" : "continue"));
      }
      return;
    case ast::StmtKind::Return: checkReturn(ast::cast<ast::ReturnStmt>(stmt)); return;
    case ast::StmtKind::Discard:
    case ast::StmtKind::Empty: return;
  }
}

void BodyChecker::checkBlock(const ast::BlockStmt& block) {
  pushScope();
  for (const ast::StmtPtr& s : block.statements) {
    if (diags_.limitReached()) break;
    checkStmt(*s);
  }
  popScope();
}

void BodyChecker::checkIf(const ast::IfStmt& s) {
  checkCondition(*s.condition, "'if'");
  pushScope();
  checkStmt(*s.thenBranch);
  popScope();
  if (s.elseBranch) {
    pushScope();
    checkStmt(*s.elseBranch);
    popScope();
  }
}

void BodyChecker::checkFor(const ast::ForStmt& s) {
  pushScope();
  if (s.init) checkStmt(*s.init);
  if (s.condition) checkCondition(*s.condition, "'for'");
  if (s.step) check(*s.step);
  ++loopDepth_;
  checkStmt(*s.body);
  --loopDepth_;
  popScope();
}

void BodyChecker::checkWhile(const ast::WhileStmt& s) {
  checkCondition(*s.condition, "'while'");
  ++loopDepth_;
  pushScope();
  checkStmt(*s.body);
  popScope();
  --loopDepth_;
}

void BodyChecker::checkDoWhile(const ast::DoWhileStmt& s) {
  ++loopDepth_;
  pushScope();
  checkStmt(*s.body);
  popScope();
  --loopDepth_;
  checkCondition(*s.condition, "'do-while'");
}

void BodyChecker::checkReturn(const ast::ReturnStmt& s) {
  if (!returnType_) return;
  if (!s.value) {
    if (!returnType_->isVoid() && !returnType_->isError()) {
      diags_.report(DiagCode::E3004, s.range,
                    fmt::format("{} must return a value of type '{}'", owner_, returnType_->name()));
    }
    return;
  }
  const Type* type = check(*s.value);
  if (type->isError() || returnType_->isError()) return;
  if (returnType_->isVoid()) {
    diags_.report(DiagCode::E3004, s.value->range, fmt::format("{} returns 'void' but a value is returned", owner_));
  } else if (!isImplicitlyConvertible(type, returnType_)) {
    diags_.report(DiagCode::E3004, s.value->range,
                  fmt::format("cannot return a value of type '{}' from {} of type '{}'", type->name(), owner_,
                              returnType_->name()));
  }
}

bool BodyChecker::alwaysReturns(const ast::Stmt& stmt) const {
  switch (stmt.kind) {
    case ast::StmtKind::Return:
    case ast::StmtKind::Discard: return true;
    case ast::StmtKind::Block:
      for (const ast::StmtPtr& s : ast::cast<ast::BlockStmt>(stmt).statements) {
        if (alwaysReturns(*s)) return true;
      }
      return false;
    case ast::StmtKind::If: {
      const auto& s = ast::cast<ast::IfStmt>(stmt);
      return s.elseBranch && alwaysReturns(*s.thenBranch) && alwaysReturns(*s.elseBranch);
    }
    case ast::StmtKind::DoWhile: return alwaysReturns(*ast::cast<ast::DoWhileStmt>(stmt).body);
    default: return false;
  }
}

}  // namespace spire::sem
