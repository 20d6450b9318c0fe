#include "search/average_probes.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "simplify/average_sites.h"
#include "support/file_io.h"

namespace spire::search {
namespace {

// Written into the shown value's alpha: no surface a shader draws has it,
// so the pixels that hold it are the probed shader's.
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

// A name of the derived shader's own, for a probe.
std::string uniqueName(const sem::Shader& shader, const std::string& stem) {
  std::string name = stem;
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

// What one render shows: scalars [first, first + 3) of value `value`.
struct ProbeImage {
  size_t value = 0;
  size_t first = 0;
  size_t scalars = 0;  // of the value
  Placement placement;
};

// The module the values are shown from: the setup's, with variations of
// the export that show each value, and the definitions the values need.
class ProbeModule {
 public:
  ProbeModule(const sem::Shader& shader, std::string shown) : shader_(shader), shown_(std::move(shown)) {}

  void define(const std::string& text) { definitions_ += text; }
  // Value `index`, a component of `scalars` scalars, in `placement`.
  void show(size_t index, const std::string& component, size_t scalars, const Placement& placement) {
    for (size_t first = 0; first < scalars; first += kScalarsPerImage) {
      const std::string variation = uniqueName(shader_, fmt::format("spireShow{}_{}", index + 1, first));
      definitions_ += fmt::format("    vec4 {}:{} = {};\n", shown_, variation, shownScalars(component, scalars, first));
      Placement shownIn = placement;
      for (auto& [name, where] : shownIn) {
        if (name == shown_) where = worldOf(where) + ":" + variation;
      }
      images_.push_back({index, first, scalars, std::move(shownIn)});
    }
  }
  std::string text(const std::string& module) const {
    std::string text = module;
    return text.insert(text.rfind('}'), definitions_);
  }
  const std::vector<ProbeImage>& images() const { return images_; }
  const sem::Shader& shader() const { return shader_; }

 private:
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

// The setup's module compiled, and the shader it derives.
Expected<std::unique_ptr<ShaderLibrary>, Failure> compileSetup(const ProbeSetup& setup) {
  auto library = compileModule(setup.compile, setup.path, setup.moduleText, setup.derived);
  if (!library) return library.error();
  if (!shownExport(*(*library)->model().findShader(setup.derived))) {
    return Failure{"the pipeline exports no vec4 color to show the probes in"};
  }
  return library;
}

// Renders every image of `module` and averages each value.
Expected<Averages, Failure> measure(const ProbeSetup& setup, const ProbeModule& module, size_t values) {
  const std::string text = module.text(setup.moduleText);
  if (auto compiled = compileModule(setup.compile, setup.path, text, setup.derived); !compiled) {
    return Failure{fmt::format("the probes do not compile: {}", compiled.error().message)};
  }
  if (auto written = writeFileAtomically(setup.path, text); !written) return written.error();
  setup.scene->instances.at(setup.instance).source = setup.path;
  setup.scene->instances.at(setup.instance).shader = setup.derived;
  Averages averages(values, std::vector<double>{});
  for (const ProbeImage& image : module.images()) {
    std::optional<std::vector<double>>& average = averages[image.value];
    if (!average) continue;
    const size_t count = std::min(kScalarsPerImage, image.scalars - image.first);
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

}  // namespace

Expected<Averages, Failure> measureAverages(const ProbeSetup& setup, const std::vector<AverageProbe>& probes,
                                            const Placement& placement) {
  auto library = compileSetup(setup);
  if (!library) return library.error();
  const sem::Shader& shader = *(*library)->model().findShader(setup.derived);
  ProbeModule module(shader, *shownExport(shader));
  for (size_t i = 0; i < probes.size(); ++i) {
    const AverageProbe& probe = probes[i];
    const std::string name = uniqueName(shader, fmt::format("spireAverageProbe{}", i + 1));
    module.define(fmt::format("    // the value of '{}' in {}, for its average\n    {} {} {}\n",
                              probe.site.rewrite.before, probe.component, probe.site.rewrite.type, name,
                              probe.site.probe));
    Placement withProbe = placement;
    withProbe.emplace_back(name, worldOf(probe.placement));
    module.show(i, name, probe.site.scalars, withProbe);
  }
  return measure(setup, module, probes.size());
}

Expected<Averages, Failure> measureComponents(const ProbeSetup& setup, const std::vector<ComponentValue>& values) {
  auto library = compileSetup(setup);
  if (!library) return library.error();
  const sem::Shader& shader = *(*library)->model().findShader(setup.derived);
  ProbeModule module(shader, *shownExport(shader));
  std::vector<size_t> unmeasured;
  for (size_t i = 0; i < values.size(); ++i) {
    const sem::Component* c = shader.findComponent(values[i].component);
    const std::optional<size_t> scalars =
        c && c->type ? simplify::floatScalarCount(c->type->name()) : std::optional<size_t>{};
    if (!scalars) {
      unmeasured.push_back(i);
      continue;
    }
    module.show(i, values[i].component, *scalars, values[i].placement);
  }
  auto averages = measure(setup, module, values.size());
  if (!averages) return averages.error();
  for (size_t i : unmeasured) (*averages)[i].reset();
  return averages;
}

}  // namespace spire::search
