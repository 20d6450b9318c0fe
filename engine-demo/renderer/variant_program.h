// A compiled shader variant as the engine consumes it: the reflection of
// every kernel (docs/reflection.md) parsed into typed records, plus each
// kernel's SPIR-V. It comes either from the compiler library in process (the
// fast path, used by the demo and the tuner) or from a `spirec -o` directory
// (the path for build pipelines); both give the same program.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "driver/compiler.h"
#include "reflection/reflection.h"
#include "renderer/error.h"
#include "renderer/world_roles.h"

namespace spire::engine {

// The engine reads the compiler's typed reflection records as they are.
using reflection::Block;
using reflection::BlockMember;
using reflection::DescriptorSlot;
using reflection::InputKind;
using reflection::KernelInput;
using reflection::KernelOutput;
using reflection::OutputKind;
using reflection::ValueType;

// A kernel's reflection and its SPIR-V, with what the engine runs its world
// as and what supplies each of its inputs (world_roles.h).
struct KernelProgram : reflection::Kernel {
  std::vector<uint32_t> spirv;
  const WorldPass* pass = nullptr;            // nullptr: a world this engine does not know
  std::vector<const WorldPass*> inputPasses;  // parallel to `inputs`: the pass of each input's world

  // The pass of the world `input` (one of `inputs`) comes from, or nullptr.
  const WorldPass* sourcePass(const KernelInput& input) const;
  // Its role; nullopt for a world this engine does not know.
  std::optional<WorldRole> sourceRole(const KernelInput& input) const;
};

struct VariantProgram {
  std::string shader;
  std::string pipeline;
  std::vector<KernelProgram> kernels;  // producers before consumers
  // Every live, non-input component -> "World" or "World:variation", in
  // reflection order: the variant as a decision file would state it.
  std::vector<std::pair<std::string, std::string>> placement;

  const KernelProgram* kernel(std::string_view world) const;
  // The kernel of the world this engine runs as `role` (its [Role], or its
  // name), or nullptr.
  const KernelProgram* kernelWithRole(WorldRole role) const;
  // Hashes of every kernel, joined: equal for variants with identical code.
  std::string fingerprint() const;
};

// A program from reflection and each kernel's SPIR-V by world. Every
// kernel's words must be there, its interface must be the one the
// reflection states (spirv_interface.h), and every world's [Role] one this
// engine implements.
Expected<VariantProgram> makeProgram(const reflection::Variant& reflection,
                                     const std::map<std::string, std::vector<uint32_t>>& spirv);

// As makeProgram, from a reflection.json document.
Expected<VariantProgram> parseReflection(const nlohmann::ordered_json& reflection,
                                         const std::map<std::string, std::vector<uint32_t>>& spirv);

// The file path: `directory` holds reflection.json and the .spv files it
// names. Each file must be the one the reflection was written with (its
// recorded hash): a directory that mixes two compiles is an error.
Expected<VariantProgram> loadProgram(const std::filesystem::path& directory);

// The library path: a variant from driver/compiler.h, compiled with SPIR-V.
Expected<VariantProgram> programFrom(const CompiledVariant& compiled);

}  // namespace spire::engine
