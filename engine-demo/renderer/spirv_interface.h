// What a SPIR-V module declares at its boundary, read from its decorations:
// the engine checks it against the reflection before binding anything, since
// a kernel whose interface differs from its reflection makes draws read
// unbound resources (a crash under the validation layer, a blank image
// without it).
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "reflection/reflection.h"
#include "support/expected.h"

namespace spire::engine {

enum class DescriptorClass { Opaque, Uniform, Storage };  // UniformConstant, Uniform, StorageBuffer

struct SpirvInterface {
  std::set<uint32_t> inputLocations;   // user `in` variables (not built-ins)
  std::set<uint32_t> outputLocations;  // user `out` variables
  std::map<reflection::DescriptorSlot, DescriptorClass> descriptors;
};

// The interface of `words`, or nullopt when they are not a SPIR-V module.
std::optional<SpirvInterface> readSpirvInterface(const std::vector<uint32_t>& words);

// Compares a kernel's SPIR-V with its reflection; an error naming the first
// difference.
spire::Expected<void, Failure> checkInterface(const std::vector<uint32_t>& words, const reflection::Kernel& kernel);

}  // namespace spire::engine
