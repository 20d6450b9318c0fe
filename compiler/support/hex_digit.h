// The value of one hexadecimal digit, for the readers that decode escapes:
// JSON's \uXXXX and the percent-encoding of URIs.
#pragma once

#include <cstdint>
#include <optional>

namespace spire {

constexpr std::optional<uint32_t> hexDigitValue(char c) {
  if (c >= '0' && c <= '9') return static_cast<uint32_t>(c - '0');
  if (c >= 'a' && c <= 'f') return static_cast<uint32_t>(c - 'a' + 10);
  if (c >= 'A' && c <= 'F') return static_cast<uint32_t>(c - 'A' + 10);
  return std::nullopt;
}

}  // namespace spire
