// Optional group members (paper section 6.1): a shader derived from a group
// becomes one instance per member; an instance of an optional member that
// fails, at any stage, for a reason of its own is left out with warning W4101
// instead of failing the compile.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "sema/semantic_model.h"
#include "support/diagnostic.h"

namespace spire::sem {

// The name a group's member gives the shaders made from it (`Derived<Name>`):
// its own, or for a member that is itself made from a group (`Barrel<LodHQ>`,
// when `B : Barrel`) the original member's, so that `B<LodHQ>` is LodHQ's
// shader of B as `Barrel<LodHQ>` is of Barrel, whatever the depth.
const std::string& memberName(const Shader& member);

// Whether `shader` is the instance of an optional member of a group.
bool isOptionalMemberInstance(const Shader& shader);

// Reports W4101 at `derived`'s name: the instance for `member` is left out
// because of `errors` (the reported diagnostics it caused). The first error's
// text is the reason; every error becomes a note at its location.
void reportMemberLeftOut(DiagnosticList& diags, const ast::ShaderDecl& derived, const std::string& member,
                         const std::vector<Diagnostic>& errors);

// Runs a stage (graph building, decisions, code generation) for `shader`.
// For an optional member's instance the stage reports into a list of its
// own, and if it fails the errors become one W4101 that leaves the member
// out; internal and I/O errors are forwarded unchanged, since they are no
// fault of the member. Returns the stage's result (false when it failed).
bool runMemberStage(const Shader& shader, DiagnosticList& diags, const std::function<bool(DiagnosticList&)>& stage);

}  // namespace spire::sem
