// Random decision maps: for a random subset of a shader's choices (its
// choice file, graph::enumerateChoices), a random alternative, written as a
// decision file so that a failure can be replayed with spirec.
#pragma once

#include <string>
#include <vector>

#include "gen/random_source.h"
#include "graph/choice_space.h"

namespace spire::testgen {

// Lines `Prefix.component = World[:variation]` for the choices picked. Now
// and then a line names an alternative outside the space, which spirec must
// skip with a warning.
std::string generateDecisions(const std::vector<graph::Choice>& choices, RandomSource& rng);

}  // namespace spire::testgen
