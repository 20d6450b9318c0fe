// Front-end throughput (Google Benchmark; not a CTest test). Run it with
// bench/frontend-throughput, or directly: build/bin/spire_bench_frontend.
//
// BM_FrontEnd_1000Components  load + parse + analyse a generated shader with
//                             1000 components on a 9-world pipeline through
//                             spire::FrontEnd, the path spirec takes
// BM_Parse_1000Components     parse only (lexing included), syntax/parser.h
// BM_Lex_1000Components       lex only, syntax/lexer.h
#include <benchmark/benchmark.h>

#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "driver/frontend.h"
#include "generate_shader.h"
#include "support/diagnostic_renderer.h"
#include "syntax/lexer.h"
#include "syntax/parser.h"

namespace {

constexpr int kComponents = 1000;
constexpr int kWorlds = 9;

const std::string& benchSource() {
  static const std::string source = spire::bench::generateShader(kComponents, kWorlds);
  return source;
}

spire::FrontEndOptions benchOptions() {
  spire::FrontEndOptions options;
  options.readFile = [](const std::string&) -> std::optional<std::string> { return std::nullopt; };
  return options;
}

// Runs the whole front end once; on errors returns their rendering.
std::optional<std::string> frontEndErrors() {
  spire::FrontEnd frontEnd(benchOptions());
  frontEnd.addSource("bench.spire", benchSource());
  frontEnd.analyze();
  if (!frontEnd.diagnostics().hasErrors()) return std::nullopt;
  return spire::renderDiagnostics(frontEnd.sources(), frontEnd.diagnostics(), spire::DiagnosticFormat::Text);
}

void skipIfInvalid(benchmark::State& state) {
  static const std::optional<std::string> errors = frontEndErrors();
  if (errors) {
    std::fprintf(stderr, "the generated benchmark program has errors:\n%s", errors->c_str());
    state.SkipWithError("generated program has front-end errors");
  }
}

void BM_FrontEnd_1000Components(benchmark::State& state) {
  skipIfInvalid(state);
  const std::string& source = benchSource();
  for (auto _ : state) {
    if (state.error_occurred()) break;
    spire::FrontEnd frontEnd(benchOptions());
    frontEnd.addSource("bench.spire", source);
    const spire::sem::Model& model = frontEnd.analyze();
    benchmark::DoNotOptimize(&model);
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(source.size()));
  state.counters["components"] = kComponents;
}
BENCHMARK(BM_FrontEnd_1000Components)->Unit(benchmark::kMillisecond);

void BM_Parse_1000Components(benchmark::State& state) {
  skipIfInvalid(state);
  const std::string& source = benchSource();
  for (auto _ : state) {
    if (state.error_occurred()) break;
    spire::SourceManager sources;
    spire::DiagnosticList diags;
    spire::ast::Program program;
    const spire::FileId file = sources.addFile("bench.spire", source);
    std::unique_ptr<spire::ast::Module> module = spire::parseModule(sources, file, program, diags);
    benchmark::DoNotOptimize(module.get());
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(source.size()));
}
BENCHMARK(BM_Parse_1000Components)->Unit(benchmark::kMillisecond);

void BM_Lex_1000Components(benchmark::State& state) {
  skipIfInvalid(state);
  const std::string& source = benchSource();
  spire::SourceManager sources;
  const spire::FileId file = sources.addFile("bench.spire", source);
  for (auto _ : state) {
    if (state.error_occurred()) break;
    spire::DiagnosticList diags;
    std::vector<spire::Token> tokens = spire::lexFile(sources, file, diags);
    benchmark::DoNotOptimize(tokens.data());
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(source.size()));
}
BENCHMARK(BM_Lex_1000Components)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
