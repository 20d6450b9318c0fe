// The simplify tests' fixture: a shader written to a file of its own
// temporary folder (the module spire-simplify writes `using`s it) and
// compiled with the repository's pipelines and stdlib.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

#include <unistd.h>

#include "driver/shader_library.h"
#include "simplify/simplification.h"

namespace spire::simplify {

class SimplifyFixture : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("spire-simplify-" + std::to_string(getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->test_suite_name() + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override {
    if (!HasFailure()) std::filesystem::remove_all(dir_);
  }
  // A library of `shader` written to a file (the module's `using` needs one).
  ShaderLibrary& load(const std::string& shader) {
    source_ = dir_ / "s.spire";
    std::ofstream(source_) << shader;
    library_ = std::make_unique<ShaderLibrary>(frontEnd());
    EXPECT_TRUE(library_->addFile(source_.string()));
    EXPECT_TRUE(library_->compile());
    return *library_;
  }
  // The module of simplified variations of the shader S of load(),
  // written beside it, with `rules` besides the built-in ones.
  Expected<Simplified, Failure> simplifyS(const UserRules* rules = nullptr) {
    SimplifyOptions options;
    options.shader = "S";
    options.outputPath = (dir_ / "s_simplified.spire").string();
    options.frontEnd = frontEnd();
    options.userRules = rules;
    return simplifyShader(*library_, options);
  }
  // The repository's pipelines and stdlib, as spirec's -I would give them.
  static FrontEndOptions frontEnd() {
    FrontEndOptions options;
    options.includeDirs = {SPIRE_SOURCE_DIR};
    return options;
  }

  std::filesystem::path dir_;
  std::filesystem::path source_;
  std::unique_ptr<ShaderLibrary> library_;
};

}  // namespace spire::simplify
