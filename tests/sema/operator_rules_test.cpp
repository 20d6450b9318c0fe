#include "sema/operator_rules.h"

#include <gtest/gtest.h>

namespace spire::sem {
namespace {

using ast::BinaryOp;

class OperatorRules : public testing::Test {
 protected:
  TypeTable t;
  const Type* f = t.floatType();
  const Type* i = t.intType();
  const Type* u = t.uintType();
  const Type* b = t.boolType();
  const Type* v2 = t.vector(ScalarKind::Float, 2);
  const Type* v3 = t.vector(ScalarKind::Float, 3);
  const Type* v4 = t.vector(ScalarKind::Float, 4);
  const Type* iv3 = t.vector(ScalarKind::Int, 3);
  const Type* m4 = t.matrix(4, 4);
  const Type* m2x3 = t.matrix(2, 3);
  const Type* m3x2 = t.matrix(3, 2);
};

TEST_F(OperatorRules, ArithmeticWithImplicitConversions) {
  EXPECT_EQ(binaryResultType(t, BinaryOp::Add, i, f), f);
  EXPECT_EQ(binaryResultType(t, BinaryOp::Mul, v3, i), v3);
  EXPECT_EQ(binaryResultType(t, BinaryOp::Add, iv3, v3), v3);
  EXPECT_EQ(binaryResultType(t, BinaryOp::Add, i, u), u);
  EXPECT_EQ(binaryResultType(t, BinaryOp::Add, v3, v4), nullptr);
  EXPECT_EQ(binaryResultType(t, BinaryOp::Add, b, i), nullptr);
  EXPECT_EQ(binaryResultType(t, BinaryOp::Mod, f, f), nullptr);
  EXPECT_EQ(binaryResultType(t, BinaryOp::Mod, iv3, i), iv3);
}

TEST_F(OperatorRules, MatrixProducts) {
  EXPECT_EQ(binaryResultType(t, BinaryOp::Mul, m4, v4), v4);
  EXPECT_EQ(binaryResultType(t, BinaryOp::Mul, m4, v3), nullptr);
  EXPECT_EQ(binaryResultType(t, BinaryOp::Mul, m2x3, v2), v3);
  EXPECT_EQ(binaryResultType(t, BinaryOp::Mul, v3, m2x3), v2);
  EXPECT_EQ(binaryResultType(t, BinaryOp::Mul, m2x3, m3x2), t.matrix(3, 3));
  EXPECT_EQ(binaryResultType(t, BinaryOp::Mul, m3x2, m2x3), t.matrix(2, 2));
  EXPECT_EQ(binaryResultType(t, BinaryOp::Add, m4, m4), m4);
  EXPECT_EQ(binaryResultType(t, BinaryOp::Add, m4, v4), nullptr);
  EXPECT_EQ(binaryResultType(t, BinaryOp::Mul, m4, i), m4);
}

TEST_F(OperatorRules, ComparisonsAndLogic) {
  EXPECT_EQ(binaryResultType(t, BinaryOp::Less, i, f), b);
  EXPECT_EQ(binaryResultType(t, BinaryOp::Less, v3, v3), nullptr);
  EXPECT_EQ(binaryResultType(t, BinaryOp::Equal, v3, iv3), b);
  EXPECT_EQ(binaryResultType(t, BinaryOp::Equal, t.sampler(SamplerKind::Sampler2D), t.sampler(SamplerKind::Sampler2D)),
            nullptr);
  EXPECT_EQ(binaryResultType(t, BinaryOp::LogicalXor, b, b), b);
  EXPECT_EQ(binaryResultType(t, BinaryOp::LogicalAnd, b, i), nullptr);
  EXPECT_EQ(binaryResultType(t, BinaryOp::Shl, iv3, u), iv3);
  EXPECT_EQ(binaryResultType(t, BinaryOp::Shl, i, iv3), nullptr);
  EXPECT_EQ(binaryResultType(t, BinaryOp::BitOr, u, i), u);
}

TEST_F(OperatorRules, Unary) {
  EXPECT_EQ(unaryResultType(ast::UnaryOp::Negate, v3), v3);
  EXPECT_EQ(unaryResultType(ast::UnaryOp::Negate, b), nullptr);
  EXPECT_EQ(unaryResultType(ast::UnaryOp::LogicalNot, b), b);
  EXPECT_EQ(unaryResultType(ast::UnaryOp::LogicalNot, t.vector(ScalarKind::Bool, 2)), nullptr);
  EXPECT_EQ(unaryResultType(ast::UnaryOp::BitNot, iv3), iv3);
  EXPECT_EQ(unaryResultType(ast::UnaryOp::BitNot, f), nullptr);
}

TEST_F(OperatorRules, Constructors) {
  EXPECT_TRUE(checkConstructor(v4, {v3, f}));
  EXPECT_TRUE(checkConstructor(v4, {f}));
  EXPECT_TRUE(checkConstructor(v3, {v4}));  // truncation is allowed
  EXPECT_FALSE(checkConstructor(v4, {v3}));
  EXPECT_FALSE(checkConstructor(v2, {v2, f}));
  EXPECT_TRUE(checkConstructor(m4, {f}));
  EXPECT_TRUE(checkConstructor(t.matrix(3, 3), {m4}));
  EXPECT_TRUE(checkConstructor(m2x3, {v3, v3}));
  EXPECT_FALSE(checkConstructor(m2x3, {v3, v2}));
  EXPECT_FALSE(checkConstructor(m4, {m4, f}));
  EXPECT_TRUE(checkConstructor(i, {v3}));
  EXPECT_FALSE(checkConstructor(i, {f, f}));
  EXPECT_FALSE(checkConstructor(t.sampler(SamplerKind::Sampler2D), {i}));
}

TEST_F(OperatorRules, TypeNames) {
  EXPECT_EQ(m2x3->name(), "mat2x3");
  EXPECT_EQ(m4->name(), "mat4");
  EXPECT_EQ(iv3->name(), "ivec3");
  EXPECT_EQ(t.array(t.array(f, 2), 3)->name(), "float[3][2]");
  EXPECT_EQ(t.lookupBuiltin("mat4x4"), m4);
}

}  // namespace
}  // namespace spire::sem
