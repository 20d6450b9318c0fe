#include "renderer/value_layout.h"

#include <charconv>
#include <cstring>
#include <string>

namespace spire::engine {

namespace {

std::optional<ValueType> parseNonArray(std::string_view type) {
  ValueType result;
  if (type == "float" || type == "int" || type == "uint" || type == "bool") {
    result.scalar = type == "float" ? ValueType::Scalar::Float
                    : type == "int" ? ValueType::Scalar::Int
                    : type == "uint" ? ValueType::Scalar::Uint
                                     : ValueType::Scalar::Bool;
    return result;
  }
  const auto digit = [](char c) -> uint32_t { return c >= '2' && c <= '4' ? static_cast<uint32_t>(c - '0') : 0; };
  if (type.size() == 4 && type.substr(0, 3) == "vec" && digit(type[3])) {
    result.rows = digit(type[3]);
    return result;
  }
  if (type.size() == 5 && type.substr(1, 3) == "vec" && digit(type[4])) {
    switch (type[0]) {
      case 'i': result.scalar = ValueType::Scalar::Int; break;
      case 'u': result.scalar = ValueType::Scalar::Uint; break;
      case 'b': result.scalar = ValueType::Scalar::Bool; break;
      default: return std::nullopt;
    }
    result.rows = digit(type[4]);
    return result;
  }
  if (type.size() == 4 && type.substr(0, 3) == "mat" && digit(type[3])) {
    result.rows = result.columns = digit(type[3]);
    return result;
  }
  if (type.size() == 6 && type.substr(0, 3) == "mat" && digit(type[3]) && type[4] == 'x' && digit(type[5])) {
    result.columns = digit(type[3]);
    result.rows = digit(type[5]);
    return result;
  }
  return std::nullopt;
}

// Every scalar type the engine moves is 32 bits wide in std140 and std430.
constexpr uint32_t kScalarSize = 4;

// Byte offset of component `i` (in flat order) relative to the member start.
size_t componentOffset(const BlockMember& member, const ValueType& type, uint32_t i) {
  const uint32_t perElement = type.rows * type.columns;
  const uint32_t element = i / perElement;
  const uint32_t within = i % perElement;
  const uint32_t column = within / type.rows;
  const uint32_t row = within % type.rows;
  const uint32_t columnStride = type.isMatrix() ? member.matrixStride : type.rows * kScalarSize;
  return size_t{element} * member.arrayStride + size_t{column} * columnStride + size_t{row} * kScalarSize;
}

}  // namespace

std::optional<ValueType> parseValueType(std::string_view type) {
  const size_t bracket = type.find('[');
  if (bracket == std::string_view::npos) return parseNonArray(type);
  if (type.back() != ']' || type.find('[', bracket + 1) != std::string_view::npos) return std::nullopt;
  auto result = parseNonArray(type.substr(0, bracket));
  if (!result) return std::nullopt;
  const std::string_view digits = type.substr(bracket + 1, type.size() - bracket - 2);
  uint32_t length = 0;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), length);
  if (ec != std::errc{} || end != digits.data() + digits.size() || length == 0) return std::nullopt;
  result->arrayLength = length;
  return result;
}

void writeValue(std::span<std::byte> memory, const BlockMember& member, const ValueType& type,
                std::span<const double> values) {
  const uint32_t count = std::min<uint32_t>(type.componentCount(), static_cast<uint32_t>(values.size()));
  for (uint32_t i = 0; i < count; ++i) {
    const size_t offset = member.offset + componentOffset(member, type, i);
    if (offset + kScalarSize > memory.size()) return;
    std::byte* dest = memory.data() + offset;
    switch (type.scalar) {
      case ValueType::Scalar::Float: {
        const auto v = static_cast<float>(values[i]);
        std::memcpy(dest, &v, sizeof v);
        break;
      }
      case ValueType::Scalar::Int: {
        const auto v = static_cast<int32_t>(values[i]);
        std::memcpy(dest, &v, sizeof v);
        break;
      }
      case ValueType::Scalar::Uint: {
        const auto v = static_cast<uint32_t>(values[i]);
        std::memcpy(dest, &v, sizeof v);
        break;
      }
      case ValueType::Scalar::Bool: {
        const uint32_t v = values[i] != 0.0 ? 1U : 0U;
        std::memcpy(dest, &v, sizeof v);
        break;
      }
    }
  }
}

std::vector<double> readValue(std::span<const std::byte> memory, const BlockMember& member, const ValueType& type) {
  std::vector<double> values;
  values.reserve(type.componentCount());
  for (uint32_t i = 0; i < type.componentCount(); ++i) {
    const size_t offset = member.offset + componentOffset(member, type, i);
    if (offset + kScalarSize > memory.size()) break;
    const std::byte* src = memory.data() + offset;
    switch (type.scalar) {
      case ValueType::Scalar::Float: {
        float v = 0;
        std::memcpy(&v, src, sizeof v);
        values.push_back(v);
        break;
      }
      case ValueType::Scalar::Int: {
        int32_t v = 0;
        std::memcpy(&v, src, sizeof v);
        values.push_back(v);
        break;
      }
      case ValueType::Scalar::Uint:
      case ValueType::Scalar::Bool: {
        uint32_t v = 0;
        std::memcpy(&v, src, sizeof v);
        values.push_back(v);
        break;
      }
    }
  }
  return values;
}

}  // namespace spire::engine
