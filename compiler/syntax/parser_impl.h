// Private to the parser: the recursive-descent Parser shared by parser.cpp
// (infrastructure and GLSL declarations), parse_decl.cpp (Spire
// declarations), parse_stmt.cpp and parse_expr.cpp. Every parse method
// implements one grammar rule, quoted in EBNF above its definition; the
// whole grammar is in docs/language.md.
//
// Error recovery follows one convention. Methods that parse a declaration,
// a member or a statement report an error, synchronize (skip to a `;` or `}`)
// and return null/nothing when they had to drop the construct. Methods for
// smaller pieces (types, expressions, attributes, strategy references) return
// null/false without skipping anything and leave recovery to their caller.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "syntax/ast.h"
#include "syntax/ast_spelling.h"
#include "syntax/parser.h"
#include "syntax/token.h"

namespace spire::parser_detail {

// Where recovery stops skipping: besides `;` and `}`, before a token that
// can only start a construct of that level.
// `WholeConstruct` stops only at `;` and braces, to skip a statement that is
// nested too deeply however many statements it contains.
enum class SyncLevel { Statement, Member, TopLevel, WholeConstruct };

// How a parenthesized header of `if`, `while` or `for` went. After an error
// inside the parentheses the parser skips to the closing ')' and still parses
// the body, so errors there are reported too.
enum class HeaderStatus { Ok, SkippedToBody, Dropped };

class Parser {
 public:
  Parser(const SourceManager& sources, FileId file, ast::Program& program, DiagnosticList& diags,
         const ParseLimits& limits);

  std::unique_ptr<ast::Module> parseModule();
  ast::ExprPtr parseStandaloneExpression();

 private:
  // Restores the nesting depth when a construct is left, however it is left.
  class DepthScope {
   public:
    explicit DepthScope(Parser& parser) : parser_(parser), saved_(parser.depth_) {}
    ~DepthScope() { parser_.depth_ = saved_; }
    DepthScope(const DepthScope&) = delete;
    DepthScope& operator=(const DepthScope&) = delete;

   private:
    Parser& parser_;
    uint32_t saved_;
  };

  // --- Tokens (parser.cpp)
  const Token& current() const { return tokens_[pos_]; }
  const Token& peek(size_t ahead) const;
  const Token& previous() const { return tokens_[pos_ == 0 ? 0 : pos_ - 1]; }
  bool at(TokenKind kind) const { return current().kind == kind; }
  bool atEnd() const { return at(TokenKind::EndOfFile); }
  bool shouldStop() const { return atEnd() || diags_.limitReached(); }
  const Token& advance();
  bool accept(TokenKind kind);
  // From `begin` (a byte offset) to the end of the last consumed token.
  SourceRange rangeFrom(uint32_t begin) const;
  uint32_t lineOf(uint32_t offset) const;

  // --- Diagnostics and recovery (parser.cpp)
  Diagnostic& report(DiagCode code, SourceRange where, std::string message);
  // A missing token (E2001): right after the previous token when the current
  // one is on a later line, where the token belongs (like clang's "expected
  // ';'"), otherwise at the current token.
  Diagnostic& reportMissing(std::string message);
  // A token that cannot be what is needed here (E2002, E2007): at the token,
  // or after the last one at the end of the file.
  Diagnostic& reportUnexpected(DiagCode code, std::string message);
  bool expect(TokenKind kind, std::string_view context);
  // An identifier naming `what` ("a shader name") after the previous token.
  bool expectName(std::string_view what);
  bool expectClosing(TokenKind kind, const Token& opening, std::string_view context);
  // A ';' missing before a line break or a '}' is reported and then assumed,
  // so that nothing else is lost; returns false when recovery should skip.
  bool expectSemicolon(std::string_view context);
  // One level deeper (undone by the enclosing DepthScope); false beyond the
  // limit, after reporting E2004 the first time.
  bool nestDeeper();
  void synchronize(SyncLevel level);
  bool stopsRecovery(SyncLevel level) const;
  void rejectUnexpected(std::string message, SyncLevel level);
  void skipToMatchingParen(size_t openIndex);
  void skipBalancedBlock();
  void ensureProgress(size_t before);
  bool atEndOfList() const;
  bool atKeywordDeclarationStart() const;
  bool atDeclarationStart() const;

  // --- GLSL declarations (parser.cpp)
  ast::DeclPtr parseTopLevelDecl();
  ast::DeclPtr parseUsing();
  ast::DeclPtr parseStruct();
  void parseStructField(ast::StructDecl& decl);
  ast::DeclPtr parseFunction();
  bool parseParamList(std::vector<ast::Param>& params);
  std::optional<ast::Param> parseParam();
  std::optional<ast::TypeSyntax> parseType();
  bool parseArrayDims(std::vector<ast::ExprPtr>& dims);

  // --- Spire declarations (parse_decl.cpp)
  ast::DeclPtr parsePipeline();
  void parsePipelineMember(ast::PipelineDecl& decl);
  std::optional<ast::WorldDecl> parseWorld(uint32_t begin, std::vector<ast::Attribute> attributes);
  std::optional<ast::ImportDecl> parseImport(uint32_t begin, std::vector<ast::Attribute> attributes);
  std::optional<ast::StrategyRef> parseStrategyRef();
  ast::DeclPtr parseShader();
  void parseShaderMember(ast::ShaderDecl& decl);
  ast::DeclPtr parseGroup();
  std::optional<ast::GroupEntry> parseGroupEntry();
  std::optional<std::vector<ast::Attribute>> parseAttributes();
  bool startsComponent() const;
  void parseComponentDecl(uint32_t begin, const std::vector<ast::Attribute>& attributes,
                          std::vector<ast::ComponentDecl>& out);
  bool parseComponentName(ast::ComponentDecl& decl);
  void closeMembers(const Token& open, std::string_view what);

  // --- Statements (parse_stmt.cpp)
  std::unique_ptr<ast::BlockStmt> parseBlock();
  ast::StmtPtr parseStatement();
  ast::StmtPtr parseUnattributedStatement();
  bool atLocalDecl() const;
  bool atTypedName() const;
  std::unique_ptr<ast::VarDeclStmt> parseLocalDecl();
  std::optional<ast::VarDeclarator> parseVarDeclarator();
  ast::StmtPtr parseExpressionStmt();
  ast::StmtPtr parseIf();
  ast::StmtPtr parseFor();
  HeaderStatus parseForHeader(ast::ForStmt& stmt);
  ast::StmtPtr parseWhile();
  ast::StmtPtr parseDoWhile();
  HeaderStatus parseCondition(std::string_view keyword, ast::ExprPtr& condition);
  ast::StmtPtr parseJump();
  ast::StmtPtr parseReturn();

  // --- Expressions (parse_expr.cpp)
  template <typename T, typename... Args>
  std::unique_ptr<T> makeExpr(Args&&... args) {
    auto expr = std::make_unique<T>(std::forward<Args>(args)...);
    expr->id = program_.exprCount++;
    return expr;
  }
  ast::ExprPtr parseExpression();
  ast::ExprPtr parseAssignment();
  ast::ExprPtr parseConditional();
  ast::ExprPtr parseBinary(ast::Precedence minPrecedence);
  ast::ExprPtr parseUnary();
  ast::ExprPtr parsePostfix();
  ast::ExprPtr parsePrimary();
  ast::ExprPtr parseNameOrCall();
  bool parseArguments(std::vector<ast::ExprPtr>& args, std::string_view context);
  bool startsExpression() const;
  ast::TypeSyntax cloneType(const ast::TypeSyntax& type);
  ast::ExprPtr cloneExpr(const ast::Expr& expr);

  const SourceManager& sources_;
  FileId file_;
  ast::Program& program_;
  DiagnosticList& diags_;
  ParseLimits limits_;
  std::vector<Token> tokens_;
  size_t pos_ = 0;
  uint32_t depth_ = 0;
  bool nestingReported_ = false;
  // The token of the last error; a second error there is a cascade.
  size_t lastErrorPos_ = SIZE_MAX;
  Diagnostic scratch_;  // returned instead of suppressed diagnostics
};

}  // namespace spire::parser_detail
