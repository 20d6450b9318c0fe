// Import/export strategies as plug-ins (paper section 5.1, Table 1). A
// strategy generates the code on one side of a world boundary: an import
// strategy declares and fetches values in the consuming kernel, an export
// strategy declares and stores them in the producing kernel. Both add the
// reflection entries an engine needs to connect the two.
//
// Adding a strategy: one new file implementing Strategy, plus one
// registration line in strategy_registry.cpp (or a call to
// StrategyRegistry::add from the embedding application).
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "codegen/kernel_builder.h"
#include "sema/strategy_catalog.h"
#include "support/expected.h"

namespace spire::codegen {

// The values imported over one import edge into one kernel.
struct ImportSite {
  KernelBuilder& consumer;
  const sem::Pipeline& pipeline;
  const sem::Import& import;
  std::vector<KernelValue> values;
  // The strategy's arguments as GLSL expressions in the consumer kernel.
  std::vector<std::string> args;
  // The location the producer world gave each value (standardImport).
  std::function<uint32_t(sem::ComponentId)> producerLocation;
  // Everything the producer world exports, in its order: what a producer
  // writes as one record (bufferExport) and a consumer must read back with
  // the same layout. For an abstract producer (the engine), and for a
  // consumer world the shader's bases finalize, it is `values`: the engine
  // then lays the records out for this consumer.
  std::vector<KernelValue> producerOutputs;
};

// The values a world exports, in location order.
struct ExportSite {
  KernelBuilder& producer;
  const sem::Pipeline& pipeline;
  const sem::World& world;
  std::vector<KernelValue> values;
  std::vector<uint32_t> locations;  // parallel to values
  std::vector<std::string> args;    // the export strategy's arguments as GLSL
};

class Strategy {
 public:
  virtual ~Strategy() = default;
  virtual const sem::StrategySignature& signature() const = 0;
  // For export strategies: the pipeline stage a world exporting this way
  // runs in (vertexExport: vertex, bufferExport: compute, ...).
  virtual std::optional<ShaderStage> stage() const { return std::nullopt; }
  // An error when the strategy cannot carry the values (e.g. an integer
  // through a texture); code generation then stops.
  virtual Expected<void, Failure> emitImport(ImportSite&) const { return {}; }
  virtual Expected<void, Failure> emitExport(ExportSite&) const { return {}; }
};

}  // namespace spire::codegen
