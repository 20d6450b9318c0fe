// The Spire abstract syntax tree. The parser produces it; later stages read it
// through const references and keep their own results in side tables keyed by
// node ids (see sema/semantic_model.h), so the tree never changes after parsing.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "support/source_manager.h"

namespace spire::ast {

// ---------------------------------------------------------------------------
// Expressions

enum class ExprKind : uint8_t {
  BoolLiteral,
  IntLiteral,
  FloatLiteral,
  Name,
  Unary,
  Binary,
  Assign,
  Ternary,
  Call,
  Member,
  Index
};

struct Expr {
  ExprKind kind;
  SourceRange range;
  // Dense per-program index for side tables; assigned by the parser.
  uint32_t id = 0;

  virtual ~Expr() = default;

 protected:
  Expr(ExprKind k, SourceRange r) : kind(k), range(r) {}
};
using ExprPtr = std::unique_ptr<Expr>;

// LLVM-style checked casts on the kind tag.
template <typename T>
const T* dyn_cast(const Expr* e) {
  return e && e->kind == T::kKind ? static_cast<const T*>(e) : nullptr;
}
template <typename T>
const T& cast(const Expr& e) {
  return static_cast<const T&>(e);
}

struct BoolLiteral final : Expr {
  static constexpr ExprKind kKind = ExprKind::BoolLiteral;
  bool value;
  BoolLiteral(SourceRange r, bool v) : Expr(kKind, r), value(v) {}
};

struct IntLiteral final : Expr {
  static constexpr ExprKind kKind = ExprKind::IntLiteral;
  uint64_t value;
  bool isUnsigned;       // written with a `u`/`U` suffix
  std::string spelling;  // as written, for faithful printing
  IntLiteral(SourceRange r, uint64_t v, bool u, std::string s)
      : Expr(kKind, r), value(v), isUnsigned(u), spelling(std::move(s)) {}
};

struct FloatLiteral final : Expr {
  static constexpr ExprKind kKind = ExprKind::FloatLiteral;
  double value;
  std::string spelling;
  FloatLiteral(SourceRange r, double v, std::string s) : Expr(kKind, r), value(v), spelling(std::move(s)) {}
};

struct NameExpr final : Expr {
  static constexpr ExprKind kKind = ExprKind::Name;
  std::string name;
  NameExpr(SourceRange r, std::string n) : Expr(kKind, r), name(std::move(n)) {}
};

enum class UnaryOp : uint8_t {
  Plus,
  Negate,
  LogicalNot,
  BitNot,
  PreIncrement,
  PreDecrement,
  PostIncrement,
  PostDecrement
};

struct UnaryExpr final : Expr {
  static constexpr ExprKind kKind = ExprKind::Unary;
  UnaryOp op;
  ExprPtr operand;
  SourceRange opRange;
  UnaryExpr(SourceRange r, UnaryOp o, ExprPtr e, SourceRange opR)
      : Expr(kKind, r), op(o), operand(std::move(e)), opRange(opR) {}
};

// GLSL binary operators, including the sequence (comma) operator.
enum class BinaryOp : uint8_t {
  Mul,
  Div,
  Mod,
  Add,
  Sub,
  Shl,
  Shr,
  Less,
  Greater,
  LessEqual,
  GreaterEqual,
  Equal,
  NotEqual,
  BitAnd,
  BitXor,
  BitOr,
  LogicalAnd,
  LogicalXor,
  LogicalOr,
  Comma,
};

struct BinaryExpr final : Expr {
  static constexpr ExprKind kKind = ExprKind::Binary;
  BinaryOp op;
  ExprPtr lhs, rhs;
  SourceRange opRange;
  BinaryExpr(SourceRange r, BinaryOp o, ExprPtr l, ExprPtr rh, SourceRange opR)
      : Expr(kKind, r), op(o), lhs(std::move(l)), rhs(std::move(rh)), opRange(opR) {}
  ~BinaryExpr() override;
};

// A chain of left-associative operators such as `a + b - c * d + ...` is a
// left spine of binary nodes as deep as the chain is long, and generated
// shaders write chains of thousands of terms. Whatever walks the tree walks
// such a spine in a loop, so that its recursion only goes as deep as the
// code is really nested: this returns the spine's nodes, innermost first.
// The innermost node's `lhs` is the chain's first operand (not binary);
// each following node's `lhs` is the node before it.
inline std::vector<const BinaryExpr*> leftSpine(const BinaryExpr& top) {
  std::vector<const BinaryExpr*> spine;
  for (const Expr* e = &top; e && e->kind == ExprKind::Binary; e = static_cast<const BinaryExpr*>(e)->lhs.get()) {
    spine.push_back(static_cast<const BinaryExpr*>(e));
  }
  return {spine.rbegin(), spine.rend()};
}

// Detaches the left spine node by node, so that each node is destroyed with
// its `lhs` already empty and the destructors never recurse along a chain.
inline BinaryExpr::~BinaryExpr() {
  ExprPtr next = std::move(lhs);
  while (next && next->kind == ExprKind::Binary) {
    ExprPtr after = std::move(static_cast<BinaryExpr&>(*next).lhs);
    next = std::move(after);
  }
}

// `Assign` is plain `=`; the others are compound assignments.
enum class AssignOp : uint8_t { Assign, Mul, Div, Mod, Add, Sub, Shl, Shr, BitAnd, BitXor, BitOr };

struct AssignExpr final : Expr {
  static constexpr ExprKind kKind = ExprKind::Assign;
  AssignOp op;
  ExprPtr target, value;
  SourceRange opRange;
  AssignExpr(SourceRange r, AssignOp o, ExprPtr t, ExprPtr v, SourceRange opR)
      : Expr(kKind, r), op(o), target(std::move(t)), value(std::move(v)), opRange(opR) {}
};

struct TernaryExpr final : Expr {
  static constexpr ExprKind kKind = ExprKind::Ternary;
  ExprPtr condition, thenValue, elseValue;
  TernaryExpr(SourceRange r, ExprPtr c, ExprPtr t, ExprPtr e)
      : Expr(kKind, r), condition(std::move(c)), thenValue(std::move(t)), elseValue(std::move(e)) {}
};

// A type as written: a name (`vec3`, `float`, a struct) with optional array
// dimensions (`float[4]`).
struct TypeSyntax {
  SourceRange range;
  std::string name;
  SourceRange nameRange;
  std::vector<ExprPtr> arraySizes;  // outermost first
};

// A call of a function, a built-in or a constructor. Constructors are calls
// whose callee names a type (`vec4(...)`, `float[3](...)`, `MyStruct(...)`);
// sema decides which it is.
struct CallExpr final : Expr {
  static constexpr ExprKind kKind = ExprKind::Call;
  TypeSyntax callee;
  std::vector<ExprPtr> args;
  CallExpr(SourceRange r, TypeSyntax c, std::vector<ExprPtr> a)
      : Expr(kKind, r), callee(std::move(c)), args(std::move(a)) {}
};

// `object.member`: a struct field, a swizzle, or `.length()` via CallExpr on a
// member is not supported (arrays are constant-size; use the literal size).
struct MemberExpr final : Expr {
  static constexpr ExprKind kKind = ExprKind::Member;
  ExprPtr object;
  std::string member;
  SourceRange memberRange;
  MemberExpr(SourceRange r, ExprPtr o, std::string m, SourceRange mr)
      : Expr(kKind, r), object(std::move(o)), member(std::move(m)), memberRange(mr) {}
};

struct IndexExpr final : Expr {
  static constexpr ExprKind kKind = ExprKind::Index;
  ExprPtr object, index;
  IndexExpr(SourceRange r, ExprPtr o, ExprPtr i) : Expr(kKind, r), object(std::move(o)), index(std::move(i)) {}
};

// ---------------------------------------------------------------------------
// Attributes

// `[Name]` or `[Name: "value"]`.
struct Attribute {
  SourceRange range;
  std::string name;
  std::optional<std::string> value;  // unescaped string contents
  SourceRange valueRange;
};

// Whether `attributes` holds one named `name` (`[Immutable]`, `[Transition]`).
inline bool hasAttribute(const std::vector<Attribute>& attributes, std::string_view name) {
  for (const Attribute& a : attributes) {
    if (a.name == name) return true;
  }
  return false;
}

// ---------------------------------------------------------------------------
// Statements

enum class StmtKind : uint8_t {
  Block,
  VarDecl,
  Expr,
  If,
  For,
  While,
  DoWhile,
  Break,
  Continue,
  Return,
  Discard,
  Empty
};

struct Stmt {
  StmtKind kind;
  SourceRange range;  // the statement, without its attributes
  // `[Immutable] { ... }`: attributes written before the statement.
  std::vector<Attribute> attributes;
  virtual ~Stmt() = default;

 protected:
  Stmt(StmtKind k, SourceRange r) : kind(k), range(r) {}
};
using StmtPtr = std::unique_ptr<Stmt>;

template <typename T>
const T* dyn_cast(const Stmt* s) {
  return s && s->kind == T::kKind ? static_cast<const T*>(s) : nullptr;
}
template <typename T>
const T& cast(const Stmt& s) {
  return static_cast<const T&>(s);
}

struct BlockStmt final : Stmt {
  static constexpr StmtKind kKind = StmtKind::Block;
  std::vector<StmtPtr> statements;
  explicit BlockStmt(SourceRange r) : Stmt(kKind, r) {}
};

// One name in a local declaration: `x`, `a[3] = ...`.
struct VarDeclarator {
  std::string name;
  SourceRange nameRange;
  std::vector<ExprPtr> arraySizes;
  ExprPtr init;  // may be null
};

// `[const] T a = 1, b[2];`
struct VarDeclStmt final : Stmt {
  static constexpr StmtKind kKind = StmtKind::VarDecl;
  bool isConst = false;
  TypeSyntax type;
  std::vector<VarDeclarator> declarators;
  explicit VarDeclStmt(SourceRange r) : Stmt(kKind, r) {}
};

struct ExprStmt final : Stmt {
  static constexpr StmtKind kKind = StmtKind::Expr;
  ExprPtr expr;
  ExprStmt(SourceRange r, ExprPtr e) : Stmt(kKind, r), expr(std::move(e)) {}
};

struct IfStmt final : Stmt {
  static constexpr StmtKind kKind = StmtKind::If;
  ExprPtr condition;
  StmtPtr thenBranch, elseBranch;  // elseBranch may be null
  explicit IfStmt(SourceRange r) : Stmt(kKind, r) {}
};

struct ForStmt final : Stmt {
  static constexpr StmtKind kKind = StmtKind::For;
  StmtPtr init;       // VarDeclStmt, ExprStmt or null
  ExprPtr condition;  // may be null
  ExprPtr step;       // may be null
  StmtPtr body;
  explicit ForStmt(SourceRange r) : Stmt(kKind, r) {}
};

struct WhileStmt final : Stmt {
  static constexpr StmtKind kKind = StmtKind::While;
  ExprPtr condition;
  StmtPtr body;
  explicit WhileStmt(SourceRange r) : Stmt(kKind, r) {}
};

struct DoWhileStmt final : Stmt {
  static constexpr StmtKind kKind = StmtKind::DoWhile;
  StmtPtr body;
  ExprPtr condition;
  explicit DoWhileStmt(SourceRange r) : Stmt(kKind, r) {}
};

struct BreakStmt final : Stmt {
  static constexpr StmtKind kKind = StmtKind::Break;
  explicit BreakStmt(SourceRange r) : Stmt(kKind, r) {}
};

struct ContinueStmt final : Stmt {
  static constexpr StmtKind kKind = StmtKind::Continue;
  explicit ContinueStmt(SourceRange r) : Stmt(kKind, r) {}
};

struct ReturnStmt final : Stmt {
  static constexpr StmtKind kKind = StmtKind::Return;
  ExprPtr value;  // may be null
  ReturnStmt(SourceRange r, ExprPtr v) : Stmt(kKind, r), value(std::move(v)) {}
};

struct DiscardStmt final : Stmt {
  static constexpr StmtKind kKind = StmtKind::Discard;
  explicit DiscardStmt(SourceRange r) : Stmt(kKind, r) {}
};

struct EmptyStmt final : Stmt {
  static constexpr StmtKind kKind = StmtKind::Empty;
  explicit EmptyStmt(SourceRange r) : Stmt(kKind, r) {}
};

// ---------------------------------------------------------------------------
// Declarations

// A strategy use: `textureImport(vert_uv)`, `standardExport`. Arguments are
// expressions evaluated in the world that runs the generated code.
struct StrategyRef {
  SourceRange range;
  std::string name;
  SourceRange nameRange;
  std::vector<ExprPtr> args;
};

// `abstract world W;` or `world W : "GLSL" export strategy(args);`
struct WorldDecl {
  SourceRange range;
  std::vector<Attribute> attributes;
  bool isAbstract = false;
  std::string name;
  SourceRange nameRange;
  std::optional<std::string> language;
  SourceRange languageRange;
  std::optional<StrategyRef> exportStrategy;
};

// `import A->B using strategy(args);`
struct ImportDecl {
  SourceRange range;
  std::vector<Attribute> attributes;
  std::string from;
  SourceRange fromRange;
  std::string to;
  SourceRange toRange;
  StrategyRef strategy;
};

// One component: `[attrs] [abstract] [export] [@W] T name[:variation]`
// followed by `= expr;`, a `{ ... }` body or `;`. The parser splits
// `@W sampler2D a, b;` into one ComponentDecl per name.
struct ComponentDecl {
  SourceRange range;
  std::vector<Attribute> attributes;
  bool isAbstract = false;
  bool isExport = false;
  std::optional<std::string> world;
  SourceRange worldRange;
  TypeSyntax type;
  std::string name;
  SourceRange nameRange;
  std::string variation;  // empty when none
  SourceRange variationRange;
  ExprPtr init;                     // `= expr;`
  std::unique_ptr<BlockStmt> body;  // `{ ... }`; at most one of init/body

  bool hasDefinition() const { return init || body; }
};

enum class DeclKind : uint8_t { Using, Struct, Function, Pipeline, Shader, Group };

struct Decl {
  DeclKind kind;
  SourceRange range;
  virtual ~Decl() = default;

 protected:
  Decl(DeclKind k, SourceRange r) : kind(k), range(r) {}
};
using DeclPtr = std::unique_ptr<Decl>;

template <typename T>
const T* dyn_cast(const Decl* d) {
  return d && d->kind == T::kKind ? static_cast<const T*>(d) : nullptr;
}
template <typename T>
const T& cast(const Decl& d) {
  return static_cast<const T&>(d);
}

// `using "file.spire";`
struct UsingDecl final : Decl {
  static constexpr DeclKind kKind = DeclKind::Using;
  std::string path;
  SourceRange pathRange;
  explicit UsingDecl(SourceRange r) : Decl(kKind, r) {}
};

struct StructField {
  TypeSyntax type;
  std::string name;
  SourceRange nameRange;
  std::vector<ExprPtr> arraySizes;
};

struct StructDecl final : Decl {
  static constexpr DeclKind kKind = DeclKind::Struct;
  std::string name;
  SourceRange nameRange;
  std::vector<StructField> fields;
  explicit StructDecl(SourceRange r) : Decl(kKind, r) {}
};

enum class ParamDirection : uint8_t { In, Out, InOut };

struct Param {
  SourceRange range;
  bool isConst = false;
  ParamDirection direction = ParamDirection::In;
  bool explicitIn = false;  // written as `in`, kept for faithful printing
  TypeSyntax type;
  std::string name;  // may be empty in a prototype
  SourceRange nameRange;
  std::vector<ExprPtr> arraySizes;
};

struct FunctionDecl final : Decl {
  static constexpr DeclKind kKind = DeclKind::Function;
  TypeSyntax returnType;
  std::string name;
  SourceRange nameRange;
  std::vector<Param> params;
  std::unique_ptr<BlockStmt> body;  // null for a prototype
  explicit FunctionDecl(SourceRange r) : Decl(kKind, r) {}
};

struct PipelineDecl final : Decl {
  static constexpr DeclKind kKind = DeclKind::Pipeline;
  std::string name;
  SourceRange nameRange;
  std::vector<WorldDecl> worlds;
  std::vector<ImportDecl> imports;
  std::vector<ComponentDecl> components;
  explicit PipelineDecl(SourceRange r) : Decl(kKind, r) {}
};

struct NameRef {
  std::string name;
  SourceRange range;
};

// `shader Name using Pipeline { ... }` or
// `shader Name : Base [finalizes W1, W2] { ... }`.
struct ShaderDecl final : Decl {
  static constexpr DeclKind kKind = DeclKind::Shader;
  std::string name;
  SourceRange nameRange;
  std::optional<NameRef> pipeline;
  std::optional<NameRef> base;  // a shader or a group
  std::vector<NameRef> finalizes;
  std::vector<ComponentDecl> components;
  explicit ShaderDecl(SourceRange r) : Decl(kKind, r) {}
};

struct GroupEntry {
  SourceRange range;
  bool isOptional = false;
  NameRef shader;
};

// `group Name { shader A; optional shader B; }`
struct GroupDecl final : Decl {
  static constexpr DeclKind kKind = DeclKind::Group;
  std::string name;
  SourceRange nameRange;
  std::vector<GroupEntry> entries;
  explicit GroupDecl(SourceRange r) : Decl(kKind, r) {}
};

// One parsed source file.
struct Module {
  FileId file = kNoFile;
  std::vector<DeclPtr> decls;
};

// Every module of one compilation, in load order (a file's includes are
// loaded before the rest of it is analysed; see syntax/module_loader.h).
struct Program {
  std::vector<std::unique_ptr<Module>> modules;
  uint32_t exprCount = 0;  // ids handed out so far
};

}  // namespace spire::ast
