// The tuner's table of measured variants, as CSV: one row per variant with
// its decisions (a column per explored component), error, time, hazards and
// kernel hashes. It is also the tuner's journal: rows are appended as
// variants finish, and an interrupted run resumes by reading them back.
#pragma once

#include <cstdint>
#include <filesystem>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "support/expected.h"
#include "tune/paired_timing.h"

namespace spire::tune {

struct VariantResult {
  uint64_t index = 0;
  std::vector<std::string> placements;  // one per explored component, in axis order
  std::string status = "ok";            // "ok", "infeasible", "failed: why" or "degenerate: why"
  double frameMs = 0.0;                 // time.median times the reference's median frame time in this run
  double firstFrameMs = 0.0;            // host time of the first frame (shader compilation)
  double prebakeMs = 0.0;               // bakes this variant ran (reused ones count 0)
  double rmse = 0.0;                    // typical: over every camera view under every parameter sample together
  double worstRmse = 0.0;               // worst case: the largest RMSE under one parameter sample
  double psnr = std::numeric_limits<double>::infinity();
  double maxError = 0.0;
  uint64_t nanPixels = 0;
  uint64_t infPixels = 0;
  std::optional<uint64_t> sameAs;  // measured once: the variant whose kernels are identical
  std::string kernels;             // "World=hash;..." of every kernel
  // The inputs under which NaN/Inf pixels first appeared: "camera view V"
  // plus the parameter sample's values ("roughness=0 shininess=1"); empty
  // without hazards.
  std::string hazardInputs;
  // What the instrumented variant found there (tool/hazard_diagnosis.h): the
  // components that went non-finite first, one per line.
  std::vector<std::string> hazardCauses;
  // In this run only: the parameter sample and camera view of hazardInputs.
  std::optional<std::pair<size_t, size_t>> hazardSample;
  // Every parameter sample that has NaN or Inf pixels, with the first camera
  // view that has them: the stability table diagnoses them after the run.
  std::vector<std::pair<size_t, size_t>> hazardSamples;
  // The variant's frame time over the reference's, frame for frame (see
  // tune/paired_timing.h).
  TimeRatio time;

  bool ok() const { return status == "ok"; }
};

// `field` as one CSV field: quoted when it holds a comma, a quote or a
// newline (a newline becomes a space).
std::string quoteCsv(const std::string& field);

std::string csvHeader(const std::vector<std::string>& components);
std::string csvRow(const VariantResult& result);

// The explored components a table at `path` was written with, from its
// header, so a reader that did not run the tuner (spire-explore --tune-dir)
// can read its rows; an error when the file is missing or not such a table.
Expected<std::vector<std::string>, Failure> readComponents(const std::filesystem::path& path);

// Reads rows written with the same components; rows of another run (a
// different header) are an error, as is a malformed row.
Expected<std::vector<VariantResult>, Failure> readResults(const std::filesystem::path& path,
                                                          const std::vector<std::string>& components);

}  // namespace spire::tune
