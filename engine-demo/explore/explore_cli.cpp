#include "explore/explore_cli.h"

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include <ostream>

#include "demo/glfw_window.h"
#include "driver/tool_arguments.h"
#include "explore/explorer.h"
#include "tool/engine_options.h"
#include "tool/tool_run.h"

namespace spire::explore {
namespace {

constexpr const char* kTool = "spire-explore";

struct CliOptions {
  ExploreOptions explore;
  std::string reference;
  std::string decisions;
  std::string script;
  std::string log;
  std::string tuneDir;
  engine::EngineOptions engine;
};

void defineOptions(CLI::App& app, CliOptions& options) {
  addVersionFlag(app);
  app.add_option("scene", options.explore.scenePath, "Scene file (docs/scene.md)")->type_name("SCENE.json");
  app.add_option("--instance", options.explore.instance, "Explore the shader of instance N (default 0)")
      ->type_name("N");
  app.add_option("--reference", options.reference,
                 "Decision file of the reference the error is measured against (default: the scene's first "
                 "variant, else the instance's decisions)")
      ->type_name("PATH");
  app.add_option("--decisions", options.decisions, "Start from this decision file (default: the reference's)")
      ->type_name("PATH");
  app.add_option("--save-to", options.explore.saveTo,
                 "Where Save writes and Load reads (default explore.decisions; on a level-of-detail scene, where "
                 "Save writes the policy: default the scene's policy file)")
      ->type_name("PATH");
  app.add_option("--script", options.script,
                 "Run the actions of FILE instead of waiting for the user (docs/explorer.md, \"Scripts\")")
      ->type_name("FILE");
  app.add_option("--tune-dir", options.tuneDir,
                 "Show a spire-tune output directory of the same shader as a Pareto view whose points apply their "
                 "decisions")
      ->type_name("DIR");
  app.add_option("--log", options.log, "Write each change's timing to FILE as JSON")->type_name("FILE");
  app.add_option("--frames", options.explore.maxFrames, "Close the window after N frames")
      ->check(CLI::Range(uint64_t{1}, uint64_t{100000000}))
      ->type_name("N");
  engine::addEngineOptions(app, options.engine);
}

void resolvePaths(CliOptions& options) {
  if (!options.reference.empty()) options.explore.reference = options.reference;
  if (!options.decisions.empty()) options.explore.decisions = options.decisions;
  if (!options.script.empty()) options.explore.script = options.script;
  if (!options.log.empty()) options.explore.log = options.log;
  if (!options.tuneDir.empty()) options.explore.tuneDir = options.tuneDir;
}

}  // namespace

int runExploreTool(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  CLI::App app{
      "spire-explore: change a Spire shader's optimization decisions live and see the variant's image, "
      "cost and error at once",
      kTool};
  CliOptions options;
  defineOptions(app, options);
  if (const auto status = parseToolArguments(app, args, out, err)) return *status;
  if (options.explore.scenePath.empty()) return usageError(kTool, "a scene file is required", err);
  resolvePaths(options);

  // Declared before the run: the context makes its surface on the window
  // and must be destroyed first.
  std::optional<demo::GlfwWindow> window;
  engine::ToolRun run(kTool, err);
  if (const auto status = run.loadScene(options.explore.scenePath, options.engine.resolution)) return *status;
  if (run.scene().lod) {
    if (const auto status = run.loadLodPolicy()) return *status;
  }
  if (options.explore.saveTo.empty()) {
    options.explore.saveTo = run.scene().lod ? run.scene().lod->policy.string() : "explore.decisions";
  }
  auto opened = demo::GlfwWindow::open(run.scene().width, run.scene().height,
                                       fmt::format("spire-explore | {}", options.explore.scenePath));
  if (!opened) {
    err << fmt::format("{}: error: {}\n", kTool, opened.error());
    return kExitInputError;
  }
  window.emplace(std::move(opened).value());
  engine::DeviceOptions device{options.engine.device, options.engine.validation, window->vulkanInstanceExtensions(),
                               [&window](VkInstance instance) { return window->createSurface(instance); }};
  if (const auto status = run.openDevice(device)) return *status;
  run.startRenderer(options.engine.bakeSize);
  return runExplorer(options.explore, run, *window, out);
}

}  // namespace spire::explore
