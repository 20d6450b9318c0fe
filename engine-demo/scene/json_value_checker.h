// Typed reads of JSON values for a file that is checked value by value (the
// scene file): each read either gives the value or reports why not, at the
// value's range (E7003 wrong type or shape, E7004 out of range, E7002 unknown
// key, E7005 missing field), and the caller keeps its default and goes on, so
// that one pass reports every error of a file.
#pragma once

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <fmt/format.h>

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "scene/json_document.h"
#include "support/diagnostic.h"
#include "support/source_manager.h"
#include "support/spelling.h"

namespace spire::scene {

using KeyList = std::vector<std::string_view>;

// "'a', 'b' or 'c'" when `conjunction` is "or".
std::string quotedList(const KeyList& names, std::string_view conjunction);

// The option `written` was probably meant to be: one that differs only in
// case ("rgba16f" is 'RGBA16F', not the nearer 'RGBA16'), else the closest
// spelling.
std::optional<std::string> suggestedChoice(std::string_view written, const KeyList& names);

inline constexpr double kMaxFloat = std::numeric_limits<float>::max();

// The numbers a value may take; by default anything a float can hold.
struct Bounds {
  double min = -kMaxFloat;
  double max = kMaxFloat;
  bool minExclusive = false;
  bool maxExclusive = false;

  bool contains(double x) const;
  // "between 0 and 1", "greater than 0 and less than 180", ...
  std::string describe() const;
};

Bounds atLeast(double min);
Bounds greaterThan(double min);
Bounds between(double min, double max);

class JsonValueChecker {
 public:
  JsonValueChecker(const SourceManager& sources, DiagnosticList& diags) : sources_(sources), diags_(diags) {}

  // "a string", or for an array how many elements it has: what a type error
  // says was found.
  static std::string kindOf(const JsonValue& value);
  // The value as written (a number's source text, a quoted string), for what
  // a range error says was found.
  std::string written(const JsonValue& value) const;

  // `what` names the value in messages, e.g. "'fovY'".
  bool expectKind(const JsonValue& value, JsonKind kind, std::string_view what);
  // An array of `minCount` to `maxCount` elements; `shape` describes it
  // ("an array of 3 numbers [x, y, z]").
  bool expectArray(const JsonValue& value, std::string_view what, size_t minCount, size_t maxCount,
                   std::string_view shape);

  std::optional<double> number(const JsonValue& value, std::string_view what, const Bounds& bounds);
  std::optional<float> real(const JsonValue& value, std::string_view what, const Bounds& bounds = {});
  // 1.5 where a count is expected is a type error, 0 a range error.
  std::optional<uint32_t> integer(const JsonValue& value, std::string_view what, uint32_t min, uint32_t max);
  // true or false.
  std::optional<bool> flag(const JsonValue& value, std::string_view what);
  // A string that is not empty.
  std::optional<std::string> text(const JsonValue& value, std::string_view what);
  // [x, y, z], each component within `bounds`.
  std::optional<glm::vec3> vector3(const JsonValue& value, std::string_view what, const Bounds& bounds = {});
  std::optional<glm::vec3> nonZeroVector(const JsonValue& value, std::string_view what);
  // [r, g, b] in [0, 1], or also [r, g, b, a] when `withAlpha` (alpha then
  // defaults to 1).
  std::optional<glm::vec4> color(const JsonValue& value, std::string_view what, bool withAlpha);

  // A string naming one of `options` (a "type", an address mode); an unknown
  // one gets a "did you mean" or the list of options.
  template <typename T>
  std::optional<T> choice(const JsonValue& value, std::string_view what,
                          const std::vector<std::pair<std::string_view, T>>& options) {
    if (!expectKind(value, JsonKind::String, what)) return std::nullopt;
    KeyList names;
    for (const auto& [name, option] : options) {
      if (name == value.string) return option;
      names.push_back(name);
    }
    std::string message = fmt::format("unknown {} {}", what, quotedForMessage(value.string));
    const std::optional<std::string> suggestion = suggestedChoice(value.string, names);
    message += suggestion ? fmt::format("; did you mean '{}'?", *suggestion)
                          : fmt::format(" (expected {})", quotedList(names, "or"));
    diags_.report(DiagCode::E7004, value.range, std::move(message));
    return std::nullopt;
  }

  // A key that `where` (e.g. "'camera'") does not have.
  void unknownKey(const JsonMember& member, const KeyList& allowed, std::string_view where);
  // A required key absent from `object`, reported at its opening brace.
  void missing(const JsonValue& object, std::string message);

 private:
  std::optional<std::vector<float>> components(const JsonValue& array, std::string_view what, const Bounds& bounds);

  const SourceManager& sources_;
  DiagnosticList& diags_;
};

}  // namespace spire::scene
