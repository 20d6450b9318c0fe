// Locations of the values that cross worlds, for every kernel of a variant
// at once, so that both sides of every edge agree.
//
// A world's outputs and a world's location-based inputs (strategies whose
// signature says usesLocations) are each one side of an interface. Sides
// that must agree are linked: a producer that writes `out` variables and
// each consumer that reads them as `in` variables. Every linked set of sides
// is numbered as one, by key (producer world, component): keys sorted by the
// producer's place in the pipeline's world order, then by component name,
// get consecutive locations. So
//  - a world that reads from several producers (the mesh and a vertex bake,
//    say) never gets two values at one location;
//  - a producer writes each value where every consumer reads it;
//  - a kernel's locations depend only on what crosses its own interfaces,
//    never on other worlds or on declaration order, which locked worlds
//    (paper section 6.2) need to share kernels.
// Keys that a finalized (locked) world writes or reads come first, so that
// shaders sharing a locked world number its interface alike even when an
// unlocked world linked to it reads more (paper section 6.2).
// Abstract producers (the engine) and producers that do not write `out`
// variables (bufferExport) link nothing: the engine binds what the
// consumer's reflection asks for.
#pragma once

#include <cstdint>
#include <map>
#include <set>
#include <utility>
#include <vector>

#include "graph/variant.h"

namespace spire::codegen {

struct Located {
  sem::ComponentId component = 0;
  uint32_t location = 0;
};

class InterfaceAllocation {
 public:
  explicit InterfaceAllocation(const graph::Variant& variant);

  // What world `w` exports (values other worlds import, and the pipeline's
  // exports computed there), in location order.
  const std::vector<Located>& outputs(sem::WorldId w) const { return outputs_[w]; }
  // Where the consumer of import `importIndex` reads `component`.
  uint32_t inputLocation(uint32_t importIndex, sem::ComponentId component) const;

 private:
  using Key = std::pair<sem::WorldId, sem::ComponentId>;  // producer world, component
  // Numbers the keys of the linked sides whose representative is `root`.
  void number(const graph::Variant& variant, uint32_t root, std::vector<Key> keys);

  std::vector<std::vector<Located>> outputs_;
  std::map<std::pair<uint32_t, Key>, uint32_t> locations_;  // (linked sides' root, key) -> location
  std::vector<uint32_t> sideRoot_;                          // side -> its linked set's root
  std::vector<sem::WorldId> importFrom_, importTo_;
  // Per cluster root: the keys a world the shader's bases finalize writes or
  // reads there. Per cluster, because one key (a mesh attribute) can be read
  // by a locked world in one cluster and by an unlocked one in another.
  std::set<std::pair<uint32_t, Key>> lockedKeys_;
};

}  // namespace spire::codegen
