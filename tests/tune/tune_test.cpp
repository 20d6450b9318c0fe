// spire-tune: the search space, the Pareto front, the CSV journal, and a whole
// run in-process on a small scene (with validation on), including resuming.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <string_view>
#include <thread>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include "common/lod_test_scene.h"
#include "driver/exit_codes.h"
#include "driver/shader_library.h"
#include "engine/device_fixture.h"
#include "lod/lod_policy.h"
#include "scene/scene_file.h"
#include "scene/texture.h"
#include "support/diagnostic_renderer.h"
#include "tune/format_selection.h"
#include "tune/parameter_range.h"
#include "tune/pareto.h"
#include "tune/results_csv.h"
#include "tune/run_settings.h"
#include "tune/tune_cli.h"
#include "tune/tune_space.h"
#include "tune/work_queue.h"

extern char** environ;

namespace spire::tune {
namespace {

namespace fs = std::filesystem;

std::vector<graph::Choice> terrainChoices() {
  std::vector<graph::Choice> choices(3);
  choices[0].key = "Terrain.albedo";
  choices[0].names = {"PrebakeTex", "Vertex", "Fragment"};
  choices[1].key = "Terrain.normal";
  choices[1].names = {"Vertex", "Fragment"};
  choices[2].key = "Terrain.lighting";
  choices[2].names = {"Vertex:basic", "Fragment:basic", "Vertex:ggx", "Fragment:ggx"};
  return choices;
}

TEST(TuneSpace, EnumeratesTheWholeProductInOrder) {
  const auto space = buildTuneSpace(terrainChoices(), {});
  ASSERT_TRUE(space) << space.error().message;
  EXPECT_EQ(space->productSize, 24U);
  ASSERT_EQ(space->points.size(), 24U);
  EXPECT_FALSE(space->sampled);
  EXPECT_EQ(space->points[0].decisions.at("albedo"), "PrebakeTex");
  EXPECT_EQ(space->points[0].decisions.at("lighting"), "Vertex:basic");
  EXPECT_EQ(space->points[23].decisions.at("albedo"), "Fragment");
  EXPECT_EQ(space->points[23].decisions.at("lighting"), "Fragment:ggx");
  for (size_t i = 0; i < space->points.size(); ++i) EXPECT_EQ(space->points[i].index, i);
}

TEST(TuneSpace, SelectsComponentsWorldsAndVariations) {
  SpaceRequest request;
  request.components = {"lighting"};
  request.only = {"ggx"};
  const auto algorithms = buildTuneSpace(terrainChoices(), request);
  ASSERT_TRUE(algorithms) << algorithms.error().message;
  ASSERT_EQ(algorithms->axes.size(), 1U);
  EXPECT_EQ(algorithms->axes[0].placements, (std::vector<std::string>{"Vertex:ggx", "Fragment:ggx"}));
  request.components = {"albedo", "normal"};
  request.only = {"Fragment"};
  const auto placement = buildTuneSpace(terrainChoices(), request);
  ASSERT_TRUE(placement) << placement.error().message;
  EXPECT_EQ(placement->productSize, 1U);
  request.components = {"albedo", "lighting@Fragment"};
  request.only = {};
  const auto perWorld = buildTuneSpace(terrainChoices(), request);
  ASSERT_TRUE(perWorld) << perWorld.error().message;
  EXPECT_EQ(perWorld->axes[1].placements, (std::vector<std::string>{"Fragment:basic", "Fragment:ggx"}));
  EXPECT_EQ(perWorld->productSize, 6U);
  // A component named with two worlds keeps both; named without one, every
  // world, whatever else names it.
  request.components = {"albedo@Fragment", "albedo@PrebakeTex", "lighting@Vertex"};
  const auto twoWorlds = buildTuneSpace(terrainChoices(), request);
  ASSERT_TRUE(twoWorlds) << twoWorlds.error().message;
  EXPECT_EQ(twoWorlds->axes[0].placements, (std::vector<std::string>{"PrebakeTex", "Fragment"}));
  EXPECT_EQ(twoWorlds->axes[1].placements, (std::vector<std::string>{"Vertex:basic", "Vertex:ggx"}));
  request.components = {"albedo@Fragment", "albedo"};
  const auto everyWorld = buildTuneSpace(terrainChoices(), request);
  ASSERT_TRUE(everyWorld) << everyWorld.error().message;
  EXPECT_EQ(everyWorld->axes[0].placements, (std::vector<std::string>{"PrebakeTex", "Vertex", "Fragment"}));
  request.components = {"albdo"};
  request.only = {};
  const auto misspelt = buildTuneSpace(terrainChoices(), request);
  ASSERT_FALSE(misspelt);
  EXPECT_NE(misspelt.error().message.find("'albdo' is not a choice"), std::string::npos) << misspelt.error().message;
}

// Definitions marked [Transition] (spire-simplify --search's blends of two
// levels) are found from the compiled shader and never explored: a
// component left without placements is no axis, unless it was asked for.
TEST(TuneSpace, LeavesOutLevelOfDetailTransitions) {
  const fs::path dir = fs::temp_directory_path() / ("spire_tune_transitions_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "t.spire") << "using \"" << fs::absolute("pipelines/engine.spire").string() << R"(";
shader T using EnginePipeline {
    @FrameUniform mat4 matMVP;
    vec4 projPos = matMVP * vec4(vert_pos, 1.0);
    vec3 tint = vec3(1.0);
    [Transition] vec3 tint:blend = vec3(0.5);
    [Transition] float fade = 0.5;
    vec4 output = vec4(tint * fade, 1.0);
}
)";
  ShaderLibrary library;
  ASSERT_TRUE(library.addFile((dir / "t.spire").string()));
  ASSERT_TRUE(library.compile());
  const graph::ChoiceSpace* choiceSpace = library.choiceSpace("T");
  ASSERT_NE(choiceSpace, nullptr);
  SpaceRequest request;
  request.transitions = transitionPlacements(*choiceSpace);
  ASSERT_EQ(request.transitions.count("tint"), 1U);
  EXPECT_EQ(request.transitions.at("tint").size(), 3U) << "tint:blend in each of its three worlds";
  for (const std::string& placement : request.transitions.at("tint")) {
    EXPECT_TRUE(placement.ends_with(":blend")) << placement;
  }
  ASSERT_EQ(request.transitions.count("fade"), 1U);
  const auto space = buildTuneSpace(library.choices("T"), request);
  ASSERT_TRUE(space) << space.error().message;
  for (const Axis& axis : space->axes) {
    EXPECT_NE(axis.component, "fade") << "every fade placement is a transition";
    for (const std::string& placement : axis.placements) EXPECT_FALSE(placement.ends_with(":blend")) << placement;
  }
  request.components = {"fade"};
  const auto asked = buildTuneSpace(library.choices("T"), request);
  ASSERT_FALSE(asked);
  EXPECT_NE(asked.error().message.find("component 'fade' has only level-of-detail transitions"), std::string::npos)
      << asked.error().message;
  fs::remove_all(dir);
}

TEST(TuneSpace, SamplesLargeProductsDeterministically) {
  SpaceRequest request;
  request.maxVariants = 5;
  const auto a = buildTuneSpace(terrainChoices(), request);
  const auto b = buildTuneSpace(terrainChoices(), request);
  ASSERT_TRUE(a && b);
  EXPECT_TRUE(a->sampled);
  ASSERT_EQ(a->points.size(), 5U);
  for (size_t i = 0; i < 5; ++i) {
    EXPECT_EQ(a->points[i].index, b->points[i].index);
    if (i > 0) {
      EXPECT_LT(a->points[i - 1].index, a->points[i].index);
    }
  }
}

// --param on a texture: NAME=MIN:MAX gives all four channels the range,
// NAME alone the texture's own per-channel range; a number input needs a
// range, and an unbound name is an error.
TEST(ParameterRange, ATextureAloneSweepsItsOwnTexelRange) {
  SourceManager sources;
  DiagnosticList diags;
  const auto scene = scene::parseSceneFile("params.json", R"({
    "camera": {"views": [{"position": [0, 1, 2], "target": [0, 0, 0]}]},
    "meshes": {"plane": {"type": "plane"}},
    "textures": {"chk": {"type": "checker", "size": 8, "cells": 2, "color": [0.2, 0.4, 0.6, 1.0],
                         "color2": [0.8, 0.1, 0.3, 1.0]}},
    "instances": [{"mesh": "plane", "source": "s.spire", "shader": "S",
                   "material": {"maskMap": "chk", "color": [0.5, 0.5, 0.5]}}]})",
                                           ".", sources, diags);
  ASSERT_TRUE(scene) << renderDiagnostics(sources, diags, DiagnosticFormat::Text);
  const scene::InstanceDesc& instance = scene->instances.front();
  const auto own = parseParameter("maskMap", instance, *scene);
  ASSERT_TRUE(own) << own.error().message;
  EXPECT_TRUE(own->texture);
  const std::vector<double> low{0.2, 0.1, 0.3, 1.0};
  const std::vector<double> high{0.8, 0.4, 0.6, 1.0};
  for (size_t c = 0; c < 4; ++c) {
    EXPECT_NEAR(own->minimum[c], low[c], 1.0 / 255) << c;
    EXPECT_NEAR(own->maximum[c], high[c], 1.0 / 255) << c;
  }
  const auto solid = parseParameter("maskMap=0:1", instance, *scene);
  ASSERT_TRUE(solid);
  EXPECT_EQ(solid->minimum, std::vector<double>(4, 0.0));
  const auto color = parseParameter("color=0:2", instance, *scene);
  ASSERT_TRUE(color);
  EXPECT_EQ(color->maximum, std::vector<double>(3, 2.0));
  EXPECT_FALSE(color->texture);
  const std::vector<ParameterSample> samples = parameterSamples({*own, *color}, 2, 7);
  ASSERT_EQ(samples.size(), 4U);
  EXPECT_EQ(samples[0].at("maskMap"), own->minimum);
  EXPECT_EQ(samples[1].at("color"), color->maximum);
  for (size_t c = 0; c < 4; ++c) {
    EXPECT_GE(samples[2].at("maskMap")[c], own->minimum[c]);
    EXPECT_LE(samples[3].at("maskMap")[c], own->maximum[c]);
  }
  const auto noRange = parseParameter("color", instance, *scene);
  ASSERT_FALSE(noRange);
  EXPECT_NE(noRange.error().message.find("only a texture has a range of its own"), std::string::npos);
  const auto unbound = parseParameter("nothing=0:1", instance, *scene);
  ASSERT_FALSE(unbound);
  EXPECT_NE(unbound.error().message.find("binds no numbers or texture to 'nothing'"), std::string::npos);
}

TEST(Pareto, KeepsOnlyUndominatedFiniteVariants) {
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<Measured> points{
      {10.0, 0.0, true, 0.0, 0.0},   // 0: reference, slowest exact
      {5.0, 0.1, true, 0.0, 0.0},    // 1: front
      {6.0, 0.2, true, 0.0, 0.0},    // 2: dominated by 1
      {2.0, inf, true, 0.0, 0.0},    // 3: NaN pixels: never on the front
      {3.0, 0.3, true, 0.0, 0.0},    // 4: front
      {1.0, 0.05, false, 0.0, 0.0},  // 5: failed
      {5.0, 0.05, true, 0.0, 0.0},   // 6: as fast as 1 and more accurate: replaces it
  };
  const std::vector<size_t> front = paretoFront(points);
  EXPECT_EQ(front, (std::vector<size_t>{4, 6, 0}));
  // Every front member is faster than every variant of lower error.
  for (size_t f : front) {
    for (size_t i = 0; i < points.size(); ++i) {
      if (points[i].valid && points[i].error < points[f].error) {
        EXPECT_LT(points[f].frameMs, points[i].frameMs);
      }
    }
  }
}

// With intervals, a variant faster than a more accurate one only within the
// noise is left off: which of the two measured faster is chance, and a
// second run would find the other. Measurably faster, it stays.
TEST(Pareto, LeavesOffWhatIsFasterOnlyWithinTheNoise) {
  const std::vector<Measured> points{
      {10.0, 0.0, true, 9.8, 10.2},  // 0: exact
      {9.9, 0.01, true, 9.7, 10.1},  // 1: faster than 0 by its median only: off
      {8.0, 0.02, true, 7.9, 8.1},   // 2: measurably faster than 0: on
      {7.9, 0.02, true, 7.8, 8.2},   // 3: as accurate as 2, faster within the noise: both stay
      {6.0, 0.05, true, 5.0, 7.9},   // 4: its interval reaches 3's: not measurably faster, off
      {4.0, 0.08, true, 3.9, 4.1},   // 5: on
  };
  EXPECT_EQ(paretoFront(points), (std::vector<size_t>{5, 3, 2, 0}));
  // Measurably faster at the same accuracy (closer than kSameError), 3
  // replaces 2.
  std::vector<Measured> apart = points;
  apart[3] = {7.0, 0.02 + kSameError / 2, true, 6.9, 7.1};
  EXPECT_EQ(paretoFront(apart), (std::vector<size_t>{5, 3, 0}));
  // The same points without intervals: the classic front.
  std::vector<Measured> classic = points;
  for (Measured& m : classic) m.lowMs = m.highMs = 0.0;
  EXPECT_EQ(paretoFront(classic), (std::vector<size_t>{5, 4, 3, 1, 0}));
}

TEST(ResultsCsv, RoundTripsAndRejectsOtherRuns) {
  const fs::path path = fs::temp_directory_path() / ("spire_tune_csv_" + std::to_string(::getpid()) + ".csv");
  VariantResult r;
  r.index = 7;
  r.placements = {"PrebakeTex", "Fragment:ggx"};
  r.status = "failed: a, \"quoted\" reason";
  r.frameMs = 1.5;
  r.rmse = std::numeric_limits<double>::infinity();
  r.psnr = 0.0;
  r.nanPixels = 3;
  r.sameAs = 2;
  r.kernels = "Vertex=00ff;";
  r.hazardSamples = {{1, 0}, {5, 2}};
  {
    std::ofstream out(path);
    out << csvHeader({"albedo", "lighting"}) << csvRow(r) << "8,Vertex";  // a row cut off by an interruption
  }
  const auto rows = readResults(path, {"albedo", "lighting"});
  ASSERT_TRUE(rows) << rows.error().message;
  ASSERT_EQ(rows->size(), 1U);
  EXPECT_EQ((*rows)[0].status, r.status);
  EXPECT_EQ((*rows)[0].placements, r.placements);
  EXPECT_TRUE(std::isinf((*rows)[0].rmse));
  EXPECT_EQ((*rows)[0].sameAs, 2U);
  EXPECT_EQ((*rows)[0].kernels, r.kernels);
  EXPECT_EQ((*rows)[0].hazardSamples, r.hazardSamples);
  EXPECT_FALSE(readResults(path, {"normal"}));
  fs::remove(path);
}

// A table from an older spire-tune, which had fewer trailing columns, is
// named as such rather than as a run over other components, and its rows are
// never mixed with new ones.
TEST(ResultsCsv, NamesATableFromAnOlderTuner) {
  const fs::path path = fs::temp_directory_path() / ("spire_tune_old_csv_" + std::to_string(::getpid()) + ".csv");
  {
    std::string header = csvHeader({"albedo"});
    header.erase(header.rfind(",hazard_causes"));  // the table before hazard causes and samples
    std::ofstream(path) << header << "\n0,Fragment,ok\n";
  }
  const auto rows = readResults(path, {"albedo"});
  ASSERT_FALSE(rows);
  EXPECT_NE(rows.error().message.find("written by an older spire-tune"), std::string::npos) << rows.error().message;
  EXPECT_NE(rows.error().message.find("hazard_causes, hazard_samples"), std::string::npos) << rows.error().message;
  const auto components = readComponents(path);
  ASSERT_FALSE(components);
  EXPECT_NE(components.error().message.find("written by an older spire-tune"), std::string::npos)
      << components.error().message;
  fs::remove(path);
}

// The settings file reads back what was written, values with colons and
// empty ones (also when an editor dropped the space after the colon)
// included; a line that is not `name: value` is named with its line.
TEST(RunSettingsFile, RoundTripsAndNamesABadLine) {
  const RunSettings settings{{{"scene", "/a/b.json"}, {"only", ""}, {"param", "roughness=0:1 mask=0.5:1"}}};
  const auto read = parseSettings(settingsText(settings), "settings.txt");
  ASSERT_TRUE(read) << read.error().message;
  EXPECT_EQ(read->entries, settings.entries);
  const auto trimmed = parseSettings("only:\nseed: 3\n", "settings.txt");
  ASSERT_TRUE(trimmed) << trimmed.error().message;
  EXPECT_EQ(trimmed->entries, (std::vector<std::pair<std::string, std::string>>{{"only", ""}, {"seed", "3"}}));
  const auto bad = parseSettings("seed: 3\nno separator\n", "dir/settings.txt");
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().message, "dir/settings.txt:2: not 'name: value': no separator");
}

// A directory without rows records the settings; the same settings resume;
// other ones are refused, naming each that differs; rows with no record are
// refused too.
TEST(RunSettingsFile, ResumesOnlyUnderTheRecordedSettings) {
  const fs::path dir = fs::temp_directory_path() / ("spire_tune_settings_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const RunSettings settings{{{"resolution", "320x240"}, {"frames", "3"}, {"seed", "1"}}};
  ASSERT_TRUE(recordOrCheckSettings(dir, settings, false));
  EXPECT_TRUE(fs::exists(dir / "settings.txt"));
  EXPECT_TRUE(recordOrCheckSettings(dir, settings, true));
  RunSettings other = settings;
  other.entries[0].second = "640x480";
  other.entries[1].second = "5";
  const auto refused = recordOrCheckSettings(dir, other, true);
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.error().message.find("resolution: '320x240' then, '640x480' now; frames: '3' then, '5' now"),
            std::string::npos)
      << refused.error().message;
  EXPECT_EQ(refused.error().message.find("seed"), std::string::npos) << refused.error().message;
  // Without rows, other settings simply replace the recorded ones.
  ASSERT_TRUE(recordOrCheckSettings(dir, other, false));
  EXPECT_TRUE(recordOrCheckSettings(dir, other, true));
  fs::remove(dir / "settings.txt");
  const auto unrecorded = recordOrCheckSettings(dir, settings, true);
  ASSERT_FALSE(unrecorded);
  EXPECT_NE(unrecorded.error().message.find("no settings.txt"), std::string::npos) << unrecorded.error().message;
  EXPECT_FALSE(fs::exists(dir / "settings.txt"));
  fs::remove_all(dir);
}

// Two workers' queues over one file take every chunk exactly once, in order.
TEST(WorkQueue, HandsOutEveryChunkOnceThenStops) {
  const fs::path path = fs::temp_directory_path() / ("spire_work_queue_" + std::to_string(::getpid()));
  ASSERT_TRUE(WorkQueue::create(path));
  WorkQueue first(path);
  WorkQueue second(path);
  std::vector<uint64_t> taken;
  for (size_t k = 0; k < 12; ++k) {
    const auto chunk = (k % 2 == 0 ? first : second).next(11);
    ASSERT_TRUE(chunk) << chunk.error().message;
    if (!chunk->has_value()) break;
    taken.push_back(**chunk);
  }
  ASSERT_EQ(taken.size(), 11U);
  for (uint64_t k = 0; k < taken.size(); ++k) EXPECT_EQ(taken[k], k);
  const auto drained = second.next(11);
  ASSERT_TRUE(drained) << drained.error().message;
  EXPECT_FALSE(drained->has_value());

  std::ofstream(path) << "garbage\n";
  const auto corrupt = first.next(11);
  ASSERT_FALSE(corrupt);
  EXPECT_NE(corrupt.error().message.find("corrupt"), std::string::npos) << corrupt.error().message;
  fs::remove(path);
  const auto missing = first.next(11);
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().message.find("cannot use the work queue"), std::string::npos) << missing.error().message;
}

// The conventions every Spire tool shares (driver/tool_arguments.h); all
// of them hold before any device is needed.
TEST(TuneCommandLine, FollowsTheToolConventions) {
  std::ostringstream out, err;
  EXPECT_EQ(runTune({"--version"}, out, err), kExitSuccess);
  EXPECT_EQ(out.str().rfind("spire-tune ", 0), 0U) << out.str();
  const std::string scene = "examples/scenes/terrain.json";
  for (const std::vector<std::string>& args : std::vector<std::vector<std::string>>{
           {scene, "--shader", "Terrain", "-o", ""}, {scene, "--shader", "Terrain", "--no-such-flag"}, {scene}}) {
    std::ostringstream usageOut, usageErr;
    EXPECT_EQ(runTune(args, usageOut, usageErr), kExitUsageError) << usageErr.str();
    EXPECT_NE(usageErr.str().find("Run 'spire-tune --help' for usage."), std::string::npos) << usageErr.str();
  }
}

class TuneRun : public vk::testing::DeviceTest {};

std::optional<std::string> environment(const char* name) {
  const char* value = std::getenv(name);
  return value ? std::optional<std::string>(value) : std::nullopt;
}

// Data-layout selection on Terrain: the baked albedo and the mix factor it
// reads hold values in [0, 1], so they get 8 bits (one channel for the
// factor), and the error that adds against the 32-bit bake is measured and
// a few 8-bit steps at most (lavapipe also filters 8-bit textures in 8-bit
// fixed point, which a 64-texel bake magnified on screen shows); a variant
// that bakes nothing has nothing to select.
TEST_F(TuneRun, SelectsLayoutsForTextureBakesOnly) {
  SourceManager sources;
  DiagnosticList diags;
  const auto scene = scene::loadSceneFile("examples/scenes/terrain.json", sources, diags);
  ASSERT_TRUE(scene);
  engine::SceneRenderer renderer(ctx(), *scene, diags);
  TunePoint baked;
  baked.decisions = {{"mixFactor", "PrebakeTex"}, {"albedo", "PrebakeTex"}};
  const auto selection = selectLayouts(renderer, 0, baked, 64);
  ASSERT_TRUE(selection) << selection.error().message << selection.error().details;
  std::map<std::string, std::string> formats;
  for (const engine::BakeLayout& layout : selection->layouts) {
    formats[layout.component] = layout.format;
    EXPECT_FALSE(layout.unitVectors) << layout.component;
    EXPECT_EQ(selection->attributes.at(layout.component).front(),
              (std::pair<std::string, std::string>{"Format", layout.format}));
  }
  EXPECT_EQ(formats, (std::map<std::string, std::string>{{"albedo", "RGBA8"}, {"mixFactor", "R8"}}));
  ASSERT_EQ(selection->addedRmse.size(), 2U);
  for (const double added : selection->addedRmse) {
    EXPECT_GT(added, 0.0);
    EXPECT_LT(added, 5.0 / 255.0);
  }
  EXPECT_GT(selection->totalAddedRmse, 0.0);
  EXPECT_LT(selection->totalAddedRmse, 5.0 / 255.0);

  TunePoint unbaked;
  unbaked.decisions = {{"albedo", "Fragment"}};
  const auto none = selectLayouts(renderer, 0, unbaked, 64);
  ASSERT_TRUE(none) << none.error().message;
  EXPECT_TRUE(none->layouts.empty());
  EXPECT_TRUE(none->attributes.empty());
}

// The Terrain scene's four choices at a tiny size: a whole run, then a rerun
// that resumes from the CSV and measures nothing again.
TEST_F(TuneRun, WritesEveryOutputAndResumes) {
  const fs::path dir = fs::temp_directory_path() / ("spire_tune_run_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const std::vector<std::string> args{"examples/scenes/terrain.json",
                                      "--shader",
                                      "Terrain",
                                      "--components",
                                      "albedo,lighting",
                                      "--jobs",
                                      "1",
                                      "--bake-size",
                                      "64",
                                      "--resolution",
                                      "320x200",
                                      "--validation",
                                      "-o",
                                      dir.string()};
  std::ostringstream out;
  std::ostringstream err;
  const auto cacheDir = environment("MESA_SHADER_CACHE_DIR");
  const auto cacheDisable = environment("MESA_SHADER_CACHE_DISABLE");
  ASSERT_EQ(runTune(args, out, err), 0) << err.str();
  // The run's own shader cache does not outlive it, in this process either.
  EXPECT_EQ(environment("MESA_SHADER_CACHE_DIR"), cacheDir);
  EXPECT_EQ(environment("MESA_SHADER_CACHE_DISABLE"), cacheDisable);
  for (const char* file :
       {"variants.csv", "pareto.csv", "plot.png", "report.md", "report.html", "best_error_budget.decisions"}) {
    EXPECT_TRUE(fs::exists(dir / file)) << file;
  }
  const auto rows = readResults(dir / "variants.csv", {"albedo", "lighting"});
  ASSERT_TRUE(rows) << rows.error().message;
  ASSERT_EQ(rows->size(), 12U);
  // The reference (albedo in Fragment, Fragment:ggx) is a point of the space
  // and has no error.
  bool sawReference = false;
  for (const VariantResult& r : *rows) {
    if (r.placements == std::vector<std::string>{"Fragment", "Fragment:ggx"} && r.ok()) {
      sawReference = true;
      EXPECT_EQ(r.rmse, 0.0);
    }
  }
  EXPECT_TRUE(sawReference);
  EXPECT_NE(out.str().find("12 variants in"), std::string::npos) << out.str();
  // Every variant's time is a ratio to the reference's with an interval that
  // holds its median; the report shows the intervals of the front.
  for (const VariantResult& r : *rows) {
    if (!r.ok()) continue;
    EXPECT_GE(r.time.pairs, 3U) << r.index;
    EXPECT_LE(r.time.interval.low, r.time.median) << r.index;
    EXPECT_GE(r.time.interval.high, r.time.median) << r.index;
    EXPECT_GT(r.frameMs, 0.0) << r.index;
  }
  std::ifstream reportFile(dir / "report.md");
  const std::string report{std::istreambuf_iterator<char>(reportFile), std::istreambuf_iterator<char>()};
  EXPECT_NE(report.find("| 95% interval (ms) | pairs |"), std::string::npos) << report;
  // --resolution replaced the scene's 640 x 480.
  EXPECT_NE(report.find(") at 320x200, "), std::string::npos) << report;
  size_t frontImages = 0;
  for (const auto& entry : fs::directory_iterator(dir / "front")) {
    const auto image = scene::loadImage(entry.path());
    ASSERT_TRUE(image) << entry.path();
    EXPECT_EQ(image->width, 320U) << entry.path();
    EXPECT_EQ(image->height, 200U) << entry.path();
    ++frontImages;
  }
  EXPECT_GT(frontImages, 0U);
  // spirec takes the chosen variant's decision file without a warning.
  const fs::path spirecErr = dir / "spirec.err";
  const std::string spirec = std::string(SPIRE_SPIREC_EXE) + " examples/terrain.spire --shader Terrain --decisions '" +
                             (dir / "best_error_budget.decisions").string() + "' --dump-placement > /dev/null 2> '" +
                             spirecErr.string() + "'";
  EXPECT_EQ(std::system(spirec.c_str()), 0) << spirec;
  EXPECT_EQ(fs::file_size(spirecErr), 0U) << std::ifstream(spirecErr).rdbuf();

  std::ostringstream again;
  ASSERT_EQ(runTune(args, again, err), 0) << err.str();
  EXPECT_NE(again.str().find("resuming with 12 measured"), std::string::npos) << again.str();

  // Two worker processes (the spire-tune executable, one lavapipe thread
  // each) measure the same errors as the serial run.
  const fs::path parallelDir = dir / "parallel";
  // Under the asan preset the child processes unload lavapipe at exit and
  // LeakSanitizer can no longer name its frames (tests/lsan.supp), so leak
  // checking stays with this process.
  std::string command = "ASAN_OPTIONS=detect_leaks=0 " + std::string(SPIRE_TUNE_EXE);
  for (size_t i = 0; i < args.size(); ++i) {
    const bool jobs = args[i] == "--jobs" || (i > 0 && args[i - 1] == "--jobs");
    if (!jobs) command += " '" + (args[i] == dir.string() ? parallelDir.string() : args[i]) + "'";
  }
  command += " --jobs 2 > /dev/null 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  const auto parallel = readResults(parallelDir / "variants.csv", {"albedo", "lighting"});
  ASSERT_TRUE(parallel) << parallel.error().message;
  ASSERT_EQ(parallel->size(), rows->size());
  for (const char* file : {"work-queue", "shard-0.csv", "shard-1.csv", "shard-0.time"}) {
    EXPECT_FALSE(fs::exists(parallelDir / file)) << file << " outlived the run";
  }
  for (size_t i = 0; i < rows->size(); ++i) {
    EXPECT_EQ((*parallel)[i].index, (*rows)[i].index);
    EXPECT_EQ((*parallel)[i].status, (*rows)[i].status);
    EXPECT_EQ((*parallel)[i].rmse, (*rows)[i].rmse) << "variant " << (*rows)[i].index;
    EXPECT_EQ((*parallel)[i].nanPixels, (*rows)[i].nanPixels);
  }
  fs::remove_all(dir);
}

// A user's division by a swept uniform: under divisor=0 the raw variations
// go Inf and are named with that input, none of them on the front; the
// guarded reference and variations stay finite and make the front.
TEST_F(TuneRun, NamesTheInputsOfAHazardAndKeepsItOffTheFront) {
  const fs::path dir = fs::temp_directory_path() / ("spire_tune_hazard_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  std::ostringstream out;
  std::ostringstream err;
  ASSERT_EQ(runTune({"tests/data/engine/stability/guarded_divide.json", "--shader", "GuardedDivide", "--param",
                     "divisor=0:1", "--param-samples", "0", "--jobs", "1", "--validation", "-o", dir.string()},
                    out, err),
            0)
      << err.str();
  const auto rows = readResults(dir / "variants.csv", {"scaled"});
  ASSERT_TRUE(rows) << rows.error().message;
  ASSERT_EQ(rows->size(), 6U);
  for (const VariantResult& r : *rows) {
    const bool raw = r.placements[0].ends_with(":raw");
    EXPECT_EQ(r.nanPixels + r.infPixels > 0, raw) << r.placements[0];
    EXPECT_EQ(std::isinf(r.rmse), raw) << r.placements[0];
    EXPECT_EQ(r.hazardInputs, raw ? "camera view 0 divisor=0" : "") << r.placements[0];
    // The worst case is one sample's RMSE, never below the typical error
    // over every sample together.
    EXPECT_GE(r.worstRmse, r.rmse) << r.placements[0];
    EXPECT_EQ(std::isinf(r.worstRmse), raw) << r.placements[0];
  }
  const auto front = readResults(dir / "pareto.csv", {"scaled"});
  ASSERT_TRUE(front) << front.error().message;
  EXPECT_FALSE(front->empty());
  for (const VariantResult& r : *front) EXPECT_TRUE(r.placements[0].ends_with(":guarded")) << r.placements[0];
  EXPECT_NE(err.str().find("first under camera view 0 divisor=0"), std::string::npos) << err.str();
  fs::remove_all(dir);
}

// A hazard that only a texture's extremes reach: the scene's mask is 0.5
// everywhere and no variant goes non-finite; sweeping the texture over
// solid 0 and solid 1 finds the raw divisions and names the input.
TEST_F(TuneRun, ATextureDrivenHazardIsFoundBySweepingTheTexture) {
  const fs::path dir = fs::temp_directory_path() / ("spire_tune_texture_" + std::to_string(::getpid()));
  for (const bool sweep : {false, true}) {
    fs::remove_all(dir);
    std::vector<std::string> args{"tests/data/engine/stability/texture_divide.json",
                                  "--shader",
                                  "TextureDivide",
                                  "--components",
                                  "scaled",
                                  "--jobs",
                                  "1",
                                  "--max-frames",
                                  "3",
                                  "--validation",
                                  "-o",
                                  dir.string()};
    if (sweep) args.insert(args.end(), {"--param", "maskMap=0:1", "--param-samples", "0"});
    std::ostringstream out;
    std::ostringstream err;
    ASSERT_EQ(runTune(args, out, err), 0) << err.str();
    const auto rows = readResults(dir / "variants.csv", {"scaled"});
    ASSERT_TRUE(rows) << rows.error().message;
    ASSERT_EQ(rows->size(), 6U);
    for (const VariantResult& r : *rows) {
      const bool hazard = sweep && r.placements[0].ends_with(":raw");
      EXPECT_EQ(r.nanPixels + r.infPixels > 0, hazard) << r.placements[0] << (sweep ? " swept" : "");
      EXPECT_EQ(r.hazardInputs, hazard ? "camera view 0 maskMap=0,0,0,0" : "") << r.placements[0];
    }
  }
  fs::remove_all(dir);
}

// A reference with NaN or Inf pixels would make every variant's error
// infinite, clean ones included: the run stops before measuring, naming the
// reference and the inputs, and writes no results. With --extremes too,
// since the reference is non-finite at the scene's own values (one only
// non-finite at an extreme is tests/tune/extremes_test.cpp's).
TEST_F(TuneRun, AHazardousReferenceStopsTheRun) {
  const fs::path dir = fs::temp_directory_path() / ("spire_tune_bad_reference_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  for (const char* mode : {"1", "2", "extremes"}) {
    std::vector<std::string> args{
        "tests/data/engine/stability/user_divide.json", "--shader",     "UserDivide", "--jobs",
        mode == std::string_view("2") ? "2" : "1",      "--validation", "-o",         dir.string()};
    if (mode == std::string_view("extremes")) args.emplace_back("--extremes");
    std::ostringstream out;
    std::ostringstream err;
    EXPECT_EQ(runTune(args, out, err, SPIRE_TUNE_EXE), kExitInputError);
    EXPECT_NE(err.str().find("the reference (tests/data/engine/stability/user_divide_fragment.decisions) has 289 NaN "
                             "or Inf pixels under camera view 0: every variant's error against it would be infinite"),
              std::string::npos)
        << err.str();
    EXPECT_NE(err.str().find("--reference DECISIONS"), std::string::npos);
    // The instrumented reference names the component and its input.
    EXPECT_NE(err.str().find(
                  "There, scaled (Fragment) went Inf in 289 px at `color / divisor` (user_divide.spire:18:19); color = "
                  "(0.5, 0.5, 0.5, 1), divisor = 0 "
                  "there [instance 0 (UserDivide), first at pixel"),
              std::string::npos)
        << err.str();
    EXPECT_FALSE(fs::exists(dir / "variants.csv"));
    EXPECT_FALSE(fs::exists(dir / "shard-0.csv")) << "no worker should have started";
  }
  fs::remove_all(dir);
}

// The run's shader cache lives in the temporary directory while the run
// lasts and is gone after it; "off" and "inherit" leave the environment as
// they found it; anything else is a usage error.
TEST_F(TuneRun, ShaderCacheModesCleanUpAfterThemselves) {
  const fs::path dir = fs::temp_directory_path() / ("spire_tune_cache_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const fs::path temp = dir / "tmp";
  fs::create_directories(temp);
  const auto tmpdir = environment("TMPDIR");
  ::setenv("TMPDIR", temp.c_str(), 1);
  const auto cacheDir = environment("MESA_SHADER_CACHE_DIR");
  const auto cacheDisable = environment("MESA_SHADER_CACHE_DISABLE");
  for (const char* mode : {"run", "off", "inherit"}) {
    std::ostringstream out;
    std::ostringstream err;
    EXPECT_EQ(runTune({"tests/data/engine/stability/guarded_divide.json", "--shader", "GuardedDivide", "--shader-cache",
                       mode, "--validation", "-o", (dir / mode).string()},
                      out, err),
              0)
        << mode << ": " << err.str();
    EXPECT_TRUE(fs::is_empty(temp)) << mode << " left " << fs::directory_iterator(temp)->path();
    EXPECT_EQ(environment("MESA_SHADER_CACHE_DIR"), cacheDir) << mode;
    EXPECT_EQ(environment("MESA_SHADER_CACHE_DISABLE"), cacheDisable) << mode;
  }
  std::ostringstream out;
  std::ostringstream err;
  EXPECT_EQ(runTune({"tests/data/engine/stability/guarded_divide.json", "--shader", "GuardedDivide", "--shader-cache",
                     "sometimes", "-o", (dir / "bad").string()},
                    out, err),
            2);
  EXPECT_NE(err.str().find("--shader-cache"), std::string::npos) << err.str();
  if (tmpdir)
    ::setenv("TMPDIR", tmpdir->c_str(), 1);
  else
    ::unsetenv("TMPDIR");
  fs::remove_all(dir);
}

// The N of each "tune: N/M variants" progress line (stderr is no terminal
// in tests, so every change is a line).
std::vector<size_t> progressCounts(const std::string& text, size_t total) {
  std::vector<size_t> counts;
  const std::string suffix = fmt::format("/{} variants", total);
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("tune: ", 0) != 0 || line.find(suffix) == std::string::npos) continue;
    counts.push_back(std::stoul(line.substr(6)));
  }
  return counts;
}

std::string readText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The first `rows` rows of a journal, as an interrupted run leaves them.
void keepRows(const fs::path& from, const fs::path& to, size_t rows) {
  std::istringstream in(readText(from));
  std::string text;
  std::string line;
  for (size_t i = 0; i <= rows && std::getline(in, line); ++i) text += line + "\n";
  fs::remove(from);
  std::ofstream(to, std::ios::binary) << text;
}

// --max-frames 3: these runs check rows and counts, not timing, so they
// race nothing.
const std::vector<std::string> kSixVariants{"examples/scenes/terrain.json",
                                            "--shader",
                                            "Terrain",
                                            "--components",
                                            "albedo,normal",
                                            "--bake-size",
                                            "64",
                                            "--max-frames",
                                            "3"};

// A resumed run counts the rows an earlier run left once, in process and
// with workers, whose shards already hold them.
TEST_F(TuneRun, ResumeCountsEachVariantOnce) {
  const fs::path dir = fs::temp_directory_path() / ("spire_tune_resume_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  std::vector<std::string> args = kSixVariants;
  args.insert(args.end(), {"--jobs", "1", "-o", dir.string()});
  std::ostringstream out, err;
  ASSERT_EQ(runTune(args, out, err), 0) << err.str();
  EXPECT_EQ(progressCounts(err.str(), 6), (std::vector<size_t>{1, 2, 3, 4, 5, 6}));

  keepRows(dir / "variants.csv", dir / "variants.csv", 2);
  std::ostringstream resumedOut, resumed;
  ASSERT_EQ(runTune(args, resumedOut, resumed), 0) << resumed.str();
  EXPECT_EQ(progressCounts(resumed.str(), 6), (std::vector<size_t>{3, 4, 5, 6})) << resumed.str();

  keepRows(dir / "variants.csv", dir / "shard-0.csv", 2);
  const fs::path log = dir / "workers.log";
  std::string command = "ASAN_OPTIONS=detect_leaks=0 " + std::string(SPIRE_TUNE_EXE);
  for (const std::string& a : kSixVariants) command += " '" + a + "'";
  command += " --jobs 2 -o '" + dir.string() + "' > /dev/null 2> '" + log.string() + "'";
  ASSERT_EQ(std::system(command.c_str()), 0) << command << "\n" << readText(log);
  const std::vector<size_t> counts = progressCounts(readText(log), 6);
  ASSERT_FALSE(counts.empty()) << readText(log);
  EXPECT_EQ(counts.front(), 2U) << readText(log);
  EXPECT_EQ(counts.back(), 6U);
  EXPECT_TRUE(std::is_sorted(counts.begin(), counts.end())) << readText(log);

  // Rows measured at one image size are not resumed at another: the run
  // stops before it measures, and the journal is left as it was.
  const std::string journal = readText(dir / "variants.csv");
  args.insert(args.end(), {"--resolution", "64x48"});
  std::ostringstream otherOut, other;
  EXPECT_EQ(runTune(args, otherOut, other), kExitInputError);
  EXPECT_NE(other.str().find("resolution: '640x480' then, '64x48' now"), std::string::npos) << other.str();
  EXPECT_EQ(readText(dir / "variants.csv"), journal);
  fs::remove_all(dir);
}

// The rows depend on the files as they were: a scene edited between two
// runs is a difference like an option, named by its path.
TEST_F(TuneRun, AnEditedSceneIsNotResumed) {
  const fs::path dir = fs::temp_directory_path() / ("spire_tune_edited_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::string text = readText("examples/scenes/terrain.json");
  const std::string examples = fs::absolute("examples").string() + "/";
  for (size_t at = text.find("\"../"); at != std::string::npos; at = text.find("\"../", at)) {
    text.replace(at + 1, 3, examples);
  }
  const fs::path scene = dir / "terrain.json";
  std::ofstream(scene, std::ios::binary) << text;
  const std::vector<std::string> args{scene.string(),
                                      "--shader",
                                      "Terrain",
                                      "--components",
                                      "albedo",
                                      "--bake-size",
                                      "64",
                                      "--max-frames",
                                      "3",
                                      "--jobs",
                                      "1",
                                      "--resolution",
                                      "64x48",
                                      "-o",
                                      (dir / "run").string()};
  std::ostringstream out, err;
  ASSERT_EQ(runTune(args, out, err), 0) << err.str();
  std::ofstream(scene, std::ios::binary | std::ios::app) << "\n";  // the same scene, other bytes
  std::ostringstream editedOut, edited;
  EXPECT_EQ(runTune(args, editedOut, edited), kExitInputError);
  EXPECT_NE(edited.str().find("(source " + fs::weakly_canonical(scene).string() + ": '"), std::string::npos)
      << edited.str();
  fs::remove_all(dir);
}

// A scene in `dir` drawing collapse.spire's shader on a 2x2 quad read from a
// .gltf whose vertices are in a separate quad.bin; returns the scene's path.
fs::path writeGltfQuadScene(const fs::path& dir) {
  const std::vector<float> positions{-1, 0, -1, 1, 0, -1, 1, 0, 1, -1, 0, 1};
  const std::vector<float> normals{0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0};
  const std::vector<float> uvs{0, 0, 1, 0, 1, 1, 0, 1};
  const std::vector<uint16_t> indices{0, 2, 1, 0, 3, 2};
  std::ofstream bin(dir / "quad.bin", std::ios::binary);
  const auto put = [&](const auto& values) {
    bin.write(reinterpret_cast<const char*>(values.data()), std::streamsize(values.size() * sizeof(values[0])));
  };
  put(positions);
  put(normals);
  put(uvs);
  put(indices);
  bin.close();
  std::ofstream(dir / "quad.gltf") << R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
  "nodes": [{"mesh": 0}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3}]}],
  "buffers": [{"uri": "quad.bin", "byteLength": 140}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 48},
                  {"buffer": 0, "byteOffset": 96, "byteLength": 32}, {"buffer": 0, "byteOffset": 128, "byteLength": 12}],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-1, 0, -1], "max": [1, 0, 1]},
    {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
    {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"},
    {"bufferView": 3, "componentType": 5123, "count": 6, "type": "SCALAR"}]})";
  const fs::path shader = fs::absolute("tests/data/engine/stability/collapse.spire");
  std::ofstream(dir / "quad.json") << fmt::format(R"({{
  "resolution": [17, 17], "frames": 1, "warmupFrames": 1,
  "camera": {{"fovY": 45, "up": [0, 0, -1], "views": [{{"position": [0, 2, 0], "target": [0, 0, 0]}}]}},
  "meshes": {{"quad": {{"type": "gltf", "file": "quad.gltf"}}}},
  "instances": [{{"mesh": "quad", "source": "{}", "shader": "Collapse", "material": {{"color": [0.5, 0.5, 0.5, 1.0]}}}}]
}})",
                                                  shader.string());
  return dir / "quad.json";
}

// The same for a file the scene reads rather than is: a glTF mesh's buffer
// edited between two runs (the scene file and the shader unchanged).
TEST_F(TuneRun, AnEditedMeshBufferIsNotResumed) {
  const fs::path dir = fs::temp_directory_path() / ("spire_tune_buffer_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path scene = writeGltfQuadScene(dir);
  const std::vector<std::string> args{scene.string(),        "--shader", "Collapse", "--jobs", "1", "-o",
                                      (dir / "run").string()};
  std::ostringstream out, err;
  ASSERT_EQ(runTune(args, out, err), 0) << err.str();
  EXPECT_NE(readText(dir / "run" / "settings.txt").find("quad.bin: "), std::string::npos);
  std::ofstream(dir / "quad.bin", std::ios::binary | std::ios::app) << "more";
  std::ostringstream editedOut, edited;
  EXPECT_EQ(runTune(args, editedOut, edited), kExitInputError);
  EXPECT_NE(edited.str().find("(source " + fs::weakly_canonical(dir / "quad.bin").string() + ": '"), std::string::npos)
      << edited.str();
  fs::remove_all(dir);
}

// SPIRE_TUNE_EXE with `args`, two workers and `-o out` in a process of its
// own, its stderr into `log`; -1 when it cannot start.
pid_t spawnTuner(const std::vector<std::string>& tuneArgs, const fs::path& out, const fs::path& log) {
  std::vector<std::string> args{SPIRE_TUNE_EXE};
  args.insert(args.end(), tuneArgs.begin(), tuneArgs.end());
  args.insert(args.end(), {"--jobs", "2", "-o", out.string()});
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 2, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  // As for the workers above: under the asan preset leak checking stays
  // with this process (tests/lsan.supp), so the exit status is the tuner's.
  std::vector<std::string> environment{"ASAN_OPTIONS=detect_leaks=0"};
  for (char** e = environ; *e; ++e) {
    if (!std::string_view(*e).starts_with("ASAN_OPTIONS=")) environment.emplace_back(*e);
  }
  std::vector<char*> envp;
  for (std::string& e : environment) envp.push_back(e.data());
  envp.push_back(nullptr);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&actions);
  return spawned == 0 ? pid : -1;
}

// Rows the workers of a run into `out` have written to their shards so far.
size_t shardRows(const fs::path& out) {
  size_t n = 0;
  for (int k = 0; k < 2; ++k) {
    std::istringstream in(readText(out / fmt::format("shard-{}.csv", k)));
    for (std::string line; std::getline(in, line);) n += line.rfind("index", 0) == 0 ? 0 : 1;
  }
  return n;
}

// The processes whose parent is `parent` (from /proc/PID/stat, whose fourth
// field is the parent's id; the command name before it is in parentheses
// and may hold spaces).
std::vector<pid_t> childrenOf(pid_t parent) {
  std::vector<pid_t> children;
  for (const auto& entry : fs::directory_iterator("/proc")) {
    const std::string name = entry.path().filename().string();
    if (name.empty() || !std::all_of(name.begin(), name.end(), [](char c) { return c >= '0' && c <= '9'; })) continue;
    const std::string stat = readText(entry.path() / "stat");
    const size_t close = stat.rfind(')');
    if (close == std::string::npos) continue;
    std::istringstream fields(stat.substr(close + 1));
    std::string state;
    pid_t ppid = 0;
    if (fields >> state >> ppid && ppid == parent) children.push_back(static_cast<pid_t>(std::stol(name)));
  }
  return children;
}

// SIGINT to the tuner alone, mid-run: its workers stop with it (nothing
// writes into the directory afterwards), it says what it kept and exits
// 130; the same command then resumes, and the rows are those of a run that
// was never interrupted. While a run holds the directory, a second is
// refused.
TEST_F(TuneRun, ASignalStopsTheWorkersAndTheRunResumes) {
  const fs::path dir = fs::temp_directory_path() / ("spire_tune_signal_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path log = dir / "run.log";
  const pid_t pid = spawnTuner(kSixVariants, dir / "run", log);
  ASSERT_GT(pid, 0);
  const auto rows = [&] { return shardRows(dir / "run"); };
  for (int wait = 0; wait < 1200 && rows() == 0; ++wait) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  ASSERT_GT(rows(), 0U) << readText(log);
  {
    std::ostringstream out, err;
    std::vector<std::string> second = kSixVariants;
    second.insert(second.end(), {"-o", (dir / "run").string()});
    EXPECT_EQ(runTune(second, out, err), kExitInputError);
    EXPECT_NE(err.str().find("is in use by another spire-tune run"), std::string::npos) << err.str();
  }
  ASSERT_EQ(::kill(pid, SIGINT), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status)) << readText(log);
  EXPECT_EQ(WEXITSTATUS(status), kExitInterrupted) << readText(log);
  EXPECT_NE(readText(log).find("spire-tune: interrupted: "), std::string::npos) << readText(log);
  const size_t kept = rows();
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  EXPECT_EQ(rows(), kept) << "a worker outlived the tuner";
  EXPECT_FALSE(fs::exists(dir / "run" / "variants.csv"));

  std::vector<std::string> serial = kSixVariants;
  serial.insert(serial.end(), {"--jobs", "1", "-o", (dir / "run").string()});
  std::ostringstream out, err;
  ASSERT_EQ(runTune(serial, out, err), 0) << err.str();
  serial.back() = (dir / "whole").string();
  ASSERT_EQ(runTune(serial, out, err), 0) << err.str();
  const auto resumed = readResults(dir / "run" / "variants.csv", {"albedo", "normal"});
  const auto whole = readResults(dir / "whole" / "variants.csv", {"albedo", "normal"});
  ASSERT_TRUE(resumed && whole);
  ASSERT_EQ(resumed->size(), 6U);
  ASSERT_EQ(whole->size(), 6U);
  for (size_t i = 0; i < whole->size(); ++i) {
    EXPECT_EQ((*resumed)[i].index, (*whole)[i].index);
    EXPECT_EQ((*resumed)[i].status, (*whole)[i].status);
    EXPECT_EQ((*resumed)[i].rmse, (*whole)[i].rmse) << "variant " << (*whole)[i].index;
  }
  fs::remove_all(dir);
}

// A worker that dies without a word (lavapipe has crashed in one, rarely and
// not again on the same variant; here SIGKILL) is named with the signal that
// ended it, and fresh workers measure what is left: the run ends with every
// variant measured, as an uninterrupted one.
TEST_F(TuneRun, AWorkerThatDiesIsNamedAndReplaced) {
  const fs::path dir = fs::temp_directory_path() / ("spire_tune_crash_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path log = dir / "run.log";
  const pid_t pid = spawnTuner(kSixVariants, dir / "run", log);
  ASSERT_GT(pid, 0);
  std::vector<pid_t> workers;
  // Killed as soon as both run: it cannot have finished yet.
  for (int wait = 0; wait < 1200 && workers.size() < 2; ++wait) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    workers = childrenOf(pid);
  }
  ASSERT_EQ(workers.size(), 2U) << readText(log);
  ASSERT_EQ(::kill(workers.front(), SIGKILL), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  const std::string text = readText(log);
  ASSERT_TRUE(WIFEXITED(status)) << text;
  EXPECT_EQ(WEXITSTATUS(status), 0) << text;
  EXPECT_NE(text.find(fmt::format("was killed by signal {} ({})", SIGKILL, ::strsignal(SIGKILL))), std::string::npos)
      << text;
  EXPECT_NE(text.find("measuring the variants left with fresh workers"), std::string::npos) << text;
  const auto rows = readResults(dir / "run" / "variants.csv", {"albedo", "normal"});
  ASSERT_TRUE(rows) << text;
  ASSERT_EQ(rows->size(), 6U);
  for (size_t i = 0; i < rows->size(); ++i) EXPECT_EQ((*rows)[i].index, i);
  for (const auto& entry : fs::directory_iterator(dir / "run")) {
    EXPECT_FALSE(entry.path().filename().string().starts_with("shard-")) << entry.path() << " left behind";
  }
  fs::remove_all(dir);
}

// A variant that collapses the mesh (collapse.spire's position per object)
// is off the trade: its status says it is degenerate, it is not on the
// front whatever its time, and the console and the report both name it.
TEST_F(TuneRun, ADegenerateVariantIsListedAndKeptOffTheFront) {
  const fs::path dir = fs::temp_directory_path() / ("spire_tune_collapse_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  std::ostringstream out;
  std::ostringstream err;
  ASSERT_EQ(runTune({"tests/data/engine/stability/collapse.json", "--shader", "Collapse", "--jobs", "1", "--validation",
                     "-o", dir.string()},
                    out, err),
            0)
      << err.str();
  const auto rows = readResults(dir / "variants.csv", {"position"});
  ASSERT_TRUE(rows) << rows.error().message;
  ASSERT_EQ(rows->size(), 3U);
  std::optional<uint64_t> collapsed;
  for (const VariantResult& r : *rows) {
    const bool perObject = r.placements.front() == "PrebakeUniform";
    EXPECT_EQ(r.status.rfind("degenerate: covers 0% of the pixels", 0) == 0, perObject) << r.status;
    if (perObject) collapsed = r.index;
  }
  ASSERT_TRUE(collapsed);
  const auto front = readResults(dir / "pareto.csv", {"position"});
  ASSERT_TRUE(front);
  for (const VariantResult& r : *front) EXPECT_NE(r.index, *collapsed);
  EXPECT_NE(err.str().find(fmt::format("spire-tune: warning: variant {} (position=PrebakeUniform) is off the trade: "
                                       "degenerate: covers 0%",
                                       *collapsed)),
            std::string::npos)
      << err.str();
  EXPECT_NE(out.str().find("1 off the trade (0 infeasible, 1 failed or degenerate)"), std::string::npos) << out.str();
  const std::string report = readText(dir / "report.md");
  EXPECT_NE(report.find("## Variants off the trade"), std::string::npos) << report;
  EXPECT_NE(report.find(fmt::format("| {} | position=PrebakeUniform | degenerate: covers 0%", *collapsed)),
            std::string::npos)
      << report;
  fs::remove_all(dir);
}

// The per-level frame times spire-tune --lod-policy printed, by member.
std::map<std::string, double> printedCosts(const std::string& out) {
  std::map<std::string, double> costs;
  const std::string label = "with every object at one level:";
  const size_t begin = out.find(label) + label.size();
  std::istringstream line(out.substr(begin, out.find('\n', begin) - begin));
  std::string member, unit;
  double ms = 0.0;
  while (line >> member >> ms >> unit) costs[member] = ms;
  return costs;
}

// spire-tune --lod-policy on a small level-of-detail scene: the policy it
// writes reads back and holds the scene's levels in order; with nothing
// tolerated it keeps full quality everywhere, with everything tolerated and
// no switch penalty it ends on the level measured cheapest.
TEST_F(TuneRun, DerivesALevelOfDetailPolicyFromMeasurements) {
  const fs::path dir = fs::temp_directory_path() / ("spire_tune_lod_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  spire::testing::LodTestScene sceneOptions;
  sceneOptions.policy = "policy.json";
  std::ofstream(dir / "scene.json") << spire::testing::lodTestSceneJson(sceneOptions);
  std::ofstream(dir / "policy.json") << spire::testing::lodTestPolicyJson();
  const fs::path tuned = dir / "tuned.json";
  const auto tune = [&](const std::vector<std::string>& extra, std::string& printed) {
    std::vector<std::string> args{(dir / "scene.json").string(),
                                  "--lod-policy",
                                  tuned.string(),
                                  "--distances",
                                  "1,3,9",
                                  "--frames",
                                  "3",
                                  "--validation"};
    args.insert(args.end(), extra.begin(), extra.end());
    std::ostringstream out, err;
    const int status = runTune(args, out, err);
    printed = out.str() + err.str();
    return status;
  };
  const auto readBack = [&]() {
    SourceManager sources;
    DiagnosticList diags;
    return lod::loadLodPolicy(tuned, sources, diags);
  };

  std::string strict;
  ASSERT_EQ(tune({"--max-error", "1e-6"}, strict), 0) << strict;
  for (const char* row : {"| 1 | 0.0000 |", "| 3 |", "| 9 |", "LodMQ RMSE", "LodLQ RMSE"}) {
    EXPECT_NE(strict.find(row), std::string::npos) << row << " in\n" << strict;
  }
  auto policy = readBack();
  ASSERT_TRUE(policy) << strict;
  ASSERT_EQ(policy->levels.size(), 1U) << strict;
  EXPECT_EQ(policy->levels[0].member, "LodHQ");
  EXPECT_FLOAT_EQ(policy->hysteresis, 0.1F);  // kept from the scene's policy
  EXPECT_EQ(policy->transitionFrames, 4U);

  std::string lax;
  ASSERT_EQ(tune({"--max-error", "10", "--switch-penalty", "0"}, lax), 0) << lax;
  policy = readBack();
  ASSERT_TRUE(policy) << lax;
  const std::vector<std::string> members{"LodHQ", "LodMQ", "LodLQ"};
  size_t next = 0;
  for (const lod::LodLevel& level : policy->levels) {
    const auto at = std::find(members.begin() + static_cast<std::ptrdiff_t>(next), members.end(), level.member);
    ASSERT_NE(at, members.end()) << level.member << " out of order:\n" << lax;
    next = static_cast<size_t>(at - members.begin()) + 1;
  }
  EXPECT_EQ(policy->levels.front().member, "LodHQ") << "nothing is tolerated at the nearest distance";
  const std::map<std::string, double> costs = printedCosts(lax);
  ASSERT_EQ(costs.size(), 3U) << lax;
  std::vector<std::pair<double, std::string>> byCost;
  for (const auto& [member, ms] : costs) byCost.emplace_back(ms, member);
  std::sort(byCost.begin(), byCost.end());
  if (byCost[0].first < byCost[1].first) {
    EXPECT_EQ(policy->levels.back().member, byCost[0].second) << lax;
  }
  if (policy->levels.size() > 1) {
    EXPECT_FLOAT_EQ(policy->levels[0].until, 3.34F);  // 3 / (1 - hysteresis), rounded up
  }
  fs::remove_all(dir);
}

TEST_F(TuneRun, LevelOfDetailPolicyInputErrorsWriteNothing) {
  const fs::path dir = fs::temp_directory_path() / ("spire_tune_lod_bad_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string tuned = (dir / "tuned.json").string();
  const std::string lodScene = (dir / "scene.json").string();
  std::ofstream(lodScene) << spire::testing::lodTestSceneJson();  // its policy file is missing
  struct Case {
    std::vector<std::string> args;
    int status;
    const char* message;
  };
  const std::vector<Case> cases{
      {{lodScene, "--lod-policy", tuned, "--distances", "4,2"}, kExitUsageError, "--distances must increase"},
      {{lodScene, "--lod-policy", tuned, "--distances", "4"}, kExitUsageError, "at least two distances"},
      {{lodScene, "--lod-policy", tuned, "--shader", "Rock"}, kExitUsageError, "excludes"},
      {{lodScene, "--lod-policy", tuned}, kExitInputError, "cannot open level-of-detail policy"},
      {{"examples/scenes/terrain.json", "--lod-policy", tuned}, kExitInputError, "the scene has no 'lod'"},
  };
  for (const Case& c : cases) {
    std::ostringstream out, err;
    EXPECT_EQ(runTune(c.args, out, err), c.status) << c.message << "\n" << err.str();
    EXPECT_NE(err.str().find(c.message), std::string::npos) << err.str();
    EXPECT_FALSE(fs::exists(tuned)) << c.message;
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace spire::tune
