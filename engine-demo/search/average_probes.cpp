#include "search/average_probes.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "support/file_io.h"

namespace spire::search {
namespace {

// Written into the probe's alpha: no surface a shader draws has it, so the
// pixels that hold it are the probed shader's.
constexpr float kProbeMark = -1.0F;
constexpr size_t kScalarsPerImage = 3;  // alpha carries the mark

// The exported vec4 the captured image is: the first export by name, as
// exports take their locations in name order (color target 0).
std::optional<std::string> shownExport(const sem::Shader& shader) {
  std::optional<std::string> shown;
  for (const sem::Component& c : shader.components) {
    if (!c.isExport || !c.type || c.type->name() != "vec4") continue;
    if (!shown || c.name < *shown) shown = c.name;
  }
  return shown;
}

std::string uniqueName(const sem::Shader& shader, size_t number) {
  std::string name = fmt::format("spireAverageProbe{}", number);
  while (shader.findComponent(name) != nullptr) name += "_";
  return name;
}

// The scalars [first, first + 3) of `value` (with `scalars` in all) as a
// vec4 marked in alpha.
std::string shownScalars(const std::string& value, size_t scalars, size_t first) {
  static constexpr const char* kLetters[] = {"x", "y", "z", "w"};
  std::vector<std::string> parts;
  for (size_t i = first; i < first + kScalarsPerImage; ++i) {
    if (i >= scalars) {
      parts.emplace_back("0.0");
    } else {
      parts.push_back(scalars == 1 ? value : value + "." + kLetters[i]);
    }
  }
  return fmt::format("vec4({}, {}, {}, {:.1f})", parts[0], parts[1], parts[2], kProbeMark);
}

struct ProbeImage {
  size_t probe = 0;
  size_t first = 0;  // the first scalar it shows
  Placement placement;
};

class ProbeModule {
 public:
  ProbeModule(const ProbeSetup& setup, const sem::Shader& shader, std::string shown)
      : setup_(setup), shader_(shader), shown_(std::move(shown)) {}

  // The definitions of probe `index` and the images that show it.
  void add(size_t index, const AverageProbe& probe) {
    const std::string name = uniqueName(shader_, index + 1);
    definitions_ +=
        fmt::format("    // the value of '{}' in {}, for its average\n    {} {} {}\n", probe.site.rewrite.before,
                    probe.component, probe.site.rewrite.type, name, probe.site.probe);
    for (size_t first = 0; first < probe.site.scalars; first += kScalarsPerImage) {
      const std::string variation = fmt::format("{}_{}", name, first);
      definitions_ +=
          fmt::format("    vec4 {}:{} = {};\n", shown_, variation, shownScalars(name, probe.site.scalars, first));
      Placement placement = setup_.placement;
      placement.emplace_back(name, worldOf(probe.placement));
      for (auto& [component, where] : placement) {
        if (component == shown_) where = worldOf(where) + ":" + variation;
      }
      images_.push_back({index, first, std::move(placement)});
    }
  }
  std::string text() const {
    std::string text = setup_.moduleText;
    return text.insert(text.rfind('}'), definitions_);
  }
  const std::vector<ProbeImage>& images() const { return images_; }

 private:
  const ProbeSetup& setup_;
  const sem::Shader& shader_;
  std::string shown_;
  std::string definitions_;
  std::vector<ProbeImage> images_;
};

// The mean of the marked pixels' first `count` channels; nullopt when no
// pixel is marked.
Expected<std::optional<std::vector<double>>, Failure> meanOfMarked(tune::Tuner& tuner, const Placement& placement,
                                                                   size_t count) {
  tune::TunePoint point;
  point.decisions = {placement.begin(), placement.end()};
  std::vector<double> sum(count, 0.0);
  uint64_t marked = 0;
  auto ok = tuner.forEachCapture(point, [&](const engine::Capture& capture) {
    for (size_t i = 0; i < capture.coverage.size(); ++i) {
      const float* rgba = &capture.color.rgba[i * 4];
      if (!capture.coverage[i] || rgba[3] != kProbeMark) continue;
      for (size_t c = 0; c < count; ++c) sum[c] += rgba[c];
      ++marked;
    }
  });
  if (!ok) return Failure{ok.error().message};
  if (marked == 0) return std::optional<std::vector<double>>{};
  for (double& s : sum) s /= static_cast<double>(marked);
  return std::optional(sum);
}

}  // namespace

Expected<std::vector<std::optional<std::vector<double>>>, Failure> measureAverages(
    const ProbeSetup& setup, const std::vector<AverageProbe>& probes) {
  auto current = compileModule(setup.compile, setup.path, setup.moduleText, setup.derived);
  if (!current) return current.error();
  const sem::Shader& shader = *(*current)->model().findShader(setup.derived);
  const std::optional<std::string> shown = shownExport(shader);
  if (!shown) return Failure{"the pipeline exports no vec4 color to show the probes in"};
  ProbeModule module(setup, shader, *shown);
  for (size_t i = 0; i < probes.size(); ++i) module.add(i, probes[i]);
  if (auto compiled = compileModule(setup.compile, setup.path, module.text(), setup.derived); !compiled) {
    return Failure{fmt::format("the probes do not compile: {}", compiled.error().message)};
  }
  if (auto written = writeFileAtomically(setup.path, module.text()); !written) return written.error();
  setup.scene->instances.at(setup.instance).source = setup.path;
  setup.scene->instances.at(setup.instance).shader = setup.derived;
  std::vector<std::optional<std::vector<double>>> averages(probes.size(), std::vector<double>{});
  for (const ProbeImage& image : module.images()) {
    std::optional<std::vector<double>>& average = averages[image.probe];
    if (!average) continue;
    const size_t count = std::min(kScalarsPerImage, probes[image.probe].site.scalars - image.first);
    auto mean = meanOfMarked(*setup.tuner, image.placement, count);
    if (!mean) return mean.error();
    if (!*mean || !std::all_of((*mean)->begin(), (*mean)->end(), [](double v) { return std::isfinite(v); })) {
      average.reset();
      continue;
    }
    average->insert(average->end(), (*mean)->begin(), (*mean)->end());
  }
  return averages;
}

}  // namespace spire::search
