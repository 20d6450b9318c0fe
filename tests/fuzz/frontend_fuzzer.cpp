// libFuzzer target for the compiler: the input bytes are the text of one
// source file, which goes through spire::ShaderLibrary (lexer, parser, include
// loader, semantic analysis, shader graphs and choice spaces), then, when it
// compiles, through the default variant of every concrete shader and GLSL
// generation, and finally through both diagnostic renderers. (SPIR-V is left
// out: glslang is not ours to fuzz, and it would slow every run a hundredfold.)
//
// Built two ways (see CMakeLists.txt beside this file):
//   spire_frontend_fuzzer  clang + -fsanitize=fuzzer,address,undefined (fuzz preset)
//   spire_fuzz_replay      any compiler; replay_main.cpp runs this function
//                          over the seed corpus as the CTest FuzzCorpusRegression
//
// Nothing here touches the disk: `using "x";` includes are answered by an
// in-memory reader that knows no files.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "codegen/kernel_generator.h"
#include "driver/shader_library.h"
#include "fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using spire::fuzz::fail;
  spire::FrontEndOptions options;
  options.errorLimit = 20;
  options.readFile = [](const std::string&) -> std::optional<std::string> { return std::nullopt; };

  spire::ShaderLibrary library(std::move(options));
  library.addSource("fuzz.spire", std::string(reinterpret_cast<const char*>(data), size));
  if (library.compile()) {
    for (const std::string& shader : library.shaderNames()) {
      if (!library.choiceSpace(shader)) fail("a listed shader has no choice space");
      const auto variant = library.buildVariant(shader, {});
      if (!variant) fail("a consistent choice space gave no default variant");
      spire::codegen::generateKernels(library.model(), library.sources(), *variant,
                                      spire::codegen::StrategyRegistry::builtin(), library.diagnostics());
    }
  }
  // Cheap oracles beyond "does not crash": every diagnostic shows up in the
  // text rendering, and the JSON rendering is valid JSON that agrees with
  // the list.
  spire::fuzz::checkRenderings(library.sources(), library.diagnostics());
  return 0;
}
