#include "tune/tuner.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "measure/image_metrics.h"
#include "renderer/view_error.h"
#include "tool/hazard_diagnosis.h"
#include "vk/timer.h"

namespace spire::tune {

Tuner::Tuner(engine::SceneRenderer& renderer, size_t instance, std::vector<Axis> axes, TunerOptions options)
    : renderer_(renderer), instance_(instance), axes_(std::move(axes)), options_(std::move(options)) {}

std::vector<ParameterSample> Tuner::samples() const {
  return options_.parameterSamples.empty() ? std::vector<ParameterSample>{ParameterSample{}}
                                           : options_.parameterSamples;
}

namespace {

std::string sampleText(const ParameterSample& sample) {
  std::string text;
  for (const auto& [component, values] : sample) text += fmt::format(" {}={}", component, fmt::join(values, ","));
  return text;
}

}  // namespace

std::string Tuner::inputsText(size_t sample, size_t view) const {
  return fmt::format("camera view {}{}", view, sampleText(samples().at(sample)));
}

bool Tuner::excluded(size_t sample) const {
  return std::any_of(referenceHazards_.begin(), referenceHazards_.end(),
                     [&](const std::pair<size_t, size_t>& hazard) { return hazard.first == sample; });
}

engine::Expected<std::vector<engine::Hazard>> Tuner::diagnoseHazards(const engine::CompileForDiagnosis& compile,
                                                                     size_t sample, size_t view) {
  const std::vector<ParameterSample> parameterSamples = samples();
  const engine::HazardSample where{&renderer_.scene().camera.views.at(view), parameterSamples.at(sample)};
  return engine::diagnoseHazards(renderer_, compile, where);
}

std::vector<std::string> Tuner::diagnose(const engine::CompileForDiagnosis& compile, size_t sample, size_t view) {
  auto hazards = diagnoseHazards(compile, sample, view);
  if (!hazards) return {fmt::format("(no diagnosis: {})", hazards.error().message)};
  return engine::hazardLines(*hazards);
}

engine::CompileForDiagnosis Tuner::referenceCompile() const {
  return [decisions = referenceDecisions_](engine::SceneRenderer& renderer) { return renderer.compile(decisions); };
}

engine::CompileForDiagnosis Tuner::variantCompile(const TunePoint& point) const {
  return [instance = instance_, decisions = point.decisions](
             engine::SceneRenderer& renderer) -> engine::Expected<std::vector<engine::VariantProgram>> {
    auto others = renderer.compile(std::nullopt);
    if (!others) return others.error();
    auto own = renderer.compileVariant(instance, decisions);
    if (!own) return own.error();
    others->at(instance) = std::move(own).value();
    return others;
  };
}

// With --extremes only the scene's own values (sample 0) must be finite: a
// later sample the reference cannot render is left out of every variant's
// error, since there is nothing to compare against there.
engine::Expected<void> Tuner::checkReference(const std::optional<std::filesystem::path>& decisions) {
  for (size_t s = 0; s < reference_.size(); ++s) {
    for (size_t v = 0; v < reference_[s].size(); ++v) {
      const uint64_t broken = measure::nonFinitePixels(reference_[s][v].color);
      if (broken == 0) continue;
      if (options_.extremes && s > 0) {
        referenceHazards_.emplace_back(s, v);
        break;
      }
      const auto causes = diagnose(referenceCompile(), s, v);
      return engine::Error{
          fmt::format("the reference ({}) has {} NaN or Inf pixels under camera view {}{}: every variant's error "
                      "against it would be infinite. Fix the shader, or choose a reference without the hazard with "
                      "--reference DECISIONS. There, {}",
                      decisions ? decisions->string() : std::string("each instance's own decisions"), broken, v,
                      sampleText(samples()[s]), fmt::join(causes, "; ")),
          {},
          {}};
    }
  }
  return {};
}

engine::Expected<void> Tuner::renderReference(const std::optional<std::filesystem::path>& decisions) {
  if (!reference_.empty()) return {};
  referenceDecisions_ = decisions;
  auto programs = renderer_.compile(decisions);
  if (!programs) return programs.error();
  for (const ParameterSample& sample : samples()) {
    renderer_.setParameterOverrides(sample);
    auto prepared = renderer_.prepare(*programs);
    if (!prepared) return prepared.error();
    std::vector<engine::Capture> views;
    for (const scene::CameraView& view : renderer_.scene().camera.views) {
      auto capture = renderer_.capture(*prepared, view);
      if (!capture) return capture.error();
      views.push_back(std::move(capture).value());
    }
    reference_.push_back(std::move(views));
    if (!referenceScene_) referenceScene_.emplace(std::move(prepared).value());
  }
  renderer_.setParameterOverrides({});
  if (auto checked = checkReference(decisions); !checked) return checked;
  const auto views = static_cast<uint32_t>(renderer_.scene().camera.views.size());
  auto stats = renderer_.measure(*referenceScene_, unmeasuredFrames() - views, options_.timing.minPairs);
  if (!stats) return stats.error();
  referenceMs_ = stats->medianGpuMs;
  return {};
}

engine::Expected<TimeRatio> Tuner::measurePaired(const engine::PreparedScene& variant, uint32_t warmup,
                                                 const StoppingRule& rule) {
  uint32_t frame = 0;
  for (; frame < warmup; ++frame) {
    if (auto timing = renderer_.renderFrame(variant, frame); !timing) return timing.error();
  }
  std::vector<double> ratios;
  while (!enoughPairs(ratios, rule)) {
    // Each goes first in every other pair, so that neither is always timed
    // right after the other.
    const bool variantFirst = ratios.size() % 2 == 0;
    double variantMs = 0.0;
    double referenceMs = 0.0;
    for (const bool isVariant : {variantFirst, !variantFirst}) {
      auto timing = renderer_.renderFrame(isVariant ? variant : *referenceScene_, frame);
      if (!timing) return timing.error();
      (isVariant ? variantMs : referenceMs) = timing->gpuMs;
    }
    ++frame;
    ratios.push_back(variantMs / std::max(referenceMs, 1e-9));
  }
  return summarizeRatios(ratios);
}

engine::Expected<TimeRatio> Tuner::remeasureTime(const TunePoint& point, const StoppingRule& rule) {
  auto programs = programsFor(point, nullptr);
  if (!programs) return programs.error();
  renderer_.setParameterOverrides(samples().front());
  auto prepared = renderer_.prepare(*programs);
  renderer_.setParameterOverrides({});
  if (!prepared) return prepared.error();
  // The first frame compiles the kernels (lavapipe); one more settles.
  return measurePaired(*prepared, std::max(options_.warmupFrames, 2U), rule);
}

engine::Expected<std::vector<engine::VariantProgram>> Tuner::programsFor(const TunePoint& point,
                                                                         std::vector<std::string>* skipped) {
  if (others_.empty()) {
    auto own = renderer_.compile(std::nullopt);
    if (!own) return own.error();
    others_ = std::move(own).value();
  }
  auto program = renderer_.compileVariant(instance_, point.decisions, skipped);
  if (!program) return program.error();
  std::vector<engine::VariantProgram> programs = others_;
  programs[instance_] = std::move(program).value();
  return programs;
}

engine::Expected<engine::VariantProgram> Tuner::program(const TunePoint& point) {
  auto programs = programsFor(point, nullptr);
  if (!programs) return programs.error();
  return std::move(programs->at(instance_));
}

VariantResult Tuner::measure(const TunePoint& point) {
  VariantResult result;
  result.index = point.index;
  for (const Axis& axis : axes_) result.placements.push_back(point.decisions.at(axis.component));

  const vk::HostTimer timer;
  std::vector<std::string> skipped;
  auto programs = programsFor(point, &skipped);
  split_.compileMs += timer.elapsedMs();
  if (!programs) {
    result.status = "failed: " + programs.error().message;
    return result;
  }
  if (!skipped.empty()) {
    // The decisions cannot hold together (one component's world rules out
    // another's): this point of the product is not a variant.
    result.status = "infeasible";
    return result;
  }
  result.kernels = programs->at(instance_).fingerprint();
  if (const auto it = byKernels_.find(result.kernels); it != byKernels_.end()) {
    VariantResult same = it->second;
    same.index = result.index;
    same.placements = result.placements;
    same.sameAs = it->second.index;
    return same;
  }

  if (auto measured = measureImages(*programs, result); !measured) {
    result.status = "failed: " + measured.error().message;
    return result;
  }
  if (result.hazardSample) {
    result.hazardCauses = diagnose(variantCompile(point), result.hazardSample->first, result.hazardSample->second);
  }
  byKernels_[result.kernels] = result;
  return result;
}

engine::Expected<void> Tuner::measureImages(const std::vector<engine::VariantProgram>& programs,
                                            VariantResult& result) {
  const vk::HostTimer timer;
  ViewTotals totals;
  const std::vector<ParameterSample> parameterSamples = samples();
  for (size_t s = 0; s < parameterSamples.size(); ++s) {
    if (excluded(s)) continue;
    renderer_.setParameterOverrides(parameterSamples[s]);
    auto prepared = renderer_.prepare(programs);
    renderer_.setParameterOverrides({});
    if (!prepared) return prepared.error();
    if (s == 0) {
      for (const engine::BakeRecord& bake : prepared->bakes) result.prebakeMs += bake.reused ? 0.0 : bake.milliseconds;
    }
    totals.sample = {};
    if (auto compared = compareViews(*prepared, s, result, totals); !compared) {
      return compared;
    }
    totals.worstRmse = std::max(totals.worstRmse, totals.sample.total().rmse);
    if (s == 0) {
      // The captures above were the warm-up: only what the option asks for
      // beyond them is rendered before the measured frames.
      const auto views = static_cast<uint32_t>(renderer_.scene().camera.views.size());
      auto time = measurePaired(*prepared, unmeasuredFrames() - views, options_.timing);
      if (!time) return time.error();
      result.time = *time;
      result.frameMs = time->median * referenceMs_;
    }
  }
  split_.errorMs += totals.errorMs;
  split_.renderMs += timer.elapsedMs() - result.firstFrameMs - totals.errorMs;
  if (totals.coverage.degenerate()) {
    result.status =
        fmt::format("degenerate: covers {:.0f}% of the pixels the reference covers", 100.0 * totals.coverage.ratio());
  }
  const measure::ImageError total = totals.error.total();
  result.worstRmse = totals.worstRmse;
  result.rmse = total.rmse;
  result.psnr = total.psnr;
  result.maxError = total.maxError;
  result.nanPixels = total.nanPixels;
  result.infPixels = total.infPixels;
  return {};
}

engine::Expected<void> Tuner::compareViews(const engine::PreparedScene& prepared, size_t s, VariantResult& result,
                                           ViewTotals& totals) {
  const auto& views = renderer_.scene().camera.views;
  for (size_t v = 0; v < views.size(); ++v) {
    auto capture = renderer_.capture(prepared, views[v]);
    if (!capture) return capture.error();
    // The first frame of a variant is its first use: lavapipe compiles the
    // kernels at the first draw.
    if (s == 0 && v == 0) {
      result.firstFrameMs = capture->timing.hostMs;
      split_.firstUseMs += capture->timing.hostMs;
    }
    const vk::HostTimer errorTimer;
    auto error = engine::viewError(reference_[s][v], *capture);
    totals.coverage.add(reference_[s][v], *capture);
    totals.errorMs += errorTimer.elapsedMs();
    if (!error) return engine::Error(error.error());
    totals.error.add(*error);
    totals.sample.add(*error);
    if (error->nanPixels + error->infPixels == 0) continue;
    if (result.hazardInputs.empty()) {
      result.hazardInputs = inputsText(s, v);
      result.hazardSample = std::pair{s, v};
    }
    if (result.hazardSamples.empty() || result.hazardSamples.back().first != s) result.hazardSamples.emplace_back(s, v);
  }
  return {};
}

uint32_t Tuner::unmeasuredFrames() const {
  return std::max(options_.warmupFrames, static_cast<uint32_t>(renderer_.scene().camera.views.size()));
}

engine::Expected<void> Tuner::forEachCapture(const TunePoint& point,
                                             const std::function<void(const engine::Capture&)>& use) {
  auto programs = programsFor(point, nullptr);
  if (!programs) return programs.error();
  const std::vector<ParameterSample> parameterSamples = samples();
  for (size_t s = 0; s < parameterSamples.size(); ++s) {
    if (excluded(s)) continue;
    renderer_.setParameterOverrides(parameterSamples[s]);
    auto prepared = renderer_.prepare(*programs);
    renderer_.setParameterOverrides({});
    if (!prepared) return prepared.error();
    for (const scene::CameraView& view : renderer_.scene().camera.views) {
      auto capture = renderer_.capture(*prepared, view);
      if (!capture) return capture.error();
      use(*capture);
    }
  }
  return {};
}

engine::Expected<engine::Capture> Tuner::capture(const TunePoint& point) {
  auto programs = programsFor(point, nullptr);
  if (!programs) return programs.error();
  auto prepared = renderer_.prepare(*programs);
  if (!prepared) return prepared.error();
  return renderer_.capture(*prepared, renderer_.scene().camera.views.front());
}

}  // namespace spire::tune
