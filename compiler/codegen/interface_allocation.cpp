#include "codegen/interface_allocation.h"

#include <algorithm>
#include <numeric>
#include <set>

#include "codegen/kernel_builder.h"

namespace spire::codegen {
namespace {

bool readsLocations(const sem::Import& import) {
  return import.strategy.signature && import.strategy.signature->usesLocations;
}

bool writesLocations(const sem::World& world) {
  return !world.isAbstract && world.exportStrategy && world.exportStrategy->signature &&
         world.exportStrategy->signature->usesLocations;
}

class Sides {
 public:
  explicit Sides(size_t count) : parent_(count) { std::iota(parent_.begin(), parent_.end(), 0u); }
  uint32_t find(uint32_t side) {
    while (parent_[side] != side) side = parent_[side] = parent_[parent_[side]];
    return side;
  }
  void join(uint32_t a, uint32_t b) { parent_[find(a)] = find(b); }

 private:
  std::vector<uint32_t> parent_;
};

}  // namespace

InterfaceAllocation::InterfaceAllocation(const graph::Variant& variant) {
  const graph::ShaderGraph& g = variant.graph();
  const sem::Pipeline& pipeline = g.pipeline();
  const uint32_t n = static_cast<uint32_t>(pipeline.worlds.size());
  // Side w is world w's outputs, side n + w its location-based inputs.
  std::vector<std::set<Key>> keys(size_t{2} * n);
  for (sem::WorldId w = 0; w < n; ++w) {
    for (const graph::Transfer& t : variant.world(w).outputs) keys[w].insert({w, t.component});
    for (const graph::Transfer& t : variant.world(w).inputs) {
      const sem::Import& import = pipeline.imports[t.importIndex];
      if (readsLocations(import)) keys[n + w].insert({import.from, t.component});
    }
  }
  for (const graph::Sink& sink : g.sinks()) {
    if (g.node(sink.component).component->isExport) keys[sink.world].insert({sink.world, sink.component});
  }
  Sides sides(size_t{2} * n);
  for (const sem::Import& import : pipeline.imports) {
    importFrom_.push_back(import.from);
    importTo_.push_back(import.to);
    if (readsLocations(import) && writesLocations(pipeline.worlds[import.from])) sides.join(import.from, n + import.to);
  }
  // Keys a locked world writes or reads come first, so that their numbers
  // depend only on what the locked world's base decides.
  const auto& finalized = g.shader().finalizedWorlds;
  for (sem::WorldId w : finalized) {
    for (const uint32_t side : {w, n + w}) {
      for (const Key& key : keys[side]) lockedKeys_.insert({sides.find(side), key});
    }
  }
  std::map<uint32_t, std::set<Key>> clusters;
  for (uint32_t side = 0; side < 2 * n; ++side) clusters[sides.find(side)].insert(keys[side].begin(), keys[side].end());
  for (const auto& [root, members] : clusters) number(variant, root, {members.begin(), members.end()});
  sideRoot_.resize(size_t{2} * n);
  for (uint32_t side = 0; side < 2 * n; ++side) sideRoot_[side] = sides.find(side);

  outputs_.resize(n);
  for (sem::WorldId w = 0; w < n; ++w) {
    for (const Key& key : keys[w]) outputs_[w].push_back({key.second, locations_.at({sideRoot_[w], key})});
    std::sort(outputs_[w].begin(), outputs_[w].end(),
              [](const Located& a, const Located& b) { return a.location < b.location; });
  }
}

void InterfaceAllocation::number(const graph::Variant& variant, uint32_t root, std::vector<Key> keys) {
  const graph::ShaderGraph& g = variant.graph();
  std::sort(keys.begin(), keys.end(), [&](const Key& a, const Key& b) {
    const bool lockedA = lockedKeys_.count({root, a}) != 0, lockedB = lockedKeys_.count({root, b}) != 0;
    if (lockedA != lockedB) return lockedA;
    if (a.first != b.first) return g.worldRank(a.first) < g.worldRank(b.first);
    return g.node(a.second).component->name < g.node(b.second).component->name;
  });
  uint32_t location = 0;
  for (const Key& key : keys) {
    locations_[{root, key}] = location;
    location += locationSlots(g.node(key.second).component->type);
  }
}

uint32_t InterfaceAllocation::inputLocation(uint32_t importIndex, sem::ComponentId component) const {
  const uint32_t n = static_cast<uint32_t>(outputs_.size());
  const uint32_t consumerSide = n + importTo_[importIndex];
  return locations_.at({sideRoot_[consumerSide], {importFrom_[importIndex], component}});
}

}  // namespace spire::codegen
