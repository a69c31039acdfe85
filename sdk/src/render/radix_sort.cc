#include "sdk/src/render/radix_sort.h"

#include <cstddef>

namespace m4d {

void RadixSortPairs(std::vector<uint32_t>* keys, std::vector<uint32_t>* values,
                    std::vector<uint32_t>* key_scratch, std::vector<uint32_t>* value_scratch) {
  const size_t n = keys->size();
  key_scratch->resize(n);
  value_scratch->resize(n);
  for (int shift = 0; shift < 32; shift += 8) {
    size_t count[256] = {};
    for (size_t i = 0; i < n; ++i) ++count[((*keys)[i] >> shift) & 0xff];
    bool trivial = false;
    for (size_t c : count) trivial = trivial || c == n;
    if (trivial) continue;
    size_t sum = 0;
    for (size_t& c : count) {
      const size_t here = c;
      c = sum;
      sum += here;
    }
    for (size_t i = 0; i < n; ++i) {
      const size_t slot = count[((*keys)[i] >> shift) & 0xff]++;
      (*key_scratch)[slot] = (*keys)[i];
      (*value_scratch)[slot] = (*values)[i];
    }
    keys->swap(*key_scratch);
    values->swap(*value_scratch);
  }
}

}  // namespace m4d
