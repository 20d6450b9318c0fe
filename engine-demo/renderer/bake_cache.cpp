#include "renderer/bake_cache.h"

#include <fmt/format.h>

#include "renderer/world_roles.h"

namespace spire::engine {

namespace {

// Everything a bake's result depends on, as text.
std::string bakeKey(const KernelProgram& kernel, const std::string& meshKey, const MaterialValues& material,
                    const std::map<WorldRole, std::string>& upstream) {
  std::string key = fmt::format("{}|{}|{}", kernel.world, kernel.hash, meshKey);
  // Format and size hints change the result but not the kernel's code.
  for (const KernelOutput& output : kernel.outputs) {
    for (const auto& [name, value] : output.hints) key += fmt::format("|{}[{}={}]", output.component, name, value);
  }
  for (const KernelInput& input : kernel.inputs) {
    const WorldPass* pass = kernel.sourcePass(input);
    if (!pass) continue;
    if (const auto it = upstream.find(pass->kind); it != upstream.end()) {
      key += fmt::format("|{}<-[{}]", input.component, it->second);
    } else if (const auto value = material.find(input.component); value != material.end()) {
      key += fmt::format("|{}={}", input.component, value->second.identity);
    }
  }
  return key;
}

template <class Result, class Run>
Expected<const Result*> cached(std::map<std::string, Result>& results, std::map<std::string, double>& times,
                               const std::string& key, BakedInputs& baked, const std::string& world, Run&& run) {
  if (const auto it = results.find(key); it != results.end()) {
    baked.records.push_back({world, times[key], true});
    return &it->second;
  }
  BakeTiming timing;
  auto result = run(timing);
  if (!result) return result.error();
  times[key] = timing.milliseconds;
  baked.records.push_back({world, timing.milliseconds, false});
  return &results.emplace(key, std::move(result).value()).first->second;
}

}  // namespace

Expected<BakedInputs> BakeCache::bake(const vk::Context& ctx, ModuleCache& modules, const VariantProgram& program,
                                      const GpuMesh& mesh, const std::string& meshKey, const MaterialValues& material,
                                      HazardCollector* hazards) {
  const PipelineCaches caches{modules, pipelines_};
  BakedInputs baked;
  BindingSources sources;
  sources.mesh = &mesh;
  sources.material = &material;
  sources.hazards = hazards;
  std::map<WorldRole, std::string> upstream;
  for (const WorldPass& pass : worldPassTable()) {
    const KernelProgram* kernel = program.kernelWithRole(pass.kind);
    if (!kernel) continue;
    const std::string key = bakeKey(*kernel, meshKey, material, upstream);
    switch (pass.kind) {
      case WorldRole::UniformBake: {
        auto result = cached(uniform_, milliseconds_, key, baked, kernel->world,
                             [&](BakeTiming& timing) { return runUniformBake(ctx, caches, *kernel, sources, timing); });
        if (!result) return result.error();
        baked.uniform = sources.uniformBake = *result;
        break;
      }
      case WorldRole::VertexBake: {
        auto result = cached(vertex_, milliseconds_, key, baked, kernel->world,
                             [&](BakeTiming& timing) { return runVertexBake(ctx, caches, *kernel, sources, timing); });
        if (!result) return result.error();
        baked.vertex = sources.vertexBake = *result;
        break;
      }
      case WorldRole::TextureBake: {
        auto result = cached(texture_, milliseconds_, key, baked, kernel->world, [&](BakeTiming& timing) {
          return runTextureBake(ctx, caches, *kernel, sources, textureOptions_, timing);
        });
        if (!result) return result.error();
        baked.texture = sources.textureBake = *result;
        break;
      }
      default: continue;
    }
    upstream[pass.kind] = key;
  }
  return baked;
}

}  // namespace spire::engine
