// Runs the bake worlds a variant uses, once per distinct bake: results are
// keyed by (world, kernel hash, mesh, the values of the kernel's inputs,
// the bakes it reads), so instances and variants with identical prebake
// work share one result, and a variant without a bake world runs none.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "renderer/compute_bake.h"
#include "renderer/texture_bake.h"

namespace spire::engine {

struct BakeRecord {
  std::string world;
  double milliseconds = 0.0;  // of the run that produced the result
  bool reused = false;        // an identical bake had already run
};

struct BakedInputs {
  const UniformBakeResult* uniform = nullptr;
  const VertexBakeResult* vertex = nullptr;
  const TextureBakeResult* texture = nullptr;
  std::vector<BakeRecord> records;
};

class BakeCache {
 public:
  explicit BakeCache(TextureBakeOptions textureOptions = {}) : textureOptions_(textureOptions) {}

  // Runs (or reuses) every bake kernel of `program` in world-table order for
  // one instance: `meshKey` names the mesh, `material` its resolved values.
  // Instrumented bake kernels give their records to `hazards`.
  // Shader modules come from `modules`; pipelines from the cache's own
  // PipelineCache, apart from the draws' so that the renderer's pipeline
  // counts stay those of its draws, and kept by the results (one per kernel
  // and state, whatever the mesh).
  Expected<BakedInputs> bake(const vk::Context& ctx, ModuleCache& modules, const VariantProgram& program,
                             const GpuMesh& mesh, const std::string& meshKey, const MaterialValues& material,
                             HazardCollector* hazards = nullptr);

  size_t size() const { return uniform_.size() + vertex_.size() + texture_.size(); }
  const PipelineCounts& pipelineCounts() const { return pipelines_.counts(); }
  const TextureBakeOptions& textureOptions() const { return textureOptions_; }

 private:
  TextureBakeOptions textureOptions_;
  PipelineCache pipelines_;
  std::map<std::string, UniformBakeResult> uniform_;
  std::map<std::string, VertexBakeResult> vertex_;
  std::map<std::string, TextureBakeResult> texture_;
  std::map<std::string, double> milliseconds_;
};

}  // namespace spire::engine
