#include "graph/locked_placement.h"

#include <fmt/format.h>

#include <algorithm>
#include <iterator>

#include "graph/variant_builder.h"
#include "sema/locked_worlds.h"

namespace spire::graph {
namespace {

WorldMask finalizedBy(const sem::Shader& s) {
  WorldMask mask = 0;
  for (const ast::NameRef& ref : s.decl->finalizes) {
    if (auto w = s.pipeline->findWorld(ref.name)) mask |= WorldMask{1} << *w;
  }
  return mask;
}

// E4015 at the derived read, naming the base's placement.
Diagnostic& reportMoved(const LockedMove& move, const ShaderGraph& graph, DiagnosticList& diags) {
  const sem::Pipeline& pipeline = graph.pipeline();
  const ComponentNode& node = graph.node(move.component);
  const std::string& name = node.component->name;
  const std::string& finalizer = move.finalizer->name;
  const sem::WorldId movedTo = node.alternatives[move.moved].world;
  const std::string base = move.held ? fmt::format("shaders derived from '{}' compute '{}' in '{}'", finalizer, name,
                                                   pipeline.worlds[node.alternatives[*move.held].world].name)
                                     : fmt::format("shaders derived from '{}' do not compute '{}'", finalizer, name);
  return diags.report(
      DiagCode::E4015, move.reader->dependencyUses[move.use],
      fmt::format("'{}' is not available in world '{}', where '{}' is defined: {}, and computing it in '{}' "
                  "would {} the finalized world '{}', whose kernel they all share; to compute it there for all of "
                  "them, decide '{}.{} = {}'",
                  name, pipeline.worlds[move.readerWorld].name, graph.node(move.readerComponent).component->name, base,
                  pipeline.worlds[movedTo].name, movedTo == move.lockedWorld ? "add it to" : "send it through",
                  pipeline.worlds[move.lockedWorld].name, finalizer, name, graph.altName(node, move.moved)));
}

// E4015 at the derived definition, with a note at the base's read.
Diagnostic& reportPassesThrough(const LockedMove& move, const ShaderGraph& graph, DiagnosticList& diags) {
  const sem::Pipeline& pipeline = graph.pipeline();
  const Alternative& alt = graph.node(move.component).alternatives[move.moved];
  const std::string& name = graph.node(move.component).component->name;
  const std::string& reader = graph.node(move.readerComponent).component->name;
  Diagnostic& d = diags.report(
      DiagCode::E4015, alt.definition->decl->nameRange,
      fmt::format("'{}', computed in '{}', reaches '{}' in world '{}' only through the finalized world '{}', and a "
                  "shader derived from '{}' passes nothing through it that '{}' does not",
                  name, pipeline.worlds[alt.world].name, reader, pipeline.worlds[move.readerWorld].name,
                  pipeline.worlds[move.lockedWorld].name, move.finalizer->name, move.finalizer->name));
  d.note(move.reader->dependencyUses[move.use], fmt::format("'{}' reads it here", reader));
  return d;
}

void reportMove(const LockedMove& move, const ShaderGraph& graph, DiagnosticList& diags) {
  Diagnostic& d =
      move.kind == LockedMove::Kind::Moved ? reportMoved(move, graph, diags) : reportPassesThrough(move, graph, diags);
  const std::string& locked = graph.pipeline().worlds[move.lockedWorld].name;
  if (const ast::NameRef* clause = sem::finalizingClause(*move.finalizer, locked)) {
    d.note(clause->range, fmt::format("'{}' is finalized here", locked));
  }
}

}  // namespace

std::vector<LockLevel> lockLevels(const sem::Shader& shader) {
  std::vector<const sem::Shader*> finalizers;
  for (const sem::Shader* s = shader.base; s; s = s->base) {
    if (finalizedBy(*s)) finalizers.push_back(s);
  }
  std::vector<LockLevel> levels;
  WorldMask locked = 0;
  for (auto it = finalizers.rbegin(); it != finalizers.rend(); ++it) {
    locked |= finalizedBy(**it);
    levels.push_back({*it, locked});
  }
  return levels;
}

uint32_t lockDepth(const sem::Shader& shader, std::string_view origin) {
  // A pipeline's name is never met: its components sit above every shader.
  uint32_t above = 0;
  bool reached = false;
  for (const sem::Shader* s = &shader; s; s = s->base) {
    if (reached && finalizedBy(*s)) ++above;
    reached = reached || s->name == origin;
  }
  return reached ? above : 0;
}

WorldMask lockedAbove(const sem::Shader& shader, std::string_view origin) {
  const uint32_t depth = lockDepth(shader, origin);
  return depth ? lockLevels(shader)[depth - 1].locked : 0;
}

LockedFootprint lockedFootprint(const ShaderGraph& graph, sem::ComponentId component, AltId alt, WorldMask reach,
                                WorldMask locked) {
  LockedFootprint footprint;
  const sem::WorldId from = graph.node(component).alternatives[alt].world;
  if ((locked >> from) & 1) footprint.lockedAlternative = alt;
  const sem::Pipeline& pipeline = graph.pipeline();
  for (sem::WorldId to = 0; to < pipeline.worlds.size(); ++to) {
    if (to == from || !((reach >> to) & 1)) continue;
    for (uint32_t k : graph.route(component, from, to)) {
      const sem::Import& import = pipeline.imports[k];
      if (((locked >> import.from) & 1) || ((locked >> import.to) & 1)) footprint.imports.push_back(k);
    }
  }
  std::sort(footprint.imports.begin(), footprint.imports.end());
  footprint.imports.erase(std::unique(footprint.imports.begin(), footprint.imports.end()), footprint.imports.end());
  return footprint;
}

sem::WorldId changedLockedWorld(const ShaderGraph& graph, sem::ComponentId component, const LockedFootprint& held,
                                const LockedFootprint& moved, WorldMask locked) {
  const auto& alternatives = graph.node(component).alternatives;
  if (held.lockedAlternative != moved.lockedAlternative) {
    return alternatives[moved.lockedAlternative ? *moved.lockedAlternative : *held.lockedAlternative].world;
  }
  std::vector<uint32_t> changed;
  std::set_symmetric_difference(held.imports.begin(), held.imports.end(), moved.imports.begin(), moved.imports.end(),
                                std::back_inserter(changed));
  const sem::Import& import = graph.pipeline().imports[changed.front()];
  return ((locked >> import.to) & 1) ? import.to : import.from;
}

bool reportLockedMove(const ChoiceSpace& space, DiagnosticList& diags) {
  const std::optional<LockedMove> move = explainLockedMove(space);
  if (!move) return false;
  reportMove(*move, space.graph(), diags);
  return true;
}

}  // namespace spire::graph
