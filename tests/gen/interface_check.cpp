#include "gen/interface_check.h"

#include <fmt/format.h>

#include <algorithm>
#include <map>

namespace spire::testgen {

namespace rf = reflection;

int locationSpan(const rf::ValueType& type) {
  return static_cast<int>(type.columns * std::max<uint32_t>(type.arrayLength, 1));
}

namespace {

const rf::Kernel* kernelOf(const codegen::GeneratedShader& shader, const std::string& world) {
  for (const codegen::Kernel& k : shader.kernels) {
    if (k.world == world) return &k.reflection;
  }
  return nullptr;
}

const rf::KernelOutput* outputOf(const rf::Kernel& kernel, const std::string& component) {
  for (const rf::KernelOutput& o : kernel.outputs) {
    if (o.component == component) return &o;
  }
  return nullptr;
}

bool writesOutVariables(const rf::Kernel& kernel) {
  return std::any_of(kernel.outputs.begin(), kernel.outputs.end(),
                     [](const rf::KernelOutput& o) { return o.kind == rf::OutputKind::Varying; });
}

// Entries of `entries` at a location whose spans overlap.
template <typename Entry, typename VaryingKind>
void overlaps(const rf::Kernel& kernel, const std::vector<Entry>& entries, VaryingKind varying, const char* list,
              std::vector<std::string>& problems) {
  std::map<uint32_t, std::string> used;  // location -> component
  for (const Entry& e : entries) {
    if (e.kind != varying) continue;
    for (uint32_t l = e.location; l < e.location + static_cast<uint32_t>(locationSpan(e.type)); ++l) {
      if (const auto [it, fresh] = used.emplace(l, e.component); !fresh) {
        problems.push_back(fmt::format("{} kernel: {} '{}' and '{}' both use location {}", kernel.world, list,
                                       it->second, e.component, l));
      }
    }
  }
}

std::string describe(const rf::Kernel& kernel, const rf::KernelInput& input) {
  return fmt::format("{} kernel reads '{}' ({}) from {}", kernel.world, input.component, input.strategy, input.from);
}

// A location input against the producer's `out` variable.
void checkVarying(const rf::Kernel& kernel, const rf::KernelInput& input, const rf::Kernel& producer,
                  std::vector<std::string>& problems) {
  if (!writesOutVariables(producer)) {
    problems.push_back(describe(kernel, input) + " at a location, but that kernel writes no out variables");
    return;
  }
  const rf::KernelOutput* out = outputOf(producer, input.component);
  if (!out || out->kind != rf::OutputKind::Varying) {
    problems.push_back(describe(kernel, input) + ", which does not write it to an out variable");
  } else if (out->location != input.location || out->type != input.type) {
    problems.push_back(fmt::format("{} at location {} as {}, written at location {} as {}", describe(kernel, input),
                                   input.location, input.type.name, out->location, out->type.name));
  }
}

// A buffer input against the producer's record.
void checkRecord(const rf::Kernel& kernel, const rf::KernelInput& input, const rf::Kernel& producer, bool repacked,
                 std::vector<std::string>& problems) {
  const rf::KernelOutput* out = outputOf(producer, input.component);
  if (!out || out->kind != rf::OutputKind::BufferMember) {
    problems.push_back(describe(kernel, input) + ", which does not write it to its buffer");
    return;
  }
  if (repacked) {
    if (out->type != input.type) {
      problems.push_back(
          fmt::format("{} as {}, written as {}", describe(kernel, input), input.type.name, out->type.name));
    }
    return;
  }
  const rf::Block* mine = kernel.block(input.slot);
  const rf::Block* theirs = producer.block(out->slot);
  if (out->offset != input.offset || out->type != input.type ||
      (mine && theirs && mine->recordStride != theirs->recordStride)) {
    problems.push_back(fmt::format("{} at record offset {}, written at offset {} (record strides {} and {})",
                                   describe(kernel, input), input.offset, out->offset,
                                   mine ? fmt::to_string(mine->recordStride) : "?",
                                   theirs ? fmt::to_string(theirs->recordStride) : "?"));
  }
}

void checkInput(const codegen::GeneratedShader& shader, const sem::Pipeline& pipeline, const rf::Kernel& kernel,
                const rf::KernelInput& input, bool repacked, std::vector<std::string>& problems) {
  const auto world = pipeline.findWorld(input.from);
  if (world && pipeline.worlds[*world].isAbstract) return;  // supplied by the engine
  const rf::Kernel* producer = kernelOf(shader, input.from);
  if (!producer) {
    problems.push_back(describe(kernel, input) + ", which has no kernel");
    return;
  }
  switch (input.kind) {
    case rf::InputKind::Varying: checkVarying(kernel, input, *producer, problems); break;
    case rf::InputKind::Texture:
      if (!outputOf(*producer, input.component)) {
        problems.push_back(describe(kernel, input) + " through a texture, but that kernel does not write it");
      }
      break;
    case rf::InputKind::BufferMember: checkRecord(kernel, input, *producer, repacked, problems); break;
    case rf::InputKind::UniformMember:
    case rf::InputKind::Sampler:
    case rf::InputKind::PushConstant: break;
  }
}

}  // namespace

std::vector<std::string> checkInterfaces(const codegen::GeneratedShader& shader, const sem::Pipeline& pipeline,
                                         const std::vector<sem::WorldId>& lockedWorlds) {
  std::vector<std::string> problems;
  for (const codegen::Kernel& k : shader.kernels) {
    overlaps(k.reflection, k.reflection.inputs, rf::InputKind::Varying, "inputs", problems);
    overlaps(k.reflection, k.reflection.outputs, rf::OutputKind::Varying, "outputs", problems);
    const auto world = pipeline.findWorld(k.world);
    const bool repacked = world && std::find(lockedWorlds.begin(), lockedWorlds.end(), *world) != lockedWorlds.end();
    for (const rf::KernelInput& input : k.reflection.inputs) {
      checkInput(shader, pipeline, k.reflection, input, repacked, problems);
    }
  }
  return problems;
}

}  // namespace spire::testgen
