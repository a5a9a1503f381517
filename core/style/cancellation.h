#pragma once
// Cooperative cancellation shared by the long-running operations of core/style (training, the
// optimisation method, dataset loading). The caller owns a std::atomic<bool> and sets it from any
// thread; the operation polls it between units of work (a file, a micro-batch, an iteration), each of
// which is far shorter than a second on this project's data, so cancellation lands within 1 s.

#include <atomic>
#include <exception>

#include "common/errors.h"

namespace motionstyle::style {

// The internal loops throw OperationCancelled (common/errors.h) when the flag is seen; the public
// operations catch it and report a cancelled result instead (dataset loading, which has no result to
// report, lets it through).

inline bool cancelRequested(const std::atomic<bool>* cancel) {
  return cancel != nullptr && cancel->load(std::memory_order_relaxed);
}

inline void throwIfCancelled(const std::atomic<bool>* cancel) {
  if (cancelRequested(cancel)) throw OperationCancelled();
}

}  // namespace motionstyle::style
