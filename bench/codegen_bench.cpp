// Code-generation throughput (Google Benchmark; not a CTest test). Run it
// with bench/codegen-throughput, or directly: build/bin/spire_bench_codegen.
//
// BM_VariantAndGlsl_Terrain  build a Terrain variant and generate its GLSL
//                            through the library (target: under 1 ms)
// BM_Glslang_Terrain         glslang alone: GLSL -> SPIR-V for those kernels
// BM_Spirv_Terrain           spirec's SPIR-V step: glslang plus spirv-val
//                            (target: under 2x BM_Glslang_Terrain)
#include <benchmark/benchmark.h>

#include <string>

#include "codegen/kernel_generator.h"
#include "codegen/spirv_compiler.h"
#include "driver/shader_library.h"

namespace {

using namespace spire;

const std::map<std::string, std::string> kDecisions = {{"albedo", "PrebakeTex"}, {"lighting", "Fragment:ggx"}};

ShaderLibrary& terrain() {
  static ShaderLibrary* library = [] {
    auto* l = new ShaderLibrary();
    l->addFile(std::string(SPIRE_SOURCE_DIR) + "/examples/terrain.spire");
    l->compile();
    return l;
  }();
  return *library;
}

const std::vector<codegen::Kernel>& terrainKernels() {
  static const std::vector<codegen::Kernel> kernels = [] {
    ShaderLibrary& library = terrain();
    const auto variant = library.buildVariant("Terrain", kDecisions);
    return codegen::generateKernels(library.model(), library.sources(), *variant, codegen::StrategyRegistry::builtin(),
                                    library.diagnostics())
        ->kernels;
  }();
  return kernels;
}

void BM_VariantAndGlsl_Terrain(benchmark::State& state) {
  ShaderLibrary& library = terrain();
  for (auto _ : state) {
    const auto variant = library.buildVariant("Terrain", kDecisions);
    const auto generated = codegen::generateKernels(library.model(), library.sources(), *variant,
                                                    codegen::StrategyRegistry::builtin(), library.diagnostics());
    benchmark::DoNotOptimize(generated->kernels.data());
  }
}
BENCHMARK(BM_VariantAndGlsl_Terrain)->Unit(benchmark::kMillisecond);

void BM_Glslang_Terrain(benchmark::State& state) {
  const auto& kernels = terrainKernels();
  for (auto _ : state) {
    for (const codegen::Kernel& k : kernels) {
      const auto spirv = codegen::compileGlslToSpirv(k.stage, k.glsl, k.world);
      benchmark::DoNotOptimize(spirv.words.data());
    }
  }
}
BENCHMARK(BM_Glslang_Terrain)->Unit(benchmark::kMillisecond);

void BM_Spirv_Terrain(benchmark::State& state) {
  const auto& kernels = terrainKernels();
  for (auto _ : state) {
    for (const codegen::Kernel& k : kernels) {
      const auto spirv = codegen::compileGlslToSpirv(k.stage, k.glsl, k.world);
      const auto valid = codegen::validateSpirv(spirv.words);
      benchmark::DoNotOptimize(valid);
    }
  }
}
BENCHMARK(BM_Spirv_Terrain)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
