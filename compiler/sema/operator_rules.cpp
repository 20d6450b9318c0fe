#include "sema/operator_rules.h"

#include <fmt/format.h>

namespace spire::sem {
namespace {

using ast::BinaryOp;

bool scalarConvertible(ScalarKind from, ScalarKind to) {
  if (from == to) return true;
  if (from == ScalarKind::Int) return to == ScalarKind::Uint || to == ScalarKind::Float;
  return from == ScalarKind::Uint && to == ScalarKind::Float;
}

// The base type both operands convert to, if any.
std::optional<ScalarKind> commonScalar(ScalarKind a, ScalarKind b) {
  if (scalarConvertible(a, b)) return b;
  if (scalarConvertible(b, a)) return a;
  return std::nullopt;
}

bool isArithmeticOperand(const Type* t) { return t->isNumericShape() && t->scalar != ScalarKind::Bool; }

// +, -, *, / and % over scalars, vectors and matrices.
const Type* arithmeticType(const TypeTable& types, BinaryOp op, const Type* lhs, const Type* rhs) {
  if (!isArithmeticOperand(lhs) || !isArithmeticOperand(rhs)) return nullptr;
  const auto base = commonScalar(lhs->scalar, rhs->scalar);
  if (!base) return nullptr;
  if (op == BinaryOp::Mod && *base == ScalarKind::Float) return nullptr;
  // Matrices exist only over float, so a matrix operand forces float.
  if ((lhs->isMatrix() || rhs->isMatrix()) && *base != ScalarKind::Float) return nullptr;
  const Type* l = lhs->isMatrix() ? lhs : types.withScalar(lhs, *base);
  const Type* r = rhs->isMatrix() ? rhs : types.withScalar(rhs, *base);

  if (l->isScalar()) return r;
  if (r->isScalar()) return l;
  if (l->isVector() && r->isVector()) return l->rows == r->rows ? l : nullptr;
  if (op == BinaryOp::Mul) {
    if (l->isMatrix() && r->isVector())
      return l->columns == r->rows ? types.vector(ScalarKind::Float, l->rows) : nullptr;
    if (l->isVector() && r->isMatrix())
      return l->rows == r->rows ? types.vector(ScalarKind::Float, r->columns) : nullptr;
    if (l->isMatrix() && r->isMatrix()) return l->columns == r->rows ? types.matrix(r->columns, l->rows) : nullptr;
    return nullptr;
  }
  if (l->isMatrix() && r->isMatrix() && op != BinaryOp::Mod) return l == r ? l : nullptr;
  return nullptr;
}

const Type* bitwiseType(const TypeTable& types, const Type* lhs, const Type* rhs) {
  if (!lhs->isIntegerShape() || !rhs->isIntegerShape()) return nullptr;
  const auto base = commonScalar(lhs->scalar, rhs->scalar);
  if (!base) return nullptr;
  const Type* l = types.withScalar(lhs, *base);
  const Type* r = types.withScalar(rhs, *base);
  if (l->isScalar()) return r;
  if (r->isScalar()) return l;
  return l == r ? l : nullptr;
}

const Type* shiftType(const Type* lhs, const Type* rhs) {
  if (!lhs->isIntegerShape() || !rhs->isIntegerShape()) return nullptr;
  if (lhs->isScalar() && !rhs->isScalar()) return nullptr;
  if (lhs->isVector() && rhs->isVector() && lhs->rows != rhs->rows) return nullptr;
  return lhs;
}

uint32_t constructorComponents(const Type* t) { return t->componentCount(); }

}  // namespace

const Type* commonType(const Type* a, const Type* b) {
  if (a == b) return a;
  if (isImplicitlyConvertible(a, b)) return b;
  if (isImplicitlyConvertible(b, a)) return a;
  return nullptr;
}

const Type* binaryResultType(const TypeTable& types, BinaryOp op, const Type* lhs, const Type* rhs) {
  switch (op) {
    case BinaryOp::Mul:
    case BinaryOp::Div:
    case BinaryOp::Mod:
    case BinaryOp::Add:
    case BinaryOp::Sub: return arithmeticType(types, op, lhs, rhs);
    case BinaryOp::Shl:
    case BinaryOp::Shr: return shiftType(lhs, rhs);
    case BinaryOp::Less:
    case BinaryOp::Greater:
    case BinaryOp::LessEqual:
    case BinaryOp::GreaterEqual:
      if (!lhs->isScalar() || !rhs->isScalar() || lhs->scalar == ScalarKind::Bool || rhs->scalar == ScalarKind::Bool)
        return nullptr;
      return commonScalar(lhs->scalar, rhs->scalar) ? types.boolType() : nullptr;
    case BinaryOp::Equal:
    case BinaryOp::NotEqual: {
      const Type* common = commonType(lhs, rhs);
      if (!common || common->containsOpaque() || common->isVoid()) return nullptr;
      return types.boolType();
    }
    case BinaryOp::BitAnd:
    case BinaryOp::BitXor:
    case BinaryOp::BitOr: return bitwiseType(types, lhs, rhs);
    case BinaryOp::LogicalAnd:
    case BinaryOp::LogicalXor:
    case BinaryOp::LogicalOr: return lhs == types.boolType() && rhs == types.boolType() ? types.boolType() : nullptr;
    case BinaryOp::Comma: return rhs;
  }
  return nullptr;
}

const Type* unaryResultType(ast::UnaryOp op, const Type* operand) {
  switch (op) {
    case ast::UnaryOp::Plus:
    case ast::UnaryOp::Negate:
    case ast::UnaryOp::PreIncrement:
    case ast::UnaryOp::PreDecrement:
    case ast::UnaryOp::PostIncrement:
    case ast::UnaryOp::PostDecrement: return isArithmeticOperand(operand) ? operand : nullptr;
    case ast::UnaryOp::LogicalNot:
      return operand->isScalar() && operand->scalar == ScalarKind::Bool ? operand : nullptr;
    case ast::UnaryOp::BitNot: return operand->isIntegerShape() ? operand : nullptr;
  }
  return nullptr;
}

Expected<void, Failure> checkConstructor(const Type* target, const std::vector<const Type*>& args) {
  if (target->isVoid() || target->isSampler()) {
    return Failure{fmt::format("values of type '{}' cannot be constructed", target->name())};
  }
  if (args.empty()) return Failure{fmt::format("constructor for '{}' needs at least one argument", target->name())};
  for (const Type* arg : args) {
    if (!arg->isNumericShape()) {
      return Failure{fmt::format("cannot construct '{}' from a value of type '{}'", target->name(), arg->name())};
    }
  }
  if (target->isScalar()) {
    if (args.size() != 1)
      return Failure{fmt::format("constructor for '{}' takes exactly one argument", target->name())};
    return {};
  }
  const uint32_t needed = constructorComponents(target);
  // A single scalar fills a vector or sets a matrix diagonal; a single matrix
  // initializes a matrix from its overlapping part.
  if (args.size() == 1 && (args[0]->isScalar() || (target->isMatrix() && args[0]->isMatrix()))) return {};
  if (target->isMatrix()) {
    for (const Type* arg : args) {
      if (arg->isMatrix()) return Failure{"a matrix argument must be the only argument of a matrix constructor"};
    }
  }
  uint32_t supplied = 0;
  for (size_t i = 0; i < args.size(); ++i) {
    if (supplied >= needed) {
      return Failure{fmt::format("too many arguments for '{}': argument {} is unused", target->name(), i + 1)};
    }
    supplied += constructorComponents(args[i]);
  }
  if (supplied < needed) {
    return Failure{
        fmt::format("too few components for '{}': {} supplied, {} needed", target->name(), supplied, needed)};
  }
  if (target->isMatrix() && supplied != needed) {
    return Failure{
        fmt::format("too many components for '{}': {} supplied, {} needed", target->name(), supplied, needed)};
  }
  return {};
}

ast::BinaryOp compoundOperator(ast::AssignOp op) {
  switch (op) {
    case ast::AssignOp::Mul: return BinaryOp::Mul;
    case ast::AssignOp::Div: return BinaryOp::Div;
    case ast::AssignOp::Mod: return BinaryOp::Mod;
    case ast::AssignOp::Add: return BinaryOp::Add;
    case ast::AssignOp::Sub: return BinaryOp::Sub;
    case ast::AssignOp::Shl: return BinaryOp::Shl;
    case ast::AssignOp::Shr: return BinaryOp::Shr;
    case ast::AssignOp::BitAnd: return BinaryOp::BitAnd;
    case ast::AssignOp::BitXor: return BinaryOp::BitXor;
    case ast::AssignOp::BitOr: return BinaryOp::BitOr;
    case ast::AssignOp::Assign: break;
  }
  return BinaryOp::Comma;
}

}  // namespace spire::sem
