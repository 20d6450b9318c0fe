// A strict JSON (RFC 8259) reader that remembers where every value and every
// object key was written, so that a scene file can be checked value by value
// and each complaint rendered at its file:line:col like a compiler diagnostic.
// General-purpose JSON libraries drop positions, hence this small reader.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "support/diagnostic.h"
#include "support/source_manager.h"

namespace spire::scene {

enum class JsonKind { Null, Bool, Number, String, Array, Object };

// "a string", "an object", ... for messages such as "expected a number, found a string".
std::string_view describeJsonKind(JsonKind kind);

// `text` in single quotes for a message, with control characters escaped so
// that a key or name read from a file cannot break a diagnostic's line.
std::string quotedForMessage(std::string_view text);

struct JsonMember;

struct JsonValue {
  JsonKind kind = JsonKind::Null;
  SourceRange range;  // the whole value: quotes of a string, brackets of an array or object
  bool boolean = false;
  double number = 0.0;
  std::string string;  // unescaped UTF-8
  std::vector<JsonValue> elements;
  std::vector<JsonMember> members;  // in file order, keys unique

  bool is(JsonKind k) const { return kind == k; }
  // The member named `key`, or nullptr.
  const JsonMember* find(std::string_view key) const;
  // The first character only: where a complaint about the whole object or
  // array points, so that the caret does not underline a multi-line value.
  SourceRange openingRange() const { return {range.file, range.begin, range.begin + 1}; }
};

struct JsonMember {
  std::string key;
  SourceRange keyRange;  // with its quotes
  JsonValue value;
};

// Objects and arrays nested deeper than this are rejected, so hostile input
// cannot exhaust the stack of the recursive reader.
inline constexpr uint32_t kMaxJsonDepth = 128;

// Parses the whole text of `file`. A syntax error (E7001) stops the parse and
// gives nullopt. A repeated key in an object is reported (E7007) and dropped,
// and the document is still returned, so the caller can go on checking it.
std::optional<JsonValue> parseJson(const SourceManager& sources, FileId file, DiagnosticList& diags);

}  // namespace spire::scene
