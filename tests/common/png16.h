#pragma once

// A minimal 16-bit RGBA PNG encoder for tests: stb_image_write writes 8-bit
// PNGs only, and the project has no zlib. The image data goes into stored
// (uncompressed) deflate blocks, which every PNG decoder reads, with filter 0
// on every row; the chunk CRCs and the zlib Adler-32 are computed here.

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

namespace spire::testing_util {

namespace png16_detail {

inline uint32_t crc32(std::string_view bytes) {
  static const std::array<uint32_t, 256> kTable = [] {
    std::array<uint32_t, 256> table{};
    for (uint32_t n = 0; n < 256; ++n) {
      uint32_t c = n;
      for (int k = 0; k < 8; ++k) c = (c & 1U) != 0 ? 0xEDB88320U ^ (c >> 1) : c >> 1;
      table[n] = c;
    }
    return table;
  }();
  uint32_t c = 0xFFFFFFFFU;
  for (char byte : bytes) c = kTable[(c ^ static_cast<uint8_t>(byte)) & 0xFFU] ^ (c >> 8);
  return c ^ 0xFFFFFFFFU;
}

inline void appendBigEndian(std::string& out, uint32_t value, int bytes = 4) {
  for (int shift = (bytes - 1) * 8; shift >= 0; shift -= 8) out.push_back(static_cast<char>((value >> shift) & 0xFFU));
}

inline void appendChunk(std::string& png, std::string_view type, std::string_view data) {
  appendBigEndian(png, static_cast<uint32_t>(data.size()));
  std::string typed(type);
  typed += data;
  png += typed;
  appendBigEndian(png, crc32(typed));
}

// `raw` as a zlib stream of stored deflate blocks.
inline std::string zlibStored(std::string_view raw) {
  std::string out = {'\x78', '\x01'};
  constexpr size_t kMaxBlock = 65535;
  size_t offset = 0;
  do {
    const size_t length = std::min(kMaxBlock, raw.size() - offset);
    out.push_back(offset + length == raw.size() ? '\x01' : '\x00');  // BFINAL, BTYPE 00
    const auto len = static_cast<uint16_t>(length);
    out.push_back(static_cast<char>(len & 0xFFU));
    out.push_back(static_cast<char>(len >> 8));
    out.push_back(static_cast<char>(~len & 0xFFU));
    out.push_back(static_cast<char>((~len >> 8) & 0xFFU));
    out.append(raw.substr(offset, length));
    offset += length;
  } while (offset < raw.size());
  uint32_t a = 1;
  uint32_t b = 0;
  for (char byte : raw) {
    a = (a + static_cast<uint8_t>(byte)) % 65521U;
    b = (b + a) % 65521U;
  }
  appendBigEndian(out, (b << 16) | a);
  return out;
}

}  // namespace png16_detail

// The bytes of a PNG of width x height RGBA texels, 16 bits per channel,
// `rgba` holding 4 values per texel, rows top to bottom.
inline std::string encodePng16(uint32_t width, uint32_t height, std::span<const uint16_t> rgba) {
  using namespace png16_detail;
  std::string header;
  appendBigEndian(header, width);
  appendBigEndian(header, height);
  header += {'\x10', '\x06', '\x00', '\x00', '\x00'};  // 16 bits, RGBA, deflate, filter 0, no interlace
  std::string raw;
  for (uint32_t y = 0; y < height; ++y) {
    raw.push_back('\0');  // filter type None
    for (uint32_t i = 0; i < width * 4; ++i) appendBigEndian(raw, rgba[size_t{y} * width * 4 + i], 2);
  }
  std::string png = "\x89PNG\r\n\x1a\n";
  appendChunk(png, "IHDR", header);
  appendChunk(png, "IDAT", zlibStored(raw));
  appendChunk(png, "IEND", "");
  return png;
}

}  // namespace spire::testing_util
