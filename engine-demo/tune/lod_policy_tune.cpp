#include "tune/lod_policy_tune.h"

#include <fmt/format.h>

#include "driver/exit_codes.h"
#include "driver/tool_arguments.h"
#include "support/file_io.h"
#include "tool/tool_run.h"
#include "tune/level_measurement.h"

namespace spire::tune {

namespace {

constexpr const char* kTool = "spire-tune";

}  // namespace

int runLodPolicyTune(const TuneOptions& options, std::ostream& out, std::ostream& err) {
  if (const auto problem = distancesProblem(options.policyChoice.distances)) return usageError(kTool, *problem, err);
  engine::ToolRun run(kTool, err);
  if (const auto status = run.loadScene(options.scenePath, options.resolution)) return *status;
  if (const auto status = run.loadLodPolicy()) return *status;
  if (const auto status = run.openDevice({options.device, options.validation, {}, {}})) return *status;
  run.startRenderer(options.bakeSize);
  const lod::LodPolicy& measured = run.lodPolicy();
  auto m = measureLevels(run.renderer(), measured, {options.policyChoice.distances, options.warmup, options.frames});
  if (!m) return run.fail(m.error());

  const lod::ChoiceRule rule = choiceRule(options.policyChoice);
  const ChosenPolicy chosen = choosePolicy(*m, measured, rule);
  const std::filesystem::path folder = std::filesystem::path(options.lodPolicyPath).parent_path();
  if (auto written = writeFileAtomically(options.lodPolicyPath, lod::formatLodPolicy(chosen.policy, folder));
      !written) {
    return run.fail(written.error().message);
  }
  out << fmt::format(
      "level-of-detail policy for '{}': {} levels, {} materials, {} distances (frame times: median "
      "of {})\n",
      options.scenePath, measured.levels.size(), m->materials, m->levels.distances.size(), options.frames);
  out << levelTable(*m, measured, chosen, rule);
  out << fmt::format("wrote {}\n", options.lodPolicyPath);
  return run.finish(kExitSuccess);
}

}  // namespace spire::tune
