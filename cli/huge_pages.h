// Transparent huge pages for the crowdbake executable's large blocks.
//
// A hero character's bake allocates and frees hundreds of megabytes in stage-sized arrays
// (quadrics, posed positions, sample plans, trees). With 4 KiB pages, page faults and TLB
// misses cost about a quarter of the 1,000,000-triangle bake (docs/accuracy.md, "At
// scale"), and most kernels give 2 MiB pages only to memory advised with MADV_HUGEPAGE.
// This executable replaces operator new: a block of 1 MiB or more is still malloc's, freed
// by the default operator delete, and advised. Nothing else changes; packs are the same
// bytes. A program that links the pipeline library gets the same effect by running with
// GLIBC_TUNABLES=glibc.malloc.hugetlb=1.
#pragma once

namespace crowdbake::cli {

// Call first in main(): blocks of 1 MiB and more get a mapping of their own (malloc's mmap
// threshold, fixed), so the advice reaches them before their pages are first touched.
void prefer_huge_pages();

}  // namespace crowdbake::cli
