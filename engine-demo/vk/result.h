// Errors as values for the Vulkan layer: every fallible call returns
// Expected<T>, never throws and never aborts, so a missing driver or a bad
// user input reaches the caller as a message it can print or skip on.
#pragma once

#include <vulkan/vulkan.h>

#include <string>
#include <utility>
#include <variant>

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

// A value or a VkError (GCC 12 has no std::expected). Accessing the wrong
// alternative is a programming error and throws std::bad_variant_access.
template <class T>
class [[nodiscard]] Expected {
 public:
  Expected(T value) : state_(std::move(value)) {}  // NOLINT(google-explicit-constructor)
  Expected(VkError error) : state_(std::move(error)) {}  // NOLINT(google-explicit-constructor)

  bool ok() const { return state_.index() == 0; }
  explicit operator bool() const { return ok(); }

  T& value() & { return std::get<0>(state_); }
  const T& value() const& { return std::get<0>(state_); }
  T&& value() && { return std::get<0>(std::move(state_)); }
  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }
  T& operator*() & { return value(); }
  const T& operator*() const& { return value(); }

  const VkError& error() const { return std::get<1>(state_); }

 private:
  std::variant<T, VkError> state_;
};

// Success or a VkError, for operations without a result value.
template <>
class [[nodiscard]] Expected<void> {
 public:
  Expected() = default;
  Expected(VkError error) : error_(std::move(error)), ok_(false) {}  // NOLINT(google-explicit-constructor)

  bool ok() const { return ok_; }
  explicit operator bool() const { return ok_; }
  const VkError& error() const { return error_; }

 private:
  VkError error_;
  bool ok_ = true;
};

// Wraps a VkResult: success for VK_SUCCESS, otherwise VkError{result, what}.
inline Expected<void> check(VkResult result, const char* what) {
  if (result == VK_SUCCESS) return {};
  return VkError{result, what, {}};
}

}  // namespace spire::vk
