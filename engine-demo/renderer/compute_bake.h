// The compute bakes, run once at load: PrebakeUniform (a kernel over the
// mesh's vertices whose outputs are averaged into per-mesh uniform values,
// the "parameter stage" of He et al. 2015) and PrebakeVertex (a kernel per
// vertex whose record buffer later kernels read as vertex data). Timed on the
// host, since lavapipe's timestamps around dispatches are not meaningful.
#pragma once

#include "renderer/kernel_bindings.h"
#include "renderer/pipeline_cache.h"

namespace spire::engine {

struct BakeTiming {
  std::string world;
  double milliseconds = 0.0;
};

// Pipelines come from `caches` and stay with the result.
Expected<UniformBakeResult> runUniformBake(const vk::Context& ctx, PipelineCaches caches, const KernelProgram& kernel,
                                           const BindingSources& sources, BakeTiming& timing);

Expected<VertexBakeResult> runVertexBake(const vk::Context& ctx, PipelineCaches caches, const KernelProgram& kernel,
                                         const BindingSources& sources, BakeTiming& timing);

}  // namespace spire::engine
