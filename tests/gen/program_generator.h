// A whole random Spire program: a random pipeline (pipeline_generator.h),
// helper functions, and shaders that use implicit and explicit overloads,
// variations, block bodies, inheritance, groups with optional members (and
// shaders derived from a group's shader), and locked worlds (`finalizes`).
// Deterministic from the seed.
#pragma once

#include <cstdint>
#include <string>

namespace spire::testgen {

struct GeneratedProgram {
  uint32_t seed = 0;
  std::string text;
};

GeneratedProgram generateProgram(uint32_t seed);

}  // namespace spire::testgen
