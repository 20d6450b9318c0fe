// GLSL spellings of Spire names. Spire accepts any identifier that is not a
// Spire keyword, so a component may be called `output`, `input`, `filter` or
// `texture`; generated code renames such names consistently, and reflection
// keeps the source name.
#pragma once

#include <set>
#include <string>
#include <string_view>

namespace spire::codegen {

// True for GLSL 4.50 keywords, reserved words, built-in type and function
// names, and names GLSL reserves by prefix (`gl_`) or by a double underscore.
bool isReservedInGlsl(std::string_view name);

// The identifiers of one kernel. Every global name (component, function,
// struct, interface variable) goes through it, so renamed and generated names
// never collide: a reserved name gains a trailing `_` (`output` -> `output_`),
// a taken one a number, and generated names start with `spire_`.
class NameTable {
 public:
  // A unique GLSL name for a user-visible entity called `source`.
  std::string claim(std::string_view source);
  // A unique generated name, `spire_<hint>`.
  std::string generate(std::string_view hint);
  // A name for a local or parameter: the source name unless it is reserved
  // or equals a renamed or generated global (hiding a global the user named
  // the same way is fine: Spire scoping already resolved to the local).
  std::string local(std::string_view source) const;
  // Whether a global (claimed or generated) already has `name`.
  bool isTaken(std::string_view name) const { return taken_.count(name) != 0; }

 private:
  std::string unique(const std::string& base, std::string_view source);
  std::set<std::string, std::less<>> taken_;
  // Names that differ from what the user wrote (renamed or generated): a
  // local with such a name would hide the entity it stands for.
  std::set<std::string, std::less<>> introduced_;
};

}  // namespace spire::codegen
