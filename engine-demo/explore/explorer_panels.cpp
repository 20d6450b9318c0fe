#include "explore/explorer_panels.h"

#include <fmt/format.h>
#include <imgui.h>

#include <array>

#include "explore/pareto_panel.h"

namespace spire::explore {
namespace {

const ImVec4 kImpossible{0.55F, 0.55F, 0.55F, 1.0F};
const ImVec4 kDecided{0.55F, 0.85F, 1.0F, 1.0F};
const ImVec4 kErrorColor{1.0F, 0.45F, 0.4F, 1.0F};

// One combo per choice; impossible alternatives are shown greyed out and
// cannot be picked. "(default)" drops the decision.
void drawChoice(const ChoiceRow& row, PanelRequests& requests) {
  const std::string current = row.decided ? *row.decided : "(default)";
  if (row.decided) ImGui::PushStyleColor(ImGuiCol_Text, kDecided);
  const bool open = ImGui::BeginCombo(row.key.c_str(), current.c_str());
  if (row.decided) ImGui::PopStyleColor();
  if (!open) return;
  if (ImGui::Selectable("(default)", !row.decided) && row.decided) requests.unset = row.key;
  for (const Alternative& alt : row.alternatives) {
    const ImGuiSelectableFlags flags = alt.possible ? 0 : ImGuiSelectableFlags_Disabled;
    const std::string label = alt.possible ? alt.placement : alt.placement + "  (impossible)";
    const bool selected = row.decided && *row.decided == alt.placement;
    if (ImGui::Selectable(label.c_str(), selected, flags) && !selected) requests.set.emplace(row.key, alt.placement);
  }
  ImGui::EndCombo();
}

// The scene's instances; picking one explores its shader instead, with the
// decisions it had. Disabled while a change compiles, which belongs to the
// instance explored now.
void drawInstances(const PanelState& state, PanelRequests& requests) {
  ImGui::BeginDisabled(state.compiling);
  ImGui::PushItemWidth(ImGui::GetFontSize() * 16.0F);
  if (ImGui::BeginCombo("instance", state.instances.at(state.instance).c_str())) {
    for (size_t i = 0; i < state.instances.size(); ++i) {
      const bool selected = i == state.instance;
      if (ImGui::Selectable(state.instances[i].c_str(), selected) && !selected) requests.instance = i;
    }
    ImGui::EndCombo();
  }
  ImGui::PopItemWidth();
  ImGui::EndDisabled();
}

constexpr ImGuiWindowFlags kPanelFlags = ImGuiWindowFlags_AlwaysAutoResize;
constexpr float kPanelAlpha = 0.85F;
constexpr float kMargin = 8.0F;

// Panels sit in fixed corners, sized to their contents, so they never cover
// each other whatever the frame's resolution: choices top left, metrics
// bottom left, diagnostics top right.
void drawChoices(const PanelState& state, PanelRequests& requests) {
  ImGui::SetNextWindowPos(ImVec2(kMargin, kMargin), ImGuiCond_Always);
  ImGui::SetNextWindowBgAlpha(kPanelAlpha);
  ImGui::Begin("Choices", nullptr, kPanelFlags);
  drawInstances(state, requests);
  ImGui::Text("%s: %zu choices", state.shader.c_str(), state.rows.size());
  requests.undo = ImGui::Button("Undo");
  ImGui::SameLine();
  requests.reset = ImGui::Button("Reset");
  ImGui::SameLine();
  requests.save = ImGui::Button("Save");
  ImGui::SameLine();
  requests.load = ImGui::Button("Load");
  ImGui::TextDisabled("file: %s", state.decisionsPath.c_str());
  ImGui::Separator();
  ImGui::PushItemWidth(ImGui::GetFontSize() * 12.0F);
  for (const ChoiceRow& row : state.rows) drawChoice(row, requests);
  ImGui::PopItemWidth();
  ImGui::End();
}

void drawChange(const ChangeRecord& change) {
  ImGui::Text("last change: %s", change.action.c_str());
  if (!change.ok) {
    ImGui::TextColored(kErrorColor, "failed (see Diagnostics)");
    return;
  }
  ImGui::Text("decision to image %.0f ms", change.totalMs);
  ImGui::Text("  compile %.0f, prepare %.0f (bakes %.0f), first frame %.0f ms", change.compileMs, change.prepareMs,
              change.bakeMs, change.firstFrameMs);
  ImGui::Text("  pipelines: %zu built, %zu reused", change.pipelinesCreated, change.pipelinesReused);
  if (!change.skipped.empty()) ImGui::TextColored(kErrorColor, "%zu decisions not applied", change.skipped.size());
}

void drawMetrics(const PanelState& state, PanelRequests& requests) {
  ImGui::SetNextWindowPos(ImVec2(kMargin, ImGui::GetIO().DisplaySize.y - kMargin), ImGuiCond_Always,
                          ImVec2(0.0F, 1.0F));
  ImGui::SetNextWindowBgAlpha(kPanelAlpha);
  ImGui::Begin("Metrics", nullptr, kPanelFlags);
  const Metrics& m = *state.metrics;
  if (m.gpuMs.empty()) {
    ImGui::Text("frame: shown in the variant view; reference %.2f ms GPU", m.referenceGpuMs);
  } else {
    ImGui::Text("frame %.2f ms GPU (median of %zu), reference %.2f ms", m.medianGpuMs(), m.gpuMs.size(),
                m.referenceGpuMs);
  }
  if (m.error) {
    ImGui::Text("error: RMSE %.5f, PSNR %.1f dB, max %.3f", m.error->rmse, m.error->psnr, m.error->maxError);
  }
  if (m.nonFinitePixels > 0)
    ImGui::TextColored(kErrorColor, "%llu NaN/Inf pixels", static_cast<unsigned long long>(m.nonFinitePixels));
  if (state.compiling) ImGui::TextColored(kDecided, "compiling...");
  if (state.lastChange) drawChange(*state.lastChange);
  static constexpr std::array<ViewMode, 5> kModes{ViewMode::Variant, ViewMode::Reference, ViewMode::Error,
                                                  ViewMode::Hazards, ViewMode::Split};
  for (ViewMode mode : kModes) {
    if (mode != kModes.front()) ImGui::SameLine();
    if (ImGui::RadioButton(viewModeName(mode), state.view == mode)) requests.view = mode;
  }
  ImGui::End();
}

}  // namespace

PanelRequests drawPanels(const PanelState& state) {
  PanelRequests requests;
  drawChoices(state, requests);
  drawMetrics(state, requests);
  drawDiagnosticsPanel(state.diagnostics);
  drawParetoPanel(state, requests);
  return requests;
}

void drawDiagnosticsPanel(const std::string& diagnostics) {
  if (diagnostics.empty()) return;
  const ImVec2 size = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos(ImVec2(size.x - kMargin, kMargin), ImGuiCond_Always, ImVec2(1.0F, 0.0F));
  ImGui::SetNextWindowSize(ImVec2(size.x * 0.6F, size.y * 0.45F), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowBgAlpha(kPanelAlpha);
  ImGui::Begin("Diagnostics", nullptr, ImGuiWindowFlags_HorizontalScrollbar);
  ImGui::PushStyleColor(ImGuiCol_Text, kErrorColor);
  ImGui::TextUnformatted(diagnostics.c_str());
  ImGui::PopStyleColor();
  ImGui::End();
}

}  // namespace spire::explore
