// Type checking of expressions and statements: component initializers and
// bodies, function bodies, strategy arguments and array sizes. Results go to
// the model's side tables; errors to the diagnostic list.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "sema/semantic_model.h"
#include "support/diagnostic.h"
#include "syntax/ast.h"

namespace spire::sem {

// User functions by name, each name with its overloads.
using FunctionTable = std::map<std::string, std::vector<Function*>, std::less<>>;

// Resolves names that are not locals: the components visible to the code
// being checked. Implemented by the shader and pipeline analyses.
class ComponentResolver {
 public:
  virtual ~ComponentResolver() = default;
  // The component's type, recording the use as a dependency; null if unknown.
  virtual const Type* useComponent(std::string_view name, SourceRange use) = 0;
  // Where `name` is declared, for "declared here" notes.
  virtual SourceRange declarationOf(std::string_view name) const = 0;
  virtual void appendNames(std::vector<std::string_view>& out) const = 0;
};

class BodyChecker {
 public:
  BodyChecker(Model& model, DiagnosticList& diags, const FunctionTable& functions, ComponentResolver* components);

  // The expression's type, or the error type (never null). Errors are
  // reported once; the error type suppresses follow-on errors.
  const Type* check(const ast::Expr& expr);
  // Checks `value` and that it implicitly converts to `target`. `what`
  // describes the destination: "component 'albedo'", "variable 'x'".
  void checkConversion(const ast::Expr& value, const Type* target, std::string_view what);

  // A component body or function body: `returnType` is what `return` must
  // produce; `owner` names it in messages.
  void checkBody(const ast::BlockStmt& body, const Type* returnType, std::string_view owner);
  void declareParameter(const ast::Param& param, const Type* type);

  // A written type with array dimensions from the type and the declarator.
  const Type* resolveType(const ast::TypeSyntax& syntax, const std::vector<ast::ExprPtr>& declaratorDims = {});

  const std::vector<const Function*>& calledFunctions() const { return calledFunctions_; }
  // The struct types the checked code declares, constructs or computes with
  // (arrays stripped), in first-use order: the structs its GLSL names.
  const std::vector<const Type*>& usedStructs() const { return usedStructs_; }
  // Adds `type`'s struct, if it is one, to usedStructs().
  void noteType(const Type* type);

 private:
  struct Local {
    const Type* type = nullptr;
    bool isConst = false;
    SourceRange declRange;
    const ast::VarDeclarator* declarator = nullptr;
    const ast::Param* param = nullptr;
    std::optional<int64_t> constant;
  };

  // Expressions (body_checker_expr.cpp)
  const Type* checkUncached(const ast::Expr& expr, ExprInfo& info);
  // Stores what check() found about `expr` in the model.
  const Type* record(const ast::Expr& expr, ExprInfo& info, const Type* type);
  const Type* checkName(const ast::NameExpr& e, ExprInfo& info);
  const Type* checkUnary(const ast::UnaryExpr& e, ExprInfo& info);
  const Type* checkBinaryChain(const ast::BinaryExpr& top);
  // One node of a chain whose left operand was checked as `lhs`.
  const Type* checkBinary(const ast::BinaryExpr& e, const Type* lhs);
  const Type* checkAssign(const ast::AssignExpr& e);
  const Type* checkTernary(const ast::TernaryExpr& e);
  const Type* checkCall(const ast::CallExpr& e, ExprInfo& info);
  const Type* checkConstructorCall(const ast::CallExpr& e, const Type* target, const std::vector<const Type*>& args);
  const Type* checkFunctionCall(const ast::CallExpr& e, ExprInfo& info, const std::vector<const Type*>& args);
  // A call of a name no function or built-in has: not a function, or a
  // misspelling. Returns the error type.
  const Type* reportUnknownFunction(const ast::CallExpr& e);
  const Type* checkMember(const ast::MemberExpr& e, ExprInfo& info);
  const Type* checkIndex(const ast::IndexExpr& e, ExprInfo& info);
  bool requireLValue(const ast::Expr& target, SourceRange opRange, std::string_view action);
  void foldConstant(const ast::Expr& expr, ExprInfo& info);
  std::optional<uint32_t> arraySize(const ast::Expr& size);

  // Statements (body_checker_stmt.cpp)
  void checkStmt(const ast::Stmt& stmt);
  void checkBlock(const ast::BlockStmt& block);
  void checkIf(const ast::IfStmt& s);
  void checkFor(const ast::ForStmt& s);
  void checkWhile(const ast::WhileStmt& s);
  void checkDoWhile(const ast::DoWhileStmt& s);
  void checkReturn(const ast::ReturnStmt& s);
  void checkVarDecl(const ast::VarDeclStmt& decl);
  void checkCondition(const ast::Expr& condition, std::string_view construct);
  bool alwaysReturns(const ast::Stmt& stmt) const;

  // Scopes
  void pushScope() { scopes_.emplace_back(); }
  void popScope() { scopes_.pop_back(); }
  const Local* findLocal(std::string_view name) const;
  void declareLocal(std::string_view name, Local local);
  std::vector<std::string_view> visibleValueNames() const;

  Model& model_;
  DiagnosticList& diags_;
  const FunctionTable& functions_;
  ComponentResolver* components_;
  std::vector<std::map<std::string, Local, std::less<>>> scopes_;
  std::vector<const Function*> calledFunctions_;
  std::vector<const Type*> usedStructs_;
  const Type* returnType_ = nullptr;
  std::string owner_;
  uint32_t loopDepth_ = 0;
};

}  // namespace spire::sem
