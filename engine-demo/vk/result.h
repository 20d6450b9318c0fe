// Errors as values for the Vulkan layer: every fallible call returns
// Expected<T>, never throws and never aborts, so a missing driver or a bad
// user input reaches the caller as a message it can print or skip on.
#pragma once

#include <vulkan/vulkan.h>

#include <string>

#include "support/expected.h"

namespace spire::vk {

// "VK_ERROR_DEVICE_LOST" for every core VkResult (and the common extension
// results); "VK_RESULT_<n>" for anything else, valid until the next such
// unknown value is named on the same thread.
const char* resultName(VkResult result);

struct VkError {
  VkResult result = VK_ERROR_UNKNOWN;
  std::string what;    // the call or operation that failed, e.g. "vkCreateDevice"
  std::string detail;  // optional context, e.g. "no device matches 'nvidia'"

  // "vkCreateDevice failed: VK_ERROR_INITIALIZATION_FAILED", with " (detail)"
  // appended when there is one.
  std::string message() const;
};

// A value or a VkError: every fallible Vulkan-layer call returns one.
template <class T>
using Expected = spire::Expected<T, VkError>;

// Wraps a VkResult: success for VK_SUCCESS, otherwise VkError{result, what}.
inline Expected<void> check(VkResult result, const char* what) {
  if (result == VK_SUCCESS) return {};
  return VkError{result, what, {}};
}

}  // namespace spire::vk
