#include "codegen/memory_layout.h"

#include <algorithm>

namespace spire::codegen {

MemberLayout layoutOf(const sem::Type* type, BlockLayout layout) {
  constexpr uint32_t kScalar = 4;  // bool, int, uint and float are 4 bytes in blocks
  MemberLayout m;
  switch (type->kind) {
    case sem::TypeKind::Scalar: m.alignment = m.size = kScalar; return m;
    case sem::TypeKind::Vector:
      m.size = kScalar * type->rows;
      m.alignment = kScalar * (type->rows == 3 ? 4 : type->rows);
      return m;
    case sem::TypeKind::Matrix: {
      // Column-major: an array of `columns` column vectors.
      uint32_t columnAlign = kScalar * (type->rows == 3 ? 4 : type->rows);
      if (layout == BlockLayout::Std140) columnAlign = alignUp(columnAlign, 16);
      m.alignment = columnAlign;
      m.matrixStride = columnAlign;
      m.size = columnAlign * type->columns;
      return m;
    }
    case sem::TypeKind::Array: {
      const MemberLayout element = layoutOf(type->element, layout);
      uint32_t stride = alignUp(element.size, element.alignment);
      uint32_t alignment = element.alignment;
      if (layout == BlockLayout::Std140) {
        stride = alignUp(stride, 16);
        alignment = alignUp(alignment, 16);
      }
      m.alignment = alignment;
      m.arrayStride = stride;
      m.matrixStride = element.matrixStride;
      m.size = stride * type->arraySize;
      return m;
    }
    case sem::TypeKind::Struct: {
      uint32_t offset = 0;
      uint32_t alignment = 0;
      for (const sem::StructField& f : type->fields) {
        const MemberLayout field = layoutOf(f.type, layout);
        offset = alignUp(offset, field.alignment) + field.size;
        alignment = std::max(alignment, field.alignment);
      }
      if (layout == BlockLayout::Std140) alignment = alignUp(alignment, 16);
      m.alignment = alignment;
      m.size = alignUp(offset, alignment);
      return m;
    }
    case sem::TypeKind::Error:
    case sem::TypeKind::Void:
    case sem::TypeKind::Sampler: return m;
  }
  return m;
}

}  // namespace spire::codegen
