// gsse-mesh's memory allocator settings: glibc's malloc with transparent huge pages and memory
// kept across the run instead of given back to the kernel (docs/design-decisions.md, "The CLI
// runs glibc's malloc with huge pages").
//
// Why: the mesher allocates and frees whole-mesh arrays every refinement round; with glibc's
// defaults each large one is mapped afresh and faulted in 4 KiB at a time, and page faults are
// dear on virtual machines. Measured (docs/benchmarks.md, forty-seventh part): 13,600 of them on
// the 1e5 trench, 37,900 on the 6e5 MOSFET, whose wall time fell by nearly half without them.
//
// How: glibc reads these settings (tunables) only from the environment when a process starts,
// so main() sets GLIBC_TUNABLES and executes the same binary again, once, before anything else
// (no file read, no thread started). Left alone: a process whose GLIBC_TUNABLES is already set
// (the user's own settings, or the second start), one with LD_PRELOAD (an instrumented run:
// valgrind, heaptrack), GSSE_MALLOC=system, and a sanitizer build (GCC's __SANITIZE_ADDRESS__ or
// __SANITIZE_THREAD__: the sanitizer's allocator is its own). If the executable cannot be run
// again (no /proc), the run goes on with the defaults.
#pragma once

#include <unistd.h>

#include <cstdlib>
#include <cstring>

namespace gsse::apps {

/// The settings: huge pages for the heaps (hugetlb=1: madvise, which the kernel's default
/// "madvise" mode honours), no trimming of the heap top (1 GiB), the heap grown 64 MiB at a time,
/// and blocks up to 32 MiB (glibc's largest allowed) taken from the heap rather than mapped alone.
inline constexpr const char* malloc_tunables =
    "glibc.malloc.hugetlb=1:glibc.malloc.trim_threshold=1073741824:glibc.malloc.top_pad=67108864:"
    "glibc.malloc.mmap_threshold=33554432";

/// Call first in main(): returns only if the process keeps its allocator as it is.
inline void tune_allocator(char** argv) {
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
  (void)argv;  // the sanitizer's allocator: glibc's tunables do not apply, a second start only costs
#elif defined(__linux__) && defined(__GLIBC__)
  if (std::getenv("GLIBC_TUNABLES") || std::getenv("LD_PRELOAD")) return;
  if (const char* m = std::getenv("GSSE_MALLOC"); m && std::strcmp(m, "system") == 0) return;
  if (::setenv("GLIBC_TUNABLES", malloc_tunables, 1) != 0) return;
  ::execv("/proc/self/exe", argv);
  ::unsetenv("GLIBC_TUNABLES");  // not run again: go on as started
#else
  (void)argv;
#endif
}

}  // namespace gsse::apps
