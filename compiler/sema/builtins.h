// The table of GLSL 4.50 built-in functions that Spire code may call, with
// every overload spelled out over concrete types.
#pragma once

#include <string_view>
#include <unordered_map>
#include <vector>

#include "sema/type.h"
#include "syntax/ast.h"

namespace spire::sem {

struct BuiltinParam {
  const Type* type;
  ast::ParamDirection direction = ast::ParamDirection::In;
};

struct BuiltinOverload {
  const Type* result;
  std::vector<BuiltinParam> params;
};

class BuiltinTable {
 public:
  explicit BuiltinTable(TypeTable& types);

  // All overloads of `name`, or null when `name` is not a built-in function.
  const std::vector<BuiltinOverload>* lookup(std::string_view name) const;
  // Every built-in function name, sorted, for "did you mean" suggestions.
  const std::vector<std::string_view>& names() const { return names_; }

 private:
  std::unordered_map<std::string_view, std::vector<BuiltinOverload>> overloads_;
  std::vector<std::string_view> names_;
};

}  // namespace spire::sem
