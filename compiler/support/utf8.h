// UTF-8 validation shared by the lexer (stray characters must be quoted in
// diagnostics without producing invalid text) and the module loader (E1103).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>

namespace spire::utf8 {

// The length of the well-formed UTF-8 sequence starting at `pos`, or 0 if the
// bytes there are not one (stray continuation byte, truncated or overlong
// sequence, surrogate, or a code point above U+10FFFF).
inline size_t sequenceLength(std::string_view text, size_t pos) {
  const auto byte = [&](size_t i) { return static_cast<uint8_t>(text[i]); };
  const uint8_t lead = byte(pos);
  if (lead < 0x80) return 1;
  size_t length = 0;
  uint32_t codePoint = 0;
  if ((lead & 0xE0) == 0xC0) {
    length = 2;
    codePoint = lead & 0x1Fu;
  } else if ((lead & 0xF0) == 0xE0) {
    length = 3;
    codePoint = lead & 0x0Fu;
  } else if ((lead & 0xF8) == 0xF0) {
    length = 4;
    codePoint = lead & 0x07u;
  } else {
    return 0;
  }
  if (pos + length > text.size()) return 0;
  for (size_t i = 1; i < length; ++i) {
    if ((byte(pos + i) & 0xC0) != 0x80) return 0;
    codePoint = (codePoint << 6) | (byte(pos + i) & 0x3Fu);
  }
  constexpr uint32_t kMinForLength[] = {0, 0, 0x80, 0x800, 0x10000};
  if (codePoint < kMinForLength[length] || codePoint > 0x10FFFF) return 0;
  if (codePoint >= 0xD800 && codePoint <= 0xDFFF) return 0;
  return length;
}

// The offset of the first byte that is not part of well-formed UTF-8, or
// npos when the whole text is valid.
inline size_t firstInvalidByte(std::string_view text) {
  for (size_t pos = 0; pos < text.size();) {
    const size_t length = sequenceLength(text, pos);
    if (length == 0) return pos;
    pos += length;
  }
  return std::string_view::npos;
}

}  // namespace spire::utf8
