// GLSL values as the engine moves them between the scene file, the CPU and
// GPU buffers: a type parsed from reflection (`float`, `vec3`, `mat3x4`,
// `ivec2`, `float[4]`) and flat lists of numbers (vectors in order, matrices
// column by column, arrays element by element), written to and read from
// std140/std430 memory at the offsets and strides reflection gives.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "renderer/variant_program.h"

namespace spire::engine {

struct ValueType {
  enum class Scalar { Float, Int, Uint, Bool };
  Scalar scalar = Scalar::Float;
  uint32_t rows = 1;         // vector size; rows of a matrix
  uint32_t columns = 1;      // > 1 for matrices
  uint32_t arrayLength = 0;  // 0 when not an array

  uint32_t componentCount() const { return rows * columns * (arrayLength == 0 ? 1 : arrayLength); }
  bool isMatrix() const { return columns > 1; }
};

// Numeric scalars, vectors, matrices and one-dimensional arrays of them;
// nullopt for samplers, structs and anything else.
std::optional<ValueType> parseValueType(std::string_view type);

// Writes `values` (componentCount() numbers) into `memory` at the member's
// offset, honouring matrixStride and arrayStride. Integers are truncated,
// booleans are non-zero. Out-of-range writes are skipped, never performed.
void writeValue(std::span<std::byte> memory, const BlockMember& member, const ValueType& type,
                std::span<const double> values);

// The inverse of writeValue.
std::vector<double> readValue(std::span<const std::byte> memory, const BlockMember& member, const ValueType& type);

}  // namespace spire::engine
