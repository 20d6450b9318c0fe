#include "sema/group_members.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>

namespace spire::sem {
namespace {

// Errors that say something is wrong with spirec or the machine, not with
// the combination of a shader and a group member.
bool isCompilerOrSystemError(DiagCode code) { return code == DiagCode::E6002 || code == DiagCode::E6003; }

}  // namespace

const std::string& memberName(const Shader& member) {
  return member.derivedFrom && member.base ? memberName(*member.base) : member.name;
}

bool isOptionalMemberInstance(const Shader& shader) {
  if (!shader.derivedFrom) return false;
  const auto& members = shader.derivedFrom->members;
  return std::any_of(members.begin(), members.end(),
                     [&](const GroupMember& m) { return m.shader == &shader && m.isOptional; });
}

void reportMemberLeftOut(DiagnosticList& diags, const ast::ShaderDecl& derived, const std::string& member,
                         const std::vector<Diagnostic>& errors) {
  const auto first =
      std::find_if(errors.begin(), errors.end(), [](const Diagnostic& d) { return d.severity == Severity::Error; });
  const std::string reason = first == errors.end() ? std::string("it does not fit") : first->message;
  Diagnostic& w =
      diags.report(DiagCode::W4101, derived.nameRange,
                   fmt::format("optional group member '{}' is left out of '{}': {}", member, derived.name, reason));
  for (const Diagnostic& e : errors) {
    w.note(e.range, fmt::format("{}[{}]: {}", severityName(e.severity), diagCodeInfo(e.code).name, e.message));
    for (const DiagNote& n : e.notes) w.note(n.range, n.message);
  }
}

bool runMemberStage(const Shader& shader, DiagnosticList& diags, const std::function<bool(DiagnosticList&)>& stage) {
  if (!isOptionalMemberInstance(shader)) return stage(diags);
  DiagnosticList own(UINT32_MAX);
  const bool ok = stage(own) && !own.hasErrors();
  const auto& reported = own.all();
  const bool forward = ok || std::any_of(reported.begin(), reported.end(),
                                         [](const Diagnostic& d) { return isCompilerOrSystemError(d.code); });
  if (!forward) {
    reportMemberLeftOut(diags, *shader.decl, shader.base->name, reported);
    return false;
  }
  for (const Diagnostic& d : reported) {
    Diagnostic& copy = diags.report(d.code, d.range, d.message);
    for (const DiagNote& n : d.notes) copy.note(n.range, n.message);
  }
  return ok;
}

}  // namespace spire::sem
