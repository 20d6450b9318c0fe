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
//
// A level draws an instance with a group member (`shader<member>`), with
// decision files of its own for some shaders, or both:
//   {"decisions": {"TerrainSearch": "level2.decisions"}, "until": 30}
// draws the instances of TerrainSearch with level2.decisions (a path
// relative to the policy file) and every other instance as the scene gives
// it. That is how a chain of decision files over one shader, such as
// spire-simplify --search writes, becomes a policy. `"blend": true` marks a
// band whose decision files are transition shaders between its neighbours.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "scene/scene_file.h"
#include "support/diagnostic.h"
#include "support/source_manager.h"

namespace spire::lod {

struct LodLevel {
  std::string member;  // the group member whose shader draws this band, e.g. "LodMQ"; empty: the instance's shader
  float until = 0.0F;  // the band's far edge; +infinity for the last level
  SourceRange range;
  // By the instance's shader name (before `member` applies): the decision
  // file its instances draw with in this band instead of their own.
  std::map<std::string, std::filesystem::path> decisions;
  // A transition shader's band (He et al. 2015): what it draws blends the
  // bands on either side by each pixel's distance, so it is drawn by every
  // object whose bounding sphere reaches into it, and its edges have no
  // hysteresis: at them the blend is one of its neighbours.
  bool blend = false;

  // Whether two levels draw every instance alike (their bands aside).
  bool drawsAs(const LodLevel& other) const {
    return member == other.member && decisions == other.decisions && blend == other.blend;
  }
};

// `instance` as `level` draws it: compiled as `shader<member>` when the
// level names a member, with the level's decision file for the instance's
// shader in place of its own decisions when the level has one.
scene::InstanceDesc levelInstance(const scene::InstanceDesc& instance, const LodLevel& level);

// A level's name for people: its member, its decision files' stems, or both
// ("LodMQ", "level2", "LodMQ level2").
std::string levelName(const LodLevel& level);

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
// that derives a policy from measurements writes. Decision files are
// written relative to `folder`, the folder the file is written to (as
// they are: when empty).
std::string formatLodPolicy(const LodPolicy& policy, const std::filesystem::path& folder = {});

}  // namespace spire::lod
