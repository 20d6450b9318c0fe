// The search's moves (search/candidates.h, proposeMoves): He et al.'s move
// to vertex and move to parameter stage, which in Spire are the worlds a
// component's choice offers. The pipeline here is a user's, with world
// names the engine's pipeline does not have: a move goes to whatever
// worlds the choice file names, the cheapest first.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "search/candidates.h"
#include "search/chain.h"
#include "search/model_cost.h"

namespace spire::search {
namespace {

constexpr const char* kModule = R"(
pipeline Baker {
    abstract world Params;
    abstract world Corners;
    world Texels : "GLSL" export standardExport;
    world PerCorner : "GLSL" export vertexExport(clipPos);
    world PerPixel : "GLSL" export standardExport;
    import Params->Texels using uniformImport;
    import Params->PerCorner using uniformImport;
    import Params->PerPixel using uniformImport;
    import Corners->PerCorner using standardImport;
    import Corners->Texels using standardImport;
    import PerCorner->PerPixel using standardImport;
    import Texels->PerPixel using textureImport(uv);
    @Corners vec3 pos;
    @Corners vec2 uv;
    abstract @PerCorner vec4 clipPos;
    abstract export @PerPixel vec4 result;
}

shader Ramp using Baker {
    @Params mat4 mvp;
    @Params sampler2D noise;
    vec4 clipPos = mvp * vec4(pos, 1.0);
    // Four scalar lanes of trigonometry: per corner, it costs less, even
    // with the varying that carries it.
    float shade = dot(sin(vec4(uv, uv.yx) * 3.0) * cos(vec4(uv.yx, uv) * 5.0) +
                      sin(vec4(uv.yx, uv) * 7.0) * cos(vec4(uv, uv.yx) * 11.0), vec4(0.5)) + 0.25;
    vec2 warped = uv * 3.0 + vec2(0.5);
    // Three fetches: baked into one texel fetch, it costs less per pixel
    // than per corner.
    float grain = texture(noise, warped).x + texture(noise, warped * 2.0).y + texture(noise, warped * 3.0).z;
    @PerPixel float glow = shade * grain;
    vec4 result = vec4(vec3(glow), 1.0);
}

shader RampSearch : Ramp {
    float shade:level1 = dot(sin(vec4(uv, uv.yx) * 3.0) * cos(vec4(uv.yx, uv) * 5.0) +
                             sin(vec4(uv.yx, uv) * 7.0) * cos(vec4(uv, uv.yx) * 11.0), vec4(0.5));
}
)";

class MovesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto compiled = compileModule({}, "ramp_search.spire", kModule, "RampSearch");
    ASSERT_TRUE(compiled) << compiled.error().message;
    module_ = std::move(compiled).value();
  }

  // The moves of `components` from `placement`, K1 `k1`.
  std::vector<Candidate> moves(const Placement& placement, std::vector<std::string> components, size_t k1) const {
    StepRequest request;
    request.current = module_.get();
    request.derived = "RampSearch";
    request.placement = placement;
    request.original = placement;
    request.components = std::move(components);
    request.k1 = k1;
    return proposeMoves(request);
  }

  std::unique_ptr<ShaderLibrary> module_;
};

const Placement kPerPixel{{"clipPos", "PerCorner"}, {"shade", "PerPixel"}, {"warped", "PerPixel"},
                          {"grain", "PerPixel"},    {"glow", "PerPixel"},  {"result", "PerPixel"}};

TEST_F(MovesTest, AComponentMovesToTheOtherWorldsItsChoiceOffersCheapestFirst) {
  const std::vector<Candidate> all = moves(kPerPixel, {"grain"}, 4);
  ASSERT_EQ(all.size(), 2U);
  EXPECT_EQ(all[0].rewriting.moved.at(0).second, "Texels");
  EXPECT_EQ(all[1].rewriting.moved.at(0).second, "PerCorner");
  const double before = *modelCost(*module_, "RampSearch", kPerPixel);
  double previous = 0.0;
  for (const Candidate& c : all) {
    EXPECT_TRUE(isMove(c.rewriting));
    EXPECT_EQ(c.rewriting.rule, kMoveRule);
    EXPECT_EQ(c.rewriting.component, "grain");
    EXPECT_EQ(c.rewriting.from, "grain");
    EXPECT_EQ(c.rewriting.before, "PerPixel");
    // grain's coordinate cannot reach it from per pixel: it comes along.
    const std::string world = c.rewriting.moved.at(0).second;
    EXPECT_EQ(c.rewriting.moved, (Placement{{"grain", world}, {"warped", world}}));
    EXPECT_EQ(c.rewriting.after, world + ", with warped " + world);
    EXPECT_EQ(c.rewriting.text, "") << "a move adds no definition";
    EXPECT_EQ(c.level.moved, c.rewriting.moved);
    const double cost = *modelCost(*module_, "RampSearch", applied(kPerPixel, c.rewriting));
    EXPECT_LT(cost, before) << c.rewriting.after;
    EXPECT_GT(cost, previous) << "cheapest first";
    previous = cost;
  }
  EXPECT_NE(all[0].key, all[1].key);
  EXPECT_EQ(placementOf(applied(kPerPixel, all[0].rewriting), "grain"), "Texels");

  // K1 keeps the cheapest.
  const std::vector<Candidate> one = moves(kPerPixel, {"grain"}, 1);
  ASSERT_EQ(one.size(), 1U);
  EXPECT_EQ(one[0].rewriting.moved.at(0).second, "Texels");
}

// Per corner, the coordinate is read where it is: only what cannot stay
// is carried.
TEST_F(MovesTest, WhatCanStayWhereItIsStays) {
  Placement perCorner = kPerPixel;
  perCorner[2].second = "PerCorner";  // warped
  const std::vector<Candidate> all = moves(perCorner, {"grain"}, 4);
  const auto move = std::find_if(all.begin(), all.end(),
                                 [](const Candidate& c) { return c.rewriting.moved.at(0).second == "PerCorner"; });
  ASSERT_NE(move, all.end());
  EXPECT_EQ(move->rewriting.moved, (Placement{{"grain", "PerCorner"}}));
  EXPECT_EQ(move->rewriting.after, "PerCorner");
}

// Baking the shade would cost a fetch per pixel, more than it saves: only
// per corner is cheaper.
TEST_F(MovesTest, AMoveThatSavesNothingIsNone) {
  const std::vector<Candidate> all = moves(kPerPixel, {"shade"}, 4);
  ASSERT_EQ(all.size(), 1U);
  EXPECT_EQ(all[0].rewriting.after, "PerCorner");
}

TEST_F(MovesTest, AMoveKeepsTheVariationItMoves) {
  Placement rewritten = kPerPixel;
  rewritten[1].second = "PerPixel:level1";
  const std::vector<Candidate> all = moves(rewritten, {"shade"}, 1);
  ASSERT_EQ(all.size(), 1U);
  EXPECT_EQ(all[0].rewriting.from, "shade:level1");
  EXPECT_EQ(all[0].rewriting.variation, "level1");
  EXPECT_EQ(all[0].rewriting.after, "PerCorner:level1");
  EXPECT_EQ(definitionName(all[0].rewriting), "shade:level1");
  EXPECT_EQ(placementOf(applied(rewritten, all[0].rewriting), "shade"), "PerCorner:level1");
}

TEST_F(MovesTest, AComponentWithOneWorldOrNotComputedHasNoMove) {
  EXPECT_TRUE(moves(kPerPixel, {"glow"}, 4).empty()) << "glow is declared @PerPixel";
  Placement withoutShade = kPerPixel;
  withoutShade.erase(withoutShade.begin() + 1);  // shade
  EXPECT_TRUE(moves(withoutShade, {"shade"}, 4).empty()) << "a component the level does not compute";
}

TEST_F(MovesTest, TheChainsModuleHasNoDefinitionForAMove) {
  const std::vector<Candidate> all = moves(kPerPixel, {"shade"}, 1);
  ASSERT_EQ(all.size(), 1U);
  const std::string text = chainModuleText({"ramp.spire", "Ramp", "RampSearch"}, {&all[0].level});
  EXPECT_EQ(text.find("float shade"), std::string::npos) << text;
  EXPECT_NE(text.find("shader RampSearch : Ramp {"), std::string::npos) << text;
}

}  // namespace
}  // namespace spire::search
