// The writer half of reflection_json.h. Key order is part of the format:
// kernel keys hash these objects' text, and goldens compare it exactly.
#include "reflection/reflection_json.h"

#include "support/content_hash.h"

namespace spire::reflection {

using Json = nlohmann::ordered_json;

namespace {

std::string_view outputKindName(OutputKind kind) {
  switch (kind) {
    case OutputKind::Varying: return "varying";
    case OutputKind::BuiltIn: return "builtin";
    case OutputKind::BufferMember: return "buffer";
  }
  return "unknown";
}

void putSlot(Json& entry, DescriptorSlot slot) {
  entry["set"] = slot.set;
  entry["binding"] = slot.binding;
}

Json valueEntry(std::string_view kind, const std::string& component, const std::string& glslName, const ValueType& type,
                const std::string& strategy) {
  Json entry;
  entry["kind"] = kind;
  entry["component"] = component;
  entry["glslName"] = glslName;
  entry["type"] = type.name;
  entry["strategy"] = strategy;
  return entry;
}

Json inputJson(const KernelInput& in) {
  Json entry = valueEntry(inputKindName(in.kind), in.component, in.glslName, in.type, in.strategy);
  entry["from"] = in.from;
  if (in.kind == InputKind::Varying) {
    entry["location"] = in.location;
    return entry;
  }
  if (in.kind == InputKind::PushConstant) {
    entry["offset"] = in.offset;
    return entry;
  }
  putSlot(entry, in.slot);
  if (in.kind == InputKind::Texture) {
    entry["sampler"] = in.sampler;
    entry["uv"] = in.uv;
    if (!in.layer.empty()) entry["layer"] = in.layer;
    entry["channels"] = in.channels;
  } else if (in.kind == InputKind::UniformMember || in.kind == InputKind::BufferMember) {
    entry["block"] = in.block;
    entry["offset"] = in.offset;
    if (in.kind == InputKind::BufferMember) entry["index"] = in.index;
  }
  return entry;
}

Json outputJson(const KernelOutput& out) {
  if (out.kind == OutputKind::BuiltIn) {
    Json entry;
    entry["kind"] = outputKindName(out.kind);
    entry["builtin"] = out.component;
    entry["expression"] = out.expression;
    entry["strategy"] = out.strategy;
    return entry;
  }
  Json entry = valueEntry(outputKindName(out.kind), out.component, out.glslName, out.type, out.strategy);
  if (out.kind == OutputKind::Varying) {
    entry["location"] = out.location;
  } else {
    putSlot(entry, out.slot);
    entry["block"] = out.block;
    entry["offset"] = out.offset;
  }
  for (const auto& [name, value] : out.hints) entry["hints"][name] = value;
  return entry;
}

Json blockJson(const Block& block) {
  Json entry;
  entry["name"] = block.name;
  entry["kind"] = block.storage ? "storage" : "uniform";
  entry["layout"] = block.layout;
  putSlot(entry, block.slot);
  if (block.storage) {
    entry["recordStride"] = block.recordStride;
  } else {
    entry["size"] = block.size;
  }
  entry["strategy"] = block.strategy;
  Json members = Json::array();
  for (const BlockMember& m : block.members) {
    Json member;
    member["component"] = m.component;
    member["glslName"] = m.glslName;
    member["type"] = m.type.name;
    member["offset"] = m.offset;
    member["size"] = m.size;
    if (m.arrayStride) member["arrayStride"] = m.arrayStride;
    if (m.matrixStride) member["matrixStride"] = m.matrixStride;
    members.push_back(std::move(member));
  }
  entry["members"] = std::move(members);
  return entry;
}

Json hazardValueJson(const HazardValue& value) {
  Json entry;
  entry["component"] = value.component;
  entry["type"] = value.type.name;
  if (value.code != 0) {
    entry["code"] = value.code;
    entry["definition"] = value.definition;
    entry["source"] = value.source;
    entry["reads"] = value.reads;
  }
  if (value.dumpOffset) entry["dumpOffset"] = *value.dumpOffset;
  return entry;
}

Json hazardJson(const HazardRecord& record) {
  Json entry;
  putSlot(entry, record.slot);
  entry["index"] = record.index;
  entry["slots"] = record.slots;
  entry["dumpFloats"] = record.dumpFloats;
  Json values = Json::array();
  for (const HazardValue& v : record.values) values.push_back(hazardValueJson(v));
  entry["values"] = std::move(values);
  Json operations = Json::array();
  for (const HazardOperation& o : record.operations) operations.push_back({{"text", o.text}, {"source", o.source}});
  entry["operations"] = std::move(operations);
  return entry;
}

template <class T, class ToJson>
Json arrayOf(const std::vector<T>& items, ToJson toJson) {
  Json list = Json::array();
  for (const T& item : items) list.push_back(toJson(item));
  return list;
}

// The part of a kernel's entry that its key covers.
Json interfaceJson(const Kernel& kernel) {
  Json entry;
  entry["world"] = kernel.world;
  entry["stage"] = stageName(kernel.stage);
  entry["inputs"] = arrayOf(kernel.inputs, inputJson);
  entry["outputs"] = arrayOf(kernel.outputs, outputJson);
  entry["blocks"] = arrayOf(kernel.blocks, blockJson);
  return entry;
}

}  // namespace

Json toJson(const Kernel& kernel) {
  Json entry;
  entry["world"] = kernel.world;
  entry["stage"] = stageName(kernel.stage);
  entry["entry"] = kernel.entry;
  entry["glsl"] = kernel.glslFile;
  entry["spirv"] = kernel.spirvFile;
  entry["hash"] = kernel.hash;
  if (!kernel.spirvHash.empty()) entry["spirvHash"] = kernel.spirvHash;
  entry["inputs"] = arrayOf(kernel.inputs, inputJson);
  entry["outputs"] = arrayOf(kernel.outputs, outputJson);
  entry["blocks"] = arrayOf(kernel.blocks, blockJson);
  if (kernel.hazards) entry["hazards"] = hazardJson(*kernel.hazards);
  entry["key"] = kernel.key;
  return entry;
}

Json toJson(const Variant& variant) {
  Json root;
  root["format"] = "spire-reflection";
  root["version"] = kFormatVersion;
  root["shader"] = variant.shader;
  root["pipeline"] = variant.pipeline;
  root["worlds"] = arrayOf(variant.worlds, [](const World& w) { return Json{{"name", w.name}, {"role", w.role}}; });
  Json placement = Json::object();
  for (const auto& [component, world] : variant.placement) placement[component] = world;
  root["placement"] = std::move(placement);
  root["kernels"] = arrayOf(variant.kernels, [](const Kernel& k) { return toJson(k); });
  return root;
}

std::string kernelKey(std::string_view glsl, const Kernel& kernel) {
  // Replacing invalid UTF-8 (which no input should carry this far) keeps a
  // key from throwing in the middle of code generation.
  return contentHash(std::string(glsl) + '\n' +
                     interfaceJson(kernel).dump(-1, ' ', false, Json::error_handler_t::replace));
}

}  // namespace spire::reflection
