// The level-of-detail chain a greedy search builds (He et al. 2015): level 0
// is the author's shader, and level k is level k-1 with one more rewrite, so
// rewrites accumulate. Each level is a placement of the derived shader's
// components, whose rewritten ones are named variations of it
// (`albedo:level2`), so a decision file selects a level like any variation
// a person wrote.
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "graph/decision_file.h"

namespace spire::search {

// component -> "World" or "World:variation", every live component: a
// variant as a decision file states it.
using Placement = std::vector<std::pair<std::string, std::string>>;

// One step of a chain, or a candidate for one: a rewrite of a component's
// current definition under a variation name (`albedo:level2`), or a move of
// the component to another world of the pipeline with its definition as it
// is (He et al.'s move to vertex and move to parameter stage, which in
// Spire are world choices: any world the choice file offers), carrying the
// components that cannot stay where they are with it.
struct Rewriting {
  std::string component;  // "albedo"
  std::string from;       // the definition it rewrites or moves: "albedo", "albedo:level1"
  std::string variation;  // its own name: "level2"; a move's is the definition's it moves
  std::string rule;       // "constant-operand", ..., "move"
  std::string before;     // the source it replaced; a move's: the placement it leaves
  std::string after;      // a move's: the placement it takes, and those of what it carries
  std::string text;       // the whole definition, named component:variation; empty for a move
  Placement moved;        // a move's new placements, its component's first; empty for a rewrite
};

// The rule name of a move, and whether a step is one.
inline constexpr const char* kMoveRule = "move";
inline bool isMove(const Rewriting& r) { return !r.moved.empty(); }

// `placement` after `step`: a rewrite's component as its variation in the
// same world, or the placements a move sets.
Placement applied(Placement placement, const Rewriting& step);
// "albedo" or "albedo:level2": the definition a step makes or moves.
std::string definitionName(const Rewriting& step);
// `placement` as the decision lines of `shader`: what a level's decision
// file says, and what its cost is computed for.
graph::DecisionFile placementDecisions(const std::string& shader, const Placement& placement);

// The placement of `component` in `placement`: "Fragment:level2", or ""
// when it has none.
std::string placementOf(const Placement& placement, const std::string& component);

// The variation a placement names ("ggx" of "Fragment:ggx"), or "".
std::string variationOf(const std::string& placement);
// The world a placement names ("Fragment" of "Fragment:ggx").
std::string worldOf(const std::string& placement);

struct Level {
  double error = 0.0;      // RMSE against level 0 over every camera view and parameter sample
  double timeRatio = 1.0;  // frame time over level 0's, frame for frame
  double frameMs = 0.0;    // timeRatio times level 0's median frame time
  std::string kernels;     // its kernels' hashes: equal ones are the same program
  Placement placement;
  double modelCost = 0.0;  // He et al. 2015's C of its program (search/model_cost.h)
};

// What a search ranks its candidates and orders its chain by.
enum class CostKind {
  Model,  // He et al.'s static C = 0.3·C_v + 0.7·C_f + 10·N_var (the default)
  Time,   // the frame time measured against level 0 (the time ratio)
};

// What a level costs, lower is cheaper: the one function a search ranks and
// orders its levels by.
double costOf(const Level& level, CostKind kind);

struct Chain {
  std::vector<Level> levels;     // levels[0] is the author's shader
  std::vector<Rewriting> steps;  // steps[k - 1] made levels[k]
  std::string stopReason;        // why there is no further level
  std::vector<std::string> log;  // what each step measured and chose, for the report
  // What errors and times are measured against: "level 0", or the
  // reference decision file's variant (`--reference`), for the outputs.
  std::string measuredAgainst = "level 0";
};

struct ModuleHeader {
  std::string usingPath;  // the shader's source, relative to the module's folder
  std::string base;       // "Terrain"
  std::string derived;    // "TerrainSearch"
};

// The derived shader holding `definitions` (each with a comment naming the
// rewrite it adds to the definition it comes from), then `more` (Spire
// source of further definitions: the chain's transitions), as Spire source.
std::string chainModuleText(const ModuleHeader& header, const std::vector<const Rewriting*>& definitions,
                            const std::string& more = {});
// The same with every step of `chain`.
std::string chainModuleText(const ModuleHeader& header, const Chain& chain, const std::string& more = {});

}  // namespace spire::search
