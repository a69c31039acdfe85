#include "sdk/src/entropy/symbol_block_reader.h"

#include <cstddef>
#include <string>
#include <vector>

#include "sdk/src/common/spec_limits.h"

namespace m4d {
namespace {

constexpr uint32_t kSlotMask = kRansTotal - 1;

// Bucket sizes of BucketDecoder: fine buckets decode fastest, coarse ones build faster, which
// wins below kMinCountForFineBuckets symbols (measured with bench/entropy_bench.cc).
constexpr int kFineBucketBits = 4;
constexpr int kCoarseBucketBits = 8;
constexpr uint32_t kMinCountForFineBuckets = 4096;

Status Error(const std::string& what) { return BitstreamError("symbol block: " + what); }

struct SymbolInfo {
  uint32_t freq;
  uint32_t cum;
};

// The symbol holding slot, given c[lo] <= slot < c[hi] + f[hi]: the last s in [lo, hi] with
// c[s] <= slot, by a branchless binary search.
inline uint32_t SearchSymbol(const SymbolInfo* info, uint32_t lo, uint32_t hi, uint32_t slot) {
  for (uint32_t size = hi - lo + 1; size > 1;) {
    const uint32_t half = size / 2;
    lo = info[lo + half].cum <= slot ? lo + half : lo;
    size -= half;
  }
  return lo;
}

// Maps states to symbols through buckets of 2^kBucketBits slots. A bucket inside a single
// symbol (nearly all of them for the peaked sources of a codec) holds that symbol's f and c,
// so decoding costs one load from a small table; other buckets search the symbols they
// overlap. With 16-slot buckets (8 KiB, in L1) this measured 25-35% faster than a full
// 2^15-entry slot -> symbol table, whose 64 KiB mostly miss L1 and need a second dependent
// load for f and c, and it builds in a fraction of the time.
template <int kBucketBits>
class BucketDecoder {
 public:
  explicit BucketDecoder(const std::vector<SymbolInfo>& info) : info_(info.data()) {
    buckets_.resize(kBuckets);
    first_symbols_.resize(kBuckets + 1);
    uint32_t s = 0;
    for (uint32_t b = 0; b < kBuckets; ++b) {
      const uint32_t start = b << kBucketBits;
      while (info[s].cum + info[s].freq <= start) ++s;  // Ends on the symbol holding start.
      first_symbols_[b] = static_cast<uint16_t>(s);
      // f - 1 and c fit 15 bits each: f = 2^15 only for a lone symbol, whose c is 0.
      const bool whole = info[s].cum + info[s].freq >= start + kBucketSize;
      buckets_[b] = whole ? (info[s].freq - 1) | (info[s].cum << kRansPrecision) : kSplit;
    }
    first_symbols_[kBuckets] = static_cast<uint16_t>(info.size() - 1);
  }

  // Returns the symbol s of state *x and replaces *x with the spec's
  // f[s] * (x >> PRECISION) + slot - c[s], before renormalisation.
  uint32_t DecodeSymbol(uint32_t* x) const {
    const uint32_t slot = *x & kSlotMask;
    const uint32_t b = slot >> kBucketBits;
    const uint32_t bucket = buckets_[b];
    if (bucket != kSplit) {
      *x = ((bucket & kSlotMask) + 1) * (*x >> kRansPrecision) + slot - (bucket >> kRansPrecision);
      return first_symbols_[b];
    }
    // The symbol holding the next bucket's first slot bounds the search.
    const uint32_t s = SearchSymbol(info_, first_symbols_[b], first_symbols_[b + 1], slot);
    *x = info_[s].freq * (*x >> kRansPrecision) + slot - info_[s].cum;
    return s;
  }

 private:
  static constexpr uint32_t kBucketSize = 1u << kBucketBits;
  static constexpr uint32_t kBuckets = kRansTotal >> kBucketBits;
  static constexpr uint32_t kSplit = 1u << 31;  // The bucket overlaps several symbols.

  const SymbolInfo* info_;
  std::vector<uint32_t> buckets_;
  std::vector<uint16_t> first_symbols_;
};

// Runs the rANS decoder of spec 5.2 with kStates interleaved states over the payload (symbol i
// uses state i mod kStates), writing min + symbol to out. The payload holds at least
// 4 * kStates bytes.
template <uint32_t kStates, typename Decoder>
Status DecodePayload(const uint8_t* p, const uint8_t* end, const Decoder& decoder, uint32_t count,
                     int32_t min, int32_t* out) {
  uint32_t x[kStates];
  for (uint32_t j = 0; j < kStates; ++j, p += 4) x[j] = ByteReader::LoadU32(p);
  // One decoding step with a bounds check on every renormalisation byte.
  auto checked_step = [&](uint32_t i) {
    uint32_t& state = x[i % kStates];
    const uint32_t s = decoder.DecodeSymbol(&state);
    while (state < kRansLow) {
      if (p == end) return false;
      state = (state << 8) | *p++;
    }
    out[i] = min + static_cast<int32_t>(s);
    return true;
  };
  uint32_t i = 0;
  // From a state >= L a step reads at most 2 bytes; only the initial states can be lower.
  for (; i < count && i < kStates; ++i) {
    if (!checked_step(i)) return Error("rANS payload exhausted");
  }
  // Unchecked rounds of one symbol per state, as many as the remaining bytes cover at 2 bytes
  // per step. The states' symbols are decoded first (independent chains), then renormalised in
  // symbol order, which is the order their bytes follow in the payload.
  for (;;) {
    const size_t safe = static_cast<size_t>(end - p) / 2;
    const uint32_t stop = count - i < safe ? count : i + static_cast<uint32_t>(safe);
    if (stop - i < kStates) break;
    for (; i + kStates <= stop; i += kStates) {
      uint32_t s[kStates];
      for (uint32_t j = 0; j < kStates; ++j) s[j] = decoder.DecodeSymbol(&x[j]);
      for (uint32_t j = 0; j < kStates; ++j) {
        // Branches beat selects here: skewed sources predict well, and selects lengthen the
        // dependency chain through x on every symbol.
        if (x[j] < kRansLow) {
          x[j] = (x[j] << 8) | *p++;
          if (x[j] < kRansLow) x[j] = (x[j] << 8) | *p++;
        }
        out[i + j] = min + static_cast<int32_t>(s[j]);
      }
    }
  }
  for (; i < count; ++i) {
    if (!checked_step(i)) return Error("rANS payload exhausted");
  }
  for (uint32_t j = 0; j < kStates; ++j) {
    if (x[j] != kRansLow) {
      return Error("final rANS state " + std::to_string(j) + " is " + std::to_string(x[j]) +
                   ", expected 8388608");
    }
  }
  if (p != end) return Error(std::to_string(end - p) + " rANS payload bytes left over");
  return Status::Ok();
}

// Decodes the payload with the bucket size that suits the count and the block's states.
template <uint32_t kStates>
Status DecodeBlock(const uint8_t* payload, const uint8_t* end, const std::vector<SymbolInfo>& info,
                   uint32_t count, int32_t min, int32_t* out) {
  if (count < kMinCountForFineBuckets) {
    return DecodePayload<kStates>(payload, end, BucketDecoder<kCoarseBucketBits>(info), count, min,
                                  out);
  }
  return DecodePayload<kStates>(payload, end, BucketDecoder<kFineBucketBits>(info), count, min,
                                out);
}

}  // namespace

Status ReadSymbolBlock(ByteReader* reader, RansLayout layout, uint32_t count, int32_t lo,
                       int32_t hi, int32_t* out) {
  uint32_t n;
  if (!reader->ReadVarUint(&n)) return Error("truncated alphabet_size");
  if (n == 0) return Error("alphabet_size 0");
  if (n > kMaxAlphabet) {
    return LimitError("symbol block: alphabet_size " + std::to_string(n) + " exceeds " +
                      std::to_string(kMaxAlphabet));
  }
  int32_t min;
  if (!reader->ReadVarSint(&min)) return Error("truncated min_value");
  const int64_t max = static_cast<int64_t>(min) + n - 1;
  if (min < -kMaxSymbolMagnitude || min > kMaxSymbolMagnitude || max > kMaxSymbolMagnitude) {
    return Error("values " + std::to_string(min) + ".." + std::to_string(max) +
                 " exceed magnitude 2^23");
  }
  if (count == 0 && n > 1) return Error("alphabet_size " + std::to_string(n) + " for 0 values");

  // Checks the range of the values that can be decoded, before decoding any.
  auto check_range = [&](int64_t low, int64_t high) {
    if (low >= lo && high <= hi) return Status::Ok();
    return Error("values " + std::to_string(low) + ".." + std::to_string(high) +
                 " outside the allowed range " + std::to_string(lo) + ".." + std::to_string(hi));
  };
  if (n == 1) {
    if (count == 0) return Status::Ok();
    M4D_RETURN_IF_ERROR(check_range(min, min));
    for (uint32_t i = 0; i < count; ++i) out[i] = min;
    return Status::Ok();
  }

  std::vector<SymbolInfo> info(n, SymbolInfo{0, 0});
  uint32_t sum = 0;
  for (uint32_t i = 0; i < n;) {
    uint32_t f;
    if (!reader->ReadVarUint(&f)) return Error("truncated frequency table");
    if (f > kRansTotal) return Error("frequency " + std::to_string(f) + " above 32768");
    info[i].freq = f;
    info[i].cum = sum;
    sum += f;
    ++i;
    if (f == 0) {
      uint32_t zeros;
      if (!reader->ReadVarUint(&zeros)) return Error("truncated frequency table");
      if (zeros > n - i) {
        return Error("zero run of " + std::to_string(zeros) + " passes the end of the alphabet");
      }
      for (const uint32_t run_end = i + zeros; i < run_end; ++i) info[i].cum = sum;
    }
  }
  if (sum != kRansTotal) {
    return Error("frequencies sum to " + std::to_string(sum) + ", expected " +
                 std::to_string(kRansTotal));
  }
  // Symbols of frequency 0 cannot be decoded, so only the used span must fit [lo, hi].
  uint32_t first = 0, last = n - 1;
  while (info[first].freq == 0) ++first;
  while (info[last].freq == 0) --last;
  M4D_RETURN_IF_ERROR(
      check_range(static_cast<int64_t>(min) + first, static_cast<int64_t>(min) + last));

  uint32_t payload_size;
  if (!reader->ReadVarUint(&payload_size)) return Error("truncated payload_size");
  const uint32_t states = RansStates(layout, count);
  if (payload_size < 4 * states) {
    return Error("payload_size " + std::to_string(payload_size) + " below " +
                 std::to_string(4 * states));
  }
  const uint8_t* payload;
  if (!reader->ReadBytes(payload_size, &payload)) {
    return Error("payload_size " + std::to_string(payload_size) + " exceeds the " +
                 std::to_string(reader->remaining()) + " remaining bytes");
  }
  const uint8_t* end = payload + payload_size;
  if (states == kRansInterleavedStates) {
    return DecodeBlock<kRansInterleavedStates>(payload, end, info, count, min, out);
  }
  return DecodeBlock<1>(payload, end, info, count, min, out);
}

}  // namespace m4d
