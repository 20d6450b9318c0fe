#include "simplify/simplification.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <memory>
#include <set>

#include "simplify/cost_model.h"
#include "simplify/rewrite_rules.h"

namespace spire::simplify {
namespace {

namespace fs = std::filesystem;

// A variation candidate: its text in the derived shader and what it is.
struct Candidate {
  Variation variation;
  std::string text;
  size_t replacementAt = 0;  // where the rewrite's replacement starts in `text`
  std::string type;          // Rewrite::type
  int64_t cost = 0;          // of the definition it rewrites, as written (cost_model.h)
};

bool immutable(const sem::Component& component) {
  return std::any_of(component.attributes.begin(), component.attributes.end(),
                     [](const ast::Attribute* a) { return a->name == "Immutable"; });
}

// The components to simplify, in the shader's order.
Expected<std::vector<const sem::Component*>, Failure> selectComponents(const sem::Shader& shader,
                                                                       const SimplifyOptions& options) {
  std::set<std::string> wanted(options.components.begin(), options.components.end());
  std::vector<const sem::Component*> selected;
  for (const sem::Component& c : shader.components) {
    const bool fromPipeline = shader.pipeline && c.origin == shader.pipeline->name;
    const bool named = wanted.erase(c.name) > 0;
    if (!options.components.empty() && !named) continue;
    if (named && (fromPipeline || immutable(c))) {
      return Failure{fmt::format("'{}' cannot be simplified: it is {}", c.name,
                                 fromPipeline ? "the pipeline's" : "marked [Immutable]")};
    }
    if (fromPipeline || immutable(c)) continue;
    selected.push_back(&c);
  }
  if (!wanted.empty()) {
    return Failure{fmt::format("'{}' has no component '{}'", shader.name, *wanted.begin())};
  }
  return selected;
}

std::string siteOf(const SourceManager& sources, const SourceRange& range) {
  const LineCol at = sources.begin(range);
  return fmt::format("{}:{}:{}", fs::path(sources.file(range.file).path).filename().string(), at.line, at.column);
}

// `decl`'s source with `rewrite` applied and the name given `variation`.
std::string rewrittenText(const SourceManager& sources, const ast::ComponentDecl& decl, const Rewrite& rewrite,
                          const std::string& variation) {
  const uint32_t base = decl.range.begin;
  std::string text(sources.text(decl.range));
  text.replace(rewrite.range.begin - base, rewrite.range.end - rewrite.range.begin, rewrite.replacement);
  // The name comes before the definition, so its offsets still hold.
  if (decl.variation.empty()) {
    text.insert(decl.nameRange.end - base, ":" + variation);
  } else {
    text.replace(decl.variationRange.begin - base, decl.variationRange.end - decl.variationRange.begin, variation);
  }
  return text;
}

// Where rewrittenText puts `rewrite`'s replacement: after the name, whose
// variation part grew or shrank.
size_t replacementOffset(const ast::ComponentDecl& decl, const Rewrite& rewrite, const std::string& variation) {
  const size_t before = rewrite.range.begin - decl.range.begin;
  if (decl.variation.empty()) return before + 1 + variation.size();
  return before + variation.size() - (decl.variationRange.end - decl.variationRange.begin);
}

std::set<std::string> variationNames(const sem::Component& component) {
  std::set<std::string> names;
  for (const sem::Definition& d : component.definitions) names.insert(d.variation);
  return names;
}

// The rewrites of all of `component`'s definitions, each with its
// definition, ranked together (rankRewrites) and cut to the first `maxCount`.
std::vector<std::pair<Rewrite, const ast::ComponentDecl*>> rankedRewrites(const ShaderLibrary& library,
                                                                          const sem::Component& component,
                                                                          const std::vector<UserRule>& userRules,
                                                                          size_t maxCount) {
  std::vector<Rewrite> rewrites;
  std::vector<const ast::ComponentDecl*> decls;
  for (const sem::Definition& definition : component.definitions) {
    if (definition.isInput()) continue;
    for (Rewrite& r : proposeRewrites(library.model(), library.sources(), *definition.decl, userRules)) {
      rewrites.push_back(std::move(r));
      decls.push_back(definition.decl);
    }
  }
  std::vector<std::pair<Rewrite, const ast::ComponentDecl*>> ranked;
  for (size_t i : rankRewrites(rewrites)) {
    if (ranked.size() >= maxCount) break;
    ranked.emplace_back(std::move(rewrites[i]), decls[i]);
  }
  return ranked;
}

std::vector<Candidate> candidatesOf(const ShaderLibrary& library, const sem::Component& component,
                                    const SimplifyOptions& options) {
  const std::vector<UserRule> none;
  const std::vector<UserRule>& userRules = options.userRules ? options.userRules->rules() : none;
  std::vector<Candidate> candidates;
  std::set<std::string> taken = variationNames(component);
  CostModel costs(library.model());
  int number = 0;
  for (const auto& [rewrite, decl] : rankedRewrites(library, component, userRules, options.maxPerComponent)) {
    std::string variation;
    do {
      variation = fmt::format("{}{}simplified{}", decl->variation, decl->variation.empty() ? "" : "_", ++number);
    } while (taken.count(variation) > 0);
    taken.insert(variation);
    Variation v{component.name, component.name + ":" + variation,
                rewrite.rule,   siteOf(library.sources(), rewrite.range),
                rewrite.before, rewrite.replacement,
                rewrite.saving};
    candidates.push_back({std::move(v), rewrittenText(library.sources(), *decl, rewrite, variation),
                          replacementOffset(*decl, rewrite, variation), rewrite.type, costs.definition(*decl)});
  }
  return candidates;
}

struct ModuleHeader {
  std::string usingPath;  // the shader's source, relative to the module's folder
  std::string base;
  std::string derived;
};

std::string moduleText(const ModuleHeader& header, const std::vector<const Candidate*>& candidates) {
  std::string text = fmt::format(
      "// Generated by spire-simplify: simplified variations of {} (Pellacini 2005's rules,\n"
      "// docs/simplification.md). Each is one rewrite of a definition of {}; `spirec --choices`\n"
      "// lists them beside the written ones, and spire-tune measures what they cost in error.\n"
      "// Per component, those that save the most scalar operations (He et al. 2015's cost model)\n"
      "// come first.\n"
      "using \"{}\";\n\nshader {} : {} {{\n",
      header.base, header.base, header.usingPath, header.derived, header.base);
  for (const Candidate* c : candidates) {
    const Variation& v = c->variation;
    const std::string saving = v.saving >= 0 ? fmt::format("saves {}", v.saving) : fmt::format("adds {}", -v.saving);
    text += fmt::format("    // {} ({} at {}, {} scalar ops): '{}' -> '{}'\n    {}\n", v.name, v.rule, v.site, saving,
                        v.before, v.after, c->text);
  }
  return text + "}\n";
}

// The definition `c` became in the compiled module's derived shader.
const ast::ComponentDecl* compiledDefinition(const sem::Shader& derived, const Candidate& c) {
  const sem::Component& component = derived.components[derived.componentByName.at(c.variation.component)];
  for (const sem::Definition& d : component.definitions) {
    if (d.decl && component.name + ":" + d.variation == c.variation.name) return d.decl;
  }
  return nullptr;
}

// A replacement whose type is not the one it must have (Candidate::type),
// found in the compiled module: a user rule can compile to another type
// (`vec3 * float` for `vec3 * vec3`) and mean something else.
std::optional<std::string> typeError(const ShaderLibrary& library, const std::string& derived,
                                     const std::vector<const Candidate*>& candidates) {
  const sem::Shader* shader = library.model().findShader(derived);
  for (const Candidate* c : candidates) {
    const ast::ComponentDecl* decl = c->type.empty() ? nullptr : compiledDefinition(*shader, *c);
    if (!decl) continue;
    const auto begin = static_cast<uint32_t>(decl->range.begin + c->replacementAt);
    const SourceRange range{decl->range.file, begin, static_cast<uint32_t>(begin + c->variation.after.size())};
    const ast::Expr* e = widestExprWithin(*decl, range);
    const sem::Type* type = e ? library.model().typeOf(*e) : nullptr;
    if (type && type->name() == c->type) continue;
    return fmt::format("'{}' has type '{}', not '{}'", c->variation.after, type ? type->name() : "?", c->type);
  }
  return std::nullopt;
}

// Whether the module compiles with its sources and `candidates` keep their
// types; the diagnostics' first message otherwise. `compiled`, if given,
// receives the compiled library.
std::optional<std::string> compileError(const std::string& path, const std::string& text, const std::string& derived,
                                        const FrontEndOptions& options, const std::vector<const Candidate*>& candidates,
                                        std::unique_ptr<ShaderLibrary>* compiled = nullptr) {
  auto library = std::make_unique<ShaderLibrary>(options);
  library->addSource(path, text);
  if (library->compile() && library->choiceSpace(derived) != nullptr) {
    auto error = typeError(*library, derived, candidates);
    if (compiled) *compiled = std::move(library);
    return error;
  }
  for (const Diagnostic& d : library->diagnostics().all()) {
    if (d.severity == Severity::Error) return d.message;
  }
  return "the derived shader was not built";
}

// Each variation's saving by name, costed on the compiled module: exact for
// user rules too, whose rewrites were ranked by an estimate
// (rewrite_rules.h).
std::map<std::string, int64_t> compiledSavings(const ShaderLibrary& compiled, const std::string& derived,
                                               const std::vector<const Candidate*>& candidates) {
  const sem::Shader& shader = *compiled.model().findShader(derived);
  CostModel costs(compiled.model());
  std::map<std::string, int64_t> savings;
  for (const Candidate* c : candidates) {
    if (const ast::ComponentDecl* decl = compiledDefinition(shader, *c)) {
      savings[c->variation.name] = c->cost - costs.definition(*decl);
    }
  }
  return savings;
}

Expected<ModuleHeader, Failure> headerFor(const ShaderLibrary& library, const sem::Shader& shader,
                                          const SimplifyOptions& options) {
  if (shader.derivedFrom || !shader.decl) {
    return Failure{fmt::format("'{}' is a member of a group; simplify the shader it is declared as", shader.name)};
  }
  const fs::path source = fs::absolute(library.sources().file(shader.decl->range.file).path);
  const fs::path folder = fs::absolute(options.outputPath).parent_path();
  return ModuleHeader{fs::relative(source, folder).generic_string(), shader.name,
                      options.derivedName.empty() ? shader.name + "Simplified" : options.derivedName};
}

}  // namespace

Expected<Simplified, Failure> simplifyShader(const ShaderLibrary& library, const SimplifyOptions& options) {
  const sem::Shader* shader = library.model().findShader(options.shader);
  if (!shader) return Failure{fmt::format("no shader named '{}'", options.shader)};
  auto header = headerFor(library, *shader, options);
  if (!header) return header.error();
  auto components = selectComponents(*shader, options);
  if (!components) return components.error();
  std::vector<Candidate> candidates;
  for (const sem::Component* component : *components) {
    for (Candidate& c : candidatesOf(library, *component, options)) candidates.push_back(std::move(c));
  }
  Simplified result;
  std::vector<const Candidate*> kept;
  for (const Candidate& c : candidates) kept.push_back(&c);
  // One compile for the common case; only when it fails is each candidate
  // tried alone, to keep those that compile.
  if (compileError(options.outputPath, moduleText(*header, kept), header->derived, options.frontEnd, kept)) {
    kept.clear();
    for (const Candidate& c : candidates) {
      if (auto error =
              compileError(options.outputPath, moduleText(*header, {&c}), header->derived, options.frontEnd, {&c})) {
        result.dropped.push_back(
            fmt::format("{} ({} at {}): {}", c.variation.name, c.variation.rule, c.variation.site, *error));
      } else {
        kept.push_back(&c);
      }
    }
  }
  std::unique_ptr<ShaderLibrary> compiled;
  if (auto error = compileError(options.outputPath, moduleText(*header, kept), header->derived, options.frontEnd, kept,
                                &compiled)) {
    return Failure{fmt::format("the simplified module does not compile (a spire-simplify bug): {}", *error)};
  }
  // Only the comments change with the exact savings, so the module
  // written compiles as the one just compiled.
  const std::map<std::string, int64_t> savings = compiledSavings(*compiled, header->derived, kept);
  for (Candidate& c : candidates) {
    if (const auto found = savings.find(c.variation.name); found != savings.end()) c.variation.saving = found->second;
  }
  result.module = moduleText(*header, kept);
  for (const Candidate* c : kept) result.variations.push_back(c->variation);
  return result;
}

}  // namespace spire::simplify
