// What the fuzz targets in this folder share (see CMakeLists.txt beside it):
// the way an invariant fails, the diagnostic-rendering oracle, and the
// example programs the decision and variant targets compile once.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "driver/compiler.h"
#include "driver/shader_library.h"
#include "support/diagnostic.h"
#include "support/source_manager.h"

namespace spire::fuzz {

// Reports a broken invariant as a crash so that libFuzzer records the input.
[[noreturn]] void fail(std::string_view what);

// Renders `diags` as text and as JSON and checks that both agree with the
// list: every diagnostic shows in the text, the JSON parses and has the
// same count of diagnostics and errors.
void checkRenderings(const SourceManager& sources, const DiagnosticList& diags);

// Reports `from` again into `to` (severity comes from the catalogue), so that
// a compile result's diagnostics go through checkRenderings too.
void reportAll(const std::vector<Diagnostic>& from, DiagnosticList& to);

bool hasInternalError(const std::vector<Diagnostic>& diags);

// Every example under examples/ in one library, analysed once per process
// (from the source tree: SPIRE_SOURCE_DIR). Failing to compile is fatal: the
// targets would then fuzz nothing.
ShaderLibrary& exampleLibrary();

// A new source manager with `from`'s files under the same ids, then `text` as
// one more file: diagnostics about an input and about the library render
// together, while the library's own manager does not grow with every input
// (which would also make libFuzzer see more mallocs than frees in every run
// and give up on leak detection).
FileId mirrorWith(const SourceManager& from, SourceManager& to, std::string path, std::string text);

// compileVariant through the library's variant cache, emptied whenever it
// holds kCachedVariants: most mutations lead to a variant compiled before,
// and generating it again would find nothing new (a crash would have
// happened the first time, and replays the same from an empty cache).
// `fresh`: this call generated the variant (check it; a cached one was).
inline constexpr size_t kCachedVariants = 256;
template <class Decided>
CompileResult compileCached(ShaderLibrary& library, std::string_view shader, const Decided& decisions,
                            const CompileOptions& options, bool& fresh) {
  auto& cache = library.compiledVariants();
  if (cache.size() >= kCachedVariants) cache.clear();
  const size_t before = cache.size();
  CompileResult result = compileVariant(library, shader, decisions, options);
  fresh = cache.size() > before;
  return result;
}

// Checks what every compiled variant must satisfy: one kernel per reflection
// kernel, reflection that survives its own JSON writer and reader
// (`fromJson(toJson(v)) == v`), and with SPIR-V, code and a spirvHash for
// every kernel.
void checkCompiled(const CompiledVariant& compiled, bool spirv);

}  // namespace spire::fuzz
