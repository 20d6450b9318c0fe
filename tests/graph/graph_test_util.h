// Compiling small programs into shader graphs for the graph tests.
#pragma once

#include <memory>
#include <random>
#include <string>
#include <vector>

#include "driver/frontend.h"
#include "graph/choice_space.h"
#include "graph/shader_graph.h"
#include "graph/variant.h"
#include "support/diagnostic_renderer.h"

namespace spire::testing_util {

struct CompiledShader {
  std::unique_ptr<FrontEnd> frontEnd;
  const sem::Model* model = nullptr;
  std::unique_ptr<graph::ShaderGraph> graph;

  std::string rendered() const {
    return renderDiagnostics(frontEnd->sources(), frontEnd->diagnostics(), DiagnosticFormat::Text);
  }
  std::vector<std::string> codes() const {
    std::vector<std::string> result;
    for (const Diagnostic& d : frontEnd->diagnostics().all()) result.emplace_back(diagCodeInfo(d.code).name);
    return result;
  }
};

// Compiles `files` (paths) or `source` and builds the graph of `shaderName`.
inline CompiledShader compileShader(const std::vector<std::string>& files, const std::string& source,
                                    const std::string& shaderName) {
  CompiledShader c;
  c.frontEnd = std::make_unique<FrontEnd>();
  for (const std::string& f : files) c.frontEnd->addFile(f);
  if (!source.empty()) c.frontEnd->addSource("test.spire", source);
  c.model = &c.frontEnd->analyze();
  if (c.frontEnd->diagnostics().hasErrors()) return c;
  if (const sem::Shader* s = c.model->findShader(shaderName)) {
    c.graph = graph::ShaderGraph::build(*s, c.frontEnd->diagnostics());
  }
  return c;
}

// Calls `visit(requests, index)` for decision maps drawn from the space's
// choice file: every map when there are fewer than 10,000, otherwise 1,000
// seeded random ones. Returns how many maps were visited.
template <typename Visit>
size_t forEachDecisionMap(const graph::ChoiceSpace& space, Visit visit) {
  const std::vector<graph::Choice> choices = graph::enumerateChoices(space);
  double total = 1;
  for (const graph::Choice& c : choices) total *= static_cast<double>(c.alternatives.size());
  const bool exhaustive = total < 10000;
  const size_t count = exhaustive ? static_cast<size_t>(total) : 1000;
  std::mt19937 rng(1234);
  for (size_t index = 0; index < count; ++index) {
    std::vector<graph::DecisionRequest> requests;
    size_t rest = index;
    for (const graph::Choice& c : choices) {
      const size_t pick = exhaustive ? rest % c.alternatives.size() : rng() % c.alternatives.size();
      rest /= c.alternatives.size();
      requests.push_back({c.component, c.alternatives[pick], {}});
    }
    visit(requests, index);
  }
  return count;
}

inline std::string altNames(const graph::ChoiceSpace& space, sem::ComponentId c) {
  std::string text;
  for (graph::AltId a : space.aliveAlternatives(c)) {
    text += (text.empty() ? "" : ",") + space.graph().altName(space.graph().node(c), a);
  }
  return text;
}

inline sem::ComponentId idOf(const graph::ShaderGraph& g, const std::string& name) {
  return g.shader().componentByName.at(name);
}

}  // namespace spire::testing_util
