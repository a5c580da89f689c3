// Transparent huge pages for the whole heap of a drawing process: glibc's malloc advises the
// memory it takes from the system for huge pages (MADV_HUGEPAGE) when the tunable
// glibc.malloc.hugetlb=1 is set (glibc 2.35 and later; read once, at the process's start), so the
// heap's first touch takes one page fault per 2 MiB instead of one per 4 KiB, the GL driver's
// buffers (llvmpipe's framebuffers, the DM pass's vertices) included, which no allocator of
// penink's reaches (core/big_allocator.hpp advises penink's own large arrays). Measured on the
// 2-core machine (kernel THP mode "madvise", Debian's default), `penink render DEM --width 1000
// --height 750 -o x.svg -o x.png`, the other core loaded: jacksboro refined 29 times (117 M cells,
// warm) 120 k page faults and 6.3-6.7 s of user CPU without it, 23 k and 5.6-5.7 s with it, 25 MB
// more resident at peak; the bundled volcano 28 k and 0.85-0.94 s, 9 k and 0.68-0.78 s, 15 MB more.
#pragma once
#include <string>

namespace penink {

// Starts this program again (execv of /proc/self/exe, the same arguments and environment) with
// glibc.malloc.hugetlb=1 added to GLIBC_TUNABLES, unless it is there already (the restarted
// process), PENINK_HUGE_PAGES is 0, the kernel never gives transparent huge pages, or the process
// runs under valgrind (its preload in LD_PRELOAD: the restart would leave it). Returns where it does
// not restart or the restart fails (the environment then as it was); the caller goes on as it is.
// Call first in main, before any thread starts.
void restart_with_huge_page_malloc(char** argv) noexcept;

// GLIBC_TUNABLES for the restart from its value now (`current`, null when unset): it with
// glibc.malloc.hugetlb=1 appended (':' between tunables); empty when it already names that tunable.
std::string huge_page_tunables(const char* current);
// Whether the kernel gives transparent huge pages to memory advised for them (its mode "always" or
// "madvise", not "never"; false where it does not say).
bool kernel_gives_huge_pages();
// Whether this process's GLIBC_TUNABLES names glibc.malloc.hugetlb (it was restarted so, or set by hand).
bool heap_in_huge_pages();

}  // namespace penink
