// Random, type-correct GLSL expressions over the components a shader can
// read in a given set of worlds. The caller names the worlds the expression
// must be computable in; the generator only reads components available in
// all of them and reports, as a world mask, where the result is computable.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "gen/random_source.h"
#include "gen/value_type.h"

namespace spire::testgen {

// A component an expression may read.
struct Operand {
  std::string name;
  ValueType type;
  uint32_t readableIn = 0;  // worlds where a definition can read it
};

// A user function `ret name(float x, vec3 v)` or `ret name(vec3 v, float x)`.
struct GenFunction {
  std::string name;
  ValueType result;
  bool vectorFirst = false;
};

class ExpressionGenerator {
 public:
  ExpressionGenerator(RandomSource& rng, const std::vector<GenFunction>& functions)
      : rng_(rng), functions_(functions) {}

  // An expression of `type` reading only operands[0, limit) that are
  // readable in every world of `need`; `where` is narrowed to the worlds
  // where all the operands it read are readable.
  std::string expr(ValueType type, const std::vector<Operand>& operands, size_t limit, uint32_t need, uint32_t& where,
                   int depth = 0);

 private:
  std::string leaf(ValueType type, const std::vector<Operand>& operands, size_t limit, uint32_t need, uint32_t& where);
  std::string arithmetic(ValueType type, const std::vector<Operand>& operands, size_t limit, uint32_t need,
                         uint32_t& where, int depth);
  const Operand* operand(const std::vector<Operand>& operands, size_t limit, uint32_t need, bool allowSampler);

  RandomSource& rng_;
  const std::vector<GenFunction>& functions_;
};

// `count` helper functions with loops, branches and locals (calls only to
// earlier ones, never recursive), as source text.
std::string generateFunctions(RandomSource& rng, int count, std::vector<GenFunction>& functions);

}  // namespace spire::testgen
