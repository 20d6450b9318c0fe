// Runs the generator's property over a range of seeds: for each seed a
// program (program_generator.h), its default variant and random decision
// maps (decision_generator.h), each checked by ProgramChecker. Shared by the
// ctest property test and bench/generate-and-check.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "gen/variant_checker.h"

namespace spire::testgen {

// Everything needed to reproduce one failing variant.
struct Failure {
  uint32_t seed = 0;
  std::string program;
  std::string decisions;
  VariantReport report;
  std::string format() const;
};

struct CampaignStats {
  uint64_t programs = 0;
  uint64_t variants = 0;
  std::map<Verdict, uint64_t> verdicts;
  std::map<std::string, uint64_t> refusals;  // first error code of each refusal
  // Failures by class (failureClass()), and the first example of each.
  std::map<std::string, uint64_t> failureClasses;
  std::vector<Failure> failures;
  static constexpr size_t kKeptFailures = 50;

  uint64_t count(Verdict v) const;
  void merge(const CampaignStats& other);
  // `R order-dependent routes, L locked kernels not shared` (before the summary line)
  std::string routesAndLocksLine() const;
  // `N variants, I internal errors, K invalid kernels, M interface mismatches`
  std::string summaryLine() const;
  // One line per refusal code: `refused E6001: 123`.
  std::string refusalTable() const;
};

// The program with the lines that start with `import` in reverse order: it
// must mean the same (issue 12, "Routing": declaration order never changes
// what a value means).
std::string withImportsReversed(const std::string& program);

// The front end's verdict on `program`, and the checks of each variant of
// `decisions`, each compared with `reordered` (the same program compiled
// from withImportsReversed()): a variant whose placement or routes change,
// or that only one order refuses, is an OrderDependentRoute failure.
VariantReport checkFrontEnd(const ProgramChecker& checker, const ProgramChecker& reordered);
// Shaders derived from one base that finalizes W must also get the same W
// kernel (issue 12, "Locked worlds"): where they differ, every shader after
// the first is a LockedKernelNotShared failure.
std::vector<VariantReport> checkVariants(ProgramChecker& checker, ProgramChecker& reordered,
                                         const std::string& decisions);

// A failure's verdict and the first line of what went wrong, with numbers
// and generated names blurred, so that one bug gives one class.
std::string failureClass(const VariantReport& report);

// The program of `seed`, its default variant and `decisionMaps` random maps,
// each checked in both import orders.
CampaignStats runSeed(uint32_t seed, int decisionMaps);

}  // namespace spire::testgen
