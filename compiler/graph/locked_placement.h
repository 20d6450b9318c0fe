// Locked worlds and the placement of inherited components (paper section
// 6.2). Every shader derived from a finalizer must get the finalizer's
// kernels for the worlds it locks. The shader graph keeps derived
// definitions out of locked worlds and their reads off routes from or
// through them; what it cannot see is placement. A component has one
// placement per variant, so a derived shader that reads an inherited
// component in another world can move it, and with it the route by which
// the base's own readers get it, into or through a locked world. The variant
// builder therefore places each level's components as the base alone would
// (reads written below the level do not count) and then holds what the
// locked worlds see of them: their locked footprint. What only derived
// shaders define has no base placement to hold: it may enter a locked
// world, not pass through one, and two derived shaders that deliver it
// differently (a texture in one, a uniform in the other) still get locked
// kernels of their own; nothing here compares derived shaders.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "graph/shader_graph.h"

namespace spire::graph {

// A finalizing shader above a concrete shader, with every world locked at
// its level: its own and those of the finalizers above it.
struct LockLevel {
  const sem::Shader* finalizer = nullptr;
  WorldMask locked = 0;
};

// The finalizing shaders strictly above `shader` (a shader's own
// `finalizes` locks nothing for itself), topmost first.
std::vector<LockLevel> lockLevels(const sem::Shader& shader);

// How many of those the author `origin` is below: 0 for the topmost
// finalizer, the shaders above it and the pipeline.
uint32_t lockDepth(const sem::Shader& shader, std::string_view origin);

// The worlds finalized above `origin` in `shader`'s chain: where its
// definitions may not be computed, nor read from or through.
WorldMask lockedAbove(const sem::Shader& shader, std::string_view origin);

// What the kernels of the `locked` worlds see of a component computed by
// alternative `alt` and read in the worlds of `reach`: the alternative
// itself when its world is locked, and each import on the value's routes
// that enters or leaves a locked world.
struct LockedFootprint {
  std::optional<AltId> lockedAlternative;
  std::vector<uint32_t> imports;  // sorted, unique

  bool operator==(const LockedFootprint&) const = default;
  bool empty() const { return !lockedAlternative && imports.empty(); }
};
LockedFootprint lockedFootprint(const ShaderGraph& graph, sem::ComponentId component, AltId alt, WorldMask reach,
                                WorldMask locked);

// A locked world that sees `component` differently in the two footprints.
sem::WorldId changedLockedWorld(const ShaderGraph& graph, sem::ComponentId component, const LockedFootprint& held,
                                const LockedFootprint& moved, WorldMask locked);

// Why no variant exists when one would without holding the base's
// placement: a definition written below a finalizer reads an inherited
// component where the base's placement does not reach, and the placement
// that would reach it sends the value into or through a locked world; or a
// component only derived shaders define reaches a reader only through one.
struct LockedMove {
  enum class Kind : uint8_t {
    // A derived shader's read needs an inherited component elsewhere.
    Moved,
    // What only derived shaders define reaches `reader` only through a
    // locked world (`lockedWorld`).
    PassesThrough,
  };
  Kind kind = Kind::Moved;
  sem::ComponentId component = 0;
  std::optional<AltId> held;  // the base's alternative, if the base computes it
  AltId moved = 0;            // the alternative the derived read needs
  sem::ComponentId readerComponent = 0;
  const sem::Definition* reader = nullptr;
  size_t use = 0;  // index into reader->dependencies
  sem::WorldId readerWorld = 0;
  const sem::Shader* finalizer = nullptr;
  sem::WorldId lockedWorld = 0;  // a locked world the move would change
};

class ChoiceSpace;

// When `space`, with no decision applied, has no variant because holding
// the base's placement leaves none: E4015 at the derived read that would
// move an inherited component (or at the derived definition that would
// pass through a locked world), with a note at the `finalizes` clause.
// Returns whether it reported one.
bool reportLockedMove(const ChoiceSpace& space, DiagnosticList& diags);

}  // namespace spire::graph
