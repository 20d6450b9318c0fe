#include "gen/value_type.h"

#include <fmt/format.h>

namespace spire::testgen {

const char* typeName(ValueType type) {
  switch (type) {
    case ValueType::Float: return "float";
    case ValueType::Vec2: return "vec2";
    case ValueType::Vec3: return "vec3";
    case ValueType::Vec4: return "vec4";
    case ValueType::Int: return "int";
    case ValueType::Mat3: return "mat3";
    case ValueType::Mat4: return "mat4";
    case ValueType::Sampler: return "sampler2D";
  }
  return "float";
}

namespace {

// Every type first becomes a float or a vec4, from which every target is
// reachable; the detour keeps the table small.
std::string toFloat(const std::string& v, ValueType from) {
  switch (from) {
    case ValueType::Float: return v;
    case ValueType::Int: return fmt::format("float({})", v);
    case ValueType::Mat3:
    case ValueType::Mat4: return fmt::format("{}[1].y", v);
    default: return fmt::format("{}.x", v);
  }
}

std::string toVec4(const std::string& v, ValueType from) {
  switch (from) {
    case ValueType::Vec2: return fmt::format("vec4({}, 0.5, 1.0)", v);
    case ValueType::Vec3: return fmt::format("vec4({}, 1.0)", v);
    case ValueType::Vec4: return v;
    case ValueType::Mat3: return fmt::format("vec4({}[2], 1.0)", v);
    case ValueType::Mat4: return fmt::format("{}[0]", v);
    default: return fmt::format("vec4({})", toFloat(v, from));
  }
}

}  // namespace

std::string convert(const std::string& value, ValueType from, ValueType to) {
  if (from == to) return value;
  switch (to) {
    case ValueType::Float: return toFloat(value, from);
    case ValueType::Int: return fmt::format("int({})", toFloat(value, from));
    case ValueType::Vec2:
      return from == ValueType::Float ? fmt::format("vec2({})", value) : fmt::format("{}.xy", toVec4(value, from));
    case ValueType::Vec3:
      return from == ValueType::Float ? fmt::format("vec3({})", value) : fmt::format("{}.xyz", toVec4(value, from));
    case ValueType::Vec4: return toVec4(value, from);
    case ValueType::Mat3: return fmt::format("mat3({})", toFloat(value, from));
    case ValueType::Mat4: return fmt::format("mat4({})", toFloat(value, from));
    case ValueType::Sampler: break;  // samplers are inputs only, never converted to
  }
  return value;
}

std::string literal(ValueType type, int salt) {
  const std::string f = fmt::format("{}.{}", salt % 3, (salt * 37) % 100);
  switch (type) {
    case ValueType::Int: return fmt::format("{}", salt % 7);
    case ValueType::Float: return f;
    default: return convert(f, ValueType::Float, type);
  }
}

}  // namespace spire::testgen
