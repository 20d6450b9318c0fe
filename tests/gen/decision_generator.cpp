#include "gen/decision_generator.h"

#include <fmt/format.h>

namespace spire::testgen {

std::string generateDecisions(const std::vector<graph::Choice>& choices, RandomSource& rng) {
  std::string out;
  const int percent = rng.pick(20, 100);  // how much of the space this map decides
  for (const graph::Choice& choice : choices) {
    if (!rng.chance(percent)) continue;
    out += fmt::format("{} = {}\n", choice.key, rng.element(choice.names));
  }
  if (!choices.empty() && rng.chance(3)) out += fmt::format("{} = NoSuchWorld\n", rng.element(choices).key);
  return out;
}

}  // namespace spire::testgen
