#include "codegen/strategies/strategy_support.h"

#include <fmt/format.h>

namespace spire::codegen {

sem::StrategySignature makeSignature(std::string name, sem::StrategyRole role, std::vector<sem::StrategyParam> params,
                                     std::string summary, sem::ValueTransfer transfer, bool usesLocations,
                                     bool carriesOpaque) {
  return {std::move(name), role, std::move(params), std::move(summary), transfer, usesLocations, carriesOpaque};
}

reflection::ValueType reflectedType(const sem::Type* type) {
  reflection::ValueType result;
  result.name = type->name();
  const sem::Type* base = type->isArray() ? type->element : type;
  if (!base->isNumericShape()) {
    result.kind = type->isSampler() ? reflection::ValueType::Kind::Sampler : reflection::ValueType::Kind::Other;
    return result;
  }
  static constexpr reflection::ValueType::Scalar kScalars[] = {
      reflection::ValueType::Scalar::Bool, reflection::ValueType::Scalar::Int, reflection::ValueType::Scalar::Uint,
      reflection::ValueType::Scalar::Float};
  result.scalar = kScalars[static_cast<size_t>(base->scalar)];
  result.rows = base->rows;
  result.columns = base->isMatrix() ? base->columns : 1;
  result.arrayLength = type->isArray() ? type->arraySize : 0;
  return result;
}

namespace {

// The fields inputs and outputs share.
template <class Entry, class Kind>
Entry valueRecord(const KernelValue& value, Kind kind, std::string_view strategy) {
  Entry entry;
  entry.kind = kind;
  entry.component = value.sourceName;
  entry.glslName = value.glslName;
  entry.type = reflectedType(value.type);
  entry.strategy = strategy;
  return entry;
}

}  // namespace

reflection::KernelInput importEntry(const ImportSite& site, const KernelValue& value, reflection::InputKind kind,
                                    std::string_view strategy) {
  auto entry = valueRecord<reflection::KernelInput>(value, kind, strategy);
  entry.from = site.pipeline.worlds[site.import.from].name;
  return entry;
}

reflection::KernelOutput exportEntry(const KernelValue& value, reflection::OutputKind kind, std::string_view strategy) {
  auto entry = valueRecord<reflection::KernelOutput>(value, kind, strategy);
  for (const auto& [name, text] : value.attributes) entry.setHint(name, text);
  return entry;
}

reflection::DescriptorSlot slotAt(const KernelBuilder& kernel, uint32_t binding) {
  return {kernel.descriptorSet(), binding};
}

BlockDeclaration declareBlock(KernelBuilder& kernel, const std::string& hint, const std::vector<KernelValue>& values,
                              BlockLayout layout, std::string_view qualifier, std::string_view strategy) {
  BlockDeclaration block;
  block.blockName = kernel.names().generate(hint);
  block.binding = kernel.allocateBinding();
  const bool isBuffer = qualifier != "uniform";
  std::string members;
  uint32_t offset = 0;
  uint32_t alignment = 0;
  reflection::Block reflected;
  for (const KernelValue& v : values) {
    const MemberLayout m = layoutOf(v.type, layout);
    offset = alignUp(offset, m.alignment);
    block.offsets.push_back(offset);
    members += fmt::format("    {};\n", kernel.declaration(v.type, v.glslName));
    reflected.members.push_back(
        {v.sourceName, v.glslName, reflectedType(v.type), offset, m.size, m.arrayStride, m.matrixStride});
    offset += m.size;
    alignment = std::max(alignment, m.alignment);
  }
  const std::string layoutName = layout == BlockLayout::Std140 ? "std140" : "std430";
  reflected.name = block.blockName;
  reflected.storage = isBuffer;
  reflected.layout = layoutName;
  reflected.slot = slotAt(kernel, block.binding);
  reflected.strategy = strategy;
  if (isBuffer) {
    // A runtime array of records: the stride is the record size rounded to
    // the record's alignment.
    block.recordType = kernel.names().generate(hint + "_record");
    block.recordsName = kernel.names().generate(hint + "_records");
    kernel.declare(fmt::format("struct {} {{\n{}}};", block.recordType, members));
    kernel.declare(fmt::format("layout(set = {}, binding = {}, {}) {} {} {{\n    {} {}[];\n}};", kernel.descriptorSet(),
                               block.binding, layoutName, qualifier, block.blockName, block.recordType,
                               block.recordsName));
    reflected.recordStride = alignUp(offset, layout == BlockLayout::Std140 ? std::max(alignment, 16u) : alignment);
  } else {
    kernel.declare(fmt::format("layout(set = {}, binding = {}, {}) {} {} {{\n{}}};", kernel.descriptorSet(),
                               block.binding, layoutName, qualifier, block.blockName, members));
    reflected.size = alignUp(offset, 16);
  }
  kernel.reflectBlock(std::move(reflected));
  return block;
}

bool needsFlat(const sem::Type* type) {
  if (type->isArray()) return needsFlat(type->element);
  return type->isIntegerShape();
}

Expected<void, Failure> checkVarying(const KernelValue& value, std::string_view strategy) {
  const sem::Type* base = value.type;
  while (base->isArray()) base = base->element;
  if (base->isNumericShape() && base->scalar != sem::ScalarKind::Bool) return {};
  return Failure{
      fmt::format("{} cannot carry '{}' of type '{}' between stages (only numeric scalars, vectors, matrices "
                  "and arrays of them)",
                  strategy, value.sourceName, value.type->name())};
}

}  // namespace spire::codegen

namespace spire::codegen {

Expected<bool, Failure> checkEncoding(const KernelValue& value) {
  bool isSigned = false;
  for (const auto& [name, text] : value.attributes) {
    // The attribute catalogue has refused any other value when the source
    // or the decisions were read.
    if (name != "Encoding" || text != "signed") continue;
    if (!(value.type->isScalar() || value.type->isVector()) || value.type->scalar != sem::ScalarKind::Float) {
      return Failure{fmt::format("Encoding \"signed\" needs a float scalar or vector, not '{}' of type '{}'",
                                 value.sourceName, value.type->name())};
    }
    isSigned = true;
  }
  return isSigned;
}

Expected<void, Failure> emitOutVariables(ExportSite& site, std::string_view strategy) {
  KernelBuilder& kernel = site.producer;
  for (size_t i = 0; i < site.values.size(); ++i) {
    const KernelValue& v = site.values[i];
    if (auto checked = checkVarying(v, strategy); !checked) return checked;
    if (kernel.stage() == ShaderStage::Fragment && (v.type->isMatrix() || v.type->isArray())) {
      return Failure{
          fmt::format("{} cannot write '{}' of type '{}' from fragment world '{}': fragment outputs are scalars "
                      "and vectors",
                      strategy, v.sourceName, v.type->name(), kernel.world())};
    }
    const std::string out = kernel.names().generate("out_" + v.glslName);
    const bool flat = kernel.stage() == ShaderStage::Vertex && needsFlat(v.type);
    kernel.declare(fmt::format("layout(location = {}) {}out {};", site.locations[i], flat ? "flat " : "",
                               kernel.declaration(v.type, out)));
    const auto encodeSigned = checkEncoding(v);
    if (!encodeSigned) return encodeSigned.error();
    kernel.addStore(*encodeSigned ? fmt::format("{} = {} * 0.5 + 0.5;", out, v.glslName)
                                  : fmt::format("{} = {};", out, v.glslName));
    reflection::KernelOutput entry = exportEntry(v, reflection::OutputKind::Varying, strategy);
    entry.glslName = out;
    entry.location = site.locations[i];
    kernel.reflectOutput(std::move(entry));
  }
  return {};
}

}  // namespace spire::codegen
