#include "measure/image_metrics.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace spire::measure {
namespace {

enum class Hazard { None, Inf, NaN };

constexpr uint8_t kNanColor[4] = {255, 0, 255, 255};
constexpr uint8_t kInfColor[4] = {255, 255, 255, 255};

Hazard pixelHazard(const float* rgba) {
  Hazard hazard = Hazard::None;
  for (int c = 0; c < 4; ++c) {
    if (std::isnan(rgba[c])) return Hazard::NaN;
    if (std::isinf(rgba[c])) hazard = Hazard::Inf;
  }
  return hazard;
}

size_t pixelCount(const FloatImage& image) { return static_cast<size_t>(image.width) * image.height; }

bool consistent(const FloatImage& image) { return image.rgba.size() == pixelCount(image) * 4; }

// RMSE, PSNR and the infinity rule, from the sums.
void finish(ImageError& error) {
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  if (error.hasHazards()) {
    error.rmse = kInfinity;
    error.maxError = kInfinity;
    error.psnr = 0.0;
    return;
  }
  error.rmse = error.coveredPixels == 0
                   ? 0.0
                   : std::sqrt(error.sumSquaredError / (3.0 * static_cast<double>(error.coveredPixels)));
  error.psnr = error.rmse == 0.0 ? kInfinity : -20.0 * std::log10(error.rmse);
}

}  // namespace

scene::Expected<ImageError> compareImages(const FloatImage& reference, const FloatImage& test,
                                          const std::vector<uint8_t>* coverage) {
  if (reference.width != test.width || reference.height != test.height) {
    return scene::Error{fmt::format("cannot compare a {}x{} image with a {}x{} reference", test.width, test.height,
                                    reference.width, reference.height)};
  }
  if (!consistent(reference) || !consistent(test)) {
    return scene::Error{fmt::format("cannot compare images: pixel data does not match {}x{} RGBA32F", reference.width,
                                    reference.height)};
  }
  size_t pixels = pixelCount(reference);
  if (coverage != nullptr && coverage->size() != pixels) {
    return scene::Error{
        fmt::format("cannot compare images: coverage mask has {} entries for {} pixels", coverage->size(), pixels)};
  }
  ImageError error;
  for (size_t p = 0; p < pixels; ++p) {
    const float* ref = &reference.rgba[p * 4];
    const float* out = &test.rgba[p * 4];
    Hazard refHazard = pixelHazard(ref);
    Hazard outHazard = pixelHazard(out);
    error.referenceNanPixels += refHazard == Hazard::NaN ? 1 : 0;
    error.referenceInfPixels += refHazard == Hazard::Inf ? 1 : 0;
    error.nanPixels += outHazard == Hazard::NaN ? 1 : 0;
    error.infPixels += outHazard == Hazard::Inf ? 1 : 0;
    if (coverage != nullptr && (*coverage)[p] == 0) continue;
    ++error.coveredPixels;
    if (refHazard != Hazard::None || outHazard != Hazard::None) continue;
    for (int c = 0; c < 3; ++c) {
      // Double: a float difference of large values would lose the error.
      double diff = static_cast<double>(out[c]) - static_cast<double>(ref[c]);
      error.sumSquaredError += diff * diff;
      error.maxError = std::max(error.maxError, std::abs(diff));
    }
  }
  finish(error);
  return error;
}

void ErrorAccumulator::add(const ImageError& error) {
  sum_.sumSquaredError += error.sumSquaredError;
  sum_.maxError = std::max(sum_.maxError, error.maxError);
  sum_.coveredPixels += error.coveredPixels;
  sum_.nanPixels += error.nanPixels;
  sum_.infPixels += error.infPixels;
  sum_.referenceNanPixels += error.referenceNanPixels;
  sum_.referenceInfPixels += error.referenceInfPixels;
}

ImageError ErrorAccumulator::total() const {
  ImageError total = sum_;
  finish(total);
  return total;
}

uint64_t nonFinitePixels(const FloatImage& image) {
  uint64_t count = 0;
  for (size_t p = 0; p + 3 < image.rgba.size(); p += 4) count += pixelHazard(&image.rgba[p]) == Hazard::None ? 0 : 1;
  return count;
}

scene::Image opaque(scene::Image image) {
  for (size_t i = 3; i < image.bytes.size(); i += 4) image.bytes[i] = 255;
  return image;
}

scene::Image toRgba8(const FloatImage& image) {
  scene::Image out;
  if (!consistent(image)) return out;
  out.width = image.width;
  out.height = image.height;
  out.bytes.resize(image.rgba.size());
  for (size_t p = 0; p < pixelCount(image); ++p) {
    const float* in = &image.rgba[p * 4];
    uint8_t* px = &out.bytes[p * 4];
    switch (pixelHazard(in)) {
      case Hazard::NaN: std::copy_n(kNanColor, 4, px); break;
      case Hazard::Inf: std::copy_n(kInfColor, 4, px); break;
      case Hazard::None:
        for (int c = 0; c < 4; ++c) px[c] = static_cast<uint8_t>(std::lround(std::clamp(in[c], 0.0F, 1.0F) * 255.0F));
        break;
    }
  }
  return out;
}

}  // namespace spire::measure
