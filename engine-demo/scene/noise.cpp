#include "scene/noise.h"

#include <cmath>

namespace spire::scene {
namespace {

// Integer avalanche hash (lowbias32 finaliser by Chris Wellons): cheap and
// well distributed, and unlike std::hash its result is specified everywhere.
uint32_t hash(uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352dU;
  x ^= x >> 15;
  x *= 0x846ca68bU;
  x ^= x >> 16;
  return x;
}

float latticeValue(int32_t ix, int32_t iy, uint32_t seed) {
  uint32_t h = hash(static_cast<uint32_t>(ix) ^ hash(static_cast<uint32_t>(iy) ^ hash(seed)));
  // Top 24 bits are exactly representable as a float.
  return static_cast<float>(h >> 8) * (1.0f / 16777215.0f);
}

float quintic(float t) { return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f); }

float lerp(float a, float b, float t) { return a + (b - a) * t; }

}  // namespace

float valueNoise(float x, float y, uint32_t seed) {
  float fx = std::floor(x);
  float fy = std::floor(y);
  auto ix = static_cast<int32_t>(fx);
  auto iy = static_cast<int32_t>(fy);
  float tx = quintic(x - fx);
  float ty = quintic(y - fy);
  float bottom = lerp(latticeValue(ix, iy, seed), latticeValue(ix + 1, iy, seed), tx);
  float top = lerp(latticeValue(ix, iy + 1, seed), latticeValue(ix + 1, iy + 1, seed), tx);
  return lerp(bottom, top, ty);
}

float fbm(float x, float y, uint32_t seed, uint32_t octaves) {
  float sum = 0.0f;
  float amplitude = 1.0f;
  float total = 0.0f;
  for (uint32_t octave = 0; octave < octaves; ++octave) {
    // A distinct seed per octave avoids visible correlation at the origin.
    sum += amplitude * valueNoise(x, y, seed + octave * 0x9e3779b9U);
    total += amplitude;
    x *= 2.0f;
    y *= 2.0f;
    amplitude *= 0.5f;
  }
  return total > 0.0f ? sum / total : 0.0f;
}

}  // namespace spire::scene
