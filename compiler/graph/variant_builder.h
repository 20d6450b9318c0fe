// The placement search behind buildVariant (section 5.2's default
// placement and the decisions it honours), with the lock levels that keep
// locked worlds' kernels the base's (locked_placement.h).
#pragma once

#include <cstdint>
#include <optional>
#include <set>
#include <utility>
#include <vector>

#include "graph/choice_space.h"
#include "graph/locked_placement.h"
#include "graph/variant.h"

namespace spire::graph {

class VariantBuilder {
 public:
  // Each decision applied to `domains`, by component: the alternative it
  // keeps and its DecisionRequest::lockDepth.
  struct Decision {
    AltId alternative = 0;
    uint32_t lockDepth = 0;
  };
  using Decided = std::vector<std::optional<Decision>>;

  explicit VariantBuilder(const ShaderGraph& graph);

  // Chooses an alternative for every live component, consumers first, with
  // backtracking when a choice leaves a dependency nowhere to go. Under
  // locked worlds, each level's components are placed first as the base
  // alone would place them, and what the locked worlds see of them is held.
  std::optional<Variant> place(const ChoiceSpace& domains, const Decided& decided);
  // Why place(), without decisions, finds no variant, when holding the
  // base's placement is the reason: the derived read that would move an
  // inherited component, or the derived definition that would pass through
  // a locked world.
  std::optional<LockedMove> explainLockedMove(const ChoiceSpace& domains) const;

 private:
  // One component's step in the search: its candidates in preference order,
  // the next to try, and what its choice changed.
  struct Frame {
    std::vector<AltId> candidates;
    size_t next = 0;
    std::vector<std::pair<sem::ComponentId, WorldMask>> saved;  // mustReach before this choice
    bool skipped = false;
  };
  using Choice = std::vector<std::optional<AltId>>;
  // A complete choice, with the worlds each live component must reach.
  struct Placement {
    Choice choice;
    std::vector<WorldMask> reach;
  };
  // A lock level placed as its base alone places it, and the footprint held
  // for each component the level owns; nullopt for the others.
  struct HeldLevel {
    WorldMask locked = 0;
    Placement placement;
    std::vector<std::optional<LockedFootprint>> footprints;
  };
  // What one search counts and keeps: reads by definitions at most
  // `counted` levels below the finalizers, and the held levels' footprints.
  struct Rules {
    uint32_t counted = UINT32_MAX;
    const std::vector<HeldLevel>* held = nullptr;
    // Set for a level's search: alternatives come from the graph, not from
    // the choice space, whose propagation includes every derived read.
    const Decided* decided = nullptr;
  };

  // The backtracking search; nullopt when no placement exists or the search
  // gives up.
  std::optional<Placement> search(const ChoiceSpace& domains, const Rules& rules) const;
  // The search of the whole shader under the held levels.
  std::optional<Placement> searchHolding(const ChoiceSpace& domains, const std::vector<HeldLevel>& held) const;
  // The alternatives of `c` a search may try.
  std::vector<AltId> candidates(const ChoiceSpace& domains, sem::ComponentId c, const Rules& rules) const;
  // `alts` in the default preference order.
  std::vector<AltId> preferred(std::vector<AltId> alts, sem::ComponentId c) const;
  // Whether alternative `a` of `c` reaches every world `c` must reach.
  bool fits(sem::ComponentId c, AltId a, const std::vector<WorldMask>& mustReach) const;
  // Whether alternative `a` of `c`, read in `reach`, shows the locked
  // worlds what every held level holds for `c`.
  bool keepsFootprints(sem::ComponentId c, AltId a, WorldMask reach, const Rules& rules) const;
  // The frame's next candidate that fits and leaves each of its dependencies
  // an alternative that fits, with `mustReach` widened for it.
  std::optional<AltId> chooseNext(Frame& frame, sem::ComponentId c, const ChoiceSpace& domains,
                                  std::vector<WorldMask>& mustReach, const Rules& rules) const;
  // Every lock level placed in turn, each under the levels above it;
  // nullopt when one has no placement (nor then has the whole shader).
  std::optional<std::vector<HeldLevel>> holdLevels(const ChoiceSpace& domains, const Decided& decided) const;
  HeldLevel holdLevel(Placement placement, uint32_t level) const;
  // Whether the level's base places `c`: a definition of it, or the
  // `abstract @W` that puts it in W, is written at or above the level's
  // finalizer. Then a derived (re)definition must deliver it as the base
  // does; what only derived shaders place may reach a locked world but not
  // pass through one.
  bool owns(sem::ComponentId c, uint32_t level) const;
  // A live definition's read of a component, in a placement.
  struct Read {
    sem::ComponentId reader = 0;
    const sem::Definition* definition = nullptr;
    size_t use = 0;  // index into definition->dependencies
    sem::WorldId world = 0;
  };
  std::vector<Read> readsOf(sem::ComponentId c, const Placement& placement) const;
  // The first reader, written below `level`, whose read moves `c` from
  // where the level holds it.
  std::optional<LockedMove> movedBy(sem::ComponentId c, uint32_t level, const HeldLevel& held,
                                    const Placement& free) const;
  // The first reader that a component only derived shaders define reaches
  // only through a world locked at `level`.
  std::optional<LockedMove> passesThrough(sem::ComponentId c, uint32_t level, const HeldLevel& held,
                                          const Placement& free) const;
  // The variant of a complete choice: its live components, kernels and routes.
  std::optional<Variant> assemble(Choice choice);
  void route(Variant& v, sem::ComponentId component, sem::WorldId from, sem::WorldId to,
             std::set<std::pair<sem::ComponentId, uint32_t>>& seen);
  bool routeStrategyArguments(Variant& v, std::set<std::pair<sem::ComponentId, uint32_t>>& seen);

  const ShaderGraph& graph_;
  std::vector<LockLevel> levels_;
  // Per component and alternative: the lock depth of the definition's author.
  std::vector<std::vector<uint32_t>> depth_;
};

// Why `space`, with no decision applied, has no variant, when holding the
// base's placement under locked worlds is the reason.
std::optional<LockedMove> explainLockedMove(const ChoiceSpace& space);

}  // namespace spire::graph
