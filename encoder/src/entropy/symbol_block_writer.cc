#include "encoder/src/entropy/symbol_block_writer.h"

#include <algorithm>
#include <cmath>
#include <queue>
#include <string>
#include <utility>

#include "sdk/src/common/spec_limits.h"

namespace m4d {
namespace {

// Bits the whole source saves when symbol s's frequency rises from f to f + 1.
double IncrementGain(uint64_t count, uint32_t f) {
  return static_cast<double>(count) * std::log2((f + 1.0) / f);
}

// Bits the whole source loses when symbol s's frequency drops from f to f - 1 (f >= 2).
double DecrementLoss(uint64_t count, uint32_t f) {
  return static_cast<double>(count) * std::log2(f / (f - 1.0));
}

// A candidate change of one frequency. It is stale once freqs[symbol] != freq.
struct Candidate {
  double bits;
  uint32_t symbol;
  uint32_t freq;
};
struct LessBits {
  bool operator()(const Candidate& a, const Candidate& b) const { return a.bits < b.bits; }
};
struct MoreBits {
  bool operator()(const Candidate& a, const Candidate& b) const { return a.bits > b.bits; }
};

// rANS encoding of spec 5.2 with `states` interleaved states, symbol i given by symbol_at(i).
template <typename SymbolAt>
std::vector<uint8_t> Encode(SymbolAt symbol_at, size_t count, const std::vector<uint32_t>& freqs,
                            uint32_t states) {
  // x / f as (x * ceil(2^47 / f)) >> 47: exact while x < 2^16 * f (always so after the
  // renormalisation, as x_max = 2^16 * f), and the product stays below 2^64.
  struct Coder {
    uint32_t freq;
    uint32_t cum;
    uint64_t reciprocal;
  };
  std::vector<Coder> coders(freqs.size());
  uint32_t sum = 0;
  for (size_t s = 0; s < freqs.size(); ++s) {
    const uint64_t f = freqs[s];
    coders[s] = {freqs[s], sum, f ? ((uint64_t{1} << 47) + f - 1) / f : 0};
    sum += freqs[s];
  }
  // x < 2^31 after every step and x_max >= 2^16, so a symbol pushes at most 2 bytes. They are
  // stored backwards from the end, which leaves them in the decoder's reading order.
  // Symbol i goes through state i mod states; in reverse order, each state's bytes land where
  // the decoder, reading forward, renormalises that state.
  std::vector<uint8_t> buffer(4 * states + 2 * count);
  uint8_t* const end = buffer.data() + buffer.size();
  uint8_t* p = end;
  std::vector<uint32_t> xs(states, kRansLow);
  for (size_t i = count; i-- > 0;) {
    uint32_t& x = xs[i % states];
    const Coder& c = coders[symbol_at(i)];
    const uint32_t x_max = ((kRansLow >> kRansPrecision) << 8) * c.freq;
    if (x >= x_max) {
      *--p = static_cast<uint8_t>(x);
      x >>= 8;
      if (x >= x_max) {
        *--p = static_cast<uint8_t>(x);
        x >>= 8;
      }
    }
    const uint32_t q = static_cast<uint32_t>((x * c.reciprocal) >> 47);
    x = q * kRansTotal + (x - q * c.freq) + c.cum;
  }
  p -= 4 * states;
  for (uint32_t j = 0; j < states; ++j) {
    for (uint32_t k = 0; k < 4; ++k) p[4 * j + k] = static_cast<uint8_t>(xs[j] >> (8 * k));
  }
  return std::vector<uint8_t>(p, end);
}

}  // namespace

std::vector<uint32_t> NormalizeFrequencies(const std::vector<uint64_t>& counts) {
  const size_t n = counts.size();
  std::vector<uint32_t> freqs(n, 0);
  double total = 0;
  for (uint64_t c : counts) total += static_cast<double>(c);
  if (total == 0) {
    // Nothing to code: any valid table will do.
    freqs[0] = kRansTotal;
    return freqs;
  }
  // Proportional rounding, at least 1 for every used symbol; the sum is then fixed greedily.
  int64_t sum = 0;
  for (size_t s = 0; s < n; ++s) {
    if (counts[s] == 0) continue;
    const double ideal = static_cast<double>(counts[s]) * kRansTotal / total;
    freqs[s] = std::max<uint32_t>(1, static_cast<uint32_t>(std::lround(ideal)));
    sum += freqs[s];
  }
  // The cost, sum of count * -log2(f / M), is convex in each f: greedy unit steps by the
  // smallest cost change reach the optimum for the sum, and pairwise exchanges that lower it
  // further make it a global optimum. Heap entries go stale when their symbol changes.
  std::priority_queue<Candidate, std::vector<Candidate>, LessBits> increments;
  std::priority_queue<Candidate, std::vector<Candidate>, MoreBits> decrements;
  auto push = [&](uint32_t s) {
    const uint32_t f = freqs[s];
    if (f < kRansTotal) increments.push({IncrementGain(counts[s], f), s, f});
    if (f > 1) decrements.push({DecrementLoss(counts[s], f), s, f});
  };
  auto apply = [&](uint32_t s, int delta) {
    freqs[s] += delta;
    sum += delta;
    push(s);
  };
  // Pops stale entries, then takes the best symbol of the heap.
  auto take_best = [&](auto* heap) {
    while (freqs[heap->top().symbol] != heap->top().freq) heap->pop();
    const uint32_t s = heap->top().symbol;
    heap->pop();
    return s;
  };
  auto peek_best = [&](auto* heap) -> const Candidate* {
    while (!heap->empty() && freqs[heap->top().symbol] != heap->top().freq) heap->pop();
    return heap->empty() ? nullptr : &heap->top();
  };
  for (uint32_t s = 0; s < n; ++s) {
    if (counts[s] > 0) push(s);
  }
  // With at most 2^15 used symbols (the alphabet limit is far lower) the heaps never run dry.
  while (sum > kRansTotal) apply(take_best(&decrements), -1);
  while (sum < kRansTotal) apply(take_best(&increments), 1);
  for (;;) {
    const Candidate* up = peek_best(&increments);
    const Candidate* down = peek_best(&decrements);
    if (!up || !down) break;
    // Convexity makes an exchange within one symbol never pay; the margin absorbs rounding.
    if (up->symbol == down->symbol || up->bits <= down->bits * (1 + 1e-12) + 1e-9) break;
    const uint32_t up_symbol = take_best(&increments);
    const uint32_t down_symbol = take_best(&decrements);
    apply(up_symbol, 1);
    apply(down_symbol, -1);
  }
  return freqs;
}

std::vector<uint8_t> RansEncode(const uint32_t* symbols, size_t count,
                                const std::vector<uint32_t>& freqs, uint32_t states) {
  return Encode([symbols](size_t i) { return symbols[i]; }, count, freqs, states);
}

Status WriteSymbolBlock(const int32_t* values, size_t count, RansLayout layout, ByteWriter* out) {
  if (count == 0) {
    out->WriteVarUint(1);
    out->WriteVarSint(0);
    return Status::Ok();
  }
  const auto [min_it, max_it] = std::minmax_element(values, values + count);
  const int32_t min = *min_it, max = *max_it;
  if (min < -kMaxSymbolMagnitude || max > kMaxSymbolMagnitude) {
    return LimitError("symbol block: value " +
                      std::to_string(min < -kMaxSymbolMagnitude ? min : max) +
                      " exceeds magnitude 2^23");
  }
  const uint32_t n = static_cast<uint32_t>(max - min) + 1;
  if (n > kMaxAlphabet) {
    return LimitError("symbol block: values span " + std::to_string(n) +
                      ", above the alphabet limit " + std::to_string(kMaxAlphabet));
  }
  if (n == 1) {
    out->WriteVarUint(1);
    out->WriteVarSint(min);
    return Status::Ok();
  }
  std::vector<uint64_t> counts(n, 0);
  for (size_t i = 0; i < count; ++i) ++counts[values[i] - min];
  const std::vector<uint32_t> freqs = NormalizeFrequencies(counts);
  if (count > UINT32_MAX / 2) return LimitError("symbol block: above 2^31 values");
  const std::vector<uint8_t> payload =
      Encode([values, min](size_t i) { return static_cast<uint32_t>(values[i] - min); }, count,
             freqs, RansStates(layout, static_cast<uint32_t>(count)));
  if (payload.size() > UINT32_MAX) return LimitError("symbol block: payload above 4 GiB");

  out->WriteVarUint(n);
  out->WriteVarSint(min);
  for (uint32_t i = 0; i < n;) {
    out->WriteVarUint(freqs[i]);
    if (freqs[i] > 0) {
      ++i;
      continue;
    }
    // A zero is followed by the number of further zeros it stands for.
    uint32_t run = 1;
    while (i + run < n && freqs[i + run] == 0) ++run;
    out->WriteVarUint(run - 1);
    i += run;
  }
  out->WriteVarUint(static_cast<uint32_t>(payload.size()));
  out->WriteBytes(payload);
  return Status::Ok();
}

size_t SymbolBlockSize(const int32_t* values, size_t count, RansLayout layout) {
  std::vector<uint8_t> scratch;
  ByteWriter writer(&scratch);
  // A block is never empty, so 0 reports values that cannot be coded.
  if (!WriteSymbolBlock(values, count, layout, &writer).ok()) return 0;
  return scratch.size();
}

}  // namespace m4d
