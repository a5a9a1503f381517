#include "common/allocator_tuning.h"

#if defined(__GLIBC__)
#include <malloc.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
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

void restartWithHugePages(char** argv) {
#if defined(__GLIBC__) && defined(__linux__)
  constexpr const char* kTunable = "glibc.malloc.hugetlb=1";
  if (std::getenv("MOTIONSTYLE_NO_HUGE_PAGES") != nullptr) return;
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  if (tunables != nullptr && std::strstr(tunables, "glibc.malloc.hugetlb") != nullptr) return;
  std::string mode;
  std::getline(std::ifstream("/sys/kernel/mm/transparent_hugepage/enabled"), mode);
  if (mode.empty() || mode.find("[never]") != std::string::npos) return;
  const std::string previous = tunables != nullptr ? tunables : "";
  const std::string value = previous.empty() ? kTunable : previous + ":" + kTunable;
  // The program's own file, not /proc/self/exe: the process keeps its name (ps, pkill).
  std::string program(4096, '\0');
  const ssize_t length = ::readlink("/proc/self/exe", program.data(), program.size() - 1);
  if (length <= 0) return;
  program.resize(static_cast<std::size_t>(length));
  if (::setenv("GLIBC_TUNABLES", value.c_str(), 1) != 0) return;
  ::execv(program.c_str(), argv);
  // Still here: the restart failed; go on as started.
  if (tunables != nullptr) ::setenv("GLIBC_TUNABLES", previous.c_str(), 1);
  else ::unsetenv("GLIBC_TUNABLES");
#else
  (void)argv;
#endif
}

}  // namespace motionstyle
