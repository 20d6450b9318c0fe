#include "explore/pareto_panel.h"

#include <fmt/format.h>
#include <imgui.h>

#include <algorithm>

#include "explore/pareto_plot.h"

namespace spire::explore {
namespace {

const ImU32 kAxisColor = IM_COL32(200, 200, 200, 255);
const ImU32 kGridColor = IM_COL32(200, 200, 200, 40);
const ImU32 kVariantColor = IM_COL32(150, 150, 160, 200);
const ImU32 kFrontColor = IM_COL32(255, 120, 60, 255);
const ImU32 kCurrentColor = IM_COL32(90, 220, 255, 255);
constexpr float kPointRadius = 3.0F;
constexpr float kFrontRadius = 4.5F;
constexpr float kCurrentRadius = 8.0F;
constexpr float kHitRadius = 7.0F;  // pixels around a point that hover and click it
constexpr float kTick = 4.0F;
constexpr float kMargin = 8.0F;
constexpr float kPanelAlpha = 0.85F;

// The plot's rectangle inside the widget, leaving room for the tick labels.
struct PlotFrame {
  ImVec2 topLeft;
  float width = 0.0F;
  float height = 0.0F;
  ImVec2 bottomRight() const { return {topLeft.x + width, topLeft.y + height}; }
};

std::string tickLabel(double value) { return fmt::format("{:.3g}", value); }

void drawAxes(ImDrawList& draw, const ParetoPlot& plot, const PlotFrame& frame) {
  const ImVec2 end = frame.bottomRight();
  const float lineHeight = ImGui::GetTextLineHeight();
  for (double t : plot.time.ticks) {
    const float x = frame.topLeft.x + static_cast<float>(plot.time.fraction(t)) * frame.width;
    draw.AddLine({x, frame.topLeft.y}, {x, end.y}, kGridColor);
    draw.AddLine({x, end.y}, {x, end.y + kTick}, kAxisColor);
    const std::string label = tickLabel(t);
    const float w = ImGui::CalcTextSize(label.c_str()).x;
    draw.AddText({x - w / 2.0F, end.y + kTick}, kAxisColor, label.c_str());
  }
  for (double t : plot.error.ticks) {
    const float y = frame.topLeft.y + static_cast<float>(1.0 - plot.error.fraction(t)) * frame.height;
    draw.AddLine({frame.topLeft.x, y}, {end.x, y}, kGridColor);
    draw.AddLine({frame.topLeft.x - kTick, y}, {frame.topLeft.x, y}, kAxisColor);
    const std::string label = tickLabel(t);
    const float w = ImGui::CalcTextSize(label.c_str()).x;
    draw.AddText({frame.topLeft.x - kTick - w - 2.0F, y - lineHeight / 2.0F}, kAxisColor, label.c_str());
  }
  draw.AddLine({frame.topLeft.x, end.y}, end, kAxisColor);
  draw.AddLine(frame.topLeft, {frame.topLeft.x, end.y}, kAxisColor);
  const char* xTitle = "frame time (ms)";
  draw.AddText({end.x - ImGui::CalcTextSize(xTitle).x, end.y + kTick + lineHeight}, kAxisColor, xTitle);
  draw.AddText({frame.topLeft.x - ImGui::CalcTextSize("RMSE").x / 2.0F, frame.topLeft.y - lineHeight - kTick},
               kAxisColor, "RMSE");
}

void drawPoints(ImDrawList& draw, const PanelState& state, const std::vector<PlotPoint>& points) {
  const TuneResults& tune = *state.tune;
  for (size_t k = 1; k < tune.front.size(); ++k) {
    const PlotPoint a = points[tune.front[k - 1]];
    const PlotPoint b = points[tune.front[k]];
    draw.AddLine({a.x, a.y}, {b.x, b.y}, kFrontColor, 1.5F);
  }
  for (size_t i = 0; i < points.size(); ++i) {
    if (!tune.variants[i].onFront) draw.AddCircleFilled({points[i].x, points[i].y}, kPointRadius, kVariantColor);
  }
  for (size_t i : tune.front) draw.AddCircleFilled({points[i].x, points[i].y}, kFrontRadius, kFrontColor);
  if (state.tunedCurrent) {
    const PlotPoint p = points[*state.tunedCurrent];
    draw.AddCircle({p.x, p.y}, kCurrentRadius, kCurrentColor, 0, 2.0F);
  }
}

void drawTooltip(const TuneResults& tune, size_t i, bool current) {
  const TunedVariant& v = tune.variants[i];
  ImGui::BeginTooltip();
  const auto front = std::find(tune.front.begin(), tune.front.end(), i);
  if (front != tune.front.end()) {
    ImGui::Text("variant %llu, front point %zu", static_cast<unsigned long long>(v.index),
                static_cast<size_t>(front - tune.front.begin()));
  } else {
    ImGui::Text("variant %llu", static_cast<unsigned long long>(v.index));
  }
  for (const auto& [component, placement] : v.decisions) ImGui::Text("  %s = %s", component.c_str(), placement.c_str());
  ImGui::Text("frame %.3f ms, RMSE %.4g", v.frameMs, v.rmse);
  ImGui::TextDisabled("%s", current ? "the session's variant" : "click to apply its decisions");
  ImGui::EndTooltip();
}

}  // namespace

void drawParetoPanel(const PanelState& state, PanelRequests& requests) {
  if (state.tune == nullptr) return;
  const TuneResults& tune = *state.tune;
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  // Top right, clear of the choices and the metrics on the left; below the
  // diagnostics' corner while there are some.
  const bool low = !state.diagnostics.empty();
  ImGui::SetNextWindowPos(ImVec2(display.x - kMargin, low ? display.y - kMargin : kMargin), ImGuiCond_Always,
                          ImVec2(1.0F, low ? 1.0F : 0.0F));
  ImGui::SetNextWindowBgAlpha(kPanelAlpha);
  ImGui::Begin("Pareto", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
  ImGui::Text("%s: %zu variants, %zu on the front", tune.dir.filename().string().c_str(), tune.variants.size(),
              tune.front.size());
  // Labels need room left of the plot (about six characters), below it (two
  // lines) and above it (the y axis' title).
  const float lineHeight = ImGui::GetTextLineHeight();
  const float labelWidth = ImGui::CalcTextSize("0.0000").x + kTick + 4.0F;
  const float width = std::clamp(display.x * 0.3F, 160.0F, 420.0F);
  const float height = width * 0.6F;
  const ImVec2 widget{width + labelWidth + kMargin, height + 3.0F * lineHeight + 2.0F * kTick};
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  ImGui::InvisibleButton("plot", widget);
  const PlotFrame frame{{origin.x + labelWidth, origin.y + lineHeight + kTick}, width, height};
  const ParetoPlot plot = planPlot(tune.variants);
  const std::vector<PlotPoint> points =
      placePoints(plot, tune.variants, {frame.topLeft.x, frame.topLeft.y}, frame.width, frame.height);
  ImDrawList& draw = *ImGui::GetWindowDrawList();
  drawAxes(draw, plot, frame);
  drawPoints(draw, state, points);
  if (ImGui::IsItemHovered()) {
    const ImVec2 mouse = ImGui::GetMousePos();
    if (const std::optional<size_t> hit = pointUnder(points, {mouse.x, mouse.y}, kHitRadius)) {
      drawTooltip(tune, *hit, state.tunedCurrent == hit);
      if (ImGui::IsItemClicked() && state.tunedCurrent != hit) requests.applyTunePoint = *hit;
    }
  }
  ImGui::End();
}

}  // namespace spire::explore
