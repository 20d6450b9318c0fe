// How the spirec process grows its heap. glslang builds its built-in symbol
// tables (~30 MB) in every process that makes SPIR-V; on 4 KiB pages that is
// ~7,000 page faults, a large share of a short spirec run. This is the
// in-process equivalent of GLIBC_TUNABLES=glibc.malloc.hugetlb=1, which a
// build system should not have to set. Built only with SPIRE_HUGE_PAGE_HEAP
// (off under the sanitizers, which replace malloc).
#pragma once

#include <string>

namespace spire {

// Makes the main heap grow in one large step backed by transparent huge
// pages where the kernel allows them (THP "madvise" or "always"). Call once,
// first thing in main, before any thread starts; a no-op without glibc or
// without SPIRE_HUGE_PAGE_HEAP. Only for executables: it changes
// process-wide malloc settings.
void useHugePageHeap();

// One line saying whether this process's heap is advised for huge pages, as
// the kernel reports it (/proc/self/smaps): "huge-page heap: on", "off (...)"
// or "unavailable (...)". spirec prints it for `spirec --heap-report`, a
// hidden diagnostic that tests/driver checks against the build's setting.
std::string describeHeap();

}  // namespace spire
