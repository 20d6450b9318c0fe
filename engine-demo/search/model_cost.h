// He et al. 2015's static cost of a search level (compiler/simplify's
// variant_cost.h: C = 0.3·C_v + 0.7·C_f + 10·N_var), computed on the module
// a step compiled, for the placement the level or candidate would have.
// The search ranks and orders its chain by it unless told to use measured
// frame time: the paper's model does not move with the machine's noise, so
// a rewrite that saves nothing never looks cheaper by chance.
#pragma once

#include <optional>
#include <string>

#include "driver/shader_library.h"
#include "search/chain.h"

namespace spire::search {

// C of `shader` under `placement` in `library`; nullopt when the placement
// is not a variant of it (a name the module lacks).
std::optional<double> modelCost(const ShaderLibrary& library, const std::string& shader, const Placement& placement);

}  // namespace spire::search
