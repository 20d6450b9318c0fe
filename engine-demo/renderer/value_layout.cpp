#include "renderer/value_layout.h"

#include <cstring>
#include <string>

namespace spire::engine {

namespace {

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

void writeValue(std::span<std::byte> memory, const BlockMember& member, std::span<const double> values) {
  const ValueType& type = member.type;
  if (!type.isNumeric()) return;
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

std::vector<double> readValue(std::span<const std::byte> memory, const BlockMember& member) {
  const ValueType& type = member.type;
  std::vector<double> values;
  if (!type.isNumeric()) return values;
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
