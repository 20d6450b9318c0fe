// spire-demo --window and what it is built on: the camera path, the frame
// blit into presentable images (both paths, headless), the context's surface
// plumbing, and the flag itself, which must fail cleanly without a display
// and leave the headless runs alone. The tests that need a display skip
// without one; under `xvfb-run` they open a real window and present to it.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "common/scoped_env.h"
#include "demo/camera_path.h"
#include "demo/demo.h"
#include "demo/glfw_window.h"
#include "engine/device_fixture.h"
#include "vk/buffer.h"
#include "vk/frame_blit.h"
#include "vk/image.h"
#include "vk/swapchain.h"

namespace spire {
namespace {

namespace fs = std::filesystem;
using vk::testing::DeviceTest;

using spire::testing::ScopedEnv;

// SAMPLED only because vk::Image always makes a view, which transfers alone
// do not allow.
constexpr VkImageUsageFlags kTransferUsage =
    VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;

bool haveDisplay() {
  for (const char* name : {"DISPLAY", "WAYLAND_DISPLAY"}) {
    const char* value = std::getenv(name);
    if (value != nullptr && value[0] != '\0') return true;
  }
  return false;
}

void expectNear(const glm::vec3& actual, const glm::vec3& expected) {
  EXPECT_LT(glm::length(actual - expected), 1e-5F) << actual.x << " " << actual.y << " " << actual.z;
}

// --- Camera path (host only) ------------------------------------------------

std::vector<scene::CameraView> threeViews() {
  std::vector<scene::CameraView> views(3);
  views[0].position = {0.0F, 1.0F, 10.0F};
  views[1].position = {10.0F, 2.0F, 0.0F};
  views[1].target = {0.0F, 1.0F, 0.0F};
  views[2].position = {0.0F, 3.0F, -10.0F};
  return views;
}

TEST(CameraPath, PassesThroughEveryViewAndLoops) {
  const auto views = threeViews();
  for (int i = -3; i <= 6; ++i) {
    const scene::CameraView& expected = views[static_cast<size_t>((i % 3 + 3) % 3)];
    const scene::CameraView view = demo::cameraOnLoop(views, i);
    expectNear(view.position, expected.position);
    expectNear(view.target, expected.target);
  }
}

TEST(CameraPath, EasesBetweenViews) {
  const auto views = threeViews();
  // Halfway is halfway; a quarter of the way is smoothstep(0.25) = 0.15625.
  expectNear(demo::cameraOnLoop(views, 0.5).position, (views[0].position + views[1].position) * 0.5F);
  expectNear(demo::cameraOnLoop(views, 1.25).target, glm::mix(views[1].target, views[2].target, 0.15625F));
  // From the last view back to the first.
  expectNear(demo::cameraOnLoop(views, 2.5).position, (views[2].position + views[0].position) * 0.5F);
}

TEST(CameraPath, OneViewStaysPut) {
  const auto views = threeViews();
  const std::span<const scene::CameraView> one(views.data(), 1);
  expectNear(demo::cameraOnLoop(one, 0.7).position, views[0].position);
}

TEST(CameraPath, OrbitTurnsAboutTheTargetAndKeepsTheDistance) {
  scene::CameraView view;
  view.position = {0.0F, 0.0F, 5.0F};
  view.target = {0.0F, 0.0F, 0.0F};
  const glm::vec3 up{0.0F, 1.0F, 0.0F};
  expectNear(demo::orbit(view, up, glm::half_pi<float>(), 0.0F).position, {5.0F, 0.0F, 0.0F});
  const scene::CameraView raised = demo::orbit(view, up, 0.0F, 0.5F);
  EXPECT_GT(raised.position.y, 0.0F);
  EXPECT_NEAR(glm::length(raised.position), 5.0F, 1e-4F);
  // Far past the top: it stops short of looking straight down.
  const scene::CameraView top = demo::orbit(view, up, 0.0F, 10.0F);
  EXPECT_LT(top.position.y, 5.0F);
  EXPECT_GT(top.position.z, 0.0F);
  EXPECT_NEAR(glm::length(top.position), 5.0F, 1e-4F);
  expectNear(top.target, view.target);
}

// --- Frame blit -------------------------------------------------------------

TEST(FrameBlit, FitRectKeepsTheAspectRatioCentred) {
  const auto expectRect = [](VkRect2D rect, int32_t x, int32_t y, uint32_t w, uint32_t h) {
    EXPECT_EQ(rect.offset.x, x);
    EXPECT_EQ(rect.offset.y, y);
    EXPECT_EQ(rect.extent.width, w);
    EXPECT_EQ(rect.extent.height, h);
  };
  expectRect(vk::fitRect({640, 480}, {640, 480}), 0, 0, 640, 480);
  expectRect(vk::fitRect({640, 480}, {1280, 720}), 160, 0, 960, 720);
  expectRect(vk::fitRect({640, 480}, {100, 1000}), 0, 462, 100, 75);
  expectRect(vk::fitRect({640, 480}, {1, 1}), 0, 0, 1, 1);
}

class FrameBlitTest : public DeviceTest {
 protected:
  static constexpr VkExtent2D kSource{4, 2};

  // A 4x2 RGBA32F frame holding kTexels.
  vk::Image sourceImage() {
    auto image =
        vk::Image::create(ctx(), {kSource.width, kSource.height, VK_FORMAT_R32G32B32A32_SFLOAT, kTransferUsage});
    EXPECT_TRUE(image.ok());
    auto staging = vk::Buffer::create(ctx(), image->byteSize(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
    EXPECT_TRUE(staging.ok());
    EXPECT_TRUE(staging->upload(std::span<const float>(kTexels)).ok());
    const auto uploaded =
        ctx().submitAndWait([&](VkCommandBuffer cmd) { EXPECT_TRUE(image->copyFromBuffer(cmd, *staging).ok()); });
    EXPECT_TRUE(uploaded.ok());
    return std::move(image).value();
  }

  // Blits the source frame into a `format` image of `extent` and reads it back.
  std::vector<uint8_t> blitInto(vk::BlitPath path, VkFormat format, VkExtent2D extent) {
    vk::Image source = sourceImage();
    auto target = vk::Image::create(ctx(), {extent.width, extent.height, format, kTransferUsage});
    EXPECT_TRUE(target.ok());
    auto blit = vk::FrameBlit::create(ctx(), path, source.format(), source.extent(), format);
    EXPECT_TRUE(blit.ok()) << blit.error().message();
    EXPECT_EQ(blit->path(), path);
    auto readback = vk::Buffer::create(ctx(), target->byteSize(), VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    EXPECT_TRUE(readback.ok());
    const auto submitted = ctx().submitAndWait([&](VkCommandBuffer cmd) {
      EXPECT_TRUE(blit->record(cmd, source, target->handle(), extent, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL).ok());
      // The target is handled as a bare VkImage (like a swapchain's), so its
      // readback is spelled out too.
      VkBufferImageCopy region{};
      region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
      region.imageExtent = {extent.width, extent.height, 1};
      vkCmdCopyImageToBuffer(cmd, target->handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback->handle(), 1,
                             &region);
      VkMemoryBarrier toHost{};
      toHost.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
      toHost.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
      toHost.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
      vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &toHost, 0, nullptr,
                           0, nullptr);
    });
    EXPECT_TRUE(submitted.ok()) << submitted.error().message();
    return readback->read<uint8_t>();
  }

  // Texel (x, y) of the source in 8 bits, RGBA.
  static std::array<uint8_t, 4> expected(uint32_t x, uint32_t y) {
    const float* texel = &kTexels[(y * kSource.width + x) * 4];
    std::array<uint8_t, 4> rgba{};
    for (size_t c = 0; c < 4; ++c) {
      rgba[c] = static_cast<uint8_t>(std::lround(std::clamp(texel[c], 0.0F, 1.0F) * 255.0F));
    }
    return rgba;
  }

  // Values whose x255 is an integer, plus out-of-range ones that clamp.
  static constexpr std::array<float, 32> kTexels = {
      0.0F, 0.2F, 0.4F, 1.0F, 0.2F, 0.4F,  0.6F, 1.0F, 0.4F, 0.6F, 0.8F, 1.0F, 0.6F, 0.8F, 1.0F, 1.0F,
      1.0F, 0.0F, 0.2F, 1.0F, 2.0F, -1.0F, 0.8F, 1.0F, 0.8F, 0.2F, 0.0F, 1.0F, 0.0F, 0.0F, 0.0F, 1.0F,
  };
};

TEST_F(FrameBlitTest, DirectBlitConvertsAndLetterboxes) {
  // 4x2 into 4x4: the frame fills rows 1 and 2, black bars above and below.
  const std::vector<uint8_t> pixels = blitInto(vk::BlitPath::Direct, VK_FORMAT_R8G8B8A8_UNORM, {4, 4});
  ASSERT_EQ(pixels.size(), 4U * 4U * 4U);
  for (uint32_t y = 0; y < 4; ++y) {
    for (uint32_t x = 0; x < 4; ++x) {
      SCOPED_TRACE(::testing::Message() << "pixel " << x << "," << y);
      const uint8_t* p = &pixels[(y * 4 + x) * 4];
      const bool inside = y == 1 || y == 2;
      const std::array<uint8_t, 4> want = inside ? expected(x, y - 1) : std::array<uint8_t, 4>{0, 0, 0, 255};
      for (size_t c = 0; c < 4; ++c) EXPECT_EQ(p[c], want[c]) << "channel " << c;
    }
  }
}

TEST_F(FrameBlitTest, StagedCopyKeepsTheByteOrderOfTheTarget) {
  // 4x2 into 6x4 BGRA: copied unscaled at (1, 1), black around it.
  const std::vector<uint8_t> pixels = blitInto(vk::BlitPath::Staged, VK_FORMAT_B8G8R8A8_UNORM, {6, 4});
  ASSERT_EQ(pixels.size(), 6U * 4U * 4U);
  for (uint32_t y = 0; y < 4; ++y) {
    for (uint32_t x = 0; x < 6; ++x) {
      SCOPED_TRACE(::testing::Message() << "pixel " << x << "," << y);
      const uint8_t* p = &pixels[(y * 6 + x) * 4];
      const bool inside = x >= 1 && x <= 4 && y >= 1 && y <= 2;
      const std::array<uint8_t, 4> rgba = inside ? expected(x - 1, y - 1) : std::array<uint8_t, 4>{0, 0, 0, 255};
      const std::array<uint8_t, 4> bgra{rgba[2], rgba[1], rgba[0], rgba[3]};
      for (size_t c = 0; c < 4; ++c) EXPECT_EQ(p[c], bgra[c]) << "channel " << c;
    }
  }
}

TEST_F(FrameBlitTest, StagedCopyCropsToASmallerTarget) {
  // 4x2 into 2x2: the middle two columns.
  const std::vector<uint8_t> pixels = blitInto(vk::BlitPath::Staged, VK_FORMAT_R8G8B8A8_UNORM, {2, 2});
  ASSERT_EQ(pixels.size(), 2U * 2U * 4U);
  for (uint32_t y = 0; y < 2; ++y) {
    for (uint32_t x = 0; x < 2; ++x) {
      const std::array<uint8_t, 4> want = expected(x + 1, y);
      for (size_t c = 0; c < 4; ++c) EXPECT_EQ(pixels[(y * 2 + x) * 4 + c], want[c]);
    }
  }
}

TEST_F(FrameBlitTest, RejectsWhatItCannotDo) {
  // No 8-bit RGBA or BGRA layout to stage through.
  auto staged = vk::FrameBlit::create(ctx(), vk::BlitPath::Staged, VK_FORMAT_R32G32B32A32_SFLOAT, kSource,
                                      VK_FORMAT_R16G16B16A16_SFLOAT);
  ASSERT_FALSE(staged.ok());
  EXPECT_EQ(staged.error().result, VK_ERROR_FORMAT_NOT_SUPPORTED);
  // A frame of another size than the blit was made for.
  auto blit = vk::FrameBlit::create(ctx(), vk::BlitPath::Direct, VK_FORMAT_R32G32B32A32_SFLOAT, {8, 8},
                                    VK_FORMAT_R8G8B8A8_UNORM);
  ASSERT_TRUE(blit.ok()) << blit.error().message();
  vk::Image source = sourceImage();
  auto target = vk::Image::create(ctx(), {8, 8, VK_FORMAT_R8G8B8A8_UNORM, kTransferUsage});
  ASSERT_TRUE(target.ok());
  ASSERT_TRUE(ctx()
                  .submitAndWait([&](VkCommandBuffer cmd) {
                    EXPECT_FALSE(
                        blit->record(cmd, source, target->handle(), {8, 8}, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL).ok());
                  })
                  .ok());
  EXPECT_EQ(vk::chooseBlitPath(ctx(), VK_FORMAT_R8G8B8A8_UNORM), vk::BlitPath::Direct);
}

// --- Context and swapchain --------------------------------------------------

TEST_F(DeviceTest, HeadlessContextHasNoSurfaceAndNoSwapchain) {
  EXPECT_EQ(ctx().surface(), VK_NULL_HANDLE);
  auto swapchain = vk::Swapchain::create(ctx(), {640, 480});
  ASSERT_FALSE(swapchain.ok());
  EXPECT_EQ(swapchain.error().result, VK_ERROR_INITIALIZATION_FAILED);
}

TEST_F(DeviceTest, ContextReportsSurfaceAndExtensionFailures) {
  auto failed = vk::Context::create({}, [](VkInstance) -> vk::Expected<VkSurfaceKHR> {
    return vk::VkError{VK_ERROR_SURFACE_LOST_KHR, "test surface", "no window"};
  });
  ASSERT_FALSE(failed.ok());
  EXPECT_EQ(failed.error().message(), "test surface failed: VK_ERROR_SURFACE_LOST_KHR (no window)");

  vk::ContextOptions options;
  options.instanceExtensions = {"VK_SPIRE_no_such_extension"};
  auto missing = vk::Context::create(options);
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.error().result, VK_ERROR_EXTENSION_NOT_PRESENT);
}

// Presents to a real window (skips without a display): frames in flight,
// then a forced rebuild while frames are still in flight, with validation.
TEST(Swapchain, PresentsAndRebuildsInAWindow) {
  if (!haveDisplay()) GTEST_SKIP() << "no display (run under xvfb-run to cover this)";
  auto window = demo::GlfwWindow::open(64, 48, "spire window_test");
  ASSERT_TRUE(window.ok()) << window.error();
  vk::ContextOptions options;
  options.validation = true;
  options.instanceExtensions = window->vulkanInstanceExtensions();
  auto ctx = vk::Context::create(options, [&](VkInstance instance) { return window->createSurface(instance); });
  const vk::testing::DeviceVerdict verdict =
      vk::testing::deviceVerdict(ctx ? nullptr : &ctx.error(), std::getenv("CI"));
  if (verdict.action == vk::testing::DeviceAction::Skip) GTEST_SKIP() << verdict.message;
  ASSERT_TRUE(ctx.ok()) << verdict.message;
#if defined(__SANITIZE_ADDRESS__)
  vk::testing::pinLoadedLibraries();  // as the device fixture does, for the same reason
#endif
  ASSERT_NE(ctx->surface(), VK_NULL_HANDLE);
  {
    auto frame = vk::Image::create(*ctx, {32, 24, VK_FORMAT_R32G32B32A32_SFLOAT, kTransferUsage});
    ASSERT_TRUE(frame.ok());
    auto swapchain = vk::Swapchain::create(*ctx, window->framebufferExtent());
    ASSERT_TRUE(swapchain.ok()) << swapchain.error().message();
    auto blit = vk::FrameBlit::create(*ctx, vk::chooseBlitPath(*ctx, swapchain->format()), frame->format(),
                                      frame->extent(), swapchain->format());
    ASSERT_TRUE(blit.ok()) << blit.error().message();
    int presented = 0;
    for (int i = 0; i < 8; ++i) {
      window->poll();
      // Halfway, pretend the window was resized: the swapchain is rebuilt.
      VkExtent2D extent = window->framebufferExtent();
      if (i >= 4) extent.width += 1;
      auto acquired = swapchain->beginFrame(extent);
      ASSERT_TRUE(acquired.ok()) << acquired.error().message();
      if (!acquired->has_value()) continue;
      const vk::SwapchainFrame& target = **acquired;
      ASSERT_TRUE(blit->record(target.cmd, *frame, target.image, target.extent, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR).ok());
      auto ended = swapchain->endFrame();
      ASSERT_TRUE(ended.ok()) << ended.error().message();
      ++presented;
    }
    EXPECT_GE(presented, 6);
  }
  for (const std::string& message : ctx->validationMessages()) ADD_FAILURE() << message;
}

// --- The --window flag --------------------------------------------------------

class WindowFlagTest : public DeviceTest {
 protected:
  static fs::path outputDir() {
    return fs::temp_directory_path() / ("spire_window_test_" + std::to_string(::getpid()));
  }
};

TEST(WindowFlag, FailsCleanlyWithoutADisplay) {
  const ScopedEnv display("DISPLAY", std::nullopt);
  const ScopedEnv wayland("WAYLAND_DISPLAY", std::nullopt);
  std::ostringstream out;
  std::ostringstream err;
  EXPECT_EQ(demo::runDemo({"examples/scenes/terrain.json", "--window"}, out, err), 1);
  EXPECT_EQ(err.str(), "spire-demo: error: --window needs a display (neither DISPLAY nor WAYLAND_DISPLAY is set)\n");
  EXPECT_EQ(out.str(), "");
}

TEST(WindowFlag, FailsCleanlyWhenTheDisplayCannotBeReached) {
  const ScopedEnv display("DISPLAY", ":9999");
  const ScopedEnv wayland("WAYLAND_DISPLAY", std::nullopt);
  std::ostringstream out;
  std::ostringstream err;
  EXPECT_EQ(demo::runDemo({"examples/scenes/terrain.json", "--window"}, out, err), 1);
  EXPECT_EQ(err.str().rfind("spire-demo: error: --window needs a display (GLFW: ", 0), 0U) << err.str();
}

TEST(WindowFlag, IsInTheHelp) {
  std::ostringstream out;
  std::ostringstream err;
  EXPECT_EQ(demo::runDemo({"--help"}, out, err), 0);
  EXPECT_NE(out.str().find("--window"), std::string::npos) << out.str();
}

TEST_F(WindowFlagTest, HeadlessRunsNeedNoDisplay) {
  const ScopedEnv display("DISPLAY", std::nullopt);
  const ScopedEnv wayland("WAYLAND_DISPLAY", std::nullopt);
  const fs::path dir = outputDir();
  std::ostringstream out;
  std::ostringstream err;
  ASSERT_EQ(demo::runDemo({"examples/scenes/terrain.json", "--validation", "--frames", "1", "--warmup", "1",
                           "--bake-size", "64", "-o", dir.string()},
                          out, err),
            0)
      << err.str();
  EXPECT_TRUE(fs::exists(dir / "comparison.png"));
  EXPECT_TRUE(fs::exists(dir / "report.md"));
  EXPECT_EQ(out.str().find("window:"), std::string::npos) << out.str();
  fs::remove_all(dir);
}

TEST_F(WindowFlagTest, ShowsTheVariantsInAWindow) {
  if (!haveDisplay()) GTEST_SKIP() << "no display (run under xvfb-run to cover this)";
  const fs::path dir = outputDir();
  std::ostringstream out;
  std::ostringstream err;
  ASSERT_EQ(demo::runDemo({"examples/scenes/terrain.json", "--window", "--validation", "--frames", "5", "--bake-size",
                           "64", "-o", dir.string()},
                          out, err),
            0)
      << err.str();
  EXPECT_NE(out.str().find("window: keys 1-3 switch variants (1 full_quality, 2 baked_albedo, 3 baked_vertex_normal)"),
            std::string::npos)
      << out.str();
  EXPECT_NE(out.str().find("window: 5 frames shown"), std::string::npos) << out.str();
  EXPECT_FALSE(fs::exists(dir)) << "a window run writes no files";
}

}  // namespace
}  // namespace spire
