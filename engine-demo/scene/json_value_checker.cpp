#include "scene/json_value_checker.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>

namespace spire::scene {

std::string quotedList(const KeyList& names, std::string_view conjunction) {
  std::string text;
  for (size_t i = 0; i < names.size(); ++i) {
    if (i > 0) text += i + 1 == names.size() ? fmt::format(" {} ", conjunction) : ", ";
    text += fmt::format("'{}'", names[i]);
  }
  return text;
}

std::optional<std::string> suggestedChoice(std::string_view written, const KeyList& names) {
  const auto lower = [](unsigned char c) { return std::tolower(c); };
  for (std::string_view name : names) {
    if (std::ranges::equal(name, written, {}, lower, lower)) return std::string(name);
  }
  return closestSpelling(written, names);
}

bool Bounds::contains(double x) const {
  return (minExclusive ? x > min : x >= min) && (maxExclusive ? x < max : x <= max);
}

std::string Bounds::describe() const {
  const bool hasMin = min > -kMaxFloat;
  const bool hasMax = max < kMaxFloat;
  if (hasMin && hasMax && !minExclusive && !maxExclusive) return fmt::format("between {} and {}", min, max);
  std::string text;
  if (hasMin) text = fmt::format("{} {}", minExclusive ? "greater than" : "at least", min);
  if (hasMin && hasMax) text += " and ";
  if (hasMax) text += fmt::format("{} {}", maxExclusive ? "less than" : "at most", max);
  return text.empty() ? "within the range of a float" : text;
}

Bounds atLeast(double min) {
  Bounds bounds;
  bounds.min = min;
  return bounds;
}

Bounds greaterThan(double min) {
  Bounds bounds = atLeast(min);
  bounds.minExclusive = true;
  return bounds;
}

Bounds between(double min, double max) {
  Bounds bounds = atLeast(min);
  bounds.max = max;
  return bounds;
}

std::string JsonValueChecker::kindOf(const JsonValue& value) {
  if (!value.is(JsonKind::Array)) return std::string(describeJsonKind(value.kind));
  const size_t count = value.elements.size();
  if (count == 0) return "an empty array";
  return fmt::format("an array of {} element{}", count, count == 1 ? "" : "s");
}

std::string JsonValueChecker::written(const JsonValue& value) const {
  if (value.is(JsonKind::String)) return quotedForMessage(value.string);
  if (value.is(JsonKind::Number)) return std::string(sources_.text(value.range));
  return kindOf(value);
}

bool JsonValueChecker::expectKind(const JsonValue& value, JsonKind kind, std::string_view what) {
  if (value.is(kind)) return true;
  diags_.report(DiagCode::E7003, value.range,
                fmt::format("{} must be {}, found {}", what, describeJsonKind(kind), kindOf(value)));
  return false;
}

bool JsonValueChecker::expectArray(const JsonValue& value, std::string_view what, size_t minCount, size_t maxCount,
                                   std::string_view shape) {
  if (value.is(JsonKind::Array) && value.elements.size() >= minCount && value.elements.size() <= maxCount) return true;
  diags_.report(DiagCode::E7003, value.range, fmt::format("{} must be {}, found {}", what, shape, kindOf(value)));
  return false;
}

std::optional<double> JsonValueChecker::number(const JsonValue& value, std::string_view what, const Bounds& bounds) {
  if (!expectKind(value, JsonKind::Number, what)) return std::nullopt;
  if (!bounds.contains(value.number)) {
    diags_.report(DiagCode::E7004, value.range,
                  fmt::format("{} must be {}, found {}", what, bounds.describe(), written(value)));
    return std::nullopt;
  }
  return value.number;
}

std::optional<float> JsonValueChecker::real(const JsonValue& value, std::string_view what, const Bounds& bounds) {
  const std::optional<double> x = number(value, what, bounds);
  if (!x) return std::nullopt;
  return static_cast<float>(*x);
}

std::optional<uint32_t> JsonValueChecker::integer(const JsonValue& value, std::string_view what, uint32_t min,
                                                  uint32_t max) {
  if (!expectKind(value, JsonKind::Number, what)) return std::nullopt;
  if (std::floor(value.number) != value.number) {
    diags_.report(DiagCode::E7003, value.range, fmt::format("{} must be an integer, found {}", what, written(value)));
    return std::nullopt;
  }
  const std::optional<double> x = number(value, what, between(min, max));
  if (!x) return std::nullopt;
  return static_cast<uint32_t>(*x);
}

std::optional<bool> JsonValueChecker::flag(const JsonValue& value, std::string_view what) {
  if (!expectKind(value, JsonKind::Bool, what)) return std::nullopt;
  return value.boolean;
}

std::optional<std::string> JsonValueChecker::text(const JsonValue& value, std::string_view what) {
  if (!expectKind(value, JsonKind::String, what)) return std::nullopt;
  if (value.string.empty()) {
    diags_.report(DiagCode::E7004, value.range, fmt::format("{} must not be empty", what));
    return std::nullopt;
  }
  return value.string;
}

// Every element of an already checked array, each reported on its own.
std::optional<std::vector<float>> JsonValueChecker::components(const JsonValue& array, std::string_view what,
                                                               const Bounds& bounds) {
  const std::string elementWhat = fmt::format("each element of {}", what);
  std::vector<float> result;
  for (const JsonValue& element : array.elements) {
    if (const std::optional<float> x = real(element, elementWhat, bounds)) result.push_back(*x);
  }
  if (result.size() != array.elements.size()) return std::nullopt;
  return result;
}

std::optional<glm::vec3> JsonValueChecker::vector3(const JsonValue& value, std::string_view what,
                                                   const Bounds& bounds) {
  if (!expectArray(value, what, 3, 3, "an array of 3 numbers [x, y, z]")) return std::nullopt;
  const std::optional<std::vector<float>> xyz = components(value, what, bounds);
  if (!xyz) return std::nullopt;
  return glm::vec3((*xyz)[0], (*xyz)[1], (*xyz)[2]);
}

std::optional<glm::vec3> JsonValueChecker::nonZeroVector(const JsonValue& value, std::string_view what) {
  const std::optional<glm::vec3> v = vector3(value, what);
  if (v && glm::length(*v) == 0.0F) {
    diags_.report(DiagCode::E7004, value.range, fmt::format("{} must not be the zero vector", what));
    return std::nullopt;
  }
  return v;
}

std::optional<glm::vec4> JsonValueChecker::color(const JsonValue& value, std::string_view what, bool withAlpha) {
  const bool ok = withAlpha ? expectArray(value, what, 3, 4, "an array of 3 or 4 numbers [r, g, b] or [r, g, b, a]")
                            : expectArray(value, what, 3, 3, "an array of 3 numbers [r, g, b]");
  if (!ok) return std::nullopt;
  const std::optional<std::vector<float>> rgba = components(value, what, between(0.0, 1.0));
  if (!rgba) return std::nullopt;
  glm::vec4 result(1.0F);
  for (size_t i = 0; i < rgba->size(); ++i) result[static_cast<glm::length_t>(i)] = (*rgba)[i];
  return result;
}

void JsonValueChecker::unknownKey(const JsonMember& member, const KeyList& allowed, std::string_view where) {
  const std::optional<std::string> suggestion = closestSpelling(member.key, allowed);
  std::string message = fmt::format("unknown key {} in {}", quotedForMessage(member.key), where);
  if (suggestion) message += fmt::format("; did you mean '{}'?", *suggestion);
  Diagnostic& diagnostic = diags_.report(DiagCode::E7002, member.keyRange, std::move(message));
  if (!suggestion) diagnostic.note({}, fmt::format("expected one of {}", quotedList(allowed, "or")));
}

void JsonValueChecker::missing(const JsonValue& object, std::string message) {
  diags_.report(DiagCode::E7005, object.openingRange(), std::move(message));
}

}  // namespace spire::scene
