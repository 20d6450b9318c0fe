#include "syntax/lexer.h"

#include <fmt/format.h>

#include <cfloat>
#include <charconv>
#include <optional>
#include <unordered_map>

#include "support/utf8.h"

namespace spire {
namespace {

using SpellingMap = std::unordered_map<std::string_view, TokenKind>;

const SpellingMap& keywords() {
  static const SpellingMap map = {
#define SPIRE_KEYWORD(kind, spelling) {spelling, TokenKind::kind},
#include "syntax/token_kinds.def"
  };
  return map;
}

const SpellingMap& punctuators() {
  static const SpellingMap map = {
#define SPIRE_PUNCT(kind, spelling) {spelling, TokenKind::kind},
#include "syntax/token_kinds.def"
  };
  return map;
}
constexpr size_t kLongestPunctuator = 3;  // `<<=` and `>>=`

// Locale-independent character classes (<cctype> depends on the locale and
// is undefined for negative chars).
bool isDigit(char c) { return c >= '0' && c <= '9'; }
bool isAlpha(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); }
bool isIdentifierStart(char c) { return isAlpha(c) || c == '_'; }
bool isIdentifierChar(char c) { return isIdentifierStart(c) || isDigit(c); }
bool isHexDigit(char c) { return isDigit(c) || (c >= 'a' && c <= 'f') || (c >= 'A' && c <= 'F'); }
bool isLineEnd(char c) { return c == '\n' || c == '\r'; }

struct IntLiteralParts {
  std::string_view digits;
  int base = 10;
  bool isUnsigned = false;
};

// Splits a well-formed integer spelling into its digits, base and suffix.
IntLiteralParts splitIntLiteral(std::string_view s) {
  IntLiteralParts parts;
  if (!s.empty() && (s.back() == 'u' || s.back() == 'U')) {
    parts.isUnsigned = true;
    s.remove_suffix(1);
  }
  if (s.size() > 2 && s[0] == '0' && (s[1] == 'x' || s[1] == 'X')) {
    parts.base = 16;
    s.remove_prefix(2);
  } else if (s.size() > 1 && s[0] == '0') {
    parts.base = 8;
  }
  parts.digits = s;
  return parts;
}

// GLSL integers are 32 bits; the literal's bit pattern is used unchanged, so
// `0xFFFFFFFF` is a valid `int` (-1) and anything wider is an error.
std::optional<IntLiteralValue> decodeIntLiteral(std::string_view spelling) {
  const IntLiteralParts parts = splitIntLiteral(spelling);
  uint64_t value = 0;
  const char* end = parts.digits.data() + parts.digits.size();
  const auto [ptr, ec] = std::from_chars(parts.digits.data(), end, value, parts.base);
  if (ec != std::errc{} || ptr != end || value > UINT32_MAX) return std::nullopt;
  return IntLiteralValue{value, parts.isUnsigned};
}

// Floats are 32 bits: a literal beyond FLT_MAX (or beyond what a double can
// hold at all) is out of range.
std::optional<double> decodeFloatLiteral(std::string_view spelling) {
  if (!spelling.empty() && (spelling.back() == 'f' || spelling.back() == 'F')) spelling.remove_suffix(1);
  double value = 0;
  const char* end = spelling.data() + spelling.size();
  const auto [ptr, ec] = std::from_chars(spelling.data(), end, value);
  if (ec != std::errc{} || ptr != end || value > FLT_MAX) return std::nullopt;
  return value;
}

class Lexer {
 public:
  Lexer(const SourceManager& sources, FileId file, DiagnosticList& diags)
      : file_(file), text_(sources.file(file).text), diags_(diags) {}

  std::vector<Token> run() {
    skipByteOrderMark();
    for (skipTrivia(); pos_ < text_.size(); skipTrivia()) lexToken();
    tokens_.push_back({TokenKind::EndOfFile, endOfFileMalformed_, false, rangeFrom(pos_), {}});
    return std::move(tokens_);
  }

 private:
  char peek(size_t ahead = 0) const { return pos_ + ahead < text_.size() ? text_[pos_ + ahead] : '\0'; }
  SourceRange rangeFrom(size_t begin) const {
    return {file_, static_cast<uint32_t>(begin), static_cast<uint32_t>(pos_)};
  }
  void emit(TokenKind kind, size_t begin, bool malformed = false) {
    tokens_.push_back({kind, malformed, strayPending_, rangeFrom(begin), text_.substr(begin, pos_ - begin)});
    strayPending_ = false;
  }

  void skipByteOrderMark() {
    if (text_.substr(0, 3) == "\xEF\xBB\xBF") pos_ = 3;
  }

  void skipTrivia() {
    while (pos_ < text_.size()) {
      const char c = text_[pos_];
      if (c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f') {
        ++pos_;
      } else if (c == '/' && peek(1) == '/') {
        while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
      } else if (c == '/' && peek(1) == '*') {
        const size_t close = text_.find("*/", pos_ + 2);
        if (close == std::string_view::npos) {
          const size_t begin = pos_;
          pos_ += 2;
          diags_.report(DiagCode::E1002, rangeFrom(begin), "unterminated block comment");
          pos_ = text_.size();
          endOfFileMalformed_ = true;
        } else {
          pos_ = close + 2;
        }
      } else {
        return;
      }
    }
  }

  void lexToken() {
    const char c = text_[pos_];
    if (isIdentifierStart(c)) return lexIdentifier();
    if (isDigit(c) || (c == '.' && isDigit(peek(1)))) return lexNumber();
    if (c == '"') return lexString();
    if (!lexPunctuator()) lexStrayCharacter();
  }

  void lexIdentifier() {
    const size_t begin = pos_;
    while (isIdentifierChar(peek())) ++pos_;
    const auto keyword = keywords().find(text_.substr(begin, pos_ - begin));
    emit(keyword == keywords().end() ? TokenKind::Identifier : keyword->second, begin);
  }

  // Lexes the longest run that looks like a number, so that `1.5ex` or `0x`
  // give one error for the whole literal rather than a literal and a stray name.
  void lexNumber() {
    const size_t begin = pos_;
    bool isFloat = false;
    bool isHex = false;
    std::optional<std::string> problem;
    if (peek() == '0' && (peek(1) == 'x' || peek(1) == 'X')) {
      isHex = true;
      pos_ += 2;
      if (!isHexDigit(peek())) problem = "hexadecimal literal has no digits";
      while (isHexDigit(peek())) ++pos_;
    } else {
      while (isDigit(peek())) ++pos_;
      if (peek() == '.') {
        isFloat = true;
        ++pos_;
        while (isDigit(peek())) ++pos_;
      }
      if (peek() == 'e' || peek() == 'E') {
        isFloat = true;
        ++pos_;
        if (peek() == '+' || peek() == '-') ++pos_;
        if (!isDigit(peek())) problem = "exponent has no digits";
        while (isDigit(peek())) ++pos_;
      }
    }
    const size_t digitsEnd = pos_;
    if (isFloat && (peek() == 'l' || peek() == 'L') && (peek(1) == 'f' || peek(1) == 'F')) {
      pos_ += 2;
      if (!problem) problem = "double-precision literals are not supported; drop the 'lf' suffix";
    } else if (isFloat ? (peek() == 'f' || peek() == 'F') : (peek() == 'u' || peek() == 'U')) {
      ++pos_;
    }
    const size_t suffixBegin = pos_;
    while (isIdentifierChar(peek())) ++pos_;
    if (pos_ != suffixBegin && !problem) {
      problem = fmt::format("invalid suffix '{}' on {} literal", text_.substr(suffixBegin, pos_ - suffixBegin),
                            isFloat ? "floating-point" : "integer");
    }
    const std::string_view spelling = text_.substr(begin, pos_ - begin);
    if (!isFloat && !isHex && !problem && spelling.size() > 1 && spelling[0] == '0') {
      const size_t bad = spelling.substr(0, digitsEnd - begin).find_first_of("89");
      if (bad != std::string_view::npos) problem = fmt::format("invalid digit '{}' in octal literal", spelling[bad]);
    }

    const TokenKind kind = isFloat ? TokenKind::FloatLiteral : TokenKind::IntLiteral;
    if (problem) {
      diags_.report(DiagCode::E1004, rangeFrom(begin), *problem);
      return emit(kind, begin, true);
    }
    const bool inRange = isFloat ? decodeFloatLiteral(spelling).has_value() : decodeIntLiteral(spelling).has_value();
    if (!inRange) {
      diags_.report(DiagCode::E1005, rangeFrom(begin),
                    isFloat ? fmt::format("floating-point literal '{}' is out of range for 'float'", spelling)
                            : fmt::format("integer literal '{}' does not fit in 32 bits", spelling));
    }
    emit(kind, begin, !inRange);
  }

  void lexString() {
    const size_t begin = pos_++;
    bool malformed = false;
    while (true) {
      if (pos_ >= text_.size() || isLineEnd(text_[pos_])) {
        diags_.report(DiagCode::E1003, rangeFrom(begin), "unterminated string literal");
        return emit(TokenKind::StringLiteral, begin, true);
      }
      const char c = text_[pos_];
      if (c == '"') break;
      if (c == '\\' && (peek(1) == '"' || peek(1) == '\\')) {
        pos_ += 2;
      } else if (c == '\\' && pos_ + 1 < text_.size() && !isLineEnd(peek(1))) {
        const auto [shown, length] = describeCharAt(pos_ + 1);
        diags_.report(DiagCode::E1001, {file_, static_cast<uint32_t>(pos_), static_cast<uint32_t>(pos_ + 1 + length)},
                      fmt::format("unknown escape sequence '\\{}' in string literal (only '\\\"' and '\\\\' are "
                                  "allowed)",
                                  shown));
        malformed = true;
        pos_ += 1 + length;
      } else {
        ++pos_;
      }
    }
    ++pos_;
    emit(TokenKind::StringLiteral, begin, malformed);
  }

  bool lexPunctuator() {
    for (size_t length = kLongestPunctuator; length > 0; --length) {
      const auto found = punctuators().find(text_.substr(pos_, length));
      if (found != punctuators().end() && found->first.size() == length) {
        const size_t begin = pos_;
        pos_ += length;
        emit(found->second, begin);
        return true;
      }
    }
    return false;
  }

  void lexStrayCharacter() {
    const size_t begin = pos_;
    const auto [shown, length] = describeCharAt(pos_);
    pos_ += length;
    diags_.report(DiagCode::E1001, rangeFrom(begin), fmt::format("stray character '{}' in program", shown));
    strayPending_ = true;
  }

  // How a diagnostic shows the character at `at`, and its length in bytes.
  // Control characters and broken UTF-8 are escaped so that messages stay
  // valid, printable text.
  std::pair<std::string, size_t> describeCharAt(size_t at) const {
    const auto byte = static_cast<uint8_t>(text_[at]);
    const size_t length = utf8::sequenceLength(text_, at);
    if (length == 0 || byte < 0x20 || byte == 0x7F) return {fmt::format("\\x{:02X}", byte), 1};
    return {std::string(text_.substr(at, length)), length};
  }

  FileId file_;
  std::string_view text_;
  DiagnosticList& diags_;
  size_t pos_ = 0;
  bool strayPending_ = false;
  bool endOfFileMalformed_ = false;
  std::vector<Token> tokens_;
};

}  // namespace

std::vector<Token> lexFile(const SourceManager& sources, FileId file, DiagnosticList& diags) {
  return Lexer(sources, file, diags).run();
}

IntLiteralValue intLiteralValue(const Token& token) {
  if (token.malformed) return {};
  return decodeIntLiteral(token.text).value_or(IntLiteralValue{});
}

double floatLiteralValue(const Token& token) {
  if (token.malformed) return 0.0;
  return decodeFloatLiteral(token.text).value_or(0.0);
}

std::string stringLiteralValue(const Token& token) {
  std::string value;
  const std::string_view text = token.text;
  // Starts after the opening quote; an unterminated literal has no closing one.
  for (size_t i = 1; i < text.size() && text[i] != '"'; ++i) {
    if (text[i] == '\\' && i + 1 < text.size() && (text[i + 1] == '"' || text[i + 1] == '\\')) ++i;
    value += text[i];
  }
  return value;
}

std::string quoteString(std::string_view value) {
  std::string quoted = "\"";
  for (const char c : value) {
    if (c == '"' || c == '\\') quoted += '\\';
    quoted += c;
  }
  quoted += '"';
  return quoted;
}

}  // namespace spire
