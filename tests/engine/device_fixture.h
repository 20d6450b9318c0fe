// The fixture of every test that needs a Vulkan device: one context for the
// suite (instance and device creation with validation dominate the run time on
// lavapipe), with VK_LAYER_KHRONOS_validation on. A test fails on any
// validation message; without a usable Vulkan driver it skips with the reason,
// or fails under CI=true (device_verdict.h).
#pragma once

#include <gtest/gtest.h>

#if defined(__SANITIZE_ADDRESS__)
#include <dlfcn.h>
#include <link.h>
#endif

#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

#include "engine/device_verdict.h"
#include "vk/context.h"

namespace spire::vk::testing {

#if defined(__SANITIZE_ADDRESS__)
// The loader dlcloses the driver (lavapipe, with LLVM) in vkDestroyInstance.
// Heap blocks the driver keeps in its globals then look unreferenced, and
// LeakSanitizer reports them at exit from "<unknown module>". Pinning every
// loaded library (RTLD_NODELETE) keeps those globals mapped and visible.
inline void pinLoadedLibraries() {
  std::vector<std::string> names;
  dl_iterate_phdr(
      [](dl_phdr_info* info, size_t /*size*/, void* out) {
        if (info->dlpi_name != nullptr && info->dlpi_name[0] != '\0') {
          static_cast<std::vector<std::string>*>(out)->push_back(info->dlpi_name);
        }
        return 0;
      },
      &names);
  // dlopen outside the iteration, which holds the loader's lock.
  for (const std::string& name : names) dlopen(name.c_str(), RTLD_NOW | RTLD_NOLOAD | RTLD_NODELETE);
}
#endif

class DeviceTest : public ::testing::Test {
 protected:
  // One context for the suite: instance and device creation with validation
  // dominate the run time on lavapipe.
  static void SetUpTestSuite() {
    ContextOptions options;
    options.validation = true;
    context_.emplace(Context::create(options));
#if defined(__SANITIZE_ADDRESS__)
    pinLoadedLibraries();
#endif
  }
  static void TearDownTestSuite() { context_.reset(); }

  void SetUp() override {
    const DeviceVerdict verdict = deviceVerdict(context_->ok() ? nullptr : &context_->error(), std::getenv("CI"));
    if (verdict.action == DeviceAction::Skip) GTEST_SKIP() << verdict.message;
    if (verdict.action == DeviceAction::Fail) FAIL() << verdict.message;
    ctx().clearValidationMessages();
  }

  void TearDown() override {
    if (!context_->ok()) return;
    for (const std::string& message : ctx().validationMessages()) ADD_FAILURE() << message;
  }

  static Context& ctx() { return context_->value(); }

  static std::optional<Expected<Context>> context_;
};

inline std::optional<Expected<Context>> DeviceTest::context_;

}  // namespace spire::vk::testing
