// He et al. 2015's transition shaders for a search's chain (section 6):
// where the chain's level-of-detail policy switches from one level to the
// next, a variant that blends the two by distance, drawn over the last part
// of the nearer band, so that the switch does not pop.
//
// Each component whose definition differs between the two levels gets a
// variation `C:transitionA_B` = mix(C as level A defines it, C as level B
// defines it, fade); the two definitions are copied into components of
// their own, in their worlds. fade rises from 0 to 1 with a distance that
// the shader computes (by default the eye's distance in world units, as the
// policy measures distances) over the transition's band. At either end the
// transition is one level: mix(a, b, 0) is a, and past the band the policy
// draws level B. A component that is not a float or float vector switches
// halfway (fade < 0.5 ? A : B): mix does not take it.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "driver/shader_library.h"
#include "lod/lod_policy.h"
#include "search/chain.h"
#include "sema/semantic_model.h"
#include "support/expected.h"

namespace spire::search {

// The distance the transitions' fades are a function of, in the policy's
// units: a Spire expression over the derived shader's components, and the
// engine values it reads that the shader must declare for it.
struct FadeDistance {
  std::string expression;
  std::string declarations;  // Spire source; empty when the shader reads them already
};

// The eye's distance from each point in world units, the distance that the
// policy's bands measure: `cameraPosWorld` and `matModel` (the engine's
// world-space eye and model matrix) with the mesh's `vert_pos`. A distance
// in model space would blend a scaled instance over a scaled band. Those of
// the two that the shader does not read are declared in the world it reads
// the engine's other per-frame values from; a shader that reads none, or
// reads one under another type, has no such distance.
Expected<FadeDistance, Failure> eyeDistanceInWorld(const sem::Shader& shader);

struct TransitionShape {
  // The part of the nearer band, from its start to its edge, over which the
  // fade rises: the transition's band is its last `width`.
  double width = 0.2;
  FadeDistance distance;
};

struct Transition {
  size_t from = 0;  // chain levels: the nearer band's and the farther one's
  size_t to = 0;
  size_t band = 0;            // the policy's band whose far edge it blends across
  double nearDistance = 0.0;  // fade 0 (level `from`) up to here
  double farDistance = 0.0;   // fade 1 (level `to`) from here: the nearer band's edge
  std::string definitions;    // Spire source, for the chain's derived shader
  Placement placement;        // what its decision file says
};

// A chain's transitions and the definitions they share: the distance, as
// the component `spireTransitionDistance`, and what it declares.
struct Transitions {
  std::string shared;
  std::vector<Transition> list;
};

// Every transition's definitions, for the chain's derived shader; none
// without transitions.
std::string transitionDefinitions(const Transitions& transitions);

// The transition's decision file: "transition1_3.decisions", and its text.
std::string transitionFileName(const Transition& transition);
std::string transitionDecisionText(const Transition& transition, const ModuleHeader& header);

// The transitions at each switch of `policy` from one chain level to
// another. The policy's levels are the chain's decision files
// (`levelK.decisions`, for the shader `derived`); `chainModule` is the
// chain's module compiled, which the definitions are copied from.
Expected<Transitions, Failure> chainTransitions(const Chain& chain, const lod::LodPolicy& policy,
                                                const ShaderLibrary& chainModule, const std::string& derived,
                                                const TransitionShape& shape);

// `policy` with a band for each transition, between the nearer band (which
// now ends at the transition's near distance) and the farther one: it draws
// the instances of `derived` with the transition's decision file in
// `folder`.
lod::LodPolicy withTransitions(lod::LodPolicy policy, const std::vector<Transition>& transitions,
                               const std::string& derived, const std::filesystem::path& folder);

}  // namespace spire::search
