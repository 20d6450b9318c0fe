// Reading back instrumented kernels (CompileOptions::instrumentHazards):
// every instrumented kernel the renderer binds, in a bake, a frame pass or a
// draw, gets a record buffer from the collector, and after the frame the
// collector turns the records into hazards: which component went NaN or Inf,
// in which world and definition, at how many pixels, vertices or texels, and
// what the values it reads were at the first of them.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "renderer/error.h"
#include "renderer/variant_program.h"
#include "vk/buffer.h"

namespace spire::engine {

struct Hazard {
  std::string instance;    // which object: "instance 0 (UserDivide)"
  std::string world;       // the kernel's world
  std::string component;   // the first value to go non-finite there
  std::string definition;  // "World" or "World:variation"
  std::string source;      // "file:line" of the definition
  bool nan = false;        // NaN; otherwise Inf
  uint64_t count = 0;      // invocations whose first non-finite value it is
  std::string unit;        // "px", "texels" or "vertices"
  std::string where;       // the first invocation: "pixel (3, 7)", "vertex 12", "texel (40, 2)"
  // The first checked operation in its definition (or a function it calls)
  // to go non-finite there, and where that is ("file:line:col"); empty
  // when none did, as when an unchecked one (a product) overflowed.
  std::string operation;
  std::string operationSource;
  // The values its definition reads, at that invocation, as the kernel held
  // them; those the kernel could not dump are left out.
  std::vector<std::pair<std::string, std::vector<double>>> reads;
  // One of those values was already NaN or Inf: the hazard came in with it.
  bool inherited = false;
};

// "scaled (Vertex) went Inf in 25 vertices at `color / divisor`
// (divide.spire:18:20); divisor = 0 there"
std::string describeHazard(const Hazard& hazard);

class HazardCollector {
 public:
  // Names the object whose kernels are bound next.
  void setInstance(std::string label) { instance_ = std::move(label); }
  // A zeroed record buffer for `kernel` (which must be instrumented), for
  // `invocations` invocations; a fragment kernel's target is `width` wide.
  Expected<VkBuffer> attach(const vk::Context& ctx, const KernelProgram& kernel, uint32_t invocations, uint32_t width);
  bool empty() const { return records_.empty(); }
  // Every hazard recorded so far, origins first (those not inherited), then
  // by count.
  std::vector<Hazard> read() const;

 private:
  struct Record {
    std::string instance;
    std::string world;
    reflection::HazardRecord layout;
    std::string unit;
    uint32_t invocations = 0;
    uint32_t width = 0;
    std::unique_ptr<vk::Buffer> buffer;
  };
  void readRecord(const Record& record, std::vector<Hazard>& out) const;

  std::string instance_;
  std::vector<Record> records_;
};

}  // namespace spire::engine
