#include "reflection/reflection.h"

#include <algorithm>
#include <charconv>

namespace spire::reflection {

std::string_view stageName(Stage stage) {
  switch (stage) {
    case Stage::Vertex: return "vertex";
    case Stage::Fragment: return "fragment";
    case Stage::Compute: return "compute";
  }
  return "unknown";
}

std::optional<Stage> parseStage(std::string_view name) {
  for (Stage stage : {Stage::Vertex, Stage::Fragment, Stage::Compute}) {
    if (stageName(stage) == name) return stage;
  }
  return std::nullopt;
}

std::string_view inputKindName(InputKind kind) {
  switch (kind) {
    case InputKind::Varying: return "varying";
    case InputKind::UniformMember: return "uniform";
    case InputKind::Sampler: return "sampler";
    case InputKind::Texture: return "texture";
    case InputKind::BufferMember: return "buffer";
    case InputKind::PushConstant: return "push";
  }
  return "unknown";
}

namespace {

std::optional<ValueType::Scalar> scalarPrefix(char c) {
  switch (c) {
    case 'i': return ValueType::Scalar::Int;
    case 'u': return ValueType::Scalar::Uint;
    case 'b': return ValueType::Scalar::Bool;
    default: return std::nullopt;
  }
}

// A scalar, vector or matrix spelling; nullopt for anything else.
std::optional<ValueType> parseNumeric(std::string_view type) {
  ValueType result;
  if (type == "float" || type == "int" || type == "uint" || type == "bool") {
    result.scalar = type == "float"  ? ValueType::Scalar::Float
                    : type == "int"  ? ValueType::Scalar::Int
                    : type == "uint" ? ValueType::Scalar::Uint
                                     : ValueType::Scalar::Bool;
    return result;
  }
  const auto digit = [](char c) -> uint32_t { return c >= '2' && c <= '4' ? static_cast<uint32_t>(c - '0') : 0; };
  if (type.size() == 4 && type.substr(0, 3) == "vec" && digit(type[3])) {
    result.rows = digit(type[3]);
    return result;
  }
  if (type.size() == 5 && type.substr(1, 3) == "vec" && digit(type[4])) {
    const auto scalar = scalarPrefix(type[0]);
    if (!scalar) return std::nullopt;
    result.scalar = *scalar;
    result.rows = digit(type[4]);
    return result;
  }
  if (type.size() == 4 && type.substr(0, 3) == "mat" && digit(type[3])) {
    result.rows = result.columns = digit(type[3]);
    return result;
  }
  if (type.size() == 6 && type.substr(0, 3) == "mat" && digit(type[3]) && type[4] == 'x' && digit(type[5])) {
    result.columns = digit(type[3]);
    result.rows = digit(type[5]);
    return result;
  }
  return std::nullopt;
}

// `element[N]` with one dimension; nullopt when `type` is not such an array.
std::optional<ValueType> parseArray(std::string_view type) {
  const size_t bracket = type.find('[');
  if (bracket == std::string_view::npos || type.back() != ']' ||
      type.find('[', bracket + 1) != std::string_view::npos) {
    return std::nullopt;
  }
  auto result = parseNumeric(type.substr(0, bracket));
  if (!result) return std::nullopt;
  const std::string_view digits = type.substr(bracket + 1, type.size() - bracket - 2);
  uint32_t length = 0;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), length);
  if (ec != std::errc{} || end != digits.data() + digits.size() || length == 0) return std::nullopt;
  result->arrayLength = length;
  return result;
}

}  // namespace

ValueType parseValueType(std::string_view glsl) {
  std::optional<ValueType> numeric = glsl.empty()         ? std::nullopt
                                     : glsl.back() == ']' ? parseArray(glsl)
                                                          : parseNumeric(glsl);
  ValueType result = numeric.value_or(ValueType{});
  if (!numeric) {
    const bool sampler = glsl.starts_with("sampler") && glsl.find('[') == std::string_view::npos;
    result.kind = sampler ? ValueType::Kind::Sampler : ValueType::Kind::Other;
  }
  result.name = std::string(glsl);
  return result;
}

const BlockMember* Block::member(std::string_view component) const {
  const auto it =
      std::find_if(members.begin(), members.end(), [&](const BlockMember& m) { return m.component == component; });
  return it == members.end() ? nullptr : &*it;
}

const std::string* KernelOutput::hint(std::string_view name) const {
  const auto it = std::find_if(hints.begin(), hints.end(), [&](const auto& h) { return h.first == name; });
  return it == hints.end() ? nullptr : &it->second;
}

void KernelOutput::setHint(std::string name, std::string value) {
  const auto it = std::find_if(hints.begin(), hints.end(), [&](const auto& h) { return h.first == name; });
  if (it != hints.end()) {
    it->second = std::move(value);
  } else {
    hints.emplace_back(std::move(name), std::move(value));
  }
}

const Block* Kernel::block(DescriptorSlot slot) const {
  const auto it = std::find_if(blocks.begin(), blocks.end(), [&](const Block& b) { return b.slot == slot; });
  return it == blocks.end() ? nullptr : &*it;
}

const HazardValue* HazardRecord::byCode(uint32_t code) const {
  const auto it = std::find_if(values.begin(), values.end(), [&](const HazardValue& v) { return v.code == code; });
  return code == 0 || it == values.end() ? nullptr : &*it;
}

const HazardValue* HazardRecord::value(std::string_view component) const {
  const auto it =
      std::find_if(values.begin(), values.end(), [&](const HazardValue& v) { return v.component == component; });
  return it == values.end() ? nullptr : &*it;
}

const Kernel* Variant::kernel(std::string_view world) const {
  const auto it = std::find_if(kernels.begin(), kernels.end(), [&](const Kernel& k) { return k.world == world; });
  return it == kernels.end() ? nullptr : &*it;
}

}  // namespace spire::reflection
