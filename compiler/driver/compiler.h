// The compiler's one compile path: decisions in, a compiled variant out.
// spirec, the engine, the tuner and the tools all compile variants here, so
// every variant gets the same kernels, the same validated SPIR-V and the same
// typed reflection, and one variant is compiled once per library.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "driver/shader_library.h"
#include "graph/decision_file.h"
#include "reflection/reflection.h"
#include "support/diagnostic.h"
#include "support/expected.h"

namespace spire {

class SpirvCache;

struct CompileOptions {
  // Compile each kernel to SPIR-V and validate it. Off, only GLSL is made:
  // glslang's start-up costs more than the rest of a spirec run.
  bool spirv = true;
  // A decision that is not applied (unknown, infeasible, conflicting) fails
  // the compile instead of warning: measuring or shipping a variant other
  // than the one asked for is worthless.
  bool strictDecisions = false;
  // The output root under which the GLSL of a kernel that glslang or the
  // validator rejects is saved, as ROOT/<directory>/<World>.glsl, for a bug
  // report; empty: nowhere.
  std::string saveRejectedTo;
  // Kernels that record, per pixel, vertex or texel, the first component to
  // go NaN or Inf (reflection::HazardRecord): for diagnosis only, since the
  // checks change what the kernels cost.
  bool instrumentHazards = false;
  // SPIR-V made earlier in this process (spirec --batch), consulted and
  // filled when `spirv` is on; null: every kernel goes through glslang.
  SpirvCache* spirvCache = nullptr;
};

struct CompiledKernel {
  std::string glsl;
  std::vector<uint32_t> spirv;  // empty when CompileOptions::spirv is off
};

struct CompiledVariant {
  std::string shader;
  std::string directory;           // file-system-safe shader name (`TerrainLOD-BaseMaterialLQ`)
  reflection::Variant reflection;  // its kernels are parallel to `kernels`
  std::vector<CompiledKernel> kernels;
  std::string placement;  // the variant as decision-file lines
  std::vector<Diagnostic> warnings;
  // In-memory decisions only: the components whose decision was not applied
  // (unknown, or infeasible with the others), for callers such as the tuner
  // that record them rather than refuse them.
  std::vector<std::string> skippedDecisions;
};

struct CompileError {
  std::string message;
  std::vector<Diagnostic> diagnostics;  // render with the library's sources
};

using CompiledVariantPtr = std::shared_ptr<const CompiledVariant>;
using CompileResult = Expected<CompiledVariantPtr, CompileError>;

// Decisions as data: component -> "World" or "World:variation", plus
// attributes as a decision line would carry them (`[Format: "RGBA8"]`).
struct Decisions {
  std::map<std::string, std::string> placement;
  ShaderLibrary::Attributes attributes;
};

// The variant of `shader` that a decision file states.
CompileResult compileVariant(ShaderLibrary& library, std::string_view shader, const graph::DecisionFile& decisions,
                             const CompileOptions& options = {});
// The variant of `shader` that in-memory decisions state.
CompileResult compileVariant(ShaderLibrary& library, std::string_view shader, const Decisions& decisions,
                             const CompileOptions& options = {});
// A variant already built, for callers that collect diagnostics themselves
// (spirec, per group member); null after errors, which go to `diags`.
CompiledVariantPtr compileVariant(ShaderLibrary& library, const graph::Variant& variant, const CompileOptions& options,
                                  DiagnosticList& diags);

}  // namespace spire
