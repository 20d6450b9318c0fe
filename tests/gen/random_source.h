// A seeded random source whose results are the same with every standard
// library: std::mt19937 is fully specified, std::uniform_*_distribution is
// not, so the mapping to ranges is written out here.
#pragma once

#include <cstdint>
#include <random>
#include <utility>
#include <vector>

namespace spire::testgen {

class RandomSource {
 public:
  explicit RandomSource(uint32_t seed) : engine_(seed) {}

  // Uniform integer in [lo, hi]; the modulo bias is irrelevant for a test
  // generator and keeps the mapping obvious.
  int pick(int lo, int hi) { return lo + static_cast<int>(engine_() % static_cast<uint32_t>(hi - lo + 1)); }
  bool chance(int percent) { return pick(0, 99) < percent; }
  uint32_t raw() { return engine_(); }

  template <typename T>
  const T& element(const std::vector<T>& items) {
    return items[static_cast<size_t>(pick(0, static_cast<int>(items.size()) - 1))];
  }

  // Fisher-Yates with our own range mapping (std::shuffle is unspecified too).
  template <typename T>
  void shuffle(std::vector<T>& items) {
    for (size_t i = items.size(); i > 1; --i) {
      std::swap(items[i - 1], items[static_cast<size_t>(pick(0, static_cast<int>(i) - 1))]);
    }
  }

 private:
  std::mt19937 engine_;
};

}  // namespace spire::testgen
