#include "explore/view_images.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace spire::explore {
namespace {

using Rgb = std::array<float, 3>;

constexpr Rgb kMagenta{1.0F, 0.0F, 1.0F};
constexpr Rgb kWhite{1.0F, 1.0F, 1.0F};
constexpr Rgb kUncovered{0.25F, 0.25F, 0.25F};

bool finitePixel(const float* p) {
  return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]) && std::isfinite(p[3]);
}

void put(measure::FloatImage& image, size_t pixel, const Rgb& rgb) {
  float* p = &image.rgba[pixel * 4];
  p[0] = rgb[0];
  p[1] = rgb[1];
  p[2] = rgb[2];
  p[3] = 1.0F;
}

// 0 black, 1/3 blue, 2/3 red, 1 yellow.
Rgb ramp(float t) {
  t = std::clamp(t, 0.0F, 1.0F) * 3.0F;
  if (t < 1.0F) return {0.0F, 0.0F, t};
  if (t < 2.0F) return {t - 1.0F, 0.0F, 2.0F - t};
  return {1.0F, t - 2.0F, 0.0F};
}

measure::FloatImage blank(const measure::FloatImage& like) {
  return {like.width, like.height, std::vector<float>(like.rgba.size(), 0.0F)};
}

}  // namespace

measure::FloatImage errorHeatMap(const measure::FloatImage& reference, const measure::FloatImage& variant,
                                 const std::vector<uint8_t>& coverage, float scale) {
  measure::FloatImage out = blank(variant);
  const size_t pixels = static_cast<size_t>(variant.width) * variant.height;
  if (reference.rgba.size() != variant.rgba.size() || variant.rgba.size() != pixels * 4) return out;
  for (size_t i = 0; i < pixels; ++i) {
    const float* r = &reference.rgba[i * 4];
    const float* v = &variant.rgba[i * 4];
    if (!finitePixel(r) || !finitePixel(v)) {
      put(out, i, kMagenta);
    } else if (i < coverage.size() && coverage[i] == 0) {
      put(out, i, kUncovered);
    } else {
      const float diff = std::max({std::abs(r[0] - v[0]), std::abs(r[1] - v[1]), std::abs(r[2] - v[2])});
      put(out, i, ramp(scale > 0.0F ? diff / scale : 0.0F));
    }
  }
  return out;
}

measure::FloatImage hazardMask(const measure::FloatImage& variant) {
  measure::FloatImage out = blank(variant);
  for (size_t i = 0; i * 4 < variant.rgba.size(); ++i) {
    const float* v = &variant.rgba[i * 4];
    if (std::isnan(v[0]) || std::isnan(v[1]) || std::isnan(v[2]) || std::isnan(v[3])) {
      put(out, i, kMagenta);
    } else if (!finitePixel(v)) {
      put(out, i, kWhite);
    } else {
      const float grey = 0.3F * std::clamp((v[0] + v[1] + v[2]) / 3.0F, 0.0F, 1.0F);
      put(out, i, {grey, grey, grey});
    }
  }
  return out;
}

measure::FloatImage splitImage(const measure::FloatImage& reference, const measure::FloatImage& variant) {
  measure::FloatImage out = variant;
  if (reference.rgba.size() != variant.rgba.size()) return out;
  const uint32_t half = variant.width / 2;
  for (uint32_t y = 0; y < variant.height; ++y) {
    for (uint32_t x = 0; x <= half && x < variant.width; ++x) {
      const size_t i = static_cast<size_t>(y) * variant.width + x;
      if (x + 1 >= half) {
        put(out, i, kWhite);  // the two-pixel line between the halves
        continue;
      }
      std::copy_n(&reference.rgba[i * 4], 4, &out.rgba[i * 4]);
    }
  }
  return out;
}

}  // namespace spire::explore
