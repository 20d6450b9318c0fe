// Statements, the GLSL subset allowed in function and component bodies.
#include <fmt/format.h>

#include "syntax/parser_impl.h"

namespace spire::parser_detail {

// block = "{" { statement } "}" ;
std::unique_ptr<ast::BlockStmt> Parser::parseBlock() {
  const Token& open = current();
  DepthScope scope(*this);
  if (!nestDeeper()) {
    skipBalancedBlock();
    return nullptr;
  }
  advance();
  auto block = std::make_unique<ast::BlockStmt>(SourceRange{});
  // A top-level declaration cannot occur in a body, so it shows a missing '}'.
  while (!atEndOfList()) {
    const size_t before = pos_;
    if (auto statement = parseStatement()) block->statements.push_back(std::move(statement));
    ensureProgress(before);
  }
  expectClosing(TokenKind::RBrace, open, "at end of block");
  block->range = rangeFrom(open.range.begin);
  return block;
}

// statement = { attribute } unattributed-statement ;
// No GLSL statement starts with '[', so attributes cannot be confused with
// an expression.
ast::StmtPtr Parser::parseStatement() {
  if (!at(TokenKind::LBracket)) return parseUnattributedStatement();
  auto attributes = parseAttributes();
  if (!attributes) {
    synchronize(SyncLevel::Statement);
    return nullptr;
  }
  // Left for the block to close: attributes need a statement to belong to.
  if (at(TokenKind::RBrace) || at(TokenKind::EndOfFile)) {
    reportMissing("expected a statement after the attributes");
    return nullptr;
  }
  ast::StmtPtr statement = parseUnattributedStatement();
  if (statement) statement->attributes = std::move(*attributes);
  return statement;
}

// unattributed-statement = block | local-decl | if-stmt | for-stmt
//           | while-stmt | do-stmt | jump-stmt | return-stmt | ";"
//           | expression-stmt ;
ast::StmtPtr Parser::parseUnattributedStatement() {
  if (at(TokenKind::LBrace)) return parseBlock();
  DepthScope scope(*this);
  if (!nestDeeper()) {
    synchronize(SyncLevel::WholeConstruct);
    return nullptr;
  }
  switch (current().kind) {
    case TokenKind::KwIf: return parseIf();
    case TokenKind::KwFor: return parseFor();
    case TokenKind::KwWhile: return parseWhile();
    case TokenKind::KwDo: return parseDoWhile();
    case TokenKind::KwBreak:
    case TokenKind::KwContinue:
    case TokenKind::KwDiscard: return parseJump();
    case TokenKind::KwReturn: return parseReturn();
    case TokenKind::Semicolon: return std::make_unique<ast::EmptyStmt>(advance().range);
    default: break;
  }
  if (!atLocalDecl()) return parseExpressionStmt();
  auto decl = parseLocalDecl();
  if (!decl) synchronize(SyncLevel::Statement);
  return decl;
}

// Decides between local-decl and expression-stmt, which can share a long
// prefix (`a[2] b;` declares, `a[2] = b;` assigns).
bool Parser::atLocalDecl() const { return at(TokenKind::KwConst) || atTypedName(); }

// Whether a type and then a name start here: an identifier, optional
// bracketed sizes and another identifier.
bool Parser::atTypedName() const {
  if (!at(TokenKind::Identifier)) return false;
  size_t ahead = 1;
  while (peek(ahead).kind == TokenKind::LBracket) {
    size_t depth = 0;
    do {
      switch (peek(ahead++).kind) {
        case TokenKind::LBracket: ++depth; break;
        case TokenKind::RBracket: --depth; break;
        // Cannot occur inside brackets: this is no declaration.
        case TokenKind::Semicolon:
        case TokenKind::LBrace:
        case TokenKind::RBrace:
        case TokenKind::EndOfFile: return false;
        default: break;
      }
    } while (depth > 0);
  }
  return peek(ahead).kind == TokenKind::Identifier;
}

// local-decl = [ "const" ] type var-declarator { "," var-declarator } ";" ;
std::unique_ptr<ast::VarDeclStmt> Parser::parseLocalDecl() {
  const uint32_t begin = current().range.begin;
  auto stmt = std::make_unique<ast::VarDeclStmt>(SourceRange{});
  stmt->isConst = accept(TokenKind::KwConst);
  auto type = parseType();
  if (!type) return nullptr;
  stmt->type = std::move(*type);
  do {
    auto declarator = parseVarDeclarator();
    if (!declarator) return nullptr;
    stmt->declarators.push_back(std::move(*declarator));
  } while (accept(TokenKind::Comma));
  if (!expectSemicolon("after declaration")) return nullptr;
  stmt->range = rangeFrom(begin);
  return stmt;
}

// var-declarator = identifier { array-dim } [ "=" assignment-expr ] ;
std::optional<ast::VarDeclarator> Parser::parseVarDeclarator() {
  if (!expectName("a variable name")) return std::nullopt;
  ast::VarDeclarator declarator;
  declarator.name = previous().text;
  declarator.nameRange = previous().range;
  if (!parseArrayDims(declarator.arraySizes)) return std::nullopt;
  if (accept(TokenKind::Assign)) {
    declarator.init = parseAssignment();
    if (!declarator.init) return std::nullopt;
  }
  return declarator;
}

// expression-stmt = expression ";" ;
ast::StmtPtr Parser::parseExpressionStmt() {
  const uint32_t begin = current().range.begin;
  auto expr = parseExpression();
  if (!expr || !expectSemicolon("after expression")) {
    synchronize(SyncLevel::Statement);
    return nullptr;
  }
  return std::make_unique<ast::ExprStmt>(rangeFrom(begin), std::move(expr));
}

// condition = "(" expression ")" ;
HeaderStatus Parser::parseCondition(std::string_view keyword, ast::ExprPtr& condition) {
  const size_t open = pos_;
  if (!expect(TokenKind::LParen, fmt::format("after '{}'", keyword))) {
    synchronize(SyncLevel::Statement);
    return HeaderStatus::Dropped;
  }
  condition = parseExpression();
  if (condition && expectClosing(TokenKind::RParen, tokens_[open], fmt::format("after '{}' condition", keyword))) {
    return HeaderStatus::Ok;
  }
  skipToMatchingParen(open);
  return HeaderStatus::SkippedToBody;
}

// if-stmt = "if" condition statement [ "else" statement ] ;
ast::StmtPtr Parser::parseIf() {
  const uint32_t begin = advance().range.begin;
  auto stmt = std::make_unique<ast::IfStmt>(SourceRange{});
  const HeaderStatus header = parseCondition("if", stmt->condition);
  if (header == HeaderStatus::Dropped) return nullptr;
  stmt->thenBranch = parseStatement();
  bool ok = header == HeaderStatus::Ok && stmt->thenBranch;
  if (accept(TokenKind::KwElse)) {
    stmt->elseBranch = parseStatement();
    ok = ok && stmt->elseBranch;
  }
  if (!ok) return nullptr;
  stmt->range = rangeFrom(begin);
  return stmt;
}

// for-stmt = "for" for-header statement ;
ast::StmtPtr Parser::parseFor() {
  const uint32_t begin = advance().range.begin;
  auto stmt = std::make_unique<ast::ForStmt>(SourceRange{});
  const HeaderStatus header = parseForHeader(*stmt);
  if (header == HeaderStatus::Dropped) return nullptr;
  stmt->body = parseStatement();
  if (header != HeaderStatus::Ok || !stmt->body) return nullptr;
  stmt->range = rangeFrom(begin);
  return stmt;
}

// for-header = "(" ( local-decl | [ expression ] ";" ) [ expression ] ";" [ expression ] ")" ;
HeaderStatus Parser::parseForHeader(ast::ForStmt& stmt) {
  const size_t open = pos_;
  if (!expect(TokenKind::LParen, "after 'for'")) {
    synchronize(SyncLevel::Statement);
    return HeaderStatus::Dropped;
  }
  bool ok = true;
  if (atLocalDecl()) {
    stmt.init = parseLocalDecl();
    ok = stmt.init != nullptr;
  } else if (!accept(TokenKind::Semicolon)) {
    const uint32_t begin = current().range.begin;
    auto init = parseExpression();
    ok = init && expect(TokenKind::Semicolon, "after for-loop initializer");
    if (ok) stmt.init = std::make_unique<ast::ExprStmt>(rangeFrom(begin), std::move(init));
  }
  if (ok && !at(TokenKind::Semicolon)) {
    stmt.condition = parseExpression();
    ok = stmt.condition != nullptr;
  }
  ok = ok && expect(TokenKind::Semicolon, "after for-loop condition");
  if (ok && !at(TokenKind::RParen)) {
    stmt.step = parseExpression();
    ok = stmt.step != nullptr;
  }
  if (ok && expectClosing(TokenKind::RParen, tokens_[open], "after for-loop header")) return HeaderStatus::Ok;
  skipToMatchingParen(open);
  return HeaderStatus::SkippedToBody;
}

// while-stmt = "while" condition statement ;
ast::StmtPtr Parser::parseWhile() {
  const uint32_t begin = advance().range.begin;
  auto stmt = std::make_unique<ast::WhileStmt>(SourceRange{});
  const HeaderStatus header = parseCondition("while", stmt->condition);
  if (header == HeaderStatus::Dropped) return nullptr;
  stmt->body = parseStatement();
  if (header != HeaderStatus::Ok || !stmt->body) return nullptr;
  stmt->range = rangeFrom(begin);
  return stmt;
}

// do-stmt = "do" statement "while" condition ";" ;
ast::StmtPtr Parser::parseDoWhile() {
  const uint32_t begin = advance().range.begin;
  auto stmt = std::make_unique<ast::DoWhileStmt>(SourceRange{});
  stmt->body = parseStatement();
  if (!expect(TokenKind::KwWhile, "after do-loop body")) {
    synchronize(SyncLevel::Statement);
    return nullptr;
  }
  const HeaderStatus header = parseCondition("while", stmt->condition);
  if (header == HeaderStatus::Dropped) return nullptr;
  if (header != HeaderStatus::Ok || !stmt->body) {
    accept(TokenKind::Semicolon);
    return nullptr;
  }
  if (!expectSemicolon("after do-while loop")) {
    synchronize(SyncLevel::Statement);
    return nullptr;
  }
  stmt->range = rangeFrom(begin);
  return stmt;
}

// jump-stmt = ( "break" | "continue" | "discard" ) ";" ;
ast::StmtPtr Parser::parseJump() {
  const Token& keyword = advance();
  if (!expectSemicolon(fmt::format("after '{}'", keyword.text))) {
    synchronize(SyncLevel::Statement);
    return nullptr;
  }
  const SourceRange range = rangeFrom(keyword.range.begin);
  switch (keyword.kind) {
    case TokenKind::KwBreak: return std::make_unique<ast::BreakStmt>(range);
    case TokenKind::KwContinue: return std::make_unique<ast::ContinueStmt>(range);
    default: return std::make_unique<ast::DiscardStmt>(range);
  }
}

// return-stmt = "return" [ expression ] ";" ;
ast::StmtPtr Parser::parseReturn() {
  const uint32_t begin = advance().range.begin;
  ast::ExprPtr value;
  if (startsExpression()) {
    value = parseExpression();
    if (!value) {
      synchronize(SyncLevel::Statement);
      return nullptr;
    }
  }
  if (!expectSemicolon("after return statement")) {
    synchronize(SyncLevel::Statement);
    return nullptr;
  }
  return std::make_unique<ast::ReturnStmt>(rangeFrom(begin), std::move(value));
}

}  // namespace spire::parser_detail
