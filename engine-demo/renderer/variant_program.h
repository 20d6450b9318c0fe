// A compiled shader variant as the engine consumes it: the reflection of
// every kernel (docs/reflection.md) parsed into typed records, plus each
// kernel's SPIR-V. It comes either from the compiler library in process (the
// fast path, used by the demo and the tuner) or from a `spirec -o` directory
// (the path for build pipelines); both give the same program.
#pragma once

#include <compare>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "codegen/kernel_generator.h"
#include "renderer/error.h"
#include "renderer/world_roles.h"

namespace spire::engine {

// Where a kernel's resource is bound: a descriptor set and a binding in it
// (docs/reflection.md, Descriptor bindings). Bindings may restart at 0 in each
// kernel, so a binding number alone does not identify a resource.
struct DescriptorSlot {
  uint32_t set = 0;
  uint32_t binding = 0;
  auto operator<=>(const DescriptorSlot&) const = default;
};

// One member of a uniform block or of a storage buffer's record.
struct BlockMember {
  std::string component;
  std::string type;
  uint32_t offset = 0;
  uint32_t size = 0;
  uint32_t arrayStride = 0;
  uint32_t matrixStride = 0;
};

struct Block {
  std::string name;
  bool storage = false;  // storage buffer of records; otherwise a uniform block
  DescriptorSlot slot;
  uint32_t size = 0;          // uniform blocks
  uint32_t recordStride = 0;  // storage blocks
  std::vector<BlockMember> members;

  const BlockMember* member(std::string_view component) const;
};

enum class InputKind { UniformMember, Sampler, Varying, Texture, BufferMember };

struct KernelInput {
  InputKind kind = InputKind::Varying;
  std::string component;
  std::string type;
  std::string from;  // the producing world
  DescriptorSlot slot;    // UniformMember, Sampler, Texture, BufferMember
  uint32_t location = 0;  // Varying
  uint32_t channels = 4;  // Texture
};

enum class OutputKind { Varying, BuiltIn, BufferMember };

struct KernelOutput {
  OutputKind kind = OutputKind::Varying;
  std::string component;
  std::string type;
  uint32_t location = 0;  // Varying
  DescriptorSlot slot;    // BufferMember
  std::map<std::string, std::string> hints;
};

struct KernelProgram {
  std::string world;
  codegen::ShaderStage stage = codegen::ShaderStage::Fragment;
  std::string hash;
  std::vector<uint32_t> spirv;
  std::vector<KernelInput> inputs;
  std::vector<KernelOutput> outputs;
  std::vector<Block> blocks;

  const Block* block(DescriptorSlot slot) const;
};

struct VariantProgram {
  std::string shader;
  std::string pipeline;
  std::vector<KernelProgram> kernels;  // producers before consumers
  // Every live, non-input component -> "World" or "World:variation", in
  // reflection order: the variant as a decision file would state it.
  std::vector<std::pair<std::string, std::string>> placement;

  const KernelProgram* kernel(std::string_view world) const;
  // The kernel of the world this engine runs as `role` (worldPassTable()),
  // or nullptr.
  const KernelProgram* kernelWithRole(WorldRole role) const;
  // Hashes of every kernel, joined: equal for variants with identical code.
  std::string fingerprint() const;
};

// Parses a reflection.json document; `spirv` supplies each kernel's words by
// world. Malformed reflection is an error naming the offending field.
Expected<VariantProgram> parseReflection(const nlohmann::ordered_json& reflection,
                                         const std::map<std::string, std::vector<uint32_t>>& spirv);

// The file path: `directory` holds reflection.json and the .spv files it names.
Expected<VariantProgram> loadProgram(const std::filesystem::path& directory);

// The library path: compiles the generated GLSL of every kernel with glslang.
Expected<VariantProgram> compileProgram(const codegen::GeneratedShader& shader, const graph::Variant& variant);

}  // namespace spire::engine
