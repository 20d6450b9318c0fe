#include "gen/interface_check.h"

#include <fmt/format.h>

#include <algorithm>
#include <map>

namespace spire::testgen {

using Json = nlohmann::ordered_json;

int locationSpan(const std::string& type) {
  const size_t bracket = type.rfind('[');
  if (bracket != std::string::npos) {
    return std::stoi(type.substr(bracket + 1)) * locationSpan(type.substr(0, bracket));
  }
  if (type.rfind("mat", 0) == 0 && type.size() > 3) return type[3] - '0';  // matC or matCxR: C columns
  return 1;
}

namespace {

const Json* kernelOf(const codegen::GeneratedShader& shader, const std::string& world) {
  for (const codegen::Kernel& k : shader.kernels) {
    if (k.world == world) return &k.reflection;
  }
  return nullptr;
}

const Json* outputOf(const Json& kernel, const std::string& component) {
  for (const Json& o : kernel["outputs"]) {
    if (o.contains("component") && o["component"] == component) return &o;
  }
  return nullptr;
}

bool writesOutVariables(const Json& kernel) {
  for (const Json& o : kernel["outputs"]) {
    if (o.contains("location")) return true;
  }
  return false;
}

const Json* blockAt(const Json& kernel, const Json& binding) {
  for (const Json& b : kernel["blocks"]) {
    if (b["binding"] == binding) return &b;
  }
  return nullptr;
}

// Entries of `list` with a location whose spans overlap.
void overlaps(const Json& kernel, const char* list, std::vector<std::string>& problems) {
  std::map<int, std::string> used;  // location -> component
  for (const Json& e : kernel[list]) {
    if (!e.contains("location")) continue;
    const int first = e["location"].get<int>();
    const std::string component = e.value("component", std::string("?"));
    for (int l = first; l < first + locationSpan(e["type"].get<std::string>()); ++l) {
      if (const auto [it, fresh] = used.emplace(l, component); !fresh) {
        problems.push_back(fmt::format("{} kernel: {} '{}' and '{}' both use location {}",
                                       kernel["world"].get<std::string>(), list, it->second, component, l));
      }
    }
  }
}

std::string describe(const Json& kernel, const Json& input) {
  return fmt::format("{} kernel reads '{}' ({}) from {}", kernel["world"].get<std::string>(),
                     input["component"].get<std::string>(), input["strategy"].get<std::string>(),
                     input["from"].get<std::string>());
}

// A location input against the producer's `out` variable.
void checkVarying(const Json& kernel, const Json& input, const Json& producer, std::vector<std::string>& problems) {
  if (!writesOutVariables(producer)) {
    problems.push_back(describe(kernel, input) + " at a location, but that kernel writes no out variables");
    return;
  }
  const Json* out = outputOf(producer, input["component"].get<std::string>());
  if (!out || !out->contains("location")) {
    problems.push_back(describe(kernel, input) + ", which does not write it to an out variable");
  } else if ((*out)["location"] != input["location"] || (*out)["type"] != input["type"]) {
    problems.push_back(fmt::format("{} at location {} as {}, written at location {} as {}", describe(kernel, input),
                                   input["location"].dump(), input["type"].dump(), (*out)["location"].dump(),
                                   (*out)["type"].dump()));
  }
}

// A buffer input against the producer's record.
void checkRecord(const Json& kernel, const Json& input, const Json& producer, bool repacked,
                 std::vector<std::string>& problems) {
  const Json* out = outputOf(producer, input["component"].get<std::string>());
  if (!out || !out->contains("offset")) {
    problems.push_back(describe(kernel, input) + ", which does not write it to its buffer");
    return;
  }
  if (repacked) {
    if ((*out)["type"] != input["type"]) {
      problems.push_back(fmt::format("{} as {}, written as {}", describe(kernel, input), input["type"].dump(),
                                     (*out)["type"].dump()));
    }
    return;
  }
  const Json* mine = blockAt(kernel, input["binding"]);
  const Json* theirs = blockAt(producer, (*out)["binding"]);
  if ((*out)["offset"] != input["offset"] || (*out)["type"] != input["type"] ||
      (mine && theirs && (*mine)["recordStride"] != (*theirs)["recordStride"])) {
    problems.push_back(fmt::format("{} at record offset {}, written at offset {} (record strides {} and {})",
                                   describe(kernel, input), input["offset"].dump(), (*out)["offset"].dump(),
                                   mine ? (*mine)["recordStride"].dump() : "?",
                                   theirs ? (*theirs)["recordStride"].dump() : "?"));
  }
}

void checkInput(const codegen::GeneratedShader& shader, const sem::Pipeline& pipeline, const Json& kernel,
                const Json& input, bool repacked, std::vector<std::string>& problems) {
  const std::string from = input["from"].get<std::string>();
  const auto world = pipeline.findWorld(from);
  if (world && pipeline.worlds[*world].isAbstract) return;  // supplied by the engine
  const Json* producer = kernelOf(shader, from);
  if (!producer) {
    problems.push_back(describe(kernel, input) + ", which has no kernel");
    return;
  }
  if (input.contains("location")) {
    checkVarying(kernel, input, *producer, problems);
  } else if (input.contains("sampler")) {
    const Json* out = outputOf(*producer, input["component"].get<std::string>());
    if (!out) problems.push_back(describe(kernel, input) + " through a texture, but that kernel does not write it");
  } else if (input.contains("index")) {
    checkRecord(kernel, input, *producer, repacked, problems);
  }
}

}  // namespace

std::vector<std::string> checkInterfaces(const codegen::GeneratedShader& shader, const sem::Pipeline& pipeline,
                                         const std::vector<sem::WorldId>& lockedWorlds) {
  std::vector<std::string> problems;
  for (const codegen::Kernel& k : shader.kernels) {
    overlaps(k.reflection, "inputs", problems);
    overlaps(k.reflection, "outputs", problems);
    const auto world = pipeline.findWorld(k.world);
    const bool repacked =
        world && std::find(lockedWorlds.begin(), lockedWorlds.end(), *world) != lockedWorlds.end();
    for (const Json& input : k.reflection["inputs"]) checkInput(shader, pipeline, k.reflection, input, repacked, problems);
  }
  return problems;
}

}  // namespace spire::testgen
