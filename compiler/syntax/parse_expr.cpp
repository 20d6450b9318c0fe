// Expressions, with GLSL's precedence and associativity. The binary levels
// are parsed by precedence climbing (parseBinary).
#include "syntax/ast_spelling.h"
#include "syntax/lexer.h"
#include "syntax/parser_impl.h"

namespace spire::parser_detail {
namespace {

std::optional<ast::AssignOp> assignmentOperator(TokenKind kind) {
  switch (kind) {
    case TokenKind::Assign: return ast::AssignOp::Assign;
    case TokenKind::StarAssign: return ast::AssignOp::Mul;
    case TokenKind::SlashAssign: return ast::AssignOp::Div;
    case TokenKind::PercentAssign: return ast::AssignOp::Mod;
    case TokenKind::PlusAssign: return ast::AssignOp::Add;
    case TokenKind::MinusAssign: return ast::AssignOp::Sub;
    case TokenKind::ShlAssign: return ast::AssignOp::Shl;
    case TokenKind::ShrAssign: return ast::AssignOp::Shr;
    case TokenKind::AmpAssign: return ast::AssignOp::BitAnd;
    case TokenKind::CaretAssign: return ast::AssignOp::BitXor;
    case TokenKind::PipeAssign: return ast::AssignOp::BitOr;
    default: return std::nullopt;
  }
}

// The binary operator a token stands for; the comma is left to
// parseExpression, whose operands are assignments.
std::optional<ast::BinaryOp> binaryOperator(TokenKind kind) {
  switch (kind) {
    case TokenKind::Star: return ast::BinaryOp::Mul;
    case TokenKind::Slash: return ast::BinaryOp::Div;
    case TokenKind::Percent: return ast::BinaryOp::Mod;
    case TokenKind::Plus: return ast::BinaryOp::Add;
    case TokenKind::Minus: return ast::BinaryOp::Sub;
    case TokenKind::Shl: return ast::BinaryOp::Shl;
    case TokenKind::Shr: return ast::BinaryOp::Shr;
    case TokenKind::Less: return ast::BinaryOp::Less;
    case TokenKind::Greater: return ast::BinaryOp::Greater;
    case TokenKind::LessEqual: return ast::BinaryOp::LessEqual;
    case TokenKind::GreaterEqual: return ast::BinaryOp::GreaterEqual;
    case TokenKind::EqualEqual: return ast::BinaryOp::Equal;
    case TokenKind::NotEqual: return ast::BinaryOp::NotEqual;
    case TokenKind::Amp: return ast::BinaryOp::BitAnd;
    case TokenKind::Caret: return ast::BinaryOp::BitXor;
    case TokenKind::Pipe: return ast::BinaryOp::BitOr;
    case TokenKind::AmpAmp: return ast::BinaryOp::LogicalAnd;
    case TokenKind::CaretCaret: return ast::BinaryOp::LogicalXor;
    case TokenKind::PipePipe: return ast::BinaryOp::LogicalOr;
    default: return std::nullopt;
  }
}

std::optional<ast::UnaryOp> prefixOperator(TokenKind kind) {
  switch (kind) {
    case TokenKind::Plus: return ast::UnaryOp::Plus;
    case TokenKind::Minus: return ast::UnaryOp::Negate;
    case TokenKind::Bang: return ast::UnaryOp::LogicalNot;
    case TokenKind::Tilde: return ast::UnaryOp::BitNot;
    case TokenKind::PlusPlus: return ast::UnaryOp::PreIncrement;
    case TokenKind::MinusMinus: return ast::UnaryOp::PreDecrement;
    default: return std::nullopt;
  }
}

}  // namespace

bool Parser::startsExpression() const {
  switch (current().kind) {
    case TokenKind::Identifier:
    case TokenKind::IntLiteral:
    case TokenKind::FloatLiteral:
    case TokenKind::KwTrue:
    case TokenKind::KwFalse:
    case TokenKind::LParen: return true;
    default: return prefixOperator(current().kind).has_value();
  }
}

// expression = assignment-expr { "," assignment-expr } ;
ast::ExprPtr Parser::parseExpression() {
  const uint32_t begin = current().range.begin;
  ast::ExprPtr lhs = parseAssignment();
  while (lhs && at(TokenKind::Comma)) {
    const Token& comma = advance();
    ast::ExprPtr rhs = parseAssignment();
    if (!rhs) return nullptr;
    lhs =
        makeExpr<ast::BinaryExpr>(rangeFrom(begin), ast::BinaryOp::Comma, std::move(lhs), std::move(rhs), comma.range);
  }
  return lhs;
}

// assignment-expr = conditional-expr [ assignment-op assignment-expr ] ;
// assignment-op   = "=" | "*=" | "/=" | "%=" | "+=" | "-=" | "<<=" | ">>=" | "&=" | "^=" | "|=" ;
ast::ExprPtr Parser::parseAssignment() {
  const uint32_t begin = current().range.begin;
  ast::ExprPtr target = parseConditional();
  const auto op = target ? assignmentOperator(current().kind) : std::nullopt;
  if (!op) return target;
  DepthScope scope(*this);
  if (!nestDeeper()) return nullptr;
  const Token& opToken = advance();
  ast::ExprPtr value = parseAssignment();
  if (!value) return nullptr;
  return makeExpr<ast::AssignExpr>(rangeFrom(begin), *op, std::move(target), std::move(value), opToken.range);
}

// conditional-expr = logical-or-expr [ "?" expression ":" assignment-expr ] ;
ast::ExprPtr Parser::parseConditional() {
  const uint32_t begin = current().range.begin;
  ast::ExprPtr condition = parseBinary(ast::Precedence::LogicalOr);
  if (!condition || !at(TokenKind::Question)) return condition;
  DepthScope scope(*this);
  if (!nestDeeper()) return nullptr;
  const Token& question = advance();
  ast::ExprPtr thenValue = parseExpression();
  if (!thenValue || !expectClosing(TokenKind::Colon, question, "in conditional expression")) return nullptr;
  ast::ExprPtr elseValue = parseAssignment();
  if (!elseValue) return nullptr;
  return makeExpr<ast::TernaryExpr>(rangeFrom(begin), std::move(condition), std::move(thenValue), std::move(elseValue));
}

// logical-or-expr  = logical-xor-expr { "||" logical-xor-expr } ;
// logical-xor-expr = logical-and-expr { "^^" logical-and-expr } ;
// logical-and-expr = bit-or-expr { "&&" bit-or-expr } ;
// bit-or-expr      = bit-xor-expr { "|" bit-xor-expr } ;
// bit-xor-expr     = bit-and-expr { "^" bit-and-expr } ;
// bit-and-expr     = equality-expr { "&" equality-expr } ;
// equality-expr    = relational-expr { ( "==" | "!=" ) relational-expr } ;
// relational-expr  = shift-expr { ( "<" | ">" | "<=" | ">=" ) shift-expr } ;
// shift-expr       = additive-expr { ( "<<" | ">>" ) additive-expr } ;
// additive-expr    = multiplicative-expr { ( "+" | "-" ) multiplicative-expr } ;
// multiplicative-expr = unary-expr { ( "*" | "/" | "%" ) unary-expr } ;
//
// All these levels by precedence climbing: the operand of the loosest
// operator allowed here (`minPrecedence`), then operators that bind at
// least as loosely, each folded into the left operand in the loop, so that
// `a + a + ... + a` is a loop however long. The recursion for a right
// operand only goes to tighter levels, so it is at most as deep as there
// are levels; unlike parentheses, a long chain is not nesting and does not
// count against the nesting limit (generated shaders write such chains).
ast::ExprPtr Parser::parseBinary(ast::Precedence minPrecedence) {
  const uint32_t begin = current().range.begin;
  ast::ExprPtr lhs = parseUnary();
  while (lhs) {
    const std::optional<ast::BinaryOp> op = binaryOperator(current().kind);
    if (!op || ast::precedenceOf(*op) < minPrecedence) break;
    const Token& opToken = advance();
    ast::ExprPtr rhs = parseBinary(ast::tighter(ast::precedenceOf(*op)));
    if (!rhs) return nullptr;
    lhs = makeExpr<ast::BinaryExpr>(rangeFrom(begin), *op, std::move(lhs), std::move(rhs), opToken.range);
  }
  return lhs;
}

// unary-expr = postfix-expr | ( "+" | "-" | "!" | "~" | "++" | "--" ) unary-expr ;
ast::ExprPtr Parser::parseUnary() {
  const auto op = prefixOperator(current().kind);
  if (!op) return parsePostfix();
  DepthScope scope(*this);
  if (!nestDeeper()) return nullptr;
  const Token& opToken = advance();
  ast::ExprPtr operand = parseUnary();
  if (!operand) return nullptr;
  return makeExpr<ast::UnaryExpr>(rangeFrom(opToken.range.begin), *op, std::move(operand), opToken.range);
}

// postfix-expr = primary-expr { "[" expression "]" | "." identifier | "++" | "--" } ;
ast::ExprPtr Parser::parsePostfix() {
  DepthScope scope(*this);
  const uint32_t begin = current().range.begin;
  ast::ExprPtr expr = parsePrimary();
  while (expr &&
         (at(TokenKind::LBracket) || at(TokenKind::Dot) || at(TokenKind::PlusPlus) || at(TokenKind::MinusMinus))) {
    if (!nestDeeper()) return nullptr;
    const Token& op = advance();
    if (op.kind == TokenKind::LBracket) {
      ast::ExprPtr index = parseExpression();
      if (!index || !expectClosing(TokenKind::RBracket, op, "after index")) return nullptr;
      expr = makeExpr<ast::IndexExpr>(rangeFrom(begin), std::move(expr), std::move(index));
    } else if (op.kind == TokenKind::Dot) {
      if (!expectName("a member name")) return nullptr;
      expr =
          makeExpr<ast::MemberExpr>(rangeFrom(begin), std::move(expr), std::string(previous().text), previous().range);
    } else {
      const auto postfix = op.kind == TokenKind::PlusPlus ? ast::UnaryOp::PostIncrement : ast::UnaryOp::PostDecrement;
      expr = makeExpr<ast::UnaryExpr>(rangeFrom(begin), postfix, std::move(expr), op.range);
    }
  }
  return expr;
}

// primary-expr = int-literal | float-literal | "true" | "false"
//              | "(" expression ")" | name-or-call ;
ast::ExprPtr Parser::parsePrimary() {
  const Token& token = current();
  switch (token.kind) {
    case TokenKind::IntLiteral: {
      advance();
      const IntLiteralValue value = intLiteralValue(token);
      return makeExpr<ast::IntLiteral>(token.range, value.value, value.isUnsigned, std::string(token.text));
    }
    case TokenKind::FloatLiteral:
      advance();
      return makeExpr<ast::FloatLiteral>(token.range, floatLiteralValue(token), std::string(token.text));
    case TokenKind::KwTrue:
    case TokenKind::KwFalse: advance(); return makeExpr<ast::BoolLiteral>(token.range, token.kind == TokenKind::KwTrue);
    case TokenKind::LParen: {
      DepthScope scope(*this);
      if (!nestDeeper()) return nullptr;
      advance();
      ast::ExprPtr inner = parseExpression();
      if (!inner || !expectClosing(TokenKind::RParen, token, "after expression")) return nullptr;
      return inner;
    }
    case TokenKind::Identifier: return parseNameOrCall();
    default: reportUnexpected(DiagCode::E2002, "expected an expression"); return nullptr;
  }
}

// name-or-call = identifier { "[" expression "]" } [ arguments ] ;
//
// With arguments, the name and sizes are the type of a constructor or the
// name of a function (`vec4(...)`, `float[3](...)`, `f(...)`); without, they
// are a variable and indexing. Which one is known only at the '(' or its
// absence, so the nodes are built then.
ast::ExprPtr Parser::parseNameOrCall() {
  DepthScope scope(*this);
  const Token& name = advance();
  ast::TypeSyntax type;
  type.name = name.text;
  type.nameRange = name.range;
  std::vector<uint32_t> indexEnds;
  while (at(TokenKind::LBracket)) {
    if (!nestDeeper()) return nullptr;
    const Token& open = advance();
    ast::ExprPtr size = parseExpression();
    if (!size || !expectClosing(TokenKind::RBracket, open, "after index")) return nullptr;
    type.arraySizes.push_back(std::move(size));
    indexEnds.push_back(previous().range.end);
  }
  if (at(TokenKind::LParen)) {
    type.range = rangeFrom(name.range.begin);
    std::vector<ast::ExprPtr> args;
    if (!parseArguments(args, "after arguments")) return nullptr;
    return makeExpr<ast::CallExpr>(rangeFrom(name.range.begin), std::move(type), std::move(args));
  }
  ast::ExprPtr expr = makeExpr<ast::NameExpr>(name.range, std::string(name.text));
  for (size_t i = 0; i < indexEnds.size(); ++i) {
    const SourceRange range{file_, name.range.begin, indexEnds[i]};
    expr = makeExpr<ast::IndexExpr>(range, std::move(expr), std::move(type.arraySizes[i]));
  }
  return expr;
}

// arguments = "(" [ assignment-expr { "," assignment-expr } ] ")" ;
bool Parser::parseArguments(std::vector<ast::ExprPtr>& args, std::string_view context) {
  DepthScope scope(*this);
  if (!nestDeeper()) return false;
  const Token& open = advance();
  if (accept(TokenKind::RParen)) return true;
  do {
    ast::ExprPtr arg = parseAssignment();
    if (!arg) return false;
    args.push_back(std::move(arg));
  } while (accept(TokenKind::Comma));
  return expectClosing(TokenKind::RParen, open, context);
}

ast::TypeSyntax Parser::cloneType(const ast::TypeSyntax& type) {
  ast::TypeSyntax copy{type.range, type.name, type.nameRange, {}};
  for (const auto& size : type.arraySizes) copy.arraySizes.push_back(cloneExpr(*size));
  return copy;
}

// Copies an expression for declarations that share one written type
// (`float[N] a, b;`). The copy gets fresh ids: side tables are per node.
ast::ExprPtr Parser::cloneExpr(const ast::Expr& expr) {
  using namespace ast;
  switch (expr.kind) {
    case ExprKind::BoolLiteral: {
      const auto& e = cast<BoolLiteral>(expr);
      return makeExpr<BoolLiteral>(e.range, e.value);
    }
    case ExprKind::IntLiteral: {
      const auto& e = cast<IntLiteral>(expr);
      return makeExpr<IntLiteral>(e.range, e.value, e.isUnsigned, e.spelling);
    }
    case ExprKind::FloatLiteral: {
      const auto& e = cast<FloatLiteral>(expr);
      return makeExpr<FloatLiteral>(e.range, e.value, e.spelling);
    }
    case ExprKind::Name: {
      const auto& e = cast<NameExpr>(expr);
      return makeExpr<NameExpr>(e.range, e.name);
    }
    case ExprKind::Unary: {
      const auto& e = cast<UnaryExpr>(expr);
      return makeExpr<UnaryExpr>(e.range, e.op, cloneExpr(*e.operand), e.opRange);
    }
    case ExprKind::Binary: {
      // Along the chain in a loop (ast::leftSpine), however long it is.
      const std::vector<const BinaryExpr*> spine = leftSpine(cast<BinaryExpr>(expr));
      ExprPtr copy = cloneExpr(*spine.front()->lhs);
      for (const BinaryExpr* e : spine) {
        copy = makeExpr<BinaryExpr>(e->range, e->op, std::move(copy), cloneExpr(*e->rhs), e->opRange);
      }
      return copy;
    }
    case ExprKind::Assign: {
      const auto& e = cast<AssignExpr>(expr);
      return makeExpr<AssignExpr>(e.range, e.op, cloneExpr(*e.target), cloneExpr(*e.value), e.opRange);
    }
    case ExprKind::Ternary: {
      const auto& e = cast<TernaryExpr>(expr);
      return makeExpr<TernaryExpr>(e.range, cloneExpr(*e.condition), cloneExpr(*e.thenValue), cloneExpr(*e.elseValue));
    }
    case ExprKind::Call: {
      const auto& e = cast<CallExpr>(expr);
      std::vector<ExprPtr> args;
      for (const auto& arg : e.args) args.push_back(cloneExpr(*arg));
      return makeExpr<CallExpr>(e.range, cloneType(e.callee), std::move(args));
    }
    case ExprKind::Member: {
      const auto& e = cast<MemberExpr>(expr);
      return makeExpr<MemberExpr>(e.range, cloneExpr(*e.object), e.member, e.memberRange);
    }
    case ExprKind::Index: {
      const auto& e = cast<IndexExpr>(expr);
      return makeExpr<IndexExpr>(e.range, cloneExpr(*e.object), cloneExpr(*e.index));
    }
  }
  return nullptr;  // unreachable: every kind is handled above
}

}  // namespace spire::parser_detail
