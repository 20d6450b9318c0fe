#include "gen/campaign.h"

#include <fmt/format.h>

#include <algorithm>

#include "gen/decision_generator.h"
#include "gen/program_generator.h"

namespace spire::testgen {

std::string Failure::format() const {
  return fmt::format("seed {}: {} in shader '{}'\n{}\n--- program (generated.spire) ---\n{}\n--- decisions ---\n{}",
                     seed, verdictName(report.verdict), report.shader, report.detail, program,
                     decisions.empty() ? "(none: the default variant)\n" : decisions);
}

uint64_t CampaignStats::count(Verdict v) const {
  const auto it = verdicts.find(v);
  return it == verdicts.end() ? 0 : it->second;
}

void CampaignStats::merge(const CampaignStats& other) {
  programs += other.programs;
  variants += other.variants;
  for (const auto& [v, n] : other.verdicts) verdicts[v] += n;
  for (const auto& [code, n] : other.refusals) refusals[code] += n;
  for (const Failure& f : other.failures) {
    if (!failureClasses.count(failureClass(f.report)) && failures.size() < kKeptFailures) failures.push_back(f);
  }
  for (const auto& [c, n] : other.failureClasses) failureClasses[c] += n;
}

std::string CampaignStats::summaryLine() const {
  return fmt::format("{} variants, {} internal errors, {} invalid kernels, {} interface mismatches", variants,
                     count(Verdict::InternalError), count(Verdict::InvalidKernel), count(Verdict::InterfaceMismatch));
}

std::string CampaignStats::routesAndLocksLine() const {
  return fmt::format("{} order-dependent routes, {} locked kernels not shared", count(Verdict::OrderDependentRoute),
                     count(Verdict::LockedKernelNotShared));
}

std::string CampaignStats::refusalTable() const {
  std::string out;
  for (const auto& [code, n] : refusals) out += fmt::format("refused {}: {}\n", code, n);
  return out;
}

std::string failureClass(const VariantReport& report) {
  std::string line = report.detail.substr(0, report.detail.find('\n'));
  std::string blurred;
  for (size_t i = 0; i < line.size() && blurred.size() < 160; ++i) {
    const char c = line[i];
    const bool digit = c >= '0' && c <= '9';
    if (digit && !blurred.empty() && blurred.back() == '#') continue;
    blurred += digit ? '#' : c;
  }
  return fmt::format("{}: {}", verdictName(report.verdict), blurred);
}

namespace {

void record(CampaignStats& stats, const GeneratedProgram& program, const std::string& decisions,
            const VariantReport& r) {
  ++stats.variants;
  ++stats.verdicts[r.verdict];
  if (r.verdict == Verdict::Refused) ++stats.refusals[r.codes.empty() ? "?" : r.codes.front()];
  if (!r.failed()) return;
  const std::string c = failureClass(r);
  if (!stats.failureClasses.count(c) && stats.failures.size() < CampaignStats::kKeptFailures) {
    stats.failures.push_back({program.seed, program.text, decisions, r});
  }
  ++stats.failureClasses[c];
}

// One decision file for every concrete shader of the program.
std::string decisionMap(const ProgramChecker& checker, RandomSource& rng) {
  std::string text;
  for (const std::string& shader : checker.shaders()) text += generateDecisions(checker.choices(shader), rng);
  return text;
}

// Lines of `a` missing from `b`, each prefixed with `mark`.
std::string missingLines(const std::string& a, const std::string& b, const char* mark) {
  std::string out;
  for (size_t start = 0; start < a.size();) {
    const size_t end = a.find('\n', start);
    const std::string line = a.substr(start, end - start);
    if (b.find(line + "\n") == std::string::npos) out += fmt::format("{} {}\n", mark, line);
    start = end == std::string::npos ? a.size() : end + 1;
  }
  return out;
}

// Marks `mine` as order-dependent when the reordered program disagrees.
void compareWithReordered(VariantReport& mine, const VariantReport& theirs) {
  const bool accepted = mine.verdict == Verdict::Accepted, theirsAccepted = theirs.verdict == Verdict::Accepted;
  if (mine.verdict != Verdict::Refused && !accepted) return;  // already a failure
  if (!accepted && !theirsAccepted) return;
  if (accepted && theirsAccepted && mine.routes == theirs.routes) return;
  std::string detail = "the program with its imports declared in reverse order ";
  if (accepted != theirsAccepted) {
    detail += fmt::format("is {} while this order is {}\n{}", verdictName(theirs.verdict), verdictName(mine.verdict),
                          accepted ? theirs.detail : mine.detail);
  } else {
    detail += "routes differently (-: as declared, +: reversed)\n" + missingLines(mine.routes, theirs.routes, "-") +
              missingLines(theirs.routes, mine.routes, "+");
  }
  mine = {mine.shader, Verdict::OrderDependentRoute, {}, detail, mine.routes, {}};
}

// The first accepted shader with each "Base/World" key sets the kernel the
// others must repeat.
void compareLockedKernels(std::vector<VariantReport>& reports) {
  std::map<std::string, const VariantReport*> first;
  for (VariantReport& r : reports) {
    if (r.verdict != Verdict::Accepted) continue;
    std::string detail;
    for (const auto& [key, glsl] : r.lockedKernels) {
      const auto [it, fresh] = first.emplace(key, &r);
      if (fresh || it->second->lockedKernels.at(key) == glsl) continue;
      detail += fmt::format(
          "the {} kernel differs from that of '{}', derived from the same locking base\n--- {} ---\n{}\n--- {} ---\n{}",
          key, it->second->shader, it->second->shader, it->second->lockedKernels.at(key), r.shader, glsl);
    }
    if (!detail.empty()) {
      r.verdict = Verdict::LockedKernelNotShared;
      r.detail = detail;
    }
  }
}

}  // namespace

std::string withImportsReversed(const std::string& program) {
  std::vector<std::string> lines;
  for (size_t start = 0; start <= program.size();) {
    const size_t end = std::min(program.find('\n', start), program.size());
    lines.push_back(program.substr(start, end - start));
    start = end + 1;
  }
  std::vector<size_t> imports;
  for (size_t i = 0; i < lines.size(); ++i) {
    if (lines[i].find_first_not_of(" \t") != std::string::npos &&
        lines[i].compare(lines[i].find_first_not_of(" \t"), 7, "import ") == 0) {
      imports.push_back(i);
    }
  }
  for (size_t a = 0, b = imports.size(); a + 1 < b; ++a, --b) std::swap(lines[imports[a]], lines[imports[b - 1]]);
  std::string out;
  for (size_t i = 0; i < lines.size(); ++i) out += lines[i] + (i + 1 < lines.size() ? "\n" : "");
  return out;
}

VariantReport checkFrontEnd(const ProgramChecker& checker, const ProgramChecker& reordered) {
  VariantReport r = checker.frontEnd();
  compareWithReordered(r, reordered.frontEnd());
  return r;
}

std::vector<VariantReport> checkVariants(ProgramChecker& checker, ProgramChecker& reordered,
                                         const std::string& decisions) {
  std::vector<VariantReport> reports = checker.check(decisions);
  const std::vector<VariantReport> others = reordered.check(decisions);
  for (size_t i = 0; i < reports.size() && i < others.size(); ++i) compareWithReordered(reports[i], others[i]);
  compareLockedKernels(reports);
  return reports;
}

CampaignStats runSeed(uint32_t seed, int decisionMaps) {
  CampaignStats stats;
  stats.programs = 1;
  const GeneratedProgram program = generateProgram(seed);
  ProgramChecker checker(program.text);
  ProgramChecker reordered(withImportsReversed(program.text), "generated.spire", false);
  if (const VariantReport front = checkFrontEnd(checker, reordered); front.verdict != Verdict::Accepted) {
    record(stats, program, "", front);
    return stats;
  }
  // A stream of its own: the maps depend on the seed and the choice files,
  // not on how many draws generating the program took.
  RandomSource rng(seed * 2654435761u + 1u);
  for (int m = 0; m <= decisionMaps; ++m) {
    const std::string decisions = m == 0 ? std::string() : decisionMap(checker, rng);
    for (const VariantReport& r : checkVariants(checker, reordered, decisions)) record(stats, program, decisions, r);
  }
  return stats;
}

}  // namespace spire::testgen
