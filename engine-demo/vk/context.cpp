#include "vk/context.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <utility>

namespace spire::vk {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

VKAPI_ATTR VkBool32 VKAPI_CALL recordMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                             VkDebugUtilsMessageTypeFlagsEXT /*types*/,
                                             const VkDebugUtilsMessengerCallbackDataEXT* data, void* userData) {
  auto* log = static_cast<ValidationLog*>(userData);
  const char* level = (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) != 0 ? "error" : "warning";
  std::lock_guard lock(log->mutex);
  log->messages.push_back(fmt::format("{}: {}", level, data->pMessage != nullptr ? data->pMessage : ""));
  // VK_FALSE: the call that triggered the message proceeds as it would without the layer.
  return VK_FALSE;
}

VkDebugUtilsMessengerCreateInfoEXT messengerInfo(ValidationLog* log) {
  VkDebugUtilsMessengerCreateInfoEXT info{};
  info.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT;
  info.messageSeverity =
      VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                     VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  info.pfnUserCallback = recordMessage;
  info.pUserData = log;
  return info;
}

bool layerAvailable(const char* name) {
  uint32_t count = 0;
  vkEnumerateInstanceLayerProperties(&count, nullptr);
  std::vector<VkLayerProperties> layers(count);
  vkEnumerateInstanceLayerProperties(&count, layers.data());
  return std::any_of(layers.begin(), layers.end(),
                     [&](const VkLayerProperties& layer) { return std::strcmp(layer.layerName, name) == 0; });
}

bool deviceExtensionAvailable(VkPhysicalDevice device, const char* name) {
  uint32_t count = 0;
  vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr);
  std::vector<VkExtensionProperties> extensions(count);
  vkEnumerateDeviceExtensionProperties(device, nullptr, &count, extensions.data());
  return std::any_of(extensions.begin(), extensions.end(),
                     [&](const VkExtensionProperties& ext) { return std::strcmp(ext.extensionName, name) == 0; });
}

std::string lower(std::string_view text) {
  std::string out(text);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

}  // namespace

const char* deviceTypeName(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated GPU";
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete GPU";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual GPU";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "CPU";
    default: return "other";
  }
}

std::optional<size_t> selectPhysicalDevice(std::span<const PhysicalDeviceInfo> devices, std::string_view filter) {
  // Without a filter prefer lavapipe: it is on every CI machine and gives
  // deterministic results, which is what the tests and goldens need.
  const std::string needle = filter.empty() ? "llvmpipe" : lower(filter);
  for (size_t i = 0; i < devices.size(); ++i) {
    if (lower(devices[i].name).find(needle) != std::string::npos) return i;
  }
  if (filter.empty() && !devices.empty()) return 0;
  return std::nullopt;
}

Expected<Context> Context::create(const ContextOptions& options, const SurfaceFactory& surfaceFactory) {
  Context ctx;
  ctx.log_ = std::make_unique<ValidationLog>();
  const auto requested = requestedApiVersion();
  if (!requested) return requested.error();
  if (auto ok = ctx.createInstance(options, *requested); !ok) return ok.error();
  if (surfaceFactory) {
    auto surface = surfaceFactory(ctx.instance());
    if (!surface) return surface.error();
    ctx.surface_ = Surface(*surface, {ctx.instance()});
  }
  if (auto ok = ctx.pickPhysicalDevice(options.deviceFilter, *requested); !ok) return ok.error();
  if (auto ok = ctx.pickQueueFamily(); !ok) return ok.error();
  if (auto ok = ctx.createDevice(); !ok) return ok.error();
  if (auto ok = ctx.createCommandPool(); !ok) return ok.error();
  return ctx;
}

Expected<uint32_t> Context::requestedApiVersion() {
  uint32_t instanceVersion = VK_API_VERSION_1_0;
  if (auto result = vkEnumerateInstanceVersion(&instanceVersion); result != VK_SUCCESS) {
    return VkError{result, "vkEnumerateInstanceVersion", {}};
  }
  if (instanceVersion < VK_API_VERSION_1_1) {
    return VkError{VK_ERROR_INCOMPATIBLE_DRIVER, "Context::create", "the Vulkan loader is older than 1.1"};
  }
  return std::min(instanceVersion, VK_API_VERSION_1_3);
}

Expected<void> Context::createInstance(const ContextOptions& options, uint32_t apiVersion) {
  VkApplicationInfo app{};
  app.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
  app.pApplicationName = options.applicationName.c_str();
  app.pEngineName = "spire-engine";
  app.apiVersion = apiVersion;

  std::vector<const char*> layers;
  std::vector<const char*> extensions;
  // Chained into the instance info so messages from vkCreateInstance and
  // vkDestroyInstance themselves are recorded too.
  VkDebugUtilsMessengerCreateInfoEXT debugInfo = messengerInfo(log_.get());
  VkInstanceCreateInfo instanceInfo{};
  instanceInfo.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
  if (options.validation) {
    if (!layerAvailable(kValidationLayer)) {
      return VkError{VK_ERROR_LAYER_NOT_PRESENT, "Context::create",
                     fmt::format("{} is not installed", kValidationLayer)};
    }
    layers.push_back(kValidationLayer);
    extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    instanceInfo.pNext = &debugInfo;
  }
  for (const std::string& extension : options.instanceExtensions) extensions.push_back(extension.c_str());
  instanceInfo.pApplicationInfo = &app;
  instanceInfo.enabledLayerCount = static_cast<uint32_t>(layers.size());
  instanceInfo.ppEnabledLayerNames = layers.data();
  instanceInfo.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
  instanceInfo.ppEnabledExtensionNames = extensions.data();
  VkInstance instance = VK_NULL_HANDLE;
  if (auto result = vkCreateInstance(&instanceInfo, nullptr, &instance); result != VK_SUCCESS) {
    return VkError{result, "vkCreateInstance", {}};
  }
  instance_ = Instance(instance, {});
  return options.validation ? createMessenger() : Expected<void>();
}

Expected<void> Context::createMessenger() {
  const VkInstance instance = instance_.get();
  auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
      vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
  auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
      vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
  if (create == nullptr || destroy == nullptr) {
    return VkError{VK_ERROR_EXTENSION_NOT_PRESENT, "Context::create", "VK_EXT_debug_utils entry points missing"};
  }
  const VkDebugUtilsMessengerCreateInfoEXT debugInfo = messengerInfo(log_.get());
  VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
  if (auto result = create(instance, &debugInfo, nullptr, &messenger); result != VK_SUCCESS) {
    return VkError{result, "vkCreateDebugUtilsMessengerEXT", {}};
  }
  messenger_ = DebugMessenger(messenger, {instance, destroy});
  return {};
}

Expected<void> Context::pickPhysicalDevice(const std::string& filter, uint32_t apiVersion) {
  uint32_t deviceCount = 0;
  if (auto result = vkEnumeratePhysicalDevices(instance(), &deviceCount, nullptr); result != VK_SUCCESS) {
    return VkError{result, "vkEnumeratePhysicalDevices", {}};
  }
  std::vector<VkPhysicalDevice> handles(deviceCount);
  vkEnumeratePhysicalDevices(instance(), &deviceCount, handles.data());
  for (VkPhysicalDevice handle : handles) {
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(handle, &props);
    devices_.push_back({handle, props.deviceName, props.deviceType, props.apiVersion});
  }
  const auto selected = selectPhysicalDevice(devices_, filter);
  if (!selected) {
    return VkError{
        VK_ERROR_INITIALIZATION_FAILED, "Context::create",
        devices_.empty() ? std::string("no Vulkan device found") : fmt::format("no device matches '{}'", filter)};
  }
  selected_ = *selected;
  vkGetPhysicalDeviceProperties(physicalDevice(), &properties_);
  vkGetPhysicalDeviceMemoryProperties(physicalDevice(), &memory_);
  apiVersion_ = std::min(apiVersion, properties_.apiVersion);
  if (apiVersion_ < VK_API_VERSION_1_1) {
    return VkError{VK_ERROR_INCOMPATIBLE_DRIVER, "Context::create",
                   fmt::format("'{}' supports only Vulkan 1.0", properties_.deviceName)};
  }
  return {};
}

// One family doing graphics and compute (and presenting, with a window)
// keeps submission and ownership trivial; every conformant implementation
// with graphics has one, and in practice it is also the one that presents.
Expected<void> Context::pickQueueFamily() {
  const VkPhysicalDevice physical = physicalDevice();
  uint32_t familyCount = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(physical, &familyCount, nullptr);
  std::vector<VkQueueFamilyProperties> families(familyCount);
  vkGetPhysicalDeviceQueueFamilyProperties(physical, &familyCount, families.data());
  const VkQueueFlags wanted = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
  const auto usable = [&](uint32_t index) {
    if ((families[index].queueFlags & wanted) != wanted) return false;
    if (!surface_) return true;
    VkBool32 presents = VK_FALSE;
    return vkGetPhysicalDeviceSurfaceSupportKHR(physical, index, surface_.get(), &presents) == VK_SUCCESS &&
           presents == VK_TRUE;
  };
  uint32_t family = 0;
  while (family < familyCount && !usable(family)) ++family;
  if (family == familyCount) {
    std::string detail = surface_
                             ? fmt::format("'{}' has no graphics+compute queue family that can present to the window",
                                           properties_.deviceName)
                             : std::string("no graphics+compute queue family");
    return VkError{VK_ERROR_FEATURE_NOT_PRESENT, "Context::create", std::move(detail)};
  }
  queueFamily_ = family;
  timestampValidBits_ = families[family].timestampValidBits;
  return {};
}

Expected<std::vector<const char*>> Context::deviceExtensions() const {
  const VkPhysicalDevice physical = physicalDevice();
  std::vector<const char*> extensions;
  if (surface_) {
    if (!deviceExtensionAvailable(physical, VK_KHR_SWAPCHAIN_EXTENSION_NAME)) {
      return VkError{VK_ERROR_FEATURE_NOT_PRESENT, "Context::create",
                     fmt::format("'{}' has no {}", properties_.deviceName, VK_KHR_SWAPCHAIN_EXTENSION_NAME)};
    }
    extensions.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
  }
  // Dynamic rendering: core feature on 1.3, otherwise the KHR extension.
  if (apiVersion_ < VK_API_VERSION_1_3) {
    if (!deviceExtensionAvailable(physical, VK_KHR_DYNAMIC_RENDERING_EXTENSION_NAME)) {
      return VkError{VK_ERROR_FEATURE_NOT_PRESENT, "Context::create",
                     fmt::format("'{}' has neither Vulkan 1.3 nor VK_KHR_dynamic_rendering", properties_.deviceName)};
    }
    extensions.push_back(VK_KHR_DYNAMIC_RENDERING_EXTENSION_NAME);
  }
  VkPhysicalDeviceDynamicRenderingFeatures dynamicRendering{};
  dynamicRendering.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DYNAMIC_RENDERING_FEATURES;
  VkPhysicalDeviceFeatures2 supported{};
  supported.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2;
  supported.pNext = &dynamicRendering;
  vkGetPhysicalDeviceFeatures2(physical, &supported);
  if (dynamicRendering.dynamicRendering != VK_TRUE) {
    return VkError{VK_ERROR_FEATURE_NOT_PRESENT, "Context::create", "dynamicRendering feature not supported"};
  }
  return extensions;
}

Expected<void> Context::createDevice() {
  const auto extensions = deviceExtensions();
  if (!extensions) return extensions.error();
  const float priority = 1.0F;
  VkDeviceQueueCreateInfo queueInfo{};
  queueInfo.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO;
  queueInfo.queueFamilyIndex = queueFamily_;
  queueInfo.queueCount = 1;
  queueInfo.pQueuePriorities = &priority;
  // Enable only what the library uses, not everything the device supports,
  // so code relying on other features fails validation here too.
  VkPhysicalDeviceDynamicRenderingFeatures enabledDynamic{};
  enabledDynamic.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DYNAMIC_RENDERING_FEATURES;
  enabledDynamic.dynamicRendering = VK_TRUE;
  // Storage writes from vertex and fragment kernels: instrumented kernels
  // record hazards that way (renderer/hazard_records.h).
  VkPhysicalDeviceFeatures supported{};
  vkGetPhysicalDeviceFeatures(physicalDevice(), &supported);
  VkPhysicalDeviceFeatures enabled{};
  enabled.vertexPipelineStoresAndAtomics = supported.vertexPipelineStoresAndAtomics;
  enabled.fragmentStoresAndAtomics = supported.fragmentStoresAndAtomics;
  graphicsStores_ =
      supported.vertexPipelineStoresAndAtomics == VK_TRUE && supported.fragmentStoresAndAtomics == VK_TRUE;
  VkDeviceCreateInfo deviceInfo{};
  deviceInfo.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO;
  deviceInfo.pNext = &enabledDynamic;
  deviceInfo.pEnabledFeatures = &enabled;
  deviceInfo.queueCreateInfoCount = 1;
  deviceInfo.pQueueCreateInfos = &queueInfo;
  deviceInfo.enabledExtensionCount = static_cast<uint32_t>(extensions->size());
  deviceInfo.ppEnabledExtensionNames = extensions->data();
  VkDevice device = VK_NULL_HANDLE;
  if (auto result = vkCreateDevice(physicalDevice(), &deviceInfo, nullptr, &device); result != VK_SUCCESS) {
    return VkError{result, "vkCreateDevice", {}};
  }
  device_ = Device(device, {});
  vkGetDeviceQueue(device, queueFamily_, 0, &queue_);
  const bool core13 = apiVersion_ >= VK_API_VERSION_1_3;
  cmdBeginRendering = reinterpret_cast<PFN_vkCmdBeginRendering>(
      vkGetDeviceProcAddr(device, core13 ? "vkCmdBeginRendering" : "vkCmdBeginRenderingKHR"));
  cmdEndRendering = reinterpret_cast<PFN_vkCmdEndRendering>(
      vkGetDeviceProcAddr(device, core13 ? "vkCmdEndRendering" : "vkCmdEndRenderingKHR"));
  if (cmdBeginRendering == nullptr || cmdEndRendering == nullptr) {
    return VkError{VK_ERROR_FEATURE_NOT_PRESENT, "Context::create", "dynamic rendering entry points missing"};
  }
  return {};
}

Expected<CommandPool> Context::makeCommandPool() const {
  VkCommandPoolCreateInfo poolInfo{};
  poolInfo.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
  poolInfo.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT | VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  poolInfo.queueFamilyIndex = queueFamily_;
  VkCommandPool pool = VK_NULL_HANDLE;
  if (auto result = vkCreateCommandPool(device(), &poolInfo, nullptr, &pool); result != VK_SUCCESS) {
    return VkError{result, "vkCreateCommandPool", {}};
  }
  return makeDeviceHandle<VkCommandPool, vkDestroyCommandPool>(device(), pool);
}

Expected<void> Context::createCommandPool() {
  auto pool = makeCommandPool();
  if (!pool) return pool.error();
  commandPool_ = std::move(pool).value();
  return {};
}

std::unique_lock<std::mutex> Context::lockQueue() const { return std::unique_lock(*queueMutex_); }

Expected<uint32_t> Context::findMemoryType(uint32_t typeBits, VkMemoryPropertyFlags properties) const {
  for (uint32_t i = 0; i < memory_.memoryTypeCount; ++i) {
    if ((typeBits & (1U << i)) != 0 && (memory_.memoryTypes[i].propertyFlags & properties) == properties) return i;
  }
  return VkError{VK_ERROR_OUT_OF_DEVICE_MEMORY, "Context::findMemoryType",
                 fmt::format("no memory type in mask {:#x} with properties {:#x}", typeBits, properties)};
}

Expected<DeviceMemory> Context::allocateMemory(const VkMemoryRequirements& requirements,
                                               VkMemoryPropertyFlags properties) const {
  auto type = findMemoryType(requirements.memoryTypeBits, properties);
  if (!type) return type.error();
  VkMemoryAllocateInfo alloc{};
  alloc.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
  alloc.allocationSize = requirements.size;
  alloc.memoryTypeIndex = *type;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  if (auto result = vkAllocateMemory(device(), &alloc, nullptr, &memory); result != VK_SUCCESS) {
    return VkError{result, "vkAllocateMemory", {}};
  }
  return makeDeviceHandle<VkDeviceMemory, vkFreeMemory>(device(), memory);
}

Expected<void> Context::submitAndWait(const std::function<void(VkCommandBuffer)>& record) const {
  // A pool of this call's own: a pool may be used by one thread at a time,
  // and making one costs microseconds against the submission's wait.
  auto pool = makeCommandPool();
  if (!pool) return pool.error();
  VkCommandBufferAllocateInfo allocInfo{};
  allocInfo.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
  allocInfo.commandPool = pool->get();
  allocInfo.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  allocInfo.commandBufferCount = 1;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  if (auto result = vkAllocateCommandBuffers(device(), &allocInfo, &cmd); result != VK_SUCCESS) {
    return VkError{result, "vkAllocateCommandBuffers", {}};
  }
  // The command buffer goes back to the pool on every path out.
  struct Free {
    VkDevice device;
    VkCommandPool pool;
    VkCommandBuffer cmd;
    ~Free() { vkFreeCommandBuffers(device, pool, 1, &cmd); }
  } freeOnExit{device(), pool->get(), cmd};

  VkCommandBufferBeginInfo beginInfo{};

  beginInfo.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
  beginInfo.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  if (auto ok = check(vkBeginCommandBuffer(cmd, &beginInfo), "vkBeginCommandBuffer"); !ok) return ok;
  record(cmd);
  // Whatever the commands wrote to host-visible memory is read once the
  // fence signals (bakes, hazard records): make it visible to the host.
  VkMemoryBarrier toHost{};
  toHost.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
  toHost.srcAccessMask = VK_ACCESS_MEMORY_WRITE_BIT;
  toHost.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &toHost, 0, nullptr,
                       0, nullptr);
  if (auto ok = check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer"); !ok) return ok;

  VkFenceCreateInfo fenceInfo{};

  fenceInfo.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
  VkFence rawFence = VK_NULL_HANDLE;
  if (auto ok = check(vkCreateFence(device(), &fenceInfo, nullptr, &rawFence), "vkCreateFence"); !ok) return ok;
  const Fence fence = makeDeviceHandle<VkFence, vkDestroyFence>(device(), rawFence);

  VkSubmitInfo submit{};

  submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &cmd;
  {
    const auto queueLock = lockQueue();
    if (auto ok = check(vkQueueSubmit(queue_, 1, &submit, fence.get()), "vkQueueSubmit"); !ok) return ok;
  }
  return check(vkWaitForFences(device(), 1, &rawFence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
}

std::vector<std::string> Context::validationMessages() const {
  std::lock_guard lock(log_->mutex);
  return log_->messages;
}

void Context::clearValidationMessages() {
  std::lock_guard lock(log_->mutex);
  log_->messages.clear();
}

}  // namespace spire::vk
