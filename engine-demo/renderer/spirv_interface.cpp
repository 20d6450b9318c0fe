#include "renderer/spirv_interface.h"

#include <fmt/format.h>

namespace spire::engine {
namespace {

// From the SPIR-V specification (section 3).
constexpr uint32_t kMagic = 0x07230203;
constexpr uint32_t kOpVariable = 59;
constexpr uint32_t kOpDecorate = 71;
constexpr uint32_t kDecorationLocation = 30;
constexpr uint32_t kDecorationBinding = 33;
constexpr uint32_t kDecorationDescriptorSet = 34;
constexpr uint32_t kStorageUniformConstant = 0;
constexpr uint32_t kStorageInput = 1;
constexpr uint32_t kStorageUniform = 2;
constexpr uint32_t kStorageOutput = 3;
constexpr uint32_t kStorageStorageBuffer = 12;

struct Decorations {
  std::map<uint32_t, uint32_t> location, binding, set;  // by result id
};

std::optional<DescriptorClass> descriptorClass(uint32_t storage) {
  switch (storage) {
    case kStorageUniformConstant: return DescriptorClass::Opaque;
    case kStorageUniform: return DescriptorClass::Uniform;
    case kStorageStorageBuffer: return DescriptorClass::Storage;
    default: return std::nullopt;
  }
}

std::string_view className(DescriptorClass c) {
  switch (c) {
    case DescriptorClass::Opaque: return "a sampler";
    case DescriptorClass::Uniform: return "a uniform block";
    case DescriptorClass::Storage: return "a storage buffer";
  }
  return "?";
}

void addVariable(const Decorations& d, uint32_t id, uint32_t storage, SpirvInterface& out) {
  const auto location = d.location.find(id);
  if (storage == kStorageInput && location != d.location.end()) out.inputLocations.insert(location->second);
  if (storage == kStorageOutput && location != d.location.end()) out.outputLocations.insert(location->second);
  const auto binding = d.binding.find(id);
  const auto kind = descriptorClass(storage);
  if (!kind || binding == d.binding.end()) return;
  const auto set = d.set.find(id);
  out.descriptors[{set == d.set.end() ? 0 : set->second, binding->second}] = *kind;
}

// The interface the reflection states, in the same terms.
SpirvInterface reflectedInterface(const reflection::Kernel& kernel) {
  SpirvInterface out;
  for (const reflection::KernelInput& in : kernel.inputs) {
    if (in.kind == reflection::InputKind::Varying) out.inputLocations.insert(in.location);
    if (in.kind == reflection::InputKind::Sampler || in.kind == reflection::InputKind::Texture) {
      out.descriptors[in.slot] = DescriptorClass::Opaque;
    }
  }
  for (const reflection::KernelOutput& o : kernel.outputs) {
    if (o.kind == reflection::OutputKind::Varying) out.outputLocations.insert(o.location);
  }
  for (const reflection::Block& block : kernel.blocks) {
    out.descriptors[block.slot] = block.storage ? DescriptorClass::Storage : DescriptorClass::Uniform;
  }
  if (kernel.hazards) out.descriptors[kernel.hazards->slot] = DescriptorClass::Storage;
  return out;
}

spire::Expected<void, Failure> compareLocations(const std::set<uint32_t>& spirv, const std::set<uint32_t>& reflected,
                                                std::string_view what) {
  for (uint32_t l : spirv) {
    if (!reflected.contains(l))
      return Failure{fmt::format("it has an {} at location {} that the reflection lacks", what, l)};
  }
  for (uint32_t l : reflected) {
    if (!spirv.contains(l))
      return Failure{fmt::format("the reflection has an {} at location {} that it lacks", what, l)};
  }
  return {};
}

}  // namespace

std::optional<SpirvInterface> readSpirvInterface(const std::vector<uint32_t>& words) {
  if (words.size() < 5 || words[0] != kMagic) return std::nullopt;
  Decorations d;
  std::vector<std::pair<uint32_t, uint32_t>> variables;  // id, storage class
  for (size_t i = 5; i < words.size();) {
    const uint32_t count = words[i] >> 16;
    const uint32_t opcode = words[i] & 0xFFFF;
    if (count == 0 || i + count > words.size()) return std::nullopt;
    if (opcode == kOpDecorate && count >= 4) {
      const uint32_t id = words[i + 1];
      const uint32_t decoration = words[i + 2];
      if (decoration == kDecorationLocation) d.location[id] = words[i + 3];
      if (decoration == kDecorationBinding) d.binding[id] = words[i + 3];
      if (decoration == kDecorationDescriptorSet) d.set[id] = words[i + 3];
    } else if (opcode == kOpVariable && count >= 4) {
      variables.emplace_back(words[i + 2], words[i + 3]);
    }
    i += count;
  }
  SpirvInterface out;
  for (const auto& [id, storage] : variables) addVariable(d, id, storage, out);
  return out;
}

spire::Expected<void, Failure> checkInterface(const std::vector<uint32_t>& words, const reflection::Kernel& kernel) {
  const auto spirv = readSpirvInterface(words);
  if (!spirv) return Failure{"it is not a SPIR-V module"};
  const SpirvInterface reflected = reflectedInterface(kernel);
  if (auto same = compareLocations(spirv->inputLocations, reflected.inputLocations, "input"); !same) return same;
  if (auto same = compareLocations(spirv->outputLocations, reflected.outputLocations, "output"); !same) return same;
  for (const auto& [slot, kind] : spirv->descriptors) {
    const auto it = reflected.descriptors.find(slot);
    if (it == reflected.descriptors.end()) {
      return Failure{fmt::format("it binds {} at set {}, binding {} that the reflection lacks", className(kind),
                                 slot.set, slot.binding)};
    }
    if (it->second != kind) {
      return Failure{fmt::format("at set {}, binding {} it binds {}, the reflection {}", slot.set, slot.binding,
                                 className(kind), className(it->second))};
    }
  }
  for (const auto& [slot, kind] : reflected.descriptors) {
    if (!spirv->descriptors.contains(slot)) {
      return Failure{fmt::format("the reflection binds {} at set {}, binding {} that it lacks", className(kind),
                                 slot.set, slot.binding)};
    }
  }
  return {};
}

}  // namespace spire::engine
