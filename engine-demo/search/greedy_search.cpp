#include "search/greedy_search.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>

#include "search/average_probes.h"
#include "search/candidate_ranking.h"
#include "search/model_cost.h"
#include "simplify/average_sites.h"
#include "simplify/rewrite_target.h"
#include "support/file_io.h"

namespace spire::search {

namespace {

// A renormalization shift below this in every scalar is rounding: no 8-bit
// pixel moves by it.
constexpr double kNegligibleShift = 1e-6;

// The RMSE between two profiles of one type, over the scalars both have
// finite; nullopt when they differ in length or share none.
std::optional<double> profileDistance(const std::vector<float>& a, const std::vector<float>& b) {
  if (a.size() != b.size()) return std::nullopt;
  double sum = 0.0;
  size_t count = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    if (!std::isfinite(a[i]) || !std::isfinite(b[i])) continue;
    sum += (double{a[i]} - double{b[i]}) * (double{a[i]} - double{b[i]});
    ++count;
  }
  if (count == 0) return std::nullopt;
  return std::sqrt(sum / static_cast<double>(count));
}

// The RMSE of a profile against its own average: what replacing it by the
// constant would cost at the profiled pixels.
double spread(const ValueProfile& value) {
  const std::vector<double>& average = *value.average;
  std::vector<float> constant(value.profile.size());
  for (size_t i = 0; i < constant.size(); ++i) constant[i] = static_cast<float>(average[i % average.size()]);
  return profileDistance(value.profile, constant).value_or(0.0);
}

// The component of the probe's type, other than the one it is in and than
// the subtree itself, whose profile is closest to the site's, with the
// distance; nullopt when none is closer than the site's own average, which
// the average rule proposes already.
std::optional<std::pair<std::string, double>> closestComponent(const sem::Shader& shader, const AverageProbe& probe,
                                                               const ValueProfile& site,
                                                               const std::vector<ComponentValue>& components,
                                                               const std::vector<ValueProfile>& profiles) {
  if (!site.average) return std::nullopt;
  std::optional<std::pair<std::string, double>> closest;
  const double constant = spread(site);
  for (size_t j = 0; j < components.size(); ++j) {
    const std::string& name = components[j].component;
    const sem::Component* c = shader.findComponent(name);
    if (name == probe.component || name == probe.site.rewrite.before || !c || !c->type ||
        c->type->name() != probe.site.rewrite.type || !profiles[j].average) {
      continue;
    }
    const std::optional<double> distance = profileDistance(site.profile, profiles[j].profile);
    if (distance && *distance < constant && (!closest || *distance < closest->second)) {
      closest = std::pair{name, *distance};
    }
  }
  return closest;
}

struct Trial {
  Candidate candidate;
  Measure measure;
  bool fromCache = false;
  tune::VariantResult result;  // when measured in this step
};

struct Accepted {
  Rewriting step;
  Level level;
};

// What a step ended with: a level, a stale cache (choose again), or nothing.
struct Choice {
  std::optional<Accepted> accepted;
  bool stale = false;
};

class GreedySearch {
 public:
  GreedySearch(const SearchSetup& setup, const SearchOptions& options, std::ostream& progress)
      : setup_(setup), options_(options), progress_(progress) {}

  Expected<Chain, Failure> run();

 private:
  Expected<std::optional<Accepted>, Failure> step(size_t level);
  Expected<std::vector<Candidate>, Failure> propose(size_t level);
  void addProbedCandidates(const StepRequest& request, size_t level, std::vector<Candidate>& candidates);
  // Probes of `moduleText`, written to `file` in the work folder.
  ProbeSetup probeSetup(std::string moduleText, const std::string& file) const {
    return {setup_.scene,
            setup_.instance,
            setup_.tuner,
            setup_.compile,
            setup_.header.derived,
            std::move(moduleText),
            (setup_.workDir / file).string()};
  }
  void renormalize(size_t level, int attempt, std::vector<Candidate>& candidates);
  // Each candidate's component: its average at level 0 (measured once), and
  // the candidate's own; nullopt where there is none.
  Expected<std::vector<std::pair<std::optional<std::vector<double>>, std::optional<std::vector<double>>>>, Failure>
  candidateAverages(size_t level, int attempt, const std::vector<Candidate>& candidates);
  Expected<void, Failure> writeStepModule(size_t level, int attempt, std::vector<Candidate>& candidates);
  // The chain so far and `candidates`, or `only` of them, as a module.
  std::string stepText(const std::vector<Candidate>& candidates, const Candidate* only = nullptr) const;
  void dropUncompilable(const std::string& path, std::vector<Candidate>& candidates);
  void dropConflicting(const std::string& path, std::vector<Candidate>& candidates);
  bool dropRetyped(const ShaderLibrary& compiled, std::vector<Candidate>& candidates);
  std::vector<Trial> measureCandidates(const std::vector<Candidate>& candidates);
  Choice choose(const std::vector<size_t>& order, std::vector<Trial>& trials);
  tune::VariantResult measure(const Placement& placement);
  Placement live(const Placement& placement);
  Level levelOf(const tune::VariantResult& result, Placement placement) const;
  Measure measureOf(const Level& level) const { return {level.error, costOf(level, options_.cost)}; }
  // C of `placement` in the step's module (search/model_cost.h); nullopt
  // when it is not a variant of it, and so no candidate (a cost of 0 would
  // look like the greatest saving).
  std::optional<double> stepModelCost(const Placement& placement) const;
  std::vector<const Rewriting*> accepted() const;
  void note(const std::string& line);

  const SearchSetup& setup_;
  const SearchOptions& options_;
  std::ostream& progress_;
  Chain chain_;
  std::map<std::string, Measure> cache_;                                        // the error cache, by rewrite
  std::map<std::string, std::optional<std::vector<double>>> originalAverages_;  // by component, at level 0
  std::unique_ptr<ShaderLibrary> stepLibrary_;  // the step's module compiled: the chain and its candidates
  uint64_t points_ = 0;
};

void GreedySearch::note(const std::string& line) {
  progress_ << line << "\n";
  chain_.log.push_back(line);
}

tune::VariantResult GreedySearch::measure(const Placement& placement) {
  tune::TunePoint point;
  point.index = points_++;
  point.decisions = {placement.begin(), placement.end()};
  return setup_.tuner->measure(point);
}

// The components `placement` computes: a rewrite can leave another
// component unread (`max(a, b)` -> `a` drops b), and rewriting that one
// would change nothing.
Placement GreedySearch::live(const Placement& placement) {
  tune::TunePoint point;
  point.decisions = {placement.begin(), placement.end()};
  auto program = setup_.tuner->program(point);
  return program ? program->placement : placement;
}

Level GreedySearch::levelOf(const tune::VariantResult& result, Placement placement) const {
  return {result.rmse, result.time.median, result.frameMs, result.kernels, std::move(placement)};
}

std::optional<double> GreedySearch::stepModelCost(const Placement& placement) const {
  if (!stepLibrary_) return std::nullopt;
  return modelCost(*stepLibrary_, setup_.header.derived, placement);
}

std::vector<const Rewriting*> GreedySearch::accepted() const {
  std::vector<const Rewriting*> steps;
  for (const Rewriting& r : chain_.steps) steps.push_back(&r);
  return steps;
}

Expected<Chain, Failure> GreedySearch::run() {
  const tune::VariantResult original = measure(setup_.original);
  if (!original.ok()) return Failure{fmt::format("the original shader cannot be measured: {}", original.status)};
  chain_.levels.push_back(levelOf(original, setup_.original));
  note(fmt::format("level 0: the original, RMSE {:.6f}, time ratio {:.3f}", original.rmse, original.time.median));
  for (size_t level = 1; level <= options_.maxLevels; ++level) {
    auto next = step(level);
    if (!next) return next.error();
    if (!*next) return std::move(chain_);
    chain_.steps.push_back((*next)->step);
    chain_.levels.push_back((*next)->level);
  }
  chain_.stopReason = fmt::format("the chain has {} levels after the original (--max-levels)", options_.maxLevels);
  return std::move(chain_);
}

Expected<std::vector<Candidate>, Failure> GreedySearch::propose(size_t level) {
  const std::string path = (setup_.workDir / fmt::format("level{}.spire", level - 1)).string();
  auto current = compileModule(setup_.compile, path, chainModuleText(setup_.header, accepted()), setup_.header.derived);
  if (!current) return Failure{fmt::format("level {} does not compile: {}", level - 1, current.error().message)};
  // The level's C, on the module that names its definitions as the level does.
  if (const auto c = modelCost(**current, setup_.header.derived, chain_.levels.back().placement)) {
    chain_.levels.back().modelCost = *c;
  }
  StepRequest request{current->get(),  setup_.header.derived, chain_.levels.back().placement,
                      setup_.original, setup_.components,     options_.k1,
                      level,           setup_.userRules};
  auto candidates = proposeCandidates(request);
  if (candidates && (options_.average || options_.acse)) addProbedCandidates(request, level, *candidates);
  if (candidates && options_.moves) {
    std::vector<Candidate> moves = proposeMoves(request);
    candidates->insert(candidates->end(), std::make_move_iterator(moves.begin()), std::make_move_iterator(moves.end()));
  }
  return candidates;
}

std::string GreedySearch::stepText(const std::vector<Candidate>& candidates, const Candidate* only) const {
  std::vector<const Rewriting*> definitions = accepted();
  if (only) {
    definitions.push_back(&only->rewriting);
  } else {
    for (const Candidate& c : candidates) definitions.push_back(&c.rewriting);
  }
  return chainModuleText(setup_.header, definitions);
}

Expected<std::vector<std::pair<std::optional<std::vector<double>>, std::optional<std::vector<double>>>>, Failure>
GreedySearch::candidateAverages(size_t level, int attempt, const std::vector<Candidate>& candidates) {
  std::vector<ComponentValue> values;
  std::vector<std::string> originals;  // components whose level-0 average is not known yet
  for (const Candidate& c : candidates) {
    const std::string& component = c.rewriting.component;
    if (isMove(c.rewriting) || originalAverages_.contains(component) ||
        std::find(originals.begin(), originals.end(), component) != originals.end()) {
      continue;
    }
    originals.push_back(component);
    values.push_back({component, setup_.original});
  }
  for (const Candidate& c : candidates) {
    if (!isMove(c.rewriting))
      values.push_back({c.rewriting.component, applied(chain_.levels.back().placement, c.rewriting)});
  }
  const ProbeSetup setup = probeSetup(stepText(candidates), fmt::format("renormalize{}-{}.spire", level, attempt));
  auto averages = measureComponents(setup, values);
  if (!averages) return averages.error();
  for (size_t i = 0; i < originals.size(); ++i) originalAverages_[originals[i]] = (*averages)[i];
  std::vector<std::pair<std::optional<std::vector<double>>, std::optional<std::vector<double>>>> result;
  size_t next = originals.size();
  for (const Candidate& c : candidates) {
    if (isMove(c.rewriting)) {
      result.emplace_back();  // a move keeps its definition: nothing to shift
      continue;
    }
    result.emplace_back(originalAverages_.at(c.rewriting.component), (*averages)[next++]);
  }
  return result;
}

// The rules that need the sites' values: each site's probe (and, for ACSE,
// each live component) rendered once over the scene's views and samples.
// Pellacini's average rule puts the site's average in its place. He et al.
// 2015's approximate common subexpression elimination puts the live
// component of its type whose profile (its values at a sample of the
// shader's pixels) is closest, even one computed in another world (the
// profile is what the fragment sees of it); a component that depends on the
// one rewritten makes a cycle, which does not compile, and the candidate is
// dropped with the compiler's reason. Probes that cannot be measured leave
// the step without these candidates, and the log says why.
void GreedySearch::addProbedCandidates(const StepRequest& request, size_t level, std::vector<Candidate>& candidates) {
  auto probes = proposeAverageProbes(request);
  if (!probes || probes->empty()) return;
  const Placement& placement = chain_.levels.back().placement;
  const sem::Shader& shader = *request.current->model().findShader(setup_.header.derived);
  std::vector<ComponentValue> components;
  for (const auto& entry : placement) {
    const sem::Component* c = options_.acse ? shader.findComponent(entry.first) : nullptr;
    if (c && !c->isExport) components.push_back({entry.first, placement});
  }
  const ProbeSetup setup = probeSetup(chainModuleText(setup_.header, accepted()), fmt::format("probe{}.spire", level));
  auto profiles = profileValues(setup, *probes, components, placement);
  if (!profiles) return note(fmt::format("  no average or acse candidates: {}", profiles.error().message));
  const std::vector<ValueProfile> componentProfiles(profiles->begin() + static_cast<std::ptrdiff_t>(probes->size()),
                                                    profiles->end());
  std::vector<std::string> keys;
  for (const Candidate& c : candidates) keys.push_back(c.key);
  const auto add = [&](const AverageProbe& probe, const std::string& rule, const std::string& replacement) {
    auto candidate = siteCandidate(request, probe, rule, replacement, candidates.size() + 1);
    if (!candidate || std::find(keys.begin(), keys.end(), candidate->key) != keys.end()) return false;
    keys.push_back(candidate->key);
    candidates.push_back(std::move(candidate).value());
    return true;
  };
  for (size_t i = 0; i < probes->size(); ++i) {
    const AverageProbe& probe = (*probes)[i];
    const ValueProfile& site = (*profiles)[i];
    if (!site.average) {
      note(fmt::format("  no average of '{}' in {}: no pixel shows it, or it is not finite", probe.site.rewrite.before,
                       probe.component));
      continue;
    }
    if (options_.average) {
      add(probe, simplify::kAverageRule, simplify::averageReplacement(probe.site.rewrite.type, *site.average));
    }
    if (!options_.acse) continue;
    const auto closest = closestComponent(shader, probe, site, components, componentProfiles);
    if (closest && add(probe, "acse", closest->first)) {
      note(fmt::format("  acse: '{}' in {} is closest to {} (RMSE {:.6f} at the profiled pixels)",
                       probe.site.rewrite.before, probe.component, closest->first, closest->second));
    }
  }
}

// Pellacini's renormalization, f_c = s_c - average(s_c) + average(f_0), per
// component: each candidate's definition shifted so that its average over
// the scene is the component's at level 0. A candidate whose averages
// cannot be measured, or whose definition returns from an [Immutable]
// statement, stays as it is, and the log says so.
void GreedySearch::renormalize(size_t level, int attempt, std::vector<Candidate>& candidates) {
  auto averages = candidateAverages(level, attempt, candidates);
  if (!averages) return note(fmt::format("  not renormalized: {}", averages.error().message));
  const sem::Shader& shader = *stepLibrary_->model().findShader(setup_.header.derived);
  for (size_t i = 0; i < candidates.size(); ++i) {
    Candidate& c = candidates[i];
    if (isMove(c.rewriting)) continue;
    const auto& [original, own] = (*averages)[i];
    const ast::ComponentDecl* decl = simplify::definitionNamed(shader, c.rewriting.component, c.rewriting.variation);
    const sem::Component* component = shader.findComponent(c.rewriting.component);
    if (!original || !own || !decl || !component || !component->type) {
      note(fmt::format("  not renormalized: {} ({}): its average cannot be measured", c.rewriting.from,
                       c.rewriting.rule));
      continue;
    }
    std::vector<double> shift;
    for (size_t s = 0; s < own->size(); ++s) shift.push_back((*original)[s] - (*own)[s]);
    // An average candidate's own average is the original's but for rounding:
    // a shift that small would only cost an addition.
    if (std::all_of(shift.begin(), shift.end(), [](double d) { return std::abs(d) < kNegligibleShift; })) continue;
    const std::string constant = simplify::averageReplacement(component->type->name(), shift);
    const auto text = simplify::shiftedText(stepLibrary_->sources(), *decl, constant, c.rewriting.variation);
    const auto levelText = simplify::shiftedText(stepLibrary_->sources(), *decl, constant, c.level.variation);
    if (!text || !levelText) {
      note(fmt::format("  not renormalized: {} ({}): it returns from an [Immutable] statement", c.rewriting.from,
                       c.rewriting.rule));
      continue;
    }
    c.rewriting.text = *text;
    c.level.text = *levelText;
    c.rewriting.rule = c.level.rule = fmt::format("{}, renormalized by {}", c.rewriting.rule, constant);
    c.key += "\n+ " + constant;
    c.type.clear();  // checked on the module before the shift, whose offsets it names
  }
}

// Keeps the candidates that compile with the chain, each alone; says why
// the others were dropped.
void GreedySearch::dropUncompilable(const std::string& path, std::vector<Candidate>& candidates) {
  std::vector<Candidate> kept;
  for (Candidate& c : candidates) {
    auto alone = compileModule(setup_.compile, path, stepText(candidates, &c), setup_.header.derived);
    if (alone) kept.push_back(std::move(c));
    if (!alone) note(fmt::format("  dropped {} ({}): {}", c.rewriting.from, c.rewriting.rule, alone.error().message));
  }
  candidates = std::move(kept);
}

// Keeps the candidates that compile together, in order, each with those
// kept before it: two that compile alone can still make a cycle together
// (ACSE's `nDotV` for a subtree of `nDotH`, and `nDotH` for one of `nDotV`).
void GreedySearch::dropConflicting(const std::string& path, std::vector<Candidate>& candidates) {
  std::vector<Candidate> kept;
  for (Candidate& c : candidates) {
    kept.push_back(std::move(c));
    auto together = compileModule(setup_.compile, path, stepText(kept), setup_.header.derived);
    if (together) continue;
    note(fmt::format("  dropped {} ({}): with the step's other candidates: {}", kept.back().rewriting.from,
                     kept.back().rewriting.rule, together.error().message));
    kept.pop_back();
  }
  candidates = std::move(kept);
}

// Drops the user rules' candidates whose replacement compiled to another
// type than the one it replaced (it compiles, and means something else);
// true when one was.
bool GreedySearch::dropRetyped(const ShaderLibrary& compiled, std::vector<Candidate>& candidates) {
  const sem::Shader* shader = compiled.model().findShader(setup_.header.derived);
  std::vector<Candidate> kept;
  for (Candidate& c : candidates) {
    const ast::ComponentDecl* decl =
        c.type.empty() || !shader ? nullptr
                                  : simplify::definitionNamed(*shader, c.rewriting.component, c.rewriting.variation);
    const auto error =
        decl ? simplify::replacementTypeError(compiled.model(), *decl, c.replacementAt, c.rewriting.after, c.type)
             : std::nullopt;
    if (error) note(fmt::format("  dropped {} ({}): {}", c.rewriting.from, c.rewriting.rule, *error));
    if (!error) kept.push_back(std::move(c));
  }
  const bool dropped = kept.size() != candidates.size();
  candidates = std::move(kept);
  return dropped;
}

// The step's module: the chain so far and every candidate. A candidate that
// does not compile with the others is tried alone, and dropped if it fails;
// so is a user rule's that changes the type it replaces.
Expected<void, Failure> GreedySearch::writeStepModule(size_t level, int attempt, std::vector<Candidate>& candidates) {
  const std::string path = (setup_.workDir / fmt::format("step{}-{}.spire", level, attempt)).string();
  auto compiled = compileModule(setup_.compile, path, stepText(candidates), setup_.header.derived);
  if (!compiled) {
    dropUncompilable(path, candidates);
    compiled = compileModule(setup_.compile, path, stepText(candidates), setup_.header.derived);
  }
  if (!compiled) {
    dropConflicting(path, candidates);
    compiled = compileModule(setup_.compile, path, stepText(candidates), setup_.header.derived);
  }
  // On the module the kept candidates compile in, so that one candidate
  // that does not compile cannot let another's change of type through.
  if (compiled && dropRetyped(**compiled, candidates)) {
    compiled = compileModule(setup_.compile, path, stepText(candidates), setup_.header.derived);
  }
  if (!compiled) {
    return Failure{fmt::format("level {}'s candidates do not compile together: {}", level, compiled.error().message)};
  }
  stepLibrary_ = std::move(*compiled);
  if (auto written = writeFileAtomically(path, stepText(candidates)); !written) return written.error();
  setup_.scene->instances.at(setup_.instance).source = path;
  setup_.scene->instances.at(setup_.instance).shader = setup_.header.derived;
  return {};
}

// Each candidate's error: from the cache, or rendered. Candidates that fail
// or whose program is the current level's (the rewrite changed nothing the
// compiler kept) are left out.
std::vector<Trial> GreedySearch::measureCandidates(const std::vector<Candidate>& candidates) {
  const Level& current = chain_.levels.back();
  std::vector<Trial> trials;
  for (const Candidate& c : candidates) {
    const Placement placement = applied(current.placement, c.rewriting);
    const std::optional<double> cost = stepModelCost(placement);
    if (!cost) {
      note(fmt::format("  skipped {} ({}): its cost C cannot be computed", c.rewriting.from, c.rewriting.rule));
      continue;
    }
    if (const auto hit = cache_.find(c.key); hit != cache_.end()) {
      // The error is cached; C is not, since it depends on what the other
      // components are now.
      Measure cached = hit->second;
      if (options_.cost == CostKind::Model) cached.cost = *cost;
      trials.push_back({c, cached, true, {}});
      continue;
    }
    tune::VariantResult result = measure(placement);
    if (!result.ok()) {
      note(fmt::format("  skipped {} ({}): {}", c.rewriting.from, c.rewriting.rule, result.status));
      continue;
    }
    if (result.kernels == current.kernels) continue;
    Level level = levelOf(result, {});
    level.modelCost = *cost;
    const Measure measured = measureOf(level);
    cache_[c.key] = measured;
    trials.push_back({c, measured, false, std::move(result)});
  }
  return trials;
}

Choice GreedySearch::choose(const std::vector<size_t>& order, std::vector<Trial>& trials) {
  const Level& current = chain_.levels.back();
  for (const size_t i : order) {
    Trial& t = trials[i];
    const Rewriting& r = t.candidate.level;
    tune::VariantResult fresh = t.fromCache ? measure(applied(current.placement, t.candidate.rewriting)) : t.result;
    if (!fresh.ok() || fresh.kernels == current.kernels) continue;
    if (t.fromCache && std::abs(fresh.rmse - t.measure.error) > options_.k3 * t.measure.error) {
      note(fmt::format("  stale: {} ({}) cached RMSE {:.6f}, now {:.6f}; the cache is emptied", r.from, r.rule,
                       t.measure.error, fresh.rmse));
      return {std::nullopt, true};
    }
    // Liveness from the step's module, which names the rewrite as the candidate.
    const Placement measured = live(applied(current.placement, t.candidate.rewriting));
    Level level = levelOf(fresh, applied(measured, r));
    const std::optional<double> cost = stepModelCost(measured);
    if (!cost) continue;
    level.modelCost = *cost;
    if (level.error > options_.errorBudget || !keepsChainMonotone(measureOf(current), measureOf(level))) {
      note(fmt::format(
          "  not taken: {} ({}) RMSE {:.6f}, time ratio {:.3f} is over the budget or breaks the monotone chain", r.from,
          r.rule, level.error, level.timeRatio));
      continue;
    }
    return {Accepted{r, std::move(level)}, false};
  }
  return {};
}

Expected<std::optional<Accepted>, Failure> GreedySearch::step(size_t level) {
  for (int attempt = 0;; ++attempt) {
    auto candidates = propose(level);
    if (!candidates) return candidates.error();
    if (candidates->empty()) {
      chain_.stopReason = "no rewrite is left";
      return std::optional<Accepted>{};
    }
    if (auto written = writeStepModule(level, attempt, *candidates); !written) return written.error();
    if (options_.renormalize) {
      renormalize(level, attempt, *candidates);
      if (auto written = writeStepModule(level, attempt, *candidates); !written) return written.error();
    }
    std::vector<Trial> trials = measureCandidates(*candidates);
    std::vector<Measure> measures;
    for (const Trial& t : trials) measures.push_back(t.measure);
    const std::vector<size_t> order =
        rankCandidates(measureOf(chain_.levels.back()), measures, {options_.k2, options_.errorBudget});
    Choice choice = choose(order, trials);
    if (choice.stale) {
      cache_.clear();
      continue;
    }
    if (!choice.accepted) {
      chain_.stopReason = trials.empty() ? "no rewrite changes the program"
                                         : "no candidate is within the error budget and keeps the chain monotone";
      note(fmt::format("level {}: {} candidate(s); stop: {}", level, candidates->size(), chain_.stopReason));
      return std::optional<Accepted>{};
    }
    const Accepted& a = *choice.accepted;
    const std::string what = isMove(a.step)
                                 ? fmt::format("{} moved", definitionName(a.step))
                                 : fmt::format("{} = {} with {}", definitionName(a.step), a.step.from, a.step.rule);
    note(fmt::format("level {}: {} candidate(s), {} ranked; {}: '{}' -> '{}', RMSE {:.6f}, time ratio {:.3f}, C {:.1f}",
                     level, candidates->size(), order.size(), what, a.step.before, a.step.after, a.level.error,
                     a.level.timeRatio, a.level.modelCost));
    return std::move(choice.accepted);
  }
}

}  // namespace

Expected<Chain, Failure> greedySearch(const SearchSetup& setup, const SearchOptions& options, std::ostream& progress) {
  return GreedySearch(setup, options, progress).run();
}

}  // namespace spire::search
