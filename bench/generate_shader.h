// Deterministic generator of large, valid Spire programs for the front-end
// benchmarks (and for anyone who needs a big input: see spire_bench_generate).
#pragma once

#include <string>

namespace spire::bench {

// A program with one pipeline `BenchPipeline` of `worlds` worlds in all (two
// abstract ones, `Uniforms` and `MeshVertex`, then concrete worlds W0..Wn-1
// with n = worlds - 2, at least 1) and one shader `BenchShader` with
// `components` generated components plus the required `output`.
//
// The concrete worlds form a chain W0->W1->...->Wn-1 with a few skip edges
// (Wi->Wi+2 for every third i), so the import graph is a DAG with diamonds.
// Uniforms is imported into every concrete world with uniformImport and
// MeshVertex with standardImport; the last world has the pipeline's
// `abstract export @W<n-1> vec4 output;`.
//
// Components mix arithmetic on earlier components with dot, normalize, mix,
// clamp and sin; some have block bodies with locals, if and for; some are
// placed explicitly with @Wk (only where their dependencies are available);
// some have variations `name:a` / `name:b`. The result depends only on the
// arguments: the random choices come from a std::mt19937 with a fixed seed
// and a mapping to ranges written out here (not std::uniform_int_distribution,
// whose results differ between standard libraries).
std::string generateShader(int components, int worlds);

}  // namespace spire::bench
