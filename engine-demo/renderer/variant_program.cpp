#include "renderer/variant_program.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstring>
#include <optional>

#include "reflection/reflection_json.h"
#include "renderer/spirv_interface.h"
#include "support/content_hash.h"
#include "support/file_io.h"

namespace spire::engine {

const KernelProgram* VariantProgram::kernel(std::string_view world) const {
  const auto it =
      std::find_if(kernels.begin(), kernels.end(), [&](const KernelProgram& k) { return k.world == world; });
  return it == kernels.end() ? nullptr : &*it;
}

const KernelProgram* VariantProgram::kernelWithRole(WorldRole role) const {
  const auto it = std::find_if(kernels.begin(), kernels.end(),
                               [&](const KernelProgram& k) { return k.pass && k.pass->kind == role; });
  return it == kernels.end() ? nullptr : &*it;
}

const WorldPass* KernelProgram::sourcePass(const KernelInput& input) const {
  const auto index = static_cast<size_t>(&input - inputs.data());
  return index < inputPasses.size() ? inputPasses[index] : nullptr;
}

std::optional<WorldRole> KernelProgram::sourceRole(const KernelInput& input) const {
  const WorldPass* source = sourcePass(input);
  return source ? std::optional(source->kind) : std::nullopt;
}

std::string VariantProgram::fingerprint() const {
  std::string key;
  for (const KernelProgram& k : kernels) key += fmt::format("{}={};", k.world, k.hash);
  return key;
}

namespace {

// The pass of `world` (resolveWorldPasses), or nullptr for a world the
// engine does not know.
const WorldPass* passOf(const WorldPasses& passes, std::string_view world) {
  const auto it = passes.find(world);
  return it != passes.end() ? it->second : nullptr;
}

}  // namespace

Expected<VariantProgram> makeProgram(const reflection::Variant& reflection,
                                     const std::map<std::string, std::vector<uint32_t>>& spirv) {
  VariantProgram program;
  program.shader = reflection.shader;
  program.pipeline = reflection.pipeline;
  program.placement = reflection.placement;
  const auto passes = resolveWorldPasses(reflection.worlds);
  if (!passes) return Error(passes.error());
  for (const reflection::Kernel& kernel : reflection.kernels) {
    const auto words = spirv.find(kernel.world);
    if (words == spirv.end() || words->second.empty()) {
      return Error{fmt::format("no SPIR-V for kernel '{}'", kernel.world), {}};
    }
    KernelProgram& added = program.kernels.emplace_back(KernelProgram{kernel, words->second, nullptr, {}});
    added.pass = passOf(*passes, kernel.world);
    for (const KernelInput& input : kernel.inputs) added.inputPasses.push_back(passOf(*passes, input.from));
    if (added.pass) {
      if (auto edges = checkEdges(added, *added.pass, added.inputPasses); !edges) return Error(edges.error());
    }
    if (auto matching = checkInterface(added.spirv, added); !matching) {
      return Error{fmt::format("the SPIR-V of kernel '{}' does not match its reflection: {}", kernel.world,
                               matching.error().message),
                   {}};
    }
  }
  return program;
}

Expected<VariantProgram> parseReflection(const nlohmann::ordered_json& document,
                                         const std::map<std::string, std::vector<uint32_t>>& spirv) {
  auto reflection = reflection::fromJson(document);
  if (!reflection) return Error{reflection.error(), {}};
  return makeProgram(*reflection, spirv);
}

namespace {

// The words of one kernel's .spv file, checked against the hash the
// reflection recorded when both were written.
Expected<std::vector<uint32_t>> readKernelSpirv(const std::filesystem::path& directory,
                                                const reflection::Kernel& kernel) {
  if (kernel.spirvFile.empty() || kernel.spirvFile.find_first_of("/\\") != std::string::npos ||
      kernel.spirvFile == "." || kernel.spirvFile == "..") {
    return Error{fmt::format("kernel '{}' names SPIR-V file '{}', which is not a file name in the reflection's "
                             "directory",
                             kernel.world, kernel.spirvFile),
                 {}};
  }
  const std::filesystem::path file = directory / kernel.spirvFile;
  if (kernel.spirvHash.empty()) {
    return Error{
        fmt::format("kernel '{}' has no SPIR-V hash: compile it with spirec --emit spirv or both", kernel.world), {}};
  }
  const auto bytes = readWholeFile(file.string());
  if (!bytes || bytes->empty() || bytes->size() % 4 != 0) {
    return Error{fmt::format("cannot read SPIR-V '{}' (missing, or not a whole number of words)", file.string()), {}};
  }
  if (const std::string hash = spire::contentHash(*bytes); hash != kernel.spirvHash) {
    return Error{fmt::format("'{}' is not the kernel this reflection describes (its hash is {}, the reflection's {}): "
                             "the directory mixes the output of two compiles",
                             file.string(), hash, kernel.spirvHash),
                 {}};
  }
  std::vector<uint32_t> words(bytes->size() / 4);
  std::memcpy(words.data(), bytes->data(), bytes->size());
  return words;
}

}  // namespace

Expected<VariantProgram> loadProgram(const std::filesystem::path& directory) {
  const std::filesystem::path reflectionPath = directory / "reflection.json";
  const auto text = readWholeFile(reflectionPath.string());
  if (!text) return Error{fmt::format("cannot read '{}'", reflectionPath.string()), {}};
  const auto reflection = reflection::parseReflection(*text);
  if (!reflection) return Error{fmt::format("{}: {}", reflectionPath.string(), reflection.error()), {}};
  std::map<std::string, std::vector<uint32_t>> spirv;
  for (const reflection::Kernel& kernel : reflection->kernels) {
    auto words = readKernelSpirv(directory, kernel);
    if (!words) return words.error();
    spirv[kernel.world] = std::move(words).value();
  }
  auto program = makeProgram(*reflection, spirv);
  if (!program) return Error{fmt::format("{}: {}", reflectionPath.string(), program.error().message), {}};
  return program;
}

Expected<VariantProgram> programFrom(const CompiledVariant& compiled) {
  std::map<std::string, std::vector<uint32_t>> spirv;
  for (size_t i = 0; i < compiled.kernels.size(); ++i) {
    spirv[compiled.reflection.kernels[i].world] = compiled.kernels[i].spirv;
  }
  return makeProgram(compiled.reflection, spirv);
}

}  // namespace spire::engine
