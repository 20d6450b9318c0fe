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
// One marked pixel in this many is kept in a value's profile: enough to
// compare two values, a sixteenth of the memory.
constexpr uint64_t kProfileStride = 16;

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

// The marked pixels' first `count` channels in the images of `placement`:
// their sums, their number, and every kProfileStride-th one.
struct MarkedPixels {
  std::vector<double> sum;
  uint64_t count = 0;
  std::vector<float> sampled;
};

Expected<MarkedPixels, Failure> markedPixels(tune::Tuner& tuner, const Placement& placement, size_t count) {
  tune::TunePoint point;
  point.decisions = {placement.begin(), placement.end()};
  MarkedPixels marked;
  marked.sum.assign(count, 0.0);
  auto ok = tuner.forEachCapture(point, [&](const engine::Capture& capture) {
    for (size_t i = 0; i < capture.coverage.size(); ++i) {
      const float* rgba = &capture.color.rgba[i * 4];
      if (!capture.coverage[i] || rgba[3] != kProbeMark) continue;
      const bool sampled = marked.count++ % kProfileStride == 0;
      for (size_t c = 0; c < count; ++c) {
        marked.sum[c] += rgba[c];
        if (sampled) marked.sampled.push_back(rgba[c]);
      }
    }
  });
  if (!ok) return Failure{ok.error().message};
  return marked;
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

// Renders every image of `module`: each value's average and profile.
Expected<std::vector<ValueProfile>, Failure> measure(const ProbeSetup& setup, const ProbeModule& module,
                                                     size_t values) {
  const std::string text = module.text(setup.moduleText);
  if (auto compiled = compileModule(setup.compile, setup.path, text, setup.derived); !compiled) {
    return Failure{fmt::format("the probes do not compile: {}", compiled.error().message)};
  }
  if (auto written = writeFileAtomically(setup.path, text); !written) return written.error();
  setup.scene->instances.at(setup.instance).source = setup.path;
  setup.scene->instances.at(setup.instance).shader = setup.derived;
  std::vector<ValueProfile> measured(values, ValueProfile{std::vector<double>{}, {}});
  for (const ProbeImage& image : module.images()) {
    ValueProfile& value = measured[image.value];
    if (!value.average) continue;
    const size_t count = std::min(kScalarsPerImage, image.scalars - image.first);
    auto marked = markedPixels(*setup.tuner, image.placement, count);
    if (!marked) return marked.error();
    for (double& s : marked->sum) s /= static_cast<double>(std::max<uint64_t>(marked->count, 1));
    if (marked->count == 0 ||
        !std::all_of(marked->sum.begin(), marked->sum.end(), [](double v) { return std::isfinite(v); })) {
      value.average.reset();
      continue;
    }
    value.average->insert(value.average->end(), marked->sum.begin(), marked->sum.end());
    value.profile.insert(value.profile.end(), marked->sampled.begin(), marked->sampled.end());
  }
  return measured;
}

Averages averagesOf(const std::vector<ValueProfile>& measured) {
  Averages averages;
  for (const ValueProfile& value : measured) averages.push_back(value.average);
  return averages;
}

// Each probe's subtree as a component of the module, shown in `placement`.
void showProbes(ProbeModule& module, const std::vector<AverageProbe>& probes, const Placement& placement) {
  for (size_t i = 0; i < probes.size(); ++i) {
    const AverageProbe& probe = probes[i];
    const std::string name = uniqueName(module.shader(), fmt::format("spireAverageProbe{}", i + 1));
    module.define(fmt::format("    // the value of '{}' in {}, for its average\n    {} {} {}\n",
                              probe.site.rewrite.before, probe.component, probe.site.rewrite.type, name,
                              probe.site.probe));
    Placement withProbe = placement;
    withProbe.emplace_back(name, worldOf(probe.placement));
    module.show(i, name, probe.site.scalars, withProbe);
  }
}

// Each component of `values` shown, as values `first` on; false for one
// whose type cannot be averaged.
std::vector<bool> showComponents(ProbeModule& module, const std::vector<ComponentValue>& values, size_t first) {
  std::vector<bool> shown;
  for (size_t i = 0; i < values.size(); ++i) {
    const sem::Component* c = module.shader().findComponent(values[i].component);
    const std::optional<size_t> scalars =
        c && c->type ? simplify::floatScalarCount(c->type->name()) : std::optional<size_t>{};
    shown.push_back(scalars.has_value());
    if (scalars) module.show(first + i, values[i].component, *scalars, values[i].placement);
  }
  return shown;
}

}  // namespace

Expected<Averages, Failure> measureComponents(const ProbeSetup& setup, const std::vector<ComponentValue>& values) {
  auto profiles = profileValues(setup, {}, values, {});
  if (!profiles) return profiles.error();
  return averagesOf(*profiles);
}

Expected<std::vector<ValueProfile>, Failure> profileValues(const ProbeSetup& setup,
                                                           const std::vector<AverageProbe>& probes,
                                                           const std::vector<ComponentValue>& components,
                                                           const Placement& placement) {
  auto library = compileSetup(setup);
  if (!library) return library.error();
  const sem::Shader& shader = *(*library)->model().findShader(setup.derived);
  ProbeModule module(shader, *shownExport(shader));
  showProbes(module, probes, placement);
  const std::vector<bool> shown = showComponents(module, components, probes.size());
  auto measured = measure(setup, module, probes.size() + components.size());
  if (!measured) return measured.error();
  for (size_t i = 0; i < shown.size(); ++i) {
    if (!shown[i]) (*measured)[probes.size() + i] = {};
  }
  return measured;
}

}  // namespace spire::search
