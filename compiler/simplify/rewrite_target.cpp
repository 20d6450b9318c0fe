#include "simplify/rewrite_target.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <set>

#include "sema/group_members.h"
#include "sema/locked_worlds.h"
#include "simplify/syntax_walk.h"

namespace spire::simplify {
namespace {

// `text`, the source of `decl` with edits after its name only, renamed
// `variation`: the name comes before the definition, so its offsets hold.
void renameDefinition(std::string& text, const ast::ComponentDecl& decl, const std::string& variation) {
  const uint32_t base = decl.range.begin;
  if (decl.variation.empty()) {
    text.insert(decl.nameRange.end - base, ":" + variation);
  } else {
    text.replace(decl.variationRange.begin - base, decl.variationRange.end - decl.variationRange.begin, variation);
  }
}

}  // namespace

bool immutable(const sem::Component& component) {
  return std::any_of(component.attributes.begin(), component.attributes.end(),
                     [](const ast::Attribute* a) { return a->name == "Immutable"; });
}

namespace {

// The group that a shader derived from a group makes its shaders in.
const sem::Group* groupMadeFor(const sem::Model& model, const std::string& name) {
  for (const auto& group : model.groups) {
    if (group->derivedDecl && group->name == name) return group.get();
  }
  return nullptr;
}

// Why a shader derived from `shader` may not redefine `c`, if it may not.
std::optional<std::string> lockedReason(const sem::Shader& shader, const sem::Component& c) {
  const std::optional<sem::WorldId> world = sem::lockedAgainstRedefinition(shader, c);
  if (!world || !shader.pipeline) return std::nullopt;
  return fmt::format(
      "'{}' may be computed in world '{}', which is finalized for shaders derived from '{}': they "
      "cannot redefine it",
      c.name, shader.pipeline->worlds[*world].name, shader.name);
}

// The same for the first of the shaders a variation must suit that does not
// let it redefine the component named as `c` is (each has its own copy).
std::optional<std::string> lockedReason(const DerivationBase& base, const sem::Component& c) {
  for (const sem::Shader* shader : base.required) {
    const auto it = shader->componentByName.find(c.name);
    if (it == shader->componentByName.end()) continue;
    if (auto locked = lockedReason(*shader, shader->components[it->second])) return locked;
  }
  return std::nullopt;
}

}  // namespace

std::string DerivationBase::derivedShader(const std::string& derived) const {
  return fromGroup ? fmt::format("{}<{}>", derived, sem::memberName(shader())) : derived;
}

Expected<DerivationBase, Failure> shaderToDerive(const sem::Model& model, const std::string& name) {
  const sem::Shader* shader = model.findShader(name);
  if (!shader) {
    const sem::Group* group = groupMadeFor(model, name);
    if (!group || group->members.empty()) return Failure{fmt::format("no shader named '{}'", name)};
    DerivationBase base{{}, true};
    for (const sem::GroupMember& member : group->members) {
      if (!member.isOptional) base.required.push_back(member.shader);
    }
    return base;
  }
  if (shader->derivedFrom) {
    return Failure{fmt::format("'{}' is one of the shaders that '{}' makes from the members of a group; simplify '{}'",
                               shader->name, shader->derivedFrom->name, shader->derivedFrom->name)};
  }
  std::vector<std::string> abstract;
  for (const sem::Component& c : shader->components) {
    if (c.isAbstract && c.definitions.empty()) abstract.push_back("'" + c.name + "'");
  }
  if (abstract.empty()) return DerivationBase{{shader}, false};
  return Failure{
      fmt::format("'{}' is abstract: it leaves {} to the shaders derived from it, and a shader derived from "
                  "it to hold its variations would have to define them",
                  shader->name, fmt::join(abstract, ", "))};
}

bool rewritable(const DerivationBase& base, const sem::Definition& definition) {
  return !definition.isInput() && (!base.fromGroup || definition.origin == base.shader().name);
}

Expected<ComponentSelection, Failure> selectComponents(const DerivationBase& base,
                                                       const std::vector<std::string>& components) {
  const sem::Shader& shader = base.shader();
  std::set<std::string> wanted(components.begin(), components.end());
  ComponentSelection selected;
  for (const sem::Component& c : shader.components) {
    const bool fromPipeline = shader.pipeline && c.origin == shader.pipeline->name;
    const bool named = wanted.erase(c.name) > 0;
    if (!components.empty() && !named) continue;
    if (named && (fromPipeline || immutable(c))) {
      return Failure{fmt::format("'{}' cannot be simplified: it is {}", c.name,
                                 fromPipeline ? "the pipeline's" : "marked [Immutable]")};
    }
    if (fromPipeline || immutable(c)) continue;
    const auto rewritableHere = [&](const sem::Definition& d) { return rewritable(base, d); };
    if (base.fromGroup && std::none_of(c.definitions.begin(), c.definitions.end(), rewritableHere)) {
      if (named) {
        return Failure{
            fmt::format("'{}' cannot be simplified: the group's members define it, each its own way, and "
                        "the shader derived from the group does not",
                        c.name)};
      }
      continue;
    }
    if (std::optional<std::string> locked = lockedReason(base, c)) {
      if (named) return Failure{fmt::format("'{}' cannot be simplified: {}", c.name, *locked)};
      selected.lockedOut.push_back(std::move(*locked));
      continue;
    }
    selected.components.push_back(&c);
  }
  if (!wanted.empty()) {
    return Failure{fmt::format("'{}' has no component '{}'", shader.name, *wanted.begin())};
  }
  return selected;
}

std::string rewrittenText(const SourceManager& sources, const ast::ComponentDecl& decl, const Rewrite& rewrite,
                          const std::string& variation) {
  const uint32_t base = decl.range.begin;
  std::string text(sources.text(decl.range));
  text.replace(rewrite.range.begin - base, rewrite.range.end - rewrite.range.begin, rewrite.replacement);
  renameDefinition(text, decl, variation);
  return text;
}

std::optional<std::string> shiftedText(const SourceManager& sources, const ast::ComponentDecl& decl,
                                       const std::string& shift, const std::string& variation) {
  std::vector<const ast::Expr*> values;
  size_t returns = 0;
  if (decl.init) values.push_back(decl.init.get());
  SyntaxWalker mutableOnly([](const ast::Expr&) {},
                           [&](const ast::Stmt& s) {
                             if (const auto* r = ast::dyn_cast<ast::ReturnStmt>(&s); r && r->value) {
                               values.push_back(r->value.get());
                             }
                           });
  mutableOnly.stmt(decl.body.get());
  SyntaxWalker every([](const ast::Expr&) {},
                     [&](const ast::Stmt& s) { returns += ast::dyn_cast<ast::ReturnStmt>(&s) != nullptr ? 1 : 0; },
                     SyntaxWalker::Immutable::Visit);
  every.stmt(decl.body.get());
  if (values.size() != returns + (decl.init ? 1 : 0)) return std::nullopt;
  const uint32_t base = decl.range.begin;
  std::string text(sources.text(decl.range));
  // From the last value back, so that the offsets of the earlier ones hold.
  std::sort(values.begin(), values.end(),
            [](const ast::Expr* a, const ast::Expr* b) { return a->range.begin > b->range.begin; });
  for (const ast::Expr* value : values) {
    text.insert(value->range.end - base, ") + " + shift + ")");
    text.insert(value->range.begin - base, "((");
  }
  renameDefinition(text, decl, variation);
  return text;
}

size_t replacementOffset(const ast::ComponentDecl& decl, const Rewrite& rewrite, const std::string& variation) {
  const size_t before = rewrite.range.begin - decl.range.begin;
  if (decl.variation.empty()) return before + 1 + variation.size();
  return before + variation.size() - (decl.variationRange.end - decl.variationRange.begin);
}

const ast::ComponentDecl* definitionNamed(const sem::Shader& shader, const std::string& component,
                                          const std::string& variation) {
  const sem::Component* found = shader.findComponent(component);
  if (!found) return nullptr;
  for (const sem::Definition& d : found->definitions) {
    if (d.decl && d.variation == variation) return d.decl;
  }
  return nullptr;
}

std::optional<std::string> replacementTypeError(const sem::Model& model, const ast::ComponentDecl& decl,
                                                size_t replacementAt, const std::string& replacement,
                                                const std::string& type) {
  const auto begin = static_cast<uint32_t>(decl.range.begin + replacementAt);
  const SourceRange range{decl.range.file, begin, static_cast<uint32_t>(begin + replacement.size())};
  const ast::Expr* e = widestExprWithin(decl, range);
  const sem::Type* found = e ? model.typeOf(*e) : nullptr;
  if (found && found->name() == type) return std::nullopt;
  return fmt::format("'{}' has type '{}', not '{}'", replacement, found ? found->name() : "?", type);
}

}  // namespace spire::simplify
