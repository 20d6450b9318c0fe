#include "search/transitions.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <optional>
#include <set>

#include "renderer/supplied_values.h"
#include "search/candidates.h"
#include "search/search_outputs.h"
#include "simplify/average_sites.h"
#include "simplify/syntax_walk.h"

namespace spire::search {
namespace {

// The component every fade reads the distance from.
constexpr const char* kDistance = "spireTransitionDistance";

// The world `shader` reads the engine's per-frame values from: that of its
// first input named as one (engine::frameValues) that is not also supplied
// per instance, as `matModel` is in an instanced pipeline.
std::optional<std::string> engineFrameWorld(const sem::Shader& shader) {
  const auto named = [](const auto& values, const std::string& name) {
    return std::any_of(values.begin(), values.end(), [&](const auto& v) { return v.component == name; });
  };
  for (const sem::Component& c : shader.components) {
    const ast::ComponentDecl* decl = c.firstDecl;
    if (!decl || decl->hasDefinition() || !decl->world) continue;
    if (named(engine::frameValues(), c.name) && !named(engine::instanceValues(), c.name)) return *decl->world;
  }
  return std::nullopt;
}

// The chain level a policy band draws `derived` with: K of its
// `levelK.decisions`; nullopt for a band that names no level of the chain.
std::optional<size_t> chainLevel(const lod::LodLevel& band, const std::string& derived) {
  const auto it = band.decisions.find(derived);
  if (it == band.decisions.end() || !band.member.empty()) return std::nullopt;
  const std::string name = it->second.filename().string();
  size_t k = 0;
  const auto parsed = std::from_chars(name.data() + std::min(name.size(), std::string_view("level").size()),
                                      name.data() + name.size(), k);
  if (parsed.ec != std::errc{} || name != levelFileName(k)) return std::nullopt;
  return k;
}

// The name of the copy of `component`'s definition at one side of a
// transition.
std::string copyName(const Transition& t, const std::string& component, size_t side) {
  return fmt::format("spireTransition{}_{}_{}_{}", t.from, t.to, component, side == 0 ? "near" : "far");
}

// `decl`'s definition from `after` (past its name) to its end, copied to
// side `side` of `t`: each reference to a `blended` component is replaced by
// that component's copy on the same side. A copy must read its side's
// copies, not the blend: a move carries the components its component reads
// into its world (albedo to PrebakeTex takes mixFactor along), and the far
// copy of albedo, computed in PrebakeTex, cannot read mixFactor's blend,
// which is in Fragment.
Expected<std::string, Failure> copiedBody(const SourceManager& sources, const ast::ComponentDecl& decl, uint32_t after,
                                          const Transition& t, size_t side, const std::set<std::string>& blended) {
  std::vector<std::pair<SourceRange, std::string>> uses;
  std::set<std::string> locals;
  simplify::SyntaxWalker walker(
      [&](const ast::Expr& e) {
        if (e.kind != ast::ExprKind::Name) return;
        const std::string& name = ast::cast<ast::NameExpr>(e).name;
        if (blended.contains(name)) uses.emplace_back(e.range, copyName(t, name, side));
      },
      [&](const ast::Stmt& st) {
        if (st.kind != ast::StmtKind::VarDecl) return;
        for (const ast::VarDeclarator& d : ast::cast<ast::VarDeclStmt>(st).declarators) locals.insert(d.name);
      },
      simplify::SyntaxWalker::Immutable::Visit);
  walker.expr(decl.init.get());
  walker.stmt(decl.body.get());
  for (const std::string& name : blended) {
    if (locals.contains(name)) {
      return Failure{
          fmt::format("'{}' declares a local '{}', which hides the component of that name that the "
                      "transition blends; rename the local",
                      decl.name, name)};
    }
  }
  std::sort(uses.begin(), uses.end(), [](const auto& a, const auto& b) { return a.first.begin < b.first.begin; });
  std::string text;
  uint32_t at = after;
  for (const auto& [range, copy] : uses) {
    text += sources.text(SourceRange{decl.range.file, at, range.begin});
    text += copy;
    at = range.end;
  }
  return text + std::string(sources.text(SourceRange{decl.range.file, at, decl.range.end}));
}

// One transition's definitions and placement, from the chain's module.
class TransitionWriter {
 public:
  TransitionWriter(const ShaderLibrary& module, const sem::Shader& shader) : module_(module), shader_(shader) {}

  Expected<Transition, Failure> write(const Level& near, const Level& far, Transition t) {
    const std::string fade = fmt::format("spireTransitionFade{}_{}", t.from, t.to);
    t.definitions = fmt::format(
        "\n    // The transition from level {0} to level {1}: level {0} up to {2:.9g} from the eye, level {1} "
        "from {3:.9g}.\n    [Transition] float {4} = clamp(({5} - {2:.9g}) / {6:.9g}, 0.0, 1.0);\n",
        t.from, t.to, t.nearDistance, t.farDistance, fade, kDistance, t.farDistance - t.nearDistance);
    t.placement = near.placement;
    // What both levels compute, each its own way.
    std::set<std::string> blended;
    for (const auto& [component, where] : t.placement) {
      const std::string other = placementOf(far.placement, component);
      if (!other.empty() && other != where) blended.insert(component);
    }
    Placement helpers;
    for (auto& [component, where] : t.placement) {
      if (!blended.contains(component)) continue;
      auto variation = blend(component, {where, placementOf(far.placement, component)}, blended, t, fade, helpers);
      if (!variation) return variation.error();
      where = worldOf(where) + ":" + *variation;
    }
    // What only the farther level computes keeps its placement.
    for (const auto& [component, where] : far.placement) {
      if (placementOf(t.placement, component).empty()) t.placement.emplace_back(component, where);
    }
    t.placement.insert(t.placement.end(), helpers.begin(), helpers.end());
    return t;
  }

 private:
  // Defines `component:transitionA_B` from copies of its definitions at its
  // near and far placements (`where`), each reading its side's copies of
  // the other `blended` components; its variation name.
  Expected<std::string, Failure> blend(const std::string& component, const std::array<std::string, 2>& where,
                                       const std::set<std::string>& blended, Transition& t, const std::string& fade,
                                       Placement& helpers) {
    const sem::Component* c = shader_.findComponent(component);
    if (!c || !c->type) return Failure{fmt::format("the chain's shader has no component '{}'", component)};
    const std::string type = c->type->name();
    const std::string copy[2] = {copyName(t, component, 0), copyName(t, component, 1)};
    for (size_t side = 0; side < 2; ++side) {
      const ast::ComponentDecl* decl = currentDecl(shader_, *c, where[side]);
      if (!decl)
        return Failure{fmt::format("the chain's shader has no definition of '{}' at '{}'", component, where[side])};
      const uint32_t after = decl->variation.empty() ? decl->nameRange.end : decl->variationRange.end;
      auto body = copiedBody(module_.sources(), *decl, after, t, side, blended);
      if (!body) return body.error();
      t.definitions += fmt::format("    [Transition] {}{} {}{}\n", decl->world ? "@" + *decl->world + " " : "", type,
                                   copy[side], *body);
      helpers.emplace_back(copy[side], worldOf(where[side]));
    }
    const std::string variation = fmt::format("transition{}_{}", t.from, t.to);
    const std::string value = simplify::floatScalarCount(type)
                                  ? fmt::format("mix({}, {}, {})", copy[0], copy[1], fade)
                                  : fmt::format("{} < 0.5 ? {} : {}", fade, copy[0], copy[1]);
    t.definitions += fmt::format("    [Transition] {} {}:{} = {};\n", type, component, variation, value);
    return variation;
  }

  const ShaderLibrary& module_;
  const sem::Shader& shader_;
};

}  // namespace

Expected<FadeDistance, Failure> eyeDistanceInWorld(const sem::Shader& shader) {
  if (!shader.findComponent("vert_pos")) return Failure{fmt::format("'{}' has no vert_pos", shader.name)};
  FadeDistance distance{"length(cameraPosWorld - (matModel * vec4(vert_pos, 1.0)).xyz)", {}};
  std::optional<std::string> world;
  for (const auto& [name, type] : {std::pair{"cameraPosWorld", "vec3"}, std::pair{"matModel", "mat4"}}) {
    if (const sem::Component* c = shader.findComponent(name)) {
      if (c->type && c->type->name() != type)
        return Failure{
            fmt::format("'{}' reads '{}' as a {}, not the engine's {}", shader.name, name, c->type->name(), type)};
      continue;
    }
    if (!world) world = engineFrameWorld(shader);
    if (!world)
      return Failure{
          fmt::format("'{}' reads no per-frame engine value (cameraPos, matMVP, ...), so no world to read "
                      "'{}' from",
                      shader.name, name)};
    distance.declarations += fmt::format("    @{} {} {};\n", *world, type, name);
  }
  return distance;
}

std::string transitionDefinitions(const Transitions& transitions) {
  if (transitions.list.empty()) return {};
  std::string text = transitions.shared;
  for (const Transition& t : transitions.list) text += t.definitions;
  return text;
}

std::string transitionFileName(const Transition& transition) {
  return fmt::format("transition{}_{}.decisions", transition.from, transition.to);
}

std::string transitionDecisionText(const Transition& transition, const ModuleHeader& header) {
  return graph::writeDecisionFile(
      placementDecisions(header.derived, transition.placement),
      fmt::format("spire-simplify --search: the transition of {}'s chain from level {} to level {}, blended by "
                  "distance from {:.9g} to {:.9g}.",
                  header.base, transition.from, transition.to, transition.nearDistance, transition.farDistance));
}

Expected<Transitions, Failure> chainTransitions(const Chain& chain, const lod::LodPolicy& policy,
                                                const ShaderLibrary& chainModule, const std::string& derived,
                                                const TransitionShape& shape) {
  const sem::Shader* shader = chainModule.model().findShader(derived);
  if (!shader) return Failure{fmt::format("the chain's module has no shader '{}'", derived)};
  TransitionWriter writer(chainModule, *shader);
  Transitions transitions;
  transitions.shared =
      fmt::format("\n    // The eye's distance, which the transitions blend by.\n{}    [Transition] float {} = {};\n",
                  shape.distance.declarations, kDistance, shape.distance.expression);
  for (size_t band = 0; band + 1 < policy.levels.size(); ++band) {
    const std::optional<size_t> from = chainLevel(policy.levels[band], derived);
    const std::optional<size_t> to = chainLevel(policy.levels[band + 1], derived);
    if (!from || !to || *from == *to || std::max(*from, *to) >= chain.levels.size()) continue;
    if (chain.levels[*from].placement == chain.levels[*to].placement) continue;
    const double start = band == 0 ? 0.0 : policy.levels[band - 1].until;
    const double edge = policy.levels[band].until;
    Transition t;
    t.band = band;
    t.from = *from;
    t.to = *to;
    t.nearDistance = edge - shape.width * (edge - start);
    t.farDistance = edge;
    auto written = writer.write(chain.levels[*from], chain.levels[*to], std::move(t));
    if (!written) return written.error();
    transitions.list.push_back(std::move(written).value());
  }
  return transitions;
}

lod::LodPolicy withTransitions(lod::LodPolicy policy, const std::vector<Transition>& transitions,
                               const std::string& derived, const std::filesystem::path& folder) {
  // From the farthest band, so that the nearer bands keep their indices.
  for (auto t = transitions.rbegin(); t != transitions.rend(); ++t) {
    if (t->band + 1 >= policy.levels.size()) continue;
    lod::LodLevel transition;
    transition.blend = true;
    transition.until = policy.levels[t->band].until;
    transition.decisions.emplace(derived, folder / transitionFileName(*t));
    policy.levels[t->band].until = static_cast<float>(t->nearDistance);
    policy.levels.insert(policy.levels.begin() + static_cast<std::ptrdiff_t>(t->band) + 1, std::move(transition));
  }
  return policy;
}

}  // namespace spire::search
