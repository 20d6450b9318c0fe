// Helpers shared by the built-in strategies.
#pragma once

#include <string>
#include <vector>

#include "codegen/memory_layout.h"
#include "codegen/strategy.h"

namespace spire::codegen {

// A signature built in place, for Strategy::signature() implementations.
sem::StrategySignature makeSignature(std::string name, sem::StrategyRole role, std::vector<sem::StrategyParam> params,
                                     std::string summary, sem::ValueTransfer transfer = sem::ValueTransfer::Exact,
                                     bool usesLocations = false, bool carriesOpaque = false);

// The reflected form of a value's type.
reflection::ValueType reflectedType(const sem::Type* type);
// An input's record: the value, its kind, strategy and producing world.
reflection::KernelInput importEntry(const ImportSite& site, const KernelValue& value, reflection::InputKind kind,
                                    std::string_view strategy);
// An output's record, with the value's attributes as hints.
reflection::KernelOutput exportEntry(const KernelValue& value, reflection::OutputKind kind, std::string_view strategy);
// Where the kernel binds a resource at `binding`.
reflection::DescriptorSlot slotAt(const KernelBuilder& kernel, uint32_t binding);

// Declares `values` as members of one interface block and reflects its
// layout; returns the block's binding. `qualifier` is `uniform`,
// `readonly buffer` or `writeonly buffer`. For buffers the members sit in a
// record struct and the block holds a runtime array `records` of it.
struct BlockDeclaration {
  std::string blockName;
  std::string recordType;   // buffers only
  std::string recordsName;  // buffers only
  uint32_t binding = 0;
  std::vector<uint32_t> offsets;  // per value
};
BlockDeclaration declareBlock(KernelBuilder& kernel, const std::string& hint, const std::vector<KernelValue>& values,
                              BlockLayout layout, std::string_view qualifier, std::string_view strategy);

// How emitTextureFetches samples: the sampler type it declares, the GLSL
// coordinate expression it passes to texture(), and what it reflects.
struct TextureFetch {
  std::string samplerType = "sampler2D";
  std::string coordinate;  // e.g. "vert_uv" or "vec3(vert_uv, bakeLayer)"
  std::string uv;          // reflected `uv`: the 2D part of `coordinate`
  std::string layer;       // reflected `layer` (sampler2DArray only)
};

// One sampler per value of `site`, each fetched at `at.coordinate` in the
// consuming kernel and reflected as a texture input of `strategy`. Float
// scalars and vectors only; honours [Encoding: "signed"].
Expected<void, Failure> emitTextureFetches(ImportSite& site, const TextureFetch& at, std::string_view strategy);

// The values of `site` read from a std430 `readonly buffer` of the
// producer's records (site.producerOutputs) at the GLSL expression `index`,
// reflected as buffer members of `strategy`; shared by bufferImport and
// instanceImport.
void emitRecordFetches(ImportSite& site, const std::string& index, std::string_view strategy);

// `flat` where GLSL requires it for integer varyings.
bool needsFlat(const sem::Type* type);
// Types that may cross stages as `in`/`out` variables.
Expected<void, Failure> checkVarying(const KernelValue& value, std::string_view strategy);

}  // namespace spire::codegen

namespace spire::codegen {

// `layout(location = L) out T spire_out_x;` for every exported value, stored
// at the end of main(); shared by standardExport and vertexExport.
Expected<void, Failure> emitOutVariables(ExportSite& site, std::string_view strategy);

// `[Encoding: "signed"]` on a component's declaration or decision line: its
// values lie in [-1, 1] (unit vectors) and are stored remapped to [0, 1], so
// that an unsigned normalized texture (RGBA8, RGB10_A2) can hold them; the
// exporting strategy writes v * 0.5 + 0.5 and textureImport undoes it.
// Whether `value` is so encoded; an error for the encoding on a value that is
// not a float scalar or vector (its value was checked against the attribute
// catalogue).
Expected<bool, Failure> checkEncoding(const KernelValue& value);

}  // namespace spire::codegen
