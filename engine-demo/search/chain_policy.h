// A search's chain as a level-of-detail policy (He et al. 2015, section 5):
// each level's error at several camera distances and its frame time are
// measured by rendering (tune::measureLevels, as spire-tune --lod-policy
// measures a scene's own policy); a level's cost is what the chain was
// ordered by (search::costOf: C, or the measured time), and the bands
// follow He et al.'s rule,
// the cheapest level within tolerated_err(d) = ((d - d_near) / (d_far -
// d_near))^Q x max_error, with a penalty per switch. The policy's levels
// are the chain's decision files, so the scene's instances of the derived
// shader draw each band with its level and every other instance as it is.
#pragma once

#include <filesystem>
#include <string>

#include "lod/lod_policy.h"
#include "renderer/scene_renderer.h"
#include "search/chain.h"
#include "search/greedy_search.h"
#include "search/search_options.h"
#include "support/expected.h"
#include "tune/level_measurement.h"

namespace spire::search {

struct ChainPolicy {
  lod::LodPolicy policy;  // decision files as `levelK.decisions` in the output folder
  std::string table;      // the measurements and the choice, Markdown (tune::levelTable)
};

// Measures `chain` on `renderer` (whose scene `setup` points at) and chooses
// the policy. The chain's module and decision files are written to
// setup.workDir for the renderer to read; the instance is left pointing at
// that module. `outputDir` is where the policy's decision files will be.
Expected<ChainPolicy, Failure> chainPolicy(const Chain& chain, const SearchSetup& setup,
                                           engine::SceneRenderer& renderer, const SearchOptions& options,
                                           const std::filesystem::path& outputDir);

}  // namespace spire::search
