// The explorer's Pareto view: the tuned variants of a spire-tune output
// directory as a scatter plot (frame time against RMSE) drawn with ImGui's
// draw list, the front joined and highlighted, the session's own variant
// ringed when the run measured it. Hovering a point shows its decisions;
// clicking it asks for them as one change.
#pragma once

#include "explore/explorer_model.h"

namespace spire::explore {

// Draws the "Pareto" window when `state` has tuning results.
void drawParetoPanel(const PanelState& state, PanelRequests& requests);

}  // namespace spire::explore
