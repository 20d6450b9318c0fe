#include "simplify/cost_model.h"

#include <algorithm>
#include <string_view>
#include <utility>

#include "codegen/expression_effects.h"
#include "simplify/syntax_walk.h"

namespace spire::simplify {
namespace {

// A loop that runs longer than this is costed as one iteration, like a loop
// whose bounds are not constant: the count would only be simulated.
constexpr int64_t kMaxTrips = 1 << 16;

// Built-ins that take a sampler but fetch no texel: they ask the texture's
// size or mip levels, and count as any other operation.
bool isTextureQuery(std::string_view name) {
  return name == "textureSize" || name == "textureQueryLod" || name == "textureQueryLevels";
}

bool isMatrixProduct(const sem::Type* lhs, const sem::Type* rhs) {
  if (!lhs || !rhs) return false;
  return (lhs->isMatrix() && (rhs->isMatrix() || rhs->isVector())) || (lhs->isVector() && rhs->isMatrix());
}

// The loop variable of `i = C` or `int i = C`, and C.
struct LoopStart {
  const ast::VarDeclarator* variable = nullptr;
  int64_t value = 0;
};

}  // namespace

int64_t scalarCount(const sem::Type* type) {
  if (!type) return 0;
  switch (type->kind) {
    case sem::TypeKind::Scalar:
    case sem::TypeKind::Vector:
    case sem::TypeKind::Matrix: return type->componentCount();
    case sem::TypeKind::Array: return scalarCount(type->element) * type->arraySize;
    case sem::TypeKind::Struct: {
      int64_t sum = 0;
      for (const sem::StructField& f : type->fields) sum += scalarCount(f.type);
      return sum;
    }
    default: return 0;
  }
}

int64_t CostModel::definition(const ast::ComponentDecl& decl, const Substitution& substitution) {
  substitution_ = substitution;
  deadLocals_ = deadLocals(decl);
  int64_t cost = 0;
  if (decl.init) cost = expr(*decl.init);
  if (decl.body) cost = stmt(*decl.body);
  substitution_ = {};
  deadLocals_.clear();
  return cost;
}

int64_t CostModel::sharedDefinition(const ast::ComponentDecl& decl, std::set<std::string>& values) {
  values_ = &values;
  unshared_ = 0;
  sharedCalls_ = 0;
  keys_.beginDefinition();
  const int64_t cost = definition(decl);
  values_ = nullptr;
  return cost;
}

bool CostModel::alreadyComputed(const ast::Expr& e) {
  if (!sharing()) return false;
  switch (e.kind) {
    case ast::ExprKind::Unary:
    case ast::ExprKind::Binary:
    case ast::ExprKind::Ternary:
    case ast::ExprKind::Call:
    case ast::ExprKind::Member:
    case ast::ExprKind::Index: break;
    default: return false;  // literals and names cost nothing; assignments are effects
  }
  const std::optional<std::string> key = keys_.key(e);
  return key && !values_->insert(*key).second;
}

void CostModel::wrote(const ast::Expr& target, std::optional<std::string> value) {
  if (values_) keys_.wrote(target, unshared_ == 0 ? std::move(value) : std::nullopt);
}

int64_t CostModel::unsharedStmt(const ast::Stmt& s) {
  ++unshared_;
  const int64_t cost = stmt(s);
  --unshared_;
  return cost;
}

int64_t CostModel::scalarsOf(const ast::Expr& e) const { return scalarCount(model_.typeOf(e)); }

std::optional<int64_t> CostModel::constantOf(const ast::Expr& e) const {
  if (&e == substitution_.target && substitution_.constant) return substitution_.constant;
  return model_.info(e).constant;
}

int64_t CostModel::expr(const ast::Expr& e) {
  if (&e == substitution_.target) {
    int64_t sum = 0;
    for (const ast::Expr* part : substitution_.parts) sum += expr(*part);
    return sum;
  }
  if (alreadyComputed(e)) return 0;
  switch (e.kind) {
    case ast::ExprKind::Unary: return unary(ast::cast<ast::UnaryExpr>(e));
    case ast::ExprKind::Binary: return binary(ast::cast<ast::BinaryExpr>(e));
    case ast::ExprKind::Assign: return assign(ast::cast<ast::AssignExpr>(e));
    case ast::ExprKind::Ternary: {
      const auto& t = ast::cast<ast::TernaryExpr>(e);
      return expr(*t.condition) + std::max(expr(*t.thenValue), expr(*t.elseValue));
    }
    case ast::ExprKind::Call: return call(ast::cast<ast::CallExpr>(e));
    case ast::ExprKind::Member: return expr(*ast::cast<ast::MemberExpr>(e).object);
    case ast::ExprKind::Index: {
      const auto& i = ast::cast<ast::IndexExpr>(e);
      return expr(*i.object) + expr(*i.index);
    }
    default: return 0;  // literals and names
  }
}

// A left-associative chain is costed in a loop (ast::leftSpine), so that
// recursion only goes as deep as the code is really nested.
int64_t CostModel::binary(const ast::BinaryExpr& top) {
  const std::vector<const ast::BinaryExpr*> spine = ast::leftSpine(top);
  int64_t cost = expr(*spine.front()->lhs);
  for (const ast::BinaryExpr* b : spine) {
    // A substituted link replaces the whole chain below it, and so does a
    // link whose value was computed before (the top one was asked by expr).
    if (b == substitution_.target) {
      cost = expr(*b);
    } else if (b != &top && alreadyComputed(*b)) {
      cost = 0;
    } else {
      cost += expr(*b->rhs) + binaryOp(b->op, *b->lhs, *b->rhs, *b);
    }
  }
  return cost;
}

int64_t CostModel::binaryOp(ast::BinaryOp op, const ast::Expr& lhs, const ast::Expr& rhs,
                            const ast::Expr& result) const {
  if (op == ast::BinaryOp::Comma) return 0;
  const sem::Type* l = model_.typeOf(lhs);
  const sem::Type* r = model_.typeOf(rhs);
  if (op == ast::BinaryOp::Mul && isMatrixProduct(l, r)) {
    // Each result scalar is a dot product over the inner dimension.
    const int64_t inner = l->isMatrix() ? l->columns : l->rows;
    return scalarsOf(result) * inner;
  }
  return std::max({scalarsOf(result), scalarCount(l), scalarCount(r)});
}

// A negated literal (`-1.0`) is a literal: no compiler negates it at run time.
int64_t CostModel::unary(const ast::UnaryExpr& u) {
  const int64_t operand = expr(*u.operand);
  if (u.op == ast::UnaryOp::PreIncrement || u.op == ast::UnaryOp::PreDecrement || u.op == ast::UnaryOp::PostIncrement ||
      u.op == ast::UnaryOp::PostDecrement) {
    wrote(*u.operand, std::nullopt);
  }
  const bool literal = u.operand->kind == ast::ExprKind::IntLiteral || u.operand->kind == ast::ExprKind::FloatLiteral;
  if (u.op == ast::UnaryOp::Plus || (u.op == ast::UnaryOp::Negate && literal)) return operand;
  return operand + std::max(scalarsOf(u), scalarsOf(*u.operand));
}

// `a = b` only moves a value; `a op= b` is the operation `a op b`.
int64_t CostModel::assign(const ast::AssignExpr& a) {
  const int64_t operands = expr(*a.target) + expr(*a.value);
  // `x op= v` is keyed as a value unlike any other: rare in straight-line code.
  wrote(*a.target, a.op == ast::AssignOp::Assign && sharing() ? keys_.key(*a.value) : std::nullopt);
  static constexpr std::pair<ast::AssignOp, ast::BinaryOp> kOps[] = {
      {ast::AssignOp::Mul, ast::BinaryOp::Mul},       {ast::AssignOp::Div, ast::BinaryOp::Div},
      {ast::AssignOp::Mod, ast::BinaryOp::Mod},       {ast::AssignOp::Add, ast::BinaryOp::Add},
      {ast::AssignOp::Sub, ast::BinaryOp::Sub},       {ast::AssignOp::Shl, ast::BinaryOp::Shl},
      {ast::AssignOp::Shr, ast::BinaryOp::Shr},       {ast::AssignOp::BitAnd, ast::BinaryOp::BitAnd},
      {ast::AssignOp::BitXor, ast::BinaryOp::BitXor}, {ast::AssignOp::BitOr, ast::BinaryOp::BitOr},
  };
  for (const auto& [assignOp, binaryOp] : kOps) {
    if (a.op == assignOp) return operands + this->binaryOp(binaryOp, *a.target, *a.value, a);
  }
  return operands;
}

int64_t CostModel::call(const ast::CallExpr& c) {
  int64_t args = 0;
  int64_t widest = scalarsOf(c);
  for (const ast::ExprPtr& arg : c.args) {
    args += expr(*arg);
    widest = std::max(widest, scalarsOf(*arg));
  }
  // What an `out` argument held before the call is not what it holds after.
  const bool writes = codegen::callWrites(model_, c);
  if (writes) {
    for (const ast::ExprPtr& arg : c.args) wrote(*arg, std::nullopt);
  }
  const sem::ExprInfo& info = model_.info(c);
  switch (info.ref) {
    case sem::RefKind::Function: {
      if (!info.function) return args;
      const ast::FunctionDecl* decl = info.function->decl;
      if (sharing() && !writes && decl && decl->body && !inProgress_.contains(info.function) &&
          sharedCalls_ < kMaxSharedCalls) {
        ++sharedCalls_;
        return args + sharedCall(*info.function, c);
      }
      return args + function(*info.function);
    }
    case sem::RefKind::Builtin: {
      const bool sampled = info.builtin && !info.builtin->params.empty() && info.builtin->params.front().type &&
                           info.builtin->params.front().type->isSampler();
      return args + (sampled && !isTextureQuery(c.callee.name) ? kTextureFetchCost : widest);
    }
    default: return args;  // constructors gather their arguments
  }
}

int64_t CostModel::function(const sem::Function& f) {
  if (const auto found = functions_.find(&f); found != functions_.end()) return found->second;
  const ast::FunctionDecl* decl = f.decl;
  if (!decl || !decl->body || !inProgress_.insert(&f).second) return 0;
  // A function body never holds the substituted expression (rewrites are of
  // component definitions), so its cost is the same for every definition;
  // costed alone, it shares no values with its caller.
  std::set<std::string>* values = std::exchange(values_, nullptr);
  const int64_t cost = stmt(*decl->body);
  values_ = values;
  inProgress_.erase(&f);
  functions_[&f] = cost;
  return cost;
}

// The body of `f` costed for this call: its parameters are the arguments'
// values, so the same work in two functions, or in one called twice with
// the same arguments, is counted once.
int64_t CostModel::sharedCall(const sem::Function& f, const ast::CallExpr& c) {
  std::vector<std::optional<std::string>> arguments;
  for (const ast::ExprPtr& arg : c.args) arguments.push_back(keys_.key(*arg));
  inProgress_.insert(&f);
  keys_.enterFunction(*f.decl, arguments);
  const int64_t cost = stmt(*f.decl->body);
  keys_.leaveFunction();
  inProgress_.erase(&f);
  return cost;
}

int64_t CostModel::stmt(const ast::Stmt& s) {
  switch (s.kind) {
    case ast::StmtKind::Block: {
      int64_t sum = 0;
      for (const ast::StmtPtr& child : ast::cast<ast::BlockStmt>(s).statements) sum += stmt(*child);
      return sum;
    }
    case ast::StmtKind::VarDecl: {
      int64_t sum = 0;
      for (const ast::VarDeclarator& d : ast::cast<ast::VarDeclStmt>(s).declarators) {
        sum += d.init && deadLocals_.count(&d) == 0 ? expr(*d.init) : 0;
        if (values_) keys_.setLocal(&d, d.init && sharing() ? keys_.key(*d.init) : std::nullopt);
      }
      return sum;
    }
    case ast::StmtKind::Expr: return expr(*ast::cast<ast::ExprStmt>(s).expr);
    case ast::StmtKind::If: {
      const auto& i = ast::cast<ast::IfStmt>(s);
      return expr(*i.condition) + std::max(unsharedStmt(*i.thenBranch), i.elseBranch ? unsharedStmt(*i.elseBranch) : 0);
    }
    case ast::StmtKind::For:
    case ast::StmtKind::While:
    case ast::StmtKind::DoWhile: return loop(s);
    case ast::StmtKind::Return: {
      const ast::Expr* value = ast::cast<ast::ReturnStmt>(s).value.get();
      return value ? expr(*value) : 0;
    }
    default: return 0;  // break, continue, discard, empty
  }
}

// A loop's values change from one iteration to the next: none is shared.
int64_t CostModel::loop(const ast::Stmt& s) {
  ++unshared_;
  int64_t cost = 0;
  if (const auto* f = ast::dyn_cast<ast::ForStmt>(&s)) cost = forLoop(*f);
  if (const auto* w = ast::dyn_cast<ast::WhileStmt>(&s)) cost = expr(*w->condition) + stmt(*w->body);
  if (const auto* d = ast::dyn_cast<ast::DoWhileStmt>(&s)) cost = stmt(*d->body) + expr(*d->condition);
  --unshared_;
  return cost;
}

int64_t CostModel::forLoop(const ast::ForStmt& f) {
  const int64_t init = f.init ? stmt(*f.init) : 0;
  const int64_t iteration =
      (f.condition ? expr(*f.condition) : 0) + (f.step ? expr(*f.step) : 0) + (f.body ? stmt(*f.body) : 0);
  return init + tripCount(f).value_or(1) * iteration;
}

namespace {

const ast::VarDeclarator* loopVariable(const sem::Model& model, const ast::Expr* e) {
  const auto* name = ast::dyn_cast<ast::NameExpr>(e);
  return name ? model.info(*name).local : nullptr;
}

// `int i = C` or `i = C`.
std::optional<LoopStart> loopStart(const sem::Model& model, const ast::Stmt* init) {
  if (const auto* decl = ast::dyn_cast<ast::VarDeclStmt>(init); decl && decl->declarators.size() == 1) {
    const ast::VarDeclarator& d = decl->declarators.front();
    if (d.init && model.info(*d.init).constant) return LoopStart{&d, *model.info(*d.init).constant};
  }
  const auto* statement = ast::dyn_cast<ast::ExprStmt>(init);
  const auto* assign = statement ? ast::dyn_cast<ast::AssignExpr>(statement->expr.get()) : nullptr;
  if (!assign || assign->op != ast::AssignOp::Assign) return std::nullopt;
  const ast::VarDeclarator* variable = loopVariable(model, assign->target.get());
  const auto value = model.info(*assign->value).constant;
  if (!variable || !value) return std::nullopt;
  return LoopStart{variable, *value};
}

// What the step `i++`, `--i`, `i += C` or `i -= C` adds to the variable.
std::optional<int64_t> loopIncrement(const sem::Model& model, const ast::Expr* step,
                                     const ast::VarDeclarator* variable) {
  if (const auto* u = ast::dyn_cast<ast::UnaryExpr>(step); u && loopVariable(model, u->operand.get()) == variable) {
    if (u->op == ast::UnaryOp::PreIncrement || u->op == ast::UnaryOp::PostIncrement) return 1;
    if (u->op == ast::UnaryOp::PreDecrement || u->op == ast::UnaryOp::PostDecrement) return -1;
  }
  const auto* a = ast::dyn_cast<ast::AssignExpr>(step);
  if (!a || loopVariable(model, a->target.get()) != variable) return std::nullopt;
  const auto value = model.info(*a->value).constant;
  if (!value || (a->op != ast::AssignOp::Add && a->op != ast::AssignOp::Sub)) return std::nullopt;
  return a->op == ast::AssignOp::Add ? *value : -*value;
}

bool compare(ast::BinaryOp op, int64_t lhs, int64_t rhs) {
  switch (op) {
    case ast::BinaryOp::Less: return lhs < rhs;
    case ast::BinaryOp::LessEqual: return lhs <= rhs;
    case ast::BinaryOp::Greater: return lhs > rhs;
    case ast::BinaryOp::GreaterEqual: return lhs >= rhs;
    case ast::BinaryOp::NotEqual: return lhs != rhs;
    default: return false;
  }
}

}  // namespace

// The iterations of `for (i = A; i < B; i += C)` with constant A, B and C
// (any of < <= > >= != with the variable on either side), counted by running
// the loop on its variable; nullopt for any other loop, or one that would
// not end within kMaxTrips. A body that assigns the variable is not seen.
std::optional<int64_t> CostModel::tripCount(const ast::ForStmt& f) const {
  const auto start = loopStart(model_, f.init.get());
  const auto* condition = ast::dyn_cast<ast::BinaryExpr>(f.condition.get());
  if (!start || !condition) return std::nullopt;
  const auto increment = loopIncrement(model_, f.step.get(), start->variable);
  const bool variableLeft = loopVariable(model_, condition->lhs.get()) == start->variable;
  const bool variableRight = loopVariable(model_, condition->rhs.get()) == start->variable;
  const auto bound = constantOf(variableLeft ? *condition->rhs : *condition->lhs);
  if (!increment || *increment == 0 || !bound || variableLeft == variableRight) return std::nullopt;
  int64_t trips = 0;
  for (int64_t i = start->value; variableLeft ? compare(condition->op, i, *bound) : compare(condition->op, *bound, i);
       i += *increment) {
    if (++trips > kMaxTrips) return std::nullopt;
  }
  return trips;
}

namespace {

bool within(const SourceRange& inner, const SourceRange& outer) {
  return inner.file == outer.file && inner.begin >= outer.begin && inner.end <= outer.end;
}

}  // namespace

// The locals of `decl` whose value nothing reads: a read outside every
// local's initializer keeps its local, and a kept local keeps those its
// initializer reads. Reads the substitution removes do not count.
std::set<const ast::VarDeclarator*> CostModel::deadLocals(const ast::ComponentDecl& decl) const {
  std::vector<const ast::VarDeclarator*> locals;  // those with an initializer
  std::vector<std::pair<const ast::VarDeclarator*, SourceRange>> reads;
  const auto removed = [&](const SourceRange& r) {
    if (!substitution_.target || !within(r, substitution_.target->range)) return false;
    return std::none_of(substitution_.parts.begin(), substitution_.parts.end(),
                        [&](const ast::Expr* part) { return within(r, part->range); });
  };
  SyntaxWalker walker(
      [&](const ast::Expr& e) {
        const ast::VarDeclarator* local = model_.info(e).local;
        if (e.kind == ast::ExprKind::Name && local && !removed(e.range)) reads.emplace_back(local, e.range);
      },
      [&](const ast::Stmt& s) {
        const auto* v = ast::dyn_cast<ast::VarDeclStmt>(&s);
        for (size_t i = 0; v && i < v->declarators.size(); ++i) {
          if (v->declarators[i].init) locals.push_back(&v->declarators[i]);
        }
      },
      SyntaxWalker::Immutable::Visit);
  walker.expr(decl.init.get());
  walker.stmt(decl.body.get());
  // Roots: reads outside every initializer, and initializers with effects.
  std::set<const ast::VarDeclarator*> live;
  std::vector<const ast::VarDeclarator*> pending;
  const auto keep = [&](const ast::VarDeclarator* local) {
    if (live.insert(local).second) pending.push_back(local);
  };
  for (const ast::VarDeclarator* local : locals) {
    // An initializer that writes something besides its local is kept even
    // if the local is never read.
    if (codegen::hasSideEffects(model_, *local->init)) keep(local);
  }
  // Not a structured binding: clang 14 (the fuzz preset) cannot capture one.
  for (const auto& read : reads) {
    const auto& range = read.second;
    if (std::none_of(locals.begin(), locals.end(), [&](const auto* l) { return within(range, l->init->range); })) {
      keep(read.first);
    }
  }
  while (!pending.empty()) {
    const ast::VarDeclarator* owner = pending.back();
    pending.pop_back();
    for (const auto& [local, range] : reads) {
      if (within(range, owner->init->range)) keep(local);
    }
  }
  std::set<const ast::VarDeclarator*> dead;
  for (const ast::VarDeclarator* local : locals) {
    if (live.count(local) == 0) dead.insert(local);
  }
  return dead;
}

}  // namespace spire::simplify
