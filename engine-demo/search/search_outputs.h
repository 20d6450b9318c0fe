// What `spire-simplify --search` writes, as one set (replaced atomically):
// the module of the chain's definitions, one decision file and one image
// per level (level0.* is the original), chain.csv, the chain's
// level-of-detail policy with its transition shaders' decision files
// (transitionA_B.decisions), report.md and the chain's error-against-time
// plot, error_time.png.
#pragma once

#include <string>
#include <vector>

#include "search/chain.h"
#include "search/chain_policy.h"
#include "search/search_options.h"
#include "search/transitions.h"
#include "support/atomic_directory.h"
#include "support/expected.h"

namespace spire::search {

// A transition as the search drew and timed it.
struct DrawnTransition {
  std::string image;  // from the scene's first camera view, PNG
  // Its frame time over level 0's, frame for frame: a transition computes
  // both levels it blends, so its band costs more than either.
  double timeRatio = 0.0;
};

struct ChainTransitions {
  Transitions transitions;
  std::vector<DrawnTransition> drawn;  // one per transition, in order
  std::string note;                    // without transitions, why
};

struct OutputRequest {
  ModuleHeader header;  // with the `using` path relative to the output folder
  const SearchOptions* options = nullptr;
  double referenceMs = 0.0;  // the reference's median frame time in this run (level 0's, or --reference's)
  // The chain as a level-of-detail policy (lod_policy.json and a section
  // of report.md); none when the chain has no level after the original.
  const ChainPolicy* policy = nullptr;
  // Each level's image from the scene's first camera view, PNG; none when
  // empty.
  std::vector<std::string> levelImages;
  // The transition shaders at the policy's switches: their definitions go
  // into the module, their decision files and images beside it, and their
  // bands into the policy.
  ChainTransitions transitions;
};

// The module's file name: the derived shader's name + ".spire".
std::string moduleFileName(const ModuleHeader& header);
// Level `k`'s decision file: its name and its text.
std::string levelFileName(size_t k);
std::string levelDecisionText(const Chain& chain, size_t k, const ModuleHeader& header);

Expected<FileSet, Failure> searchOutputs(const Chain& chain, const OutputRequest& request);

}  // namespace spire::search
