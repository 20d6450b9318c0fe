// A scene drawn with level of detail at scale (docs/lod.md; the Spire paper,
// section 7.2): every instance of the scene file, scattered copies
// included, is drawn each frame at the member of its shader's group that
// the level-of-detail policy gives for its distance. Objects whose programs
// share Vertex and Fragment kernel keys (and read the same shared values)
// are drawn together: one pipeline, descriptors and per-instance record
// buffers per draw group, one instanced draw per mesh in each spatial
// block. Batches come from the reflection's kernel keys, never from shader
// names, so a locked base shader's levels batch across materials.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "lod/instance_batches.h"
#include "lod/lod_policy.h"
#include "renderer/scene_renderer.h"
#include "support/diagnostic.h"

namespace spire::engine {

struct LodOptions {
  // Every instance at this level of the policy instead of by distance
  // (0: the nearest band's member, the scene at full quality).
  std::optional<uint32_t> fixedLevel;
  bool transitions = true;  // false: switch levels at once, whatever the policy says
  // Where preparing the levels reports problems, else the renderer's list:
  // a thread of its own (createCompiled) passes a list of its own.
  DiagnosticList* diagnostics = nullptr;
};

struct LodFrameStats {
  uint32_t visible = 0;         // instances inside the view frustum
  uint32_t batches = 0;         // pipeline and descriptor binds, overlays included
  uint32_t overlayBatches = 0;  // of which blended cross-fades
  uint32_t drawCalls = 0;       // instanced draws
};

class LodScene {
 public:
  // Compiles every instance's shader as each member the policy names
  // (`Shader<Member>`), runs their bakes, and builds one pipeline per draw
  // group. `renderer` must outlive the scene.
  static Expected<std::unique_ptr<LodScene>> create(SceneRenderer& renderer, lod::LodPolicy policy,
                                                    const LodOptions& options = {});
  // Per level of a policy, per scene-file instance (prototype): the programs
  // create compiles.
  using LevelPrograms = std::vector<std::vector<VariantProgram>>;
  // As create, with the programs compiled already, for a tool that compiles
  // them on a thread of its own (SceneRenderer::compileLevelIn) while the
  // previous scene draws: only the bakes and pipelines are made here. That
  // thread may call this too, while the previous scene keeps drawing on
  // another (SceneRenderer::prepare with TargetUse::Keep): the new levels
  // must draw into the frame's target as it is. `programs` has one entry per
  // level of the policy as `options` applies it.
  static Expected<std::unique_ptr<LodScene>> createCompiled(SceneRenderer& renderer, lod::LodPolicy policy,
                                                            LevelPrograms programs, const LodOptions& options = {});
  ~LodScene();
  LodScene(const LodScene&) = delete;
  LodScene& operator=(const LodScene&) = delete;

  // Every instance at the level of its distance from `view`, without fading:
  // the first frame of a camera path.
  void resetLevels(const scene::CameraView& view);
  // One frame's level update for a camera at `view`: each instance's level
  // from its distance (hysteresis), cross-fades advanced.
  void updateLevels(const scene::CameraView& view);
  // Draws the instances at their current levels from `view` at `time`
  // seconds: culled, batched, recorded, submitted.
  Expected<FrameTiming> draw(const scene::CameraView& view, float time);
  // One frame: updateLevels, then draw.
  Expected<FrameTiming> render(const scene::CameraView& view, float time);
  // Color target 0 as the last frame left it, read back.
  Expected<measure::FloatImage> readColor();
  // 1 where the last frame drew (depth < 1), else 0.
  Expected<std::vector<uint8_t>> readCoverage();
  // Draws only these instances from now on (every instance when empty): one
  // object alone in the frame, as spire-tune --lod-policy measures a level's
  // error at a distance. Indices must be below instanceCount().
  void drawOnly(std::vector<uint32_t> instances);
  // New band edges, hysteresis or cross-fade length for the levels already
  // compiled, without compiling anything: `policy` must name the same
  // members in the same order (else an error, and nothing changes). Levels
  // are placed again from `view` without fading, so an edit shows at once.
  Expected<void> setBands(const lod::LodPolicy& policy, const scene::CameraView& view);
  // The policy the scene draws with (LodOptions applied).
  const lod::LodPolicy& policy() const;
  // W7102, at the policy's level, for each shader whose kernels at that
  // level do not read lodFade where switches into the level should
  // cross-fade (transitionFrames > 0, from a neighbouring band that is not
  // a blend band): they are drawn at once. Not reported while the scene is
  // made, since a tool may make it on a thread of its own.
  void reportSwitchesThatCannotFade(DiagnosticList& diags) const;

  const LodFrameStats& lastStats() const;
  size_t instanceCount() const;
  const lod::DrawGroups& drawGroups() const;
  // The level `instance` is at (or switching to).
  uint32_t levelOf(size_t instance) const;
  // Where instance `instance` stands and its prototype (the scene-file
  // instance it is a copy of).
  const lod::SceneInstance& instance(size_t instance) const;

 private:
  struct Impl;
  explicit LodScene(std::unique_ptr<Impl> impl);
  static Expected<std::unique_ptr<LodScene>> make(SceneRenderer& renderer, lod::LodPolicy policy,
                                                  const LodOptions& options, LevelPrograms* programs);
  std::unique_ptr<Impl> impl_;
};

}  // namespace spire::engine
