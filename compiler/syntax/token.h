// Tokens produced by the lexer (lexer.h) and consumed by the parser.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>

#include "support/source_manager.h"

namespace spire {

enum class TokenKind : uint8_t {
#define SPIRE_TOKEN(kind, description) kind,
#define SPIRE_KEYWORD(kind, spelling) kind,
#define SPIRE_PUNCT(kind, spelling) kind,
#include "syntax/token_kinds.def"
};

// A file is lexed whole before it is parsed, so a token's size counts: the
// flags come first to pack beside the kind (32 bytes rather than 40).
struct Token {
  TokenKind kind = TokenKind::EndOfFile;
  // The lexer already reported an error for this token (an unterminated
  // string, a bad number, or, on the end-of-file token, an unterminated
  // comment). The parser stays quiet about it to avoid a second error.
  bool malformed = false;
  // A stray character the lexer reported and skipped stood right before this
  // token; an error here is usually that character's consequence.
  bool followsStray = false;
  SourceRange range;
  // The token as written; points into the SourceManager's copy of the file.
  std::string_view text;
};
static_assert(sizeof(Token) <= 32);

namespace detail {
inline constexpr std::array kTokenSpellings = {
#define SPIRE_TOKEN(kind, description) std::string_view(description),
#define SPIRE_KEYWORD(kind, spelling) std::string_view(spelling),
#define SPIRE_PUNCT(kind, spelling) std::string_view(spelling),
#include "syntax/token_kinds.def"
};
}  // namespace detail

// The fixed spelling of a keyword or punctuator (`while`, `->`), or a
// description of a token class (`identifier`).
constexpr std::string_view tokenSpelling(TokenKind kind) { return detail::kTokenSpellings[static_cast<size_t>(kind)]; }

constexpr bool hasFixedSpelling(TokenKind kind) {
  return kind != TokenKind::EndOfFile && kind != TokenKind::Identifier && kind != TokenKind::IntLiteral &&
         kind != TokenKind::FloatLiteral && kind != TokenKind::StringLiteral;
}

// How diagnostics name a token kind: `';'` or `identifier`.
inline std::string describeToken(TokenKind kind) {
  const std::string_view spelling = tokenSpelling(kind);
  return hasFixedSpelling(kind) ? "'" + std::string(spelling) + "'" : std::string(spelling);
}

}  // namespace spire
