// Backing the heap with 2 MB pages. A crowd's thousands of worlds each touch a few kilobytes per tick,
// spread over hundreds of megabytes of heap: with 4 KB pages nearly every world the tick reaches costs a
// TLB miss (a page walk, longer still in a virtual machine), and 2 MB pages leave a few hundred pages for
// the whole crowd. Linux only; elsewhere, or where the kernel declines, nothing changes. Memory contents
// never change either way, so results do not depend on it.
#pragma once

#include <cstdint>

namespace prep {

struct HugePageReport {
  std::uintptr_t begin = 0, end = 0;  // the part of the heap asked for: whole 2 MB pages, [begin, end)
  bool advised = false;               // the kernel took the advice for that range (MADV_HUGEPAGE)
  bool collapsed = false;             // and moved what was there onto huge pages now (MADV_COLLAPSE)
};

// Asks the kernel to back the heap as it is now (the program break's region, where small allocations
// live) with huge pages. Call it once the big structures are built: the heap the program gains afterwards
// is not covered, and the collapse copies what the range holds.
HugePageReport back_heap_with_huge_pages();

// Kilobytes of this process's memory on transparent huge pages now (0 where unknown).
long huge_page_kb();

}  // namespace prep
