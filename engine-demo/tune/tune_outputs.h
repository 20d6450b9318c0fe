// What a tuning run writes once every point is measured: the Pareto front
// (pareto.csv, plot.png), the best variant under each budget as a decision
// file with its data-layout selection, report.md with the front's images,
// report.html (tune/report_html.h) from the same results, and the summary on
// stdout.
#pragma once

#include <ostream>
#include <vector>

#include "tool/tool_run.h"
#include "tune/results_csv.h"
#include "tune/tune_options.h"
#include "tune/tune_session.h"
#include "tune/tuner.h"
#include "vk/timer.h"

namespace spire::tune {

// `results` is one row per point of the run in index order; `split` the
// workers' time summed; `wall` timed the whole run. Returns the exit status.
int writeTuneOutputs(const TuneOptions& options, engine::ToolRun& run, TuneSession& session,
                     const std::vector<VariantResult>& results, const TimeSplit& split, const vk::HostTimer& wall,
                     std::ostream& out, std::ostream& err);

}  // namespace spire::tune
