#include "renderer/kernel_bindings.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstring>

#include "renderer/world_roles.h"

namespace spire::engine {

namespace {

VkShaderStageFlags stageFlags(codegen::ShaderStage stage) {
  switch (stage) {
    case codegen::ShaderStage::Vertex: return VK_SHADER_STAGE_VERTEX_BIT;
    case codegen::ShaderStage::Fragment: return VK_SHADER_STAGE_FRAGMENT_BIT;
    case codegen::ShaderStage::Compute: return VK_SHADER_STAGE_COMPUTE_BIT;
  }
  return VK_SHADER_STAGE_ALL;
}

std::span<std::byte> bytesOf(const vk::Buffer& buffer) {
  return {static_cast<std::byte*>(buffer.mapped()), static_cast<size_t>(buffer.size())};
}

Error missing(const KernelProgram& kernel, const KernelInput& input, std::string_view what) {
  return Error{fmt::format("the {} kernel's input '{}' ({} from {}) has no value: {}", kernel.world, input.component,
                           input.type.name, input.from, what),
               {},
               {}};
}

WorldRole roleOf(const KernelProgram& kernel, const KernelInput& input) {
  // resolveMaterial rejected unknown worlds before any kernel is bound.
  return kernel.sourceRole(input).value_or(WorldRole::MaterialParameters);
}

class KernelBinder {
 public:
  KernelBinder(const vk::Context& ctx, const KernelProgram& kernel, const BindingSources& sources)
      : ctx_(ctx), kernel_(kernel), sources_(sources) {
    bound_.world = kernel.world;
    bound_.stage = stageFlags(kernel.stage);
  }

  Expected<BoundKernel> bind() {
    for (const Block& block : kernel_.blocks) {
      auto result = block.storage ? bindStorage(block) : bindUniform(block);
      if (!result) return result.error();
    }
    for (const KernelInput& input : kernel_.inputs) {
      if (input.kind != InputKind::Sampler && input.kind != InputKind::Texture) continue;
      auto result = bindImage(input);
      if (!result) return result.error();
    }
    if (kernel_.hazards) {
      if (auto result = bindHazardRecord(*kernel_.hazards); !result) return result.error();
    }
    return std::move(bound_);
  }

 private:
  Expected<vk::Buffer*> newBuffer(VkDeviceSize size, VkBufferUsageFlags usage) {
    auto buffer = vk::Buffer::create(ctx_, std::max<VkDeviceSize>(size, 16), usage);
    if (!buffer) return Error::fromVk(buffer.error());
    std::memset(buffer->mapped(), 0, static_cast<size_t>(buffer->size()));
    bound_.buffers.push_back(std::make_unique<vk::Buffer>(std::move(buffer).value()));
    return bound_.buffers.back().get();
  }

  Expected<void> bindUniform(const Block& block) {
    auto buffer = newBuffer(block.size, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
    if (!buffer) return buffer.error();
    for (const KernelInput& input : kernel_.inputs) {
      if (input.kind != InputKind::UniformMember || input.slot != block.slot) continue;
      const BlockMember* member = block.member(input.component);
      if (!member || !member->type.isNumeric()) {
        return missing(kernel_, input, "its block member or type is not in the reflection");
      }
      const MaterialValue* bound = materialValue(input.component);
      const WorldRole role = roleOf(kernel_, input);
      if (role == WorldRole::FrameParameters && !bound) {
        bound_.frameWrites.push_back({*buffer, *member, input.component});
        continue;
      }
      if (bound && !bound->engineValue.empty()) {
        bound_.frameWrites.push_back({*buffer, *member, bound->engineValue});
        continue;
      }
      if (role == WorldRole::UniformBake) {
        const std::vector<double>* baked = bakedUniform(input.component);
        if (!baked) return missing(kernel_, input, "the uniform bake did not produce it");
        writeValue(bytesOf(**buffer), *member, *baked);
        continue;
      }
      if (!bound) return missing(kernel_, input, "not bound in the material");
      writeValue(bytesOf(**buffer), *member, bound->numbers);
    }
    bound_.descriptors.push_back({block.slot, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, (*buffer)->handle(), VK_NULL_HANDLE,
                                  VK_NULL_HANDLE, fmt::format("uniform block '{}'", block.name)});
    return {};
  }

  const std::vector<double>* bakedUniform(const std::string& component) const {
    if (!sources_.uniformBake) return nullptr;
    const auto it = sources_.uniformBake->values.find(component);
    return it == sources_.uniformBake->values.end() ? nullptr : &it->second;
  }

  const MaterialValue* materialValue(const std::string& component) const {
    if (!sources_.material) return nullptr;
    const auto it = sources_.material->find(component);
    return it == sources_.material->end() ? nullptr : &it->second;
  }

  bool readPerInstance(const Block& block) const {
    return std::any_of(kernel_.inputs.begin(), kernel_.inputs.end(), [&](const KernelInput& input) {
      return input.kind == InputKind::BufferMember && input.slot == block.slot && input.index == "gl_InstanceIndex";
    });
  }

  Expected<void> bindInstanceBlock(const Block& block) {
    const uint32_t capacity = std::max(sources_.instanceCapacity, 1U);
    auto buffer = newBuffer(VkDeviceSize{capacity} * block.recordStride, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    if (!buffer) return buffer.error();
    InstanceBlock records{*buffer, block.recordStride, capacity, {}};
    for (const KernelInput& input : kernel_.inputs) {
      if (input.kind != InputKind::BufferMember || input.slot != block.slot) continue;
      const BlockMember* member = block.member(input.component);
      if (!member || !member->type.isNumeric()) {
        return missing(kernel_, input, "its record member or type is not in the reflection");
      }
      const bool baked = roleOf(kernel_, input) == WorldRole::UniformBake;
      if (baked && !bakedUniform(input.component))
        return missing(kernel_, input, "the uniform bake did not produce it");
      records.fields.push_back({*member, input.component, baked});
    }
    for (uint32_t i = 0; i < capacity; ++i) writeInstanceRecord(records, i, InstanceState{}, sources_.uniformBake);
    bound_.instanceBlocks.push_back(std::move(records));
    bound_.descriptors.push_back({block.slot, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, (*buffer)->handle(), VK_NULL_HANDLE,
                                  VK_NULL_HANDLE, fmt::format("per-instance storage block '{}'", block.name)});
    return {};
  }

  Expected<void> bindStorage(const Block& block) {
    if (readPerInstance(block)) return bindInstanceBlock(block);
    if (!sources_.recordVertices())
      return Error{fmt::format("the {} kernel reads vertex records but has no mesh", kernel_.world), {}, {}};
    const auto records = static_cast<uint32_t>(sources_.recordVertices()->size());
    const bool written = std::any_of(kernel_.outputs.begin(), kernel_.outputs.end(), [&](const KernelOutput& o) {
      return o.kind == OutputKind::BufferMember && o.slot == block.slot;
    });
    // A vertex bake's records may later be bound as vertex data (vertex_inputs.h).
    VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    if (written) usage |= VK_BUFFER_USAGE_VERTEX_BUFFER_BIT;
    auto buffer = newBuffer(VkDeviceSize{records} * block.recordStride, usage);
    if (!buffer) return buffer.error();
    if (written) {
      bound_.outputs[block.slot] = *buffer;
    } else {
      for (const KernelInput& input : kernel_.inputs) {
        if (input.kind != InputKind::BufferMember || input.slot != block.slot) continue;
        auto filled = fillRecords(**buffer, block, input, records);
        if (!filled) return filled.error();
      }
    }
    bound_.descriptors.push_back({block.slot, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, (*buffer)->handle(), VK_NULL_HANDLE,
                                  VK_NULL_HANDLE, fmt::format("storage block '{}'", block.name)});
    return {};
  }

  // Records are laid out per consumer (docs/reflection.md, known
  // limitations), so vertex-bake results are repacked member by member
  // rather than bound as the producer wrote them.
  Expected<void> fillRecords(vk::Buffer& buffer, const Block& block, const KernelInput& input, uint32_t records) {
    const BlockMember* member = block.member(input.component);
    if (!member || !member->type.isNumeric()) {
      return missing(kernel_, input, "its record member or type is not in the reflection");
    }
    const std::span<std::byte> memory = bytesOf(buffer);
    const WorldRole role = roleOf(kernel_, input);
    if (role == WorldRole::MeshAttributes) {
      const MeshAttribute* attribute = findMeshAttribute(input.component, input.type.name);
      if (!attribute) return missing(kernel_, input, "the engine supplies no such mesh attribute");
      for (uint32_t i = 0; i < records; ++i) {
        writeValue(memory.subspan(size_t{i} * block.recordStride, block.recordStride), *member,
                   attributeValue((*sources_.recordVertices())[i], *attribute));
      }
      return {};
    }
    if (role == WorldRole::VertexBake && sources_.vertexBake) {
      const BlockMember* produced = sources_.vertexBake->layout.member(input.component);
      if (!produced) return missing(kernel_, input, "the vertex bake did not produce it");
      const std::span<const std::byte> source = bytesOf(*sources_.vertexBake->buffer);
      const uint32_t stride = sources_.vertexBake->layout.recordStride;
      for (uint32_t i = 0; i < records; ++i) {
        const auto values = readValue(source.subspan(size_t{i} * stride, stride), *produced);
        writeValue(memory.subspan(size_t{i} * block.recordStride, block.recordStride), *member, values);
      }
      return {};
    }
    return missing(kernel_, input, "no engine pass provides per-vertex records from that world");
  }

  Expected<void> bindHazardRecord(const reflection::HazardRecord& layout) {
    const bool fragment = kernel_.stage == codegen::ShaderStage::Fragment;
    const VkExtent2D extent = sources_.fragmentExtent;
    if (fragment && (extent.width == 0 || extent.height == 0)) {
      return Error{fmt::format("the instrumented {} kernel is bound without its target's size", kernel_.world), {}, {}};
    }
    if (!fragment && !sources_.recordVertices()) {
      return Error{fmt::format("the instrumented {} kernel is bound without a mesh", kernel_.world), {}, {}};
    }
    const uint32_t invocations =
        fragment ? extent.width * extent.height : static_cast<uint32_t>(sources_.recordVertices()->size());
    VkBuffer handle = VK_NULL_HANDLE;
    if (sources_.hazards) {
      auto attached = sources_.hazards->attach(ctx_, kernel_, invocations, extent.width);
      if (!attached) return attached.error();
      handle = *attached;
    } else {
      auto buffer = newBuffer(layout.codesOffset() + VkDeviceSize{invocations} * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
      if (!buffer) return buffer.error();
      handle = (*buffer)->handle();
    }
    bound_.descriptors.push_back(
        {layout.slot, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, handle, VK_NULL_HANDLE, VK_NULL_HANDLE, "hazard record"});
    return {};
  }

  Expected<void> bindImage(const KernelInput& input) {
    VkImageView view = VK_NULL_HANDLE;
    VkSampler sampler = VK_NULL_HANDLE;
    if (input.kind == InputKind::Texture && !input.layer.empty()) {
      const auto* arrays = sources_.textureArrays;
      const auto it = arrays ? arrays->find(input.component) : PassTextures::const_iterator{};
      if (!arrays || it == arrays->end()) return missing(kernel_, input, "no texture array holds its bakes");
      view = it->second.view;
      sampler = it->second.sampler;
    } else if (input.kind == InputKind::Texture && roleOf(kernel_, input) != WorldRole::TextureBake) {
      if (!sources_.passTextures) return missing(kernel_, input, "no pass of this frame renders it");
      const auto it = sources_.passTextures->find(input.component);
      if (it == sources_.passTextures->end()) return missing(kernel_, input, "its pass did not render it");
      view = it->second.view;
      sampler = it->second.sampler;
    } else if (input.kind == InputKind::Texture) {
      if (!sources_.textureBake) return missing(kernel_, input, "no texture bake ran");
      const auto it = sources_.textureBake->textures.find(input.component);
      if (it == sources_.textureBake->textures.end())
        return missing(kernel_, input, "the texture bake did not produce it");
      view = it->second.image.view();
      sampler = it->second.sampler.get();
    } else {
      const MaterialValue* bound = materialValue(input.component);
      if (!bound || !bound->texture) return missing(kernel_, input, "no texture is bound to it in the material");
      view = bound->texture->image.view();
      sampler = bound->texture->sampler.get();
    }
    bound_.descriptors.push_back(
        {input.slot, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_NULL_HANDLE, view, sampler,
         fmt::format("{} '{}'", input.kind == InputKind::Texture ? "texture" : "sampler", input.component)});
    return {};
  }

  const vk::Context& ctx_;
  const KernelProgram& kernel_;
  const BindingSources& sources_;
  BoundKernel bound_;
};

}  // namespace

Expected<BoundKernel> bindKernel(const vk::Context& ctx, const KernelProgram& kernel, const BindingSources& sources) {
  return KernelBinder(ctx, kernel, sources).bind();
}

void writeInstanceRecord(const InstanceBlock& block, uint32_t index, const InstanceState& instance,
                         const UniformBakeResult* bake) {
  const std::span<std::byte> record = bytesOf(*block.buffer).subspan(size_t{index} * block.stride, block.stride);
  for (const InstanceField& field : block.fields) {
    if (field.baked) {
      if (!bake) continue;
      const auto it = bake->values.find(field.component);
      if (it != bake->values.end()) writeValue(record, field.member, it->second);
    } else if (const auto value = instanceValue(field.component, instance)) {
      writeValue(record, field.member, value->numbers);
    }
  }
}

void writeFrameValues(const BoundKernel& kernel, const FrameState& frame, const glm::mat4& model) {
  for (const FrameWrite& write : kernel.frameWrites) {
    if (const auto value = frameValue(write.component, frame, model)) {
      writeValue(bytesOf(*write.buffer), write.member, value->numbers);
    }
  }
  for (const InstanceBlock& block : kernel.instanceBlocks) writeInstanceRecord(block, 0, {.model = model}, nullptr);
}

}  // namespace spire::engine
