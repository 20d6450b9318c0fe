// reflection.json (docs/reflection.md, docs/reflection.schema.json): the one
// writer and the one reader of the typed reflection records.
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <string_view>

#include "reflection/reflection.h"
#include "support/expected.h"

namespace spire::reflection {

inline constexpr int kFormatVersion = 4;

nlohmann::ordered_json toJson(const Kernel& kernel);
nlohmann::ordered_json toJson(const Variant& variant);

// A kernel's content key: the hash of its GLSL text and its interface (world,
// stage, inputs, outputs, blocks). Kernels with equal keys are
// interchangeable: two kernels with one text could still be fed from
// different worlds, and then one binding would not serve both.
std::string kernelKey(std::string_view glsl, const Kernel& kernel);

// Reads a reflection document. Anything malformed (a missing or mistyped
// field, an unknown kind or stage, a descriptor index out of range) is an
// error naming the kernel and the entry.
Expected<Variant, std::string> fromJson(const nlohmann::ordered_json& document);
// The same from text, which must be one JSON document.
Expected<Variant, std::string> parseReflection(std::string_view text);

}  // namespace spire::reflection
