// spire-tune --lod-policy (docs/lod.md, "Policies from measurements"): a
// level-of-detail policy derived from what each level costs and how far it
// is from full quality at each camera distance (He et al. 2015, section 5).
//
// Each material of the scene is probed alone: one of its objects is drawn
// at every level of the scene's policy from each distance (to the nearest
// point of its bounding sphere, along the scene's first view direction),
// and a level's error is the RMSE of its covered pixels against level 0's.
// A level's cost is the scene's median frame time with every object at that
// level. The policy's bands then follow lod::chooseLevels, with the error of
// a level at a distance the largest over the materials, since one policy
// serves them all.
#pragma once

#include <ostream>

#include "tune/tune_options.h"

namespace spire::tune {

// Measures and writes `options.lodPolicyPath` (atomically), printing the
// measurements and the bands chosen. Returns the exit status.
int runLodPolicyTune(const TuneOptions& options, std::ostream& out, std::ostream& err);

}  // namespace spire::tune
