#include "tune/parameter_range.h"

#include <fmt/format.h>

#include <charconv>
#include <random>

namespace spire::tune {

// Parameter samples as in Pellacini 2005: every parameter at its minimum,
// every one at its maximum, then `randomSamples` uniform draws (seeded, so
// workers and reruns agree).
std::vector<ParameterSample> parameterSamples(const std::vector<ParameterRange>& ranges, uint32_t randomSamples,
                                              uint64_t seed) {
  if (ranges.empty()) return {};
  std::vector<ParameterSample> samples(2);
  for (const ParameterRange& r : ranges) {
    samples[0][r.component] = std::vector<double>(r.arity, r.minimum);
    samples[1][r.component] = std::vector<double>(r.arity, r.maximum);
  }
  std::mt19937_64 rng(seed);
  for (uint32_t k = 0; k < randomSamples; ++k) {
    ParameterSample sample;
    for (const ParameterRange& r : ranges) {
      std::uniform_real_distribution<double> draw(r.minimum, r.maximum);
      std::vector<double> values(r.arity);
      for (double& v : values) v = draw(rng);
      sample[r.component] = std::move(values);
    }
    samples.push_back(std::move(sample));
  }
  return samples;
}

// Parses NAME=MIN:MAX against the instance's material, which gives the
// value's arity (every component of a vector gets the same range).
Expected<ParameterRange, Failure> parseParameter(const std::string& text, const scene::InstanceDesc& instance) {
  const size_t equals = text.find('=');
  const size_t colon = text.find(':', equals == std::string::npos ? 0 : equals);
  ParameterRange range;
  if (equals == std::string::npos || colon == std::string::npos) {
    return Failure{fmt::format("--param '{}': expected NAME=MIN:MAX", text)};
  }
  range.component = text.substr(0, equals);
  const std::string low = text.substr(equals + 1, colon - equals - 1);
  const std::string high = text.substr(colon + 1);
  const auto [lowEnd, lowError] = std::from_chars(low.data(), low.data() + low.size(), range.minimum);
  const auto [highEnd, highError] = std::from_chars(high.data(), high.data() + high.size(), range.maximum);
  if (lowError != std::errc{} || highError != std::errc{} || lowEnd != low.data() + low.size() ||
      highEnd != high.data() + high.size() || !(range.minimum <= range.maximum)) {
    return Failure{fmt::format("--param '{}': MIN and MAX must be numbers with MIN <= MAX", text)};
  }
  for (const scene::MaterialBinding& binding : instance.material) {
    if (binding.component != range.component || binding.engineValue) continue;
    range.texture = binding.texture.has_value();
    range.arity = range.texture ? 4 : binding.numbers.size();
    return range;
  }
  return Failure{
      fmt::format("--param '{}': the instance's material binds no numbers or texture to '{}'", text, range.component)};
}

}  // namespace spire::tune
