// The Pareto view without a window: a spire-tune output directory read into
// tuned variants with their decisions and front (and refused when it tuned
// another shader), and the plot's axes, ticks, point positions and hit test.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include <unistd.h>

#include "driver/shader_library.h"
#include "explore/decision_state.h"
#include "explore/pareto_plot.h"
#include "explore/tune_results.h"
#include "tune/results_csv.h"

namespace spire::explore {
namespace {

namespace fs = std::filesystem;

tune::VariantResult row(uint64_t index, std::vector<std::string> placements, double ms, double rmse) {
  tune::VariantResult r;
  r.index = index;
  r.placements = std::move(placements);
  r.frameMs = ms;
  r.rmse = rmse;
  r.time = {1.0, {0.9, 1.1}, 3};
  return r;
}

class TuneDirectory : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(library_.addFile("examples/terrain.spire"));
    ASSERT_TRUE(library_.compile());
    state_.emplace(*library_.choiceSpace("Terrain"));
    dir_ = fs::temp_directory_path() / ("spire-pareto-" + std::to_string(getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    const std::vector<std::string> components{"albedo", "lighting"};
    auto hazard = row(2, {"Vertex", "Fragment:ggx"}, 0.5, 0.0);
    hazard.nanPixels = 4;
    auto failed = row(3, {"PrebakeTex", "Vertex:basic"}, 0.0, 0.0);
    failed.status = "infeasible";
    const std::vector<tune::VariantResult> rows{row(0, {"Fragment", "Fragment:ggx"}, 2.0, 0.0), hazard, failed,
                                                row(1, {"PrebakeTex", "Fragment:ggx"}, 1.0, 0.01),
                                                row(4, {"Fragment", "Vertex:basic"}, 1.5, 0.05)};
    std::ofstream variants(dir_ / "variants.csv");
    variants << tune::csvHeader(components);
    for (const auto& r : rows) variants << tune::csvRow(r);
    std::ofstream(dir_ / "pareto.csv") << tune::csvHeader(components) << tune::csvRow(rows[3]) << tune::csvRow(rows[0]);
  }
  void TearDown() override { fs::remove_all(dir_); }

  ShaderLibrary library_;
  std::optional<DecisionState> state_;
  fs::path dir_;
};

TEST_F(TuneDirectory, ReadsTheTradeWithItsDecisionsAndFront) {
  std::ofstream(dir_ / "best_error_budget.decisions") << "Terrain.albedo = PrebakeTex\n";
  auto tune = loadTuneResults(dir_, "Terrain", *state_);
  ASSERT_TRUE(tune) << tune.error().message;
  EXPECT_EQ(tune->components, (std::vector<std::string>{"albedo", "lighting"}));
  // The hazard and the infeasible variant are off the trade.
  ASSERT_EQ(tune->variants.size(), 3U);
  EXPECT_EQ(tune->variants[0].index, 0U);
  EXPECT_EQ(tune->variants[1].index, 1U);
  EXPECT_EQ(tune->variants[2].index, 4U);
  ASSERT_EQ(tune->front.size(), 2U);
  const TunedVariant& fastest = tune->variants[tune->front[0]];
  EXPECT_EQ(fastest.index, 1U);
  EXPECT_EQ(fastest.decisions,
            (std::map<std::string, std::string>{{"albedo", "PrebakeTex"}, {"lighting", "Fragment:ggx"}}));
  EXPECT_TRUE(fastest.onFront);
  EXPECT_FALSE(tune->variants[2].onFront);
  EXPECT_EQ(decisionsText(fastest), "albedo=PrebakeTex lighting=Fragment:ggx");
  EXPECT_EQ(matchingVariant(*tune, fastest.decisions), tune->front[0]);
  EXPECT_EQ(matchingVariant(*tune, {{"albedo", "PrebakeTex"}}), std::nullopt) << "the same decisions, all of them";
}

TEST_F(TuneDirectory, AnotherShadersRunIsRefused) {
  std::ofstream(dir_ / "best_error_budget.decisions") << "GuardedDivide.quotient = Fragment\n";
  auto tune = loadTuneResults(dir_, "Terrain", *state_);
  ASSERT_FALSE(tune);
  EXPECT_NE(tune.error().message.find("spire-tune's output for shader 'GuardedDivide', but the explored instance's "
                                      "shader is 'Terrain'"),
            std::string::npos)
      << tune.error().message;
}

TEST_F(TuneDirectory, AComponentTheShaderLacksIsRefused) {
  std::ofstream(dir_ / "variants.csv") << tune::csvHeader({"quotient"});
  auto tune = loadTuneResults(dir_, "Terrain", *state_);
  ASSERT_FALSE(tune);
  EXPECT_NE(tune.error().message.find("the component 'quotient', which is not a choice of the explored shader"),
            std::string::npos)
      << tune.error().message;
  fs::remove(dir_ / "variants.csv");
  EXPECT_FALSE(loadTuneResults(dir_, "Terrain", *state_)) << "no table";
}

TEST(ParetoPlot, AxesTicksAndPositions) {
  const std::vector<TunedVariant> variants{{0, {}, 2.0, 0.0, true}, {1, {}, 1.0, 0.04, true}, {2, {}, 1.5, 0.1, false}};
  const ParetoPlot plot = planPlot(variants);
  // A margin around the data; errors from 0.
  EXPECT_LT(plot.time.low, 1.0);
  EXPECT_GT(plot.time.high, 2.0);
  EXPECT_EQ(plot.error.low, 0.0);
  EXPECT_GT(plot.error.high, 0.1);
  for (const PlotAxis* axis : {&plot.time, &plot.error}) {
    ASSERT_GE(axis->ticks.size(), 3U);
    for (double t : axis->ticks) {
      EXPECT_GE(t, axis->low);
      EXPECT_LE(t, axis->high);
    }
  }
  EXPECT_EQ(plot.error.ticks.front(), 0.0);
  EXPECT_NEAR(plot.time.ticks[1] - plot.time.ticks[0], 0.2, 1e-12) << "1, 2 or 5 times a power of ten";

  const std::vector<PlotPoint> points = placePoints(plot, variants, {10.0F, 20.0F}, 100.0F, 50.0F);
  ASSERT_EQ(points.size(), 3U);
  EXPECT_LT(points[1].x, points[2].x) << "faster is further left";
  EXPECT_LT(points[2].x, points[0].x);
  EXPECT_FLOAT_EQ(points[0].y, 70.0F) << "no error lies on the bottom edge";
  EXPECT_LT(points[2].y, points[1].y) << "larger errors are higher up";
  for (const PlotPoint& p : points) {
    EXPECT_GT(p.x, 10.0F);
    EXPECT_LT(p.x, 110.0F);
  }
  EXPECT_EQ(pointUnder(points, {points[2].x + 3.0F, points[2].y}, 5.0F), 2U);
  EXPECT_EQ(pointUnder(points, {points[2].x + 6.0F, points[2].y}, 5.0F), std::nullopt);
}

TEST(ParetoPlot, OnePointSitsInsideTheAxes) {
  const ParetoPlot plot = planPlot({{0, {}, 3.0, 0.0, true}});
  EXPECT_LT(plot.time.low, 3.0);
  EXPECT_GT(plot.time.high, 3.0);
  EXPECT_GT(plot.error.high, 0.0);
  EXPECT_NEAR(plot.time.fraction(3.0), 0.5, 1e-9);
}

}  // namespace
}  // namespace spire::explore
