#include "fuzz/fuzz_support.h"

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include <cstdio>
#include <cstdlib>
#include <memory>

#include "reflection/reflection_json.h"
#include "support/diagnostic_renderer.h"

namespace spire::fuzz {

void fail(std::string_view what) {
  std::fprintf(stderr, "spire fuzz invariant violated: %.*s\n", static_cast<int>(what.size()), what.data());
  std::abort();
}

void checkRenderings(const SourceManager& sources, const DiagnosticList& diags) {
  const std::string text = renderDiagnostics(sources, diags, DiagnosticFormat::Text);
  const std::string json = renderDiagnostics(sources, diags, DiagnosticFormat::Json);
  if (!diags.all().empty() && text.empty()) fail("diagnostics rendered as empty text");
  const nlohmann::json parsed = nlohmann::json::parse(json, nullptr, /*allow_exceptions=*/false);
  if (parsed.is_discarded()) fail("JSON diagnostics are not valid JSON");
  if (!parsed.contains("diagnostics") || !parsed["diagnostics"].is_array() ||
      parsed["diagnostics"].size() != diags.all().size()) {
    fail("JSON diagnostics do not match the diagnostic list");
  }
  if (!parsed.contains("errorCount") || parsed["errorCount"] != diags.errorCount()) {
    fail("JSON errorCount does not match the diagnostic list");
  }
}

void reportAll(const std::vector<Diagnostic>& from, DiagnosticList& to) {
  for (const Diagnostic& d : from) to.report(d.code, d.range, d.message).notes = d.notes;
}

bool hasInternalError(const std::vector<Diagnostic>& diags) {
  for (const Diagnostic& d : diags) {
    if (d.code == DiagCode::E6002) return true;
  }
  return false;
}

ShaderLibrary& exampleLibrary() {
  static ShaderLibrary* library = [] {
    // Never destroyed: the fuzzers exit without running it, and a static
    // destructor racing libFuzzer's exit would only add noise.
    auto* lib = new ShaderLibrary();
    for (const char* name : {"terrain", "terrain_five_world", "couch", "gltf_material", "lod_library"}) {
      const std::string path = fmt::format("{}/examples/{}.spire", SPIRE_SOURCE_DIR, name);
      if (!lib->addFile(path)) fail(fmt::format("cannot read {}", path));
    }
    if (!lib->compile()) {
      std::fputs(renderDiagnostics(lib->sources(), lib->diagnostics(), DiagnosticFormat::Text).c_str(), stderr);
      fail("the examples do not compile together");
    }
    return lib;
  }();
  return *library;
}

FileId mirrorWith(const SourceManager& from, SourceManager& to, std::string path, std::string text) {
  for (FileId id = 0; id < from.fileCount(); ++id) {
    const SourceFile& file = from.file(id);
    to.addFile(file.path, file.text, file.logicalName);
  }
  return to.addFile(std::move(path), std::move(text));
}

void checkCompiled(const CompiledVariant& compiled, bool spirv) {
  const reflection::Variant& variant = compiled.reflection;
  if (variant.kernels.size() != compiled.kernels.size()) fail("reflection and kernels differ in number");
  // Through the text, as spirec writes reflection.json and the engine reads
  // it: writing text is what fails on strings JSON cannot hold.
  const auto reread = reflection::parseReflection(reflection::toJson(variant).dump());
  if (!reread) fail(fmt::format("reflection.json does not read back: {}", reread.error()));
  if (!(*reread == variant)) fail("reflection.json reads back as different reflection");
  for (size_t i = 0; i < compiled.kernels.size(); ++i) {
    if (compiled.kernels[i].glsl.empty()) fail("a kernel without GLSL");
    if (spirv && (compiled.kernels[i].spirv.empty() || variant.kernels[i].spirvHash.empty())) {
      fail("a kernel compiled with SPIR-V has no SPIR-V or no spirvHash");
    }
  }
}

}  // namespace spire::fuzz
