// libFuzzer target for decision files: the input bytes are the text of one
// decision file, applied as `spirec --decisions FILE` applies it to the
// examples (fuzz_support.h: every examples/*.spire in one library, compiled
// once per process). The file is parsed, its prefixes checked against the
// model, and applied to every concrete shader's choice space; each shader
// that a line names and that gets a variant is compiled to GLSL and its
// reflection (no SPIR-V: glslang is slow and not ours to fuzz, the variant
// target samples it). Every diagnostic is rendered as text and JSON.
//
// Built two ways (see CMakeLists.txt beside this file):
//   spire_decisions_fuzzer  clang + -fsanitize=fuzzer,address,undefined (fuzz preset)
//   spire_decisions_replay  any compiler, with replay_main.cpp: the CTest
//                           FuzzDecisionsCorpusRegression over corpus_decisions/
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz/fuzz_support.h"
#include "graph/decision_file.h"

namespace {

// Whether a decision line can apply to `shader`: its prefix is the shader,
// one of its bases, or the group-derived declaration it instantiates. The
// others would build the default variant, which the front-end target covers.
bool named(const spire::graph::DecisionFile& decisions, const spire::sem::Shader& shader) {
  for (const spire::graph::DecisionLine& line : decisions.lines) {
    for (const spire::sem::Shader* s = &shader; s; s = s->base) {
      if (s->name == line.prefix) return true;
    }
    if (shader.derivedFrom && shader.decl->name == line.prefix) return true;
  }
  return false;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace spire;
  ShaderLibrary& library = fuzz::exampleLibrary();
  SourceManager sources;
  const FileId file = fuzz::mirrorWith(library.sources(), sources, "fuzz.decisions",
                                       std::string(reinterpret_cast<const char*>(data), size));

  DiagnosticList diags;
  const graph::DecisionFile decisions = graph::parseDecisionFile(sources, file, diags);
  graph::checkDecisionPrefixes(decisions, library.model(), diags);

  CompileOptions options;
  options.spirv = false;
  for (const std::string& name : library.shaderNames()) {
    if (!named(decisions, library.choiceSpace(name)->graph().shader())) continue;
    bool fresh = false;
    const CompileResult result = fuzz::compileCached(library, name, decisions, options, fresh);
    if (result) {
      if (fresh) fuzz::checkCompiled(**result, /*spirv=*/false);
      fuzz::reportAll((*result)->warnings, diags);
    } else {
      if (result.error().message.empty()) fuzz::fail("a refused variant without a message");
      if (fuzz::hasInternalError(result.error().diagnostics)) fuzz::fail("an internal error (E6002)");
      fuzz::reportAll(result.error().diagnostics, diags);
    }
  }
  fuzz::checkRenderings(sources, diags);
  return 0;
}
