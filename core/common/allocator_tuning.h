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

// Restarts the program once (execv of its own file with the same arguments: same process id and name) with
// glibc's malloc asking for transparent huge pages (GLIBC_TUNABLES=glibc.malloc.hugetlb=1: glibc reads
// its tunables only when a process starts). Call it first thing in main(). Returns without restarting
// when the tunable is already set (by an earlier start or by the user), when
// MOTIONSTYLE_NO_HUGE_PAGES is set, when the kernel's transparent huge pages are off, or when the
// restart fails.
//
// Why: the networks' prepared kernels and a clip's buffers are tens of MB, first touched page by page:
// 20,000 page faults, half of a one-clip stylize (0.24 s -> 0.13 s with 2 MB pages), and the part of a
// batch that no second core divides (docs/decisions.md).
void restartWithHugePages(char** argv);

}  // namespace motionstyle
