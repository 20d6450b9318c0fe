// A level-of-detail policy (He et al. 2015, section 6; the Spire paper,
// section 7.2): distance bands mapped to the members of a shader group, with
// hysteresis so that an object near a band's edge does not flip between two
// levels, and a cross-fade of a few frames that hides each switch.
//
// The file is JSON (docs/lod.md):
//   {"levels": [{"member": "LodHQ", "until": 12},
//               {"member": "LodMQ", "until": 40},
//               {"member": "LodLQ"}],
//    "hysteresis": 0.1, "transitionFrames": 8}
// Levels go from nearest to farthest; each but the last ends at `until`
// (world units from the camera to the nearest point of the object's
// bounding sphere), the last has no end.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "support/diagnostic.h"
#include "support/source_manager.h"

namespace spire::lod {

struct LodLevel {
  std::string member;  // the group member whose shader draws this band, e.g. "LodMQ"
  float until = 0.0F;  // the band's far edge; +infinity for the last level
  SourceRange range;
};

struct LodPolicy {
  std::vector<LodLevel> levels;  // nearest first, `until` strictly increasing
  // A switch to the farther level happens at until * (1 + hysteresis), back
  // to the nearer one at until * (1 - hysteresis).
  float hysteresis = 0.1F;
  // Frames over which a switch cross-fades the two levels (blended); 0
  // switches at once.
  uint32_t transitionFrames = 8;
  SourceRange range;  // the whole file, for messages about the policy
};

// Reads and checks a policy file; every problem is reported with its
// file:line:col (E7001-E7007, as in scene files) and gives nullopt. A file
// that cannot be read is reported at `namedAt`, where the path was given.
std::optional<LodPolicy> loadLodPolicy(const std::filesystem::path& path, SourceManager& sources, DiagnosticList& diags,
                                       SourceRange namedAt = {});
std::optional<LodPolicy> parseLodPolicy(std::string displayPath, std::string text, SourceManager& sources,
                                        DiagnosticList& diags);

// The policy file's JSON text, as loadLodPolicy reads it back: what a tool
// that derives a policy from measurements writes.
std::string formatLodPolicy(const LodPolicy& policy);

}  // namespace spire::lod
