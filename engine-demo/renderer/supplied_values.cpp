#include "renderer/supplied_values.h"

#include <fmt/format.h>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstring>

namespace spire::engine {

namespace {

constexpr std::array kMeshAttributes = {
    MeshAttribute{"vert_pos", "vec3", offsetof(scene::Vertex, position), 3, VK_FORMAT_R32G32B32_SFLOAT},
    MeshAttribute{"vert_uv", "vec2", offsetof(scene::Vertex, uv), 2, VK_FORMAT_R32G32_SFLOAT},
    MeshAttribute{"vert_normal", "vec3", offsetof(scene::Vertex, normal), 3, VK_FORMAT_R32G32B32_SFLOAT},
    MeshAttribute{"vert_tangent", "vec4", offsetof(scene::Vertex, tangent), 4, VK_FORMAT_R32G32B32A32_SFLOAT},
    MeshAttribute{"vert_tangent", "vec3", offsetof(scene::Vertex, tangent), 3, VK_FORMAT_R32G32B32_SFLOAT},
};

constexpr std::array kFrameValues = {
    FrameValueInfo{"matMVP", "mat4", "projection * view * model"},
    FrameValueInfo{"matModel", "mat4", "model to world"},
    FrameValueInfo{"matView", "mat4", "world to view"},
    FrameValueInfo{"matProj", "mat4", "view to Vulkan clip space"},
    FrameValueInfo{"matViewProj", "mat4", "projection * view"},
    FrameValueInfo{"matNormal", "mat3", "inverse transpose of the model matrix's upper 3x3"},
    FrameValueInfo{"cameraPos", "vec3", "the eye in model space"},
    FrameValueInfo{"cameraPosWorld", "vec3", "the eye in world space"},
    FrameValueInfo{"lightDir", "vec3", "unit vector towards the light, model space"},
    FrameValueInfo{"lightDirWorld", "vec3", "unit vector towards the light, world space"},
    FrameValueInfo{"lightColor", "vec3", "light color"},
    FrameValueInfo{"time", "float", "seconds since the first frame"},
    FrameValueInfo{"resolution", "vec2", "render target size in pixels"},
};

template <class M>
std::vector<double> flatten(const M& m) {
  std::vector<double> numbers;
  for (int c = 0; c < M::length(); ++c) {
    for (int r = 0; r < M::col_type::length(); ++r) numbers.push_back(m[c][r]);
  }
  return numbers;
}

std::vector<double> flattenVector(const glm::vec3& v) { return {v.x, v.y, v.z}; }

}  // namespace

std::span<const MeshAttribute> meshAttributes() { return kMeshAttributes; }

const MeshAttribute* findMeshAttribute(std::string_view component, std::string_view type) {
  const auto it = std::find_if(kMeshAttributes.begin(), kMeshAttributes.end(), [&](const MeshAttribute& a) {
    return a.component == component && (type.empty() || a.type == type);
  });
  return it == kMeshAttributes.end() ? nullptr : &*it;
}

std::string meshAttributeTypes(std::string_view component) {
  std::string types;
  for (const MeshAttribute& a : kMeshAttributes) {
    if (a.component == component) types += fmt::format("{}{}", types.empty() ? "" : " or ", a.type);
  }
  return types;
}

std::vector<double> attributeValue(const scene::Vertex& vertex, const MeshAttribute& attribute) {
  std::array<float, 4> floats{};
  std::memcpy(floats.data(), reinterpret_cast<const std::byte*>(&vertex) + attribute.offset,
              attribute.components * sizeof(float));
  return {floats.begin(), floats.begin() + attribute.components};
}

std::span<const FrameValueInfo> frameValues() { return kFrameValues; }

std::optional<SuppliedValue> frameValue(std::string_view component, const FrameState& frame, const glm::mat4& model) {
  const auto info = std::find_if(kFrameValues.begin(), kFrameValues.end(),
                                 [&](const FrameValueInfo& v) { return v.component == component; });
  if (info == kFrameValues.end()) return std::nullopt;
  const glm::mat4 modelInverse = glm::inverse(model);
  std::vector<double> numbers;
  if (component == "matMVP")
    numbers = flatten(frame.projection * frame.view * model);
  else if (component == "matModel")
    numbers = flatten(model);
  else if (component == "matView")
    numbers = flatten(frame.view);
  else if (component == "matProj")
    numbers = flatten(frame.projection);
  else if (component == "matViewProj")
    numbers = flatten(frame.projection * frame.view);
  else if (component == "matNormal")
    numbers = flatten(glm::transpose(glm::mat3(modelInverse)));
  else if (component == "cameraPos")
    numbers = flattenVector(glm::vec3(modelInverse * glm::vec4(frame.cameraPosition, 1.0F)));
  else if (component == "cameraPosWorld")
    numbers = flattenVector(frame.cameraPosition);
  else if (component == "lightDir")
    numbers = flattenVector(glm::normalize(glm::mat3(modelInverse) * frame.lightDirection));
  else if (component == "lightDirWorld")
    numbers = flattenVector(frame.lightDirection);
  else if (component == "lightColor")
    numbers = flattenVector(frame.lightColor);
  else if (component == "time")
    numbers = {frame.time};
  else
    numbers = {frame.resolution.x, frame.resolution.y};
  return SuppliedValue{info->type, std::move(numbers)};
}

namespace {

constexpr std::array kInstanceValues = {
    FrameValueInfo{"matModel", "mat4", "model to world, the instance's transform"},
    FrameValueInfo{"bakeLayer", "float", "the layer of the instance's texture bakes in the draw's texture arrays"},
    FrameValueInfo{"lodFade", "float",
                   "level-of-detail transition weight: 1 opaque; f in (0, 1) while the instance fades into this "
                   "level, drawn blended with weight f over the level it leaves"},
};

}  // namespace

std::span<const FrameValueInfo> instanceValues() { return kInstanceValues; }

std::optional<SuppliedValue> instanceValue(std::string_view component, const InstanceState& instance) {
  if (component == "matModel") return SuppliedValue{"mat4", flatten(instance.model)};
  if (component == "bakeLayer") return SuppliedValue{"float", {instance.bakeLayer}};
  if (component == "lodFade") return SuppliedValue{"float", {instance.fade}};
  return std::nullopt;
}

std::string instanceValueNames() {
  std::string text;
  for (const FrameValueInfo& v : kInstanceValues) {
    text += fmt::format("{}{} ({})", text.empty() ? "" : ", ", v.component, v.type);
  }
  return text;
}

}  // namespace spire::engine
