#include "explore/imgui_overlay.h"

#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>
#include <imgui.h>

#include <GLFW/glfw3.h>

#include <array>

#include "vk/pipeline.h"
#include "vk/swapchain.h"

namespace spire::explore {
namespace {

// Frames that may still be drawn when the next one is recorded, plus this one.
constexpr size_t kKeptFramebuffers = vk::Swapchain::kFramesInFlight + 1;

vk::Expected<vk::RenderPass> createRenderPass(const vk::Context& ctx, VkFormat format) {
  VkAttachmentDescription color{};
  color.format = format;
  color.samples = VK_SAMPLE_COUNT_1_BIT;
  color.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
  color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  color.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  color.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  color.initialLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  color.finalLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  VkAttachmentReference reference{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = 1;
  subpass.pColorAttachments = &reference;
  // The image's transition to COLOR_ATTACHMENT_OPTIMAL (vk::Image::transition)
  // comes before the pass; its barrier orders the writes.
  VkRenderPassCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO;
  info.attachmentCount = 1;
  info.pAttachments = &color;
  info.subpassCount = 1;
  info.pSubpasses = &subpass;
  VkRenderPass raw = VK_NULL_HANDLE;
  if (auto ok = vk::check(vkCreateRenderPass(ctx.device(), &info, nullptr, &raw), "vkCreateRenderPass"); !ok) {
    return ok.error();
  }
  return vk::makeDeviceHandle<VkRenderPass, vkDestroyRenderPass>(ctx.device(), raw);
}

}  // namespace

vk::Expected<std::unique_ptr<ImGuiOverlay>> ImGuiOverlay::create(const vk::Context& ctx, GLFWwindow* window,
                                                                 VkFormat format) {
  std::unique_ptr<ImGuiOverlay> overlay(new ImGuiOverlay(ctx));
  const std::array<VkDescriptorPoolSize, 1> sizes{{{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1}}};
  auto pool = vk::createDescriptorPool(ctx, 1, sizes);
  if (!pool) return pool.error();
  overlay->pool_ = std::move(pool).value();
  auto renderPass = createRenderPass(ctx, format);
  if (!renderPass) return renderPass.error();
  overlay->renderPass_ = std::move(renderPass).value();

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini written into the user's directory
  ImGui::StyleColorsDark();
  overlay->window_ = window;
  overlay->glfwReady_ = ImGui_ImplGlfw_InitForVulkan(window, true);
  ImGui_ImplVulkan_InitInfo info{};
  info.Instance = ctx.instance();
  info.PhysicalDevice = ctx.physicalDevice();
  info.Device = ctx.device();
  info.QueueFamily = ctx.queueFamily();
  info.Queue = ctx.queue();
  info.DescriptorPool = overlay->pool_.get();
  info.MinImageCount = vk::Swapchain::kFramesInFlight;
  info.ImageCount = vk::Swapchain::kFramesInFlight;
  info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
  overlay->vulkanReady_ = ImGui_ImplVulkan_Init(&info, overlay->renderPass_.get());
  if (!overlay->glfwReady_ || !overlay->vulkanReady_) {
    return vk::VkError{VK_ERROR_INITIALIZATION_FAILED, "ImGui_ImplVulkan_Init", "Dear ImGui could not start"};
  }
  if (auto ok = ctx.submitAndWait([](VkCommandBuffer cmd) { ImGui_ImplVulkan_CreateFontsTexture(cmd); }); !ok) {
    return ok.error();
  }
  ImGui_ImplVulkan_DestroyFontUploadObjects();
  return overlay;
}

ImGuiOverlay::~ImGuiOverlay() {
  if (ctx_->device() != VK_NULL_HANDLE) {
    const auto queueLock = ctx_->lockQueue();
    vkDeviceWaitIdle(ctx_->device());
  }
  if (vulkanReady_) ImGui_ImplVulkan_Shutdown();
  if (glfwReady_) ImGui_ImplGlfw_Shutdown();
  if (ImGui::GetCurrentContext() != nullptr) ImGui::DestroyContext();
}

void ImGuiOverlay::beginFrame(VkExtent2D extent) {
  ImGui_ImplVulkan_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  // The backend laid ImGui out in window coordinates; the panels are drawn
  // into the image, which the blit stretches over the window.
  ImGuiIO& io = ImGui::GetIO();
  int width = 0;
  int height = 0;
  glfwGetWindowSize(window_, &width, &height);
  if (width > 0 && height > 0 && io.MousePos.x > -FLT_MAX) {
    io.MousePos.x *= static_cast<float>(extent.width) / static_cast<float>(width);
    io.MousePos.y *= static_cast<float>(extent.height) / static_cast<float>(height);
  }
  io.DisplaySize = ImVec2(static_cast<float>(extent.width), static_cast<float>(extent.height));
  io.DisplayFramebufferScale = ImVec2(1.0F, 1.0F);
  ImGui::NewFrame();
}

vk::Expected<VkFramebuffer> ImGuiOverlay::framebufferFor(const vk::Image& target) {
  VkImageView view = target.view();
  VkFramebufferCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO;
  info.renderPass = renderPass_.get();
  info.attachmentCount = 1;
  info.pAttachments = &view;
  info.width = target.extent().width;
  info.height = target.extent().height;
  info.layers = 1;
  VkFramebuffer raw = VK_NULL_HANDLE;
  if (auto ok = vk::check(vkCreateFramebuffer(ctx_->device(), &info, nullptr, &raw), "vkCreateFramebuffer"); !ok) {
    return ok.error();
  }
  framebuffers_.push_back(vk::makeDeviceHandle<VkFramebuffer, vkDestroyFramebuffer>(ctx_->device(), raw));
  while (framebuffers_.size() > kKeptFramebuffers) framebuffers_.pop_front();
  return raw;
}

vk::Expected<void> ImGuiOverlay::record(VkCommandBuffer cmd, vk::Image& target) {
  ImGui::Render();
  auto framebuffer = framebufferFor(target);
  if (!framebuffer) return framebuffer.error();
  target.transition(cmd, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
  VkRenderPassBeginInfo begin{};
  begin.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO;
  begin.renderPass = renderPass_.get();
  begin.framebuffer = *framebuffer;
  begin.renderArea.extent = target.extent();
  vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
  ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), cmd);
  vkCmdEndRenderPass(cmd);
  return {};
}

bool ImGuiOverlay::wantsMouse() const { return ImGui::GetIO().WantCaptureMouse; }
bool ImGuiOverlay::wantsKeyboard() const { return ImGui::GetIO().WantCaptureKeyboard; }

}  // namespace spire::explore
