#include "sema/route_selection.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <set>
#include <tuple>

#include "sema/attribute_catalog.h"

namespace spire::sem {
namespace {

// The additive part of a route's cost, smaller is better; the worst
// transfer is handled by searching one transfer level at a time.
using Cost = std::tuple<uint32_t, int64_t, uint32_t>;  // lossy imports, -priority, imports

constexpr uint32_t kTransferLevels = 4;

struct Search {
  const Pipeline& pipeline;
  WorldId source = 0;
  uint32_t level = 0;  // the worst transfer allowed
  std::vector<std::optional<Cost>> cost;

  bool allowed(const Import& import) const { return static_cast<uint32_t>(transferOf(pipeline, import)) <= level; }
  Cost through(const Import& import) const {
    const Cost& before = *cost[import.from];
    const bool lossy = transferOf(pipeline, import) != ValueTransfer::Exact;
    return {std::get<0>(before) + (lossy ? 1 : 0), std::get<1>(before) - import.priority, std::get<2>(before) + 1};
  }
  // Best costs from `source` over the allowed imports, in topological order.
  void run() {
    cost.assign(pipeline.worlds.size(), std::nullopt);
    cost[source] = Cost{0, 0, 0};
    for (WorldId w : pipeline.topologicalOrder) {
      if (!cost[w]) continue;
      for (const Import& import : pipeline.imports) {
        if (import.from != w || !allowed(import)) continue;
        const Cost next = through(import);
        if (!cost[import.to] || next < *cost[import.to]) cost[import.to] = next;
      }
    }
  }
  // The imports into `w` that lie on a best route, by producer name.
  std::vector<uint32_t> bestInto(WorldId w) const {
    std::vector<uint32_t> best;
    for (uint32_t k = 0; k < pipeline.imports.size(); ++k) {
      const Import& import = pipeline.imports[k];
      if (import.to == w && allowed(import) && cost[import.from] && through(import) == *cost[w]) best.push_back(k);
    }
    std::sort(best.begin(), best.end(), [&](uint32_t a, uint32_t b) {
      return pipeline.worlds[pipeline.imports[a].from].name < pipeline.worlds[pipeline.imports[b].from].name;
    });
    return best;
  }
};

class RouteSelector {
 public:
  RouteSelector(Pipeline& pipeline, DiagnosticList& diags) : pipeline_(pipeline), diags_(diags) {}

  void run() {
    const size_t n = pipeline_.worlds.size();
    pipeline_.routes.assign(n * n, {});
    for (WorldId source = 0; source < n; ++source) {
      std::vector<bool> done(n, false);
      done[source] = true;
      for (uint32_t level = 0; level < kTransferLevels; ++level) {
        Search search{pipeline_, source, level, {}};
        search.run();
        for (WorldId target = 0; target < n; ++target) {
          if (done[target] || !search.cost[target]) continue;
          done[target] = true;
          pipeline_.routes[source * n + target] = walkBack(search, target, done);
        }
      }
    }
  }

 private:
  // The route to `target`, back to the source or to the first world on the
  // way whose route is already chosen, which it then extends: the routes
  // from one source form a tree, so a value carried to several worlds
  // enters each of them once, by one import.
  std::vector<uint32_t> walkBack(const Search& search, WorldId target, const std::vector<bool>& done) {
    std::vector<uint32_t> route;
    WorldId w = target;
    while (w == target || !done[w]) {
      const std::vector<uint32_t> best = search.bestInto(w);
      if (best.size() > 1) reportTie(search.source, target, best);
      route.push_back(best.front());
      w = pipeline_.imports[best.front()].from;
    }
    const std::vector<uint32_t>& prefix = pipeline_.routes[search.source * pipeline_.worlds.size() + w];
    route.insert(route.end(), prefix.rbegin(), prefix.rend());
    std::reverse(route.begin(), route.end());
    return route;
  }

  void reportTie(WorldId source, WorldId target, const std::vector<uint32_t>& tied) {
    if (!reported_.insert(tied).second) return;
    const Import& chosen = pipeline_.imports[tied.front()];
    std::string others;
    for (size_t i = 1; i < tied.size(); ++i) {
      others += fmt::format("{}'{}'", i == 1 ? "" : ", ", pipeline_.worlds[pipeline_.imports[tied[i]].from].name);
    }
    const std::string& via = pipeline_.worlds[chosen.from].name;
    Diagnostic& d = diags_.report(
        DiagCode::W4110, SourceRange::cover(chosen.decl->fromRange, chosen.decl->toRange),
        fmt::format("values reach world '{}' equally well from '{}' and from {} (for example a value of '{}' read in "
                    "'{}'); spirec routes them through '{}', the first by name. Give the import you want a higher "
                    "[Priority: \"N\"] to choose",
                    pipeline_.worlds[chosen.to].name, via, others, pipeline_.worlds[source].name,
                    pipeline_.worlds[target].name, via));
    for (size_t i = 1; i < tied.size(); ++i) {
      const Import& other = pipeline_.imports[tied[i]];
      d.note(SourceRange::cover(other.decl->fromRange, other.decl->toRange), "the equally good import is here");
    }
  }

  Pipeline& pipeline_;
  DiagnosticList& diags_;
  std::set<std::vector<uint32_t>> reported_;
};

}  // namespace

ValueTransfer transferOf(const Pipeline& pipeline, const Import& import) {
  if (pipeline.worlds[import.from].isAbstract || !import.strategy.signature) return ValueTransfer::Exact;
  return import.strategy.signature->transfer;
}

int importPriority(const ast::ImportDecl& decl) {
  int priority = 0;
  for (const ast::Attribute& a : decl.attributes) {
    if (a.name != "Priority" || !a.value || checkAttribute(AttributeSite::Import, a.name, a.value)) continue;
    std::from_chars(a.value->data(), a.value->data() + a.value->size(), priority);
  }
  return priority;
}

void selectRoutes(Pipeline& pipeline, DiagnosticList& diags) { RouteSelector(pipeline, diags).run(); }

}  // namespace spire::sem
