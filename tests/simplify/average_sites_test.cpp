// Pellacini's average rule on the typed tree (simplify/average_sites.h):
// which subtrees it may replace (float and float vectors that are not
// constants already, never what is assigned, nothing in loops, ifs or
// [Immutable] statements), what a probe of each computes (the statements
// before it, then the subtree), how sites rank, and the constants the
// measured averages become, and the shifted definitions of renormalization.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "simplify/average_sites.h"
#include "simplify/rewrite_target.h"
#include "simplify_fixture.h"

namespace spire::simplify {
namespace {

class AverageSitesTest : public SimplifyFixture {
 protected:
  std::vector<AverageSite> sitesOf(const std::string& component) {
    const sem::Shader* shader = library_->model().findShader("S");
    const sem::Component& c = shader->components[shader->componentByName.at(component)];
    return proposeAverageSites(library_->model(), library_->sources(), *c.definitions.front().decl);
  }
  static std::vector<std::string> befores(const std::vector<AverageSite>& sites) {
    std::vector<std::string> result;
    for (const AverageSite& s : sites) result.push_back(s.rewrite.before);
    return result;
  }
};

constexpr const char* kShader = R"(using "pipelines/engine.spire";
shader S using EnginePipeline {
    @FrameUniform mat4 mvp;
    @MaterialUniform sampler2D map;
    @MaterialUniform float gain;
    vec4 projPos = mvp * vec4(vert_pos, 1.0);
    vec3 shade = texture(map, vert_uv).rgb * gain + vec3(0.5);
    float blended {
        float s = gain * 2.0;
        s += vert_uv.x;
        for (int i = 0; i < 4; i++) { s += gain; }
        if (s > 1.0) { s = s * 0.5; }
        [Immutable] float kept = gain * 3.0;
        return s + kept;
    }
    vec4 output = vec4(shade, blended);
}
)";

TEST_F(AverageSitesTest, FloatSubtreesThatAreNotConstantsRankedByWhatTheySave) {
  load(kShader);
  const std::vector<AverageSite> shade = sitesOf("shade");
  // The texture fetch is the dearest part: sites holding it save the most;
  // then, saving alike, the longer source first.
  EXPECT_EQ(befores(shade), (std::vector<std::string>{"texture(map, vert_uv).rgb * gain + vec3(0.5)",
                                                      "texture(map, vert_uv).rgb * gain", "texture(map, vert_uv).rgb",
                                                      "texture(map, vert_uv)", "vert_uv", "gain"}));
  for (const AverageSite& s : shade) {
    EXPECT_EQ(s.rewrite.rule, kAverageRule);
    EXPECT_TRUE(s.rewrite.replacement.empty()) << "filled in once measured";
    EXPECT_EQ(s.probe, "= (" + s.rewrite.before + ");") << "a definition `T c = e;` is probed as itself";
  }
  EXPECT_EQ(shade[0].rewrite.type, "vec3");
  EXPECT_EQ(shade[0].scalars, 3U);
  EXPECT_EQ(shade[3].rewrite.type, "vec4");
  EXPECT_EQ(shade[3].scalars, 4U);
  EXPECT_GT(shade[0].rewrite.saving, 100) << "the fetch and the arithmetic";
  EXPECT_EQ(shade[5].rewrite.saving, 0) << "a name costs nothing";
}

TEST_F(AverageSitesTest, NeverWhatIsAssignedNorInsideLoopsIfsOrImmutableStatements) {
  load(kShader);
  const std::vector<AverageSite> blended = sitesOf("blended");
  std::vector<std::string> found = befores(blended);
  std::sort(found.begin(), found.end());
  // `s` of `s += ...` is assigned; the loop, the if and the [Immutable]
  // declaration are left out whole.
  EXPECT_EQ(found, (std::vector<std::string>{"gain", "gain * 2.0", "kept", "s", "s + kept", "vert_uv", "vert_uv.x"}));
  for (const AverageSite& s : blended) {
    if (s.rewrite.before != "s + kept") continue;
    // The probe runs every statement before the return, then returns the subtree.
    EXPECT_NE(s.probe.find("float s = gain * 2.0;"), std::string::npos) << s.probe;
    EXPECT_NE(s.probe.find("for (int i = 0; i < 4; i++) { s += gain; }"), std::string::npos) << s.probe;
    EXPECT_NE(s.probe.find("float kept = gain * 3.0;"), std::string::npos) << s.probe;
    EXPECT_NE(s.probe.find("return (s + kept);"), std::string::npos) << s.probe;
    EXPECT_EQ(s.probe.find("return s + kept;"), std::string::npos) << "the statement holding the site is not run";
  }
}

// Renormalization's text: every value the definition gives is shifted, its
// expression or each return however nested, and the name is the variation's;
// a return inside an [Immutable] statement cannot be, so nothing is.
TEST_F(AverageSitesTest, ShiftedDefinitionsAddTheShiftToEveryValueTheyGive) {
  load(R"(using "pipelines/engine.spire";
shader S using EnginePipeline {
    @FrameUniform mat4 mvp;
    @MaterialUniform float gain;
    vec4 projPos = mvp * vec4(vert_pos, 1.0);
    float plain = gain * 2.0;
    float branchy {
        if (gain > 0.5) { return gain; }
        return gain * 0.5;
    }
    float guarded {
        [Immutable] { if (gain > 0.5) { return gain; } }
        return 1.0;
    }
    vec4 output = vec4(plain, branchy, guarded, 1.0);
}
)");
  const sem::Shader* shader = library_->model().findShader("S");
  const auto decl = [&](const char* name) { return shader->findComponent(name)->definitions.front().decl; };
  EXPECT_EQ(shiftedText(library_->sources(), *decl("plain"), "float(0.25)", "level1"),
            "float plain:level1 = ((gain * 2.0) + float(0.25));");
  const std::optional<std::string> branchy =
      shiftedText(library_->sources(), *decl("branchy"), "float(-1)", "candidate2");
  ASSERT_TRUE(branchy);
  EXPECT_EQ(branchy->rfind("float branchy:candidate2 {", 0), 0U) << *branchy;
  EXPECT_NE(branchy->find("return ((gain) + float(-1));"), std::string::npos) << *branchy;
  EXPECT_NE(branchy->find("return ((gain * 0.5) + float(-1));"), std::string::npos) << *branchy;
  EXPECT_FALSE(shiftedText(library_->sources(), *decl("guarded"), "float(1)", "level1"));
}

TEST_F(AverageSitesTest, AveragesBecomeConstantsOfTheSitesType) {
  EXPECT_EQ(averageReplacement("float", {0.5}), "float(0.5)");
  EXPECT_EQ(averageReplacement("vec3", {0.25, -1.0, 1.0 / 3.0}), "vec3(0.25, -1, 0.333333343)");
  // Nine significant digits read back to the same float.
  const std::string third = averageReplacement("float", {1.0 / 3.0});
  EXPECT_EQ(std::stof(third.substr(6)), static_cast<float>(1.0 / 3.0));
}

}  // namespace
}  // namespace spire::simplify
