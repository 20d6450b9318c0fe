#include "renderer/variant_program.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstring>

#include "codegen/spirv_compiler.h"
#include "support/file_io.h"

namespace spire::engine {

using Json = nlohmann::ordered_json;

const BlockMember* Block::member(std::string_view component) const {
  const auto it = std::find_if(members.begin(), members.end(),
                               [&](const BlockMember& m) { return m.component == component; });
  return it == members.end() ? nullptr : &*it;
}

const Block* KernelProgram::block(DescriptorSlot slot) const {
  const auto it = std::find_if(blocks.begin(), blocks.end(), [&](const Block& b) { return b.slot == slot; });
  return it == blocks.end() ? nullptr : &*it;
}

const KernelProgram* VariantProgram::kernel(std::string_view world) const {
  const auto it = std::find_if(kernels.begin(), kernels.end(), [&](const KernelProgram& k) { return k.world == world; });
  return it == kernels.end() ? nullptr : &*it;
}

const KernelProgram* VariantProgram::kernelWithRole(WorldRole role) const {
  const auto it = std::find_if(kernels.begin(), kernels.end(), [&](const KernelProgram& k) {
    const WorldPass* pass = findWorldPass(k.world);
    return pass && pass->role == role;
  });
  return it == kernels.end() ? nullptr : &*it;
}

std::string VariantProgram::fingerprint() const {
  std::string key;
  for (const KernelProgram& k : kernels) key += fmt::format("{}={};", k.world, k.hash);
  return key;
}

namespace {

std::optional<codegen::ShaderStage> parseStage(const std::string& name) {
  if (name == "vertex") return codegen::ShaderStage::Vertex;
  if (name == "fragment") return codegen::ShaderStage::Fragment;
  if (name == "compute") return codegen::ShaderStage::Compute;
  return std::nullopt;
}

// One descriptor index ("set" or "binding") of `entry`; `what` names the entry
// in errors. Checked here because nlohmann would truncate 1.5 and wrap -1.
Expected<uint32_t> descriptorIndex(const Json& entry, const char* key, const std::string& what) {
  if (!entry.contains(key)) return Error{fmt::format("{} has no \"{}\"", what, key), {}};
  const Json& value = entry.at(key);
  const bool valid = value.is_number_unsigned()
                         ? value.get<uint64_t>() <= UINT32_MAX
                         : value.is_number_integer() && value.get<int64_t>() >= 0 && value.get<int64_t>() <= UINT32_MAX;
  if (!valid) {
    return Error{fmt::format("{}: \"{}\" must be a whole number from 0 to {}, not {}", what, key, UINT32_MAX,
                             value.dump()),
                 {}};
  }
  return static_cast<uint32_t>(value.get<uint64_t>());
}

Expected<DescriptorSlot> parseSlot(const Json& entry, const std::string& what) {
  const auto set = descriptorIndex(entry, "set", what);
  if (!set) return set.error();
  const auto binding = descriptorIndex(entry, "binding", what);
  if (!binding) return binding.error();
  return DescriptorSlot{*set, *binding};
}

Expected<Block> parseBlock(const Json& json, const std::string& world) {
  Block block;
  block.name = json.at("name").get<std::string>();
  block.storage = json.at("kind").get<std::string>() == "storage";
  const auto slot = parseSlot(json, fmt::format("kernel '{}', block '{}'", world, block.name));
  if (!slot) return slot.error();
  block.slot = *slot;
  block.size = json.value("size", 0U);
  block.recordStride = json.value("recordStride", 0U);
  for (const Json& m : json.at("members")) {
    BlockMember member;
    member.component = m.at("component").get<std::string>();
    member.type = m.at("type").get<std::string>();
    member.offset = m.at("offset").get<uint32_t>();
    member.size = m.at("size").get<uint32_t>();
    member.arrayStride = m.value("arrayStride", 0U);
    member.matrixStride = m.value("matrixStride", 0U);
    block.members.push_back(std::move(member));
  }
  return block;
}

// The kind of an input follows from its fields (docs/reflection.md, Inputs).
Expected<KernelInput> parseInput(const Json& json, const std::string& world) {
  KernelInput input;
  input.component = json.at("component").get<std::string>();
  input.type = json.at("type").get<std::string>();
  input.from = json.at("from").get<std::string>();
  if (json.contains("location")) {
    input.kind = InputKind::Varying;
    input.location = json.at("location").get<uint32_t>();
    return input;
  }
  const auto slot = parseSlot(json, fmt::format("kernel '{}', input '{}'", world, input.component));
  if (!slot) return slot.error();
  input.slot = *slot;
  if (json.contains("sampler")) {
    input.kind = InputKind::Texture;
    input.channels = json.at("channels").get<uint32_t>();
  } else if (json.contains("index")) {
    input.kind = InputKind::BufferMember;
  } else if (json.contains("block")) {
    input.kind = InputKind::UniformMember;
  } else {
    input.kind = InputKind::Sampler;
  }
  return input;
}

Expected<KernelOutput> parseOutput(const Json& json, const std::string& world) {
  KernelOutput output;
  if (json.contains("builtin")) {
    output.kind = OutputKind::BuiltIn;
    output.component = json.at("builtin").get<std::string>();
    return output;
  }
  output.component = json.at("component").get<std::string>();
  output.type = json.at("type").get<std::string>();
  if (json.contains("location")) {
    output.kind = OutputKind::Varying;
    output.location = json.at("location").get<uint32_t>();
  } else {
    output.kind = OutputKind::BufferMember;
    const auto slot = parseSlot(json, fmt::format("kernel '{}', output '{}'", world, output.component));
    if (!slot) return slot.error();
    output.slot = *slot;
  }
  if (json.contains("hints")) {
    for (const auto& [key, value] : json.at("hints").items()) output.hints[key] = value.get<std::string>();
  }
  return output;
}

// Appends what `parse` makes of each element of `list` to `into`.
template <class T, class Parse>
Expected<void> parseEach(const Json& list, const std::string& world, std::vector<T>& into, Parse parse) {
  for (const Json& element : list) {
    auto parsed = parse(element, world);
    if (!parsed) return parsed.error();
    into.push_back(std::move(parsed).value());
  }
  return {};
}

// One entry of "kernels"; `spirv` supplies its words by world.
Expected<KernelProgram> parseKernel(const Json& k, const std::map<std::string, std::vector<uint32_t>>& spirv) {
  KernelProgram kernel;
  kernel.world = k.at("world").get<std::string>();
  const auto stage = parseStage(k.at("stage").get<std::string>());
  if (!stage) return Error{fmt::format("kernel '{}' has an unknown stage", kernel.world), {}};
  kernel.stage = *stage;
  kernel.hash = k.at("hash").get<std::string>();
  const auto words = spirv.find(kernel.world);
  if (words == spirv.end() || words->second.empty()) {
    return Error{fmt::format("no SPIR-V for kernel '{}'", kernel.world), {}};
  }
  kernel.spirv = words->second;
  // Errors from the entries name the kernel and the entry; the prefix matches
  // the one nlohmann's exceptions get.
  const auto malformed = [](const Error& error) { return Error{"malformed reflection: " + error.message, {}}; };
  if (auto parsed = parseEach(k.at("inputs"), kernel.world, kernel.inputs, parseInput); !parsed) {
    return malformed(parsed.error());
  }
  if (auto parsed = parseEach(k.at("outputs"), kernel.world, kernel.outputs, parseOutput); !parsed) {
    return malformed(parsed.error());
  }
  if (auto parsed = parseEach(k.at("blocks"), kernel.world, kernel.blocks, parseBlock); !parsed) {
    return malformed(parsed.error());
  }
  return kernel;
}

}  // namespace

Expected<VariantProgram> parseReflection(const Json& reflection,
                                         const std::map<std::string, std::vector<uint32_t>>& spirv) {
  // nlohmann reports a missing field or a wrong type by exception; every such
  // problem is the same user-facing error, so it is caught once here.
  try {
    if (reflection.at("format").get<std::string>() != "spire-reflection" || reflection.at("version").get<int>() != 1) {
      return Error{"not a version 1 spire-reflection document", {}};
    }
    VariantProgram program;
    program.shader = reflection.at("shader").get<std::string>();
    program.pipeline = reflection.at("pipeline").get<std::string>();
    for (const auto& [component, world] : reflection.at("placement").items()) {
      program.placement.emplace_back(component, world.get<std::string>());
    }
    for (const Json& k : reflection.at("kernels")) {
      auto kernel = parseKernel(k, spirv);
      if (!kernel) return kernel.error();
      program.kernels.push_back(std::move(kernel).value());
    }
    return program;
  } catch (const nlohmann::json::exception& e) {
    return Error{fmt::format("malformed reflection: {}", e.what()), {}};
  }
}

Expected<VariantProgram> loadProgram(const std::filesystem::path& directory) {
  const std::filesystem::path reflectionPath = directory / "reflection.json";
  const auto text = readWholeFile(reflectionPath.string());
  if (!text) return Error{fmt::format("cannot read '{}'", reflectionPath.string()), {}};
  Json reflection = Json::parse(*text, nullptr, /*allow_exceptions=*/false);
  if (reflection.is_discarded()) return Error{fmt::format("'{}' is not valid JSON", reflectionPath.string()), {}};
  std::map<std::string, std::vector<uint32_t>> spirv;
  if (reflection.contains("kernels") && reflection["kernels"].is_array()) {
    for (const Json& k : reflection["kernels"]) {
      if (!k.contains("world") || !k.contains("spirv") || !k["spirv"].is_string()) continue;
      const std::filesystem::path file = directory / k["spirv"].get<std::string>();
      const auto bytes = readWholeFile(file.string());
      if (!bytes || bytes->empty() || bytes->size() % 4 != 0) {
        return Error{fmt::format("cannot read SPIR-V '{}' (missing, or not a whole number of words)", file.string()),
                     {}};
      }
      std::vector<uint32_t> words(bytes->size() / 4);
      std::memcpy(words.data(), bytes->data(), bytes->size());
      spirv[k["world"].get<std::string>()] = std::move(words);
    }
  }
  auto program = parseReflection(reflection, spirv);
  if (!program) return Error{fmt::format("{}: {}", reflectionPath.string(), program.error().message), {}};
  return program;
}

Expected<VariantProgram> compileProgram(const codegen::GeneratedShader& shader, const graph::Variant& variant) {
  std::map<std::string, std::vector<uint32_t>> spirv;
  for (const codegen::Kernel& kernel : shader.kernels) {
    codegen::SpirvResult result = codegen::compileGlslToSpirv(kernel.stage, kernel.glsl, kernel.world + ".glsl");
    if (!result.ok()) {
      return Error{fmt::format("glslang rejected the {} kernel of '{}' (a spirec bug):\n{}", kernel.world,
                               shader.shader, result.log),
                   {}};
    }
    spirv[kernel.world] = std::move(result.words);
  }
  return parseReflection(shader.reflection(variant), spirv);
}

}  // namespace spire::engine
