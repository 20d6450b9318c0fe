// The attributes the compiler and the engine interpret, in one table, and
// the check every attribute goes through when a source or a decision file is
// read: a known attribute in the wrong place, or with a value it cannot
// take, is an error there, not a surprise at bake time. An unknown attribute
// is an engine's own hint and passes through to reflection unchecked, unless
// its name is a near miss of a known one (`[Fromat]`), which is a warning.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "support/diagnostic.h"
#include "syntax/ast.h"

namespace spire::sem {

enum class AttributeSite : uint8_t { World, Import, Component, Decision, Statement };

struct AttributeSpec {
  std::string_view name;
  std::vector<AttributeSite> sites;
  std::string_view meaning;
  // Allowed values; empty with `minimum`/`maximum` set: an integer range;
  // empty without them: any non-empty name, which its consumer checks.
  std::vector<std::string_view> values;
  std::optional<long> minimum;
  std::optional<long> maximum;
  std::string_view example;  // a valid value, for messages
  bool flag = false;         // written without a value (`[Immutable]`)
};

std::span<const AttributeSpec> attributeCatalog();
const AttributeSpec* findAttribute(std::string_view name);

struct AttributeProblem {
  bool isError = true;
  bool atValue = false;  // the value is wrong, rather than the name or its place
  std::string message;
};

// What is wrong with `[name]` or `[name: "value"]` at `site`, if anything.
std::optional<AttributeProblem> checkAttribute(AttributeSite site, std::string_view name,
                                               const std::optional<std::string>& value);

// Checks every attribute of a declaration at `site`: errors are E4021,
// near misses W4022. False when any attribute is in error.
bool checkAttributes(const std::vector<ast::Attribute>& attributes, AttributeSite site, DiagnosticList& diags);

// The bake formats [Format] names, as an engine maps them to texture formats.
std::span<const std::string_view> textureFormatNames();

}  // namespace spire::sem
