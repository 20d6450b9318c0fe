// spire-tune --extremes: the automatic ranges of every material input, the
// per-input corner samples, and whole runs on lavapipe (with validation) in
// which the extremes find a texture-driven hazard no --param names, and a
// reference that goes non-finite only at an extreme.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include <unistd.h>

#include "common/scoped_env.h"
#include "engine/device_fixture.h"
#include "scene/scene_file.h"
#include "support/diagnostic_renderer.h"
#include "tune/extremes.h"
#include "tune/parameter_range.h"
#include "tune/results_csv.h"
#include "tune/stability_table.h"
#include "tune/tune_cli.h"

namespace spire::tune {
namespace {

namespace fs = std::filesystem;

std::string readText(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

// A number's range has 0 at one end and max(1, 2|v|) on v's side at the
// other, per component of a vector.
TEST(Extremes, NumberRangesReachZeroAndBeyondTheSceneValue) {
  const ParameterRange range = numberRange("v", {0.5, -0.3, 3.0, 0.0, -4.0});
  EXPECT_FALSE(range.texture);
  EXPECT_EQ(range.minimum, (std::vector<double>{0.0, -1.0, 0.0, 0.0, -8.0}));
  EXPECT_EQ(range.maximum, (std::vector<double>{1.0, 0.0, 6.0, 1.0, 0.0}));
  EXPECT_TRUE(range.extraCorners.empty());
}

struct CheckerScene {
  SourceManager sources;
  DiagnosticList diags;
  std::optional<scene::SceneFile> scene;
};

// A checker texture (channels between 0.1 and 0.8) and a vec3 color.
void parseCheckerScene(CheckerScene& s) {
  auto parsed = scene::parseSceneFile("extremes.json", R"({
    "camera": {"views": [{"position": [0, 1, 2], "target": [0, 0, 0]}]},
    "meshes": {"plane": {"type": "plane"}},
    "textures": {"chk": {"type": "checker", "size": 8, "cells": 2, "color": [0.2, 0.4, 0.6, 1.0],
                         "color2": [0.8, 0.1, 0.3, 1.0]}},
    "instances": [{"mesh": "plane", "source": "s.spire", "shader": "S",
                   "material": {"maskMap": "chk", "color": [0.5, 0.5, 2.0], "matMVP": {"engine": "matMVP"}}}]})",
                                      ".", s.sources, s.diags);
  ASSERT_TRUE(parsed) << renderDiagnostics(s.sources, s.diags, DiagnosticFormat::Text);
  s.scene = std::move(parsed).value();
}

// Every input the material binds gets a range (engine values none); a
// texture's is solid 0 to solid 1 per channel with its own darkest and
// brightest texels as extra corners; --param replaces an input's range.
TEST(Extremes, EveryMaterialInputGetsARangeAndParamOverridesIt) {
  CheckerScene s;
  parseCheckerScene(s);
  ASSERT_TRUE(s.scene);
  const scene::InstanceDesc& instance = s.scene->instances.front();
  const auto ranges = extremeRanges(instance, *s.scene, {});
  ASSERT_TRUE(ranges) << ranges.error().message;
  ASSERT_EQ(ranges->size(), 2U);
  const ParameterRange& mask = ranges->at(0);
  EXPECT_EQ(mask.component, "maskMap");
  EXPECT_TRUE(mask.texture);
  EXPECT_EQ(mask.minimum, std::vector<double>(4, 0.0));
  EXPECT_EQ(mask.maximum, std::vector<double>(4, 1.0));
  ASSERT_EQ(mask.extraCorners.size(), 2U);
  EXPECT_EQ(mask.extraCorners[0].kind, "texture-min");
  EXPECT_NEAR(mask.extraCorners[0].values[1], 0.1, 1.0 / 255);
  EXPECT_EQ(mask.extraCorners[1].kind, "texture-max");
  EXPECT_NEAR(mask.extraCorners[1].values[0], 0.8, 1.0 / 255);
  const ParameterRange& color = ranges->at(1);
  EXPECT_EQ(color.component, "color");
  EXPECT_EQ(color.maximum, (std::vector<double>{1.0, 1.0, 4.0}));

  const auto given = parseParameter("color=0.25:0.75", instance, *s.scene);
  ASSERT_TRUE(given);
  const auto overridden = extremeRanges(instance, *s.scene, {*given});
  ASSERT_TRUE(overridden);
  EXPECT_EQ(overridden->at(1).minimum, std::vector<double>(3, 0.25));
  EXPECT_EQ(overridden->at(1).maximum, std::vector<double>(3, 0.75));
  EXPECT_TRUE(overridden->at(0).texture) << "the texture keeps its automatic range";
}

// The scene's values, every input at its minimum and at its maximum, each
// input alone at each of its corners, then seeded draws: as many as the
// formula says, the same for the same seed, and each corner changing
// exactly one input.
TEST(Extremes, CornerSamplesChangeOneInputEachAndAreDeterministic) {
  CheckerScene s;
  parseCheckerScene(s);
  ASSERT_TRUE(s.scene);
  const auto ranges = extremeRanges(s.scene->instances.front(), *s.scene, {});
  ASSERT_TRUE(ranges);
  const SamplePlan plan = extremeSamples(*ranges, 3, 11);
  EXPECT_EQ(extremeSampleCount(*ranges, 3), 3U + 4U + 2U + 3U);
  ASSERT_EQ(plan.samples.size(), extremeSampleCount(*ranges, 3));
  ASSERT_EQ(plan.labels.size(), plan.samples.size());
  const SamplePlan again = extremeSamples(*ranges, 3, 11);
  EXPECT_EQ(plan.samples, again.samples);
  EXPECT_NE(plan.samples.back(), extremeSamples(*ranges, 3, 12).samples.back()) << "the seed drives the draws";
  EXPECT_TRUE(plan.samples[0].empty());
  EXPECT_EQ(plan.labels[0].kind, "scene");
  EXPECT_EQ(plan.samples[1].at("maskMap"), ranges->at(0).minimum);
  EXPECT_EQ(plan.samples[2].at("color"), ranges->at(1).maximum);
  std::multiset<std::string> corners;
  for (size_t k = 3; k < 9; ++k) {
    ASSERT_EQ(plan.samples[k].size(), 1U) << k;
    EXPECT_EQ(plan.samples[k].begin()->first, plan.labels[k].input) << k;
    corners.insert(plan.labels[k].input + " " + plan.labels[k].kind);
  }
  EXPECT_EQ(corners, (std::multiset<std::string>{"maskMap min", "maskMap max", "maskMap texture-min",
                                                 "maskMap texture-max", "color min", "color max"}));
  for (size_t k = 9; k < plan.samples.size(); ++k) {
    EXPECT_EQ(plan.labels[k].kind, "sample");
    for (const ParameterRange& r : *ranges) {
      for (size_t c = 0; c < r.minimum.size(); ++c) {
        EXPECT_GE(plan.samples[k].at(r.component)[c], r.minimum[c]);
        EXPECT_LE(plan.samples[k].at(r.component)[c], r.maximum[c]);
      }
    }
  }
}

// The table diagnoses a variant's hazardous per-input corners; the scene's
// own values alone when they are hazardous; a combination only when no
// corner is.
TEST(Extremes, TheTableDiagnosesCornersFirst) {
  const std::vector<SampleLabel> labels{{"", "scene"}, {"", "all-min"}, {"", "all-max"}, {"a", "min"},
                                        {"a", "max"},  {"b", "min"},    {"b", "max"},    {"", "sample"}};
  using Pairs = std::vector<std::pair<size_t, size_t>>;
  EXPECT_EQ(samplesToDiagnose({{1, 0}, {3, 0}, {6, 1}}, labels), (Pairs{{3, 0}, {6, 1}}));
  EXPECT_EQ(samplesToDiagnose({{0, 0}, {1, 0}, {3, 0}}, labels), (Pairs{{0, 0}}));
  EXPECT_EQ(samplesToDiagnose({{1, 0}, {7, 0}}, labels), (Pairs{{1, 0}}));
  EXPECT_TRUE(samplesToDiagnose({}, labels).empty());
}

// The report's lines name the component, its definition, the input and its
// value; the notes say which samples the reference left out and when the
// limit on diagnoses cut the table short.
TEST(Extremes, TheReportSaysWhatTheLimitCut) {
  StabilityTable table;
  table.samples = 10;
  table.limit = 16;
  table.cut = 3;
  table.referenceExcluded = {"when maskMap = 0,0,0,0 (min)"};
  table.rows.push_back({"4",
                        "scaled=Vertex:raw",
                        "scaled",
                        "Vertex:raw",
                        "Vertex",
                        "all",
                        "all-min",
                        "color=0,0 maskMap=0,0",
                        true,
                        25,
                        "vertices",
                        {},
                        {}});
  const std::string text = stabilityMarkdown(table);
  EXPECT_NE(text.find("- variant 4 (scaled=Vertex:raw): scaled (Vertex:raw) goes NaN under all-min (color=0,0 "
                      "maskMap=0,0) (25 vertices)"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("The reference is NaN or Inf under 1 of the 10 samples"), std::string::npos) << text;
  EXPECT_NE(text.find("The limit of 16 diagnosed (variant, sample) pairs cut 3 more short"), std::string::npos) << text;
  EXPECT_EQ(lines(stabilityCsv(table)).back(),
            "4,scaled=Vertex:raw,scaled,Vertex:raw,Vertex,all,all-min,\"color=0,0 maskMap=0,0\",NaN,25,vertices,,");
}

class ExtremesRun : public vk::testing::DeviceTest {};

// spire-tune --extremes on the texture division's `scaled` into a fresh
// `dir`, with `extra` arguments: the rows of variants.csv (none when the
// run failed, its messages in `err`).
std::vector<VariantResult> tuneTextureDivide(const fs::path& dir, const std::vector<std::string>& extra,
                                             std::ostringstream& err) {
  fs::remove_all(dir);
  std::vector<std::string> args{"tests/data/engine/stability/texture_divide.json",
                                "--shader",
                                "TextureDivide",
                                "--components",
                                "scaled",
                                "--extremes",
                                "--max-frames",
                                "3",
                                "--validation",
                                "-o",
                                dir.string()};
  args.insert(args.end(), extra.begin(), extra.end());
  std::ostringstream out;
  // Under the asan preset the worker processes unload lavapipe at exit and
  // LeakSanitizer can no longer name its frames (tests/lsan.supp), so leak
  // checking stays with this process, as in tune_test.cpp.
  const spire::testing::ScopedEnv workers("ASAN_OPTIONS", "detect_leaks=0");
  if (runTune(args, out, err, SPIRE_TUNE_EXE) != 0) return {};
  auto rows = readResults(dir / "variants.csv", {"scaled"});
  if (!rows) return {};
  return std::move(rows).value();
}

// The scene's mask is 0.5 everywhere: without --param nothing names it, but
// --extremes sweeps it to solid 0 and the raw divisions go Inf there. The
// table names the component, its world and the texture input; the guarded
// variants and the reference stay out of it.
TEST_F(ExtremesRun, FindATextureDrivenHazardWithoutAnyParam) {
  const fs::path dir = fs::temp_directory_path() / ("spire_tune_extremes_" + std::to_string(::getpid()));
  std::ostringstream err;
  const std::vector<VariantResult> rows = tuneTextureDivide(dir, {"--param-samples", "1", "--jobs", "1"}, err);
  ASSERT_EQ(rows.size(), 6U) << err.str();
  for (const VariantResult& r : rows) {
    const bool raw = r.placements[0].ends_with(":raw");
    EXPECT_EQ(std::isinf(r.worstRmse), raw) << r.placements[0];
    EXPECT_GE(r.worstRmse, r.rmse) << r.placements[0];
    EXPECT_EQ(r.hazardSamples.empty(), !raw) << r.placements[0];
  }
  const std::vector<std::string> table = lines(readText(dir / "stability.csv"));
  ASSERT_FALSE(table.empty());
  EXPECT_EQ(table[0],
            "variant,decisions,component,definition,world,input,value_kind,value,non_finite,count,unit,operation,"
            "operation_source");
  EXPECT_NE(std::find(table.begin(), table.end(),
                      "2,scaled=Fragment:raw,scaled,Fragment:raw,Fragment,maskMap,min,\"0,0,0,0\",Inf,289,px,color / "
                      "mask,texture_divide.spire:20:23"),
            table.end())
      << readText(dir / "stability.csv");
  for (size_t k = 1; k < table.size(); ++k) {
    EXPECT_NE(table[k].find(":raw,scaled,"), std::string::npos) << table[k];
    EXPECT_NE(table[k].find(",maskMap,min,"), std::string::npos) << table[k];
  }
  const std::string report = readText(dir / "report.md");
  EXPECT_NE(report.find("## Stability"), std::string::npos);
  EXPECT_NE(report.find("- variant 2 (scaled=Fragment:raw): scaled (Fragment:raw) goes Inf at `color / mask` "
                        "(texture_divide.spire:20:23) when maskMap = 0,0,0,0 "
                        "(min) (289 px)"),
            std::string::npos)
      << report;
  EXPECT_NE(readText(dir / "report.html").find("<h2>Stability</h2>"), std::string::npos);
  fs::remove_all(dir);
}

// A reference that is finite at the scene's values but Inf where the mask
// is 0 does not stop an --extremes run: those samples leave every variant's
// error, so the raw variants, equal to it elsewhere, are finite, and the
// table lists the reference under the mask's minimum. Workers agree.
TEST_F(ExtremesRun, AReferenceHazardousOnlyAtAnExtremeLeavesThoseSamplesOut) {
  const fs::path dir = fs::temp_directory_path() / ("spire_tune_extreme_ref_" + std::to_string(::getpid()));
  for (const char* jobs : {"1", "2"}) {
    std::ostringstream err;
    const std::vector<VariantResult> rows = tuneTextureDivide(
        dir, {"--reference", "tests/data/engine/stability/texture_divide_raw_fragment.decisions", "--jobs", jobs}, err);
    ASSERT_EQ(rows.size(), 6U) << err.str();
    for (const VariantResult& r : rows) {
      EXPECT_EQ(r.nanPixels + r.infPixels, 0U) << r.placements[0] << " jobs " << jobs;
      EXPECT_TRUE(std::isfinite(r.worstRmse)) << r.placements[0];
    }
    const std::vector<std::string> table = lines(readText(dir / "stability.csv"));
    ASSERT_EQ(table.size(), 2U) << readText(dir / "stability.csv");
    EXPECT_EQ(table[1],
              "reference,,scaled,Fragment:raw,Fragment,maskMap,min,\"0,0,0,0\",Inf,289,px,color / "
              "mask,texture_divide.spire:20:23");
    const std::string report = readText(dir / "report.md");
    EXPECT_NE(report.find("- reference: scaled (Fragment:raw) goes Inf at `color / mask` (texture_divide.spire:20:23) "
                          "when maskMap = 0,0,0,0 (min) (289 px)"),
              std::string::npos)
        << report;
    EXPECT_NE(report.find("The reference is NaN or Inf under 2 of the 10 samples, which every variant's error "
                          "leaves out"),
              std::string::npos)
        << report;
    EXPECT_NE(err.str().find("spire-tune: warning: The reference is NaN or Inf under 2 of the 10 samples"),
              std::string::npos)
        << err.str();
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace spire::tune
