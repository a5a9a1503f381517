#include "common/allocator_tuning.h"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace motionstyle {

void keepLargeAllocationsInHeap() {
#if defined(__GLIBC__)
  // 1 GiB: above any matrix the networks allocate, so none of them is mmap'ed. Setting either
  // threshold also turns off glibc's dynamic adjustment of both.
  constexpr int kThreshold = 1 << 30;
  mallopt(M_MMAP_THRESHOLD, kThreshold);
  mallopt(M_TRIM_THRESHOLD, kThreshold);
#endif
}

}  // namespace motionstyle
