#include "demo/demo.h"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <filesystem>
#include <optional>
#include <ostream>

#include "demo/glfw_window.h"
#include "demo/window.h"
#include "measure/comparison_image.h"
#include "measure/image_metrics.h"
#include "measure/report_table.h"
#include "renderer/error_report.h"
#include "driver/tool_arguments.h"
#include "renderer/host_allocator.h"
#include "renderer/scene_renderer.h"
#include "renderer/view_error.h"
#include "scene/texture.h"
#include "support/diagnostic_renderer.h"
#include "support/file_io.h"
#include "vk/context.h"

namespace spire::demo {

namespace {

namespace fs = std::filesystem;

struct Options {
  std::string scenePath;
  std::vector<std::string> variants;
  std::string outputDir = "out/demo";
  std::optional<uint32_t> frames;
  std::optional<uint32_t> warmup;
  std::string device;
  uint32_t bakeSize = 1024;
  bool listDevices = false;
  bool validation = false;
  bool window = false;
};

struct VariantRun {
  std::string name;
  std::optional<fs::path> decisions;
};

struct VariantResult {
  std::string name;
  engine::FrameStats stats;
  std::vector<engine::BakeRecord> bakes;
  std::vector<engine::Capture> views;
  scene::Image image;  // view 0, 8 bits
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

std::optional<std::string> writeText(const fs::path& path, const std::string& text) {
  return writeFileAtomically(path.string(), text);
}

int listDevices(const Options& options, std::ostream& out, std::ostream& err) {
  vk::ContextOptions contextOptions;
  contextOptions.deviceFilter = options.device;
  auto ctx = vk::Context::create(contextOptions);
  if (!ctx) {
    err << fmt::format("spire-demo: error: no usable Vulkan device: {}\n", ctx.error().message());
    return kExitNoDevice;
  }
  for (const vk::PhysicalDeviceInfo& device : ctx->physicalDevices()) {
    out << fmt::format("{} {} ({}){}\n", &device == &ctx->selectedDevice() ? "*" : " ", device.name,
                       vk::deviceTypeName(device.type), &device == &ctx->selectedDevice() ? "  [selected]" : "");
  }
  return kExitSuccess;
}

}  // namespace

int runDemo(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  CLI::App app{"spire-demo: renders a scene's Spire shader variants on Vulkan and measures their speed/accuracy trade",
               "spire-demo"};
  Options options;
  addVersionFlag(app);
  app.add_option("scene", options.scenePath, "Scene file (docs/scene.md)")->type_name("SCENE.json");
  app.add_option("--variant", options.variants,
                 "Render with decision file PATH applied to every instance (repeatable; replaces the scene's "
                 "\"variants\"; the first is the reference)")
      ->type_name("PATH");
  addOutputDirectory(app, options.outputDir, "Write PNGs, comparison.png and report.md to DIR");
  app.add_option("--frames", options.frames,
                 "Measured frames per variant (default: the scene's); with --window, close it after N frames")
      ->type_name("N");
  app.add_option("--warmup", options.warmup, "Unmeasured frames first (default: the scene's; at least 1)")
      ->type_name("N");
  app.add_option("--device", options.device, "Use the Vulkan device whose name contains TEXT (default: llvmpipe)")
      ->type_name("TEXT");
  app.add_option("--bake-size", options.bakeSize, "PrebakeTex texture size without a TextureSize hint")
      ->check(CLI::Range(1, 8192))
      ->type_name("N");
  app.add_flag("--list-devices", options.listDevices, "List the Vulkan devices and exit");
  app.add_flag("--validation", options.validation,
               "Enable VK_LAYER_KHRONOS_validation; any message makes the run fail");
  app.add_flag("--window", options.window,
               "Show the variants in a window instead of measuring them (needs a display): keys 1-9 switch "
               "variants, dragging orbits the camera, Space pauses it, Escape quits");
  if (const auto status = parseToolArguments(app, args, out, err)) return *status;
  if (options.listDevices) return listDevices(options, out, err);
  engine::stabilizeHostAllocator();
  if (options.scenePath.empty()) {
    return usageError("spire-demo", "a scene file is required", err);
  }

  SourceManager sources;
  DiagnosticList diags;
  engine::ErrorReporter reporter(sources, diags, err, "spire-demo");
  const auto scene = scene::loadSceneFile(options.scenePath, sources, diags);
  if (!scene) {
    reporter.flush();
    return kExitInputError;
  }
  std::vector<VariantRun> runs;
  for (const std::string& path : options.variants) runs.push_back({fs::path(path).stem().string(), fs::path(path)});
  if (runs.empty()) {
    for (const scene::VariantDesc& variant : scene->variants) runs.push_back({variant.name, variant.decisions});
  }
  if (runs.empty()) runs.push_back({"scene", std::nullopt});
  const uint32_t warmup = std::max<uint32_t>(1, options.warmup.value_or(scene->warmupFrames));
  const uint32_t frames = std::max<uint32_t>(1, options.frames.value_or(scene->frames));

  vk::ContextOptions contextOptions;
  contextOptions.validation = options.validation;
  contextOptions.deviceFilter = options.device;
  contextOptions.applicationName = "spire-demo";
  // Opened before the context, which makes its surface on it and must be
  // destroyed first.
  std::optional<GlfwWindow> window;
  vk::SurfaceFactory surfaceFactory;
  if (options.window) {
    auto opened = GlfwWindow::open(scene->width, scene->height, fmt::format("spire-demo | {}", options.scenePath));
    if (!opened) {
      err << fmt::format("spire-demo: error: {}\n", opened.error());
      return kExitInputError;
    }
    window.emplace(std::move(opened).value());
    contextOptions.instanceExtensions = window->vulkanInstanceExtensions();
    surfaceFactory = [&window](VkInstance instance) { return window->createSurface(instance); };
  }
  auto ctx = vk::Context::create(contextOptions, surfaceFactory);
  if (!ctx) {
    err << fmt::format("spire-demo: error: no usable Vulkan device: {}\n", ctx.error().message());
    return kExitNoDevice;
  }
  out << fmt::format("device: {} ({})\n", ctx->selectedDevice().name, vk::deviceTypeName(ctx->selectedDevice().type));

  engine::TextureBakeOptions bakeOptions;
  bakeOptions.defaultSize = options.bakeSize;
  engine::SceneRenderer renderer(*ctx, *scene, diags, bakeOptions);
  // Every variant is compiled, baked and warmed up before any is timed, and
  // the measured frames then alternate between variants, so that no variant
  // is timed under different conditions (a cold renderer, load-time work)
  // than the others and the ratios come from one interleaved run.
  std::vector<engine::PreparedScene> prepared;
  std::vector<VariantResult> results;
  std::vector<std::vector<engine::FrameTiming>> timings(runs.size());
  for (const VariantRun& run : runs) {
    auto programs = renderer.compile(run.decisions);
    if (!programs) return reporter.fail(programs.error());
    err << renderer.compilerWarnings();
    auto scenePrepared = renderer.prepare(*programs);
    reporter.flush();
    if (!scenePrepared) return reporter.fail(scenePrepared.error());
    results.push_back({run.name, {}, scenePrepared->bakes, {}, {}});
    prepared.push_back(std::move(scenePrepared).value());
  }
  if (window) {
    std::vector<std::string> names;
    for (const VariantRun& run : runs) names.push_back(run.name);
    const WindowOptions windowOptions{fs::path(options.scenePath).filename().string(), options.frames};
    return engine::reportValidation(*ctx, runWindow(*window, renderer, prepared, names, windowOptions, out, reporter), err);
  }
  for (uint32_t f = 0; f < warmup + frames; ++f) {
    for (size_t v = 0; v < runs.size(); ++v) {
      auto timing = renderer.renderFrame(prepared[v], f);
      if (!timing) return reporter.fail(timing.error());
      if (f == 0) results[v].stats.firstFrameMs = timing->hostMs;
      if (f >= warmup) timings[v].push_back(*timing);
    }
  }
  for (size_t v = 0; v < runs.size(); ++v) {
    VariantResult& result = results[v];
    result.stats = engine::summarizeFrames(result.stats.firstFrameMs, timings[v]);
    for (const scene::CameraView& view : scene->camera.views) {
      auto capture = renderer.capture(prepared[v], view);
      if (!capture) return reporter.fail(capture.error());
      result.views.push_back(std::move(capture).value());
    }
    result.image = measure::toRgba8(result.views.front().color);
    out << fmt::format("{}: {:.3f} ms/frame (median of {}), first frame {:.1f} ms, bakes: {}\n", result.name,
                       result.stats.medianGpuMs, frames, result.stats.firstFrameMs, bakeSummary(result.bakes));
  }

  std::vector<measure::ReportRow> rows;
  for (const VariantResult& result : results) {
    const auto viewsError = engine::viewsError(results.front().views, result.views);
    if (!viewsError) return reporter.fail({viewsError.error(), {}, {}});
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
    rows.push_back(row);
    if (error.nanPixels + error.infPixels > 0) {
      err << fmt::format("spire-demo: warning: variant '{}' produced {} NaN and {} Inf pixels; its error is infinite\n",
                         result.name, error.nanPixels, error.infPixels);
    }
  }
  out << measure::formatTextTable(rows);

  std::error_code ec;
  fs::create_directories(options.outputDir, ec);
  if (ec) return reporter.fail({fmt::format("cannot create '{}': {}", options.outputDir, ec.message()), {}, {}});
  std::vector<measure::Panel> panels;
  for (size_t i = 0; i < results.size(); ++i) {
    const fs::path png = fs::path(options.outputDir) / (results[i].name + ".png");
    if (auto written = scene::writePng(png, results[i].image); !written) {
      return reporter.fail({written.error(), {}, {}});
    }
    panels.push_back({results[i].image, fmt::format("{} {:.2f}X RMSE {:.4f}", results[i].name, rows[i].speedup,
                                                    rows[i].rmse)});
  }
  auto comparison = measure::makeComparisonImage(panels);
  if (!comparison) return reporter.fail({comparison.error(), {}, {}});
  if (auto written = scene::writePng(fs::path(options.outputDir) / "comparison.png", *comparison); !written) {
    return reporter.fail({written.error(), {}, {}});
  }
  std::string report = fmt::format(
      "# spire-demo report\n\nScene `{}` on {}, {}x{}, {} measured frames after {} warm-up, error over {} camera "
      "view(s) against `{}`.\n\n{}\n| variant | bakes |\n| --- | --- |\n",
      options.scenePath, ctx->selectedDevice().name, scene->width, scene->height, frames, warmup,
      scene->camera.views.size(), results.front().name, measure::formatMarkdownTable(rows));
  for (const VariantResult& result : results) report += fmt::format("| {} | {} |\n", result.name, bakeSummary(result.bakes));
  if (auto error = writeText(fs::path(options.outputDir) / "report.md", report)) {
    return reporter.fail({*error, {}, {}});
  }
  out << fmt::format("wrote {}/{{{}}}.png, comparison.png, report.md\n", options.outputDir,
                     [&] {
                       std::string names;
                       for (const VariantResult& r : results) names += (names.empty() ? "" : ",") + r.name;
                       return names;
                     }());

  return engine::reportValidation(*ctx, kExitSuccess, err);
}

}  // namespace spire::demo
