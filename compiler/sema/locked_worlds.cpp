#include "sema/locked_worlds.h"

#include <fmt/format.h>

#include <algorithm>

#include "sema/analyzer_impl.h"

namespace spire::sem {

const ast::NameRef* finalizingClause(const Shader& base, std::string_view world) {
  for (const Shader* s = &base; s; s = s->base) {
    for (const ast::NameRef& ref : s->decl->finalizes) {
      if (ref.name == world) return &ref;
    }
  }
  return nullptr;
}

bool isLocked(const Shader& base, WorldId world) {
  return std::find(base.finalizedWorlds.begin(), base.finalizedWorlds.end(), world) != base.finalizedWorlds.end();
}

std::optional<WorldId> lockedWorldOf(const Shader& base, const Component& component) {
  for (const Definition& d : component.definitions) {
    if (d.isInput()) continue;
    if (d.world && isLocked(base, *d.world)) return d.world;
    if (!d.world && !base.finalizedWorlds.empty()) return base.finalizedWorlds.front();
  }
  return std::nullopt;
}

std::optional<WorldId> lockedAgainstRedefinition(const Shader& base, const Component& component) {
  if (component.requiredWorld && isLocked(base, *component.requiredWorld)) return component.requiredWorld;
  return lockedWorldOf(base, component);
}

bool Analyzer::checkLockedDefinition(const Shader& base, const Pipeline& pipeline, const ast::ComponentDecl& decl) {
  if (base.finalizedWorlds.empty() || !decl.hasDefinition()) return true;
  const Component* inherited = base.findComponent(decl.name);
  std::optional<WorldId> world;
  if (decl.world)
    world = pipeline.findWorld(*decl.world);
  else if (inherited)
    world = inherited->requiredWorld;
  std::string message;
  SourceRange where = decl.world ? decl.worldRange : decl.nameRange;
  if (world && isLocked(base, *world)) {
    message = decl.world ? fmt::format("world '{}' is finalized by '{}'; a derived shader cannot add definitions there",
                                       pipeline.worlds[*world].name, base.name)
                         : fmt::format(
                               "'{}' can only be computed in world '{}', which is finalized by '{}'; a derived "
                               "shader cannot redefine it",
                               decl.name, pipeline.worlds[*world].name, base.name);
  } else if (inherited && (world = lockedWorldOf(base, *inherited))) {
    where = decl.nameRange;
    message = fmt::format(
        "'{}' is defined by '{}' and may be computed in world '{}', which is finalized; a derived "
        "shader cannot redefine it",
        decl.name, inherited->origin, pipeline.worlds[*world].name);
  } else {
    return true;
  }
  Diagnostic& d = diags_.report(DiagCode::E4020, where, message);
  if (const ast::NameRef* clause = finalizingClause(base, pipeline.worlds[*world].name)) {
    d.note(clause->range, fmt::format("'{}' is finalized here", clause->name));
  }
  return false;
}

}  // namespace spire::sem
