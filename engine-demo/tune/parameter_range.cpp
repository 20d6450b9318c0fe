#include "tune/parameter_range.h"

#include <fmt/format.h>

#include "scene/pixel_format.h"
#include "scene/scene_resources.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <random>
#include <span>

namespace spire::tune {

std::vector<ParameterSample> randomSamples(const std::vector<ParameterRange>& ranges, uint32_t count, uint64_t seed) {
  std::vector<ParameterSample> samples;
  std::mt19937_64 rng(seed);
  for (uint32_t k = 0; k < count; ++k) {
    ParameterSample sample;
    for (const ParameterRange& r : ranges) {
      std::vector<double> values(r.minimum.size());
      for (size_t c = 0; c < values.size(); ++c) {
        values[c] = std::uniform_real_distribution<double>(r.minimum[c], r.maximum[c])(rng);
      }
      sample[r.component] = std::move(values);
    }
    samples.push_back(std::move(sample));
  }
  return samples;
}

std::vector<ParameterSample> parameterSamples(const std::vector<ParameterRange>& ranges, uint32_t randomCount,
                                              uint64_t seed) {
  if (ranges.empty()) return {};
  std::vector<ParameterSample> samples(2);
  for (const ParameterRange& r : ranges) {
    samples[0][r.component] = r.minimum;
    samples[1][r.component] = r.maximum;
  }
  for (ParameterSample& sample : randomSamples(ranges, randomCount, seed)) samples.push_back(std::move(sample));
  return samples;
}

// The texture's own range: per channel, its smallest and largest texel.
Expected<ParameterRange, Failure> textureRange(const std::string& text, const scene::MaterialBinding& binding,
                                               const scene::SceneFile& scene) {
  const scene::TextureDesc* desc = scene.findTexture(*binding.texture);
  if (!desc) return Failure{fmt::format("--param '{}': no texture named '{}'", text, *binding.texture)};
  auto image = scene::buildTexture(*desc, scene);
  if (!image) return Failure{fmt::format("--param '{}': texture '{}': {}", text, desc->name, image.error().message)};
  ParameterRange range{
      binding.component, std::vector<double>(4, HUGE_VAL), std::vector<double>(4, -HUGE_VAL), true, {}};
  const size_t bytes = scene::texelBytes(image->format);
  for (size_t at = 0; at + bytes <= image->bytes.size(); at += bytes) {
    const glm::vec4 texel = scene::decodeTexel(image->format, std::span(image->bytes).subspan(at, bytes));
    for (size_t c = 0; c < 4; ++c) {
      const double value = texel[static_cast<int>(c)];
      range.minimum[c] = std::min(range.minimum[c], value);
      range.maximum[c] = std::max(range.maximum[c], value);
    }
  }
  return range;
}

namespace {

const scene::MaterialBinding* findBinding(const scene::InstanceDesc& instance, const std::string& component) {
  for (const scene::MaterialBinding& binding : instance.material) {
    if (binding.component == component && !binding.engineValue) return &binding;
  }
  return nullptr;
}

}  // namespace

// Parses NAME=MIN:MAX (or a texture's NAME alone) against the instance's
// material.
Expected<ParameterRange, Failure> parseParameter(const std::string& text, const scene::InstanceDesc& instance,
                                                 const scene::SceneFile& scene) {
  const size_t equals = text.find('=');
  const scene::MaterialBinding* binding = findBinding(instance, text.substr(0, equals));
  if (!binding) {
    return Failure{fmt::format("--param '{}': the instance's material binds no numbers or texture to '{}'", text,
                               text.substr(0, equals))};
  }
  if (equals == std::string::npos) {
    if (binding->texture) return textureRange(text, *binding, scene);
    return Failure{fmt::format("--param '{}': expected NAME=MIN:MAX (only a texture has a range of its own)", text)};
  }
  const size_t colon = text.find(':', equals);
  if (colon == std::string::npos) return Failure{fmt::format("--param '{}': expected NAME=MIN:MAX", text)};
  const std::string low = text.substr(equals + 1, colon - equals - 1);
  const std::string high = text.substr(colon + 1);
  double minimum = 0.0;
  double maximum = 0.0;
  const auto [lowEnd, lowError] = std::from_chars(low.data(), low.data() + low.size(), minimum);
  const auto [highEnd, highError] = std::from_chars(high.data(), high.data() + high.size(), maximum);
  if (lowError != std::errc{} || highError != std::errc{} || lowEnd != low.data() + low.size() ||
      highEnd != high.data() + high.size() || !(minimum <= maximum)) {
    return Failure{fmt::format("--param '{}': MIN and MAX must be numbers with MIN <= MAX", text)};
  }
  const size_t arity = binding->texture ? 4 : binding->numbers.size();
  return ParameterRange{binding->component,
                        std::vector<double>(arity, minimum),
                        std::vector<double>(arity, maximum),
                        binding->texture.has_value(),
                        {}};
}

Expected<std::vector<ParameterRange>, Failure> parseParameters(const std::vector<std::string>& texts,
                                                               const scene::InstanceDesc& instance,
                                                               const scene::SceneFile& scene) {
  std::vector<ParameterRange> ranges;
  for (const std::string& text : texts) {
    auto range = parseParameter(text, instance, scene);
    if (!range) return range.error();
    ranges.push_back(std::move(*range));
  }
  return ranges;
}

}  // namespace spire::tune
