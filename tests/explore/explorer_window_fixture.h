// What spire-explore's window tests share: a device test (engine/
// device_fixture.h), so that under the asan preset lavapipe stays loaded and
// LeakSanitizer can name (and tests/lsan.supp suppress) the blocks the
// driver keeps, and under CI a missing device fails; skipped without a
// display (run under xvfb-run); a fresh folder per test for scripts, logs and
// screenshots, kept when the test fails.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "common/have_display.h"
#include "engine/device_fixture.h"
#include "explore/explore_cli.h"
#include "support/file_io.h"

namespace spire::explore::testing {

class ExplorerWindowFixture : public vk::testing::DeviceTest {
 protected:
  void SetUp() override {
    namespace fs = std::filesystem;
    DeviceTest::SetUp();
    if (IsSkipped() || HasFatalFailure()) return;
    if (!spire::testing::haveDisplay()) GTEST_SKIP() << "no display (run under xvfb-run to cover this)";
    dir_ = fs::temp_directory_path() / ("spire-explore-" + std::to_string(getpid()) + "-" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    if (!HasFailure() && !dir_.empty()) std::filesystem::remove_all(dir_);
  }
  std::filesystem::path script(const std::string& text) const {
    const std::filesystem::path path = dir_ / "script.explore";
    std::ofstream(path) << text;
    return path;
  }
  int explore(std::vector<std::string> args) { return runExploreTool(args, out_, err_); }
  nlohmann::json log() const {
    return nlohmann::json::parse(readWholeFile((dir_ / "log.json").string()).value_or("null"));
  }

  std::filesystem::path dir_;
  std::ostringstream out_;
  std::ostringstream err_;
};

}  // namespace spire::explore::testing
