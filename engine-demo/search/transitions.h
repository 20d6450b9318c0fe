// He et al. 2015's transition shaders for a search's chain (section 6):
// where the chain's level-of-detail policy switches from one level to the
// next, a variant that blends the two by distance, drawn over the last part
// of the nearer band, so that the switch does not pop.
//
// Each component whose definition differs between the two levels gets a
// variation `C:transitionA_B` = mix(C as level A defines it, C as level B
// defines it, fade); the two definitions are copied into components of
// their own, in their worlds. fade rises from 0 to 1 with a distance that
// the shader computes (by default `length(cameraPos - vert_pos)`, the eye's
// distance in model space) over the transition's band. At either end the
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
#include "support/expected.h"

namespace spire::search {

struct TransitionShape {
  // The part of the nearer band, from its start to its edge, over which the
  // fade rises: the transition's band is its last `width`.
  double width = 0.2;
  // A Spire expression over the derived shader's components: the distance
  // the fade is a function of, in the policy's units.
  std::string distance = "length(cameraPos - vert_pos)";
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

// Every transition's definitions, for the chain's derived shader.
std::string transitionDefinitions(const std::vector<Transition>& transitions);

// The transition's decision file: "transition1_3.decisions", and its text.
std::string transitionFileName(const Transition& transition);
std::string transitionDecisionText(const Transition& transition, const ModuleHeader& header);

// The transitions at each switch of `policy` from one chain level to
// another. The policy's levels are the chain's decision files
// (`levelK.decisions`, for the shader `derived`); `chainModule` is the
// chain's module compiled, which the definitions are copied from.
Expected<std::vector<Transition>, Failure> chainTransitions(const Chain& chain, const lod::LodPolicy& policy,
                                                            const ShaderLibrary& chainModule,
                                                            const std::string& derived, const TransitionShape& shape);

// `policy` with a band for each transition, between the nearer band (which
// now ends at the transition's near distance) and the farther one: it draws
// the instances of `derived` with the transition's decision file in
// `folder`.
lod::LodPolicy withTransitions(lod::LodPolicy policy, const std::vector<Transition>& transitions,
                               const std::string& derived, const std::filesystem::path& folder);

}  // namespace spire::search
