// How operators of the AST are written in source and how tightly they bind,
// for printers (Spire and GLSL) and for diagnostics that quote an operator.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "syntax/ast.h"

namespace spire::ast {

// Binding strength, loosest first, as in GLSL 4.50 section 5.1 and the
// expression grammar; printers use it to place parentheses.
enum class Precedence : uint8_t {
  Comma,
  Assignment,
  Conditional,
  LogicalOr,
  LogicalXor,
  LogicalAnd,
  BitOr,
  BitXor,
  BitAnd,
  Equality,
  Relational,
  Shift,
  Additive,
  Multiplicative,
  Unary,
  Postfix,
  Primary,
};

constexpr Precedence precedenceOf(BinaryOp op) {
  switch (op) {
    case BinaryOp::Mul:
    case BinaryOp::Div:
    case BinaryOp::Mod: return Precedence::Multiplicative;
    case BinaryOp::Add:
    case BinaryOp::Sub: return Precedence::Additive;
    case BinaryOp::Shl:
    case BinaryOp::Shr: return Precedence::Shift;
    case BinaryOp::Less:
    case BinaryOp::Greater:
    case BinaryOp::LessEqual:
    case BinaryOp::GreaterEqual: return Precedence::Relational;
    case BinaryOp::Equal:
    case BinaryOp::NotEqual: return Precedence::Equality;
    case BinaryOp::BitAnd: return Precedence::BitAnd;
    case BinaryOp::BitXor: return Precedence::BitXor;
    case BinaryOp::BitOr: return Precedence::BitOr;
    case BinaryOp::LogicalAnd: return Precedence::LogicalAnd;
    case BinaryOp::LogicalXor: return Precedence::LogicalXor;
    case BinaryOp::LogicalOr: return Precedence::LogicalOr;
    case BinaryOp::Comma: return Precedence::Comma;
  }
  return Precedence::Comma;
}

// The next level up: where a right operand of a left-associative operator
// of level `p` must bind.
constexpr Precedence tighter(Precedence p) { return static_cast<Precedence>(static_cast<uint8_t>(p) + 1); }

constexpr bool isPostfix(UnaryOp op) { return op == UnaryOp::PostIncrement || op == UnaryOp::PostDecrement; }

constexpr std::string_view spelling(UnaryOp op) {
  switch (op) {
    case UnaryOp::Plus: return "+";
    case UnaryOp::Negate: return "-";
    case UnaryOp::LogicalNot: return "!";
    case UnaryOp::BitNot: return "~";
    case UnaryOp::PreIncrement:
    case UnaryOp::PostIncrement: return "++";
    case UnaryOp::PreDecrement:
    case UnaryOp::PostDecrement: return "--";
  }
  return "?";
}

constexpr std::string_view spelling(BinaryOp op) {
  switch (op) {
    case BinaryOp::Mul: return "*";
    case BinaryOp::Div: return "/";
    case BinaryOp::Mod: return "%";
    case BinaryOp::Add: return "+";
    case BinaryOp::Sub: return "-";
    case BinaryOp::Shl: return "<<";
    case BinaryOp::Shr: return ">>";
    case BinaryOp::Less: return "<";
    case BinaryOp::Greater: return ">";
    case BinaryOp::LessEqual: return "<=";
    case BinaryOp::GreaterEqual: return ">=";
    case BinaryOp::Equal: return "==";
    case BinaryOp::NotEqual: return "!=";
    case BinaryOp::BitAnd: return "&";
    case BinaryOp::BitXor: return "^";
    case BinaryOp::BitOr: return "|";
    case BinaryOp::LogicalAnd: return "&&";
    case BinaryOp::LogicalXor: return "^^";
    case BinaryOp::LogicalOr: return "||";
    case BinaryOp::Comma: return ",";
  }
  return "?";
}

constexpr std::string_view spelling(AssignOp op) {
  switch (op) {
    case AssignOp::Assign: return "=";
    case AssignOp::Mul: return "*=";
    case AssignOp::Div: return "/=";
    case AssignOp::Mod: return "%=";
    case AssignOp::Add: return "+=";
    case AssignOp::Sub: return "-=";
    case AssignOp::Shl: return "<<=";
    case AssignOp::Shr: return ">>=";
    case AssignOp::BitAnd: return "&=";
    case AssignOp::BitXor: return "^=";
    case AssignOp::BitOr: return "|=";
  }
  return "?";
}

// The text of the chain `top` (see leftSpine) where the grammar expects
// `context` or tighter, written in one pass and without recursing along the
// chain: `operand(expr, context)` writes the first operand and each right
// operand, `separator(op)` each operator with its spacing. A node is
// parenthesized where it binds more loosely than the place it stands in;
// all opening parentheses precede the first operand.
template <class WriteOperand, class WriteSeparator>
std::string writeChain(const BinaryExpr& top, Precedence context, WriteOperand operand, WriteSeparator separator) {
  const std::vector<const BinaryExpr*> spine = leftSpine(top);
  // A node stands as its parent's left operand, or where the chain does.
  const auto parenthesized = [&](size_t i) {
    return precedenceOf(spine[i]->op) < (i + 1 < spine.size() ? precedenceOf(spine[i + 1]->op) : context);
  };
  std::string text;
  for (size_t i = 0; i < spine.size(); ++i) {
    if (parenthesized(i)) text += '(';
  }
  text += operand(*spine.front()->lhs, precedenceOf(spine.front()->op));
  for (size_t i = 0; i < spine.size(); ++i) {
    text += separator(spine[i]->op);
    text += operand(*spine[i]->rhs, tighter(precedenceOf(spine[i]->op)));
    if (parenthesized(i)) text += ')';
  }
  return text;
}

}  // namespace spire::ast
