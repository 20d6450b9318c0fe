// Values of the abstract worlds that the engine itself supplies: mesh vertex
// attributes (MeshVertex) and per-frame parameters (FrameUniform), both looked
// up by component name. A shader input by another name must be bound in the
// scene file's material.
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <vulkan/vulkan.h>

#include "scene/mesh.h"

namespace spire::engine {

struct MeshAttribute {
  std::string_view component;  // vert_pos, vert_uv, vert_normal, vert_tangent
  std::string_view type;       // its GLSL type
  uint32_t offset;             // in scene::Vertex
  uint32_t components;
  VkFormat format;
};

// One row per attribute and declared type: vert_tangent may be declared vec4
// (xyz and the bitangent sign in w) or vec3 (xyz only).
std::span<const MeshAttribute> meshAttributes();
// The attribute `component` declared as `type`; with an empty `type`, its
// first row (the one with every component).
const MeshAttribute* findMeshAttribute(std::string_view component, std::string_view type = {});
// "vec4 or vec3": the types `component` may be declared with.
std::string meshAttributeTypes(std::string_view component);
// The attribute of `vertex` as numbers.
std::vector<double> attributeValue(const scene::Vertex& vertex, const MeshAttribute& attribute);

// Camera and light of one frame, in world space.
struct FrameState {
  glm::mat4 view{1.0F};
  glm::mat4 projection{1.0F};  // Vulkan clip space: y down, depth in [0, 1]
  glm::vec3 cameraPosition{0.0F};
  glm::vec3 lightDirection{0.0F, 1.0F, 0.0F};  // towards the light, normalized
  glm::vec3 lightColor{1.0F};
  float time = 0.0F;
  glm::vec2 resolution{1.0F};
};

struct SuppliedValue {
  std::string_view type;
  std::vector<double> numbers;
};

struct FrameValueInfo {
  std::string_view component;
  std::string_view type;
  std::string_view meaning;
};
// Every per-frame value, for documentation and "did you mean" notes.
std::span<const FrameValueInfo> frameValues();

// What the engine knows of one instance of an instanced draw (the "instance"
// role): values that differ between the objects one draw call renders.
struct InstanceState {
  glm::mat4 model{1.0F};
  float bakeLayer = 0.0F;  // the layer of the object's texture bakes in the draw's texture arrays
  float fade = 1.0F;       // level-of-detail transition weight (lod_policy.h): 1 fully this level
};

// Every per-instance value, for documentation and messages.
std::span<const FrameValueInfo> instanceValues();
// The per-instance value named `component`; nullopt for unknown names.
std::optional<SuppliedValue> instanceValue(std::string_view component, const InstanceState& instance);
// "matModel (mat4), ...": the names instanceValue knows.
std::string instanceValueNames();

// The per-frame value named `component` for an instance with model matrix
// `model`; model-space values (cameraPos, lightDir) are transformed so that
// shaders can light in the space of vert_pos. nullopt for unknown names.
std::optional<SuppliedValue> frameValue(std::string_view component, const FrameState& frame, const glm::mat4& model);

}  // namespace spire::engine
