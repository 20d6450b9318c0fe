#include "codegen/strategies/strategy_support.h"

#include <fmt/format.h>

namespace spire::codegen {

sem::StrategySignature makeSignature(std::string name, sem::StrategyRole role, std::vector<sem::StrategyParam> params,
                                     std::string summary, sem::ValueTransfer transfer, bool usesLocations,
                                     bool carriesOpaque) {
  return {std::move(name), role, std::move(params), std::move(summary), transfer, usesLocations, carriesOpaque};
}

nlohmann::ordered_json valueEntry(const KernelValue& value, std::string_view strategy) {
  nlohmann::ordered_json entry;
  entry["component"] = value.sourceName;
  entry["glslName"] = value.glslName;
  entry["type"] = value.type->name();
  entry["strategy"] = strategy;
  return entry;
}

nlohmann::ordered_json importEntry(const ImportSite& site, const KernelValue& value, std::string_view strategy) {
  nlohmann::ordered_json entry = valueEntry(value, strategy);
  entry["from"] = site.pipeline.worlds[site.import.from].name;
  return entry;
}

void setBinding(nlohmann::ordered_json& entry, const KernelBuilder& kernel, uint32_t binding) {
  entry["set"] = kernel.descriptorSet();
  entry["binding"] = binding;
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
  nlohmann::ordered_json memberList = nlohmann::ordered_json::array();
  for (const KernelValue& v : values) {
    const MemberLayout m = layoutOf(v.type, layout);
    offset = alignUp(offset, m.alignment);
    block.offsets.push_back(offset);
    members += fmt::format("    {};\n", kernel.declaration(v.type, v.glslName));
    nlohmann::ordered_json member;
    member["component"] = v.sourceName;
    member["glslName"] = v.glslName;
    member["type"] = v.type->name();
    member["offset"] = offset;
    member["size"] = m.size;
    if (m.arrayStride) member["arrayStride"] = m.arrayStride;
    if (m.matrixStride) member["matrixStride"] = m.matrixStride;
    memberList.push_back(std::move(member));
    offset += m.size;
    alignment = std::max(alignment, m.alignment);
  }
  const std::string layoutName = layout == BlockLayout::Std140 ? "std140" : "std430";
  nlohmann::ordered_json reflection;
  reflection["name"] = block.blockName;
  reflection["kind"] = isBuffer ? "storage" : "uniform";
  reflection["layout"] = layoutName;
  reflection["set"] = kernel.descriptorSet();
  reflection["binding"] = block.binding;
  if (isBuffer) {
    // A runtime array of records: the stride is the record size rounded to
    // the record's alignment.
    block.recordType = kernel.names().generate(hint + "_record");
    block.recordsName = kernel.names().generate(hint + "_records");
    kernel.declare(fmt::format("struct {} {{\n{}}};", block.recordType, members));
    kernel.declare(fmt::format("layout(set = {}, binding = {}, {}) {} {} {{\n    {} {}[];\n}};",
                               kernel.descriptorSet(), block.binding, layoutName, qualifier, block.blockName,
                               block.recordType, block.recordsName));
    reflection["recordStride"] = alignUp(offset, layout == BlockLayout::Std140 ? std::max(alignment, 16u) : alignment);
  } else {
    kernel.declare(fmt::format("layout(set = {}, binding = {}, {}) {} {} {{\n{}}};", kernel.descriptorSet(),
                               block.binding, layoutName, qualifier, block.blockName, members));
    reflection["size"] = alignUp(offset, 16);
  }
  reflection["strategy"] = strategy;
  reflection["members"] = std::move(memberList);
  kernel.reflectBlock(std::move(reflection));
  return block;
}

bool needsFlat(const sem::Type* type) {
  if (type->isArray()) return needsFlat(type->element);
  return type->isIntegerShape();
}

std::optional<std::string> checkVarying(const KernelValue& value, std::string_view strategy) {
  const sem::Type* base = value.type;
  while (base->isArray()) base = base->element;
  if (base->isNumericShape() && base->scalar != sem::ScalarKind::Bool) return std::nullopt;
  return fmt::format("{} cannot carry '{}' of type '{}' between stages (only numeric scalars, vectors, matrices "
                     "and arrays of them)",
                     strategy, value.sourceName, value.type->name());
}

}  // namespace spire::codegen

namespace spire::codegen {

std::optional<std::string> checkEncoding(const KernelValue& value, bool& isSigned) {
  isSigned = false;
  for (const auto& [name, text] : value.attributes) {
    if (name != "Encoding") continue;
    if (text != "signed") {
      return fmt::format("unknown Encoding \"{}\" on '{}'; the only encoding is \"signed\"", text, value.sourceName);
    }
    if (!(value.type->isScalar() || value.type->isVector()) || value.type->scalar != sem::ScalarKind::Float) {
      return fmt::format("Encoding \"signed\" needs a float scalar or vector, not '{}' of type '{}'", value.sourceName,
                         value.type->name());
    }
    isSigned = true;
  }
  return std::nullopt;
}

std::optional<std::string> emitOutVariables(ExportSite& site, std::string_view strategy) {
  KernelBuilder& kernel = site.producer;
  for (size_t i = 0; i < site.values.size(); ++i) {
    const KernelValue& v = site.values[i];
    if (auto problem = checkVarying(v, strategy)) return problem;
    if (kernel.stage() == ShaderStage::Fragment && (v.type->isMatrix() || v.type->isArray())) {
      return fmt::format("{} cannot write '{}' of type '{}' from fragment world '{}': fragment outputs are scalars "
                         "and vectors",
                         strategy, v.sourceName, v.type->name(), kernel.world());
    }
    const std::string out = kernel.names().generate("out_" + v.glslName);
    const bool flat = kernel.stage() == ShaderStage::Vertex && needsFlat(v.type);
    kernel.declare(fmt::format("layout(location = {}) {}out {};", site.locations[i], flat ? "flat " : "",
                               kernel.declaration(v.type, out)));
    bool encodeSigned = false;
    if (auto problem = checkEncoding(v, encodeSigned)) return problem;
    kernel.addStore(encodeSigned ? fmt::format("{} = {} * 0.5 + 0.5;", out, v.glslName)
                                 : fmt::format("{} = {};", out, v.glslName));
    nlohmann::ordered_json entry = valueEntry(v, strategy);
    entry["glslName"] = out;
    entry["location"] = site.locations[i];
    for (const auto& [name, value] : v.attributes) entry["hints"][name] = value;
    kernel.reflectOutput(std::move(entry));
  }
  return std::nullopt;
}

}  // namespace spire::codegen
