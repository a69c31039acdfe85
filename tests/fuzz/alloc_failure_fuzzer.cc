// libFuzzer target for allocation failure: a real stream is decoded with allocator hooks that
// fail at random (the input seeds the pattern and sets the rate). Every failure must come back
// as M4D_ERR_NOMEM, never a crash or a leak; every frame that is output must be exactly the
// clean decode's; every hooked allocation must be freed once the context and frames are gone.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <map>
#include <string>

#include "tests/encoder/stream_test_util.h"

namespace {

struct FailingHeap {
  uint64_t state = 1;
  uint32_t one_in = 8;  // each allocation fails with probability 1 / one_in
  long live = 0;
};

void* Alloc(void* cookie, size_t size) {
  FailingHeap* heap = static_cast<FailingHeap*>(cookie);
  heap->state ^= heap->state << 13;
  heap->state ^= heap->state >> 7;
  heap->state ^= heap->state << 17;
  if (heap->state % heap->one_in == 0) return nullptr;
  void* p = std::malloc(size ? size : 1);
  if (p) ++heap->live;
  return p;
}

void Free(void* cookie, void* p) {
  if (p) --static_cast<FailingHeap*>(cookie)->live;
  std::free(p);
}

struct Clean {
  std::vector<m4d::testing::Packet> packets;
  std::map<uint32_t, std::string> hashes;
};

const Clean& CleanStream() {
  static const Clean clean = [] {
    m4d::testing::TestStreamShape shape;
    shape.gops = 2;
    shape.frames_per_gop = 3;
    shape.static_count = 60;
    shape.dynamic_count = 50;
    Clean c;
    c.packets = m4d::testing::MakeTestStream(shape).packets;
    const auto r = m4d::testing::DecodeWith(m4d::testing::DefaultSettings(), c.packets);
    for (size_t i = 0; i < r.hashes.size(); ++i) c.hashes[r.frame_indices[i]] = r.hashes[i];
    return c;
  }();
  return clean;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 9) return 0;
  FailingHeap heap;
  for (int i = 0; i < 8; ++i) heap.state = heap.state * 131 + data[i];
  heap.state |= 1;
  heap.one_in = 2 + data[8] % 30;
  M4dSettings settings = m4d::testing::DefaultSettings();
  settings.allocator.cookie = &heap;
  settings.allocator.alloc = Alloc;
  settings.allocator.free = Free;
  const Clean& clean = CleanStream();
  const auto r = m4d::testing::DecodeWith(settings, clean.packets);
  for (size_t i = 0; i < r.hashes.size(); ++i) {
    if (clean.hashes.at(r.frame_indices[i]) != r.hashes[i]) std::abort();
  }
  for (int e : r.errors) {
    if (e != M4D_ERR_NOMEM && e != M4D_ERR_BITSTREAM) std::abort();
  }
  if (heap.live != 0) std::abort();
  return 0;
}
