// Pipelines: worlds, imports, strategies, world order and pipeline components.
#include <fmt/format.h>

#include <algorithm>
#include <queue>

#include "sema/analyzer_impl.h"
#include "sema/attribute_catalog.h"
#include "sema/route_selection.h"
#include "support/spelling.h"

namespace spire::sem {

std::optional<WorldId> Pipeline::findWorld(std::string_view worldName) const {
  auto it = worldByName.find(worldName);
  if (it == worldByName.end()) return std::nullopt;
  return it->second;
}

bool Pipeline::reaches(WorldId from, WorldId to) const {
  if (from == to) return true;
  const size_t index = static_cast<size_t>(from) * worlds.size() + to;
  return index < reachability.size() && reachability[index];
}

const std::vector<uint32_t>& Pipeline::route(WorldId from, WorldId to) const {
  static const std::vector<uint32_t> kNone;
  const size_t index = static_cast<size_t>(from) * worlds.size() + to;
  return index < routes.size() ? routes[index] : kNone;
}

const Type* ComponentTableResolver::useComponent(std::string_view name, SourceRange use) {
  auto it = byName_.find(name);
  if (it == byName_.end()) return nullptr;
  used_.try_emplace(it->second, use);
  return components_[it->second].type;
}

SourceRange ComponentTableResolver::declarationOf(std::string_view name) const {
  auto it = byName_.find(name);
  return it == byName_.end() ? SourceRange{} : components_[it->second].firstDecl->nameRange;
}

void ComponentTableResolver::appendNames(std::vector<std::string_view>& out) const {
  for (const Component& c : components_) out.push_back(c.name);
}

void ComponentTableResolver::takeDependencies(std::vector<ComponentId>& ids, std::vector<SourceRange>& uses) const {
  ids.clear();
  uses.clear();
  for (const auto& [id, use] : used_) {
    ids.push_back(id);
    uses.push_back(use);
  }
}

std::optional<WorldId> Analyzer::resolveWorld(const Pipeline& pipeline, std::string_view name, SourceRange range) {
  if (auto id = pipeline.findWorld(name)) return id;
  std::vector<std::string_view> names;
  for (const World& w : pipeline.worlds) names.push_back(w.name);
  const auto suggestion = closestSpelling(name, names);
  Diagnostic& d = diags_.report(DiagCode::E4001, range,
                                suggestion ? fmt::format("unknown world '{}' in pipeline '{}'; did you mean '{}'?",
                                                         name, pipeline.name, *suggestion)
                                           : fmt::format("unknown world '{}' in pipeline '{}'", name, pipeline.name));
  if (suggestion)
    d.note(pipeline.worlds[*pipeline.findWorld(*suggestion)].decl->nameRange,
           fmt::format("'{}' declared here", *suggestion));
  return std::nullopt;
}

void Analyzer::analyzePipeline(const ast::PipelineDecl& decl) {
  auto owned = std::make_unique<Pipeline>();
  Pipeline& pipeline = *owned;
  pipeline.name = decl.name;
  pipeline.decl = &decl;
  model_->pipelines.push_back(std::move(owned));

  for (const ast::WorldDecl& world : decl.worlds) {
    if (auto existing = pipeline.findWorld(world.name)) {
      diags_.report(DiagCode::E3003, world.nameRange, fmt::format("redefinition of world '{}'", world.name))
          .note(pipeline.worlds[*existing].decl->nameRange, "previous definition is here");
      pipeline.valid = false;
      continue;
    }
    pipeline.worldByName[world.name] = static_cast<WorldId>(pipeline.worlds.size());
    pipeline.worlds.push_back({world.name, &world, world.isAbstract, std::nullopt});
  }
  // Components come before strategies: strategy arguments read them.
  for (const ast::ComponentDecl& component : decl.components) addComponent(pipeline, component);
  checkComponentBodies(pipeline, pipeline.name);
  for (const ast::WorldDecl& world : decl.worlds) checkWorld(pipeline, world);
  for (const ast::ImportDecl& import : decl.imports) checkImport(pipeline, import);
  orderWorlds(pipeline);
  if (pipeline.valid) selectRoutes(pipeline, diags_);
}

void Analyzer::checkWorld(Pipeline& pipeline, const ast::WorldDecl& decl) {
  auto id = pipeline.findWorld(decl.name);
  if (!id || pipeline.worlds[*id].decl != &decl) return;  // a reported duplicate
  if (!checkAttributes(decl.attributes, AttributeSite::World, diags_)) pipeline.valid = false;
  World& world = pipeline.worlds[*id];
  if (decl.isAbstract) {
    if (decl.language) {
      diags_.report(
          DiagCode::E4010, decl.languageRange,
          fmt::format("abstract world '{}' cannot have a target language: it holds no computation", decl.name));
      pipeline.valid = false;
    }
    if (decl.exportStrategy) {
      diags_.report(
          DiagCode::E4010, decl.exportStrategy->range,
          fmt::format("abstract world '{}' cannot have an export strategy: it holds no computation", decl.name));
      pipeline.valid = false;
    }
    return;
  }
  if (!decl.language) {
    diags_.report(DiagCode::E4010, decl.nameRange,
                  fmt::format("world '{}' needs a target language, as in 'world {} : \"GLSL\" export standardExport;'",
                              decl.name, decl.name));
    pipeline.valid = false;
  } else if (*decl.language != "GLSL") {
    diags_.report(DiagCode::E4010, decl.languageRange,
                  fmt::format("unsupported target language \"{}\" for world '{}' (supported: \"GLSL\")", *decl.language,
                              decl.name));
    pipeline.valid = false;
  }
  if (!decl.exportStrategy) {
    diags_.report(DiagCode::E4010, decl.nameRange,
                  fmt::format("world '{}' needs an export strategy, as in 'export standardExport'", decl.name));
    pipeline.valid = false;
    return;
  }
  world.exportStrategy = StrategyUse{};
  world.exportStrategy->ref = &*decl.exportStrategy;
  world.exportStrategy->componentArgs = checkStrategy(pipeline, *decl.exportStrategy, StrategyRole::Export);
  world.exportStrategy->signature = strategies_.find(decl.exportStrategy->name);
}

void Analyzer::checkImport(Pipeline& pipeline, const ast::ImportDecl& decl) {
  if (!checkAttributes(decl.attributes, AttributeSite::Import, diags_)) pipeline.valid = false;
  const auto from = resolveWorld(pipeline, decl.from, decl.fromRange);
  const auto to = resolveWorld(pipeline, decl.to, decl.toRange);
  std::vector<std::string> componentArgs = checkStrategy(pipeline, decl.strategy, StrategyRole::Import);
  if (!from || !to) {
    pipeline.valid = false;
    return;
  }
  const SourceRange edge = SourceRange::cover(decl.fromRange, decl.toRange);
  if (*from == *to) {
    diags_.report(DiagCode::E4004, edge, fmt::format("world '{}' cannot import from itself", decl.from));
    pipeline.valid = false;
    return;
  }
  if (pipeline.worlds[*to].isAbstract) {
    diags_
        .report(DiagCode::E4010, decl.toRange,
                fmt::format("cannot import into abstract world '{}': abstract worlds hold no computation", decl.to))
        .note(pipeline.worlds[*to].decl->nameRange, fmt::format("'{}' declared abstract here", decl.to));
    pipeline.valid = false;
    return;
  }
  for (const Import& existing : pipeline.imports) {
    if (existing.from == *from && existing.to == *to) {
      diags_.report(DiagCode::E3003, edge, fmt::format("duplicate import {}->{}", decl.from, decl.to))
          .note(SourceRange::cover(existing.decl->fromRange, existing.decl->toRange), "previous import is here");
      pipeline.valid = false;
      return;
    }
  }
  Import import{*from, *to, &decl, {}, importPriority(decl)};
  import.strategy.ref = &decl.strategy;
  import.strategy.signature = strategies_.find(decl.strategy.name);
  import.strategy.componentArgs = std::move(componentArgs);
  pipeline.imports.push_back(std::move(import));
}

std::vector<std::string> Analyzer::checkStrategy(Pipeline& pipeline, const ast::StrategyRef& ref, StrategyRole role) {
  const StrategySignature* signature = strategies_.find(ref.name);
  if (!signature || signature->role != role) {
    const auto suggestion = closestSpelling(ref.name, strategies_.names(role));
    std::string message = signature ? fmt::format("'{}' is an {} strategy, but an {} strategy is needed here", ref.name,
                                                  roleName(signature->role), roleName(role))
                                    : fmt::format("unknown {} strategy '{}'", roleName(role), ref.name);
    if (suggestion) message += fmt::format("; did you mean '{}'?", *suggestion);
    Diagnostic& d = diags_.report(DiagCode::E4002, ref.nameRange, message);
    std::string known;
    for (std::string_view name : strategies_.names(role)) known += fmt::format("{}{}", known.empty() ? "" : ", ", name);
    d.note({}, fmt::format("known {} strategies: {}", roleName(role), known));
    pipeline.valid = false;
    return {};
  }
  std::string expected;
  for (const StrategyParam& p : signature->params) {
    expected += fmt::format("{}{} {}", expected.empty() ? "" : ", ", p.typeName, p.name);
  }
  if (ref.args.size() != signature->params.size()) {
    diags_.report(
        DiagCode::E4003, ref.range,
        fmt::format("strategy '{}' takes {} argument{}{}, but {} {} given", ref.name, signature->params.size(),
                    signature->params.size() == 1 ? "" : "s", expected.empty() ? "" : fmt::format(" ({})", expected),
                    ref.args.size(), ref.args.size() == 1 ? "was" : "were"));
    pipeline.valid = false;
    return {};
  }
  ComponentTableResolver resolver(pipeline);
  BodyChecker checker(*model_, diags_, functions_, &resolver);
  for (size_t i = 0; i < ref.args.size(); ++i) {
    const Type* type = checker.check(*ref.args[i]);
    if (type->isError()) {
      pipeline.valid = false;
      continue;
    }
    const StrategyParam& param = signature->params[i];
    if (type->name() != param.typeName) {
      diags_.report(DiagCode::E4003, ref.args[i]->range,
                    fmt::format("argument '{}' of strategy '{}' must be a '{}', not a '{}'", param.name, ref.name,
                                param.typeName, type->name()));
      pipeline.valid = false;
    }
  }
  std::vector<ComponentId> ids;
  std::vector<SourceRange> uses;
  resolver.takeDependencies(ids, uses);
  std::vector<std::string> componentArgs;
  for (ComponentId id : ids) componentArgs.push_back(pipeline.components[id].name);
  return componentArgs;
}

void Analyzer::orderWorlds(Pipeline& pipeline) {
  const size_t n = pipeline.worlds.size();
  std::vector<std::vector<const Import*>> out(n);
  std::vector<uint32_t> inDegree(n, 0);
  for (const Import& import : pipeline.imports) {
    out[import.from].push_back(&import);
    ++inDegree[import.to];
  }
  // Kahn's algorithm taking the earliest-declared ready world first, so the
  // order is deterministic and follows the author's declaration order.
  std::priority_queue<WorldId, std::vector<WorldId>, std::greater<>> ready;
  for (WorldId w = 0; w < n; ++w) {
    if (inDegree[w] == 0) ready.push(w);
  }
  std::vector<WorldId> order;
  while (!ready.empty()) {
    const WorldId w = ready.top();
    ready.pop();
    order.push_back(w);
    for (const Import* import : out[w]) {
      if (--inDegree[import->to] == 0) ready.push(import->to);
    }
  }
  if (order.size() != n) {
    // Find one cycle among the worlds left over and report it at the import
    // that closes it, with the other edges as notes.
    WorldId start = 0;
    while (inDegree[start] == 0) ++start;
    std::vector<const Import*> path;
    std::vector<int> position(n, -1);
    WorldId w = start;
    while (position[w] < 0) {
      position[w] = static_cast<int>(path.size());
      const Import* next = nullptr;
      for (const Import* import : out[w]) {
        if (inDegree[import->to] > 0) {
          next = import;
          break;
        }
      }
      path.push_back(next);
      w = next->to;
    }
    std::vector<const Import*> cycle(path.begin() + position[w], path.end());
    std::string text;
    for (const Import* import : cycle) text += pipeline.worlds[import->from].name + " -> ";
    text += pipeline.worlds[w].name;
    const Import* closing = cycle.back();
    Diagnostic& d = diags_.report(DiagCode::E4004, SourceRange::cover(closing->decl->fromRange, closing->decl->toRange),
                                  fmt::format("cyclic imports between worlds: {}", text));
    for (const Import* import : cycle) {
      if (import != closing) {
        d.note(SourceRange::cover(import->decl->fromRange, import->decl->toRange),
               fmt::format("import {}->{} is here", import->decl->from, import->decl->to));
      }
    }
    pipeline.valid = false;
    return;
  }
  pipeline.topologicalOrder = std::move(order);
  pipeline.reachability.assign(n * n, false);
  // Reverse topological order: a world reaches what its successors reach.
  for (auto it = pipeline.topologicalOrder.rbegin(); it != pipeline.topologicalOrder.rend(); ++it) {
    const WorldId from = *it;
    pipeline.reachability[from * n + from] = true;
    for (const Import* import : out[from]) {
      for (WorldId to = 0; to < n; ++to) {
        if (pipeline.reachability[import->to * n + to]) pipeline.reachability[from * n + to] = true;
      }
    }
  }
}

}  // namespace spire::sem
