// The Vulkan context of the engine: an instance (optionally with the Khronos
// validation layer), one physical device, one graphics+compute queue, a
// command pool and a one-shot submit helper. Headless unless the caller hands
// it a window's surface, which it then owns and can present to.
//
// The one-shot helper may be called from any thread (a tool prepares the
// next scene's bakes and pipelines on a worker while the window draws the
// current one): each call records into a command pool of its own, and
// every use of the queue holds the queue lock, which Vulkan requires of
// queue submissions and presents from more than one thread.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "vk/handle.h"
#include "vk/result.h"

namespace spire::vk {

struct ContextOptions {
  // Loads VK_LAYER_KHRONOS_validation and records its warnings and errors
  // (see Context::validationMessages). Fails with VK_ERROR_LAYER_NOT_PRESENT
  // when the layer is not installed.
  bool validation = false;
  // Case-insensitive substring of the device name (the demo's --device);
  // empty picks llvmpipe (lavapipe) when present, else the first device.
  std::string deviceFilter;
  std::string applicationName = "spire-engine";
  // Instance extensions besides the library's own, e.g. the surface
  // extensions a window system needs (glfwGetRequiredInstanceExtensions).
  std::vector<std::string> instanceExtensions;
};

// Creates the surface of a window once the instance exists. It is a callback
// because the surface needs the instance while the choice of queue family
// needs the surface; the context takes ownership of what it returns.
using SurfaceFactory = std::function<Expected<VkSurfaceKHR>(VkInstance)>;

struct PhysicalDeviceInfo {
  VkPhysicalDevice handle = VK_NULL_HANDLE;
  std::string name;
  VkPhysicalDeviceType type = VK_PHYSICAL_DEVICE_TYPE_OTHER;
  uint32_t apiVersion = 0;
};

// "discrete GPU", "CPU", ...
const char* deviceTypeName(VkPhysicalDeviceType type);

// Index of the device to use among `devices` (see ContextOptions::deviceFilter);
// std::nullopt when none matches or the list is empty.
std::optional<size_t> selectPhysicalDevice(std::span<const PhysicalDeviceInfo> devices, std::string_view filter);

// Warnings and errors reported through VK_EXT_debug_utils. Held behind a
// pointer so the messenger's user data stays valid when a Context moves.
struct ValidationLog {
  std::mutex mutex;
  std::vector<std::string> messages;
};

class Context {
 public:
  // With a `surfaceFactory`, the queue must be able to present to the surface
  // and VK_KHR_swapchain is enabled; a device that cannot present fails with
  // VK_ERROR_FEATURE_NOT_PRESENT. Without one the context is headless.
  static Expected<Context> create(const ContextOptions& options, const SurfaceFactory& surfaceFactory = {});

  VkInstance instance() const { return instance_.get(); }
  VkPhysicalDevice physicalDevice() const { return devices_[selected_].handle; }
  VkDevice device() const { return device_.get(); }
  VkQueue queue() const { return queue_; }
  uint32_t queueFamily() const { return queueFamily_; }
  // For the thread that draws frames (the swapchain's command buffers);
  // submitAndWait does not use it.
  VkCommandPool commandPool() const { return commandPool_.get(); }
  // Held around every vkQueueSubmit, vkQueuePresentKHR and vkDeviceWaitIdle
  // outside submitAndWait, which takes it itself.
  [[nodiscard]] std::unique_lock<std::mutex> lockQueue() const;
  // The window's surface (see create); VK_NULL_HANDLE when headless.
  VkSurfaceKHR surface() const { return surface_.get(); }

  // Every physical device the instance reports, and the selected one.
  const std::vector<PhysicalDeviceInfo>& physicalDevices() const { return devices_; }
  const PhysicalDeviceInfo& selectedDevice() const { return devices_[selected_]; }
  // The API version the device was created for: min(instance, device), >= 1.1.
  uint32_t apiVersion() const { return apiVersion_; }
  const VkPhysicalDeviceProperties& properties() const { return properties_; }
  // Whether vertex and fragment kernels may write storage buffers (enabled
  // whenever the device supports it).
  bool graphicsStores() const { return graphicsStores_; }
  uint32_t timestampValidBits() const { return timestampValidBits_; }

  // vkCmdBeginRendering / vkCmdEndRendering: core on 1.3, otherwise the
  // VK_KHR_dynamic_rendering entry points. Context creation fails when the
  // device has neither.
  PFN_vkCmdBeginRendering cmdBeginRendering = nullptr;
  PFN_vkCmdEndRendering cmdEndRendering = nullptr;

  // A memory type allowed by `typeBits` (VkMemoryRequirements) that has all of
  // `properties`; VK_ERROR_OUT_OF_DEVICE_MEMORY when none has.
  Expected<uint32_t> findMemoryType(uint32_t typeBits, VkMemoryPropertyFlags properties) const;
  // Allocates memory that satisfies `requirements` with `properties`.
  Expected<DeviceMemory> allocateMemory(const VkMemoryRequirements& requirements,
                                        VkMemoryPropertyFlags properties) const;

  // Records `record` into a fresh primary command buffer, submits it to the
  // queue and blocks until it finished. Any thread may call it.
  Expected<void> submitAndWait(const std::function<void(VkCommandBuffer)>& record) const;

  // Validation warnings and errors recorded so far (empty without validation).
  std::vector<std::string> validationMessages() const;
  void clearValidationMessages();

 private:
  Context() = default;

  // The steps of create(), in order; each fills in what the next needs.
  // The API version to ask for: the loader's, at most 1.3, at least 1.1.
  static Expected<uint32_t> requestedApiVersion();
  // The instance, with the validation layer and its messenger when asked.
  Expected<void> createInstance(const ContextOptions& options, uint32_t apiVersion);
  Expected<void> createMessenger();
  // The device `filter` selects, its properties and the version to use.
  Expected<void> pickPhysicalDevice(const std::string& filter, uint32_t apiVersion);
  // A graphics+compute family (that presents to the surface, with one).
  Expected<void> pickQueueFamily();
  // The extensions the device needs (swapchain with a surface, dynamic
  // rendering before 1.3); an error when it lacks them or the feature.
  Expected<std::vector<const char*>> deviceExtensions() const;
  // The device, its queue and the dynamic rendering entry points.
  Expected<void> createDevice();
  Expected<void> createCommandPool();
  Expected<CommandPool> makeCommandPool() const;

  // Declaration order is destruction order reversed: the log outlives the
  // messenger and instance that write to it; the pool dies before the device;
  // the surface after the device and before the instance.
  std::unique_ptr<ValidationLog> log_;
  Instance instance_;
  DebugMessenger messenger_;
  Surface surface_;
  std::vector<PhysicalDeviceInfo> devices_;
  size_t selected_ = 0;
  VkPhysicalDeviceProperties properties_{};
  VkPhysicalDeviceMemoryProperties memory_{};
  uint32_t apiVersion_ = 0;
  uint32_t timestampValidBits_ = 0;
  bool graphicsStores_ = false;
  Device device_;
  uint32_t queueFamily_ = 0;
  VkQueue queue_ = VK_NULL_HANDLE;
  CommandPool commandPool_;
  std::unique_ptr<std::mutex> queueMutex_ = std::make_unique<std::mutex>();  // behind a pointer: a Context moves
};

}  // namespace spire::vk
