// Whether a device test runs, skips or fails, decided from the error of its
// Vulkan context and the CI environment variable. A machine without a Vulkan
// driver or VK_LAYER_KHRONOS_validation skips every device test, which on a
// developer's machine is the honest outcome but in CI would report a green
// run that tested nothing; so under CI=true the same error fails the test.
#pragma once

#include <cctype>
#include <string>
#include <string_view>

#include "vk/result.h"

namespace spire::vk::testing {

// Failures that mean "no usable Vulkan here" rather than a bug in the library.
inline bool vulkanUnavailable(const VkError& error) {
  return error.result == VK_ERROR_INCOMPATIBLE_DRIVER || error.result == VK_ERROR_INITIALIZATION_FAILED ||
         error.result == VK_ERROR_LAYER_NOT_PRESENT;
}

// The value of the CI variable (nullptr when unset) says CI when it is "true"
// (any case) or "1", as CI services set it.
inline bool runningInCi(const char* ci) {
  if (ci == nullptr) return false;
  std::string value(ci);
  for (char& c : value) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return value == "true" || value == "1";
}

enum class DeviceAction { Run, Skip, Fail };

struct DeviceVerdict {
  DeviceAction action = DeviceAction::Run;
  std::string message;  // why, for Skip and Fail
};

// `error` is the context's creation error, nullptr when the context exists;
// `ci` is the CI variable's value (std::getenv("CI")).
inline DeviceVerdict deviceVerdict(const VkError* error, const char* ci) {
  if (error == nullptr) return {};
  if (!vulkanUnavailable(*error)) return {DeviceAction::Fail, error->message()};
  if (!runningInCi(ci)) return {DeviceAction::Skip, "no Vulkan: " + error->message()};
  return {DeviceAction::Fail,
          "no Vulkan under CI=true, where the device tests must run rather than skip: " + error->message() +
              ". Install a Vulkan driver and VK_LAYER_KHRONOS_validation (scripts/install-deps.sh), or unset CI to "
              "let these tests skip"};
}

}  // namespace spire::vk::testing
