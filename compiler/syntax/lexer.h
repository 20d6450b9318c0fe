// The Spire lexer: turns one source file into tokens. See docs/language.md
// ("Lexical structure") for what it accepts.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "support/diagnostic.h"
#include "support/source_manager.h"
#include "syntax/token.h"

namespace spire {

// Lexes the whole of `file`. Lexical errors (E1001-E1005) are reported to
// `diags` and lexing continues, so the result is always usable: it ends with
// exactly one EndOfFile token and skips stray characters and comments.
std::vector<Token> lexFile(const SourceManager& sources, FileId file, DiagnosticList& diags);

struct IntLiteralValue {
  uint64_t value = 0;
  bool isUnsigned = false;
};

// The values of literal tokens. A token the lexer marked malformed has
// already been diagnosed and yields zero / its best-effort text.
IntLiteralValue intLiteralValue(const Token& token);
double floatLiteralValue(const Token& token);
// The contents of a string literal without quotes, escapes resolved.
std::string stringLiteralValue(const Token& token);

// The inverse of stringLiteralValue: `value` as a quoted, escaped literal.
std::string quoteString(std::string_view value);

}  // namespace spire
