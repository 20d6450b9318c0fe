// std140 and std430 layouts (GLSL 4.50 section 7.6.2.2), computed here so that
// reflection can tell an engine the byte offset of every block member.
#pragma once

#include <cstdint>

#include "sema/type.h"

namespace spire::codegen {

enum class BlockLayout : uint8_t { Std140, Std430 };

struct MemberLayout {
  uint32_t alignment = 0;
  uint32_t size = 0;
  uint32_t arrayStride = 0;   // arrays only
  uint32_t matrixStride = 0;  // matrices (and arrays of them)
};

// Base alignment and size of a member of `type`. Opaque and void types have
// no layout (size 0).
MemberLayout layoutOf(const sem::Type* type, BlockLayout layout);

inline uint32_t alignUp(uint32_t value, uint32_t alignment) {
  return alignment == 0 ? value : (value + alignment - 1) / alignment * alignment;
}

}  // namespace spire::codegen
