#include "tune/extremes.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace spire::tune {

ParameterRange numberRange(const std::string& component, const std::vector<double>& values) {
  ParameterRange range{component, {}, {}, false, {}};
  for (const double v : values) {
    const double far = std::max(1.0, 2.0 * std::abs(v));
    range.minimum.push_back(v < 0 ? -far : 0.0);
    range.maximum.push_back(v < 0 ? 0.0 : far);
  }
  return range;
}

Expected<ParameterRange, Failure> automaticTextureRange(const scene::MaterialBinding& binding,
                                                        const scene::SceneFile& scene) {
  auto own = textureRange(binding.component, binding, scene);
  if (!own) return own.error();
  ParameterRange range{binding.component, {}, {}, true, {}};
  for (size_t c = 0; c < own->minimum.size(); ++c) {
    range.minimum.push_back(std::min(0.0, own->minimum[c]));
    range.maximum.push_back(std::max(1.0, own->maximum[c]));
  }
  range.extraCorners = {{"texture-min", own->minimum}, {"texture-max", own->maximum}};
  return range;
}

Expected<std::vector<ParameterRange>, Failure> extremeRanges(const scene::InstanceDesc& instance,
                                                             const scene::SceneFile& scene,
                                                             const std::vector<ParameterRange>& explicitRanges) {
  std::vector<ParameterRange> ranges;
  for (const scene::MaterialBinding& binding : instance.material) {
    if (binding.engineValue) continue;
    const auto given = std::find_if(explicitRanges.begin(), explicitRanges.end(),
                                    [&](const ParameterRange& r) { return r.component == binding.component; });
    if (given != explicitRanges.end()) {
      ranges.push_back(*given);
    } else if (binding.texture) {
      auto range = automaticTextureRange(binding, scene);
      if (!range) return Failure{fmt::format("--extremes: {}", range.error().message)};
      ranges.push_back(std::move(range).value());
    } else {
      ranges.push_back(numberRange(binding.component, binding.numbers));
    }
  }
  return ranges;
}

SamplePlan extremeSamples(const std::vector<ParameterRange>& ranges, uint32_t randomCount, uint64_t seed) {
  SamplePlan plan;
  const auto add = [&](ParameterSample sample, std::string input, std::string kind) {
    plan.samples.push_back(std::move(sample));
    plan.labels.push_back({std::move(input), std::move(kind)});
  };
  add({}, "", "scene");
  ParameterSample low;
  ParameterSample high;
  for (const ParameterRange& r : ranges) {
    low[r.component] = r.minimum;
    high[r.component] = r.maximum;
  }
  add(low, "", "all-min");
  add(high, "", "all-max");
  for (const ParameterRange& r : ranges) {
    add({{r.component, r.minimum}}, r.component, "min");
    add({{r.component, r.maximum}}, r.component, "max");
    for (const Corner& corner : r.extraCorners) add({{r.component, corner.values}}, r.component, corner.kind);
  }
  for (ParameterSample& sample : randomSamples(ranges, randomCount, seed)) add(std::move(sample), "", "sample");
  return plan;
}

size_t extremeSampleCount(const std::vector<ParameterRange>& ranges, uint32_t randomCount) {
  size_t count = 3 + randomCount;
  for (const ParameterRange& r : ranges) count += 2 + r.extraCorners.size();
  return count;
}

}  // namespace spire::tune
