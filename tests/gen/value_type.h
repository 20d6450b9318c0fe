// The value types the generator uses, and how one converts into another in
// generated expressions (so that any operand can feed any use).
#pragma once

#include <string>

namespace spire::testgen {

enum class ValueType { Float, Vec2, Vec3, Vec4, Int, Mat3, Mat4, Sampler };

const char* typeName(ValueType type);
// `value` (of type `from`) as an expression of type `to`.
std::string convert(const std::string& value, ValueType from, ValueType to);
// A literal of a numeric type.
std::string literal(ValueType type, int salt);

}  // namespace spire::testgen
