// libFuzzer target for the files the engine tools read besides Spire
// sources: scene files, level-of-detail policy files and spire-simplify's
// rule files. The first byte picks the reader ('S', 'P' or 'R'; any other
// byte by its value modulo 3), the rest is the file's text. Each reader
// must either give a value and no error, or report at least one error, and
// every one of its diagnostics has a place and renders (fuzz_support.h). A
// policy that reads must write a file that reads back to itself; rules that
// read are matched against every definition of every example shader, as
// spire-simplify does.
//
// Built two ways (see CMakeLists.txt beside this file):
//   spire_engine_files_fuzzer  clang + -fsanitize=fuzzer,address,undefined (fuzz preset)
//   spire_engine_files_replay  any compiler, with replay_main.cpp: the CTest
//                              FuzzEngineFilesCorpusRegression over corpus_engine_files/
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz/fuzz_support.h"
#include "lod/lod_policy.h"
#include "scene/scene_file.h"
#include "simplify/rewrite_rules.h"
#include "simplify/user_rules.h"

namespace {

using spire::DiagnosticList;
using spire::SourceManager;

// What every reader promises: a value exactly when there is no error, and
// every diagnostic at a place in the file but the one that says the error
// limit is reached (E2005), which is about the whole file.
void checkOutcome(bool read, const SourceManager& sources, const DiagnosticList& diags) {
  if (read == diags.hasErrors()) spire::fuzz::fail(read ? "read with errors" : "refused without an error");
  for (const spire::Diagnostic& d : diags.all()) {
    if (!d.range.valid() && d.code != spire::DiagCode::E2005) spire::fuzz::fail("a diagnostic without a place");
  }
  spire::fuzz::checkRenderings(sources, diags);
}

void scene(std::string text) {
  SourceManager sources;
  DiagnosticList diags;
  // The reader opens none of the files a scene names: any folder will do.
  const auto read = spire::scene::parseSceneFile("fuzz.json", std::move(text), ".", sources, diags);
  checkOutcome(read.has_value(), sources, diags);
}

void policy(std::string text) {
  SourceManager sources;
  DiagnosticList diags;
  const auto read = spire::lod::parseLodPolicy("policy.json", std::move(text), sources, diags);
  checkOutcome(read.has_value(), sources, diags);
  if (!read) return;
  const std::string written = spire::lod::formatLodPolicy(*read);
  SourceManager again;
  DiagnosticList againDiags;
  const auto reread = spire::lod::parseLodPolicy("policy.json", written, again, againDiags);
  if (!reread || spire::lod::formatLodPolicy(*reread) != written) spire::fuzz::fail("a policy that does not read back");
}

void rules(std::string text) {
  spire::simplify::UserRules rules;
  const bool read = rules.add("fuzz.rules", std::move(text));
  checkOutcome(read, rules.sources(), rules.diagnostics());
  if (!read || rules.rules().empty()) return;
  spire::ShaderLibrary& library = spire::fuzz::exampleLibrary();
  for (const std::string& name : library.shaderNames()) {
    const spire::sem::Shader* shader = library.model().findShader(name);
    if (!shader) continue;
    for (const spire::sem::Component& component : shader->components) {
      for (const spire::sem::Definition& definition : component.definitions) {
        if (definition.isInput()) continue;
        for (const spire::simplify::Rewrite& rewrite :
             spire::simplify::proposeRewrites(library.model(), library.sources(), *definition.decl, rules.rules())) {
          if (!rewrite.range.valid()) spire::fuzz::fail("a rewrite without a place");
        }
      }
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  std::string text(reinterpret_cast<const char*>(data) + 1, size - 1);
  const uint8_t kind = data[0] == 'S' ? 0 : data[0] == 'P' ? 1 : data[0] == 'R' ? 2 : data[0] % 3;
  if (kind == 0) scene(std::move(text));
  if (kind == 1) policy(std::move(text));
  if (kind == 2) rules(std::move(text));
  return 0;
}
