// Random pipelines for the generator (issue 12, "Testing at the scale of the
// space"): 2 to 9 worlds, all seven built-in strategies, abstract uniform-like
// and mesh-like worlds, compute worlds, several producers into one world,
// diamonds and equal-length alternative routes. Edges follow the strategy
// semantics of docs/reflection.md (a vertex kernel feeds fragments through
// standardImport, a compute kernel feeds others through buffers or uniforms,
// a fragment kernel through textures), plus a few edges the compiler must
// refuse with a clear diagnostic (standardImport into a compute world,
// bufferImport into a fragment world).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "gen/random_source.h"
#include "gen/value_type.h"

namespace spire::testgen {

// What a world is for. Abstract: Uniform, Mesh. Concrete: Compute
// (bufferExport), Bake (standardExport, rasterized by the engine in texture
// space from the mesh), Vertex (vertexExport), Fragment (standardExport).
enum class WorldKind { Uniform, Mesh, Compute, Bake, Vertex, Fragment };

struct GenWorld {
  std::string name;
  WorldKind kind;
  bool stageAttribute = false;  // `[Stage: "..."]`, which must agree with the export strategy
  bool isAbstract() const { return kind == WorldKind::Uniform || kind == WorldKind::Mesh; }
};

struct GenImport {
  int from = 0;  // indices into PipelineSpec::worlds
  int to = 0;
  std::string strategy;  // as written: `textureImport(m0_uv)`
};

// An input component: a mesh attribute (declared in the pipeline) or a
// uniform (declared in the pipeline or the first shader).
struct GenInput {
  std::string name;
  ValueType type;
  int world = 0;
  bool inPipeline = false;
};

struct PipelineSpec {
  std::string name;
  std::vector<GenWorld> worlds;    // topological order (producers first)
  std::vector<int> declOrder;      // the order the worlds are declared in
  std::vector<GenImport> imports;  // in declaration order
  std::vector<GenInput> inputs;
  std::vector<int> vertexWorlds;  // each has `abstract @Vk vec4 clipK;`
  int outputWorld = 0;            // `abstract export @W vec4 output;`
  std::vector<uint32_t> reach;    // reach[w]: worlds reachable from w, w included

  uint32_t concreteMask() const;
  std::string positionOf(int vertexWorld) const;  // `clip<k>`
  std::string text() const;
};

PipelineSpec generatePipeline(RandomSource& rng);

}  // namespace spire::testgen
