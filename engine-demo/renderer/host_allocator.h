// lavapipe rasterizes on the CPU and allocates its per-frame working memory
// with malloc. glibc serves large blocks with mmap until a large free raises
// its dynamic mmap threshold; until then every frame pays for fresh pages
// (measured here: the same Terrain frame took 40 ms before the engine's first
// 8 MB bake readback was freed and 13 ms after). Timings would then depend on
// what ran earlier in the process, so the engine fixes the thresholds first.
#pragma once

namespace spire::engine {

// Call once at startup, before any Vulkan work. Idempotent.
void stabilizeHostAllocator();

}  // namespace spire::engine
