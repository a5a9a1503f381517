#pragma once
// Process-wide allocator setting for programs that run the networks (motionstyle-cli, the app, the
// benchmarks): called once at the start of main(), never by the library itself.
//
// Why: every network layer returns matrices of a few hundred kB to tens of MB. glibc serves blocks
// over 128 kB with a fresh mmap and unmaps them on free, so each training step page-faulted and
// zero-filled its temporaries anew (a 16 x 240 style step touches ~100 MB of them). Keeping freed
// memory in the heap instead made a 100-epoch style training 5-10 % faster and its setup twice as
// fast (tests/bench/nn, README). The price: the process keeps its peak heap until it exits.

namespace motionstyle {

// Serves large blocks from the heap and stops returning freed memory to the system (glibc's
// M_MMAP_THRESHOLD and M_TRIM_THRESHOLD). Does nothing on other C libraries.
void keepLargeAllocationsInHeap();

}  // namespace motionstyle
