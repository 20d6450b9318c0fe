#include "gen/expression_generator.h"

#include <fmt/format.h>

namespace spire::testgen {
namespace {

bool isFloating(ValueType t) {
  return t == ValueType::Float || t == ValueType::Vec2 || t == ValueType::Vec3 || t == ValueType::Vec4;
}

}  // namespace

const Operand* ExpressionGenerator::operand(const std::vector<Operand>& operands, size_t limit, uint32_t need,
                                            bool allowSampler) {
  std::vector<const Operand*> fit;
  for (size_t i = 0; i < limit && i < operands.size(); ++i) {
    const Operand& o = operands[i];
    if ((o.readableIn & need) == need && (allowSampler || o.type != ValueType::Sampler)) fit.push_back(&o);
  }
  if (fit.empty()) return nullptr;
  // Prefer recent components, so that dependency chains get long.
  const int n = static_cast<int>(fit.size());
  const int lo = rng_.chance(60) ? std::max(0, n - 6) : 0;
  return fit[static_cast<size_t>(rng_.pick(lo, n - 1))];
}

std::string ExpressionGenerator::leaf(ValueType type, const std::vector<Operand>& operands, size_t limit, uint32_t need,
                                      uint32_t& where) {
  const Operand* o = rng_.chance(88) ? operand(operands, limit, need, true) : nullptr;
  if (!o) return literal(type, rng_.pick(0, 999));
  where &= o->readableIn;
  if (o->type != ValueType::Sampler) return convert(o->name, o->type, type);
  // A sampler is only ever read through texture(), at a coordinate made of
  // operands readable in the same worlds.
  const Operand* uv = operand(operands, limit, need, false);
  std::string coord = uv ? convert(uv->name, uv->type, ValueType::Vec2) : literal(ValueType::Vec2, 7);
  if (uv) where &= uv->readableIn;
  return convert(fmt::format("texture({}, {})", o->name, coord), ValueType::Vec4, type);
}

std::string ExpressionGenerator::arithmetic(ValueType type, const std::vector<Operand>& operands, size_t limit,
                                            uint32_t need, uint32_t& where, int depth) {
  // Every random draw is its own statement: argument evaluation order is
  // unspecified and the output must not depend on it.
  auto sub = [&](ValueType t) { return expr(t, operands, limit, need, where, depth + 1); };
  const std::string a = sub(type);
  switch (rng_.pick(0, 7)) {
    case 0: {
      const std::string b = sub(type);
      return fmt::format("({} + {})", a, b);
    }
    case 1: {
      const std::string b = sub(ValueType::Float);
      return fmt::format("({} * {})", a, b);
    }
    case 2: return fmt::format("sin({})", a);
    case 3: return fmt::format("clamp({}, 0.0, 1.0)", a);
    case 4: {
      const std::string b = sub(type);
      return fmt::format("mix({}, {}, 0.25)", a, b);
    }
    case 5: {
      const std::string b = sub(type);
      return fmt::format("max({}, {} - 0.5)", a, b);
    }
    case 6:
      if (!functions_.empty()) {
        const GenFunction& f = rng_.element(functions_);
        const std::string x = sub(ValueType::Float), v = sub(ValueType::Vec3);
        const std::string call =
            f.vectorFirst ? fmt::format("{}({}, {})", f.name, v, x) : fmt::format("{}({}, {})", f.name, x, v);
        return convert(call, f.result, type);
      }
      return fmt::format("abs({})", a);
    default:
      if (type == ValueType::Float) {
        const std::string v = sub(ValueType::Vec3);
        return fmt::format("({} + dot({}, {}))", a, v, v);
      }
      return fmt::format("normalize({} + {})", a, literal(type, rng_.pick(1, 99)));
  }
}

std::string ExpressionGenerator::expr(ValueType type, const std::vector<Operand>& operands, size_t limit, uint32_t need,
                                      uint32_t& where, int depth) {
  if (type == ValueType::Mat3 && rng_.chance(70)) {
    const std::string a = expr(ValueType::Vec3, operands, limit, need, where, depth + 1);
    const std::string b = expr(ValueType::Vec3, operands, limit, need, where, depth + 1);
    return fmt::format("mat3({}, {}, vec3(0.0, 0.0, 1.0))", a, b);
  }
  if (type == ValueType::Int)
    return fmt::format("int({} * 4.0)", expr(ValueType::Float, operands, limit, need, where, depth + 1));
  if (!isFloating(type) || depth >= 2 || rng_.chance(35)) return leaf(type, operands, limit, need, where);
  return arithmetic(type, operands, limit, need, where, depth);
}

namespace {

std::string functionBody(RandomSource& rng, ValueType result, const std::vector<GenFunction>& earlier) {
  const char* t = typeName(result);
  std::string b;
  b += result == ValueType::Float
           ? fmt::format("    float acc = x * {} + v.y;\n", literal(ValueType::Float, rng.pick(1, 99)))
           : fmt::format("    vec3 acc = v * x + vec3({});\n", literal(ValueType::Float, rng.pick(1, 99)));
  if (rng.chance(70)) {
    b += fmt::format("    if (x > {}) {{\n        acc = acc * 2.0;\n    }} else {{\n        acc = sin(acc);\n    }}\n",
                     literal(ValueType::Float, rng.pick(1, 99)));
  }
  if (rng.chance(60)) {
    b += fmt::format("    for (int i = 0; i < {}; i++) {{\n        acc += {}(dot(v, v) * 0.1);\n    }}\n",
                     rng.pick(2, 4), t);
  }
  if (!earlier.empty() && rng.chance(50)) {
    const GenFunction& f = rng.element(earlier);
    const std::string call = f.vectorFirst ? fmt::format("{}(v, x)", f.name) : fmt::format("{}(x, v)", f.name);
    b += fmt::format("    acc += {};\n", convert(call, f.result, result));
  }
  return b + "    return acc;\n";
}

}  // namespace

std::string generateFunctions(RandomSource& rng, int count, std::vector<GenFunction>& functions) {
  std::string out;
  for (int i = 0; i < count; ++i) {
    GenFunction f{fmt::format("fn{}", i), rng.chance(50) ? ValueType::Float : ValueType::Vec3, rng.chance(50)};
    const char* params = f.vectorFirst ? "vec3 v, float x" : "float x, vec3 v";
    out += fmt::format("{} {}({}) {{\n{}}}\n\n", typeName(f.result), f.name, params,
                       functionBody(rng, f.result, functions));
    functions.push_back(f);
  }
  return out;
}

}  // namespace spire::testgen
