// The device tests' verdict on a missing Vulkan (device_verdict.h): a skip
// with the reason on a developer's machine, a failure under CI=true.
#include "engine/device_verdict.h"

#include <gtest/gtest.h>

namespace spire::vk::testing {
namespace {

const VkError kNoLayer{VK_ERROR_LAYER_NOT_PRESENT, "Context::create", "VK_LAYER_KHRONOS_validation is not installed"};
const VkError kNoDriver{VK_ERROR_INCOMPATIBLE_DRIVER, "vkCreateInstance", {}};

TEST(DeviceVerdict, RunsWhenTheContextExists) {
  EXPECT_EQ(deviceVerdict(nullptr, nullptr).action, DeviceAction::Run);
  EXPECT_EQ(deviceVerdict(nullptr, "true").action, DeviceAction::Run);
}

TEST(DeviceVerdict, SkipsWithTheReasonOutsideCi) {
  for (const char* ci : {static_cast<const char*>(nullptr), "", "false", "0"}) {
    for (const VkError& error : {kNoLayer, kNoDriver}) {
      const DeviceVerdict verdict = deviceVerdict(&error, ci);
      EXPECT_EQ(verdict.action, DeviceAction::Skip) << (ci ? ci : "unset");
      EXPECT_EQ(verdict.message, "no Vulkan: " + error.message());
    }
  }
}

TEST(DeviceVerdict, FailsWithAClearMessageUnderCi) {
  for (const char* ci : {"true", "TRUE", "1"}) {
    for (const VkError& error : {kNoLayer, kNoDriver}) {
      const DeviceVerdict verdict = deviceVerdict(&error, ci);
      EXPECT_EQ(verdict.action, DeviceAction::Fail) << ci;
      EXPECT_EQ(verdict.message.rfind("no Vulkan under CI=true", 0), 0U) << verdict.message;
      EXPECT_NE(verdict.message.find(error.message()), std::string::npos) << verdict.message;
    }
  }
  EXPECT_NE(deviceVerdict(&kNoLayer, "true").message.find("VK_LAYER_KHRONOS_validation is not installed"),
            std::string::npos);
}

// Anything else is a bug in the library, not a missing driver: it fails
// whether or not CI is set.
TEST(DeviceVerdict, OtherErrorsAlwaysFail) {
  const VkError outOfMemory{VK_ERROR_OUT_OF_HOST_MEMORY, "vkCreateDevice", {}};
  for (const char* ci : {static_cast<const char*>(nullptr), "true"}) {
    const DeviceVerdict verdict = deviceVerdict(&outOfMemory, ci);
    EXPECT_EQ(verdict.action, DeviceAction::Fail);
    EXPECT_EQ(verdict.message, outOfMemory.message());
  }
}

}  // namespace
}  // namespace spire::vk::testing
