// The semantic model: what the front end understood about a program. It is
// the input of the shader-graph stage and of code generation, which read it
// (and the AST it points into) without re-parsing.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "sema/builtins.h"
#include "sema/strategy_catalog.h"
#include "sema/type.h"
#include "syntax/ast.h"

namespace spire::sem {

using WorldId = uint32_t;
using ComponentId = uint32_t;

// A strategy named by a world's export or an import, with its arguments
// checked against the pipeline's components.
struct StrategyUse {
  const StrategySignature* signature = nullptr;  // null when unknown
  const ast::StrategyRef* ref = nullptr;
  // Components the arguments read (e.g. `projPos` for vertexExport(projPos)):
  // the pipeline requires them to be available where the strategy runs.
  std::vector<std::string> componentArgs;
};

struct World {
  std::string name;
  const ast::WorldDecl* decl = nullptr;
  bool isAbstract = false;
  std::optional<StrategyUse> exportStrategy;
};

struct Import {
  WorldId from = 0;
  WorldId to = 0;
  const ast::ImportDecl* decl = nullptr;
  StrategyUse strategy;
  int priority = 0;  // [Priority: "N"]: breaks ties between equally faithful routes
};

struct Function;

// One definition of a component: where it may be computed (an explicit
// world, or none for an implicitly overloaded one), under which variation
// name, and which other components its body reads.
struct Definition {
  const ast::ComponentDecl* decl = nullptr;
  std::optional<WorldId> world;
  std::string variation;
  std::vector<ComponentId> dependencies;    // sorted, unique
  std::vector<SourceRange> dependencyUses;  // first use of each dependency, same order
  std::vector<const Function*> functions;   // user functions called directly
  std::string origin;                       // shader or pipeline that wrote it
  std::vector<const Type*> structs;         // struct types its body names (BodyChecker::usedStructs)

  bool isInput() const { return !decl->hasDefinition(); }
};

struct Component {
  std::string name;
  const Type* type = nullptr;
  const ast::ComponentDecl* firstDecl = nullptr;  // where the name was introduced
  std::string origin;                             // shader or pipeline that introduced it: the choice-file prefix
  bool isAbstract = false;                        // declared `abstract`: a derived shader must define it
  bool isExport = false;
  // From `abstract @W`: definitions without an explicit world go to W.
  std::optional<WorldId> requiredWorld;
  std::vector<Definition> definitions;
  std::vector<const ast::Attribute*> attributes;  // from every declaration, in order
};

// The flattened components visible in a pipeline or shader.
struct ComponentSet {
  std::vector<Component> components;
  std::map<std::string, ComponentId, std::less<>> componentByName;

  const Component* findComponent(std::string_view name) const;
};

struct Pipeline : ComponentSet {
  std::string name;
  const ast::PipelineDecl* decl = nullptr;
  std::vector<World> worlds;    // declaration order
  std::vector<Import> imports;  // declaration order; both ends resolved
  // Worlds sorted so that every import goes from an earlier to a later world;
  // ties keep declaration order. Empty when the imports have a cycle.
  std::vector<WorldId> topologicalOrder;
  std::map<std::string, WorldId, std::less<>> worldByName;
  // The components (ComponentSet) are the pipeline's own, inherited by every
  // shader using it.
  bool valid = true;

  std::optional<WorldId> findWorld(std::string_view name) const;
  // True when `to` is reachable from `from` through zero or more imports.
  bool reaches(WorldId from, WorldId to) const;
  // reachability[from * worlds.size() + to]
  std::vector<bool> reachability;
  // The imports that carry a value from one world to another, in order
  // (route_selection.h says how they are chosen); empty for from == to or
  // unreachable pairs.
  const std::vector<uint32_t>& route(WorldId from, WorldId to) const;
  // routes[from * worlds.size() + to]
  std::vector<std::vector<uint32_t>> routes;
};

struct Group;

struct Shader : ComponentSet {
  std::string name;
  const ast::ShaderDecl* decl = nullptr;
  const Pipeline* pipeline = nullptr;
  const Shader* base = nullptr;          // the base shader, or the group member for an instance
  const Group* derivedFrom = nullptr;    // set on instances of a shader whose base is a group
  std::vector<WorldId> finalizedWorlds;  // own and inherited
  // The components (ComponentSet) are the pipeline's first, then each
  // base's, then this shader's own; ids of inherited components are stable.
  bool valid = true;
};

struct GroupMember {
  const Shader* shader = nullptr;
  bool isOptional = false;
};

// A declared group, or the group synthesized by a shader whose base is a group.
struct Group {
  std::string name;
  const ast::GroupDecl* decl = nullptr;
  const ast::ShaderDecl* derivedDecl = nullptr;  // set for synthesized groups
  std::vector<GroupMember> members;
};

struct Param {
  const Type* type = nullptr;
  ast::ParamDirection direction = ast::ParamDirection::In;
};

struct Function {
  std::string name;
  const ast::FunctionDecl* decl = nullptr;  // the definition, or the first prototype
  const Type* returnType = nullptr;
  std::vector<Param> params;
  std::vector<const Function*> callees;  // user functions called directly, in first-call order
  std::vector<const Type*> structs;      // struct types its signature and body name
  bool defined = false;
};

// What a name or call in an expression refers to.
enum class RefKind : uint8_t {
  None,
  Local,        // local variable (VarDeclarator)
  Parameter,    // function parameter
  Component,    // a component, by name in the enclosing shader
  Function,     // a user function call
  Builtin,      // a built-in function call
  Constructor,  // a built-in type constructor (vec4(...), float[2](...))
  StructConstructor,
  Swizzle,  // vector swizzle (MemberExpr)
  Field,    // struct field (MemberExpr)
};

struct ExprInfo {
  const Type* type = nullptr;  // null for expressions never analysed
  RefKind ref = RefKind::None;
  bool isLValue = false;
  const ast::VarDeclarator* local = nullptr;
  const ast::Param* parameter = nullptr;
  const Function* function = nullptr;
  const BuiltinOverload* builtin = nullptr;
  uint32_t fieldIndex = 0;
  std::optional<int64_t> constant;  // integer constant value, when known
};

class Model {
 public:
  Model() : builtins_(types_) {}
  Model(const Model&) = delete;
  Model& operator=(const Model&) = delete;

  TypeTable& types() { return types_; }
  const TypeTable& types() const { return types_; }
  const BuiltinTable& builtins() const { return builtins_; }

  const ExprInfo& info(const ast::Expr& e) const { return exprInfo_[e.id]; }
  ExprInfo& mutableInfo(const ast::Expr& e) { return exprInfo_[e.id]; }
  const Type* typeOf(const ast::Expr& e) const { return exprInfo_[e.id].type; }
  void reserveExprs(uint32_t count) { exprInfo_.resize(count); }

  const Pipeline* findPipeline(std::string_view name) const;
  const Shader* findShader(std::string_view name) const;
  const Group* findGroup(std::string_view name) const;

  // Owned entities, in declaration order (shaders: bases before derived).
  std::vector<std::unique_ptr<Pipeline>> pipelines;
  std::vector<std::unique_ptr<Shader>> shaders;
  std::vector<std::unique_ptr<Group>> groups;
  std::vector<std::unique_ptr<Function>> functions;
  std::map<std::string, const Type*, std::less<>> structs;
  std::vector<const Type*> structOrder;  // declaration order
  // Each local declarator's resolved type.
  std::map<const ast::VarDeclarator*, const Type*> localTypes;

 private:
  TypeTable types_;
  BuiltinTable builtins_;
  std::vector<ExprInfo> exprInfo_;
};

}  // namespace spire::sem
