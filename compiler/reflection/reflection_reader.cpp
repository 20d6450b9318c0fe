// The reader half of reflection_json.h. nlohmann reports a missing field or a
// wrong type by exception; each kernel's entries are read under a try that
// turns it into an error naming the kernel, and numbers that nlohmann would
// silently truncate or wrap (1.5, -1) are checked first.
#include <fmt/format.h>

#include "reflection/reflection_json.h"

namespace spire::reflection {

using Json = nlohmann::ordered_json;

namespace {

using Result = Expected<void, std::string>;

Expected<uint32_t, std::string> wholeNumber(const Json& entry, const char* key, const std::string& what) {
  if (!entry.contains(key)) return fmt::format("{} has no \"{}\"", what, key);
  const Json& value = entry.at(key);
  const bool valid = value.is_number_unsigned()
                         ? value.get<uint64_t>() <= UINT32_MAX
                         : value.is_number_integer() && value.get<int64_t>() >= 0 && value.get<int64_t>() <= UINT32_MAX;
  if (!valid) {
    return fmt::format("{}: \"{}\" must be a whole number from 0 to {}, not {}", what, key, UINT32_MAX, value.dump());
  }
  return static_cast<uint32_t>(value.get<uint64_t>());
}

Result readNumber(const Json& entry, const char* key, const std::string& what, uint32_t& into) {
  auto number = wholeNumber(entry, key, what);
  if (!number) return number.error();
  into = *number;
  return {};
}

Result readSlot(const Json& entry, const std::string& what, DescriptorSlot& slot) {
  if (auto r = readNumber(entry, "set", what, slot.set); !r) return r;
  return readNumber(entry, "binding", what, slot.binding);
}

template <class Kind>
Expected<Kind, std::string> readKind(const Json& entry, const std::string& what,
                                     std::initializer_list<std::pair<std::string_view, Kind>> kinds) {
  const std::string name = entry.at("kind").get<std::string>();
  std::string known;
  for (const auto& [spelling, kind] : kinds) {
    if (spelling == name) return kind;
    known += fmt::format("{}\"{}\"", known.empty() ? "" : ", ", spelling);
  }
  return fmt::format("{}: unknown kind \"{}\" (expected one of {})", what, name, known);
}

Expected<BlockMember, std::string> readMember(const Json& json, const std::string& what) {
  BlockMember member;
  member.component = json.at("component").get<std::string>();
  member.glslName = json.at("glslName").get<std::string>();
  member.type = parseValueType(json.at("type").get<std::string>());
  const std::string where = fmt::format("{}, member '{}'", what, member.component);
  for (auto [key, field] : {std::pair{"offset", &member.offset}, std::pair{"size", &member.size}}) {
    if (auto r = readNumber(json, key, where, *field); !r) return r.error();
  }
  for (auto [key, field] : {std::pair{"arrayStride", &member.arrayStride}, {"matrixStride", &member.matrixStride}}) {
    if (!json.contains(key)) continue;
    if (auto r = readNumber(json, key, where, *field); !r) return r.error();
  }
  return member;
}

Expected<Block, std::string> readBlock(const Json& json, const std::string& world) {
  Block block;
  block.name = json.at("name").get<std::string>();
  const std::string what = fmt::format("kernel '{}', block '{}'", world, block.name);
  auto kind = readKind<bool>(json, what, {{"uniform", false}, {"storage", true}});
  if (!kind) return kind.error();
  block.storage = *kind;
  block.layout = json.at("layout").get<std::string>();
  if (auto r = readSlot(json, what, block.slot); !r) return r.error();
  const auto r = block.storage ? readNumber(json, "recordStride", what, block.recordStride)
                               : readNumber(json, "size", what, block.size);
  if (!r) return r.error();
  block.strategy = json.at("strategy").get<std::string>();
  for (const Json& m : json.at("members")) {
    auto member = readMember(m, what);
    if (!member) return member.error();
    block.members.push_back(std::move(member).value());
  }
  return block;
}

Result readInputFields(const Json& json, const std::string& what, KernelInput& input) {
  if (input.kind == InputKind::Varying) return readNumber(json, "location", what, input.location);
  if (input.kind == InputKind::PushConstant) return readNumber(json, "offset", what, input.offset);
  if (auto r = readSlot(json, what, input.slot); !r) return r;
  if (input.kind == InputKind::Texture) {
    input.sampler = json.at("sampler").get<std::string>();
    input.uv = json.at("uv").get<std::string>();
    if (json.contains("layer")) input.layer = json.at("layer").get<std::string>();
    if (auto r = readNumber(json, "channels", what, input.channels); !r) return r;
    if (input.channels < 1 || input.channels > 4) return fmt::format("{}: \"channels\" must be 1 to 4", what);
  }
  if (input.kind == InputKind::UniformMember || input.kind == InputKind::BufferMember) {
    input.block = json.at("block").get<std::string>();
    if (auto r = readNumber(json, "offset", what, input.offset); !r) return r;
  }
  if (input.kind == InputKind::BufferMember) input.index = json.at("index").get<std::string>();
  return {};
}

Expected<KernelInput, std::string> readInput(const Json& json, const std::string& world) {
  KernelInput input;
  input.component = json.at("component").get<std::string>();
  const std::string what = fmt::format("kernel '{}', input '{}'", world, input.component);
  auto kind = readKind<InputKind>(json, what,
                                  {{"varying", InputKind::Varying},
                                   {"uniform", InputKind::UniformMember},
                                   {"sampler", InputKind::Sampler},
                                   {"texture", InputKind::Texture},
                                   {"buffer", InputKind::BufferMember},
                                   {"push", InputKind::PushConstant}});
  if (!kind) return kind.error();
  input.kind = *kind;
  input.glslName = json.at("glslName").get<std::string>();
  input.type = parseValueType(json.at("type").get<std::string>());
  input.strategy = json.at("strategy").get<std::string>();
  input.from = json.at("from").get<std::string>();
  if (auto r = readInputFields(json, what, input); !r) return r.error();
  return input;
}

Expected<KernelOutput, std::string> readOutput(const Json& json, const std::string& world) {
  KernelOutput output;
  const bool builtin = json.contains("builtin");
  output.component = json.at(builtin ? "builtin" : "component").get<std::string>();
  const std::string what = fmt::format("kernel '{}', output '{}'", world, output.component);
  auto kind = readKind<OutputKind>(
      json, what,
      {{"varying", OutputKind::Varying}, {"builtin", OutputKind::BuiltIn}, {"buffer", OutputKind::BufferMember}});
  if (!kind) return kind.error();
  output.kind = *kind;
  output.strategy = json.at("strategy").get<std::string>();
  if (output.kind == OutputKind::BuiltIn) {
    output.expression = json.at("expression").get<std::string>();
    return output;
  }
  output.glslName = json.at("glslName").get<std::string>();
  output.type = parseValueType(json.at("type").get<std::string>());
  if (output.kind == OutputKind::Varying) {
    if (auto r = readNumber(json, "location", what, output.location); !r) return r.error();
  } else {
    if (auto r = readSlot(json, what, output.slot); !r) return r.error();
    output.block = json.at("block").get<std::string>();
    if (auto r = readNumber(json, "offset", what, output.offset); !r) return r.error();
  }
  if (json.contains("hints")) {
    for (const auto& [name, value] : json.at("hints").items()) output.setHint(name, value.get<std::string>());
  }
  return output;
}

Expected<HazardValue, std::string> readHazardValue(const Json& json, const std::string& what) {
  HazardValue value;
  value.component = json.at("component").get<std::string>();
  value.type = parseValueType(json.at("type").get<std::string>());
  const std::string where = fmt::format("{}, value '{}'", what, value.component);
  if (json.contains("code")) {
    if (auto r = readNumber(json, "code", where, value.code); !r) return r.error();
    value.definition = json.at("definition").get<std::string>();
    value.source = json.at("source").get<std::string>();
    value.reads = json.at("reads").get<std::vector<std::string>>();
  }
  if (json.contains("dumpOffset")) {
    uint32_t offset = 0;
    if (auto r = readNumber(json, "dumpOffset", where, offset); !r) return r.error();
    value.dumpOffset = offset;
  }
  return value;
}

// The record's numbers must describe a buffer the engine can index: every
// code within `slots`, every dump within `dumpFloats`.
Expected<HazardRecord, std::string> readHazards(const Json& json, const std::string& world) {
  HazardRecord record;
  const std::string what = fmt::format("kernel '{}', hazard record", world);
  if (auto r = readSlot(json, what, record.slot); !r) return r.error();
  record.index = json.at("index").get<std::string>();
  if (auto r = readNumber(json, "slots", what, record.slots); !r) return r.error();
  if (auto r = readNumber(json, "dumpFloats", what, record.dumpFloats); !r) return r.error();
  if (record.slots == 0 || record.dumpFloats == 0 || record.slots > 4096 || record.dumpFloats > 4096) {
    return fmt::format("{}: \"slots\" and \"dumpFloats\" must be 1 to 4096", what);
  }
  for (const Json& v : json.at("values")) {
    auto value = readHazardValue(v, what);
    if (!value) return value.error();
    const uint32_t floats = value->type.componentCount();
    if (value->code > record.slots || (value->dumpOffset && *value->dumpOffset + floats > record.dumpFloats)) {
      return fmt::format("{}: value '{}' lies outside the record", what, value->component);
    }
    record.values.push_back(std::move(value).value());
  }
  for (const Json& o : json.at("operations")) {
    record.operations.push_back({o.at("text").get<std::string>(), o.at("source").get<std::string>()});
  }
  return record;
}

template <class T, class Read>
Result readEach(const Json& list, const std::string& world, std::vector<T>& into, Read read) {
  if (!list.is_array()) return fmt::format("kernel '{}': expected an array, not {}", world, list.type_name());
  for (const Json& element : list) {
    auto parsed = read(element, world);
    if (!parsed) return parsed.error();
    into.push_back(std::move(parsed).value());
  }
  return {};
}

Expected<Kernel, std::string> readKernel(const Json& k) {
  Kernel kernel;
  kernel.world = k.at("world").get<std::string>();
  try {
    const auto stage = parseStage(k.at("stage").get<std::string>());
    if (!stage) return fmt::format("kernel '{}' has an unknown stage", kernel.world);
    kernel.stage = *stage;
    kernel.entry = k.at("entry").get<std::string>();
    kernel.glslFile = k.at("glsl").get<std::string>();
    kernel.spirvFile = k.at("spirv").get<std::string>();
    kernel.hash = k.at("hash").get<std::string>();
    kernel.spirvHash = k.value("spirvHash", std::string());
    kernel.key = k.at("key").get<std::string>();
    if (auto r = readEach(k.at("inputs"), kernel.world, kernel.inputs, readInput); !r) return r.error();
    if (auto r = readEach(k.at("outputs"), kernel.world, kernel.outputs, readOutput); !r) return r.error();
    if (auto r = readEach(k.at("blocks"), kernel.world, kernel.blocks, readBlock); !r) return r.error();
    if (k.contains("hazards")) {
      auto hazards = readHazards(k.at("hazards"), kernel.world);
      if (!hazards) return hazards.error();
      kernel.hazards = std::move(hazards).value();
    }
  } catch (const nlohmann::json::exception& e) {
    return fmt::format("kernel '{}': {}", kernel.world, e.what());
  }
  return kernel;
}

Expected<Variant, std::string> readVariant(const Json& document) {
  if (!document.is_object() || document.value("format", "") != "spire-reflection") {
    return std::string("not a spire-reflection document");
  }
  if (document.value("version", 0) != kFormatVersion) {
    return fmt::format("reflection version {} is not the version this reader knows ({}); compile the shader again",
                       document.at("version").dump(), kFormatVersion);
  }
  Variant variant;
  variant.shader = document.at("shader").get<std::string>();
  variant.pipeline = document.at("pipeline").get<std::string>();
  for (const Json& w : document.at("worlds")) {
    variant.worlds.push_back({w.at("name").get<std::string>(), w.at("role").get<std::string>()});
  }
  for (const auto& [component, world] : document.at("placement").items()) {
    variant.placement.emplace_back(component, world.get<std::string>());
  }
  for (const Json& k : document.at("kernels")) {
    auto kernel = readKernel(k);
    if (!kernel) return kernel.error();
    variant.kernels.push_back(std::move(kernel).value());
  }
  return variant;
}

}  // namespace

Expected<Variant, std::string> fromJson(const Json& document) {
  try {
    auto variant = readVariant(document);
    if (!variant) return "malformed reflection: " + variant.error();
    return variant;
  } catch (const nlohmann::json::exception& e) {
    return fmt::format("malformed reflection: {}", e.what());
  }
}

Expected<Variant, std::string> parseReflection(std::string_view text) {
  const Json document = Json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (document.is_discarded()) return std::string("not valid JSON");
  return fromJson(document);
}

}  // namespace spire::reflection
