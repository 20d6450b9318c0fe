#include "renderer/vertex_inputs.h"

#include <fmt/format.h>

#include <array>

#include "renderer/supplied_values.h"
#include "renderer/world_roles.h"

namespace spire::engine {

namespace {

constexpr uint32_t kMeshBinding = 0;
constexpr uint32_t kVertexBakeBinding = 1;

Error unsupplied(const KernelProgram& kernel, const KernelInput& input, std::string_view why) {
  return Error{fmt::format("the {} kernel reads '{}' ({} from {}) as a vertex input, but {}", kernel.world,
                           input.component, input.type.name, input.from, why),
               {},
               {}};
}

Expected<VertexInputs::Attribute> meshAttribute(const KernelProgram& kernel, const KernelInput& input) {
  const MeshAttribute* attribute = findMeshAttribute(input.component, input.type.name);
  if (!attribute) return unsupplied(kernel, input, "it is not a mesh attribute of that type");
  return VertexInputs::Attribute{input.location, kMeshBinding, attribute->format, attribute->offset};
}

// The vertex format that holds one `type` (float, int and uint scalars and
// vectors), or nullopt: GLSL has no bool inputs, and a matrix input would
// take one location per column.
std::optional<VkFormat> vertexFormat(const ValueType& type) {
  if (!type.isNumeric() || type.isMatrix() || type.arrayLength != 0 || type.rows < 1 || type.rows > 4) {
    return std::nullopt;
  }
  using Formats = std::array<VkFormat, 4>;
  static constexpr Formats kFloat = {VK_FORMAT_R32_SFLOAT, VK_FORMAT_R32G32_SFLOAT, VK_FORMAT_R32G32B32_SFLOAT,
                                     VK_FORMAT_R32G32B32A32_SFLOAT};
  static constexpr Formats kInt = {VK_FORMAT_R32_SINT, VK_FORMAT_R32G32_SINT, VK_FORMAT_R32G32B32_SINT,
                                   VK_FORMAT_R32G32B32A32_SINT};
  static constexpr Formats kUint = {VK_FORMAT_R32_UINT, VK_FORMAT_R32G32_UINT, VK_FORMAT_R32G32B32_UINT,
                                    VK_FORMAT_R32G32B32A32_UINT};
  switch (type.scalar) {
    case ValueType::Scalar::Float: return kFloat[type.rows - 1];
    case ValueType::Scalar::Int: return kInt[type.rows - 1];
    case ValueType::Scalar::Uint: return kUint[type.rows - 1];
    case ValueType::Scalar::Bool: return std::nullopt;
  }
  return std::nullopt;
}

Expected<VertexInputs::Attribute> bakedAttribute(const KernelProgram& kernel, const KernelInput& input,
                                                 const VertexBakeResult* bake) {
  if (!bake) return unsupplied(kernel, input, "no vertex bake ran before it");
  const BlockMember* member = bake->layout.member(input.component);
  if (!member) return unsupplied(kernel, input, "the vertex bake's records do not hold it");
  if (member->type != input.type) {
    return unsupplied(kernel, input, fmt::format("the vertex bake writes it as {}", member->type.name));
  }
  const auto format = vertexFormat(input.type);
  if (!format) return unsupplied(kernel, input, "the engine binds only scalar and vector vertex inputs");
  return VertexInputs::Attribute{input.location, kVertexBakeBinding, *format, member->offset};
}

}  // namespace

void VertexInputs::addMeshAttribute(uint32_t location, VkFormat format, uint32_t offset) {
  attributes.push_back({location, kMeshBinding, format, offset});
}

void VertexInputs::applyTo(vk::GraphicsPipelineBuilder& builder) const {
  for (const Binding& b : bindings) builder.vertexBinding(b.binding, b.stride);
  for (const Attribute& a : attributes) builder.vertexAttribute(a.location, a.binding, a.format, a.offset);
}

void VertexInputs::bind(VkCommandBuffer cmd) const {
  for (const Binding& b : bindings) {
    const VkDeviceSize offset = 0;
    vkCmdBindVertexBuffers(cmd, b.binding, 1, &b.buffer, &offset);
  }
}

Expected<VertexInputs> vertexInputs(const KernelProgram& kernel, const BindingSources& sources) {
  if (!sources.mesh) return Error{fmt::format("the {} kernel is drawn without a mesh", kernel.world), {}, {}};
  VertexInputs inputs;
  inputs.bindings.push_back({kMeshBinding, sizeof(scene::Vertex), sources.mesh->vertices.handle()});
  bool readsBake = false;
  for (const KernelInput& input : kernel.inputs) {
    if (input.kind != InputKind::Varying) continue;
    const WorldPass* pass = kernel.sourcePass(input);
    const WorldRole role = pass ? pass->kind : WorldRole::MaterialParameters;
    Expected<VertexInputs::Attribute> attribute =
        role == WorldRole::MeshAttributes ? meshAttribute(kernel, input)
        : role == WorldRole::VertexBake   ? bakedAttribute(kernel, input, sources.vertexBake)
                                        : unsupplied(kernel, input, "its world is neither the mesh nor a vertex bake");
    if (!attribute) return attribute.error();
    readsBake = readsBake || attribute->binding == kVertexBakeBinding;
    inputs.attributes.push_back(*attribute);
  }
  if (readsBake) {
    inputs.bindings.push_back(
        {kVertexBakeBinding, sources.vertexBake->layout.recordStride, sources.vertexBake->buffer->handle()});
  }
  return inputs;
}

}  // namespace spire::engine
