// Shader-graph throughput (Google Benchmark; not a CTest test). Run it with
// bench/graph-throughput, or directly: build/bin/spire_bench_graph.
//
// BM_Choices_1000Components   graph + constraint propagation + choice file of
//                             a generated 1000-component shader on a 9-world
//                             pipeline (target: under 20 ms)
// BM_Variant_1000Components   one variant of that shader, default placement
//                             plus a decision for every tenth choice
// BM_Variant_Terrain          one variant of examples/terrain.spire
//                             (target for both variant benchmarks: under 2 ms)
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdio>
#include <map>
#include <optional>
#include <string>

#include "driver/shader_library.h"
#include "generate_shader.h"
#include "support/diagnostic_renderer.h"

namespace {

struct Compiled {
  std::unique_ptr<spire::ShaderLibrary> library;
  std::string shader;
  std::string errors;
};

Compiled compileGenerated() {
  Compiled c;
  spire::FrontEndOptions options;
  options.readFile = [](const std::string&) -> std::optional<std::string> { return std::nullopt; };
  c.library = std::make_unique<spire::ShaderLibrary>(options);
  c.library->addSource("bench.spire", spire::bench::generateShader(1000, 9));
  if (!c.library->compile()) {
    c.errors = spire::renderDiagnostics(c.library->sources(), c.library->diagnostics(), spire::DiagnosticFormat::Text);
  }
  c.shader = "BenchShader";
  return c;
}

const Compiled& generated() {
  static const Compiled compiled = compileGenerated();
  return compiled;
}

void BM_Choices_1000Components(benchmark::State& state) {
  const Compiled& c = generated();
  if (!c.errors.empty()) {
    std::fprintf(stderr, "%s", c.errors.c_str());
    state.SkipWithError("generated program has errors");
    return;
  }
  const spire::sem::Model& model = c.library->model();
  const spire::sem::Shader* shader = model.findShader(c.shader);
  size_t lines = 0;
  for (auto _ : state) {
    spire::DiagnosticList diags;
    auto graph = spire::graph::ShaderGraph::build(*shader, diags);
    spire::graph::ChoiceSpace space(*graph);
    const std::string choices = spire::graph::writeChoiceFile(space);
    lines = static_cast<size_t>(std::count(choices.begin(), choices.end(), '\n'));
    benchmark::DoNotOptimize(choices.data());
  }
  // One counter name for every benchmark: the CSV reporter needs the same set.
  state.counters["items"] = static_cast<double>(lines);
}
BENCHMARK(BM_Choices_1000Components)->Unit(benchmark::kMillisecond);

void BM_Variant_1000Components(benchmark::State& state) {
  const Compiled& c = generated();
  if (!c.errors.empty()) {
    state.SkipWithError("generated program has errors");
    return;
  }
  const auto choices = c.library->choices(c.shader);
  std::map<std::string, std::string> decisions;
  for (size_t i = 0; i < choices.size(); i += 10) {
    const auto& choice = choices[i];
    decisions[choice.key.substr(choice.key.find('.') + 1)] = choice.names[i % choice.names.size()];
  }
  size_t live = 0;
  for (auto _ : state) {
    const auto variant = c.library->buildVariant(c.shader, decisions);
    live = variant ? variant->live().size() : 0;
    benchmark::DoNotOptimize(live);
  }
  state.counters["items"] = static_cast<double>(live);
}
BENCHMARK(BM_Variant_1000Components)->Unit(benchmark::kMillisecond);

void BM_Variant_Terrain(benchmark::State& state) {
  spire::ShaderLibrary library;
  library.addFile(std::string(SPIRE_SOURCE_DIR) + "/examples/terrain.spire");
  if (!library.compile()) {
    state.SkipWithError("examples/terrain.spire has errors");
    return;
  }
  const std::map<std::string, std::string> decisions = {
      {"mixFactor", "PrebakeTex"}, {"albedo", "PrebakeTex"}, {"normal", "Vertex"}, {"lighting", "Fragment:basic"}};
  for (auto _ : state) {
    const auto variant = library.buildVariant("Terrain", decisions);
    benchmark::DoNotOptimize(variant->live().size());
  }
  state.counters["items"] = static_cast<double>(decisions.size());
}
BENCHMARK(BM_Variant_Terrain)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
