// One kernel under construction: its sections of GLSL text, its names and
// its reflection. Strategies add to it; the generator assembles it.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "codegen/glsl_names.h"
#include "codegen/spirv_compiler.h"
#include "reflection/reflection.h"
#include "sema/semantic_model.h"

namespace spire::codegen {

// GLSL spelling of a type; struct names go through `structNames` (a struct
// named like a GLSL reserved word is renamed in the kernel).
std::string glslTypeName(const sem::Type* type, const std::map<std::string, std::string, std::less<>>& structNames);
// `T name` with array dimensions where GLSL wants them.
std::string declareVariable(const sem::Type* type, const std::string& name,
                            const std::map<std::string, std::string, std::less<>>& structNames);
// Number of `in`/`out` locations a value of `type` occupies.
uint32_t locationSlots(const sem::Type* type);

// A component crossing this kernel's boundary.
struct KernelValue {
  sem::ComponentId component = 0;
  std::string sourceName;  // the Spire name, kept in reflection
  std::string glslName;    // the global that holds the value in this kernel
  const sem::Type* type = nullptr;
  // Hints from component and decision attributes ([Format], [TextureSize]).
  std::vector<std::pair<std::string, std::string>> attributes;
};

class KernelBuilder {
 public:
  KernelBuilder(std::string world, ShaderStage stage) : world_(std::move(world)), stage_(stage) {}

  const std::string& world() const { return world_; }
  ShaderStage stage() const { return stage_; }
  NameTable& names() { return names_; }
  std::map<std::string, std::string, std::less<>>& structNames() { return structNames_; }
  std::string declaration(const sem::Type* type, const std::string& name) const {
    return declareVariable(type, name, structNames_);
  }
  // Bindings are numbered from 0 in each kernel, and each stage of a GPU
  // pipeline has its own descriptor set (vertex and compute 0, fragment 1),
  // so a kernel's resources depend on nothing outside its world and the
  // stages of one pipeline never collide.
  uint32_t allocateBinding() { return nextBinding_++; }
  uint32_t descriptorSet() const { return stage_ == ShaderStage::Fragment ? 1 : 0; }

  // Interface declarations (in/out variables, blocks, samplers, buffers).
  void declare(std::string text) { declarations_.push_back(std::move(text)); }
  // A private global holding a component value in this kernel.
  void declareGlobal(const sem::Type* type, const std::string& name);
  // Statements at the start of main(), before anything else.
  void addEntry(std::string statement) { entry_.push_back(std::move(statement)); }
  // Statements that fetch imported values, before the computations.
  void addFetch(std::string statement) { fetches_.push_back(std::move(statement)); }
  // Statements that store exported values, after the computations.
  void addStore(std::string statement) { stores_.push_back(std::move(statement)); }

  // Reflection records: one per input, output and block.
  void reflectInput(reflection::KernelInput entry) { inputs_.push_back(std::move(entry)); }
  void reflectOutput(reflection::KernelOutput entry) { outputs_.push_back(std::move(entry)); }
  void reflectBlock(reflection::Block entry) { blocks_.push_back(std::move(entry)); }

  const std::vector<std::string>& declarations() const { return declarations_; }
  const std::vector<std::string>& globals() const { return globals_; }
  const std::vector<std::string>& entry() const { return entry_; }
  const std::vector<std::string>& fetches() const { return fetches_; }
  const std::vector<std::string>& stores() const { return stores_; }
  const std::vector<reflection::KernelInput>& inputs() const { return inputs_; }
  const std::vector<reflection::KernelOutput>& outputs() const { return outputs_; }
  const std::vector<reflection::Block>& blocks() const { return blocks_; }

 private:
  std::string world_;
  ShaderStage stage_;
  uint32_t nextBinding_ = 0;
  NameTable names_;
  std::map<std::string, std::string, std::less<>> structNames_;
  std::vector<std::string> declarations_;
  std::vector<std::string> globals_;
  std::vector<std::string> entry_;
  std::vector<std::string> fetches_;
  std::vector<std::string> stores_;
  std::vector<reflection::KernelInput> inputs_;
  std::vector<reflection::KernelOutput> outputs_;
  std::vector<reflection::Block> blocks_;
};

}  // namespace spire::codegen
