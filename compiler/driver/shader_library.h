// The compiler as a library: what spirec, the engine and the tuner use.
// Sources are parsed and analysed once; each concrete shader's graph and
// choice space are built once; variants are then built from in-memory
// decisions without re-parsing anything.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "driver/frontend.h"
#include "graph/choice_space.h"
#include "graph/shader_graph.h"
#include "graph/variant.h"

namespace spire {

using graph::Choice;
struct CompiledVariant;

class ShaderLibrary {
 public:
  explicit ShaderLibrary(FrontEndOptions options = {});

  bool addFile(const std::string& path) { return frontEnd_.addFile(path); }
  void addSource(std::string displayPath, std::string text) {
    frontEnd_.addSource(std::move(displayPath), std::move(text));
  }
  // Analyses everything loaded and builds the graph of every concrete shader.
  // False if there were errors (see diagnostics()).
  bool compile();

  FrontEnd& frontEnd() { return frontEnd_; }
  const SourceManager& sources() const { return frontEnd_.sources(); }
  DiagnosticList& diagnostics() { return frontEnd_.diagnostics(); }
  const sem::Model& model() const { return *model_; }

  // Concrete shaders in declaration order.
  std::vector<std::string> shaderNames() const;
  // The choice space of a concrete shader, or null if there is none by that name.
  const graph::ChoiceSpace* choiceSpace(std::string_view shader) const;
  // The shader's choice-file lines as data (graph::enumerateChoices).
  std::vector<Choice> choices(std::string_view shader) const;

  // Builds a variant from decisions keyed by component name with values
  // spelled as in decision files ("Fragment", "Vertex:ggx"). Unknown names
  // and infeasible or conflicting decisions are skipped, as in decision files;
  // `skipped` (if given) receives their component names.
  // `attributes` (component -> attributes) are carried like a decision
  // line's (`[Format: "RGBA8"]`), for components that have a decision.
  using Attributes = std::map<std::string, std::vector<std::pair<std::string, std::string>>>;
  std::optional<graph::Variant> buildVariant(std::string_view shader,
                                             const std::map<std::string, std::string>& decisions,
                                             std::vector<std::string>* skipped = nullptr,
                                             const Attributes& attributes = {}) const;

  // Variants compiled from this library, by variant (driver/compiler.h).
  std::map<std::string, std::shared_ptr<const CompiledVariant>>& compiledVariants() { return compiled_; }

 private:
  struct Entry {
    const sem::Shader* shader;
    std::unique_ptr<graph::ShaderGraph> graph;
    std::unique_ptr<graph::ChoiceSpace> space;
  };
  const Entry* find(std::string_view shader) const;
  // Builds the shader's graph and choice space; false after errors.
  bool addEntry(const sem::Shader& shader, DiagnosticList& diags);

  FrontEnd frontEnd_;
  const sem::Model* model_ = nullptr;
  std::vector<Entry> entries_;
  std::map<std::string, std::shared_ptr<const CompiledVariant>> compiled_;
};

}  // namespace spire
