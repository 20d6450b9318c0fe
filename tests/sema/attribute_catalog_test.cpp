// The attribute catalogue: what each known attribute accepts and where, and
// that decision files and in-memory decisions are checked against it when
// they are read, as sources are (the golden invalid_attributes covers
// sources).
#include "sema/attribute_catalog.h"

#include <gtest/gtest.h>

#include "driver/compiler.h"
#include "graph/decision_file.h"
#include "support/diagnostic_renderer.h"

namespace spire::sem {
namespace {

TEST(AttributeCatalog, KnownAttributesTakeTheirValuesInTheirPlaces) {
  EXPECT_FALSE(checkAttribute(AttributeSite::World, "Stage", "compute"));
  // [Role] takes any name; the engine, which knows its roles, checks it.
  EXPECT_FALSE(checkAttribute(AttributeSite::World, "Role", "someEnginesRole"));
  EXPECT_TRUE(checkAttribute(AttributeSite::World, "Role", std::nullopt));
  EXPECT_TRUE(checkAttribute(AttributeSite::World, "Role", ""));
  EXPECT_TRUE(checkAttribute(AttributeSite::Component, "Role", "fragment"));
  EXPECT_FALSE(checkAttribute(AttributeSite::Import, "Priority", "-1000"));
  EXPECT_FALSE(checkAttribute(AttributeSite::Decision, "TextureSize", "8192"));
  for (std::string_view format : textureFormatNames()) {
    EXPECT_FALSE(checkAttribute(AttributeSite::Component, "Format", std::string(format))) << format;
  }
  const auto badSize = checkAttribute(AttributeSite::Decision, "TextureSize", "8193");
  ASSERT_TRUE(badSize);
  EXPECT_TRUE(badSize->isError && badSize->atValue);
  EXPECT_EQ(badSize->message,
            "[TextureSize] takes an integer from 1 to 8192 as a string, as in [TextureSize: \"512\"]; got \"8193\"");
  const auto noValue = checkAttribute(AttributeSite::World, "Stage", std::nullopt);
  ASSERT_TRUE(noValue);
  EXPECT_FALSE(noValue->atValue);
  // [Immutable] is a flag: it takes no value, and only components and
  // statements have it.
  EXPECT_FALSE(checkAttribute(AttributeSite::Component, "Immutable", std::nullopt));
  const auto immutableValue = checkAttribute(AttributeSite::Component, "Immutable", "yes");
  ASSERT_TRUE(immutableValue);
  EXPECT_TRUE(immutableValue->isError && immutableValue->atValue);
  EXPECT_NE(immutableValue->message.find("takes no value; write [Immutable]"), std::string::npos);
  EXPECT_TRUE(checkAttribute(AttributeSite::Decision, "Immutable", std::nullopt));
  const auto misplaced = checkAttribute(AttributeSite::Decision, "Stage", "vertex");
  ASSERT_TRUE(misplaced);
  EXPECT_NE(misplaced->message.find("does not belong on a decision; it goes on a world declaration"),
            std::string::npos);
  const auto typo = checkAttribute(AttributeSite::Decision, "Format", "rgba8");
  ASSERT_TRUE(typo);
  EXPECT_NE(typo->message.find("did you mean \"RGBA8\"?"), std::string::npos) << typo->message;
}

// A statement takes [Immutable] only: nothing reads a statement's other
// attributes, so an unknown one there is an error, not a hint.
TEST(AttributeCatalog, StatementsTakeImmutableAndNothingElse) {
  EXPECT_FALSE(checkAttribute(AttributeSite::Statement, "Immutable", std::nullopt));
  const auto unknown = checkAttribute(AttributeSite::Statement, "Tonemap", std::nullopt);
  ASSERT_TRUE(unknown);
  EXPECT_TRUE(unknown->isError);
  EXPECT_EQ(unknown->message, "unknown attribute [Tonemap] on a statement; a statement takes [Immutable]");
  const auto misplaced = checkAttribute(AttributeSite::Statement, "Format", "RGBA8");
  ASSERT_TRUE(misplaced);
  EXPECT_NE(misplaced->message.find("does not belong on a statement"), std::string::npos) << misplaced->message;
}

TEST(AttributeCatalog, UnknownNamesAreHintsUnlessTheyLookLikeKnownOnes) {
  EXPECT_FALSE(checkAttribute(AttributeSite::Component, "Tonemap", "aces"));
  EXPECT_FALSE(checkAttribute(AttributeSite::Decision, "Interpolation", "smooth"));
  const auto nearMiss = checkAttribute(AttributeSite::Decision, "TextureSise", "512");
  ASSERT_TRUE(nearMiss);
  EXPECT_FALSE(nearMiss->isError);
  EXPECT_NE(nearMiss->message.find("did you mean [TextureSize]?"), std::string::npos);
}

TEST(AttributeCatalog, DecisionFilesAreCheckedWhenRead) {
  SourceManager sources;
  DiagnosticList diags;
  const FileId file = sources.addFile("d.decisions",
                                      "[Format: \"RGBA9\"] Terrain.albedo = PrebakeTex\n"
                                      "[TextureSise: \"512\"] Terrain.mixFactor = PrebakeTex\n");
  const graph::DecisionFile decisions = graph::parseDecisionFile(sources, file, diags);
  EXPECT_EQ(decisions.lines.size(), 2U);
  const std::string text = renderDiagnostics(sources, diags, DiagnosticFormat::Text);
  EXPECT_NE(text.find("d.decisions:1:10: error[E5010]: [Format] takes one of \"R8\""), std::string::npos) << text;
  EXPECT_NE(text.find("did you mean \"RGBA8\"?"), std::string::npos) << text;
  EXPECT_NE(text.find("d.decisions:2:2: warning[W5011]: unknown attribute [TextureSise]"), std::string::npos) << text;
}

TEST(AttributeCatalog, InMemoryDecisionsAreCheckedBeforeCompiling) {
  ShaderLibrary library;
  library.addFile(std::string(SPIRE_SOURCE_DIR) + "/examples/terrain.spire");
  ASSERT_TRUE(library.compile());
  Decisions decisions;
  decisions.placement = {{"albedo", "PrebakeTex"}};
  decisions.attributes["albedo"] = {{"Format", "BC7"}};
  const CompileResult compiled = compileVariant(library, "Terrain", decisions);
  ASSERT_FALSE(compiled);
  ASSERT_FALSE(compiled.error().diagnostics.empty());
  EXPECT_EQ(compiled.error().diagnostics[0].code, DiagCode::E5010);
  EXPECT_NE(compiled.error().diagnostics[0].message.find("'albedo': [Format] takes one of"), std::string::npos);
}

}  // namespace
}  // namespace spire::sem
