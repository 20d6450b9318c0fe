// spire-explore's panels on a level-of-detail scene: the policy editor (one
// row per distance band: the group member that draws it and its far edge;
// hysteresis, cross-fade length, Save) and the fly-through with the frame's
// metrics. Drawing only: edits come back as requests for the loop.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "lod/lod_policy.h"

namespace spire::explore {

struct LodMetrics {
  double gpuMs = 0.0;              // the frame, averaged over the last few
  std::vector<uint32_t> perLevel;  // instances at each level of the drawn policy (all, not only the visible)
  size_t instances = 0;
  uint32_t visible = 0;
  uint32_t batches = 0;  // pipeline binds, cross-fade overlays included
  uint32_t overlayBatches = 0;
  uint32_t drawCalls = 0;
};

struct LodPanelState {
  const lod::LodPolicy* edited = nullptr;             // as edited, valid or not
  const lod::LodPolicy* drawn = nullptr;              // what draws: the last valid policy that compiled
  const std::vector<std::string>* members = nullptr;  // what every instance's group offers
  bool valid = true;
  bool canUndo = false;
  bool canRedo = false;
  bool compiling = false;  // new levels compile while the drawn policy's draw
  std::string savePath;
  float flyFrame = 0.0F;
  uint32_t flyFrames = 1;
  bool playing = false;
  const LodMetrics* metrics = nullptr;
  std::string status;  // the last save's or failed rebuild's message
};

struct LodPanelRequests {
  std::optional<lod::LodPolicy> policy;  // the edited policy after an edit in the panel
  bool dragging = false;                 // a value of the policy is held (dragged, typed) this frame
  bool undo = false;                     // the Undo button, or Ctrl+Z
  bool redo = false;                     // the Redo button, or Ctrl+Y / Ctrl+Shift+Z
  bool addLevel = false;
  std::optional<size_t> removeLevel;
  bool save = false;
  std::optional<float> flyFrame;
  bool togglePlay = false;
};

LodPanelRequests drawLodPanels(const LodPanelState& state);

}  // namespace spire::explore
