#include "support/content_hash.h"

#include <fmt/format.h>

#include <cstdint>

namespace spire {

std::string contentHash(std::string_view bytes) {
  uint64_t hash = 14695981039346656037ull;
  for (char c : bytes) {
    hash ^= static_cast<unsigned char>(c);
    hash *= 1099511628211ull;
  }
  return fmt::format("{:016x}", hash);
}

}  // namespace spire
