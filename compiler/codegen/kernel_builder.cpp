#include "codegen/kernel_builder.h"

#include <fmt/format.h>

namespace spire::codegen {

std::string glslTypeName(const sem::Type* type, const std::map<std::string, std::string, std::less<>>& structNames) {
  if (type->isStruct()) {
    auto it = structNames.find(type->structName);
    return it == structNames.end() ? type->structName : it->second;
  }
  if (type->isArray()) {
    const sem::Type* base = type;
    std::string dims;
    while (base->isArray()) {
      dims += fmt::format("[{}]", base->arraySize);
      base = base->element;
    }
    return glslTypeName(base, structNames) + dims;
  }
  return type->name();
}

std::string declareVariable(const sem::Type* type, const std::string& name,
                            const std::map<std::string, std::string, std::less<>>& structNames) {
  if (!type->isArray()) return fmt::format("{} {}", glslTypeName(type, structNames), name);
  // `float name[3][2]`: the element type first, then every dimension.
  const sem::Type* base = type;
  std::string dims;
  while (base->isArray()) {
    dims += fmt::format("[{}]", base->arraySize);
    base = base->element;
  }
  return fmt::format("{} {}{}", glslTypeName(base, structNames), name, dims);
}

uint32_t locationSlots(const sem::Type* type) {
  switch (type->kind) {
    case sem::TypeKind::Matrix: return type->columns;
    case sem::TypeKind::Array: return type->arraySize * locationSlots(type->element);
    case sem::TypeKind::Struct: {
      uint32_t slots = 0;
      for (const sem::StructField& f : type->fields) slots += locationSlots(f.type);
      return slots;
    }
    default: return 1;
  }
}

void KernelBuilder::declareGlobal(const sem::Type* type, const std::string& name) {
  globals_.push_back(declaration(type, name) + ";");
}

}  // namespace spire::codegen
