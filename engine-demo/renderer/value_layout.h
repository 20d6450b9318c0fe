// GLSL values as the engine moves them between the scene file, the CPU and
// GPU buffers: a reflected type (`float`, `vec3`, `mat3x4`, `ivec2`,
// `float[4]`) and flat lists of numbers (vectors in order, matrices
// column by column, arrays element by element), written to and read from
// std140/std430 memory at the offsets and strides reflection gives.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "renderer/variant_program.h"

namespace spire::engine {

// Writes `values` (the type's componentCount() numbers) into `memory` at the
// member's offset, honouring matrixStride and arrayStride. Integers are
// truncated, booleans are non-zero. Out-of-range writes, and values of a
// non-numeric member, are skipped, never performed.
void writeValue(std::span<std::byte> memory, const BlockMember& member, std::span<const double> values);

// The inverse of writeValue; empty for a non-numeric member.
std::vector<double> readValue(std::span<const std::byte> memory, const BlockMember& member);

}  // namespace spire::engine
