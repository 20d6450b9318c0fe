#include "syntax/parser.h"

#include <fmt/format.h>

#include <algorithm>

#include "syntax/lexer.h"
#include "syntax/parser_impl.h"

namespace spire {
namespace parser_detail {

Parser::Parser(const SourceManager& sources, FileId file, ast::Program& program, DiagnosticList& diags,
               const ParseLimits& limits)
    : sources_(sources),
      file_(file),
      program_(program),
      diags_(diags),
      limits_(limits),
      tokens_(lexFile(sources, file, diags)) {}

// ---------------------------------------------------------------------------
// Tokens

const Token& Parser::peek(size_t ahead) const { return tokens_[std::min(pos_ + ahead, tokens_.size() - 1)]; }

const Token& Parser::advance() {
  const Token& token = tokens_[pos_];
  if (!atEnd()) ++pos_;
  return token;
}

bool Parser::accept(TokenKind kind) {
  if (!at(kind)) return false;
  advance();
  return true;
}

SourceRange Parser::rangeFrom(uint32_t begin) const { return {file_, begin, std::max(begin, previous().range.end)}; }

// Only the line is needed, which a binary search finds without the column
// computation of SourceManager::lineCol (linear in the line's length).
uint32_t Parser::lineOf(uint32_t offset) const {
  const std::vector<uint32_t>& starts = sources_.file(file_).lineStarts;
  return static_cast<uint32_t>(std::upper_bound(starts.begin(), starts.end(), offset) - starts.begin());
}

// ---------------------------------------------------------------------------
// Diagnostics and recovery

Diagnostic& Parser::report(DiagCode code, SourceRange where, std::string message) {
  // A second error at the same token, or next to a token the lexer already
  // complained about, is almost always a consequence of the first.
  const bool cascade =
      pos_ == lastErrorPos_ || current().malformed || current().followsStray || (pos_ > 0 && previous().malformed);
  if (cascade) {
    scratch_ = {};
    return scratch_;
  }
  lastErrorPos_ = pos_;
  return diags_.report(code, where, std::move(message));
}

Diagnostic& Parser::reportMissing(std::string message) {
  SourceRange where = current().range;
  if (pos_ > 0 && lineOf(current().range.begin) > lineOf(previous().range.end)) {
    where = {file_, previous().range.end, previous().range.end};
  }
  return report(DiagCode::E2001, where, std::move(message));
}

Diagnostic& Parser::reportUnexpected(DiagCode code, std::string message) {
  const SourceRange where =
      atEnd() && pos_ > 0 ? SourceRange{file_, previous().range.end, previous().range.end} : current().range;
  return report(code, where, std::move(message));
}

bool Parser::expect(TokenKind kind, std::string_view context) {
  if (accept(kind)) return true;
  reportMissing(fmt::format("expected {} {}", describeToken(kind), context));
  return false;
}

bool Parser::expectName(std::string_view what) {
  if (accept(TokenKind::Identifier)) return true;
  reportMissing(fmt::format("expected {} after '{}'", what, previous().text));
  return false;
}

bool Parser::expectClosing(TokenKind kind, const Token& opening, std::string_view context) {
  if (accept(kind)) return true;
  reportMissing(fmt::format("expected {} {}", describeToken(kind), context))
      .note(opening.range, fmt::format("to match this '{}'", opening.text));
  return false;
}

bool Parser::expectSemicolon(std::string_view context) {
  if (expect(TokenKind::Semicolon, context)) return true;
  return atEnd() || at(TokenKind::RBrace) || lineOf(current().range.begin) > lineOf(previous().range.end);
}

bool Parser::nestDeeper() {
  if (++depth_ <= limits_.maxNesting) return true;
  if (!nestingReported_) {
    nestingReported_ = true;
    report(DiagCode::E2004, current().range, fmt::format("nesting too deep (the limit is {})", limits_.maxNesting));
  }
  return false;
}

// A top-level declaration plausibly starts here: a declaration keyword with
// what must follow it, so that a stray keyword (`shader a += b;`) is not taken
// for one.
bool Parser::atKeywordDeclarationStart() const {
  const bool named = peek(1).kind == TokenKind::Identifier;
  switch (current().kind) {
    case TokenKind::KwUsing: return peek(1).kind == TokenKind::StringLiteral;
    case TokenKind::KwPipeline:
    case TokenKind::KwGroup:
    case TokenKind::KwStruct: return named && peek(2).kind == TokenKind::LBrace;
    case TokenKind::KwShader: return named && (peek(2).kind == TokenKind::KwUsing || peek(2).kind == TokenKind::Colon);
    default: return false;
  }
}

// The same, or `type name (` of a function. A return type with array sizes
// is not recognized, which keeps the check constant-time where recovery
// applies it to every token.
bool Parser::atDeclarationStart() const {
  return atKeywordDeclarationStart() ||
         (at(TokenKind::Identifier) && peek(1).kind == TokenKind::Identifier && peek(2).kind == TokenKind::LParen);
}

bool Parser::stopsRecovery(SyncLevel level) const {
  switch (current().kind) {
    case TokenKind::KwWorld:
    case TokenKind::KwImport:
    case TokenKind::KwAbstract:
    case TokenKind::At: return level == SyncLevel::Member;
    case TokenKind::KwIf:
    case TokenKind::KwFor:
    case TokenKind::KwWhile:
    case TokenKind::KwDo:
    case TokenKind::KwReturn:
    case TokenKind::KwBreak:
    case TokenKind::KwContinue:
    case TokenKind::KwDiscard:
    case TokenKind::KwConst: return level == SyncLevel::Statement;
    default: return level != SyncLevel::Statement && atDeclarationStart();
  }
}

// Skips the rest of a broken construct: through the next `;`, or through a
// complete `{ ... }` (and a `;` right after it), or up to a `}` that belongs
// to an enclosing construct, or up to a token that starts a new construct.
void Parser::synchronize(SyncLevel level) {
  size_t braces = 0;
  while (!atEnd()) {
    const TokenKind kind = current().kind;
    if (braces == 0 && (kind == TokenKind::RBrace || stopsRecovery(level))) return;
    advance();
    if (kind == TokenKind::LBrace) ++braces;
    const bool ended = braces == 0 ? kind == TokenKind::Semicolon : kind == TokenKind::RBrace && --braces == 0;
    if (!ended) continue;
    if (kind == TokenKind::RBrace) accept(TokenKind::Semicolon);
    // A whole `if` statement includes its `else` branch.
    if (level != SyncLevel::WholeConstruct || !at(TokenKind::KwElse)) return;
  }
  // Recovery ran into the end of the file: whatever is missing there (a '}',
  // a ')') is part of the error already reported.
  lastErrorPos_ = pos_;
}

// After an error inside `( ... )`, continues after the matching ')'. Stops
// early at a brace, which cannot occur inside the parentheses.
void Parser::skipToMatchingParen(size_t openIndex) {
  pos_ = openIndex;
  size_t depth = 0;
  while (!atEnd() && !at(TokenKind::LBrace) && !at(TokenKind::RBrace)) {
    const TokenKind kind = advance().kind;
    if (kind == TokenKind::LParen || kind == TokenKind::LBracket) ++depth;
    if ((kind == TokenKind::RParen || kind == TokenKind::RBracket) && --depth == 0) return;
  }
  if (atEnd()) lastErrorPos_ = pos_;
}

// Skips a `{ ... }` starting at the current '{' without parsing it; used when
// it is nested too deeply to parse.
void Parser::skipBalancedBlock() {
  size_t depth = 0;
  do {
    const TokenKind kind = advance().kind;
    if (kind == TokenKind::LBrace) ++depth;
    if (kind == TokenKind::RBrace) --depth;
  } while (depth > 0 && !atEnd());
  if (atEnd()) lastErrorPos_ = pos_;
}

// A list in braces (members, fields, statements) ends at its '}', or where a
// missing '}' is evident because a new top-level declaration starts: no
// member or statement can start like one.
bool Parser::atEndOfList() const { return at(TokenKind::RBrace) || shouldStop() || atDeclarationStart(); }

// Reports a token that cannot start anything here (E2003) and skips what it
// begins. A '{' starts a block that recovery skips as a whole; any other
// token is dropped first, as recovery might otherwise stop right at it.
void Parser::rejectUnexpected(std::string message, SyncLevel level) {
  report(DiagCode::E2003, current().range, std::move(message));
  if (!at(TokenKind::LBrace) && advance().kind == TokenKind::Semicolon) return;
  synchronize(level);
}

// A construct that fails on its first token, where recovery stops again
// because that token could start the next construct, would be retried
// forever; dropping the token guarantees progress.
void Parser::ensureProgress(size_t before) {
  if (pos_ == before) advance();
}

// ---------------------------------------------------------------------------
// Module and GLSL declarations

// module = { top-level-decl } end-of-file ;
std::unique_ptr<ast::Module> Parser::parseModule() {
  auto module = std::make_unique<ast::Module>();
  module->file = file_;
  while (!shouldStop()) {
    const size_t before = pos_;
    auto decl = parseTopLevelDecl();
    ensureProgress(before);
    if (decl) {
      module->decls.push_back(std::move(decl));
      continue;
    }
    // Lost at the top level, typically among statements spilled out of a
    // function whose braces do not match: skip to the next declaration
    // rather than report every line.
    while (!atEnd() && !atDeclarationStart()) advance();
  }
  return module;
}

// top-level-decl = using-decl | struct-decl | pipeline-decl | shader-decl
//                | group-decl | function-decl ;
ast::DeclPtr Parser::parseTopLevelDecl() {
  switch (current().kind) {
    case TokenKind::KwUsing: return parseUsing();
    case TokenKind::KwStruct: return parseStruct();
    case TokenKind::KwPipeline: return parsePipeline();
    case TokenKind::KwShader: return parseShader();
    case TokenKind::KwGroup: return parseGroup();
    default:
      if (atTypedName()) return parseFunction();
      rejectUnexpected("expected a declaration", SyncLevel::TopLevel);
      return nullptr;
  }
}

// using-decl = "using" string-literal ";" ;
ast::DeclPtr Parser::parseUsing() {
  const uint32_t begin = advance().range.begin;
  if (!expect(TokenKind::StringLiteral, "after 'using'")) {
    synchronize(SyncLevel::TopLevel);
    return nullptr;
  }
  const Token& path = previous();
  auto decl = std::make_unique<ast::UsingDecl>(SourceRange{});
  decl->path = stringLiteralValue(path);
  decl->pathRange = path.range;
  if (!expectSemicolon("after using declaration")) {
    synchronize(SyncLevel::TopLevel);
    return nullptr;
  }
  decl->range = rangeFrom(begin);
  return decl;
}

// struct-decl = "struct" identifier "{" { struct-field } "}" ";" ;
ast::DeclPtr Parser::parseStruct() {
  const uint32_t begin = advance().range.begin;
  if (!expectName("a struct name")) {
    synchronize(SyncLevel::TopLevel);
    return nullptr;
  }
  auto decl = std::make_unique<ast::StructDecl>(SourceRange{});
  decl->name = previous().text;
  decl->nameRange = previous().range;
  const Token& open = current();
  if (!expect(TokenKind::LBrace, "after struct name")) {
    synchronize(SyncLevel::TopLevel);
    return nullptr;
  }
  while (!atEndOfList()) {
    const size_t before = pos_;
    parseStructField(*decl);
    ensureProgress(before);
  }
  if (expectClosing(TokenKind::RBrace, open, fmt::format("at end of struct '{}'", decl->name))) {
    // GLSL requires the ';'; a missing one is reported but loses nothing.
    expect(TokenKind::Semicolon, "after struct declaration");
  }
  decl->range = rangeFrom(begin);
  return decl;
}

// struct-field = type identifier { array-dim } { "," identifier { array-dim } } ";" ;
void Parser::parseStructField(ast::StructDecl& decl) {
  auto type = parseType();
  if (!type) return synchronize(SyncLevel::Member);
  std::vector<ast::StructField> fields;
  do {
    if (!expectName("a field name")) return synchronize(SyncLevel::Member);
    ast::StructField field;
    field.name = previous().text;
    field.nameRange = previous().range;
    if (!parseArrayDims(field.arraySizes)) return synchronize(SyncLevel::Member);
    fields.push_back(std::move(field));
  } while (accept(TokenKind::Comma));
  if (!expectSemicolon("after struct field")) return synchronize(SyncLevel::Member);
  // `float a, b;` declares two fields, each with its own copy of the type.
  for (size_t i = 0; i < fields.size(); ++i) {
    fields[i].type = i + 1 < fields.size() ? cloneType(*type) : std::move(*type);
    decl.fields.push_back(std::move(fields[i]));
  }
}

// function-decl = type identifier "(" param-list ")" ( block | ";" ) ;
ast::DeclPtr Parser::parseFunction() {
  const uint32_t begin = current().range.begin;
  auto decl = std::make_unique<ast::FunctionDecl>(SourceRange{});
  auto returnType = parseType();
  if (!returnType || !expectName("a function name")) {
    synchronize(SyncLevel::TopLevel);
    return nullptr;
  }
  decl->returnType = std::move(*returnType);
  decl->name = previous().text;
  decl->nameRange = previous().range;
  if (at(TokenKind::Assign) || at(TokenKind::Semicolon) || at(TokenKind::Comma) || at(TokenKind::LBracket)) {
    report(DiagCode::E2003, decl->nameRange,
           "file-scope variables are not supported; declare a component in a pipeline or shader instead");
    synchronize(SyncLevel::TopLevel);
    return nullptr;
  }
  const size_t open = pos_;
  if (!expect(TokenKind::LParen, "after function name")) {
    synchronize(SyncLevel::TopLevel);
    return nullptr;
  }
  if (!parseParamList(decl->params) || !expectClosing(TokenKind::RParen, tokens_[open], "after parameters")) {
    // Still parse the body, so that errors in it are reported too.
    skipToMatchingParen(open);
    if (at(TokenKind::LBrace)) {
      parseBlock();
    } else {
      synchronize(SyncLevel::TopLevel);
    }
    return nullptr;
  }
  if (at(TokenKind::LBrace)) {
    decl->body = parseBlock();
    if (!decl->body) return nullptr;
  } else if (!expectSemicolon("after function prototype")) {
    synchronize(SyncLevel::TopLevel);
    return nullptr;
  }
  decl->range = rangeFrom(begin);
  return decl;
}

// param-list = [ "void" | param { "," param } ] ;
bool Parser::parseParamList(std::vector<ast::Param>& params) {
  if (at(TokenKind::RParen)) return true;
  if (at(TokenKind::Identifier) && current().text == "void" && peek(1).kind == TokenKind::RParen) {
    advance();
    return true;
  }
  do {
    auto param = parseParam();
    if (!param) return false;
    params.push_back(std::move(*param));
  } while (accept(TokenKind::Comma));
  return true;
}

// param = [ "const" ] [ "in" | "out" | "inout" ] type [ identifier { array-dim } ] ;
std::optional<ast::Param> Parser::parseParam() {
  ast::Param param;
  const uint32_t begin = current().range.begin;
  param.isConst = accept(TokenKind::KwConst);
  if (accept(TokenKind::KwIn)) {
    param.explicitIn = true;
  } else if (accept(TokenKind::KwOut)) {
    param.direction = ast::ParamDirection::Out;
  } else if (accept(TokenKind::KwInout)) {
    param.direction = ast::ParamDirection::InOut;
  }
  auto type = parseType();
  if (!type) return std::nullopt;
  param.type = std::move(*type);
  if (accept(TokenKind::Identifier)) {
    param.name = previous().text;
    param.nameRange = previous().range;
    if (!parseArrayDims(param.arraySizes)) return std::nullopt;
  }
  param.range = rangeFrom(begin);
  return param;
}

// type = identifier { array-dim } ;
std::optional<ast::TypeSyntax> Parser::parseType() {
  if (!at(TokenKind::Identifier)) {
    reportUnexpected(DiagCode::E2007, "expected a type");
    return std::nullopt;
  }
  ast::TypeSyntax type;
  const Token& name = advance();
  type.name = name.text;
  type.nameRange = name.range;
  if (!parseArrayDims(type.arraySizes)) return std::nullopt;
  type.range = rangeFrom(name.range.begin);
  return type;
}

// { array-dim }, where
// array-dim = "[" conditional-expr "]" ;
bool Parser::parseArrayDims(std::vector<ast::ExprPtr>& dims) {
  while (at(TokenKind::LBracket)) {
    const Token& open = advance();
    auto size = parseConditional();
    if (!size || !expectClosing(TokenKind::RBracket, open, "after array size")) return false;
    dims.push_back(std::move(size));
  }
  return true;
}

// standalone-expression = expression EOF ;
ast::ExprPtr Parser::parseStandaloneExpression() {
  ast::ExprPtr expr = parseExpression();
  if (expr && !atEnd()) {
    reportUnexpected(DiagCode::E2001, fmt::format("unexpected {} after the expression", describeToken(current().kind)));
    return nullptr;
  }
  return expr;
}

}  // namespace parser_detail

std::unique_ptr<ast::Module> parseModule(const SourceManager& sources, FileId file, ast::Program& program,
                                         DiagnosticList& diags, const ParseLimits& limits) {
  return parser_detail::Parser(sources, file, program, diags, limits).parseModule();
}

ast::ExprPtr parseStandaloneExpression(const SourceManager& sources, FileId file, ast::Program& program,
                                       DiagnosticList& diags, const ParseLimits& limits) {
  return parser_detail::Parser(sources, file, program, diags, limits).parseStandaloneExpression();
}

}  // namespace spire
