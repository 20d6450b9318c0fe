// A stable hash of bytes, the same on every machine and in every run: what
// kernels are keyed by (reflection::contentHash) and what a tool records of
// a file to notice that it changed.
#pragma once

#include <string>
#include <string_view>

namespace spire {

// 64-bit FNV-1a of `bytes`, as 16 hex digits.
std::string contentHash(std::string_view bytes);

}  // namespace spire
