#include "scene/json_document.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <unordered_map>

#include "support/hex_digit.h"
#include "support/utf8.h"

namespace spire::scene {
namespace {

bool isDigit(char c) { return c >= '0' && c <= '9'; }
bool isWordChar(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || isDigit(c) || c == '_'; }

void appendUtf8(std::string& out, uint32_t codePoint) {
  if (codePoint < 0x80) {
    out += static_cast<char>(codePoint);
  } else if (codePoint < 0x800) {
    out += static_cast<char>(0xC0 | (codePoint >> 6));
    out += static_cast<char>(0x80 | (codePoint & 0x3F));
  } else if (codePoint < 0x10000) {
    out += static_cast<char>(0xE0 | (codePoint >> 12));
    out += static_cast<char>(0x80 | ((codePoint >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (codePoint & 0x3F));
  } else {
    out += static_cast<char>(0xF0 | (codePoint >> 18));
    out += static_cast<char>(0x80 | ((codePoint >> 12) & 0x3F));
    out += static_cast<char>(0x80 | ((codePoint >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (codePoint & 0x3F));
  }
}

// The code point of `bytes`, one well-formed UTF-8 sequence.
uint32_t decodeUtf8(std::string_view bytes) {
  const auto byte = [&](size_t i) { return static_cast<uint32_t>(static_cast<uint8_t>(bytes[i])); };
  if (bytes.size() == 1) return byte(0);
  uint32_t codePoint = byte(0) & (0x7Fu >> bytes.size());
  for (size_t i = 1; i < bytes.size(); ++i) codePoint = (codePoint << 6) | (byte(i) & 0x3Fu);
  return codePoint;
}

// The decimal exponent of a number's leading significant digit, so that a
// literal out of a double's range can be told apart as overflow or underflow.
// `literal` matches the JSON number grammar.
int64_t leadingDigitExponent(std::string_view literal) {
  size_t pos = literal[0] == '-' ? 1 : 0;
  const size_t intBegin = pos;
  while (pos < literal.size() && isDigit(literal[pos])) ++pos;
  int64_t magnitude = static_cast<int64_t>(pos - intBegin) - 1;
  if (literal[intBegin] == '0' && pos < literal.size() && literal[pos] == '.') {
    ++pos;
    magnitude = -1;
    while (pos < literal.size() && literal[pos] == '0') {
      --magnitude;
      ++pos;
    }
  }
  const size_t e = literal.find_first_of("eE");
  if (e == std::string_view::npos) return magnitude;
  pos = e + 1;
  const bool negative = literal[pos] == '-';
  if (literal[pos] == '-' || literal[pos] == '+') ++pos;
  // Saturating: an exponent of a million digits must not overflow the sum.
  int64_t exponent = 0;
  for (; pos < literal.size(); ++pos) exponent = std::min<int64_t>(exponent * 10 + (literal[pos] - '0'), 1'000'000'000);
  return magnitude + (negative ? -exponent : exponent);
}

class JsonParser {
 public:
  JsonParser(std::string_view text, FileId file, DiagnosticList& diags) : text_(text), file_(file), diags_(diags) {}

  std::optional<JsonValue> parseDocument() {
    if (text_.starts_with("\xEF\xBB\xBF")) {
      fail(0, 3, "the file starts with a byte order mark, which JSON does not allow; save it as UTF-8 without a BOM");
      return std::nullopt;
    }
    if (const size_t bad = utf8::firstInvalidByte(text_); bad != std::string_view::npos) {
      const auto offset = static_cast<uint32_t>(bad);
      fail(offset, offset + 1, "the file is not valid UTF-8 text");
      return std::nullopt;
    }
    JsonValue root;
    skipWhitespace();
    if (!parseValue(root, 0)) return std::nullopt;
    skipWhitespace();
    if (!atEnd()) {
      unexpected("the end of the file after the top-level value");
      return std::nullopt;
    }
    return root;
  }

 private:
  bool atEnd() const { return pos_ >= text_.size(); }
  char peek() const { return atEnd() ? '\0' : text_[pos_]; }
  uint32_t position() const { return static_cast<uint32_t>(pos_); }

  void skipWhitespace() {
    while (!atEnd() && (peek() == ' ' || peek() == '\t' || peek() == '\n' || peek() == '\r')) ++pos_;
  }

  bool fail(uint32_t begin, uint32_t end, std::string message) {
    diags_.report(DiagCode::E7001, {file_, begin, end}, std::move(message));
    return false;
  }

  // Reports "expected X, found Y" at the current position, where Y is the
  // word, character or end of file found there.
  bool unexpected(std::string_view expected) {
    const auto begin = position();
    if (atEnd()) return fail(begin, begin, fmt::format("expected {}, found the end of the file", expected));
    const char c = peek();
    size_t length = 1;
    std::string found;
    if (isWordChar(c)) {
      while (pos_ + length < text_.size() && isWordChar(text_[pos_ + length])) ++length;
      found = fmt::format("'{}'", text_.substr(pos_, length));
    } else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7F) {
      found = fmt::format("control character U+{:04X}", static_cast<unsigned>(c));
    } else if (static_cast<unsigned char>(c) >= 0x80) {
      length = utf8::sequenceLength(text_, pos_);
      found = fmt::format("U+{:04X} '{}'", decodeUtf8(text_.substr(pos_, length)), text_.substr(pos_, length));
    } else {
      found = fmt::format("'{}'", c);
    }
    std::string hint;
    if (c == '/' && pos_ + 1 < text_.size() && (text_[pos_ + 1] == '/' || text_[pos_ + 1] == '*')) {
      hint = " (JSON does not allow comments)";
    } else if (c == '\'') {
      hint = " (JSON strings use double quotes)";
    }
    return fail(begin, begin + static_cast<uint32_t>(length),
                fmt::format("expected {}, found {}{}", expected, found, hint));
  }

  bool parseValue(JsonValue& out, uint32_t depth) {
    const uint32_t begin = position();
    bool ok = false;
    switch (peek()) {
      case '{': ok = parseObject(out, depth); break;
      case '[': ok = parseArray(out, depth); break;
      case '"':
        out.kind = JsonKind::String;
        ok = parseString(out.string);
        break;
      case '-':
      case '0':
      case '1':
      case '2':
      case '3':
      case '4':
      case '5':
      case '6':
      case '7':
      case '8':
      case '9': ok = parseNumber(out); break;
      default: ok = parseLiteral(out); break;
    }
    out.range = {file_, begin, position()};
    return ok;
  }

  bool parseLiteral(JsonValue& out) {
    size_t length = 0;
    while (pos_ + length < text_.size() && isWordChar(text_[pos_ + length])) ++length;
    const std::string_view word = text_.substr(pos_, length);
    if (word == "true" || word == "false") {
      out.kind = JsonKind::Bool;
      out.boolean = word == "true";
    } else if (word == "null") {
      out.kind = JsonKind::Null;
    } else {
      return unexpected("a JSON value");
    }
    pos_ += length;
    return true;
  }

  bool skipDigits() {
    const size_t begin = pos_;
    while (isDigit(peek())) ++pos_;
    return pos_ > begin;
  }

  bool parseNumber(JsonValue& out) {
    const uint32_t begin = position();
    if (peek() == '-') ++pos_;
    if (peek() == '0') {
      ++pos_;
      if (isDigit(peek())) return fail(begin, position() + 1, "leading zeros are not allowed in a JSON number");
    } else if (!skipDigits()) {
      return unexpected("a digit after '-'");
    }
    if (peek() == '.') {
      ++pos_;
      if (!skipDigits()) return unexpected("a digit after the decimal point");
    }
    if (peek() == 'e' || peek() == 'E') {
      ++pos_;
      if (peek() == '+' || peek() == '-') ++pos_;
      if (!skipDigits()) return unexpected("a digit in the exponent");
    }
    const std::string_view literal = text_.substr(begin, pos_ - begin);
    out.kind = JsonKind::Number;
    const auto [end, error] = std::from_chars(literal.data(), literal.data() + literal.size(), out.number);
    if (error == std::errc::result_out_of_range) {
      if (leadingDigitExponent(literal) >= 0) {
        return fail(begin, position(), fmt::format("number {} is too large for a double", literal));
      }
      out.number = literal[0] == '-' ? -0.0 : 0.0;
    } else if (error != std::errc() || end != literal.data() + literal.size()) {
      return fail(begin, position(), fmt::format("malformed number {}", literal));
    }
    return true;
  }

  // Four hex digits after "\u" at `escape`; the code unit, or nullopt after
  // reporting.
  std::optional<uint32_t> parseCodeUnit(size_t escape) {
    uint32_t unit = 0;
    for (size_t i = escape + 2; i < escape + 6; ++i) {
      const std::optional<uint32_t> digit = i < text_.size() ? hexDigitValue(text_[i]) : std::nullopt;
      if (!digit) {
        fail(static_cast<uint32_t>(escape), static_cast<uint32_t>(std::min(i + 1, text_.size())),
             "expected four hexadecimal digits after '\\u'");
        return std::nullopt;
      }
      unit = unit * 16 + *digit;
    }
    pos_ = escape + 6;
    return unit;
  }

  bool parseUnicodeEscape(std::string& out) {
    const size_t escape = pos_;
    const std::optional<uint32_t> unit = parseCodeUnit(escape);
    if (!unit) return false;
    const auto escapeBegin = static_cast<uint32_t>(escape);
    if (*unit >= 0xDC00 && *unit <= 0xDFFF) {
      return fail(escapeBegin, position(),
                  fmt::format("unpaired UTF-16 low surrogate '\\u{:04X}' (it must follow a high surrogate)", *unit));
    }
    if (*unit < 0xD800 || *unit > 0xDBFF) {
      appendUtf8(out, *unit);
      return true;
    }
    if (!text_.substr(pos_).starts_with("\\u")) {
      return fail(escapeBegin, position(),
                  fmt::format("unpaired UTF-16 high surrogate '\\u{:04X}' (a low surrogate '\\uDC00'-'\\uDFFF' must "
                              "follow)",
                              *unit));
    }
    const std::optional<uint32_t> low = parseCodeUnit(pos_);
    if (!low) return false;
    if (*low < 0xDC00 || *low > 0xDFFF) {
      return fail(escapeBegin, position(),
                  fmt::format("unpaired UTF-16 high surrogate '\\u{:04X}' (a low surrogate '\\uDC00'-'\\uDFFF' must "
                              "follow)",
                              *unit));
    }
    appendUtf8(out, 0x10000 + ((*unit - 0xD800) << 10) + (*low - 0xDC00));
    return true;
  }

  bool parseEscape(std::string& out) {
    const uint32_t begin = position();
    if (pos_ + 1 >= text_.size()) return fail(begin, begin + 1, "unterminated string: the file ends inside it");
    const char c = text_[pos_ + 1];
    const char* simple = nullptr;
    switch (c) {
      case '"': simple = "\""; break;
      case '\\': simple = "\\"; break;
      case '/': simple = "/"; break;
      case 'b': simple = "\b"; break;
      case 'f': simple = "\f"; break;
      case 'n': simple = "\n"; break;
      case 'r': simple = "\r"; break;
      case 't': simple = "\t"; break;
      case 'u': return parseUnicodeEscape(out);
      default: break;
    }
    if (simple == nullptr) {
      if (static_cast<unsigned char>(c) < 0x20) {
        return fail(begin, begin + 1,
                    fmt::format("invalid escape sequence: '\\' followed by control character U+{:04X}",
                                static_cast<unsigned>(c)));
      }
      const size_t length = 1 + utf8::sequenceLength(text_, pos_ + 1);
      return fail(begin, begin + static_cast<uint32_t>(length),
                  fmt::format("invalid escape sequence '{}'", text_.substr(pos_, length)));
    }
    out += simple;
    pos_ += 2;
    return true;
  }

  // At the opening quote.
  bool parseString(std::string& out) {
    const uint32_t quote = position();
    ++pos_;
    while (true) {
      if (atEnd()) return fail(quote, position(), "unterminated string: the file ends inside it");
      const char c = peek();
      if (c == '"') {
        ++pos_;
        return true;
      }
      if (c == '\n' || c == '\r') {
        return fail(quote, position(),
                    "unterminated string: a string cannot span lines (write '\\n' for a line break)");
      }
      if (static_cast<unsigned char>(c) < 0x20) {
        return fail(position(), position() + 1,
                    fmt::format("control character U+{:04X} must be escaped in a string", static_cast<unsigned>(c)));
      }
      if (c == '\\') {
        if (!parseEscape(out)) return false;
        continue;
      }
      out += c;
      ++pos_;
    }
  }

  bool enter(uint32_t depth) {
    if (depth < kMaxJsonDepth) return true;
    return fail(position(), position() + 1,
                fmt::format("arrays and objects are nested more than {} levels deep", kMaxJsonDepth));
  }

  // At '{'.
  bool parseObject(JsonValue& out, uint32_t depth) {
    if (!enter(depth)) return false;
    out.kind = JsonKind::Object;
    ++pos_;
    skipWhitespace();
    if (peek() == '}') {
      ++pos_;
      return true;
    }
    std::unordered_map<std::string, size_t> indexByKey;
    std::optional<uint32_t> comma;  // the last separator, for a trailing comma's error
    while (true) {
      if (peek() != '"') {
        if (comma && peek() == '}') return fail(*comma, *comma + 1, "trailing comma before '}' is not allowed in JSON");
        return unexpected("a string key in double quotes");
      }
      JsonMember member;
      const uint32_t keyBegin = position();
      if (!parseString(member.key)) return false;
      member.keyRange = {file_, keyBegin, position()};
      skipWhitespace();
      if (peek() != ':') return unexpected("':' after an object key");
      ++pos_;
      skipWhitespace();
      if (!parseValue(member.value, depth + 1)) return false;
      const auto [first, inserted] = indexByKey.try_emplace(member.key, out.members.size());
      if (inserted) {
        out.members.push_back(std::move(member));
      } else {
        diags_.report(DiagCode::E7007, member.keyRange, fmt::format("duplicate key {}", quotedForMessage(member.key)))
            .note(out.members[first->second].keyRange, "first defined here");
      }
      skipWhitespace();
      if (peek() == '}') {
        ++pos_;
        return true;
      }
      if (peek() != ',') return unexpected("',' or '}' after an object member");
      comma = position();
      ++pos_;
      skipWhitespace();
    }
  }

  // At '['.
  bool parseArray(JsonValue& out, uint32_t depth) {
    if (!enter(depth)) return false;
    out.kind = JsonKind::Array;
    ++pos_;
    skipWhitespace();
    if (peek() == ']') {
      ++pos_;
      return true;
    }
    std::optional<uint32_t> comma;  // the last separator, for a trailing comma's error
    while (true) {
      if (comma && peek() == ']') return fail(*comma, *comma + 1, "trailing comma before ']' is not allowed in JSON");
      JsonValue element;
      if (!parseValue(element, depth + 1)) return false;
      out.elements.push_back(std::move(element));
      skipWhitespace();
      if (peek() == ']') {
        ++pos_;
        return true;
      }
      if (peek() != ',') return unexpected("',' or ']' after an array element");
      comma = position();
      ++pos_;
      skipWhitespace();
    }
  }

  std::string_view text_;
  FileId file_;
  DiagnosticList& diags_;
  size_t pos_ = 0;
};

}  // namespace

std::string_view describeJsonKind(JsonKind kind) {
  switch (kind) {
    case JsonKind::Null: return "null";
    case JsonKind::Bool: return "a boolean";
    case JsonKind::Number: return "a number";
    case JsonKind::String: return "a string";
    case JsonKind::Array: return "an array";
    case JsonKind::Object: return "an object";
  }
  return "a value";
}

std::string quotedForMessage(std::string_view text) {
  std::string out = "'";
  for (const char c : text) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7F) {
      out += fmt::format("\\u{:04X}", static_cast<unsigned>(c));
    } else {
      out += c;
    }
  }
  return out + "'";
}

const JsonMember* JsonValue::find(std::string_view key) const {
  for (const JsonMember& member : members) {
    if (member.key == key) return &member;
  }
  return nullptr;
}

std::optional<JsonValue> parseJson(const SourceManager& sources, FileId file, DiagnosticList& diags) {
  return JsonParser(sources.file(file).text, file, diags).parseDocument();
}

}  // namespace spire::scene
