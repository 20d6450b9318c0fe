// The checks the generator's property relies on, on hand-made inputs: the
// interface check must see a mismatch when there is one (or the property
// would pass vacuously), and reversing imports must touch nothing else.
#include "gen/interface_check.h"

#include <gtest/gtest.h>

#include "gen/campaign.h"

namespace spire::testgen {
namespace {

namespace rf = reflection;

sem::Pipeline twoStagePipeline() {
  sem::Pipeline p;
  for (const char* name : {"M0", "V0", "F0"}) {
    p.worldByName.emplace(name, static_cast<sem::WorldId>(p.worlds.size()));
    sem::World world;
    world.name = name;
    world.isAbstract = std::string(name) == "M0";
    p.worlds.push_back(world);
  }
  return p;
}

rf::KernelInput varyingIn(const char* component, const char* type, uint32_t location, const char* from) {
  rf::KernelInput in;
  in.component = component;
  in.type = rf::parseValueType(type);
  in.strategy = "standardImport";
  in.from = from;
  in.location = location;
  return in;
}

rf::KernelOutput varyingOut(const char* component, const char* type, uint32_t location) {
  rf::KernelOutput out;
  out.component = component;
  out.type = rf::parseValueType(type);
  out.location = location;
  return out;
}

codegen::Kernel kernel(const char* world, std::vector<rf::KernelInput> inputs, std::vector<rf::KernelOutput> outputs) {
  codegen::Kernel k;
  k.world = world;
  k.reflection.world = world;
  k.reflection.inputs = std::move(inputs);
  k.reflection.outputs = std::move(outputs);
  return k;
}

codegen::GeneratedShader shader(uint32_t fragmentLocation, const char* fragmentType) {
  codegen::GeneratedShader s;
  s.kernels.push_back(kernel("V0", {varyingIn("pos", "vec3", 0, "M0"), varyingIn("m", "mat3", 1, "M0")},
                             {varyingOut("n", "vec3", 0), varyingOut("t", "vec2", 1)}));
  s.kernels.push_back(
      kernel("F0", {varyingIn("n", fragmentType, fragmentLocation, "V0")}, {varyingOut("output", "vec4", 0)}));
  return s;
}

TEST(GeneratorInterfaceCheck, MatchingVaryingsPass) {
  EXPECT_TRUE(checkInterfaces(shader(0, "vec3"), twoStagePipeline()).empty());
}

TEST(GeneratorInterfaceCheck, LocationOrTypeMismatchIsReported) {
  EXPECT_EQ(checkInterfaces(shader(1, "vec3"), twoStagePipeline()).size(), 1u);
  EXPECT_EQ(checkInterfaces(shader(0, "vec4"), twoStagePipeline()).size(), 1u);
}

TEST(GeneratorInterfaceCheck, OverlappingSpansAreReported) {
  codegen::GeneratedShader s = shader(0, "vec3");
  s.kernels[0].reflection.inputs.push_back(varyingIn("uv", "vec2", 3, "M0"));  // inside mat3 m's 1..3
  ASSERT_EQ(checkInterfaces(s, twoStagePipeline()).size(), 1u);
  EXPECT_NE(checkInterfaces(s, twoStagePipeline())[0].find("location 3"), std::string::npos);
  EXPECT_EQ(locationSpan(rf::parseValueType("mat4x3")), 4);
  EXPECT_EQ(locationSpan(rf::parseValueType("vec4[3]")), 3);
  EXPECT_EQ(locationSpan(rf::parseValueType("mat2[2]")), 4);
}

TEST(GeneratorInterfaceCheck, ImportsReversedTouchesOnlyImportLines) {
  const std::string program = "pipeline P {\n  import A->B using x;\n  world B;\n    import C->B using y;\n}\n";
  EXPECT_EQ(withImportsReversed(program),
            "pipeline P {\n    import C->B using y;\n  world B;\n  import A->B using x;\n}\n");
}

}  // namespace
}  // namespace spire::testgen
