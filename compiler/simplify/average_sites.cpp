#include "simplify/average_sites.h"

#include <fmt/format.h>

#include <algorithm>
#include <optional>

#include "simplify/cost_model.h"
#include "simplify/syntax_walk.h"

namespace spire::simplify {
namespace {

bool within(const SourceRange& inner, const SourceRange& outer) {
  return inner.file == outer.file && inner.begin >= outer.begin && inner.end <= outer.end;
}

class SiteFinder {
 public:
  SiteFinder(const sem::Model& model, const SourceManager& sources, const ast::ComponentDecl& decl)
      : model_(model), sources_(sources), decl_(decl), costs_(model), cost_(costs_.definition(decl)) {}

  // Every site in `e` (the definition's expression) or `s` (a top-level
  // statement), whose value the probe computes after `before`, the source
  // of the statements ahead of it ("" for the expression).
  void expr(const ast::Expr& e) {
    walk([&](SyntaxWalker& w) { w.expr(&e); }, std::nullopt);
  }
  void stmt(const ast::Stmt& s, const std::string& before) {
    walk([&](SyntaxWalker& w) { w.stmt(&s); }, before);
  }
  std::vector<AverageSite> take() { return std::move(sites_); }

 private:
  template <class Walk>
  void walk(const Walk& run, const std::optional<std::string>& before) {
    std::vector<SourceRange> written;  // assigned or incremented: not values to replace
    SyntaxWalker walker([&](const ast::Expr& e) { consider(e, before, written); }, [](const ast::Stmt&) {});
    run(walker);
  }

  void consider(const ast::Expr& e, const std::optional<std::string>& before, std::vector<SourceRange>& written) {
    if (const auto* a = ast::dyn_cast<ast::AssignExpr>(&e)) {
      written.push_back(a->target->range);
      return;
    }
    if (const auto* u = ast::dyn_cast<ast::UnaryExpr>(&e);
        u && u->op >= ast::UnaryOp::PreIncrement && u->op <= ast::UnaryOp::PostDecrement) {
      written.push_back(u->operand->range);
      return;
    }
    const sem::Type* type = model_.typeOf(e);
    const std::optional<size_t> scalars = type ? floatScalarCount(type->name()) : std::nullopt;
    if (!scalars || isConstantExpr(model_, e)) return;
    if (std::any_of(written.begin(), written.end(), [&](const SourceRange& r) { return within(e.range, r); })) return;
    const std::string source(sources_.text(e.range));
    AverageSite site;
    site.rewrite = {kAverageRule, e.range, "", source, type->name()};
    site.rewrite.saving = cost_ - costs_.definition(decl_, {&e, {}, std::nullopt});
    site.scalars = *scalars;
    site.probe =
        before ? fmt::format("{{\n{}        return ({});\n    }}", *before, source) : fmt::format("= ({});", source);
    sites_.push_back(std::move(site));
  }

  const sem::Model& model_;
  const SourceManager& sources_;
  const ast::ComponentDecl& decl_;
  CostModel costs_;
  int64_t cost_ = 0;
  std::vector<AverageSite> sites_;
};

bool valueStatement(const ast::Stmt& s) {
  return s.kind == ast::StmtKind::VarDecl || s.kind == ast::StmtKind::Expr || s.kind == ast::StmtKind::Return;
}

}  // namespace

std::vector<AverageSite> proposeAverageSites(const sem::Model& model, const SourceManager& sources,
                                             const ast::ComponentDecl& decl) {
  SiteFinder finder(model, sources, decl);
  if (decl.init) finder.expr(*decl.init);
  if (const auto* body = ast::dyn_cast<ast::BlockStmt>(decl.body.get())) {
    std::string before;
    for (const ast::StmtPtr& s : body->statements) {
      if (valueStatement(*s)) finder.stmt(*s, before);
      before += fmt::format("        {}\n", sources.text(s->range));
    }
  }
  std::vector<AverageSite> sites = finder.take();
  std::vector<Rewrite> rewrites;
  for (const AverageSite& site : sites) rewrites.push_back(site.rewrite);
  std::vector<AverageSite> ranked;
  for (size_t i : rankRewrites(rewrites)) ranked.push_back(std::move(sites[i]));
  return ranked;
}

std::optional<size_t> floatScalarCount(const std::string& type) {
  if (type == "float") return 1;
  if (type == "vec2") return 2;
  if (type == "vec3") return 3;
  if (type == "vec4") return 4;
  return std::nullopt;
}

std::string averageReplacement(const std::string& type, const std::vector<double>& values) {
  std::vector<std::string> parts;
  // Nine significant digits read back to the same float.
  for (double v : values) parts.push_back(fmt::format("{:.9g}", static_cast<float>(v)));
  return fmt::format("{}({})", type, fmt::join(parts, ", "));
}

}  // namespace spire::simplify
