#include "explore/lod_panel.h"

#include <imgui.h>

#include <algorithm>

namespace spire::explore {
namespace {

constexpr ImGuiWindowFlags kPanelFlags = ImGuiWindowFlags_AlwaysAutoResize;
constexpr float kPanelAlpha = 0.85F;
constexpr float kMargin = 8.0F;
const ImVec4 kErrorColor{1.0F, 0.45F, 0.4F, 1.0F};

// The member combo offers what the groups offer; a name typed into a script
// that is none of them still shows, so the row says what the policy holds.
bool drawMember(lod::LodLevel& level, const std::vector<std::string>& members) {
  bool changed = false;
  ImGui::SetNextItemWidth(ImGui::GetFontSize() * 8.0F);
  if (ImGui::BeginCombo("member", level.member.c_str())) {
    for (const std::string& member : members) {
      const bool selected = member == level.member;
      if (ImGui::Selectable(member.c_str(), selected) && !selected) {
        level.member = member;
        changed = true;
      }
    }
    ImGui::EndCombo();
  }
  return changed;
}

// One row per band, nearest first. Edges are dragged without bounds: an
// edge dragged past its neighbour's is the policy reader's error to show.
void drawBands(const LodPanelState& state, lod::LodPolicy& policy, LodPanelRequests& requests, bool& changed) {
  for (size_t i = 0; i < policy.levels.size(); ++i) {
    lod::LodLevel& level = policy.levels[i];
    ImGui::PushID(static_cast<int>(i));
    ImGui::Text("level %zu", i);
    ImGui::SameLine();
    changed = drawMember(level, *state.members) || changed;
    ImGui::SameLine();
    ImGui::SetNextItemWidth(ImGui::GetFontSize() * 6.0F);
    if (i + 1 < policy.levels.size()) {
      changed = ImGui::DragFloat("until", &level.until, 0.1F, 0.0F, 0.0F, "%.2f") || changed;
      requests.dragging = requests.dragging || ImGui::IsItemActive();
    } else {
      ImGui::TextDisabled("and beyond");
    }
    ImGui::SameLine();
    ImGui::BeginDisabled(policy.levels.size() == 1);
    if (ImGui::SmallButton("remove")) requests.removeLevel = i;
    ImGui::EndDisabled();
    ImGui::PopID();
  }
}

// Undo and Redo, as buttons and as the keys, which are the panel's only
// while no ImGui widget reads the keyboard (a typed frame count has its own
// Ctrl+Z).
void drawUndo(const LodPanelState& state, LodPanelRequests& requests) {
  const ImGuiIO& io = ImGui::GetIO();
  const bool keys = !io.WantCaptureKeyboard && io.KeyCtrl;
  const bool keyZ = keys && ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Z), false);
  const bool keyY = keys && ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Y), false);
  ImGui::BeginDisabled(!state.canUndo);
  requests.undo = ImGui::Button("Undo") || (state.canUndo && keyZ && !io.KeyShift);
  ImGui::EndDisabled();
  ImGui::SameLine();
  ImGui::BeginDisabled(!state.canRedo);
  requests.redo = ImGui::Button("Redo") || (state.canRedo && (keyY || (keyZ && io.KeyShift)));
  ImGui::EndDisabled();
  if (state.compiling) {
    ImGui::SameLine();
    ImGui::TextDisabled("compiling new levels; the previous ones draw meanwhile");
  }
}

void drawPolicy(const LodPanelState& state, LodPanelRequests& requests) {
  ImGui::SetNextWindowPos(ImVec2(kMargin, kMargin), ImGuiCond_Always);
  ImGui::SetNextWindowBgAlpha(kPanelAlpha);
  ImGui::Begin("LOD policy", nullptr, kPanelFlags);
  lod::LodPolicy policy = *state.edited;
  bool changed = false;
  drawBands(state, policy, requests, changed);
  requests.addLevel = ImGui::Button("Add band");
  ImGui::SetNextItemWidth(ImGui::GetFontSize() * 6.0F);
  changed = ImGui::DragFloat("hysteresis", &policy.hysteresis, 0.005F, 0.0F, 0.0F, "%.3f") || changed;
  requests.dragging = requests.dragging || ImGui::IsItemActive();
  int frames = static_cast<int>(std::min<uint32_t>(policy.transitionFrames, 1000000));
  ImGui::SetNextItemWidth(ImGui::GetFontSize() * 6.0F);
  if (ImGui::InputInt("transition frames", &frames)) {
    policy.transitionFrames = static_cast<uint32_t>(std::max(frames, 0));
    changed = true;
  }
  requests.dragging = requests.dragging || ImGui::IsItemActive();
  drawUndo(state, requests);
  if (!state.valid) ImGui::TextColored(kErrorColor, "not valid (see Diagnostics): the last valid policy draws");
  requests.save = ImGui::Button("Save");
  ImGui::SameLine();
  ImGui::TextDisabled("file: %s", state.savePath.c_str());
  if (!state.status.empty()) ImGui::TextUnformatted(state.status.c_str());
  if (changed) requests.policy = std::move(policy);
  ImGui::End();
}

void drawFlyThrough(const LodPanelState& state, LodPanelRequests& requests) {
  ImGui::SetNextWindowPos(ImVec2(kMargin, ImGui::GetIO().DisplaySize.y - kMargin), ImGuiCond_Always,
                          ImVec2(0.0F, 1.0F));
  ImGui::SetNextWindowBgAlpha(kPanelAlpha);
  ImGui::Begin("Fly-through", nullptr, kPanelFlags);
  float frame = state.flyFrame;
  ImGui::SetNextItemWidth(ImGui::GetFontSize() * 12.0F);
  if (ImGui::SliderFloat("frame", &frame, 0.0F, static_cast<float>(state.flyFrames), "%.1f")) {
    requests.flyFrame = frame;
  }
  ImGui::SameLine();
  requests.togglePlay = ImGui::Button(state.playing ? "Pause" : "Play");
  const LodMetrics& m = *state.metrics;
  ImGui::Text("frame %.2f ms GPU; %u of %zu instances visible", m.gpuMs, m.visible, m.instances);
  ImGui::Text("%u batches (%u cross-fades), %u draw calls", m.batches, m.overlayBatches, m.drawCalls);
  for (size_t i = 0; i < m.perLevel.size() && i < state.drawn->levels.size(); ++i) {
    ImGui::Text("level %zu (%s): %u instances", i, state.drawn->levels[i].member.c_str(), m.perLevel[i]);
  }
  ImGui::End();
}

}  // namespace

LodPanelRequests drawLodPanels(const LodPanelState& state) {
  LodPanelRequests requests;
  drawPolicy(state, requests);
  drawFlyThrough(state, requests);
  return requests;
}

}  // namespace spire::explore
