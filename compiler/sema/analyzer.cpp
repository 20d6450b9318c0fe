// The analysis driver and the global declarations: structs and functions.
#include <fmt/format.h>

#include <algorithm>
#include <functional>

#include "sema/analyzer_impl.h"

namespace spire::sem {

std::unique_ptr<Model> analyze(const ast::Program& program, DiagnosticList& diags, const StrategyCatalog& strategies,
                               const AnalysisOptions& options) {
  return Analyzer(program, diags, strategies, options).run();
}

Analyzer::Analyzer(const ast::Program& program, DiagnosticList& diags, const StrategyCatalog& strategies,
                   const AnalysisOptions& options)
    : program_(program), diags_(diags), strategies_(strategies), options_(options), model_(std::make_unique<Model>()) {
  model_->reserveExprs(program.exprCount);
}

std::unique_ptr<Model> Analyzer::run() {
  collectDeclarations();
  for (const auto& module : program_.modules) {
    for (const ast::DeclPtr& decl : module->decls) {
      if (diags_.limitReached()) return std::move(model_);
      // A redefined pipeline was reported when its name was claimed.
      const auto* p = ast::dyn_cast<ast::PipelineDecl>(decl.get());
      if (p && !model_->findPipeline(p->name)) analyzePipeline(*p);
    }
  }
  checkFunctionBodies();
  checkRecursion();
  analyzeShaders();
  checkUndefinedFunctions();
  return std::move(model_);
}

bool Analyzer::claimGlobalName(const std::string& name, SourceRange range, std::string_view kind) {
  auto [it, inserted] = globalNames_.try_emplace(name, GlobalName{std::string(kind), range});
  if (inserted) return true;
  if (kind == "function" && it->second.kind == "function") return true;
  diags_.report(DiagCode::E3003, range, fmt::format("redefinition of '{}' as a {}", name, kind))
      .note(it->second.range, fmt::format("previously declared here as a {}", it->second.kind));
  return false;
}

void Analyzer::collectDeclarations() {
  for (const auto& module : program_.modules) {
    for (const ast::DeclPtr& decl : module->decls) {
      switch (decl->kind) {
        case ast::DeclKind::Using: break;
        case ast::DeclKind::Struct: declareStruct(ast::cast<ast::StructDecl>(*decl)); break;
        case ast::DeclKind::Function: declareFunction(ast::cast<ast::FunctionDecl>(*decl)); break;
        case ast::DeclKind::Pipeline: {
          const auto& p = ast::cast<ast::PipelineDecl>(*decl);
          claimGlobalName(p.name, p.nameRange, "pipeline");
          break;
        }
        case ast::DeclKind::Shader: {
          const auto& s = ast::cast<ast::ShaderDecl>(*decl);
          if (claimGlobalName(s.name, s.nameRange, "shader")) shaderDecls_[s.name] = &s;
          break;
        }
        case ast::DeclKind::Group: {
          const auto& g = ast::cast<ast::GroupDecl>(*decl);
          if (claimGlobalName(g.name, g.nameRange, "group")) groupDecls_[g.name] = &g;
          break;
        }
      }
    }
  }
}

void Analyzer::declareStruct(const ast::StructDecl& decl) {
  if (model_->types().lookupBuiltin(decl.name)) {
    diags_.report(DiagCode::E3003, decl.nameRange,
                  fmt::format("'{}' is a built-in type and cannot be redefined", decl.name));
    return;
  }
  if (!claimGlobalName(decl.name, decl.nameRange, "struct")) return;
  BodyChecker types(*model_, diags_, functions_, nullptr);
  std::vector<StructField> fields;
  std::map<std::string, SourceRange, std::less<>> seen;
  for (const ast::StructField& field : decl.fields) {
    const Type* type = types.resolveType(field.type, field.arraySizes);
    if (type->isVoid() || type->containsOpaque()) {
      diags_.report(DiagCode::E3004, field.type.range,
                    fmt::format("struct field '{}' cannot have type '{}'", field.name, type->name()));
    }
    if (auto [it, inserted] = seen.try_emplace(field.name, field.nameRange); !inserted) {
      diags_
          .report(DiagCode::E3003, field.nameRange,
                  fmt::format("duplicate field '{}' in struct '{}'", field.name, decl.name))
          .note(it->second, "previous declaration is here");
    }
    fields.push_back({field.name, type});
  }
  if (fields.empty()) {
    diags_.report(DiagCode::E3004, decl.nameRange, fmt::format("struct '{}' must have at least one field", decl.name));
  }
  // A struct with errors is still registered so that its uses do not cascade
  // into "unknown type" errors.
  const Type* type = model_->types().structType(decl.name, std::move(fields));
  model_->structs[decl.name] = type;
  model_->structOrder.push_back(type);
}

void Analyzer::declareFunction(const ast::FunctionDecl& decl) {
  if (model_->types().lookupBuiltin(decl.name) || model_->structs.count(decl.name)) {
    diags_.report(DiagCode::E3003, decl.nameRange,
                  fmt::format("'{}' is a type and cannot be used as a function name", decl.name));
    return;
  }
  if (!claimGlobalName(decl.name, decl.nameRange, "function")) return;
  BodyChecker types(*model_, diags_, functions_, nullptr);
  auto function = std::make_unique<Function>();
  function->name = decl.name;
  function->decl = &decl;
  function->returnType = types.resolveType(decl.returnType);
  function->defined = decl.body != nullptr;
  if (function->returnType->containsOpaque()) {
    diags_.report(DiagCode::E3004, decl.returnType.range,
                  fmt::format("function '{}' cannot return opaque type '{}'", decl.name, function->returnType->name()));
  }
  for (const ast::Param& p : decl.params) {
    const Type* type = types.resolveType(p.type, p.arraySizes);
    if (type->isVoid()) {
      diags_.report(DiagCode::E3004, p.type.range, "a parameter cannot have type 'void'");
      type = model_->types().error();
    } else if (type->containsOpaque() && p.direction != ast::ParamDirection::In) {
      diags_.report(DiagCode::E3004, p.type.range,
                    fmt::format("opaque type '{}' can only be an 'in' parameter", type->name()));
    }
    function->params.push_back({type, p.direction});
  }

  if (const auto* builtins = model_->builtins().lookup(decl.name)) {
    for (const BuiltinOverload& o : *builtins) {
      bool same = o.params.size() == function->params.size();
      for (size_t i = 0; same && i < o.params.size(); ++i) same = o.params[i].type == function->params[i].type;
      if (same) {
        diags_.report(DiagCode::E3003, decl.nameRange,
                      fmt::format("redefinition of built-in function '{}' with the same parameter types", decl.name));
        return;
      }
    }
  }
  std::vector<Function*>& overloads = functions_[decl.name];
  for (Function* existing : overloads) {
    bool same = existing->params.size() == function->params.size();
    for (size_t i = 0; same && i < existing->params.size(); ++i) {
      same = existing->params[i].type == function->params[i].type;
    }
    if (!same) continue;
    if (existing->returnType != function->returnType) {
      diags_
          .report(DiagCode::E3003, decl.nameRange,
                  fmt::format("functions '{}' differ only in their return type", decl.name))
          .note(existing->decl->nameRange, "previous declaration is here");
      return;
    }
    if (existing->defined && decl.body) {
      diags_.report(DiagCode::E3003, decl.nameRange, fmt::format("redefinition of function '{}'", decl.name))
          .note(existing->decl->nameRange, "previous definition is here");
      return;
    }
    if (decl.body) {
      existing->decl = &decl;
      existing->defined = true;
    }
    return;
  }
  overloads.push_back(function.get());
  model_->functions.push_back(std::move(function));
}

void Analyzer::checkFunctionBodies() {
  for (const auto& f : model_->functions) {
    if (diags_.limitReached()) return;
    if (!f->defined) continue;
    BodyChecker checker(*model_, diags_, functions_, nullptr);
    for (const ast::Param& p : f->decl->params) {
      checker.declareParameter(p, f->params[static_cast<size_t>(&p - f->decl->params.data())].type);
    }
    checker.noteType(f->returnType);
    checker.checkBody(*f->decl->body, f->returnType, fmt::format("function '{}'", f->name));
    f->callees = checker.calledFunctions();
    f->structs = checker.usedStructs();
  }
}

void Analyzer::checkRecursion() {
  // GLSL forbids recursion, static or dynamic; report each cycle once.
  enum class Mark { None, Active, Done };
  std::map<const Function*, Mark> marks;
  std::vector<const Function*> stack;
  std::function<void(const Function*)> visit = [&](const Function* f) {
    marks[f] = Mark::Active;
    stack.push_back(f);
    for (const Function* callee : f->callees) {
      if (marks[callee] == Mark::Active) {
        std::string path;
        auto start = std::find(stack.begin(), stack.end(), callee);
        for (auto it = start; it != stack.end(); ++it) path += (*it)->name + " -> ";
        path += callee->name;
        diags_.report(DiagCode::E3017, callee->decl->nameRange,
                      fmt::format("recursive function calls are not allowed: {}", path));
      } else if (marks[callee] == Mark::None) {
        visit(callee);
      }
    }
    stack.pop_back();
    marks[f] = Mark::Done;
  };
  for (const auto& f : model_->functions) {
    if (marks[f.get()] == Mark::None) visit(f.get());
  }
}

}  // namespace spire::sem

namespace spire::sem {

void Analyzer::checkUndefinedFunctions() {
  // A prototype is fine until something calls it: report the first call.
  std::map<const Function*, SourceRange> firstCall;
  auto record = [&](const Function* f, SourceRange where) { firstCall.try_emplace(f, where); };
  for (const auto& f : model_->functions) {
    for (const Function* callee : f->callees) record(callee, f->decl->nameRange);
  }
  for (const auto& shader : model_->shaders) {
    for (const Component& c : shader->components) {
      for (const Definition& d : c.definitions) {
        for (const Function* callee : d.functions) record(callee, d.decl->nameRange);
      }
    }
  }
  for (const auto& f : model_->functions) {
    if (f->defined) continue;
    if (auto it = firstCall.find(f.get()); it != firstCall.end()) {
      diags_
          .report(DiagCode::E3019, f->decl->nameRange, fmt::format("function '{}' is used but never defined", f->name))
          .note(it->second, "used from here");
    }
  }
}

}  // namespace spire::sem
