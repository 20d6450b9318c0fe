// Shaders, inheritance, groups, components and the component graph.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>

#include "sema/analyzer_impl.h"
#include "sema/attribute_catalog.h"
#include "sema/group_members.h"
#include "support/spelling.h"

namespace spire::sem {
namespace {

std::string definitionLabel(const std::optional<WorldId>& world, const std::string& variation, const Pipeline& p) {
  std::string label = world ? "@" + p.worlds[*world].name : std::string("without a world");
  if (!variation.empty()) label += " with variation '" + variation + "'";
  return label;
}

// Why a component declaration is rejected before it is added, if it is.
struct Rejection {
  SourceRange where;
  std::string message;
};

std::optional<Rejection> rejectionOf(const ast::ComponentDecl& decl, const Type* type, bool worldResolved,
                                     bool isWorldAbstract, bool isInput, bool inPipeline) {
  if (decl.isAbstract && decl.hasDefinition()) {
    return Rejection{decl.nameRange, fmt::format("abstract component '{}' cannot have a definition", decl.name)};
  }
  if (decl.isExport && !inPipeline) {
    return Rejection{decl.range,
                     fmt::format("'export' is only allowed on pipeline components, not on '{}'", decl.name)};
  }
  if (decl.isExport && isInput) {
    return Rejection{decl.nameRange, fmt::format("exported component '{}' must be abstract or defined", decl.name)};
  }
  if (!decl.variation.empty() && !decl.hasDefinition()) {
    return Rejection{decl.variationRange,
                     fmt::format("only a definition can have a variation name, not '{}'", decl.name)};
  }
  if (decl.hasDefinition() && isWorldAbstract) {
    return Rejection{
        decl.worldRange,
        fmt::format("component '{}' cannot be defined in abstract world '{}': abstract worlds hold no computation",
                    decl.name, *decl.world)};
  }
  if (isInput && !decl.world) {
    return Rejection{decl.nameRange, fmt::format("input component '{}' needs a world, as in '@MaterialUniform {} {};'",
                                                 decl.name, decl.type.name, decl.name)};
  }
  if (isInput && worldResolved && !isWorldAbstract) {
    return Rejection{decl.nameRange,
                     fmt::format("component '{}' in concrete world '{}' needs a definition; mark it 'abstract' if "
                                 "shaders must define it",
                                 decl.name, *decl.world)};
  }
  if (decl.isAbstract && isWorldAbstract) {
    return Rejection{decl.worldRange, fmt::format("abstract component '{}' must be at a concrete world, not '{}'",
                                                  decl.name, *decl.world)};
  }
  if (decl.hasDefinition() && type->containsOpaque()) {
    return Rejection{decl.type.range,
                     fmt::format("component '{}' of opaque type '{}' must be an input at an abstract world", decl.name,
                                 type->name())};
  }
  return std::nullopt;
}

void appendComponent(ComponentSet& set, Component component) {
  set.componentByName.emplace(component.name, static_cast<ComponentId>(set.components.size()));
  set.components.push_back(std::move(component));
}

// A rejected declaration still introduces its name, so that its uses do
// not cascade into "undeclared identifier" errors.
void addPlaceholder(ComponentSet& set, const ast::ComponentDecl& decl, const Type* type, const std::string& origin) {
  if (set.componentByName.count(decl.name)) return;
  Component placeholder;
  placeholder.name = decl.name;
  placeholder.type = type;
  placeholder.firstDecl = &decl;
  placeholder.origin = origin;
  appendComponent(set, std::move(placeholder));
}

void addFirstDeclaration(ComponentSet& set, const ast::ComponentDecl& decl, const Type* type,
                         std::optional<WorldId> world, const std::string& origin) {
  Component c;
  c.name = decl.name;
  c.type = type;
  c.firstDecl = &decl;
  c.origin = origin;
  c.isAbstract = decl.isAbstract;
  c.isExport = decl.isExport;
  if (decl.isAbstract) c.requiredWorld = world;
  for (const ast::Attribute& a : decl.attributes) c.attributes.push_back(&a);
  if (!decl.isAbstract) c.definitions.push_back({&decl, world, decl.variation, {}, {}, {}, origin, {}});
  appendComponent(set, std::move(c));
}

// An abstract redeclaration may only repeat or add the required world.
void redeclareAbstract(Component& existing, const Pipeline& pipeline, const ast::ComponentDecl& decl,
                       std::optional<WorldId> world, DiagnosticList& diags) {
  if (!existing.isAbstract || !existing.definitions.empty()) {
    diags
        .report(DiagCode::E4008, decl.nameRange,
                fmt::format("component '{}' is already defined and cannot be redeclared abstract", decl.name))
        .note(existing.firstDecl->nameRange, "previous declaration is here");
  } else if (world && existing.requiredWorld && *world != *existing.requiredWorld) {
    diags
        .report(DiagCode::E4008, decl.worldRange,
                fmt::format("abstract component '{}' is required at '{}' here, but at '{}' before", decl.name,
                            *decl.world, pipeline.worlds[*existing.requiredWorld].name))
        .note(existing.firstDecl->nameRange, "previous declaration is here");
  } else if (world) {
    existing.requiredWorld = world;
  }
}

// Adds a definition to a declared component, or overrides the base's
// definition of the same world and variation.
void addDefinition(Component& existing, const Pipeline& pipeline, const ast::ComponentDecl& decl,
                   std::optional<WorldId> world, const std::string& origin, DiagnosticList& diags) {
  const std::optional<WorldId> effectiveWorld = world ? world : existing.requiredWorld;
  Definition definition{&decl, effectiveWorld, decl.variation, {}, {}, {}, origin, {}};
  for (Definition& d : existing.definitions) {
    if (d.world != effectiveWorld || d.variation != decl.variation) continue;
    if (d.origin == origin) {
      diags
          .report(DiagCode::E3003, decl.nameRange,
                  fmt::format("redefinition of component '{}' {}", decl.name,
                              definitionLabel(effectiveWorld, decl.variation, pipeline)))
          .note(d.decl->nameRange, "previous definition is here");
      return;
    }
    // A derived shader overrides the base's definition of the same slot.
    d = std::move(definition);
    return;
  }
  existing.definitions.push_back(std::move(definition));
}

void mergeDeclaration(Component& existing, const Pipeline& pipeline, const ast::ComponentDecl& decl, const Type* type,
                      std::optional<WorldId> world, const std::string& origin, bool isInput, DiagnosticList& diags) {
  if (existing.type != type && !type->isError() && !existing.type->isError()) {
    diags
        .report(DiagCode::E4008, decl.type.range,
                fmt::format("conflicting types for component '{}': '{}' here, but '{}' in '{}'", decl.name,
                            type->name(), existing.type->name(), existing.origin))
        .note(existing.firstDecl->nameRange, "previous declaration is here");
    return;
  }
  for (const ast::Attribute& a : decl.attributes) existing.attributes.push_back(&a);
  const bool existingIsInput = !existing.definitions.empty() && existing.definitions.front().isInput();
  if (decl.isAbstract) return redeclareAbstract(existing, pipeline, decl, world, diags);
  // The same input declared again by a shader of the pipeline (or a derived
  // shader) that provides it: the engine supplies one value either way, so a
  // pipeline can rely on an input (a retargeting pipeline positioning its own
  // pass with matMVP) that the shaders written for it also declare.
  if (isInput && existingIsInput) {
    Definition& input = existing.definitions.front();
    if (input.origin != origin && input.world == world) {
      input.origin = origin;  // so that a second declaration in the same shader is still a redefinition
      return;
    }
  }
  if (isInput || existingIsInput) {
    diags
        .report(
            DiagCode::E3003, decl.nameRange,
            fmt::format("redefinition of component '{}'{}", decl.name, existingIsInput ? ", which is an input" : ""))
        .note(existing.firstDecl->nameRange, "previous declaration is here");
    return;
  }
  addDefinition(existing, pipeline, decl, world, origin, diags);
}

}  // namespace

const Component* ComponentSet::findComponent(std::string_view name) const {
  auto it = componentByName.find(name);
  return it == componentByName.end() ? nullptr : &components[it->second];
}

const Pipeline* Model::findPipeline(std::string_view name) const {
  for (const auto& p : pipelines) {
    if (p->name == name) return p.get();
  }
  return nullptr;
}

const Shader* Model::findShader(std::string_view name) const {
  for (const auto& s : shaders) {
    if (s->name == name) return s.get();
  }
  return nullptr;
}

const Group* Model::findGroup(std::string_view name) const {
  for (const auto& g : groups) {
    if (g->name == name) return g.get();
  }
  return nullptr;
}

void Analyzer::addComponent(ComponentSet& set, const Pipeline& pipeline, const ast::ComponentDecl& decl,
                            const std::string& origin, bool inPipeline) {
  checkAttributes(decl.attributes, AttributeSite::Component, diags_);
  BodyChecker types(*model_, diags_, functions_, nullptr);
  const Type* type = types.resolveType(decl.type);
  if (type->isVoid()) {
    diags_.report(DiagCode::E3004, decl.type.range, fmt::format("component '{}' cannot have type 'void'", decl.name));
    type = model_->types().error();
  }
  std::optional<WorldId> world;
  if (decl.world) world = resolveWorld(pipeline, *decl.world, decl.worldRange);
  const bool isWorldAbstract = world && pipeline.worlds[*world].isAbstract;
  const bool isInput = !decl.isAbstract && !decl.hasDefinition();

  if (auto rejection = rejectionOf(decl, type, world.has_value(), isWorldAbstract, isInput, inPipeline)) {
    diags_.report(DiagCode::E4011, rejection->where, std::move(rejection->message));
    return addPlaceholder(set, decl, type, origin);
  }
  if (decl.world && !world) return;  // unknown world, already reported

  auto existingIt = set.componentByName.find(decl.name);
  if (existingIt == set.componentByName.end()) return addFirstDeclaration(set, decl, type, world, origin);
  mergeDeclaration(set.components[existingIt->second], pipeline, decl, type, world, origin, isInput, diags_);
}

void Analyzer::checkComponentBodies(ComponentSet& set, const std::string& origin) {
  for (Component& component : set.components) {
    for (Definition& definition : component.definitions) {
      if (diags_.limitReached()) return;
      if (definition.origin != origin || definition.isInput()) continue;
      ComponentTableResolver resolver(set);
      BodyChecker checker(*model_, diags_, functions_, &resolver);
      const std::string owner = fmt::format("component '{}'", component.name);
      if (definition.decl->init)
        checker.checkConversion(*definition.decl->init, component.type, owner);
      else
        checker.checkBody(*definition.decl->body, component.type, owner);
      resolver.takeDependencies(definition.dependencies, definition.dependencyUses);
      definition.functions = checker.calledFunctions();
      definition.structs = checker.usedStructs();
    }
  }
}

void Analyzer::checkComponentCycles(Shader& shader) {
  const size_t n = shader.components.size();
  enum class Mark : uint8_t { None, Active, Done };
  std::vector<Mark> marks(n, Mark::None);
  // Iterative DFS (a long dependency chain must not exhaust the stack). Each
  // frame is a component and the position in its flattened edge list.
  struct Edge {
    ComponentId to;
    SourceRange use;
  };
  std::vector<std::vector<Edge>> edges(n);
  for (ComponentId id = 0; id < n; ++id) {
    for (const Definition& d : shader.components[id].definitions) {
      for (size_t i = 0; i < d.dependencies.size(); ++i) edges[id].push_back({d.dependencies[i], d.dependencyUses[i]});
    }
  }
  struct Frame {
    ComponentId id;
    size_t next;
  };
  for (ComponentId root = 0; root < n; ++root) {
    if (marks[root] != Mark::None) continue;
    std::vector<Frame> stack{{root, 0}};
    marks[root] = Mark::Active;
    while (!stack.empty()) {
      Frame& frame = stack.back();
      if (frame.next == edges[frame.id].size()) {
        marks[frame.id] = Mark::Done;
        stack.pop_back();
        continue;
      }
      const Edge edge = edges[frame.id][frame.next++];
      if (marks[edge.to] == Mark::None) {
        marks[edge.to] = Mark::Active;
        stack.push_back({edge.to, 0});
        continue;
      }
      if (marks[edge.to] != Mark::Active) continue;
      // A back edge closes a cycle: from edge.to down the stack to here.
      auto start = std::find_if(stack.begin(), stack.end(), [&](const Frame& f) { return f.id == edge.to; });
      std::vector<ComponentId> cycle;
      for (auto it = start; it != stack.end(); ++it) cycle.push_back(it->id);
      const bool ownsCycle = std::any_of(cycle.begin(), cycle.end(), [&](ComponentId id) {
        const auto& defs = shader.components[id].definitions;
        return std::any_of(defs.begin(), defs.end(), [&](const Definition& d) { return d.origin == shader.name; });
      });
      if (!ownsCycle) continue;  // reported with the base shader
      std::string path;
      for (ComponentId id : cycle) path += shader.components[id].name + " -> ";
      path += shader.components[edge.to].name;
      const Component& first = shader.components[cycle.front()];
      Diagnostic& d =
          diags_.report(DiagCode::E4007, first.firstDecl->nameRange, fmt::format("cycle among components: {}", path));
      for (size_t i = 0; i < cycle.size(); ++i) {
        const ComponentId from = cycle[i];
        const ComponentId to = i + 1 < cycle.size() ? cycle[i + 1] : edge.to;
        for (const Edge& e : edges[from]) {
          if (e.to == to) {
            d.note(e.use, fmt::format("'{}' uses '{}' here", shader.components[from].name, shader.components[to].name));
            break;
          }
        }
      }
      shader.valid = false;
    }
  }
}

void Analyzer::analyzeShaders() {
  for (const auto& module : program_.modules) {
    for (const ast::DeclPtr& decl : module->decls) {
      if (diags_.limitReached()) return;
      if (const auto* s = ast::dyn_cast<ast::ShaderDecl>(decl.get())) analyzeShaderDecl(*s);
      if (const auto* g = ast::dyn_cast<ast::GroupDecl>(decl.get())) analyzeGroup(*g);
    }
  }
}

void Analyzer::analyzeShaderDecl(const ast::ShaderDecl& decl) {
  if (auto it = std::find(shadersInProgress_.begin(), shadersInProgress_.end(), &decl);
      it != shadersInProgress_.end()) {
    std::string path;
    for (auto p = it; p != shadersInProgress_.end(); ++p) path += (*p)->name + " -> ";
    path += decl.name;
    const ast::ShaderDecl& closing = *shadersInProgress_.back();
    diags_.report(DiagCode::E4009, closing.base->range, fmt::format("cyclic shader inheritance: {}", path));
    return;
  }
  if (analyzedShaders_.count(&decl)) return;
  if (shaderDecls_.count(decl.name) && shaderDecls_[decl.name] != &decl) return;  // a reported duplicate
  shadersInProgress_.push_back(&decl);
  analyzedShaders_.insert(&decl);

  if (decl.pipeline) {
    if (const Pipeline* pipeline = pipelineOf(decl)) buildShader(decl, decl.name, *pipeline, nullptr);
  } else if (decl.base) {
    if (auto it = shaderDecls_.find(decl.base->name); it != shaderDecls_.end()) {
      analyzeShaderDecl(*it->second);
      if (auto group = derivedGroups_.find(it->second); group != derivedGroups_.end()) {
        buildGroupInstances(decl, *group->second);
      } else if (const Shader* base = model_->findShader(decl.base->name)) {
        buildShader(decl, decl.name, *base->pipeline, base);
      }
    } else if (auto g = groupDecls_.find(decl.base->name); g != groupDecls_.end()) {
      if (const Group* group = analyzeGroup(*g->second)) buildGroupInstances(decl, *group);
    } else {
      std::vector<std::string_view> names;
      for (const auto& [name, d] : shaderDecls_) names.push_back(name);
      for (const auto& [name, d] : groupDecls_) names.push_back(name);
      const auto suggestion = closestSpelling(decl.base->name, names);
      diags_.report(DiagCode::E4006, decl.base->range,
                    suggestion ? fmt::format("unknown base shader or group '{}'; did you mean '{}'?", decl.base->name,
                                             *suggestion)
                               : fmt::format("unknown base shader or group '{}'", decl.base->name));
    }
  } else {
    diags_.report(DiagCode::E4011, decl.nameRange,
                  fmt::format("shader '{}' needs a pipeline ('using Pipeline') or a base (': Base')", decl.name));
  }
  shadersInProgress_.pop_back();
}

const Pipeline* Analyzer::pipelineOf(const ast::ShaderDecl& decl) {
  const bool retargeted = !options_.pipeline.empty();
  const std::string& name = retargeted ? options_.pipeline : decl.pipeline->name;
  if (const Pipeline* pipeline = model_->findPipeline(name)) return pipeline;
  std::vector<std::string_view> names;
  for (const auto& p : model_->pipelines) names.push_back(p->name);
  const auto suggestion = closestSpelling(name, names);
  // A retargeting pipeline comes from the command line or the scene, so the
  // error stands at the `using` it replaces and lists what is loaded.
  const std::string loaded = names.empty() ? "none" : fmt::format("{}", fmt::join(names, ", "));
  diags_.report(DiagCode::E4005, decl.pipeline->range,
                retargeted   ? fmt::format("cannot retarget '{}' to pipeline '{}', which no loaded file declares{}; "
                                             "loaded pipelines: {}",
                                           decl.name, name,
                                         suggestion ? fmt::format(" (did you mean '{}'?)", *suggestion) : "", loaded)
                : suggestion ? fmt::format("unknown pipeline '{}'; did you mean '{}'?", name, *suggestion)
                             : fmt::format("unknown pipeline '{}'", name));
  return nullptr;
}

Shader* Analyzer::buildShader(const ast::ShaderDecl& decl, std::string name, const Pipeline& pipeline,
                              const Shader* base) {
  const uint32_t errorsBefore = diags_.errorCount();
  auto owned = std::make_unique<Shader>();
  Shader& shader = *owned;
  shader.name = std::move(name);
  shader.decl = &decl;
  shader.pipeline = &pipeline;
  shader.base = base;
  if (base) {
    static_cast<ComponentSet&>(shader) = static_cast<const ComponentSet&>(*base);
    shader.finalizedWorlds = base->finalizedWorlds;
  } else {
    static_cast<ComponentSet&>(shader) = static_cast<const ComponentSet&>(pipeline);
  }
  for (const ast::NameRef& ref : decl.finalizes) {
    const auto world = resolveWorld(pipeline, ref.name, ref.range);
    if (!world) continue;
    if (pipeline.worlds[*world].isAbstract) {
      diags_.report(DiagCode::E4010, ref.range, fmt::format("abstract world '{}' cannot be finalized", ref.name));
    } else if (std::find(shader.finalizedWorlds.begin(), shader.finalizedWorlds.end(), *world) ==
               shader.finalizedWorlds.end()) {
      shader.finalizedWorlds.push_back(*world);
    }
  }
  for (const ast::ComponentDecl& component : decl.components) {
    if (diags_.limitReached()) break;
    if (base && !checkLockedDefinition(*base, pipeline, component)) continue;
    addComponent(shader, pipeline, component, shader.name, false);
  }
  checkComponentBodies(shader, shader.name);
  checkComponentCycles(shader);
  if (diags_.errorCount() != errorsBefore) shader.valid = false;
  Shader* result = owned.get();
  model_->shaders.push_back(std::move(owned));
  return result;
}

const Group* Analyzer::analyzeGroup(const ast::GroupDecl& decl) {
  if (auto it = groups_.find(&decl); it != groups_.end()) return it->second;
  if (groupsInProgress_.count(&decl)) return nullptr;
  groupsInProgress_.insert(&decl);
  auto group = std::make_unique<Group>();
  group->name = decl.name;
  group->decl = &decl;
  bool valid = true;
  for (const ast::GroupEntry& entry : decl.entries) {
    auto it = shaderDecls_.find(entry.shader.name);
    if (it == shaderDecls_.end()) {
      std::vector<std::string_view> names;
      for (const auto& [name, d] : shaderDecls_) names.push_back(name);
      const auto suggestion = closestSpelling(entry.shader.name, names);
      diags_.report(DiagCode::E4006, entry.shader.range,
                    suggestion ? fmt::format("unknown shader '{}' in group '{}'; did you mean '{}'?", entry.shader.name,
                                             decl.name, *suggestion)
                               : fmt::format("unknown shader '{}' in group '{}'", entry.shader.name, decl.name));
      valid = false;
      continue;
    }
    analyzeShaderDecl(*it->second);
    const Shader* member = derivedGroups_.count(it->second) ? nullptr : model_->findShader(entry.shader.name);
    if (!member) {
      diags_.report(DiagCode::E4012, entry.shader.range,
                    fmt::format("'{}' cannot be a member of group '{}': it is not a valid single shader",
                                entry.shader.name, decl.name));
      valid = false;
      continue;
    }
    for (const GroupMember& m : group->members) {
      if (m.shader == member) {
        diags_.report(DiagCode::E4012, entry.shader.range,
                      fmt::format("shader '{}' appears twice in group '{}'", entry.shader.name, decl.name));
        valid = false;
      }
    }
    group->members.push_back({member, entry.isOptional});
  }
  if (decl.entries.empty() ||
      std::all_of(decl.entries.begin(), decl.entries.end(), [](const ast::GroupEntry& e) { return e.isOptional; })) {
    diags_.report(DiagCode::E4012, decl.nameRange,
                  fmt::format("group '{}' needs at least one required (non-optional) shader", decl.name));
    valid = false;
  }
  groupsInProgress_.erase(&decl);
  const Group* result = valid ? group.get() : nullptr;
  groups_[&decl] = result;
  model_->groups.push_back(std::move(group));
  return result;
}

void Analyzer::buildGroupInstances(const ast::ShaderDecl& decl, const Group& base) {
  // Paper section 6.1: deriving from a group derives from each member. The
  // declarations must be valid against every required member; an optional
  // member that rejects them is left out with a warning. Later stages leave
  // out an optional member the same way (runMemberStage).
  auto derived = std::make_unique<Group>();
  derived->name = decl.name;
  derived->derivedDecl = &decl;
  for (const GroupMember& member : base.members) {
    const size_t mark = diags_.size();
    Shader* instance = buildShader(decl, fmt::format("{}<{}>", decl.name, memberName(*member.shader)),
                                   *member.shader->pipeline, member.shader);
    instance->derivedFrom = derived.get();
    if (member.isOptional && !instance->valid) {
      reportMemberLeftOut(diags_, decl, member.shader->name, diags_.takeSince(mark));
      model_->shaders.pop_back();  // the rejected instance, added last by buildShader
      continue;
    }
    derived->members.push_back({instance, member.isOptional});
  }
  derivedGroups_[&decl] = derived.get();
  model_->groups.push_back(std::move(derived));
}

}  // namespace spire::sem
