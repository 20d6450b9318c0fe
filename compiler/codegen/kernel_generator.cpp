#include "codegen/kernel_generator.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <functional>
#include <map>
#include <queue>
#include <set>

#include "codegen/glsl_writer.h"
#include "codegen/hazard_instrumentation.h"
#include "codegen/interface_allocation.h"
#include "reflection/reflection_json.h"
#include "support/content_hash.h"

namespace spire::codegen {
namespace {

// Each newline-terminated line of `text` as a line of `out`.
void writeLines(GlslOutput& out, std::string_view text) {
  for (size_t start = 0, end = text.find('\n'); end != std::string_view::npos;
       start = end + 1, end = text.find('\n', start)) {
    out.line(text.substr(start, end - start));
  }
}

// The value of the world's attribute `name` ([Role]).
std::optional<std::string> attributeValue(const ast::WorldDecl& decl, std::string_view name) {
  for (const ast::Attribute& a : decl.attributes) {
    if (a.name == name && a.value) return a.value;
  }
  return std::nullopt;
}

// One kernel's components, the names it gave them and the functions they
// call, from which its text is written.
struct KernelText {
  std::vector<sem::ComponentId> computed;  // producers first
  std::set<sem::ComponentId> touched;      // computed, imported or exported
  std::map<sem::ComponentId, std::string> names;
  std::vector<const sem::Function*> functions;
  std::map<sem::ComponentId, std::string> helpers;  // the function of each block body
};

class KernelGenerator {
 public:
  KernelGenerator(const sem::Model& model, const SourceManager& sources, const graph::Variant& variant,
                  const StrategyRegistry& strategies, DiagnosticList& diags, const KernelOptions& options)
      : model_(model),
        sources_(sources),
        variant_(variant),
        graph_(variant.graph()),
        pipeline_(graph_.pipeline()),
        strategies_(strategies),
        diags_(diags),
        options_(options),
        interfaces_(variant) {}

  std::optional<Kernel> generate(sem::WorldId world);

 private:
  // Reported at `where` when the cause is in the source, else at the shader.
  void fail(std::string message, SourceRange where = {}) {
    diags_.report(DiagCode::E6001, where.valid() ? where : graph_.shader().decl->nameRange,
                  fmt::format("cannot generate the kernel of world '{}' for shader '{}': {}", currentWorld_,
                              graph_.shader().name, message));
  }
  KernelValue value(sem::ComponentId id, const std::map<sem::ComponentId, std::string>& names) const;
  std::vector<sem::ComponentId> byName(const std::set<sem::ComponentId>& ids) const;
  std::vector<sem::ComponentId> canonicalOrder(const std::vector<sem::ComponentId>& computed) const;
  bool emitImports(sem::WorldId w, KernelBuilder& kernel, const std::map<sem::ComponentId, std::string>& names,
                   GlslWriter& writer);
  bool emitExports(sem::WorldId w, const Strategy* exportStrategy, KernelBuilder& kernel,
                   const std::map<sem::ComponentId, std::string>& names, GlslWriter& writer);
  std::vector<const sem::Function*> calledFunctions(const std::vector<sem::ComponentId>& computed) const;
  std::set<const sem::Type*> usedStructs(const std::set<sem::ComponentId>& touched,
                                         const std::vector<sem::ComponentId>& computed,
                                         const std::vector<const sem::Function*>& functions) const;
  std::string structDeclarations(const std::set<const sem::Type*>& used,
                                 const std::map<std::string, std::string, std::less<>>& names) const;
  void claimNames(const graph::WorldPlan& plan, const std::vector<Located>& outputs, KernelBuilder& kernel,
                  KernelText& text, GlslNameMaps& maps) const;
  void declareComputed(KernelBuilder& kernel, KernelText& text) const;
  // The declaration of the definition the variant chose for `id`.
  const ast::ComponentDecl& chosenDecl(sem::ComponentId id) const;
  void writeHeader(GlslOutput& out, const sem::World& world, ShaderStage stage, const std::string& structs) const;
  // Interface declarations, globals, functions and block bodies' functions.
  void writeDefinitions(GlslOutput& out, const KernelBuilder& kernel, const KernelText& text, const GlslNameMaps& maps,
                        GlslWriter& writer) const;
  void writeMain(GlslOutput& out, const KernelBuilder& kernel, const KernelText& text, GlslWriter& writer,
                 const HazardInstrumentation* hazards) const;
  // What the instrumentation sees: the kernel's inputs, then its computed
  // values in evaluation order.
  std::vector<InstrumentedValue> instrumentedValues(const graph::WorldPlan& plan, const KernelText& text) const;
  Kernel packageKernel(const sem::World& world, ShaderStage stage, std::string glsl, const KernelBuilder& kernel,
                       const HazardInstrumentation* hazards) const;

  const sem::Model& model_;
  const SourceManager& sources_;
  const graph::Variant& variant_;
  const graph::ShaderGraph& graph_;
  const sem::Pipeline& pipeline_;
  const StrategyRegistry& strategies_;
  DiagnosticList& diags_;
  KernelOptions options_;
  InterfaceAllocation interfaces_;
  std::string currentWorld_;
};

KernelValue KernelGenerator::value(sem::ComponentId id, const std::map<sem::ComponentId, std::string>& names) const {
  const sem::Component& c = *graph_.node(id).component;
  KernelValue v{id, c.name, names.at(id), c.type, {}};
  for (const ast::Attribute* a : c.attributes) v.attributes.emplace_back(a->name, a->value.value_or(""));
  for (const auto& attribute : variant_.attributes(id)) v.attributes.push_back(attribute);
  return v;
}

std::vector<sem::ComponentId> KernelGenerator::byName(const std::set<sem::ComponentId>& ids) const {
  std::vector<sem::ComponentId> sorted(ids.begin(), ids.end());
  std::sort(sorted.begin(), sorted.end(), [&](sem::ComponentId a, sem::ComponentId b) {
    return graph_.node(a).component->name < graph_.node(b).component->name;
  });
  return sorted;
}

// Producers first, ties by name: an order that depends only on what this
// kernel computes, not on component ids, which differ between shaders that
// share a locked world.
std::vector<sem::ComponentId> KernelGenerator::canonicalOrder(const std::vector<sem::ComponentId>& computed) const {
  const std::set<sem::ComponentId> pending(computed.begin(), computed.end());
  std::map<sem::ComponentId, uint32_t> waiting;
  std::map<sem::ComponentId, std::vector<sem::ComponentId>> consumers;
  for (sem::ComponentId id : computed) {
    waiting[id] = 0;
    for (sem::ComponentId dep : graph_.node(id).alternatives[*variant_.choice(id)].definition->dependencies) {
      if (!pending.count(dep)) continue;
      ++waiting[id];
      consumers[dep].push_back(id);
    }
  }
  auto later = [&](sem::ComponentId a, sem::ComponentId b) {
    return graph_.node(a).component->name > graph_.node(b).component->name;
  };
  std::priority_queue<sem::ComponentId, std::vector<sem::ComponentId>, decltype(later)> ready(later);
  for (const auto& [id, count] : waiting) {
    if (count == 0) ready.push(id);
  }
  std::vector<sem::ComponentId> order;
  while (!ready.empty()) {
    const sem::ComponentId id = ready.top();
    ready.pop();
    order.push_back(id);
    for (sem::ComponentId consumer : consumers[id]) {
      if (--waiting[consumer] == 0) ready.push(consumer);
    }
  }
  return order;
}

std::vector<const sem::Function*> KernelGenerator::calledFunctions(
    const std::vector<sem::ComponentId>& computed) const {
  // Callees before callers, each once: GLSL needs a declaration before use.
  std::vector<const sem::Function*> ordered;
  std::set<const sem::Function*> seen;
  std::function<void(const sem::Function*)> visit = [&](const sem::Function* f) {
    if (!seen.insert(f).second) return;
    for (const sem::Function* callee : f->callees) visit(callee);
    ordered.push_back(f);
  };
  for (sem::ComponentId id : computed) {
    const graph::Alternative& alt = graph_.node(id).alternatives[*variant_.choice(id)];
    for (const sem::Function* f : alt.definition->functions) visit(f);
  }
  return ordered;
}

// The structs the kernel's code names, as sema recorded them: those of the
// values it touches, and those its computations and functions declare,
// construct or compute with.
std::set<const sem::Type*> KernelGenerator::usedStructs(const std::set<sem::ComponentId>& touched,
                                                        const std::vector<sem::ComponentId>& computed,
                                                        const std::vector<const sem::Function*>& functions) const {
  std::set<const sem::Type*> used;
  for (sem::ComponentId id : touched) {
    const sem::Type* type = graph_.node(id).component->type;
    while (type->isArray()) type = type->element;
    if (type->isStruct()) used.insert(type);
  }
  for (sem::ComponentId id : computed) {
    const auto& structs = graph_.node(id).alternatives[*variant_.choice(id)].definition->structs;
    used.insert(structs.begin(), structs.end());
  }
  for (const sem::Function* f : functions) used.insert(f->structs.begin(), f->structs.end());
  return used;
}

std::string KernelGenerator::structDeclarations(const std::set<const sem::Type*>& directlyUsed,
                                                const std::map<std::string, std::string, std::less<>>& names) const {
  // A struct is needed when the kernel names it, or a needed struct has a
  // field of its type; declarations follow the source order, which already
  // puts field types first.
  std::set<const sem::Type*> needed;
  for (auto it = model_.structOrder.rbegin(); it != model_.structOrder.rend(); ++it) {
    const sem::Type* s = *it;
    bool used = directlyUsed.contains(s);
    for (const sem::Type* other : needed) {
      for (const sem::StructField& f : other->fields) {
        const sem::Type* base = f.type;
        while (base->isArray()) base = base->element;
        used = used || base == s;
      }
    }
    if (used) needed.insert(s);
  }
  std::string text;
  for (const sem::Type* s : model_.structOrder) {
    if (!needed.count(s)) continue;
    text += fmt::format("struct {} {{\n", names.at(s->structName));
    for (const sem::StructField& f : s->fields) {
      const std::string field = isReservedInGlsl(f.name) ? f.name + "_" : f.name;
      text += fmt::format("    {};\n", declareVariable(f.type, field, names));
    }
    text += "};\n\n";
  }
  return text;
}

// Inputs, one import edge at a time in declaration order; false after E6001.
bool KernelGenerator::emitImports(sem::WorldId w, KernelBuilder& kernel,
                                  const std::map<sem::ComponentId, std::string>& names, GlslWriter& writer) {
  std::map<uint32_t, std::set<sem::ComponentId>> byImport;
  for (const graph::Transfer& t : variant_.world(w).inputs) byImport[t.importIndex].insert(t.component);
  // A locked world sees only what it reads of a producer's record, so its
  // kernel does not depend on what the producer writes for other worlds.
  const auto& locked = graph_.shader().finalizedWorlds;
  const bool isLocked = std::find(locked.begin(), locked.end(), w) != locked.end();
  for (const auto& [importIndex, ids] : byImport) {
    const sem::Import& import = pipeline_.imports[importIndex];
    const Strategy* strategy = strategies_.find(import.strategy.ref->name);
    if (!strategy) {
      fail(fmt::format("no code generator is registered for strategy '{}'", import.strategy.ref->name));
      return false;
    }
    ImportSite site{
        kernel, pipeline_,
        import, {},
        {},     [&, index = importIndex](sem::ComponentId id) { return interfaces_.inputLocation(index, id); },
        {}};
    for (sem::ComponentId id : byName(ids)) site.values.push_back(value(id, names));
    if (pipeline_.worlds[import.from].isAbstract || isLocked) {
      site.producerOutputs = site.values;
    } else {
      for (const Located& l : interfaces_.outputs(import.from)) {
        const sem::Component& c = *graph_.node(l.component).component;
        site.producerOutputs.push_back({l.component, c.name, c.name, c.type, {}});
      }
    }
    for (const ast::ExprPtr& arg : import.strategy.ref->args) site.args.push_back(writer.expr(*arg));
    if (auto emitted = strategy->emitImport(site); !emitted) {
      fail(emitted.error().message);
      return false;
    }
  }
  return true;
}

// Outputs, through the world's export strategy; false after E6001.
bool KernelGenerator::emitExports(sem::WorldId w, const Strategy* exportStrategy, KernelBuilder& kernel,
                                  const std::map<sem::ComponentId, std::string>& names, GlslWriter& writer) {
  const sem::World& world = pipeline_.worlds[w];
  const std::vector<Located>& outputs = interfaces_.outputs(w);
  if (outputs.empty() && !(world.exportStrategy && !world.exportStrategy->ref->args.empty())) return true;
  if (!exportStrategy) {
    fail(fmt::format("no code generator is registered for strategy '{}'", world.exportStrategy->ref->name));
    return false;
  }
  ExportSite site{kernel, pipeline_, world, {}, {}, {}};
  for (const Located& o : outputs) {
    site.values.push_back(value(o.component, names));
    site.locations.push_back(o.location);
  }
  for (const ast::ExprPtr& arg : world.exportStrategy->ref->args) site.args.push_back(writer.expr(*arg));
  if (auto emitted = exportStrategy->emitExport(site); !emitted) {
    fail(emitted.error().message);
    return false;
  }
  return true;
}

std::optional<Kernel> KernelGenerator::generate(sem::WorldId w) {
  const sem::World& world = pipeline_.worlds[w];
  currentWorld_ = world.name;
  const graph::WorldPlan& plan = variant_.world(w);
  const std::vector<Located>& outputs = interfaces_.outputs(w);
  if (plan.computed.empty() && outputs.empty()) return std::nullopt;

  const Strategy* exportStrategy = world.exportStrategy ? strategies_.find(world.exportStrategy->ref->name) : nullptr;
  const std::optional<ShaderStage> stage = worldStage(world, strategies_);
  if (!stage) {
    fail("its export strategy implies no pipeline stage; add [Stage: \"vertex\"], \"fragment\" or \"compute\"");
    return std::nullopt;
  }
  KernelBuilder kernel(world.name, *stage);
  KernelText text;
  GlslNameMaps maps;
  claimNames(plan, outputs, kernel, text, maps);
  GlslWriter writer(model_, sources_, maps, kernel.names());

  if (!emitImports(w, kernel, text.names, writer)) return std::nullopt;
  declareComputed(kernel, text);
  if (!emitExports(w, exportStrategy, kernel, text.names, writer)) return std::nullopt;
  // After every strategy's bindings, so the instrumented kernel binds its
  // resources where the plain one does.
  std::optional<HazardInstrumentation> hazards;
  if (options_.instrumentHazards) {
    hazards.emplace(kernel, instrumentedValues(plan, text));
    writer.probeOperations(&hazards->probe());
  }

  GlslOutput out(world.name + ".glsl");
  writeHeader(out, world, *stage,
              structDeclarations(usedStructs(text.touched, text.computed, text.functions), kernel.structNames()));
  writeDefinitions(out, kernel, text, maps, writer);
  writeMain(out, kernel, text, writer, hazards ? &*hazards : nullptr);
  if (const auto& problem = writer.problem()) {
    fail(problem->message, problem->range);
    return std::nullopt;
  }
  return packageKernel(world, *stage, out.text(), kernel, hazards ? &*hazards : nullptr);
}

void KernelGenerator::claimNames(const graph::WorldPlan& plan, const std::vector<Located>& outputs,
                                 KernelBuilder& kernel, KernelText& text, GlslNameMaps& maps) const {
  // Names first, in a fixed order, so renaming is deterministic: structs,
  // then every component this kernel touches, then functions.
  for (const sem::Type* s : model_.structOrder)
    kernel.structNames()[s->structName] = kernel.names().claim(s->structName);
  text.computed = canonicalOrder(plan.computed);
  text.touched.insert(text.computed.begin(), text.computed.end());
  for (const graph::Transfer& t : plan.inputs) text.touched.insert(t.component);
  for (const Located& o : outputs) text.touched.insert(o.component);
  for (sem::ComponentId id : byName(text.touched)) {
    text.names[id] = kernel.names().claim(graph_.node(id).component->name);
  }
  text.functions = calledFunctions(text.computed);
  for (const sem::Function* f : text.functions) maps.functions[f] = kernel.names().claim(f->name);
  maps.structs = &kernel.structNames();
  maps.component = [this, &names = text.names](std::string_view name) {
    const auto it = graph_.shader().componentByName.find(name);
    if (it != graph_.shader().componentByName.end()) {
      if (auto n = names.find(it->second); n != names.end()) return n->second;
    }
    return std::string(name);
  };
}

void KernelGenerator::declareComputed(KernelBuilder& kernel, KernelText& text) const {
  // The world's computations, producers first. A block body becomes a
  // function, so its locals and returns stay as written.
  for (sem::ComponentId id : text.computed) {
    kernel.declareGlobal(graph_.node(id).component->type, text.names.at(id));
    if (!chosenDecl(id).init) text.helpers[id] = kernel.names().generate(text.names.at(id));
  }
}

const ast::ComponentDecl& KernelGenerator::chosenDecl(sem::ComponentId id) const {
  return *graph_.node(id).alternatives[*variant_.choice(id)].definition->decl;
}

void KernelGenerator::writeHeader(GlslOutput& out, const sem::World& world, ShaderStage stage,
                                  const std::string& structs) const {
  writeLines(out, kGlslVersionLines);
  out.line("#extension GL_GOOGLE_cpp_style_line_directive : require");
  // The header names no shader: shaders that share a locked world share
  // this text byte for byte.
  out.line(fmt::format("// Generated by spirec: pipeline '{}', world '{}' ({} stage). Do not edit.", pipeline_.name,
                       world.name, stageName(stage)));
  out.line("");
  if (stage == ShaderStage::Compute) {
    out.line("layout(local_size_x = 64) in;");
    out.line("");
  }
  writeLines(out, structs);
}

void KernelGenerator::writeDefinitions(GlslOutput& out, const KernelBuilder& kernel, const KernelText& text,
                                       const GlslNameMaps& maps, GlslWriter& writer) const {
  for (const std::string& d : kernel.declarations()) {
    size_t start = 0;
    for (size_t end = d.find('\n'); end != std::string::npos; start = end + 1, end = d.find('\n', start)) {
      out.line(std::string_view(d).substr(start, end - start));
    }
    out.line(std::string_view(d).substr(start));
    out.line("");
  }
  for (const std::string& g : kernel.globals()) out.line(g);
  if (!kernel.globals().empty()) out.line("");
  for (const sem::Function* f : text.functions) {
    writer.function(out, *f, maps.functions.at(f));
    out.line("");
  }
  for (sem::ComponentId id : text.computed) {
    if (!text.helpers.count(id)) continue;
    const std::string& helper = text.helpers.at(id);
    const ast::ComponentDecl& decl = chosenDecl(id);
    out.mapTo(sources_.file(decl.range.file).logicalName, sources_.begin(decl.range).line);
    out.line(fmt::format("{} {}() {{", writer.typeName(graph_.node(id).component->type), helper));
    writer.block(out, *decl.body, 1);
    out.line("}");
    out.mapToKernel();
    out.line("");
  }
}

std::vector<InstrumentedValue> KernelGenerator::instrumentedValues(const graph::WorldPlan& plan,
                                                                   const KernelText& text) const {
  std::vector<InstrumentedValue> values;
  std::set<sem::ComponentId> inputs;
  for (const graph::Transfer& t : plan.inputs) inputs.insert(t.component);
  for (sem::ComponentId id : byName(inputs)) {
    const sem::Component& c = *graph_.node(id).component;
    values.push_back({c.name, text.names.at(id), c.type, false, {}, {}, {}});
  }
  for (sem::ComponentId id : text.computed) {
    const graph::ComponentNode& node = graph_.node(id);
    const graph::Alternative& alt = node.alternatives[*variant_.choice(id)];
    const SourceRange where = alt.definition->decl->range;
    InstrumentedValue v{node.component->name,
                        text.names.at(id),
                        node.component->type,
                        true,
                        graph_.altName(node, *variant_.choice(id)),
                        fmt::format("{}:{}", sources_.file(where.file).logicalName, sources_.begin(where).line),
                        {}};
    for (sem::ComponentId dep : alt.definition->dependencies) v.reads.push_back(graph_.node(dep).component->name);
    values.push_back(std::move(v));
  }
  return values;
}

void KernelGenerator::writeMain(GlslOutput& out, const KernelBuilder& kernel, const KernelText& text,
                                GlslWriter& writer, const HazardInstrumentation* hazards) const {
  out.line("void main() {");
  if (hazards) out.line("    " + hazards->entry());
  for (const std::string& statement : kernel.entry()) out.line("    " + statement);
  for (const std::string& statement : kernel.fetches()) out.line("    " + statement);
  for (sem::ComponentId id : text.computed) {
    const ast::ComponentDecl& decl = chosenDecl(id);
    const SourceRange where = decl.init ? decl.init->range : decl.range;
    if (hazards) out.line("    " + hazards->probe().reset());
    out.mapTo(sources_.file(where.file).logicalName, sources_.begin(where).line);
    std::vector<std::string> before;
    const std::string value = decl.init ? writer.statementExpr(*decl.init, before) : text.helpers.at(id) + "()";
    writer.writeHoisted(out, "    ", before, where);
    out.line(fmt::format("    {} = {};", text.names.at(id), value));
    if (hazards) {
      if (const std::string check = hazards->checkAfter(graph_.node(id).component->name); !check.empty())
        out.line("    " + check);
    }
  }
  out.mapToKernel();
  for (const std::string& statement : kernel.stores()) out.line("    " + statement);
  if (hazards) {
    for (const std::string& statement : hazards->record()) out.line("    " + statement);
  }
  out.line("}");
}

Kernel KernelGenerator::packageKernel(const sem::World& world, ShaderStage stage, std::string glsl,
                                      const KernelBuilder& kernel, const HazardInstrumentation* hazards) const {
  Kernel result;
  result.world = world.name;
  result.stage = stage;
  result.glsl = std::move(glsl);
  reflection::Kernel& r = result.reflection;
  r.world = world.name;
  r.stage = stage;
  r.glslFile = world.name + ".glsl";
  r.spirvFile = world.name + ".spv";
  r.hash = spire::contentHash(result.glsl);
  r.inputs = kernel.inputs();
  r.outputs = kernel.outputs();
  r.blocks = kernel.blocks();
  if (hazards) r.hazards = hazards->reflection();
  r.key = reflection::kernelKey(result.glsl, r);
  return result;
}

}  // namespace

reflection::Variant GeneratedShader::reflection(const graph::Variant& variant) const {
  const graph::ShaderGraph& g = variant.graph();
  reflection::Variant result;
  result.shader = shader;
  result.pipeline = g.pipeline().name;
  for (const sem::World& world : g.pipeline().worlds) {
    result.worlds.push_back({world.name, attributeValue(*world.decl, "Role").value_or("")});
  }
  for (sem::ComponentId c : variant.live()) {
    const graph::ComponentNode& node = g.node(c);
    if (!node.isInput) result.placement.emplace_back(node.component->name, g.altName(node, *variant.choice(c)));
  }
  for (const Kernel& k : kernels) result.kernels.push_back(k.reflection);
  return result;
}

std::optional<GeneratedShader> generateKernels(const sem::Model& model, const SourceManager& sources,
                                               const graph::Variant& variant, const StrategyRegistry& strategies,
                                               DiagnosticList& diags, const KernelOptions& options) {
  GeneratedShader result;
  result.shader = variant.graph().shader().name;
  result.directory = result.shader;
  for (char& c : result.directory) {
    if (c == '<') c = '-';
  }
  result.directory.erase(std::remove(result.directory.begin(), result.directory.end(), '>'), result.directory.end());
  KernelGenerator generator(model, sources, variant, strategies, diags, options);
  const sem::Pipeline& pipeline = variant.graph().pipeline();
  const uint32_t errors = diags.errorCount();
  for (sem::WorldId w : pipeline.topologicalOrder) {
    if (pipeline.worlds[w].isAbstract) continue;
    if (auto kernel = generator.generate(w)) result.kernels.push_back(std::move(*kernel));
    if (diags.errorCount() != errors) return std::nullopt;
  }
  return result;
}

}  // namespace spire::codegen
