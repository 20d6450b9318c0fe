// Spire's own declarations: pipelines, worlds, imports, shaders, groups and
// components.
#include <fmt/format.h>

#include "syntax/lexer.h"
#include "syntax/parser_impl.h"

namespace spire::parser_detail {

// Consumes the '}' that closes the list opened by `open`, and an optional ';'.
void Parser::closeMembers(const Token& open, std::string_view what) {
  if (expectClosing(TokenKind::RBrace, open, fmt::format("at end of {}", what))) accept(TokenKind::Semicolon);
}

// pipeline-decl = "pipeline" identifier "{" { pipeline-member } "}" [ ";" ] ;
ast::DeclPtr Parser::parsePipeline() {
  const uint32_t begin = advance().range.begin;
  if (!expectName("a pipeline name")) {
    synchronize(SyncLevel::TopLevel);
    return nullptr;
  }
  auto decl = std::make_unique<ast::PipelineDecl>(SourceRange{});
  decl->name = previous().text;
  decl->nameRange = previous().range;
  const Token& open = current();
  if (!expect(TokenKind::LBrace, "after pipeline name")) {
    synchronize(SyncLevel::TopLevel);
    return nullptr;
  }
  while (!atEndOfList()) {
    const size_t before = pos_;
    parsePipelineMember(*decl);
    ensureProgress(before);
  }
  closeMembers(open, fmt::format("pipeline '{}'", decl->name));
  decl->range = rangeFrom(begin);
  return decl;
}

// pipeline-member = { attribute } ( world-decl | import-decl | component-decl ) ;
void Parser::parsePipelineMember(ast::PipelineDecl& decl) {
  const uint32_t begin = current().range.begin;
  auto attributes = parseAttributes();
  if (!attributes) return synchronize(SyncLevel::Member);
  if (at(TokenKind::KwWorld) || (at(TokenKind::KwAbstract) && peek(1).kind == TokenKind::KwWorld)) {
    if (auto world = parseWorld(begin, std::move(*attributes))) decl.worlds.push_back(std::move(*world));
  } else if (at(TokenKind::KwImport)) {
    if (auto import = parseImport(begin, std::move(*attributes))) decl.imports.push_back(std::move(*import));
  } else if (startsComponent()) {
    parseComponentDecl(begin, *attributes, decl.components);
  } else {
    rejectUnexpected("expected a world, import or component declaration", SyncLevel::Member);
  }
}

// world-decl = [ "abstract" ] "world" identifier [ ":" string-literal ]
//              [ "export" strategy-ref ] ";" ;
std::optional<ast::WorldDecl> Parser::parseWorld(uint32_t begin, std::vector<ast::Attribute> attributes) {
  ast::WorldDecl world;
  world.attributes = std::move(attributes);
  world.isAbstract = accept(TokenKind::KwAbstract);
  advance();  // `world`
  bool ok = expectName("a world name");
  if (ok) {
    world.name = previous().text;
    world.nameRange = previous().range;
  }
  if (ok && accept(TokenKind::Colon)) {
    ok = expect(TokenKind::StringLiteral, "after ':' in world declaration");
    if (ok) {
      world.language = stringLiteralValue(previous());
      world.languageRange = previous().range;
    }
  }
  if (ok && accept(TokenKind::KwExport)) {
    world.exportStrategy = parseStrategyRef();
    ok = world.exportStrategy.has_value();
  }
  if (!ok || !expectSemicolon("after world declaration")) {
    synchronize(SyncLevel::Member);
    return std::nullopt;
  }
  world.range = rangeFrom(begin);
  return world;
}

// import-decl = "import" identifier "->" identifier "using" strategy-ref ";" ;
std::optional<ast::ImportDecl> Parser::parseImport(uint32_t begin, std::vector<ast::Attribute> attributes) {
  ast::ImportDecl import;
  import.attributes = std::move(attributes);
  advance();  // `import`
  bool ok = expectName("a world name");
  if (ok) {
    import.from = previous().text;
    import.fromRange = previous().range;
    ok = expect(TokenKind::Arrow, "after the source world of an import");
  }
  if (ok) ok = expectName("a world name");
  if (ok) {
    import.to = previous().text;
    import.toRange = previous().range;
    ok = expect(TokenKind::KwUsing, "after the target world of an import");
  }
  std::optional<ast::StrategyRef> strategy;
  if (ok) strategy = parseStrategyRef();
  if (!strategy || !expectSemicolon("after import declaration")) {
    synchronize(SyncLevel::Member);
    return std::nullopt;
  }
  import.strategy = std::move(*strategy);
  import.range = rangeFrom(begin);
  return import;
}

// strategy-ref = identifier [ arguments ] ;
std::optional<ast::StrategyRef> Parser::parseStrategyRef() {
  if (!expectName("a strategy name")) return std::nullopt;
  ast::StrategyRef ref;
  ref.name = previous().text;
  ref.nameRange = previous().range;
  if (at(TokenKind::LParen) && !parseArguments(ref.args, "after strategy arguments")) return std::nullopt;
  ref.range = rangeFrom(ref.nameRange.begin);
  return ref;
}

// shader-decl = "shader" identifier
//               ( "using" identifier | ":" identifier [ "finalizes" identifier { "," identifier } ] )
//               "{" { shader-member } "}" [ ";" ] ;
ast::DeclPtr Parser::parseShader() {
  const uint32_t begin = advance().range.begin;
  auto decl = std::make_unique<ast::ShaderDecl>(SourceRange{});
  const auto nameRef = [this] { return ast::NameRef{std::string(previous().text), previous().range}; };
  bool ok = expectName("a shader name");
  if (ok) {
    decl->name = previous().text;
    decl->nameRange = previous().range;
    if (accept(TokenKind::KwUsing)) {
      ok = expectName("a pipeline name");
      if (ok) decl->pipeline = nameRef();
    } else if (accept(TokenKind::Colon)) {
      ok = expectName("a base shader or group name");
      if (ok) decl->base = nameRef();
      if (ok && accept(TokenKind::KwFinalizes)) {
        do {
          ok = expectName("a world name");
          if (ok) decl->finalizes.push_back(nameRef());
        } while (ok && accept(TokenKind::Comma));
      }
    } else {
      reportMissing("expected 'using' or ':' after shader name");
      ok = false;
    }
  }
  const Token& open = current();
  if (!ok || !expect(TokenKind::LBrace, "after shader header")) {
    synchronize(SyncLevel::TopLevel);
    return nullptr;
  }
  while (!atEndOfList()) {
    const size_t before = pos_;
    parseShaderMember(*decl);
    ensureProgress(before);
  }
  closeMembers(open, fmt::format("shader '{}'", decl->name));
  decl->range = rangeFrom(begin);
  return decl;
}

// shader-member = { attribute } component-decl ;
void Parser::parseShaderMember(ast::ShaderDecl& decl) {
  const uint32_t begin = current().range.begin;
  auto attributes = parseAttributes();
  if (!attributes) return synchronize(SyncLevel::Member);
  if (startsComponent()) return parseComponentDecl(begin, *attributes, decl.components);
  rejectUnexpected(at(TokenKind::KwWorld) || at(TokenKind::KwImport)
                       ? "worlds and imports can only be declared in a pipeline"
                       : "expected a component declaration",
                   SyncLevel::Member);
}

// group-decl = "group" identifier "{" { group-entry } "}" [ ";" ] ;
ast::DeclPtr Parser::parseGroup() {
  const uint32_t begin = advance().range.begin;
  if (!expectName("a group name")) {
    synchronize(SyncLevel::TopLevel);
    return nullptr;
  }
  auto decl = std::make_unique<ast::GroupDecl>(SourceRange{});
  decl->name = previous().text;
  decl->nameRange = previous().range;
  const Token& open = current();
  if (!expect(TokenKind::LBrace, "after group name")) {
    synchronize(SyncLevel::TopLevel);
    return nullptr;
  }
  while (!atEndOfList()) {
    const size_t before = pos_;
    if (auto entry = parseGroupEntry()) decl->entries.push_back(std::move(*entry));
    ensureProgress(before);
  }
  closeMembers(open, fmt::format("group '{}'", decl->name));
  decl->range = rangeFrom(begin);
  return decl;
}

// group-entry = [ "optional" ] "shader" identifier ";" ;
std::optional<ast::GroupEntry> Parser::parseGroupEntry() {
  ast::GroupEntry entry;
  const uint32_t begin = current().range.begin;
  entry.isOptional = accept(TokenKind::KwOptional);
  if (!entry.isOptional && !at(TokenKind::KwShader)) {
    rejectUnexpected("expected a group entry ('shader Name;' or 'optional shader Name;')", SyncLevel::Member);
    return std::nullopt;
  }
  const bool ok = expect(TokenKind::KwShader, "after 'optional'") && expectName("a shader name");
  if (ok) entry.shader = {std::string(previous().text), previous().range};
  if (!ok || !expectSemicolon("after group entry")) {
    synchronize(SyncLevel::Member);
    return std::nullopt;
  }
  entry.range = rangeFrom(begin);
  return entry;
}

// attribute = "[" identifier [ ":" string-literal ] "]" ;
std::optional<std::vector<ast::Attribute>> Parser::parseAttributes() {
  std::vector<ast::Attribute> attributes;
  while (at(TokenKind::LBracket)) {
    const Token& open = advance();
    ast::Attribute& attribute = attributes.emplace_back();
    if (!expectName("an attribute name")) return std::nullopt;
    attribute.name = previous().text;
    if (accept(TokenKind::Colon)) {
      if (!expect(TokenKind::StringLiteral, "after ':' in attribute")) return std::nullopt;
      attribute.value = stringLiteralValue(previous());
      attribute.valueRange = previous().range;
    }
    if (!expectClosing(TokenKind::RBracket, open, "after attribute")) return std::nullopt;
    attribute.range = rangeFrom(open.range.begin);
  }
  return attributes;
}

bool Parser::startsComponent() const {
  return at(TokenKind::KwAbstract) || at(TokenKind::KwExport) || at(TokenKind::At) || at(TokenKind::Identifier);
}

// component-decl = [ "abstract" ] [ "export" ] [ "@" identifier ] type
//                  ( component-name block
//                  | component-name [ "=" assignment-expr ]
//                    { "," component-name [ "=" assignment-expr ] } ";" ) ;
//
// Each name becomes its own ComponentDecl sharing the attributes, flags,
// world and (a copy of) the type.
void Parser::parseComponentDecl(uint32_t begin, const std::vector<ast::Attribute>& attributes,
                                std::vector<ast::ComponentDecl>& out) {
  const bool isAbstract = accept(TokenKind::KwAbstract);
  const bool isExport = accept(TokenKind::KwExport);
  std::optional<std::string> world;
  SourceRange worldRange;
  if (accept(TokenKind::At)) {
    if (!expectName("a world name")) return synchronize(SyncLevel::Member);
    world = previous().text;
    worldRange = previous().range;
  }
  auto type = parseType();
  if (!type) return synchronize(SyncLevel::Member);

  std::vector<ast::ComponentDecl> decls(1);
  if (!parseComponentName(decls.front())) return synchronize(SyncLevel::Member);
  if (at(TokenKind::LBrace)) {
    decls.front().body = parseBlock();
    if (!decls.front().body) return;
    decls.front().range = rangeFrom(begin);
    if (at(TokenKind::Comma)) {
      report(DiagCode::E2006, current().range, "a component with a body block must be declared on its own");
      synchronize(SyncLevel::Member);
    }
  } else {
    while (true) {
      ast::ComponentDecl& decl = decls.back();
      if (accept(TokenKind::Assign)) {
        decl.init = parseAssignment();
        if (!decl.init) return synchronize(SyncLevel::Member);
      }
      decl.range = rangeFrom(begin);
      if (!accept(TokenKind::Comma)) break;
      if (!parseComponentName(decls.emplace_back())) return synchronize(SyncLevel::Member);
      if (at(TokenKind::LBrace)) {
        report(DiagCode::E2006, current().range, "a component with a body block must be declared on its own");
        parseBlock();
        return;
      }
    }
    if (!expectSemicolon("after component declaration")) return synchronize(SyncLevel::Member);
    decls.back().range = rangeFrom(begin);
  }

  for (size_t i = 0; i < decls.size(); ++i) {
    ast::ComponentDecl& decl = decls[i];
    decl.attributes = attributes;
    decl.isAbstract = isAbstract;
    decl.isExport = isExport;
    decl.world = world;
    decl.worldRange = worldRange;
    decl.type = i + 1 < decls.size() ? cloneType(*type) : std::move(*type);
    out.push_back(std::move(decl));
  }
}

// component-name = identifier [ ":" identifier ] ;
bool Parser::parseComponentName(ast::ComponentDecl& decl) {
  if (!expectName("a component name")) return false;
  decl.name = previous().text;
  decl.nameRange = previous().range;
  if (accept(TokenKind::Colon)) {
    if (!expectName("a variation name")) return false;
    decl.variation = previous().text;
    decl.variationRange = previous().range;
  }
  if (at(TokenKind::LBracket)) {
    report(DiagCode::E2006, current().range,
           "array dimensions of a component belong to its type, as in 'float[4] weights'");
    return false;
  }
  return true;
}

}  // namespace spire::parser_detail
