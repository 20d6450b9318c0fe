// Private to sema: the state shared by the analysis passes
// (analyzer.cpp, pipeline_analysis.cpp, shader_analysis.cpp).
#pragma once

#include <map>
#include <set>
#include <string>
#include <vector>

#include "sema/analyzer.h"
#include "sema/body_checker.h"

namespace spire::sem {

// Resolves component names against a flattened component table (a
// pipeline's or a shader's) and records which components were read.
class ComponentTableResolver final : public ComponentResolver {
 public:
  explicit ComponentTableResolver(const ComponentSet& set)
      : components_(set.components), byName_(set.componentByName) {}

  const Type* useComponent(std::string_view name, SourceRange use) override;
  SourceRange declarationOf(std::string_view name) const override;
  void appendNames(std::vector<std::string_view>& out) const override;

  // Dependencies in id order with the first use of each.
  void takeDependencies(std::vector<ComponentId>& ids, std::vector<SourceRange>& uses) const;

 private:
  const std::vector<Component>& components_;
  const std::map<std::string, ComponentId, std::less<>>& byName_;
  std::map<ComponentId, SourceRange> used_;
};

class Analyzer {
 public:
  Analyzer(const ast::Program& program, DiagnosticList& diags, const StrategyCatalog& strategies,
           const AnalysisOptions& options);
  std::unique_ptr<Model> run();

 private:
  // analyzer.cpp: global declarations
  void collectDeclarations();
  void declareStruct(const ast::StructDecl& decl);
  void declareFunction(const ast::FunctionDecl& decl);
  void checkFunctionBodies();
  void checkRecursion();
  void checkUndefinedFunctions();
  bool claimGlobalName(const std::string& name, SourceRange range, std::string_view kind);

  // pipeline_analysis.cpp
  void analyzePipeline(const ast::PipelineDecl& decl);
  void checkWorld(Pipeline& pipeline, const ast::WorldDecl& world);
  void checkImport(Pipeline& pipeline, const ast::ImportDecl& decl);
  // Checks a strategy use and returns the components its arguments read.
  std::vector<std::string> checkStrategy(Pipeline& pipeline, const ast::StrategyRef& ref, StrategyRole role);
  void orderWorlds(Pipeline& pipeline);
  std::optional<WorldId> resolveWorld(const Pipeline& pipeline, std::string_view name, SourceRange range);

  // shader_analysis.cpp
  void analyzeShaders();
  void analyzeShaderDecl(const ast::ShaderDecl& decl);
  // The pipeline a `using` shader is built against: the one it names, or
  // the retargeting pipeline (AnalysisOptions::pipeline); null after E4005.
  const Pipeline* pipelineOf(const ast::ShaderDecl& decl);
  Shader* buildShader(const ast::ShaderDecl& decl, std::string name, const Pipeline& pipeline, const Shader* base);
  // Adds one declaration to a pipeline's or shader's components. `origin`
  // names the pipeline or shader that wrote it.
  void addComponent(ComponentSet& set, const Pipeline& pipeline, const ast::ComponentDecl& decl,
                    const std::string& origin, bool inPipeline);
  void addComponent(Pipeline& pipeline, const ast::ComponentDecl& decl) {
    addComponent(pipeline, pipeline, decl, pipeline.name, true);
  }
  void checkComponentBodies(ComponentSet& set, const std::string& origin);
  void checkComponentCycles(Shader& shader);
  // locked_worlds.cpp: false (after E4020) when `decl`, written in a shader
  // derived from `base`, would change a world `base` locks.
  bool checkLockedDefinition(const Shader& base, const Pipeline& pipeline, const ast::ComponentDecl& decl);
  const Group* analyzeGroup(const ast::GroupDecl& decl);
  void buildGroupInstances(const ast::ShaderDecl& decl, const Group& base);

  const ast::Program& program_;
  DiagnosticList& diags_;
  const StrategyCatalog& strategies_;
  AnalysisOptions options_;
  std::unique_ptr<Model> model_;
  FunctionTable functions_;
  // Every global name with what it is and where it was declared.
  struct GlobalName {
    std::string kind;
    SourceRange range;
  };
  std::map<std::string, GlobalName, std::less<>> globalNames_;
  std::map<std::string, const ast::ShaderDecl*, std::less<>> shaderDecls_;
  std::map<std::string, const ast::GroupDecl*, std::less<>> groupDecls_;
  std::map<const ast::ShaderDecl*, const Group*> derivedGroups_;  // decls whose base is a group
  std::map<const ast::GroupDecl*, const Group*> groups_;
  std::set<const ast::ShaderDecl*> analyzedShaders_;
  std::vector<const ast::ShaderDecl*> shadersInProgress_;
  std::set<const ast::GroupDecl*> groupsInProgress_;
};

}  // namespace spire::sem
