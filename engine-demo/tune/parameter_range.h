// Material parameters the tuner samples (--param NAME=MIN:MAX): the error of
// a variant that looks right at the scene's values may not be at others, so
// the tuner measures it over samples of each parameter's range. A number
// parameter takes values in the range; a texture parameter is replaced by
// solid textures whose channels take them (Pellacini 2005's extremes for an
// input that varies over the surface).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "scene/scene_file.h"
#include "support/expected.h"
#include "tune/tuner.h"

namespace spire::tune {

// A value an input takes alone in a per-input corner sample besides its
// minimum and maximum (--extremes: a texture's own darkest and brightest
// texels, inside its solid 0 to 1 range).
struct Corner {
  std::string kind;  // how the report names it: "texture-min", "texture-max"
  std::vector<double> values;
};

struct ParameterRange {
  std::string component;
  // Per component of the value (4, RGBA, for a texture).
  std::vector<double> minimum;
  std::vector<double> maximum;
  bool texture = false;  // the material binds a texture: samples are solid colors
  std::vector<Corner> extraCorners;
};

// Parameter samples as in Pellacini 2005: every parameter at its minimum,
// every one at its maximum, then `randomCount` uniform draws (seeded, so
// workers and reruns agree).
std::vector<ParameterSample> parameterSamples(const std::vector<ParameterRange>& ranges, uint32_t randomCount,
                                              uint64_t seed);

// `count` uniform draws of every range's values, seeded.
std::vector<ParameterSample> randomSamples(const std::vector<ParameterRange>& ranges, uint32_t count, uint64_t seed);

// Parses NAME=MIN:MAX against the instance's material, which gives the
// value's arity (every component of a vector gets the same range). A
// texture input may be given as NAME alone: its range is then the
// texture's own, per channel, from its darkest to its brightest texel.
Expected<ParameterRange, Failure> parseParameter(const std::string& text, const scene::InstanceDesc& instance,
                                                 const scene::SceneFile& scene);

// parseParameter of every text of a command line's --param options.
Expected<std::vector<ParameterRange>, Failure> parseParameters(const std::vector<std::string>& texts,
                                                               const scene::InstanceDesc& instance,
                                                               const scene::SceneFile& scene);

// The texture bound to `binding`'s range, per channel from its smallest to
// its largest texel.
Expected<ParameterRange, Failure> textureRange(const std::string& text, const scene::MaterialBinding& binding,
                                               const scene::SceneFile& scene);

}  // namespace spire::tune
