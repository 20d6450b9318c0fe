// The explorer's Dear ImGui panels: choices, metrics with the last change's
// timing, view modes, diagnostics and the Pareto view. Drawing only: what the user clicks
// comes back as requests for the loop to carry out.
#pragma once

#include <string>

#include "explore/explorer_model.h"

namespace spire::explore {

// Draws the panels of `state` into the current ImGui frame.
PanelRequests drawPanels(const PanelState& state);
// The top right panel of messages (compiler diagnostics, a bad edit's),
// shown only when there are some.
void drawDiagnosticsPanel(const std::string& diagnostics);

}  // namespace spire::explore
