// Measures tuning points in process: each point's variant is built from
// in-memory decisions through the compiler library (no re-parsing), rendered
// by the engine (reusing bakes and shader modules across variants), timed,
// and compared with the reference over every camera view. Variants whose
// kernels are identical (by content hash) are measured once.
#pragma once

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "measure/image_metrics.h"
#include "renderer/scene_renderer.h"
#include "renderer/view_error.h"
#include "tool/hazard_diagnosis.h"
#include "tune/paired_timing.h"
#include "tune/results_csv.h"
#include "tune/tune_space.h"

namespace spire::tune {

// Where a run's time goes, summed over the points a tuner measured.
struct TimeSplit {
  double compileMs = 0.0;   // variant building, GLSL generation, glslang
  double firstUseMs = 0.0;  // first frames: lavapipe compiles the kernels at the first draw
  double renderMs = 0.0;    // bakes, measured frames and captures
  double errorMs = 0.0;     // image comparison

  TimeSplit& operator+=(const TimeSplit& other) {
    compileMs += other.compileMs;
    firstUseMs += other.firstUseMs;
    renderMs += other.renderMs;
    errorMs += other.errorMs;
    return *this;
  }
};

// Material values for one parameter sample: component -> numbers.
using ParameterSample = std::map<std::string, std::vector<double>>;

// What a sample of an --extremes run is, for the stability table.
struct SampleLabel {
  std::string input;  // the one input it changes; empty when it sets every input, or none ("scene")
  std::string kind;   // "scene", "all-min", "all-max", "min", "max", "texture-min", "texture-max", "sample"
};

struct TunerOptions {
  // Unmeasured frames before the measured ones. The captures of the camera
  // views come first and count: the first frame pays lavapipe's shader
  // compilation whatever it is used for.
  uint32_t warmupFrames = 1;
  // Pairs of frames (variant, reference) per variant: at least minPairs,
  // more while the time ratio's interval is wide.
  StoppingRule timing;
  // Error is measured over every sample (and every camera view); time over
  // the first. Empty: the scene's own values only.
  std::vector<ParameterSample> parameterSamples;
  std::vector<SampleLabel> sampleLabels;  // one per sample with --extremes, else empty
  // --extremes: the first sample is the scene's own values, and a reference
  // that is finite there but not under a later sample leaves that sample
  // out of every variant's error instead of stopping the run.
  bool extremes = false;
};

// What a variant's views add up to against the reference's.
struct ViewTotals {
  measure::ErrorAccumulator error;   // every view under every sample
  measure::ErrorAccumulator sample;  // the views under the sample being compared
  double worstRmse = 0.0;            // the largest RMSE of one sample
  engine::Coverage coverage;
  double errorMs = 0.0;  // spent comparing
};

class Tuner {
 public:
  Tuner(engine::SceneRenderer& renderer, size_t instance, std::vector<Axis> axes, TunerOptions options);

  // Renders the reference variant (`decisions`: a decision file for every
  // instance, or each instance's own) from every camera view, once. A
  // reference with NaN or Inf pixels is an error: every variant's error
  // against it would be infinite, clean ones included.
  engine::Expected<void> renderReference(const std::optional<std::filesystem::path>& decisions);

  VariantResult measure(const TunePoint& point);
  // The point's time ratio measured again under `rule` (racing: the
  // candidates for the front get more pairs).
  engine::Expected<TimeRatio> remeasureTime(const TunePoint& point, const StoppingRule& rule);
  // The reference's median frame time in this process: a time ratio times
  // this is a frame time.
  double referenceMs() const { return referenceMs_; }

  // The variant's image from camera view 0 and its placement, for reports
  // and decision files.
  engine::Expected<engine::Capture> capture(const TunePoint& point);
  engine::Expected<engine::VariantProgram> program(const TunePoint& point);
  // Every camera view of the point's variant under every parameter sample
  // the reference is finite under, read back and given to `use` in turn:
  // the domain the variant's error is measured over, for a caller that
  // averages what a probe variant shows there (spire-simplify --search).
  engine::Expected<void> forEachCapture(const TunePoint& point, const std::function<void(const engine::Capture&)>& use);

  const TimeSplit& timeSplit() const { return split_; }

  // The samples: the options' or, without them, the scene's values alone.
  std::vector<ParameterSample> samples() const;
  const std::vector<SampleLabel>& sampleLabels() const { return options_.sampleLabels; }
  // "camera view 0 maskMap=0,0,0,0": where a hazard showed, for people.
  std::string inputsText(size_t sample, size_t view) const;
  // The samples (with the first camera view that has them) under which the
  // reference is non-finite and that every variant's error leaves out.
  const std::vector<std::pair<size_t, size_t>>& referenceHazards() const { return referenceHazards_; }
  // Compiles the reference, or the point's variant, in a diagnosis renderer.
  engine::CompileForDiagnosis referenceCompile() const;
  engine::CompileForDiagnosis variantCompile(const TunePoint& point) const;
  // What instrumented kernels find under sample `sample` and camera view
  // `view` (tool/hazard_diagnosis.h).
  engine::Expected<std::vector<engine::Hazard>> diagnoseHazards(const engine::CompileForDiagnosis& compile,
                                                                size_t sample, size_t view);

  // Frames rendered before the measured ones: the captures of every camera
  // view, then more if the options ask for more warm-up than that.
  uint32_t unmeasuredFrames() const;

 private:
  // The images and times of a variant that is not measured yet: its bakes,
  // every camera view under every parameter sample against the reference,
  // and its frame time under the first.
  engine::Expected<void> measureImages(const std::vector<engine::VariantProgram>& programs, VariantResult& result);
  // The views of `prepared` (under sample `s`) against the reference's,
  // added to `accumulated`; the first capture of sample 0 is the first use.
  engine::Expected<void> compareViews(const engine::PreparedScene& prepared, size_t s, VariantResult& result,
                                      ViewTotals& totals);
  // Frames of `variant` and of the reference in turn, after `warmup` of the
  // variant's, until `rule` is met.
  engine::Expected<TimeRatio> measurePaired(const engine::PreparedScene& variant, uint32_t warmup,
                                            const StoppingRule& rule);
  engine::Expected<void> checkReference(const std::optional<std::filesystem::path>& decisions);
  // What the instrumented programs find under parameter sample `sample`
  // and camera view `view` (tool/hazard_diagnosis.h), as lines.
  std::vector<std::string> diagnose(const engine::CompileForDiagnosis& compile, size_t sample, size_t view);
  engine::Expected<std::vector<engine::VariantProgram>> programsFor(const TunePoint& point,
                                                                    std::vector<std::string>* skipped);

  engine::SceneRenderer& renderer_;
  size_t instance_;
  std::vector<Axis> axes_;
  TunerOptions options_;
  std::vector<engine::VariantProgram> others_;  // every instance at its own decisions
  bool excluded(size_t sample) const;

  std::vector<std::vector<engine::Capture>> reference_;  // [sample][view]
  std::optional<std::filesystem::path> referenceDecisions_;
  std::vector<std::pair<size_t, size_t>> referenceHazards_;
  std::optional<engine::PreparedScene> referenceScene_;  // under the first sample: the timing partner
  double referenceMs_ = 0.0;
  std::map<std::string, VariantResult> byKernels_;
  TimeSplit split_;
};

}  // namespace spire::tune
