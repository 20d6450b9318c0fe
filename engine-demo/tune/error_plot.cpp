#include "tune/error_plot.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "measure/caption_text.h"

namespace spire::tune {

namespace {

constexpr scene::Rgba8 kAxis{40, 40, 40, 255};
constexpr scene::Rgba8 kPoint{120, 140, 170, 255};
constexpr scene::Rgba8 kFront{210, 40, 30, 255};

void put(scene::Image& image, int64_t x, int64_t y, scene::Rgba8 color) {
  if (x < 0 || y < 0 || x >= image.width || y >= image.height) return;
  const size_t i = (static_cast<size_t>(y) * image.width + static_cast<size_t>(x)) * 4;
  image.bytes[i] = color.r;
  image.bytes[i + 1] = color.g;
  image.bytes[i + 2] = color.b;
  image.bytes[i + 3] = color.a;
}

void disc(scene::Image& image, int64_t cx, int64_t cy, int64_t radius, scene::Rgba8 color) {
  for (int64_t dy = -radius; dy <= radius; ++dy) {
    for (int64_t dx = -radius; dx <= radius; ++dx) {
      if (dx * dx + dy * dy <= radius * radius) put(image, cx + dx, cy + dy, color);
    }
  }
}

void line(scene::Image& image, int64_t x0, int64_t y0, int64_t x1, int64_t y1, scene::Rgba8 color) {
  const int64_t steps = std::max({std::abs(x1 - x0), std::abs(y1 - y0), int64_t{1}});
  for (int64_t s = 0; s <= steps; ++s) {
    put(image, x0 + (x1 - x0) * s / steps, y0 + (y1 - y0) * s / steps, color);
  }
}

}  // namespace

scene::Image plotErrorAgainstTime(const std::vector<Measured>& points, const std::vector<size_t>& front, uint32_t width,
                                  uint32_t height) {
  scene::Image image;
  image.width = width;
  image.height = height;
  image.bytes.assign(size_t{width} * height * 4, 255);
  double maxTime = 0.0;
  double maxError = 0.0;
  for (const Measured& p : points) {
    if (!p.valid || !std::isfinite(p.error)) continue;
    maxTime = std::max(maxTime, p.frameMs);
    maxError = std::max(maxError, p.error);
  }
  maxTime = maxTime > 0.0 ? maxTime * 1.05 : 1.0;
  maxError = maxError > 0.0 ? maxError * 1.05 : 1.0;
  const int64_t left = 80;
  const int64_t right = width - 20;
  const int64_t top = 20;
  const int64_t bottom = height - 50;
  const auto px = [&](double ms) {
    return left + static_cast<int64_t>(std::lround(ms / maxTime * double(right - left)));
  };
  const auto py = [&](double e) {
    return bottom - static_cast<int64_t>(std::lround(e / maxError * double(bottom - top)));
  };

  line(image, left, bottom, right, bottom, kAxis);
  line(image, left, bottom, left, top, kAxis);
  for (int tick = 0; tick <= 4; ++tick) {
    const double ms = maxTime * tick / 4.0;
    const double e = maxError * tick / 4.0;
    line(image, px(ms), bottom, px(ms), bottom + 5, kAxis);
    line(image, left - 5, py(e), left, py(e), kAxis);
    measure::drawText(image, static_cast<uint32_t>(std::max<int64_t>(0, px(ms) - 12)),
                      static_cast<uint32_t>(bottom + 10), fmt::format("{:.3g}", ms), 1, kAxis);
    measure::drawText(image, 4, static_cast<uint32_t>(std::max<int64_t>(0, py(e) - 3)), fmt::format("{:.4f}", e), 1,
                      kAxis);
  }
  measure::drawText(image, static_cast<uint32_t>((left + right) / 2 - 40), height - 18, "frame ms", 2, kAxis);
  measure::drawText(image, static_cast<uint32_t>(left + 10), static_cast<uint32_t>(top), "RMSE", 2, kAxis);

  for (const Measured& p : points) {
    if (p.valid && std::isfinite(p.error)) disc(image, px(p.frameMs), py(p.error), 3, kPoint);
  }
  for (size_t i = 1; i < front.size(); ++i) {
    const Measured& a = points[front[i - 1]];
    const Measured& b = points[front[i]];
    line(image, px(a.frameMs), py(a.error), px(b.frameMs), py(b.error), kFront);
  }
  for (size_t i : front) disc(image, px(points[i].frameMs), py(points[i].error), 5, kFront);
  return image;
}

}  // namespace spire::tune
