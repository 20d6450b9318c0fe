// Every overload of the built-in table that Spire code may call must compile
// in the GLSL dialect the kernels are written in (kGlslVersionLines): the
// table follows GLSL 4.50, and the kernels declare an older version plus
// extensions, so a 4.50 function that no extension brings back would pass
// Spire's checks and then fail in glslang.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <map>
#include <string>

#include "codegen/spirv_compiler.h"
#include "sema/builtins.h"

namespace spire::codegen {
namespace {

// A constant expression of `type` with every component 0, so that the
// arguments that must be constant (offsets, gather components) are.
std::string zeroOf(const sem::Type& type) {
  if (!type.isArray()) return fmt::format("{}(0)", type.name());
  std::string elements;
  for (uint32_t i = 0; i < type.arraySize; ++i) elements += (i ? ", " : "") + zeroOf(*type.element);
  return fmt::format("{}({})", type.name(), elements);
}

// One fragment shader calling every overload once; samplers are uniforms,
// one per sampler type, and `out` and `inout` arguments are variables.
std::string callEveryOverload(const sem::BuiltinTable& table, size_t& calls) {
  std::map<std::string, std::string> samplers;  // type -> uniform name
  std::string body;
  for (std::string_view name : table.names()) {
    for (const sem::BuiltinOverload& overload : *table.lookup(name)) {
      std::string block = "  {\n";
      std::string arguments;
      for (size_t i = 0; i < overload.params.size(); ++i) {
        const sem::Type& type = *overload.params[i].type;
        std::string argument = fmt::format("a{}", i);
        if (type.isSampler()) {
          auto [it, added] = samplers.try_emplace(type.name(), fmt::format("spire_sampler{}", samplers.size()));
          argument = it->second;
        } else if (overload.params[i].direction == ast::ParamDirection::In) {
          block += fmt::format("    const {} {} = {};\n", type.name(), argument, zeroOf(type));
        } else {
          block += fmt::format("    {} {} = {};\n", type.name(), argument, zeroOf(type));
        }
        arguments += (i ? ", " : "") + argument;
      }
      body += block + fmt::format("    {}({});\n  }}\n", name, arguments);
      ++calls;
    }
  }
  std::string uniforms;
  uint32_t binding = 0;
  for (const auto& [type, uniform] : samplers) {
    uniforms += fmt::format("layout(set = 0, binding = {}) uniform {} {};\n", binding++, type, uniform);
  }
  return fmt::format(
      "{}{}layout(location = 0) out vec4 spire_color;\nvoid main() {{\n{}  spire_color = vec4(0.0);\n}}\n",
      kGlslVersionLines, uniforms, body);
}

TEST(BuiltinGlslTest, EveryOverloadOfTheBuiltinTableCompilesInTheKernelsGlslVersion) {
  sem::TypeTable types;
  const sem::BuiltinTable table(types);
  size_t calls = 0;
  const std::string glsl = callEveryOverload(table, calls);
  ASSERT_GT(calls, 500u);  // the whole table, not a part of it
  const SpirvResult result = compileGlslToSpirv(ShaderStage::Fragment, glsl, "builtins.frag");
  EXPECT_TRUE(result.ok()) << result.log;
}

// The functions GLSL 4.50 added, which the extensions must bring back, and
// which fail without them: the test above is not passing because glslang
// accepts anything.
TEST(BuiltinGlslTest, TheGlsl450FunctionsFailInGlsl440WithoutTheExtensions) {
  for (const char* call : {"dFdxFine(1.0)", "fwidthCoarse(1.0)", "mix(1, 2, true)", "mix(true, false, true)"}) {
    const std::string glsl = fmt::format(
        "#version 440\nlayout(location = 0) out vec4 c;\nvoid main() {{\n  {};\n  c = vec4(0.0);\n}}\n", call);
    EXPECT_FALSE(compileGlslToSpirv(ShaderStage::Fragment, glsl, "old.frag").ok()) << call;
  }
}

}  // namespace
}  // namespace spire::codegen
