// The in-process compile chain the generator's property runs on, and the
// property itself: a variant is either refused with a diagnostic that is not
// an internal error, or all its kernels compile with glslang, pass the
// SPIR-V validator and agree on their interfaces (interface_check.h).
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "codegen/kernel_generator.h"
#include "driver/shader_library.h"

namespace spire::testgen {

// OrderDependentRoute: the same program with its imports declared in another
// order places or routes some value differently, or is refused only in one
// order (see campaign.h).
// LockedKernelNotShared: two shaders derived from one base that finalizes a
// world W got different W kernels for the same decision map (campaign.h).
enum class Verdict {
  Accepted,
  Refused,
  InternalError,
  InvalidKernel,
  InterfaceMismatch,
  OrderDependentRoute,
  LockedKernelNotShared
};
const char* verdictName(Verdict verdict);

struct VariantReport {
  std::string shader;  // empty when the whole program was refused
  Verdict verdict = Verdict::Accepted;
  std::vector<std::string> codes;  // error codes of a refusal, in order
  std::string detail;              // for anything but Accepted: what happened
  std::string routes;              // Accepted: the placement and where each kernel input comes from
  // Accepted: for each world W the shader's bases lock, "Base/W" (Base: the
  // shader whose `finalizes` names W) -> the W kernel's text ("" for none).
  std::map<std::string, std::string> lockedKernels;
  bool failed() const { return verdict != Verdict::Accepted && verdict != Verdict::Refused; }
};

// One program, compiled once; decision files are then applied to every
// concrete shader, as `spirec --decisions FILE -o DIR` does.
class ProgramChecker {
 public:
  // `compileKernels` false: stop after generating kernels (for comparing
  // routes only; glslang is most of the time).
  explicit ProgramChecker(std::string source, std::string displayPath = "generated.spire", bool compileKernels = true);

  // The front end's verdict: Accepted, or why the program has no variants.
  const VariantReport& frontEnd() const { return frontEnd_; }
  std::vector<std::string> shaders() const { return library_.shaderNames(); }
  std::vector<graph::Choice> choices(const std::string& shader) const { return library_.choices(shader); }

  // One report per concrete shader (one for the whole map when the decision
  // file itself is refused).
  std::vector<VariantReport> check(const std::string& decisions);

 private:
  // The front end reads `generated.decisions` from decisions_, files otherwise.
  FrontEndOptions readingDecisionsFromMemory();
  VariantReport checkVariant(const graph::Variant& variant, DiagnosticList& diags);
  std::optional<std::string> kernelProblem(const codegen::Kernel& kernel);
  VariantReport refusal(std::string shader, const DiagnosticList& diags) const;

  bool compileKernels_;
  std::string decisions_;  // served to the front end as `generated.decisions`
  ShaderLibrary library_;
  VariantReport frontEnd_;
  // Kernels repeat across decision maps; glslang is deterministic, so each
  // distinct text is compiled once (the value is the problem, if any).
  std::map<std::string, std::optional<std::string>> kernelCache_;
};

}  // namespace spire::testgen
