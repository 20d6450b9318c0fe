#include "gen/pipeline_generator.h"

#include <fmt/format.h>

#include <algorithm>

namespace spire::testgen {
namespace {

// Worlds in topological order: abstract ones, then compute (it feeds the
// others through buffers and uniforms), bake, vertex and fragment worlds.
int kindRank(WorldKind kind) { return static_cast<int>(kind); }

std::vector<WorldKind> pickKinds(RandomSource& rng) {
  const int total = rng.pick(2, 9);
  std::vector<WorldKind> kinds = {WorldKind::Mesh, WorldKind::Vertex};
  while (static_cast<int>(kinds.size()) < total) {
    const int roll = rng.pick(0, 99);
    const WorldKind kind = roll < 22   ? WorldKind::Uniform
                           : roll < 30 ? WorldKind::Mesh
                           : roll < 52 ? WorldKind::Compute
                           : roll < 66 ? WorldKind::Bake
                           : roll < 92 ? WorldKind::Fragment
                                       : WorldKind::Vertex;
    kinds.push_back(kind);
  }
  std::stable_sort(kinds.begin(), kinds.end(), [](WorldKind a, WorldKind b) { return kindRank(a) < kindRank(b); });
  return kinds;
}

const char* kindPrefix(WorldKind kind) {
  switch (kind) {
    case WorldKind::Uniform: return "U";
    case WorldKind::Mesh: return "M";
    case WorldKind::Compute: return "C";
    case WorldKind::Bake: return "T";
    case WorldKind::Vertex: return "V";
    case WorldKind::Fragment: return "F";
  }
  return "W";
}

void addWorlds(PipelineSpec& p, RandomSource& rng) {
  int counts[6] = {};
  for (WorldKind kind : pickKinds(rng)) {
    const int k = counts[kindRank(kind)]++;
    p.worlds.push_back({fmt::format("{}{}", kindPrefix(kind), k), kind, rng.chance(10)});
    const int index = static_cast<int>(p.worlds.size()) - 1;
    if (kind == WorldKind::Vertex) p.vertexWorlds.push_back(index);
  }
  // The last fragment world (earlier ones may feed it through textures);
  // without one, the output is a varying of the first vertex world.
  p.outputWorld = p.vertexWorlds[0];
  for (size_t w = 0; w < p.worlds.size(); ++w) {
    if (p.worlds[w].kind == WorldKind::Fragment) p.outputWorld = static_cast<int>(w);
  }
  for (size_t i = 0; i < p.worlds.size(); ++i) p.declOrder.push_back(static_cast<int>(i));
  // Declaration order must not matter (ties in the topological order aside).
  if (rng.chance(50)) rng.shuffle(p.declOrder);
}

// The first world of a kind, -1 if none.
int firstOf(const PipelineSpec& p, WorldKind kind) {
  for (size_t i = 0; i < p.worlds.size(); ++i) {
    if (p.worlds[i].kind == kind) return static_cast<int>(i);
  }
  return -1;
}

// The import from a world of kind `a` into one of kind `b`, or "" for none.
// `forced` asks for the edge the consumer needs (its mesh or vertex source).
std::string edgeStrategy(const PipelineSpec& p, int from, int to, bool forced, RandomSource& rng) {
  const WorldKind a = p.worlds[static_cast<size_t>(from)].kind;
  const WorldKind b = p.worlds[static_cast<size_t>(to)].kind;
  const std::string uv = "textureImport(m0_uv)";
  switch (a) {
    case WorldKind::Uniform: return rng.chance(60) ? "uniformImport" : "";
    case WorldKind::Mesh:
      if (b == WorldKind::Compute)
        return forced || rng.chance(60) ? (rng.chance(3) ? "standardImport" : "bufferImport") : "";
      if (b == WorldKind::Fragment) return rng.chance(8) ? "standardImport" : "";
      return forced || rng.chance(50) ? "standardImport" : "";
    case WorldKind::Compute:
      if (b == WorldKind::Compute || b == WorldKind::Vertex) {
        return rng.chance(45) ? "bufferImport" : rng.chance(25) ? "uniformImport" : "";
      }
      if (b == WorldKind::Fragment && rng.chance(3)) return "bufferImport";  // refused: no buffers in fragments
      return rng.chance(30) ? "uniformImport" : "";
    case WorldKind::Bake:
      if (b == WorldKind::Fragment) return rng.chance(65) ? uv : "";
      return b == WorldKind::Bake || b == WorldKind::Vertex ? (rng.chance(12) ? uv : "") : "";
    case WorldKind::Vertex: return b == WorldKind::Fragment && (forced || rng.chance(25)) ? "standardImport" : "";
    case WorldKind::Fragment: return b == WorldKind::Fragment && rng.chance(30) ? uv : "";
  }
  return "";
}

// Mesh M0 feeds every vertex, bake and compute world and V0 every fragment
// world, so `m0_uv` (textureImport's argument) reaches every consumer.
bool isForced(const PipelineSpec& p, int from, int to) {
  const WorldKind b = p.worlds[static_cast<size_t>(to)].kind;
  if (from == firstOf(p, WorldKind::Mesh))
    return b == WorldKind::Vertex || b == WorldKind::Bake || b == WorldKind::Compute;
  return from == firstOf(p, WorldKind::Vertex) && b == WorldKind::Fragment;
}

void addImports(PipelineSpec& p, RandomSource& rng) {
  for (size_t to = 0; to < p.worlds.size(); ++to) {
    if (p.worlds[to].isAbstract()) continue;
    for (size_t from = 0; from < to; ++from) {
      const int f = static_cast<int>(from), t = static_cast<int>(to);
      std::string strategy = edgeStrategy(p, f, t, isForced(p, f, t), rng);
      if (!strategy.empty()) p.imports.push_back({f, t, std::move(strategy)});
    }
  }
  // Routing must not depend on the order imports are declared in.
  rng.shuffle(p.imports);
}

void computeReach(PipelineSpec& p) {
  const size_t n = p.worlds.size();
  p.reach.assign(n, 0);
  for (size_t w = n; w-- > 0;) {
    p.reach[w] = 1u << w;
    for (const GenImport& i : p.imports) {
      if (i.from == static_cast<int>(w)) p.reach[w] |= p.reach[static_cast<size_t>(i.to)];
    }
  }
}

void addMeshAttributes(PipelineSpec& p, RandomSource& rng) {
  for (size_t w = 0; w < p.worlds.size(); ++w) {
    if (p.worlds[w].kind != WorldKind::Mesh) continue;
    const std::string m = fmt::format("m{}", p.worlds[w].name.substr(1));
    const int world = static_cast<int>(w);
    p.inputs.push_back({m + "_pos", ValueType::Vec3, world, true});
    p.inputs.push_back({m + "_uv", ValueType::Vec2, world, true});
    if (rng.chance(60)) p.inputs.push_back({m + "_normal", ValueType::Vec3, world, true});
    if (rng.chance(30)) p.inputs.push_back({m + "_color", ValueType::Vec4, world, true});
    if (rng.chance(15)) p.inputs.push_back({m + "_weight", ValueType::Float, world, true});
    if (rng.chance(10)) p.inputs.push_back({m + "_frame", ValueType::Mat3, world, true});
  }
}

const char* exportOf(WorldKind kind) {
  switch (kind) {
    case WorldKind::Compute: return "bufferExport";
    case WorldKind::Vertex: return "vertexExport";
    default: return "standardExport";
  }
}

const char* stageOf(WorldKind kind) {
  switch (kind) {
    case WorldKind::Compute: return "compute";
    case WorldKind::Vertex: return "vertex";
    default: return "fragment";
  }
}

}  // namespace

std::string PipelineSpec::text() const {
  std::string out = fmt::format("pipeline {} {{\n", name);
  for (int w : declOrder) {
    const GenWorld& world = worlds[static_cast<size_t>(w)];
    if (world.isAbstract()) {
      out += fmt::format("    abstract world {};\n", world.name);
      continue;
    }
    const std::string attr = world.stageAttribute ? fmt::format("[Stage: \"{}\"] ", stageOf(world.kind)) : "";
    const std::string args = world.kind == WorldKind::Vertex ? fmt::format("({})", positionOf(w)) : "";
    out += fmt::format("    {}world {} : \"GLSL\" export {}{};\n", attr, world.name, exportOf(world.kind), args);
  }
  for (const GenImport& i : imports) {
    out += fmt::format("    import {}->{} using {};\n", worlds[static_cast<size_t>(i.from)].name,
                       worlds[static_cast<size_t>(i.to)].name, i.strategy);
  }
  for (const GenInput& in : inputs) {
    if (in.inPipeline) {
      out += fmt::format("    @{} {} {};\n", worlds[static_cast<size_t>(in.world)].name, typeName(in.type), in.name);
    }
  }
  for (int v : vertexWorlds) {
    out += fmt::format("    abstract @{} vec4 {};\n", worlds[static_cast<size_t>(v)].name, positionOf(v));
  }
  out += fmt::format("    abstract export @{} vec4 output;\n}}\n\n", worlds[static_cast<size_t>(outputWorld)].name);
  return out;
}

uint32_t PipelineSpec::concreteMask() const {
  uint32_t mask = 0;
  for (size_t w = 0; w < worlds.size(); ++w) {
    if (!worlds[w].isAbstract()) mask |= 1u << w;
  }
  return mask;
}

std::string PipelineSpec::positionOf(int vertexWorld) const {
  return fmt::format("clip{}", worlds[static_cast<size_t>(vertexWorld)].name.substr(1));
}

PipelineSpec generatePipeline(RandomSource& rng) {
  PipelineSpec p;
  p.name = "GenPipeline";
  addWorlds(p, rng);
  addImports(p, rng);
  computeReach(p);
  addMeshAttributes(p, rng);
  if (rng.chance(40)) {
    const int u = firstOf(p, WorldKind::Uniform);
    if (u >= 0) p.inputs.push_back({"u_shared", ValueType::Vec4, u, true});
  }
  return p;
}

}  // namespace spire::testgen
