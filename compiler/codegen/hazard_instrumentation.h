// Instrumented kernels, for finding where a variant goes NaN or Inf
// (CompileOptions::instrumentHazards). After each value a kernel computes,
// the kernel checks it; at the end of main() each invocation records the
// first value whose check failed, and the first invocation to fail on a
// value also dumps every numeric value the kernel holds, so the engine can
// name the component and show what its inputs were there. Inside component
// and function bodies the operations that can make NaN or Inf are checked
// too (OperationProbe), so a hazard also names the first of them to fail. The layout is
// reflection::HazardRecord's. The checks and the stores change what a
// kernel costs, so instrumented kernels are for diagnosis, never timing.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "codegen/kernel_builder.h"
#include "codegen/operation_probe.h"
#include "reflection/reflection.h"
#include "sema/type.h"

namespace spire::codegen {

// A value of the kernel, as the instrumentation sees it.
struct InstrumentedValue {
  std::string component;
  std::string glslName;
  const sem::Type* type = nullptr;
  bool computed = false;   // computed here (checked), or an input (only dumped)
  std::string definition;  // computed: "World" or "World:variation"
  std::string source;      // computed: "file:line" of its definition
  std::vector<std::string> reads;
};

class HazardInstrumentation {
 public:
  // Declares the record buffer and the check functions in `kernel`, at the
  // next binding of its set. `values`: the inputs, then the computed values
  // in evaluation order.
  HazardInstrumentation(KernelBuilder& kernel, const std::vector<InstrumentedValue>& values);

  // The statements that declare the invocation's hazard, first in main().
  std::string entry() const;
  // Writes the checks of operations in the bodies written from now on.
  OperationProbe& probe() { return probe_; }
  const OperationProbe& probe() const { return probe_; }
  // The check after `component` is assigned; empty for a value with no float.
  std::string checkAfter(std::string_view component) const;
  // The statements that record the invocation, last in main().
  std::vector<std::string> record() const;
  // Complete once every body has been written through the probe.
  reflection::HazardRecord reflection() const;

 private:
  struct Checked {
    std::string component;
    uint32_t code = 0;
    std::string kindExpression;  // 0, kHazardInf or kHazardNaN
  };
  void declare(KernelBuilder& kernel);

  ShaderStage stage_;
  bool earlyTests_ = false;
  std::string buffer_;
  std::string hazard_;     // the invocation's code << 2 | kind
  std::string operation_;  // the probe's operation when `hazard_` was set
  std::string index_;
  std::string slot_;
  std::string kindFunction_;
  std::vector<Checked> checked_;
  std::vector<std::pair<std::string, uint32_t>> dumps_;  // GLSL float expression, index in a slot's dump
  reflection::HazardRecord record_;
  OperationProbe probe_;
};

}  // namespace spire::codegen
