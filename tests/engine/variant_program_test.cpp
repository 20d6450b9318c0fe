// What the engine verifies when it loads a `spirec -o` directory: each
// kernel's SPIR-V is the one its reflection was written with, and each
// kernel's interface (locations, descriptor bindings) is the one its
// reflection states. A directory that fails either is a clear error, never
// a program that draws garbage or crashes in recordDraw.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <unistd.h>
#include <string>

#include "driver/spirec.h"
#include "reflection/reflection_json.h"
#include "renderer/variant_program.h"
#include "support/file_io.h"

namespace spire::engine {
namespace {

namespace fs = std::filesystem;

class VariantProgramLoadTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::path(::testing::TempDir()) / ("spire_load_" + std::to_string(::getpid()));
    fs::remove_all(root_);
    ASSERT_EQ(spirec("terrain_full_quality.decisions", "a"), 0);
    ASSERT_EQ(spirec("terrain_baked_albedo.decisions", "b"), 0);
  }
  void TearDown() override { fs::remove_all(root_); }

  // Compiles the Terrain example with one decision file into ROOT/<out>/Terrain.
  int spirec(const std::string& decisions, const std::string& out) {
    std::ostringstream sink;
    const std::string examples = std::string(SPIRE_SOURCE_DIR) + "/examples/";
    return runSpirec({examples + "terrain.spire", "--decisions", examples + "decisions/" + decisions, "-o",
                      (root_ / out).string(), "--emit", "both"},
                     sink, sink);
  }
  fs::path dir(const std::string& out) const { return root_ / out / "Terrain"; }

  fs::path root_;
};

TEST_F(VariantProgramLoadTest, WhatSpirecWroteLoads) {
  auto program = loadProgram(dir("a"));
  ASSERT_TRUE(program) << program.error().message;
  EXPECT_EQ(program->shader, "Terrain");
  for (const KernelProgram& kernel : program->kernels) EXPECT_FALSE(kernel.spirv.empty()) << kernel.world;
}

TEST_F(VariantProgramLoadTest, SpirvFromAnotherCompileIsAnError) {
  // The Fragment kernel of another variant, beside this variant's reflection.
  fs::copy_file(dir("b") / "Fragment.spv", dir("a") / "Fragment.spv", fs::copy_options::overwrite_existing);
  auto program = loadProgram(dir("a"));
  ASSERT_FALSE(program);
  EXPECT_NE(program.error().message.find("Fragment.spv' is not the kernel this reflection describes"),
            std::string::npos)
      << program.error().message;
  EXPECT_NE(program.error().message.find("mixes the output of two compiles"), std::string::npos);
}

TEST_F(VariantProgramLoadTest, ReflectionThatDoesNotMatchTheSpirvIsAnError) {
  // A reflection edited to move a varying: the hashes still match, the interface does not.
  const fs::path file = dir("a") / "reflection.json";
  auto document = nlohmann::ordered_json::parse(*readWholeFile(file.string()));
  bool moved = false;
  for (auto& kernel : document["kernels"]) {
    if (kernel["world"] != "Fragment") continue;
    for (auto& input : kernel["inputs"]) {
      if (input["kind"] == "varying" && !moved) {
        input["location"] = 17;
        moved = true;
      }
    }
  }
  ASSERT_TRUE(moved);
  std::ofstream(file) << document.dump(2);
  auto program = loadProgram(dir("a"));
  ASSERT_FALSE(program);
  EXPECT_NE(program.error().message.find("the SPIR-V of kernel 'Fragment' does not match its reflection"),
            std::string::npos)
      << program.error().message;
  EXPECT_NE(program.error().message.find(" at location "), std::string::npos) << program.error().message;
}

TEST_F(VariantProgramLoadTest, AFileNameOutsideTheDirectoryIsAnError) {
  const fs::path file = dir("a") / "reflection.json";
  auto document = nlohmann::ordered_json::parse(*readWholeFile(file.string()));
  document["kernels"][0]["spirv"] = "../../b/Terrain/Vertex.spv";
  std::ofstream(file) << document.dump(2);
  auto program = loadProgram(dir("a"));
  ASSERT_FALSE(program);
  EXPECT_NE(program.error().message.find("not a file name in the reflection's directory"), std::string::npos)
      << program.error().message;
}

TEST_F(VariantProgramLoadTest, AMissingOrTruncatedKernelIsAnError) {
  fs::resize_file(dir("a") / "Vertex.spv", 6);
  auto program = loadProgram(dir("a"));
  ASSERT_FALSE(program);
  EXPECT_NE(program.error().message.find("Vertex.spv"), std::string::npos) << program.error().message;
  fs::remove(dir("a") / "Vertex.spv");
  EXPECT_FALSE(loadProgram(dir("a")));
}

}  // namespace
}  // namespace spire::engine
