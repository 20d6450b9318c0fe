#include "sema/attribute_catalog.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>

#include "support/spelling.h"

namespace spire::sem {
namespace {

constexpr std::string_view kFormats[] = {"R8",    "RG8",     "RGBA8", "RGB10_A2", "R16F",
                                         "RG16F", "RGBA16F", "R32F",  "RGBA32F"};

std::string_view siteName(AttributeSite site) {
  switch (site) {
    case AttributeSite::World: return "a world declaration";
    case AttributeSite::Import: return "an import";
    case AttributeSite::Component: return "a component declaration";
    case AttributeSite::Decision: return "a decision";
    case AttributeSite::Statement: return "a statement";
  }
  return "?";
}

const std::vector<AttributeSpec>& catalog() {
  static const std::vector<AttributeSpec> specs = {
      {"Stage",
       {AttributeSite::World},
       "the pipeline stage of the world's kernel",
       {"vertex", "fragment", "compute"},
       {},
       {},
       "vertex"},
      {"Role",
       {AttributeSite::World},
       "what the engine runs the world as (its engine role); the engine checks the name",
       {},
       {},
       {},
       "fragment"},
      {"Priority", {AttributeSite::Import}, "breaks ties between equally faithful routes", {}, -1000, 1000, "1"},
      {"Format",
       {AttributeSite::Component, AttributeSite::Decision},
       "the texture format a bake stores the value in",
       std::vector<std::string_view>(std::begin(kFormats), std::end(kFormats)),
       {},
       {},
       "RGBA8"},
      {"TextureSize",
       {AttributeSite::Component, AttributeSite::Decision},
       "the size in texels of a baked texture",
       {},
       1,
       8192,
       "512"},
      {"Encoding",
       {AttributeSite::Component, AttributeSite::Decision},
       "stores values in [-1, 1] remapped to [0, 1] for unsigned texture formats",
       {"signed"},
       {},
       {},
       "signed"},
      {"Immutable",
       {AttributeSite::Component, AttributeSite::Statement},
       "automatic simplification leaves the component or statement as written",
       {},
       {},
       {},
       "",
       true},
      {"Transition",
       {AttributeSite::Component},
       "a definition of a level-of-detail transition (spire-simplify --search writes them); spire-tune leaves it "
       "out of the space it explores",
       {},
       {},
       {},
       "",
       true},
  };
  return specs;
}

std::string allowedValues(const AttributeSpec& spec) {
  if (spec.values.empty() && !spec.minimum) return "a name";
  if (spec.values.empty()) return fmt::format("an integer from {} to {} as a string", *spec.minimum, *spec.maximum);
  std::string text;
  for (std::string_view v : spec.values) text += fmt::format("{}\"{}\"", text.empty() ? "" : ", ", v);
  return spec.values.size() == 1 ? text : "one of " + text;
}

bool valueAllowed(const AttributeSpec& spec, std::string_view value) {
  if (spec.values.empty() && !spec.minimum) return !value.empty();
  if (!spec.values.empty()) return std::find(spec.values.begin(), spec.values.end(), value) != spec.values.end();
  long number = 0;
  const auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), number);
  return ec == std::errc{} && end == value.data() + value.size() && number >= *spec.minimum && number <= *spec.maximum;
}

std::optional<AttributeProblem> unknownName(std::string_view name) {
  std::vector<std::string_view> names;
  for (const AttributeSpec& spec : catalog()) names.push_back(spec.name);
  const auto suggestion = closestSpelling(name, names);
  if (!suggestion) return std::nullopt;
  return AttributeProblem{false, false,
                          fmt::format("unknown attribute [{}]; did you mean [{}]? An unknown attribute is passed to "
                                      "the engine as a hint",
                                      name, *suggestion)};
}

// No engine reads a statement's attributes, so an unknown one there is a
// mistake rather than a hint.
AttributeProblem unknownOnStatement(std::string_view name) {
  std::vector<std::string_view> names;
  for (const AttributeSpec& spec : catalog()) {
    if (std::find(spec.sites.begin(), spec.sites.end(), AttributeSite::Statement) != spec.sites.end()) {
      names.push_back(spec.name);
    }
  }
  std::string message = fmt::format("unknown attribute [{}] on a statement; a statement takes ", name);
  for (size_t i = 0; i < names.size(); ++i) message += fmt::format("{}[{}]", i == 0 ? "" : " or ", names[i]);
  return AttributeProblem{true, false, std::move(message)};
}

}  // namespace

std::span<const AttributeSpec> attributeCatalog() { return catalog(); }

const AttributeSpec* findAttribute(std::string_view name) {
  const auto& specs = catalog();
  const auto it = std::find_if(specs.begin(), specs.end(), [&](const AttributeSpec& s) { return s.name == name; });
  return it == specs.end() ? nullptr : &*it;
}

std::optional<AttributeProblem> checkAttribute(AttributeSite site, std::string_view name,
                                               const std::optional<std::string>& value) {
  const AttributeSpec* spec = findAttribute(name);
  if (!spec) return site == AttributeSite::Statement ? unknownOnStatement(name) : unknownName(name);
  if (std::find(spec->sites.begin(), spec->sites.end(), site) == spec->sites.end()) {
    return AttributeProblem{true, false,
                            fmt::format("[{}] ({}) does not belong on {}; it goes on {}", name, spec->meaning,
                                        siteName(site), siteName(spec->sites.front()))};
  }
  if (spec->flag) {
    if (!value) return std::nullopt;
    return AttributeProblem{true, true, fmt::format("[{}] ({}) takes no value; write [{}]", name, spec->meaning, name)};
  }
  if (!value || !valueAllowed(*spec, *value)) {
    std::string message = fmt::format("[{}] takes {}, as in [{}: \"{}\"]; got {}", name, allowedValues(*spec), name,
                                      spec->example, value ? fmt::format("\"{}\"", *value) : std::string("no value"));
    if (value && !spec->values.empty()) {
      if (const auto suggestion = closestSpelling(*value, spec->values)) {
        message += fmt::format("; did you mean \"{}\"?", *suggestion);
      }
    }
    return AttributeProblem{true, value.has_value(), std::move(message)};
  }
  return std::nullopt;
}

bool checkAttributes(const std::vector<ast::Attribute>& attributes, AttributeSite site, DiagnosticList& diags) {
  bool ok = true;
  for (const ast::Attribute& a : attributes) {
    auto problem = checkAttribute(site, a.name, a.value);
    if (!problem) continue;
    diags.report(problem->isError ? DiagCode::E4021 : DiagCode::W4022, problem->atValue ? a.valueRange : a.range,
                 std::move(problem->message));
    ok = ok && !problem->isError;
  }
  return ok;
}

std::span<const std::string_view> textureFormatNames() { return kFormats; }

}  // namespace spire::sem
