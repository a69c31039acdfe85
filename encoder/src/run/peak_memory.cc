#include "encoder/src/run/peak_memory.h"

#include <sys/resource.h>

namespace m4d {

size_t PeakMemoryBytes() {
  struct rusage usage = {};
  if (getrusage(RUSAGE_SELF, &usage) != 0 || usage.ru_maxrss < 0) return 0;
  return static_cast<size_t>(usage.ru_maxrss) * 1024;  // Linux counts kilobytes
}

}  // namespace m4d
