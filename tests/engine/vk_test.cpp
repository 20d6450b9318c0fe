// Tests of the engine's Vulkan foundation (engine-demo/vk). The device tests
// run on whatever the loader finds (lavapipe on CI, installed by
// scripts/install-deps.sh) with validation on, and fail on any validation
// warning or error. Without a usable Vulkan driver they skip with the reason.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "codegen/spirv_compiler.h"
#include "engine/device_fixture.h"
#include "vk/buffer.h"
#include "vk/context.h"
#include "vk/handle.h"
#include "vk/image.h"
#include "vk/pipeline.h"
#include "vk/result.h"
#include "vk/timer.h"

namespace spire::vk {
namespace {

using codegen::ShaderStage;

// --- Host-only parts -------------------------------------------------------

TEST(VkResult, NamesCoreResults) {
  EXPECT_STREQ(resultName(VK_SUCCESS), "VK_SUCCESS");
  EXPECT_STREQ(resultName(VK_ERROR_DEVICE_LOST), "VK_ERROR_DEVICE_LOST");
  EXPECT_STREQ(resultName(VK_ERROR_OUT_OF_POOL_MEMORY), "VK_ERROR_OUT_OF_POOL_MEMORY");
  EXPECT_STREQ(resultName(VK_PIPELINE_COMPILE_REQUIRED), "VK_PIPELINE_COMPILE_REQUIRED");
  EXPECT_STREQ(resultName(static_cast<VkResult>(-12345)), "VK_RESULT_-12345");
}

TEST(VkResult, ErrorMessage) {
  EXPECT_EQ((VkError{VK_ERROR_INITIALIZATION_FAILED, "vkCreateDevice", {}}).message(),
            "vkCreateDevice failed: VK_ERROR_INITIALIZATION_FAILED");
  EXPECT_EQ((VkError{VK_ERROR_LAYER_NOT_PRESENT, "Context::create", "no layer"}).message(),
            "Context::create failed: VK_ERROR_LAYER_NOT_PRESENT (no layer)");
}

TEST(VkResult, ExpectedHoldsValueOrError) {
  Expected<int> value = 7;
  ASSERT_TRUE(value.ok());
  EXPECT_EQ(*value, 7);
  Expected<int> error = VkError{VK_TIMEOUT, "wait", {}};
  ASSERT_FALSE(error);
  EXPECT_EQ(error.error().result, VK_TIMEOUT);
  EXPECT_TRUE(check(VK_SUCCESS, "x").ok());
  EXPECT_EQ(check(VK_ERROR_DEVICE_LOST, "vkQueueSubmit").error().message(),
            "vkQueueSubmit failed: VK_ERROR_DEVICE_LOST");
}

struct CountingDeleter {
  int* count = nullptr;
  void operator()(VkFence /*fence*/) const { ++*count; }
};

TEST(VkHandle, DestroysOnceAndMoves) {
  int destroyed = 0;
  const auto fake = reinterpret_cast<VkFence>(uintptr_t{0x10});
  {
    Handle<VkFence, CountingDeleter> a(fake, {&destroyed});
    Handle<VkFence, CountingDeleter> b(std::move(a));
    EXPECT_FALSE(a);  // NOLINT(bugprone-use-after-move): moved-from is empty by contract
    EXPECT_EQ(b.get(), fake);
    Handle<VkFence, CountingDeleter> c;
    c = std::move(b);
    EXPECT_EQ(destroyed, 0);
  }
  EXPECT_EQ(destroyed, 1);
  Handle<VkFence, CountingDeleter> d(fake, {&destroyed});
  EXPECT_EQ(d.release(), fake);
  d.reset();
  EXPECT_EQ(destroyed, 1);
}

TEST(VkContext, SelectsLavapipeByDefaultAndFiltersByName) {
  const std::vector<PhysicalDeviceInfo> devices{
      {VK_NULL_HANDLE, "NVIDIA GeForce RTX 4090", VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU, VK_API_VERSION_1_3},
      {VK_NULL_HANDLE, "llvmpipe (LLVM 15.0.6, 256 bits)", VK_PHYSICAL_DEVICE_TYPE_CPU, VK_API_VERSION_1_3},
  };
  EXPECT_EQ(selectPhysicalDevice(devices, ""), 1U);
  EXPECT_EQ(selectPhysicalDevice(devices, "rtx"), 0U);
  EXPECT_EQ(selectPhysicalDevice(devices, "radeon"), std::nullopt);
  EXPECT_EQ(selectPhysicalDevice(std::span(devices).first(1), ""), 0U);
  EXPECT_EQ(selectPhysicalDevice({}, ""), std::nullopt);
}

// --- Device tests ----------------------------------------------------------

std::vector<uint32_t> compile(ShaderStage stage, const char* glsl) {
  auto result = codegen::compileGlslToSpirv(stage, glsl, "vk_test");
  EXPECT_TRUE(result.ok()) << result.log;
  return result.words;
}

ContextOptions options(bool validation, std::string deviceFilter = {}) {
  ContextOptions result;
  result.validation = validation;
  result.deviceFilter = std::move(deviceFilter);
  return result;
}

using DeviceTest = testing::DeviceTest;

TEST_F(DeviceTest, CreatesContextOnASupportedDevice) {
  ASSERT_FALSE(ctx().physicalDevices().empty());
  const PhysicalDeviceInfo& device = ctx().selectedDevice();
  EXPECT_FALSE(device.name.empty());
  EXPECT_GE(ctx().apiVersion(), VK_API_VERSION_1_1);
  EXPECT_NE(ctx().queue(), VK_NULL_HANDLE);
  EXPECT_NE(ctx().cmdBeginRendering, nullptr);
  // The default selection takes lavapipe whenever the loader lists it.
  const auto& all = ctx().physicalDevices();
  if (std::any_of(all.begin(), all.end(), [](const auto& d) { return d.name.find("llvmpipe") != std::string::npos; })) {
    EXPECT_NE(device.name.find("llvmpipe"), std::string::npos) << device.name;
    EXPECT_STREQ(deviceTypeName(device.type), "CPU");
  }
  auto hostVisible = ctx().findMemoryType(~0U, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT);
  EXPECT_TRUE(hostVisible.ok());
}

// Guards the "no validation message" checks against a silent messenger: a
// known-invalid call must be recorded.
TEST_F(DeviceTest, RecordsValidationErrors) {
  VkSamplerCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO;
  info.anisotropyEnable = VK_TRUE;  // the samplerAnisotropy feature is not enabled
  info.maxAnisotropy = 4.0F;
  VkSampler sampler = VK_NULL_HANDLE;
  if (vkCreateSampler(ctx().device(), &info, nullptr, &sampler) == VK_SUCCESS) {
    vkDestroySampler(ctx().device(), sampler, nullptr);
  }
  const auto messages = ctx().validationMessages();
  ASSERT_FALSE(messages.empty());
  EXPECT_NE(messages.front().find("anisotropy"), std::string::npos) << messages.front();
  ctx().clearValidationMessages();
}

TEST_F(DeviceTest, UnknownDeviceFilterIsAnError) {
  auto other = Context::create(options(false, "no-such-device"));
  ASSERT_FALSE(other.ok());
  EXPECT_NE(other.error().message().find("no device matches 'no-such-device'"), std::string::npos)
      << other.error().message();
}

TEST_F(DeviceTest, RejectsBadInputWithoutCrashing) {
  auto buffer = Buffer::create(ctx(), 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  ASSERT_TRUE(buffer.ok()) << buffer.error().message();
  const std::array<uint32_t, 8> words{};
  EXPECT_FALSE(buffer->upload(std::span<const uint32_t>(words)).ok());
  EXPECT_TRUE(buffer->upload(std::span<const uint32_t>(words).first(4)).ok());
  EXPECT_FALSE(createShaderModule(ctx(), words).ok());
  EXPECT_FALSE(Image::create(ctx(), {4, 4, VK_FORMAT_B8G8R8A8_SRGB, VK_IMAGE_USAGE_SAMPLED_BIT}).ok());
  EXPECT_FALSE(Buffer::create(ctx(), 0, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT).ok());
}

TEST_F(DeviceTest, RendersTriangleWithDepthIntoOffscreenImage) {
  constexpr uint32_t kSize = 64;
  const auto vsWords = compile(ShaderStage::Vertex, R"(#version 440
layout(location = 0) in vec2 inPosition;
void main() { gl_Position = vec4(inPosition, 0.5, 1.0); }
)");
  const auto fsWords = compile(ShaderStage::Fragment, R"(#version 440
layout(push_constant) uniform Push { vec4 color; } pc;
layout(location = 0) out vec4 outColor;
void main() { outColor = pc.color; }
)");
  auto vs = createShaderModule(ctx(), vsWords);
  auto fs = createShaderModule(ctx(), fsWords);
  ASSERT_TRUE(vs.ok() && fs.ok());

  auto color = Image::create(ctx(), {kSize, kSize, VK_FORMAT_R8G8B8A8_UNORM,
                                     VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT});
  auto depth = Image::create(ctx(), {kSize, kSize, VK_FORMAT_D32_SFLOAT,
                                     VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT});
  ASSERT_TRUE(color.ok()) << color.error().message();
  ASSERT_TRUE(depth.ok()) << depth.error().message();

  auto pipeline = GraphicsPipelineBuilder()
                      .vertexShader(vs->get())
                      .fragmentShader(fs->get())
                      .vertexBinding(0, 2 * sizeof(float))
                      .vertexAttribute(0, 0, VK_FORMAT_R32G32_SFLOAT, 0)
                      .colorFormat(VK_FORMAT_R8G8B8A8_UNORM)
                      .depthFormat(VK_FORMAT_D32_SFLOAT)
                      .pushConstants(VK_SHADER_STAGE_FRAGMENT_BIT, 0, 4 * sizeof(float))
                      .build(ctx());
  ASSERT_TRUE(pipeline.ok()) << pipeline.error().message();

  // Apex at the top (Vulkan NDC y points down); covers the image centre.
  const std::array<float, 6> triangle{0.0F, -0.75F, 0.75F, 0.75F, -0.75F, 0.75F};
  auto vertices = Buffer::create(ctx(), sizeof(triangle), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
  ASSERT_TRUE(vertices.ok());
  ASSERT_TRUE(vertices->upload(std::span<const float>(triangle)).ok());
  auto colorReadback = Buffer::create(ctx(), color->byteSize(), VK_BUFFER_USAGE_TRANSFER_DST_BIT);
  auto depthReadback = Buffer::create(ctx(), depth->byteSize(), VK_BUFFER_USAGE_TRANSFER_DST_BIT);
  ASSERT_TRUE(colorReadback.ok() && depthReadback.ok());
  auto timer = GpuTimer::create(ctx());
  ASSERT_TRUE(timer.ok()) << timer.error().message();

  const std::array<float, 4> red{1.0F, 0.0F, 0.0F, 1.0F};
  auto submitted = ctx().submitAndWait([&](VkCommandBuffer cmd) {
    timer->begin(cmd);
    color->transition(cmd, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
    depth->transition(cmd, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL);
    const std::array targets{ColorTarget{color->view(), {{0.0F, 0.0F, 1.0F, 1.0F}}}};
    beginRendering(ctx(), cmd, color->extent(), targets, DepthTarget{depth->view(), 1.0F});
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline->pipeline.get());
    vkCmdPushConstants(cmd, pipeline->layout.get(), VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(red), red.data());
    const VkBuffer vertexBuffer = vertices->handle();
    const VkDeviceSize offset = 0;
    vkCmdBindVertexBuffers(cmd, 0, 1, &vertexBuffer, &offset);
    vkCmdDraw(cmd, 3, 1, 0, 0);
    endRendering(ctx(), cmd);
    timer->end(cmd);
    ASSERT_TRUE(color->copyToBuffer(cmd, *colorReadback).ok());
    ASSERT_TRUE(depth->copyToBuffer(cmd, *depthReadback).ok());
  });
  ASSERT_TRUE(submitted.ok()) << submitted.error().message();

  const auto pixels = colorReadback->read<uint32_t>();
  const auto depths = depthReadback->read<float>();
  auto at = [&](const auto& values, uint32_t x, uint32_t y) { return values[y * kSize + x]; };
  // RGBA8 little-endian: red = 0xff0000ff, blue clear = 0xffff0000.
  EXPECT_EQ(at(pixels, kSize / 2, kSize / 2), 0xff0000ffU);
  EXPECT_EQ(at(pixels, kSize / 2, kSize - 12), 0xff0000ffU);
  EXPECT_EQ(at(pixels, 2, 2), 0xffff0000U);
  EXPECT_EQ(at(pixels, kSize - 3, 4), 0xffff0000U);
  EXPECT_EQ(at(pixels, kSize / 2, kSize - 2), 0xffff0000U);
  EXPECT_FLOAT_EQ(at(depths, kSize / 2, kSize / 2), 0.5F);
  EXPECT_FLOAT_EQ(at(depths, 2, 2), 1.0F);

  auto elapsed = timer->elapsedMs();
  ASSERT_TRUE(elapsed.ok()) << elapsed.error().message();
  EXPECT_GE(*elapsed, 0.0);
}

TEST_F(DeviceTest, ComputeWritesStorageBuffer) {
  constexpr uint32_t kCount = 256;
  const auto words = compile(ShaderStage::Compute, R"(#version 440
layout(local_size_x = 64) in;
layout(std430, set = 0, binding = 0) buffer Out { uint values[]; } outBuffer;
layout(push_constant) uniform Push { uint offset; } pc;
void main() {
  uint i = gl_GlobalInvocationID.x;
  outBuffer.values[i] = i * i + pc.offset;
}
)");
  auto module = createShaderModule(ctx(), words);
  ASSERT_TRUE(module.ok()) << module.error().message();
  auto setLayout = DescriptorSetLayoutBuilder()
                       .binding(0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT)
                       .build(ctx());
  ASSERT_TRUE(setLayout.ok());
  const VkDescriptorSetLayout layouts[] = {setLayout->get()};
  const VkPushConstantRange push{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(uint32_t)};
  auto pipeline = createComputePipeline(ctx(), module->get(), layouts, std::span(&push, 1));
  ASSERT_TRUE(pipeline.ok()) << pipeline.error().message();

  const VkDescriptorPoolSize poolSize{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1};
  auto pool = createDescriptorPool(ctx(), 1, std::span(&poolSize, 1));
  ASSERT_TRUE(pool.ok());
  auto set = allocateDescriptorSet(ctx(), pool->get(), setLayout->get());
  ASSERT_TRUE(set.ok()) << set.error().message();
  auto output = Buffer::create(ctx(), kCount * sizeof(uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  ASSERT_TRUE(output.ok());
  DescriptorWriter().buffer(0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, output->handle()).update(ctx(), *set);

  const uint32_t offset = 1000;
  HostTimer timer;
  auto submitted = ctx().submitAndWait([&](VkCommandBuffer cmd) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline->pipeline.get());
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline->layout.get(), 0, 1, &*set, 0, nullptr);
    vkCmdPushConstants(cmd, pipeline->layout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(offset), &offset);
    vkCmdDispatch(cmd, kCount / 64, 1, 1);
    VkMemoryBarrier toHost{};
    toHost.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
    toHost.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
    toHost.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &toHost, 0,
                         nullptr, 0, nullptr);
  });
  ASSERT_TRUE(submitted.ok()) << submitted.error().message();
  EXPECT_GT(timer.elapsedMs(), 0.0);

  const auto values = output->read<uint32_t>();
  ASSERT_EQ(values.size(), kCount);
  for (uint32_t i = 0; i < kCount; ++i) ASSERT_EQ(values[i], i * i + offset) << "index " << i;
}

// submitAndWait from several threads at once (a tool prepares the next
// scene's bakes on a worker while the window draws): each thread's commands
// come from a pool of its own and the queue is submitted to under one lock,
// so every fill lands and the validation layer's thread-safety checks stay
// silent.
TEST_F(DeviceTest, SubmitsFromSeveralThreadsAtOnce) {
  constexpr uint32_t kThreads = 3;
  constexpr uint32_t kSubmits = 40;
  constexpr uint32_t kCount = 64;
  std::vector<Buffer> buffers;
  for (uint32_t t = 0; t < kThreads; ++t) {
    auto buffer = Buffer::create(ctx(), kCount * sizeof(uint32_t), VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    ASSERT_TRUE(buffer.ok()) << buffer.error().message();
    buffers.push_back(std::move(buffer).value());
  }
  std::vector<std::string> failures(kThreads);
  std::vector<std::thread> threads;
  for (uint32_t t = 0; t < kThreads; ++t) {
    threads.emplace_back([&, t] {
      for (uint32_t i = 0; i < kSubmits && failures[t].empty(); ++i) {
        const uint32_t value = t * 1000 + i;
        auto submitted = ctx().submitAndWait(
            [&](VkCommandBuffer cmd) { vkCmdFillBuffer(cmd, buffers[t].handle(), 0, VK_WHOLE_SIZE, value); });
        if (!submitted) {
          failures[t] = submitted.error().message();
        } else if (buffers[t].read<uint32_t>() != std::vector<uint32_t>(kCount, value)) {
          failures[t] = fmt::format("submit {} did not fill the buffer with {}", i, value);
        }
      }
    });
  }
  for (std::thread& thread : threads) thread.join();
  for (uint32_t t = 0; t < kThreads; ++t) EXPECT_EQ(failures[t], "") << "thread " << t;
}

// Clears every color format the engine uses and reads the texel back, which
// checks the texel sizes and the transfer path per format.
TEST_F(DeviceTest, ClearsAndReadsBackEveryColorFormat) {
  const VkClearColorValue clear{{0.25F, 0.5F, 0.75F, 1.0F}};
  struct Case {
    VkFormat format;
    std::vector<uint8_t> firstTexel;
  };
  auto bytesOf = [](const auto& values) {
    std::vector<uint8_t> bytes(sizeof(values));
    std::memcpy(bytes.data(), &values, sizeof(values));
    return bytes;
  };
  const std::vector<Case> cases{
      {VK_FORMAT_R8G8B8A8_UNORM, {64, 128, 191, 255}},
      {VK_FORMAT_R16G16B16A16_SFLOAT, bytesOf(std::array<uint16_t, 4>{0x3400, 0x3800, 0x3a00, 0x3c00})},
      {VK_FORMAT_R32G32B32A32_SFLOAT, bytesOf(std::array<float, 4>{0.25F, 0.5F, 0.75F, 1.0F})},
      {VK_FORMAT_R32_SFLOAT, bytesOf(0.25F)},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(static_cast<int>(c.format));
    auto image = Image::create(
        ctx(), {8, 8, c.format,
                VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_SAMPLED_BIT});
    ASSERT_TRUE(image.ok()) << image.error().message();
    ASSERT_EQ(formatTexelSize(c.format), c.firstTexel.size());
    auto readback = Buffer::create(ctx(), image->byteSize(), VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    ASSERT_TRUE(readback.ok());
    auto submitted = ctx().submitAndWait([&](VkCommandBuffer cmd) {
      image->transition(cmd, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
      const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
      vkCmdClearColorImage(cmd, image->handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &clear, 1, &range);
      ASSERT_TRUE(image->copyToBuffer(cmd, *readback).ok());
    });
    ASSERT_TRUE(submitted.ok()) << submitted.error().message();
    const auto bytes = readback->read<uint8_t>();
    // The last texel, so the whole image was copied.
    const std::vector<uint8_t> last(bytes.end() - static_cast<std::ptrdiff_t>(c.firstTexel.size()), bytes.end());
    EXPECT_EQ(last, c.firstTexel);
  }
  auto sampler = createSampler(ctx(), {VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_REPEAT});
  EXPECT_TRUE(sampler.ok());
}

}  // namespace
}  // namespace spire::vk
