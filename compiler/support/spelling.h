// "Did you mean ...?" suggestions for misspelled names.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace spire {

// Optimal string alignment distance (Levenshtein plus adjacent transposition).
size_t editDistance(std::string_view a, std::string_view b);

// The closest candidate within a distance that scales with the name's length,
// or nothing when no candidate is plausibly what was meant. Ties go to the
// earliest candidate, so results are deterministic.
std::optional<std::string> closestSpelling(std::string_view name, const std::vector<std::string_view>& candidates);

}  // namespace spire
