#pragma once

// Image error of a shader variant against the reference rendering, measured
// on the raw linear floats read back from the render target, so that an
// optimization's error is not hidden by 8-bit quantisation.
//
// Floating-point hazards (NaN, Inf) are never averaged away: a single
// non-finite channel anywhere in either image makes the RMSE and maximum
// error infinite and the PSNR 0.

#include "scene/expected.h"
#include "scene/texture.h"

#include <cstdint>
#include <limits>
#include <vector>

namespace spire::measure {

// RGBA32F pixels, rows top to bottom: width * height * 4 floats.
struct FloatImage {
  uint32_t width = 0;
  uint32_t height = 0;
  std::vector<float> rgba;
};

struct ImageError {
  double rmse = 0.0;                                      // over the RGB channels of covered pixels
  double psnr = std::numeric_limits<double>::infinity();  // dB, peak 1.0; infinite when rmse is 0
  double maxError = 0.0;                                  // largest absolute RGB channel difference over covered pixels
  // Kept so that errors of several views combine exactly (ErrorAccumulator).
  double sumSquaredError = 0.0;
  uint64_t coveredPixels = 0;
  // Pixels with a NaN or an Inf (either sign) in any of their four channels,
  // counted over the whole image whether covered or not; a pixel with both
  // counts as NaN.
  uint64_t nanPixels = 0;  // of the test image
  uint64_t infPixels = 0;
  uint64_t referenceNanPixels = 0;
  uint64_t referenceInfPixels = 0;

  [[nodiscard]] bool hasHazards() const { return nanPixels + infPixels + referenceNanPixels + referenceInfPixels > 0; }
};

// A pixel is covered when `coverage` (width * height bytes, or null for every
// pixel) is non-zero there; the renderer marks pixels where either image has
// depth < 1, so the background does not dilute the error. Images of different
// sizes, or a mask or pixel array of the wrong length, give an error.
scene::Expected<ImageError> compareImages(const FloatImage& reference, const FloatImage& test,
                                          const std::vector<uint8_t>* coverage);

// Combines the errors of several views of one variant: squared errors and
// pixel counts are summed, so the total RMSE is that of all covered pixels of
// all views together, not an average of per-view RMSEs.
class ErrorAccumulator {
 public:
  void add(const ImageError& error);
  [[nodiscard]] ImageError total() const;

 private:
  ImageError sum_;
};

// Pixels with a NaN or Inf in any channel, covered or not: a hazard shows
// wherever it is, also in a reference that has no image to compare with.
uint64_t nonFinitePixels(const FloatImage& image);

// For PNGs of the renderings: each channel clamped to [0, 1] and rounded to
// 8 bits (no sRGB encoding). Hazards are painted so they stand out: a pixel
// with a NaN becomes opaque magenta, one with an Inf (and no NaN) opaque white.
// An image whose pixel array does not match its size converts to an empty one.
scene::Image toRgba8(const FloatImage& image);

// `image` with alpha 255: the shader's alpha is rarely meant as
// transparency, and viewers show a translucent image washed out.
scene::Image opaque(scene::Image image);

}  // namespace spire::measure
