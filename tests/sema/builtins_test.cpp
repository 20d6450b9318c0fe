#include "sema/builtins.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <initializer_list>
#include <set>
#include <string>
#include <vector>

namespace spire::sem {
namespace {

using ast::ParamDirection;

class BuiltinTableTest : public ::testing::Test {
 protected:
  TypeTable types;
  BuiltinTable table{types};

  const Type* T(std::string_view name) const {
    const Type* type = types.lookupBuiltin(name);
    EXPECT_NE(type, nullptr) << name;
    return type;
  }

  // The overload of `name` whose parameter types are exactly `params`, or null.
  const BuiltinOverload* find(std::string_view name, std::initializer_list<std::string_view> params) const {
    const std::vector<BuiltinOverload>* set = table.lookup(name);
    if (!set) return nullptr;
    std::vector<const Type*> wanted;
    for (std::string_view p : params) wanted.push_back(T(p));
    for (const BuiltinOverload& o : *set) {
      if (o.params.size() != wanted.size()) continue;
      bool same = true;
      for (size_t i = 0; i < wanted.size(); ++i) same = same && o.params[i].type == wanted[i];
      if (same) return &o;
    }
    return nullptr;
  }

  // The result type name of the exact overload, or "<none>".
  std::string result(std::string_view name, std::initializer_list<std::string_view> params) const {
    const BuiltinOverload* o = find(name, params);
    return o ? o->result->name() : "<none>";
  }
};

TEST_F(BuiltinTableTest, TextureLookups) {
  EXPECT_EQ(result("texture", {"sampler2D", "vec2"}), "vec4");
  EXPECT_EQ(result("texture", {"sampler2D", "vec2", "float"}), "vec4");
  EXPECT_EQ(result("texture", {"sampler3D", "vec3"}), "vec4");
  EXPECT_EQ(result("texture", {"samplerCube", "vec3"}), "vec4");
  EXPECT_EQ(result("texture", {"sampler2DArray", "vec3", "float"}), "vec4");
  EXPECT_EQ(result("texture", {"sampler2D", "vec3"}), "<none>");
  EXPECT_EQ(result("textureLod", {"samplerCube", "vec3", "float"}), "vec4");
  EXPECT_EQ(result("textureOffset", {"sampler2D", "vec2", "ivec2"}), "vec4");
  EXPECT_EQ(result("textureOffset", {"sampler3D", "vec3", "ivec3"}), "vec4");
  EXPECT_EQ(result("textureOffset", {"sampler2DArray", "vec3", "ivec2", "float"}), "vec4");
  EXPECT_EQ(result("texelFetch", {"sampler2D", "ivec2", "int"}), "vec4");
  EXPECT_EQ(result("texelFetch", {"sampler2DArray", "ivec3", "int"}), "vec4");
  EXPECT_EQ(result("texelFetchOffset", {"sampler3D", "ivec3", "int", "ivec3"}), "vec4");
  EXPECT_EQ(result("textureProj", {"sampler2D", "vec3"}), "vec4");
  EXPECT_EQ(result("textureProj", {"sampler2D", "vec4", "float"}), "vec4");
  EXPECT_EQ(result("textureProj", {"sampler3D", "vec4"}), "vec4");
  EXPECT_EQ(result("textureProjLod", {"sampler2D", "vec4", "float"}), "vec4");
  EXPECT_EQ(result("textureGrad", {"sampler2DArray", "vec3", "vec2", "vec2"}), "vec4");
  EXPECT_EQ(result("textureGrad", {"samplerCube", "vec3", "vec3", "vec3"}), "vec4");
  EXPECT_EQ(result("textureGradOffset", {"sampler2D", "vec2", "vec2", "vec2", "ivec2"}), "vec4");
  EXPECT_EQ(result("textureLodOffset", {"sampler3D", "vec3", "float", "ivec3"}), "vec4");
  EXPECT_EQ(result("textureGather", {"sampler2D", "vec2"}), "vec4");
  EXPECT_EQ(result("textureGather", {"samplerCube", "vec3", "int"}), "vec4");
  EXPECT_EQ(result("textureGather", {"sampler2DArray", "vec3", "int"}), "vec4");
  EXPECT_EQ(result("textureGatherOffset", {"sampler2D", "vec2", "ivec2", "int"}), "vec4");
  EXPECT_EQ(result("textureGatherOffset", {"sampler2DArray", "vec3", "ivec2"}), "vec4");
}

TEST_F(BuiltinTableTest, TextureFormsTheSpecLeavesOut) {
  // Cube maps take no offsets and cannot be fetched by texel; 3D textures
  // cannot be gathered; only 2D and 3D samplers have projective lookups.
  EXPECT_EQ(result("textureOffset", {"samplerCube", "vec3", "ivec3"}), "<none>");
  EXPECT_EQ(result("textureOffset", {"samplerCube", "vec3", "ivec2"}), "<none>");
  EXPECT_EQ(result("texelFetch", {"samplerCube", "ivec3", "int"}), "<none>");
  EXPECT_EQ(result("textureGather", {"sampler3D", "vec3"}), "<none>");
  EXPECT_EQ(result("textureProj", {"samplerCube", "vec4"}), "<none>");
  EXPECT_EQ(result("textureProj", {"sampler2DArray", "vec4"}), "<none>");
  EXPECT_EQ(result("textureGatherOffset", {"samplerCube", "vec3", "ivec2"}), "<none>");
}

TEST_F(BuiltinTableTest, TextureQueries) {
  EXPECT_EQ(result("textureSize", {"sampler2D", "int"}), "ivec2");
  EXPECT_EQ(result("textureSize", {"sampler3D", "int"}), "ivec3");
  EXPECT_EQ(result("textureSize", {"samplerCube", "int"}), "ivec2");
  EXPECT_EQ(result("textureSize", {"sampler2DArray", "int"}), "ivec3");
  EXPECT_EQ(result("textureQueryLod", {"sampler2D", "vec2"}), "vec2");
  EXPECT_EQ(result("textureQueryLod", {"samplerCube", "vec3"}), "vec2");
  // Arrays query the LOD with the coordinate without the layer.
  EXPECT_EQ(result("textureQueryLod", {"sampler2DArray", "vec2"}), "vec2");
  EXPECT_EQ(result("textureQueryLevels", {"sampler3D"}), "int");
}

TEST_F(BuiltinTableTest, CommonFunctions) {
  EXPECT_EQ(result("mix", {"vec3", "vec3", "float"}), "vec3");
  EXPECT_EQ(result("mix", {"vec4", "vec4", "vec4"}), "vec4");
  EXPECT_EQ(result("mix", {"vec2", "vec2", "bvec2"}), "vec2");
  EXPECT_EQ(result("mix", {"float", "float", "float"}), "float");
  EXPECT_EQ(result("mix", {"vec3", "vec3", "vec2"}), "<none>");
  EXPECT_EQ(result("clamp", {"vec3", "float", "float"}), "vec3");
  EXPECT_EQ(result("clamp", {"ivec2", "int", "int"}), "ivec2");
  EXPECT_EQ(result("clamp", {"uint", "uint", "uint"}), "uint");
  EXPECT_EQ(result("min", {"vec4", "float"}), "vec4");
  EXPECT_EQ(result("max", {"uvec3", "uvec3"}), "uvec3");
  EXPECT_EQ(result("abs", {"ivec4"}), "ivec4");
  EXPECT_EQ(result("sign", {"int"}), "int");
  EXPECT_EQ(result("mod", {"vec3", "float"}), "vec3");
  EXPECT_EQ(result("mod", {"vec3", "vec3"}), "vec3");
  EXPECT_EQ(result("step", {"float", "vec3"}), "vec3");
  EXPECT_EQ(result("smoothstep", {"float", "float", "vec2"}), "vec2");
  EXPECT_EQ(result("isnan", {"vec3"}), "bvec3");
  EXPECT_EQ(result("floatBitsToUint", {"vec2"}), "uvec2");
  EXPECT_EQ(result("intBitsToFloat", {"ivec4"}), "vec4");
  EXPECT_EQ(result("ldexp", {"vec3", "ivec3"}), "vec3");
  EXPECT_EQ(result("fma", {"float", "float", "float"}), "float");
  EXPECT_EQ(result("atan", {"float", "float"}), "float");
  EXPECT_EQ(result("atan", {"vec2"}), "vec2");
  EXPECT_EQ(result("inversesqrt", {"vec4"}), "vec4");
  EXPECT_EQ(result("pow", {"vec3", "vec3"}), "vec3");
}

TEST_F(BuiltinTableTest, OutParameters) {
  const BuiltinOverload* modf = find("modf", {"vec3", "vec3"});
  ASSERT_NE(modf, nullptr);
  EXPECT_EQ(modf->result, T("vec3"));
  EXPECT_EQ(modf->params[0].direction, ParamDirection::In);
  EXPECT_EQ(modf->params[1].direction, ParamDirection::Out);

  const BuiltinOverload* frexp = find("frexp", {"vec2", "ivec2"});
  ASSERT_NE(frexp, nullptr);
  EXPECT_EQ(frexp->result, T("vec2"));
  EXPECT_EQ(frexp->params[1].direction, ParamDirection::Out);

  const BuiltinOverload* carry = find("uaddCarry", {"uvec2", "uvec2", "uvec2"});
  ASSERT_NE(carry, nullptr);
  EXPECT_EQ(carry->params[0].direction, ParamDirection::In);
  EXPECT_EQ(carry->params[2].direction, ParamDirection::Out);

  const BuiltinOverload* mul = find("imulExtended", {"int", "int", "int", "int"});
  ASSERT_NE(mul, nullptr);
  EXPECT_TRUE(mul->result->isVoid());
  EXPECT_EQ(mul->params[2].direction, ParamDirection::Out);
  EXPECT_EQ(mul->params[3].direction, ParamDirection::Out);

  // Ordinary functions take only `in` parameters.
  for (const BuiltinOverload& o : *table.lookup("mix")) {
    for (const BuiltinParam& p : o.params) EXPECT_EQ(p.direction, ParamDirection::In);
  }
}

TEST_F(BuiltinTableTest, GeometricAndMatrix) {
  EXPECT_EQ(result("dot", {"vec3", "vec3"}), "float");
  EXPECT_EQ(result("length", {"vec2"}), "float");
  EXPECT_EQ(result("distance", {"vec4", "vec4"}), "float");
  EXPECT_EQ(result("cross", {"vec3", "vec3"}), "vec3");
  EXPECT_EQ(result("cross", {"vec4", "vec4"}), "<none>");
  EXPECT_EQ(result("normalize", {"vec3"}), "vec3");
  EXPECT_EQ(result("reflect", {"vec3", "vec3"}), "vec3");
  EXPECT_EQ(result("refract", {"vec3", "vec3", "float"}), "vec3");
  EXPECT_EQ(result("faceforward", {"vec3", "vec3", "vec3"}), "vec3");

  // outerProduct(c, r): rows from c, columns from r.
  EXPECT_EQ(result("outerProduct", {"vec3", "vec2"}), "mat2x3");
  EXPECT_EQ(result("outerProduct", {"vec2", "vec4"}), "mat4x2");
  EXPECT_EQ(result("outerProduct", {"vec4", "vec4"}), "mat4");
  EXPECT_EQ(result("transpose", {"mat2x3"}), "mat3x2");
  EXPECT_EQ(result("transpose", {"mat4"}), "mat4");
  EXPECT_EQ(result("matrixCompMult", {"mat3x4", "mat3x4"}), "mat3x4");
  EXPECT_EQ(result("determinant", {"mat3"}), "float");
  EXPECT_EQ(result("determinant", {"mat2x3"}), "<none>");
  EXPECT_EQ(result("inverse", {"mat4"}), "mat4");
  EXPECT_EQ(result("inverse", {"mat4x3"}), "<none>");
}

TEST_F(BuiltinTableTest, VectorRelational) {
  EXPECT_EQ(result("lessThan", {"ivec3", "ivec3"}), "bvec3");
  EXPECT_EQ(result("lessThan", {"vec2", "vec2"}), "bvec2");
  EXPECT_EQ(result("greaterThanEqual", {"uvec4", "uvec4"}), "bvec4");
  EXPECT_EQ(result("equal", {"bvec2", "bvec2"}), "bvec2");
  EXPECT_EQ(result("notEqual", {"vec3", "vec3"}), "bvec3");
  EXPECT_EQ(result("lessThan", {"bvec2", "bvec2"}), "<none>");
  // Scalars compare with operators, not these functions.
  EXPECT_EQ(result("lessThan", {"float", "float"}), "<none>");
  EXPECT_EQ(result("any", {"bvec3"}), "bool");
  EXPECT_EQ(result("all", {"bvec4"}), "bool");
  EXPECT_EQ(result("not", {"bvec2"}), "bvec2");
}

TEST_F(BuiltinTableTest, IntegerAndPacking) {
  EXPECT_EQ(result("bitfieldExtract", {"uvec2", "int", "int"}), "uvec2");
  EXPECT_EQ(result("bitfieldInsert", {"int", "int", "int", "int"}), "int");
  EXPECT_EQ(result("bitfieldReverse", {"uint"}), "uint");
  EXPECT_EQ(result("bitCount", {"uvec3"}), "ivec3");
  EXPECT_EQ(result("findMSB", {"uint"}), "int");
  EXPECT_EQ(result("findLSB", {"ivec4"}), "ivec4");
  EXPECT_EQ(result("packUnorm4x8", {"vec4"}), "uint");
  EXPECT_EQ(result("unpackSnorm2x16", {"uint"}), "vec2");
  EXPECT_EQ(result("packHalf2x16", {"vec2"}), "uint");
  EXPECT_EQ(result("unpackHalf2x16", {"uint"}), "vec2");
}

TEST_F(BuiltinTableTest, Derivatives) {
  for (std::string_view name :
       {"dFdx", "dFdy", "dFdxFine", "dFdyFine", "dFdxCoarse", "dFdyCoarse", "fwidth", "fwidthFine", "fwidthCoarse"}) {
    EXPECT_EQ(result(name, {"vec3"}), "vec3") << name;
    EXPECT_EQ(result(name, {"float"}), "float") << name;
  }
}

TEST_F(BuiltinTableTest, UnknownNamesGiveNull) {
  EXPECT_EQ(table.lookup("textur"), nullptr);
  EXPECT_EQ(table.lookup(""), nullptr);
  EXPECT_EQ(table.lookup("vec3"), nullptr);  // constructors are not built-in functions
  EXPECT_EQ(table.lookup("Texture"), nullptr);
  EXPECT_EQ(table.lookup("imageLoad"), nullptr);  // no images
  EXPECT_EQ(table.lookup("atomicAdd"), nullptr);  // no atomics
}

TEST_F(BuiltinTableTest, NamesAreSortedUniqueAndMatchTheTable) {
  const std::vector<std::string_view>& names = table.names();
  EXPECT_TRUE(std::is_sorted(names.begin(), names.end()));
  EXPECT_EQ(std::adjacent_find(names.begin(), names.end()), names.end());
  EXPECT_GE(names.size(), 100u);
  for (std::string_view name : names) {
    const std::vector<BuiltinOverload>* set = table.lookup(name);
    ASSERT_NE(set, nullptr) << name;
    EXPECT_FALSE(set->empty()) << name;
  }
}

TEST_F(BuiltinTableTest, NoDuplicateOverloads) {
  for (std::string_view name : table.names()) {
    std::set<std::vector<const Type*>> seen;
    for (const BuiltinOverload& o : *table.lookup(name)) {
      std::vector<const Type*> params;
      for (const BuiltinParam& p : o.params) params.push_back(p.type);
      EXPECT_TRUE(seen.insert(params).second) << "duplicate overload of " << name;
    }
  }
}

TEST_F(BuiltinTableTest, EveryOverloadIsWellFormed) {
  for (std::string_view name : table.names()) {
    for (const BuiltinOverload& o : *table.lookup(name)) {
      ASSERT_NE(o.result, nullptr) << name;
      EXPECT_FALSE(o.result->isError()) << name;
      EXPECT_FALSE(o.params.empty()) << name;
      for (const BuiltinParam& p : o.params) {
        ASSERT_NE(p.type, nullptr) << name;
        EXPECT_FALSE(p.type->isError()) << name;
        EXPECT_FALSE(p.type->isVoid()) << name;
      }
    }
  }
}

TEST_F(BuiltinTableTest, GenericFormsAreExpandedOverEverySize) {
  // Each genType function has exactly one overload per float size.
  for (std::string_view name : {"sin", "exp", "floor", "normalize", "dFdx"}) {
    const std::vector<BuiltinOverload>* set = table.lookup(name);
    ASSERT_NE(set, nullptr) << name;
    EXPECT_EQ(set->size(), 4u) << name;
  }
  // mod(float, float) comes from both mod forms but appears once.
  EXPECT_EQ(table.lookup("mod")->size(), 7u);
  // Two independent tables over separate type tables agree in shape.
  TypeTable otherTypes;
  BuiltinTable other(otherTypes);
  EXPECT_EQ(other.names(), table.names());
}

}  // namespace
}  // namespace spire::sem
