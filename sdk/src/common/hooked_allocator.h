// HookedAllocator: a std allocator that routes the decoder's large buffers through the
// caller's allocation hooks (M4dSettings.allocator). Without hooks it uses malloc.
// Failure throws std::bad_alloc, which the C API turns into M4D_ERR_NOMEM. The hooks are held
// by value: a frame's buffers outlive the context whose settings named them.
#ifndef M4D_SDK_COMMON_HOOKED_ALLOCATOR_H_
#define M4D_SDK_COMMON_HOOKED_ALLOCATOR_H_

#include <cstddef>
#include <cstdlib>
#include <new>
#include <vector>

#include "m4d/m4d.h"

namespace m4d {

template <typename T>
class HookedAllocator {
 public:
  using value_type = T;

  HookedAllocator() = default;
  // hooks may be null (malloc); only a pair with both callbacks set is used.
  explicit HookedAllocator(const M4dAllocator* hooks) {
    if (hooks && hooks->alloc && hooks->free) hooks_ = *hooks;
  }
  template <typename U>
  HookedAllocator(const HookedAllocator<U>& other) : hooks_(other.hooks()) {}

  T* allocate(size_t n) {
    if (n > static_cast<size_t>(-1) / sizeof(T)) throw std::bad_alloc();
    void* p =
        hooks_.alloc ? hooks_.alloc(hooks_.cookie, n * sizeof(T)) : std::malloc(n * sizeof(T));
    if (!p) throw std::bad_alloc();
    return static_cast<T*>(p);
  }
  void deallocate(T* p, size_t) {
    if (hooks_.alloc)
      hooks_.free(hooks_.cookie, p);
    else
      std::free(p);
  }

  const M4dAllocator& hooks() const { return hooks_; }

  template <typename U>
  bool operator==(const HookedAllocator<U>& o) const {
    return hooks_.alloc == o.hooks().alloc && hooks_.free == o.hooks().free &&
           hooks_.cookie == o.hooks().cookie;
  }
  template <typename U>
  bool operator!=(const HookedAllocator<U>& o) const {
    return !(*this == o);
  }

 private:
  M4dAllocator hooks_{nullptr, nullptr, nullptr};
};

template <typename T>
using Buffer = std::vector<T, HookedAllocator<T>>;

}  // namespace m4d

#endif  // M4D_SDK_COMMON_HOOKED_ALLOCATOR_H_
