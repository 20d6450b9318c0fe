// The variants a tuning run explores: the product of the selected choices
// (paper section 7.4). Each selected component contributes its alternatives
// from the choice file, optionally narrowed to some worlds or variation
// names; the product is enumerated in a fixed order (first component varies
// slowest), and sampled deterministically when it exceeds a limit.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "graph/choice_space.h"
#include "support/expected.h"

namespace spire::tune {

// One explored component and the placements tried for it.
struct Axis {
  std::string component;
  std::vector<std::string> placements;  // "World" or "World:variation", choice-file order
};

struct TunePoint {
  size_t index = 0;  // position in the full product
  std::map<std::string, std::string> decisions;
};

struct TuneSpace {
  std::vector<Axis> axes;
  uint64_t productSize = 1;
  std::vector<TunePoint> points;  // every point, or the sample
  bool sampled = false;
};

struct SpaceRequest {
  // Components to explore; empty means every choice of the shader. An entry
  // `name@World` keeps only that component's placements in World (so
  // `specular@Fragment` explores the specular models per fragment only);
  // several such entries for one component keep each of their worlds, and
  // the plain `name` every world.
  std::vector<std::string> components;
  // When non-empty, keep only placements whose world or variation name is
  // listed ("PrebakeTex", "ggx"): listing variation names explores
  // algorithms, listing worlds explores placement.
  std::vector<std::string> only;
  uint64_t maxVariants = 4096;  // above this the product is sampled
  uint64_t seed = 1;
  // Placements never explored, by component: definitions marked
  // [Transition], which blend two levels of detail by distance and cost
  // both (transitionPlacements). A component left with none is no axis
  // unless it was asked for, which is an error.
  std::map<std::string, std::set<std::string>> transitions;
};

// The placements of the shader's choices whose definition is marked
// [Transition], by component.
std::map<std::string, std::set<std::string>> transitionPlacements(const graph::ChoiceSpace& space);

// Builds the space from the shader's choices (graph::enumerateChoices).
// Errors name the component that has no choice or no placement left.
Expected<TuneSpace, Failure> buildTuneSpace(const std::vector<graph::Choice>& choices, const SpaceRequest& request);

// The point at `index` of the full product.
TunePoint pointAt(const std::vector<Axis>& axes, uint64_t index);

}  // namespace spire::tune
