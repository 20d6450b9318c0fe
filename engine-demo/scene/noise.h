#pragma once

// Deterministic value noise shared by the terrain and texture generators.
// Only integer hashing and float +,-,* are used (no libm transcendentals), so a
// fixed seed gives bit-identical results on every IEEE-754 machine.

#include <cstdint>

namespace spire::scene {

// Lattice value noise in [0, 1] with quintic interpolation (C2-continuous, so
// finite-difference normals of a heightfield built on it are smooth).
float valueNoise(float x, float y, uint32_t seed);

// Fractal Brownian motion: `octaves` layers of value noise, each at twice the
// frequency and half the amplitude, normalised back to [0, 1].
float fbm(float x, float y, uint32_t seed, uint32_t octaves);

}  // namespace spire::scene
