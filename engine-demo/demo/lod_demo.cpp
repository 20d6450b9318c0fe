#include "demo/lod_demo.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <vector>

#include "demo/camera_path.h"
#include "demo/window.h"
#include "measure/comparison_image.h"
#include "measure/image_metrics.h"
#include "renderer/lod_scene.h"
#include "renderer/view_error.h"
#include "scene/texture.h"
#include "support/atomic_directory.h"

namespace spire::demo {

namespace {

// The three configurations, in the report's order (the window puts lod
// first, on key 1).
constexpr std::array kNames = {"full_quality", "lod", "lod_no_transitions"};
constexpr size_t kFull = 0;
constexpr size_t kLod = 1;
constexpr size_t kHard = 2;

struct Configuration {
  std::unique_ptr<engine::LodScene> scene;
  std::vector<double> gpuMs;    // per measured frame
  std::vector<double> batches;  // per measured frame
  std::vector<double> draws;
  measure::FloatImage previous;  // the last measured frame
  double popping = 0.0;          // the largest change level switches alone made between two frames (FrameChange)
  size_t popped = 0;             // pixels that level switches changed by more than 0.1, over every frame
  measure::ErrorAccumulator error;
};

double percentile(std::vector<double> values, double q) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const auto index = static_cast<size_t>(std::lround(q * static_cast<double>(values.size() - 1)));
  return values[index];
}

// How much level switches changed a frame: per pixel the largest RGB
// change; `popping` is the change that all but 0.01% of the pixels stay
// under (so that a few silhouette pixels do not decide it), `popped` the
// pixels that changed by more than 0.1.
struct FrameChange {
  double popping = 0.0;
  size_t popped = 0;
};

FrameChange frameChange(const measure::FloatImage& now, const measure::FloatImage& before) {
  std::vector<double> changes(now.rgba.size() / 4);
  FrameChange change;
  for (size_t p = 0; p < changes.size(); ++p) {
    double largest = 0.0;
    for (size_t c = 0; c < 3; ++c) {
      largest = std::max(largest, std::abs(double{now.rgba[p * 4 + c]} - before.rgba[p * 4 + c]));
    }
    changes[p] = largest;
    change.popped += largest > 0.1 ? 1 : 0;
  }
  change.popping = percentile(std::move(changes), 0.9999);
  return change;
}

engine::Expected<std::array<Configuration, 3>> createConfigurations(engine::ToolRun& run) {
  std::array<Configuration, 3> configs;
  const engine::LodOptions options[] = {{0, true}, {std::nullopt, true}, {std::nullopt, false}};
  for (size_t c = 0; c < configs.size(); ++c) {
    auto scene = engine::LodScene::create(run.renderer(), run.lodPolicy(), options[c]);
    if (!scene) return scene.error();
    configs[c].scene = std::move(scene).value();
    configs[c].scene->resetLevels(run.scene().camera.views.front());
  }
  return configs;
}

// Popping: what level switches alone change. The new frame's levels are
// drawn from the previous frame's camera and compared with the previous
// frame, so the camera's motion, which changes far more pixels, does not
// count; a switch without a cross-fade changes its object's pixels all at
// once, one with a cross-fade by a fraction each frame.
engine::Expected<void> measurePopping(Configuration& config, const scene::CameraView& previousView, float time) {
  if (config.previous.rgba.empty()) return {};
  if (auto drawn = config.scene->draw(previousView, time); !drawn) return drawn.error();
  auto held = config.scene->readColor();
  if (!held) return held.error();
  const FrameChange change = frameChange(*held, config.previous);
  config.popping = std::max(config.popping, change.popping);
  config.popped += change.popped;
  return {};
}

// One frame of every configuration at `view`; measured ones recorded.
engine::Expected<void> renderFrame(std::array<Configuration, 3>& configs, const scene::CameraView& view,
                                   const scene::CameraView& previousView, float time, bool measured) {
  engine::Capture full;
  for (size_t c = 0; c < configs.size(); ++c) {
    Configuration& config = configs[c];
    config.scene->updateLevels(view);
    if (measured && c != kFull) {
      if (auto popped = measurePopping(config, previousView, time); !popped) return popped.error();
    }
    auto timing = config.scene->draw(view, time);
    if (!timing) return timing.error();
    auto image = config.scene->readColor();
    if (!image) return image.error();
    if (!measured) continue;
    config.gpuMs.push_back(timing->gpuMs);
    config.batches.push_back(config.scene->lastStats().batches);
    config.draws.push_back(config.scene->lastStats().drawCalls);
    // Error over the pixels either image covers, as for variants: the sky,
    // the same in both, dilutes nothing.
    auto coverage = config.scene->readCoverage();
    if (!coverage) return coverage.error();
    engine::Capture capture{std::move(image).value(), std::move(coverage).value(), *timing};
    if (c == kFull) {
      full = std::move(capture);
      continue;
    }
    auto error = engine::viewError(full, capture);
    if (!error) return engine::Error{error.error().message, {}, {}};
    config.error.add(*error);
    config.previous = std::move(capture.color);
  }
  return {};
}

double median(const std::vector<double>& v) { return percentile(v, 0.5); }
double mean(const std::vector<double>& v) {
  double sum = 0.0;
  for (double x : v) sum += x;
  return v.empty() ? 0.0 : sum / static_cast<double>(v.size());
}

struct Summary {
  std::vector<double> speedups;  // per measured frame: full quality / lod
  double speedup = 0.0;
};

Summary summarize(const std::array<Configuration, 3>& configs) {
  Summary s;
  const auto& full = configs[kFull].gpuMs;
  const auto& lod = configs[kLod].gpuMs;
  for (size_t f = 0; f < full.size() && f < lod.size(); ++f) s.speedups.push_back(full[f] / std::max(lod[f], 1e-9));
  s.speedup = median(s.speedups);
  return s;
}

std::string reportText(const LodRunOptions& options, const engine::ToolRun& run,
                       const std::array<Configuration, 3>& configs, const Summary& summary) {
  const scene::SceneFile& scene = run.scene();
  std::string text = fmt::format(
      "# spire-demo level-of-detail report\n\nScene `{}` on {}, {}x{}, {} instances, {} blocks per side; {} frames "
      "along a loop through its {} camera views after {} warm-up, the three configurations rendered in turn each "
      "frame. Error against full quality over every measured frame, over the pixels either image covers; popping is "
      "the largest change level switches "
      "alone made from one frame to the next (the new frame's levels drawn from the previous frame's camera, "
      "against the previous frame): the largest RGB change of a pixel that all but 0.01% of the pixels stay "
      "under; popped pixels are those the switches changed by more than 0.1, summed over the frames.\n\n"
      "| configuration | median frame (ms) | speedup (median, p10-p90 per frame) | batches | draw calls | RMSE | "
      "popping | popped pixels |\n| --- | --- | --- | --- | --- | --- | --- | --- |\n",
      options.scenePath, run.context().selectedDevice().name, scene.width, scene.height,
      configs[kFull].scene->instanceCount(), scene.lod->blocks, options.measured, scene.camera.views.size(),
      options.warmup);
  for (size_t c = 0; c < configs.size(); ++c) {
    const Configuration& config = configs[c];
    std::vector<double> ratios;
    for (size_t f = 0; f < config.gpuMs.size(); ++f) {
      ratios.push_back(configs[kFull].gpuMs[f] / std::max(config.gpuMs[f], 1e-9));
    }
    const measure::ImageError error = config.error.total();
    text += fmt::format("| {} | {:.2f} | {:.2f}x ({:.2f}-{:.2f}) | {:.1f} | {:.1f} | {:.4f} | {:.4f} | {} |\n",
                        kNames[c], median(config.gpuMs), median(ratios), percentile(ratios, 0.1),
                        percentile(ratios, 0.9), mean(config.batches), mean(config.draws),
                        c == kFull ? 0.0 : error.rmse, config.popping, config.popped);
  }
  text += fmt::format("\nSpeedup of lod over full quality: {:.2f}x.\n", summary.speedup);
  return text;
}

// full_quality.png and lod.png at the first view, levels as they are there
// without fading, and both side by side.
engine::Expected<void> addImages(engine::ToolRun& run, std::array<Configuration, 3>& configs, const Summary& summary,
                                 FileSet& files) {
  // Panels refer to their images, which must outlive them.
  std::array<scene::Image, 2> images;
  std::vector<measure::Panel> panels;
  const scene::CameraView& view = run.scene().camera.views.front();
  for (size_t c : {kFull, kLod}) {
    configs[c].scene->resetLevels(view);
    if (auto timing = configs[c].scene->render(view, 0.0F); !timing) return timing.error();
    auto image = configs[c].scene->readColor();
    if (!image) return image.error();
    scene::Image& rgba = images[c == kFull ? 0 : 1];
    rgba = measure::toRgba8(*image);
    for (size_t i = 3; i < rgba.bytes.size(); i += 4) rgba.bytes[i] = 255;
    auto png = scene::encodePng(rgba);
    if (!png) return engine::Error{png.error().message, {}, {}};
    files.emplace_back(fmt::format("{}.png", kNames[c]), std::move(png).value());
    panels.push_back(
        {rgba, c == kFull ? std::string("full quality")
                          : fmt::format("lod {:.2f}X RMSE {:.4f}", summary.speedup, configs[c].error.total().rmse)});
  }
  auto comparison = measure::makeComparisonImage(panels);
  if (!comparison) return engine::Error{comparison.error().message, {}, {}};
  auto png = scene::encodePng(*comparison);
  if (!png) return engine::Error{png.error().message, {}, {}};
  files.emplace_back("comparison.png", std::move(png).value());
  return {};
}

int measureLod(const LodRunOptions& options, engine::ToolRun& run, std::array<Configuration, 3>& configs,
               std::ostream& out) {
  const auto& views = run.scene().camera.views;
  for (uint32_t f = 0; f < options.warmup; ++f) {
    if (auto ok = renderFrame(configs, views.front(), views.front(), 0.0F, false); !ok) return run.fail(ok.error());
  }
  scene::CameraView previous = views.front();
  for (uint32_t f = 0; f < options.measured; ++f) {
    const scene::CameraView view = flyThroughView(views, f, options.measured);
    if (auto ok = renderFrame(configs, view, previous, static_cast<float>(f) / 60.0F, true); !ok) {
      return run.fail(ok.error());
    }
    previous = view;
  }
  const Summary summary = summarize(configs);
  FileSet files;
  if (auto ok = addImages(run, configs, summary, files); !ok) return run.fail(ok.error());
  const std::string report = reportText(options, run, configs, summary);
  files.emplace_back("report.md", report);
  if (auto written = replaceDirectoryAtomically(options.outputDir, files); !written) {
    return run.fail(written.error().message);
  }
  out << report.substr(report.find("| configuration"));
  out << fmt::format("wrote {}/{{full_quality,lod,comparison}}.png, report.md\n", options.outputDir);
  out << fmt::format(
      "lod: speedup {:.2f}, batches {:.1f} vs full quality {:.1f}, rmse {:.4f}, popping {:.4f} with "
      "transitions vs {:.4f} without\n",
      summary.speedup, mean(configs[kLod].batches), mean(configs[kFull].batches), configs[kLod].error.total().rmse,
      configs[kLod].popping, configs[kHard].popping);
  return 0;
}

}  // namespace

int runLodDemo(const LodRunOptions& options, engine::ToolRun& run, GlfwWindow* window, std::ostream& out) {
  auto configs = createConfigurations(run);
  if (!configs) return run.fail(configs.error());
  // Every level is prepared now: a material value that none of them reads
  // is worth a warning (W7101), as for variants, and so is a switch that
  // the policy cross-fades but the level's shader cannot (W7102).
  run.renderer().reportUnreadBindings();
  (*configs)[kLod].scene->reportSwitchesThatCannotFade(run.diagnostics());
  run.reporter().flush();
  if (!window) return run.finish(measureLod(options, run, *configs, out));
  FrameSource source;
  source.names.assign(kNames.begin(), kNames.end());
  // The window opens on the level-of-detail configuration.
  std::swap(source.names[0], source.names[1]);
  source.render = [&configs](size_t c, const scene::CameraView& view, float time) {
    return (*configs)[c == 0 ? kLod : c == 1 ? kFull : c].scene->render(view, time);
  };
  const WindowOptions windowOptions{std::filesystem::path(options.scenePath).filename().string(), options.windowFrames};
  return run.finish(runWindow(*window, run.renderer(), source, windowOptions, out, run.reporter()));
}

}  // namespace spire::demo
