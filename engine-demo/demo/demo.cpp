#include "demo/demo.h"

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <filesystem>
#include <optional>
#include <ostream>

#include "demo/glfw_window.h"
#include "demo/lod_demo.h"
#include "demo/window.h"
#include "driver/tool_arguments.h"
#include "measure/comparison_image.h"
#include "measure/image_metrics.h"
#include "measure/report_table.h"
#include "renderer/scene_renderer.h"
#include "renderer/view_error.h"
#include "scene/texture.h"
#include "support/atomic_directory.h"
#include "support/file_io.h"
#include "tool/engine_options.h"
#include "tool/hazard_diagnosis.h"
#include "tool/tool_run.h"
#include "vk/context.h"

namespace spire::demo {

namespace {

namespace fs = std::filesystem;

constexpr const char* kTool = "spire-demo";

struct Options {
  std::string scenePath;
  std::vector<std::string> variants;
  std::string outputDir = "out/demo";
  std::optional<uint32_t> frames;
  std::optional<uint32_t> warmup;
  engine::EngineOptions engine;
  bool listDevices = false;
  bool window = false;
  bool keepAlpha = false;
};

struct VariantRun {
  std::string name;
  std::optional<fs::path> decisions;
};

struct VariantResult {
  std::string name;
  std::optional<fs::path> decisions;
  engine::FrameStats stats;
  std::vector<engine::BakeRecord> bakes;
  std::vector<engine::Capture> views;
  scene::Image image;  // view 0, 8 bits
  // With NaN or Inf pixels: the first view that has them, and what the
  // instrumented variant found there (or why it could not say).
  std::optional<size_t> hazardView;
  std::vector<std::string> hazards;
};

// A variant that could not be compiled or prepared, and why.
struct FailedVariant {
  std::string name;
  std::string decisions;  // the decision file, or "" for the scene as it is
  std::string reason;
};

// The frames of one run: the warm-up first, then the measured ones.
struct FramePlan {
  uint32_t warmup = 1;
  uint32_t measured = 1;
};

double prebakeMs(const std::vector<engine::BakeRecord>& bakes) {
  double total = 0.0;
  for (const engine::BakeRecord& bake : bakes) total += bake.reused ? 0.0 : bake.milliseconds;
  return total;
}

std::string bakeSummary(const std::vector<engine::BakeRecord>& bakes) {
  if (bakes.empty()) return "none";
  std::string text;
  for (const engine::BakeRecord& bake : bakes) {
    text += fmt::format("{}{} {:.1f} ms{}", text.empty() ? "" : ", ", bake.world, bake.milliseconds,
                        bake.reused ? " (reused)" : "");
  }
  return text;
}

void defineOptions(CLI::App& app, Options& options) {
  addVersionFlag(app);
  app.add_option("scene", options.scenePath, "Scene file (docs/scene.md)")->type_name("SCENE.json");
  app.add_option("--variant", options.variants,
                 "Render with decision file PATH applied to every instance (repeatable; replaces the scene's "
                 "\"variants\"; the first is the reference)")
      ->type_name("PATH");
  addOutputDirectory(app, options.outputDir, "Write PNGs, comparison.png and report.md to DIR");
  app.add_option("--frames", options.frames,
                 "Measured frames per variant (default: the scene's); with --window, close it after N frames")
      ->check(CLI::Range(1U, 1000000U))
      ->type_name("N");
  app.add_option("--warmup", options.warmup, "Unmeasured frames first (default: the scene's; at least 1)")
      ->type_name("N");
  engine::addEngineOptions(app, options.engine);
  app.add_flag("--keep-alpha", options.keepAlpha,
               "Write variant images with the alpha the shader wrote (default: opaque, as image viewers expect)");
  app.add_flag("--list-devices", options.listDevices, "List the Vulkan devices and exit");
  app.add_flag("--window", options.window,
               "Show the variants in a window instead of measuring them (needs a display): keys 1-9 switch "
               "variants, dragging orbits the camera, Space pauses it, Escape quits");
}

int listDevices(const Options& options, std::ostream& out, std::ostream& err) {
  engine::ToolRun run(kTool, err);
  if (const auto status = run.openDevice({options.engine.device, false, {}, {}})) return *status;
  const vk::Context& ctx = run.context();
  for (const vk::PhysicalDeviceInfo& device : ctx.physicalDevices()) {
    out << fmt::format("{} {} ({}){}\n", &device == &ctx.selectedDevice() ? "*" : " ", device.name,
                       vk::deviceTypeName(device.type), &device == &ctx.selectedDevice() ? "  [selected]" : "");
  }
  return kExitSuccess;
}

// The --variant files, else the scene's variants, else the scene as it is.
std::vector<VariantRun> variantRuns(const Options& options, const scene::SceneFile& scene) {
  std::vector<VariantRun> runs;
  for (const std::string& path : options.variants) runs.push_back({fs::path(path).stem().string(), fs::path(path)});
  if (runs.empty()) {
    for (const scene::VariantDesc& variant : scene.variants) runs.push_back({variant.name, variant.decisions});
  }
  if (runs.empty()) runs.push_back({"scene", std::nullopt});
  return runs;
}

// Opens the device, and with --window first the window whose surface the
// context presents to; prints the device.
std::optional<int> openDevice(const Options& options, engine::ToolRun& run, std::optional<GlfwWindow>& window,
                              std::ostream& out, std::ostream& err) {
  engine::DeviceOptions device{options.engine.device, options.engine.validation, {}, {}};
  if (options.window) {
    auto opened =
        GlfwWindow::open(run.scene().width, run.scene().height, fmt::format("spire-demo | {}", options.scenePath));
    if (!opened) {
      err << fmt::format("spire-demo: error: {}\n", opened.error());
      return kExitInputError;
    }
    window.emplace(std::move(opened).value());
    device.instanceExtensions = window->vulkanInstanceExtensions();
    device.surfaceFactory = [&window](VkInstance instance) { return window->createSurface(instance); };
  }
  if (const auto status = run.openDevice(device)) return status;
  const vk::PhysicalDeviceInfo& selected = run.context().selectedDevice();
  out << fmt::format("device: {} ({})\n", selected.name, vk::deviceTypeName(selected.type));
  return std::nullopt;
}

// Reports why `variant` failed, naming it and its decision file, and keeps
// the reason for report.md.
void reportFailure(engine::ToolRun& run, const VariantRun& variant, const engine::Error& error,
                   std::vector<FailedVariant>& failed) {
  const std::string decisions = variant.decisions ? variant.decisions->string() : std::string();
  engine::Error named = error;
  // The scene as it is needs no name: its errors are the scene's.
  if (variant.decisions)
    named.message = fmt::format("variant '{}' ({}) failed: {}", variant.name, decisions, error.message);
  run.fail(named);
  failed.push_back({variant.name, decisions, error.message});
}

// Compiles and prepares (bakes) every variant before any is measured. A
// variant that fails is reported and left out; the others go on. Fails when
// none is left.
std::optional<int> prepareVariants(engine::ToolRun& run, const std::vector<VariantRun>& runs,
                                   std::vector<engine::PreparedScene>& prepared, std::vector<VariantResult>& results,
                                   std::vector<FailedVariant>& failed, std::ostream& err) {
  engine::SceneRenderer& renderer = run.renderer();
  for (const VariantRun& variant : runs) {
    auto programs = renderer.compile(variant.decisions);
    if (!programs) {
      reportFailure(run, variant, programs.error(), failed);
      continue;
    }
    err << renderer.compilerWarnings();
    auto scenePrepared = renderer.prepare(*programs);
    run.reporter().flush();
    if (!scenePrepared) {
      reportFailure(run, variant, scenePrepared.error(), failed);
      continue;
    }
    results.push_back({variant.name, variant.decisions, {}, scenePrepared->bakes, {}, {}, {}, {}});
    prepared.push_back(std::move(scenePrepared).value());
  }
  renderer.reportUnreadBindings();
  run.reporter().flush();
  if (results.empty()) {
    return runs.size() == 1 ? kExitInputError
                            : run.fail(fmt::format("nothing was rendered: all {} variants failed", runs.size()));
  }
  return std::nullopt;
}

// Every variant is compiled, baked and warmed up before any is timed, and
// the measured frames then alternate between variants, so that no variant
// is timed under different conditions (a cold renderer, load-time work)
// than the others and the ratios come from one interleaved run.
std::optional<int> measureFrames(engine::ToolRun& run, const std::vector<engine::PreparedScene>& prepared,
                                 const FramePlan& plan, std::vector<VariantResult>& results) {
  std::vector<std::vector<engine::FrameTiming>> timings(prepared.size());
  for (uint32_t f = 0; f < plan.warmup + plan.measured; ++f) {
    for (size_t v = 0; v < prepared.size(); ++v) {
      auto timing = run.renderer().renderFrame(prepared[v], f);
      if (!timing) return run.fail(timing.error());
      if (f == 0) results[v].stats.firstFrameMs = timing->hostMs;
      if (f >= plan.warmup) timings[v].push_back(*timing);
    }
  }
  for (size_t v = 0; v < prepared.size(); ++v) {
    results[v].stats = engine::summarizeFrames(results[v].stats.firstFrameMs, timings[v]);
  }
  return std::nullopt;
}

// Renders every camera view of every variant and prints its timings.
std::optional<int> captureViews(const Options& options, engine::ToolRun& run,
                                const std::vector<engine::PreparedScene>& prepared, const FramePlan& plan,
                                std::vector<VariantResult>& results, std::ostream& out) {
  for (size_t v = 0; v < prepared.size(); ++v) {
    VariantResult& result = results[v];
    for (const scene::CameraView& view : run.scene().camera.views) {
      auto capture = run.renderer().capture(prepared[v], view);
      if (!capture) return run.fail(capture.error());
      result.views.push_back(std::move(capture).value());
    }
    result.image = measure::toRgba8(result.views.front().color);
    if (!options.keepAlpha) result.image = measure::opaque(std::move(result.image));
    out << fmt::format("{}: {:.3f} ms/frame (median of {}), first frame {:.1f} ms, bakes: {}\n", result.name,
                       result.stats.medianGpuMs, plan.measured, result.stats.firstFrameMs, bakeSummary(result.bakes));
  }
  return std::nullopt;
}

// One row per variant: its times, and its error against the first variant
// over every view; warns about variants with NaN or Inf pixels.
std::optional<int> reportRows(engine::ToolRun& run, const std::vector<VariantResult>& results,
                              std::vector<measure::ReportRow>& rows, std::ostream& err) {
  for (const VariantResult& result : results) {
    const auto viewsError = engine::viewsError(results.front().views, result.views);
    if (!viewsError) return run.fail(viewsError.error());
    const measure::ImageError& error = *viewsError;
    measure::ReportRow row;
    row.variant = result.name;
    row.frameMs = result.stats.medianGpuMs;
    row.firstUseMs = result.stats.firstFrameMs;
    row.prebakeMs = prebakeMs(result.bakes);
    row.speedup = results.front().stats.medianGpuMs / std::max(result.stats.medianGpuMs, 1e-9);
    row.rmse = error.rmse;
    row.psnr = error.psnr;
    row.maxError = error.maxError;
    row.nanPixels = error.nanPixels + error.infPixels;
    engine::Coverage coverage;
    for (size_t v = 0; v < result.views.size(); ++v) coverage.add(results.front().views[v], result.views[v]);
    row.degenerate = coverage.degenerate();
    rows.push_back(row);
    if (error.nanPixels + error.infPixels > 0) {
      err << fmt::format("spire-demo: warning: variant '{}' produced {} NaN and {} Inf pixels; its error is infinite\n",
                         result.name, error.nanPixels, error.infPixels);
    }
    if (row.degenerate) {
      err << fmt::format(
          "spire-demo: warning: variant '{}' covers {:.0f}% of the pixels '{}' covers: its image is degenerate (a "
          "collapsed or missing surface), so its time is no speedup\n",
          result.name, 100.0 * coverage.ratio(), results.front().name);
    }
  }
  return std::nullopt;
}

std::optional<size_t> firstHazardousView(const std::vector<engine::Capture>& views) {
  for (size_t v = 0; v < views.size(); ++v) {
    if (measure::nonFinitePixels(views[v].color) > 0) return v;
  }
  return std::nullopt;
}

// Finds, for each variant with NaN or Inf pixels, the component that went
// non-finite first, with its instrumented kernels (tool/hazard_diagnosis.h).
void diagnoseVariants(engine::ToolRun& run, std::vector<VariantResult>& results, std::ostream& err) {
  for (VariantResult& result : results) {
    result.hazardView = firstHazardousView(result.views);
    if (!result.hazardView) continue;
    const engine::HazardSample sample{&run.scene().camera.views[*result.hazardView], {}};
    const auto compile = [&](engine::SceneRenderer& renderer) { return renderer.compile(result.decisions); };
    auto hazards = engine::diagnoseHazards(run.renderer(), compile, sample);
    if (!hazards) {
      result.hazards.push_back(fmt::format("(no diagnosis: {})", hazards.error().message));
    } else {
      result.hazards = engine::hazardLines(*hazards);
    }
    for (const std::string& line : result.hazards) {
      err << fmt::format("spire-demo: hazard: variant '{}', camera view {}: {}\n", result.name, *result.hazardView,
                         line);
    }
  }
}

// <variant>.png and comparison.png, captioned with speedup and RMSE.
std::optional<int> encodeImages(engine::ToolRun& run, const std::vector<VariantResult>& results,
                                const std::vector<measure::ReportRow>& rows, FileSet& files) {
  std::vector<measure::Panel> panels;
  for (size_t i = 0; i < results.size(); ++i) {
    auto png = scene::encodePng(results[i].image);
    if (!png) return run.fail(fmt::format("variant '{}': {}", results[i].name, png.error().message));
    files.emplace_back(results[i].name + ".png", std::move(png).value());
    const std::string speed = rows[i].degenerate ? "DEGENERATE" : fmt::format("{:.2f}X", rows[i].speedup);
    panels.push_back({results[i].image, fmt::format("{} {} RMSE {:.4f}", results[i].name, speed, rows[i].rmse)});
  }
  auto comparison = measure::makeComparisonImage(panels);
  if (!comparison) return run.fail(comparison.error());
  auto png = scene::encodePng(*comparison);
  if (!png) return run.fail(png.error());
  files.emplace_back("comparison.png", std::move(png).value());
  return std::nullopt;
}

// What the instrumented kernels found in each variant with NaN or Inf pixels.
std::string hazardSection(const std::vector<VariantResult>& results) {
  std::string text;
  for (const VariantResult& result : results) {
    if (!result.hazardView) continue;
    text += fmt::format("\nVariant `{}`, camera view {}:\n\n", result.name, *result.hazardView);
    for (const std::string& line : result.hazards) text += fmt::format("- {}\n", line);
  }
  if (text.empty()) return text;
  return "\n## Hazards\n\nThe first component to go NaN or Inf, per pixel, vertex or texel, found by rendering the "
         "variant again with instrumented kernels; origins first, then values that only carried a non-finite "
         "input on.\n" +
         text;
}

std::string reportText(const Options& options, const engine::ToolRun& run, const FramePlan& plan,
                       const std::vector<VariantResult>& results, const std::vector<measure::ReportRow>& rows,
                       const std::vector<FailedVariant>& failed) {
  const scene::SceneFile& scene = run.scene();
  std::string report = fmt::format(
      "# spire-demo report\n\nScene `{}` on {}, {}x{}, {} measured frames after {} warm-up, error over {} camera "
      "view(s) against `{}`.\n\n{}\n| variant | bakes |\n| --- | --- |\n",
      options.scenePath, run.context().selectedDevice().name, scene.width, scene.height, plan.measured, plan.warmup,
      scene.camera.views.size(), results.front().name, measure::formatMarkdownTable(rows));
  for (const VariantResult& result : results) {
    report += fmt::format("| {} | {} |\n", result.name, bakeSummary(result.bakes));
  }
  report += hazardSection(results);
  if (failed.empty()) return report;
  report +=
      "\n## Failed variants\n\nNot measured; the run exits with status 1.\n\n| variant | decisions | why |\n"
      "| --- | --- | --- |\n";
  for (const FailedVariant& f : failed) {
    std::string reason = f.reason;
    std::replace(reason.begin(), reason.end(), '\n', ' ');
    std::replace(reason.begin(), reason.end(), '|', '/');
    report += fmt::format("| {} | {} | {} |\n", f.name, f.decisions.empty() ? "(scene)" : f.decisions, reason);
  }
  return report;
}

// The PNGs, comparison.png and report.md, written as a set: the output
// directory then holds this run's files and nothing of an earlier run's.
std::optional<int> writeOutputs(const Options& options, engine::ToolRun& run, const FramePlan& plan,
                                const std::vector<VariantResult>& results, const std::vector<measure::ReportRow>& rows,
                                const std::vector<FailedVariant>& failed, std::ostream& out) {
  FileSet files;
  if (const auto status = encodeImages(run, results, rows, files)) return status;
  files.emplace_back("report.md", reportText(options, run, plan, results, rows, failed));
  if (auto written = replaceDirectoryAtomically(options.outputDir, files); !written) {
    return run.fail(written.error().message);
  }
  std::string names;
  for (const VariantResult& result : results) names += (names.empty() ? "" : ",") + result.name;
  out << fmt::format("wrote {}/{{{}}}.png, comparison.png, report.md\n", options.outputDir, names);
  return std::nullopt;
}

// Measures the prepared variants and writes what the measurement found.
int measureVariants(const Options& options, engine::ToolRun& run, const std::vector<engine::PreparedScene>& prepared,
                    std::vector<VariantResult>& results, const std::vector<FailedVariant>& failed, std::ostream& out,
                    std::ostream& err) {
  const FramePlan plan{std::max<uint32_t>(1, options.warmup.value_or(run.scene().warmupFrames)),
                       std::max<uint32_t>(1, options.frames.value_or(run.scene().frames))};
  if (const auto status = measureFrames(run, prepared, plan, results)) return *status;
  if (const auto status = captureViews(options, run, prepared, plan, results, out)) return *status;
  std::vector<measure::ReportRow> rows;
  if (const auto status = reportRows(run, results, rows, err)) return *status;
  diagnoseVariants(run, results, err);
  out << measure::formatTextTable(rows);
  if (const auto status = writeOutputs(options, run, plan, results, rows, failed, out)) return *status;
  if (failed.empty()) return kExitSuccess;
  err << fmt::format("{}: error: {} of {} variants failed (see above and report.md); the others were measured\n", kTool,
                     failed.size(), failed.size() + results.size());
  return kExitInputError;
}

int showVariants(const Options& options, engine::ToolRun& run, GlfwWindow& window,
                 const std::vector<engine::PreparedScene>& prepared, const std::vector<VariantResult>& results,
                 std::ostream& out) {
  std::vector<std::string> names;
  for (const VariantResult& result : results) names.push_back(result.name);
  const WindowOptions windowOptions{fs::path(options.scenePath).filename().string(), options.frames};
  return runWindow(window, run.renderer(), variantFrames(run.renderer(), prepared, names), windowOptions, out,
                   run.reporter());
}

// A scene with "lod": its configurations instead of variants.
int runLod(const Options& options, engine::ToolRun& run, GlfwWindow* window, std::ostream& out) {
  const FramePlan plan{std::max<uint32_t>(1, options.warmup.value_or(run.scene().warmupFrames)),
                       options.frames.value_or(run.scene().frames)};
  LodRunOptions lod{options.scenePath, options.outputDir, plan.warmup, plan.measured, std::nullopt};
  if (window) lod.windowFrames = options.frames;
  return runLodDemo(lod, run, window, out);
}

}  // namespace

int runDemo(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  CLI::App app{"spire-demo: renders a scene's Spire shader variants on Vulkan and measures their speed/accuracy trade",
               kTool};
  Options options;
  defineOptions(app, options);
  if (const auto status = parseToolArguments(app, args, out, err)) return *status;
  if (options.listDevices) return listDevices(options, out, err);
  if (options.scenePath.empty()) return usageError(kTool, "a scene file is required", err);

  // Declared before the run: the context makes its surface on the window
  // and must be destroyed first.
  std::optional<GlfwWindow> window;
  engine::ToolRun run(kTool, err);
  if (const auto status = run.loadScene(options.scenePath, options.engine.resolution)) return *status;
  // The policy is read before the device opens, so a bad one costs no start-up.
  if (run.scene().lod) {
    if (const auto status = run.loadLodPolicy()) return *status;
  }
  if (const auto status = openDevice(options, run, window, out, err)) return *status;
  run.startRenderer(options.engine.bakeSize);
  if (run.scene().lod) return runLod(options, run, window ? &*window : nullptr, out);
  std::vector<engine::PreparedScene> prepared;
  std::vector<VariantResult> results;
  std::vector<FailedVariant> failed;
  if (const auto status = prepareVariants(run, variantRuns(options, run.scene()), prepared, results, failed, err)) {
    return *status;
  }
  if (window) return run.finish(showVariants(options, run, *window, prepared, results, out));
  // A failed measurement has said why; validation is reported on success.
  const int status = measureVariants(options, run, prepared, results, failed, out, err);
  // With failed variants the outputs are written; validation still counts.
  return status == kExitSuccess || !failed.empty() ? run.finish(status) : status;
}

}  // namespace spire::demo
