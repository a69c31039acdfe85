#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "encoder/src/entropy/symbol_block_writer.h"
#include "sdk/src/common/byte_reader.h"
#include "sdk/src/common/byte_writer.h"
#include "sdk/src/common/spec_limits.h"
#include "sdk/src/entropy/symbol_block_reader.h"

namespace m4d {
namespace {

constexpr int32_t kMaxMag = kMaxSymbolMagnitude;

std::vector<uint8_t> EncodeBlock(const std::vector<int32_t>& values,
                                 RansLayout layout = RansLayout::kInterleaved) {
  std::vector<uint8_t> bytes;
  ByteWriter writer(&bytes);
  const Status status = WriteSymbolBlock(values.data(), values.size(), layout, &writer);
  EXPECT_TRUE(status.ok()) << status.message();
  return bytes;
}

// Decodes from an exactly sized heap copy, so a sanitizer build catches any overread.
Status DecodeBlock(const std::vector<uint8_t>& bytes, uint32_t count, int32_t lo, int32_t hi,
                   std::vector<int32_t>* values, size_t* consumed = nullptr,
                   RansLayout layout = RansLayout::kInterleaved) {
  const std::vector<uint8_t> copy(bytes);
  ByteReader reader(copy.data(), copy.size());
  values->assign(count, 0x7eadbeef);
  const Status status = ReadSymbolBlock(&reader, layout, count, lo, hi, values->data());
  if (consumed) *consumed = reader.position();
  return status;
}

void ExpectRoundTrip(const std::vector<int32_t>& values, int32_t lo = -kMaxMag,
                     int32_t hi = kMaxMag) {
  const std::vector<uint8_t> bytes = EncodeBlock(values);
  EXPECT_EQ(SymbolBlockSize(values.data(), values.size(), RansLayout::kInterleaved), bytes.size());
  std::vector<int32_t> decoded;
  size_t consumed = 0;
  const Status status =
      DecodeBlock(bytes, static_cast<uint32_t>(values.size()), lo, hi, &decoded, &consumed);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(consumed, bytes.size());
  ASSERT_EQ(decoded, values);
}

// A block written field by field, for streams the writer would never produce.
std::vector<uint8_t> RawBlock(uint32_t n, int32_t min, const std::vector<uint32_t>& table,
                              const std::vector<uint8_t>& payload) {
  std::vector<uint8_t> bytes;
  ByteWriter writer(&bytes);
  writer.WriteVarUint(n);
  writer.WriteVarSint(min);
  for (uint32_t v : table) writer.WriteVarUint(v);
  writer.WriteVarUint(static_cast<uint32_t>(payload.size()));
  writer.WriteBytes(payload);
  return bytes;
}

std::vector<int32_t> Uniform(size_t count, int32_t lo, int32_t hi, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int32_t> dist(lo, hi);
  std::vector<int32_t> values(count);
  for (auto& v : values) v = dist(rng);
  return values;
}

// Rounded Laplacian around 0 with the given scale, clamped to +-limit.
std::vector<int32_t> Laplacian(size_t count, double scale, int32_t limit, uint32_t seed) {
  std::mt19937 rng(seed);
  std::exponential_distribution<double> magnitude(1.0 / scale);
  std::vector<int32_t> values(count);
  for (auto& v : values) {
    const double m = std::min<double>(std::round(magnitude(rng)), limit);
    v = static_cast<int32_t>(rng() & 1 ? m : -m);
  }
  return values;
}

// Zero with probability 1 - p_nonzero, otherwise a Laplacian value that is not 0.
std::vector<int32_t> MostlyZero(size_t count, double p_nonzero, uint32_t seed) {
  std::mt19937 rng(seed);
  std::bernoulli_distribution nonzero(p_nonzero);
  std::geometric_distribution<int32_t> magnitude(0.3);
  std::vector<int32_t> values(count, 0);
  for (auto& v : values) {
    if (!nonzero(rng)) continue;
    const int32_t m = 1 + std::min(magnitude(rng), 200);
    v = rng() & 1 ? m : -m;
  }
  return values;
}

std::vector<int32_t> Binary(size_t count, double p_one, uint32_t seed) {
  std::mt19937 rng(seed);
  std::bernoulli_distribution one(p_one);
  std::vector<int32_t> values(count);
  for (auto& v : values) v = one(rng) ? 1 : 0;
  return values;
}

TEST(EntropyTest, RoundTripUniform) {
  uint32_t seed = 1;
  for (size_t count : {2, 3, 17, 1000, 4095, 4096, 4097, 100000}) {
    ExpectRoundTrip(Uniform(count, -100, 200, seed++));
    ExpectRoundTrip(Uniform(count, 0, 1, seed++));
  }
}

TEST(EntropyTest, RoundTripLaplacian) {
  uint32_t seed = 10;
  for (double scale : {0.3, 1.0, 4.0, 50.0, 400.0}) {
    for (size_t count : {5, 500, 3000, 200000})
      ExpectRoundTrip(Laplacian(count, scale, 2047, seed++));
  }
}

TEST(EntropyTest, RoundTripSingleValue) {
  for (int32_t value : {0, 1, -1, 12345, -kMaxMag, kMaxMag}) {
    for (size_t count : {1, 2, 5000}) {
      const std::vector<int32_t> values(count, value);
      const std::vector<uint8_t> bytes = EncodeBlock(values);
      // alphabet_size 1 and min_value only.
      std::vector<uint8_t> expected;
      ByteWriter writer(&expected);
      writer.WriteVarUint(1);
      writer.WriteVarSint(value);
      EXPECT_EQ(bytes, expected);
      ExpectRoundTrip(values);
    }
  }
}

TEST(EntropyTest, RoundTripSkewedBinary) {
  ExpectRoundTrip(Binary(1000000, 0.001, 3));
  ExpectRoundTrip(Binary(100000, 0.999, 4));
  // A single 1 among many zeros, at either end.
  std::vector<int32_t> values(50000, 0);
  values.front() = 1;
  ExpectRoundTrip(values);
  values.front() = 0;
  values.back() = 1;
  ExpectRoundTrip(values);
}

TEST(EntropyTest, RoundTripFullAlphabet) {
  std::vector<int32_t> values = Laplacian(100000, 300.0, 2047, 5);
  values.push_back(-2048);
  values.push_back(2047);
  ExpectRoundTrip(values);
  ExpectRoundTrip(Uniform(300000, -2048, 2047, 6));
  // Far more symbols than frequency slots per symbol.
  ExpectRoundTrip(Uniform(3000, kMaxMag - 4095, kMaxMag, 7));
  ExpectRoundTrip(Uniform(3000, -kMaxMag, -kMaxMag + 4095, 8));
}

TEST(EntropyTest, RoundTripManyRareSymbols) {
  // 4095 symbols of frequency 1 next to a dominant one: decoding goes through buckets that
  // overlap many symbols.
  for (size_t repeats : {1000u, 1000000u}) {
    std::vector<int32_t> values(repeats, 100);
    for (int32_t v = -2000; v <= 2095; ++v) {
      if (v != 100) values.push_back(v);
    }
    std::shuffle(values.begin(), values.end(), std::mt19937(27));
    ExpectRoundTrip(values);
  }
}

TEST(EntropyTest, RoundTripNegativeMins) {
  ExpectRoundTrip(Uniform(10000, -5000, -4000, 9));
  ExpectRoundTrip(Uniform(10, -3, -1, 10));
  ExpectRoundTrip({-7, -7, -7, -8});
}

TEST(EntropyTest, RoundTripSparseAlphabetUsesZeroRuns) {
  std::vector<int32_t> values = Uniform(20000, 0, 2, 11);
  for (auto& v : values) v = (v - 1) * 1000;  // -1000, 0, 1000
  const std::vector<uint8_t> bytes = EncodeBlock(values);
  // Two runs of 999 zeros cost a few bytes each, not ~2000 bytes of table.
  EXPECT_LT(bytes.size(), 20000u / 8 * 2 + 64);
  ExpectRoundTrip(values);
}

TEST(EntropyTest, CountZero) {
  const std::vector<uint8_t> bytes = EncodeBlock({});
  EXPECT_EQ(bytes, (std::vector<uint8_t>{1, 0}));
  EXPECT_EQ(SymbolBlockSize(nullptr, 0, RansLayout::kInterleaved), 2u);
  std::vector<int32_t> decoded;
  size_t consumed = 0;
  // No value is decoded, so the range does not apply.
  EXPECT_TRUE(DecodeBlock(bytes, 0, 5, 10, &decoded, &consumed).ok());
  EXPECT_EQ(consumed, 2u);
  // Any min is fine with n = 1.
  EXPECT_TRUE(DecodeBlock({1, 0x80, 0x02}, 0, 0, 0, &decoded).ok());
  // count 0 with n > 1 is an error.
  const Status status =
      DecodeBlock(RawBlock(2, 0, {16384, 16384}, {0, 0, 0x80, 0}), 0, -kMaxMag, kMaxMag, &decoded);
  EXPECT_EQ(status.code(), M4D_ERR_BITSTREAM);
}

TEST(EntropyTest, BlocksAreSelfDelimiting) {
  const std::vector<int32_t> a = Laplacian(3000, 2.0, 100, 12), b = Uniform(40, -9, 9, 13);
  std::vector<uint8_t> bytes;
  ByteWriter writer(&bytes);
  ASSERT_TRUE(WriteSymbolBlock(a.data(), a.size(), RansLayout::kInterleaved, &writer).ok());
  ASSERT_TRUE(WriteSymbolBlock(b.data(), b.size(), RansLayout::kInterleaved, &writer).ok());
  ASSERT_TRUE(WriteSymbolBlock(nullptr, 0, RansLayout::kInterleaved, &writer).ok());
  ByteReader reader(bytes.data(), bytes.size());
  std::vector<int32_t> da(a.size()), db(b.size());
  ASSERT_TRUE(ReadSymbolBlock(&reader, RansLayout::kInterleaved, 3000, -100, 100, da.data()).ok());
  ASSERT_TRUE(ReadSymbolBlock(&reader, RansLayout::kInterleaved, 40, -9, 9, db.data()).ok());
  ASSERT_TRUE(ReadSymbolBlock(&reader, RansLayout::kInterleaved, 0, 0, 0, nullptr).ok());
  EXPECT_EQ(reader.remaining(), 0u);
  EXPECT_EQ(da, a);
  EXPECT_EQ(db, b);
}

TEST(EntropyTest, WriterRejectsValuesBeyondLimits) {
  std::vector<uint8_t> bytes;
  ByteWriter writer(&bytes);
  const std::vector<int32_t> too_wide = {-2048, 2048};  // alphabet 4097
  EXPECT_EQ(WriteSymbolBlock(too_wide.data(), 2, RansLayout::kInterleaved, &writer).code(),
            M4D_ERR_LIMIT);
  const std::vector<int32_t> too_big = {kMaxMag + 1};
  EXPECT_EQ(WriteSymbolBlock(too_big.data(), 1, RansLayout::kInterleaved, &writer).code(),
            M4D_ERR_LIMIT);
  const std::vector<int32_t> too_small = {-kMaxMag - 1, -kMaxMag};
  EXPECT_EQ(WriteSymbolBlock(too_small.data(), 2, RansLayout::kInterleaved, &writer).code(),
            M4D_ERR_LIMIT);
  EXPECT_TRUE(bytes.empty());  // Nothing is written on failure.
  EXPECT_EQ(SymbolBlockSize(too_wide.data(), 2, RansLayout::kInterleaved), 0u);
}

double CostBits(const std::vector<uint64_t>& counts, const std::vector<uint32_t>& freqs) {
  double bits = 0;
  for (size_t s = 0; s < counts.size(); ++s) {
    if (counts[s] > 0) bits -= counts[s] * std::log2(freqs[s] / double(kRansTotal));
  }
  return bits;
}

TEST(EntropyTest, NormalizedFrequenciesAreValidAndOptimal) {
  std::mt19937 rng(14);
  for (int trial = 0; trial < 200; ++trial) {
    const size_t n = 1 + rng() % (trial < 100 ? 12 : 4096);
    std::vector<uint64_t> counts(n);
    for (auto& c : counts) {
      const uint32_t kind = rng() % 4;
      c = kind == 0 ? 0 : kind == 1 ? rng() % 3 : kind == 2 ? rng() % 1000 : rng() % 10000000;
    }
    counts[rng() % n] += 1;
    const std::vector<uint32_t> freqs = NormalizeFrequencies(counts);
    ASSERT_EQ(freqs.size(), n);
    uint64_t sum = 0;
    for (size_t s = 0; s < n; ++s) {
      sum += freqs[s];
      ASSERT_EQ(freqs[s] > 0, counts[s] > 0) << "symbol " << s;
    }
    ASSERT_EQ(sum, kRansTotal);
    if (n > 12) continue;
    // No single exchange of one frequency unit between two symbols lowers the cost.
    const double cost = CostBits(counts, freqs);
    for (size_t i = 0; i < n; ++i) {
      for (size_t j = 0; j < n; ++j) {
        if (i == j || counts[i] == 0 || freqs[j] <= 1) continue;
        std::vector<uint32_t> moved = freqs;
        ++moved[i];
        --moved[j];
        ASSERT_GE(CostBits(counts, moved), cost - 1e-6 * cost - 1e-9) << i << " " << j;
      }
    }
  }
}

TEST(EntropyTest, RansEncodeMatchesSpecBoundaries) {
  // One symbol takes the whole range: the state never moves and the payload is L itself.
  for (uint32_t count : {1000u, 5000u}) {
    const std::vector<uint32_t> symbols(count, 1);
    const uint32_t states = RansStates(RansLayout::kInterleaved, count);
    const std::vector<uint8_t> payload = RansEncode(symbols.data(), count, {0, 32768}, states);
    std::vector<uint8_t> expected;
    for (uint32_t j = 0; j < states; ++j) expected.insert(expected.end(), {0, 0, 0x80, 0});
    EXPECT_EQ(payload, expected);
    std::vector<int32_t> decoded;
    ASSERT_TRUE(DecodeBlock(RawBlock(2, -1, {0, 0, 32768}, payload), count, -1, 0, &decoded).ok());
    EXPECT_EQ(decoded, std::vector<int32_t>(count, 0));
  }
  // Nothing coded at all.
  EXPECT_EQ(RansEncode(nullptr, 0, {1, 32767}), (std::vector<uint8_t>{0, 0, 0x80, 0}));
}

struct SizeCase {
  const char* name;
  std::vector<int32_t> values;
};

TEST(EntropyTest, CodedSizeWithinOnePercentOfIdeal) {
  SizeCase cases[] = {
      {"laplacian_scale3", Laplacian(1000000, 3.0, 2047, 15)},
      {"mostly_zero_95", MostlyZero(1000000, 0.05, 16)},
      {"binary_p0.001", Binary(1000000, 0.001, 17)},
      {"uniform_4096", Uniform(1000000, -2048, 2047, 18)},
  };
  for (const SizeCase& c : cases) {
    const auto [min_it, max_it] = std::minmax_element(c.values.begin(), c.values.end());
    std::vector<uint64_t> counts(*max_it - *min_it + 1, 0);
    std::vector<uint32_t> symbols(c.values.size());
    for (size_t i = 0; i < c.values.size(); ++i) {
      symbols[i] = static_cast<uint32_t>(c.values[i] - *min_it);
      ++counts[symbols[i]];
    }
    const std::vector<uint32_t> freqs = NormalizeFrequencies(counts);
    const double ideal_bytes = CostBits(counts, freqs) / 8;
    double entropy_bits = 0;
    for (uint64_t k : counts) {
      if (k > 0) entropy_bits -= k * std::log2(double(k) / c.values.size());
    }
    const std::vector<uint8_t> payload =
        RansEncode(symbols.data(), symbols.size(), freqs, kRansInterleavedStates);
    // The block sends exactly this table and payload.
    const std::vector<uint8_t> block = EncodeBlock(c.values);
    ASSERT_GE(block.size(), payload.size());
    EXPECT_TRUE(std::equal(payload.begin(), payload.end(), block.end() - payload.size()));
    EXPECT_LE(payload.size(), 1.01 * ideal_bytes + 8) << c.name;
    const double ratio = payload.size() / ideal_bytes;
    std::printf(
        "[ size     ] %-18s payload %8zu B, ideal for table %10.1f B, ratio %.5f; "
        "table vs empirical entropy %.5f; block %zu B\n",
        c.name, payload.size(), ideal_bytes, ratio, ideal_bytes * 8 / entropy_bits, block.size());
    ::testing::Test::RecordProperty(std::string(c.name) + "_ratio", std::to_string(ratio));
    std::vector<int32_t> decoded;
    ASSERT_TRUE(DecodeBlock(block, 1000000, -kMaxMag, kMaxMag, &decoded).ok());
    ASSERT_EQ(decoded, c.values);
  }
}

// ---- Malformed input: every case must fail cleanly (a sanitizer build checks the rest). ----

void ExpectError(const std::vector<uint8_t>& bytes, uint32_t count, int code,
                 const std::string& message_part = "", int32_t lo = -kMaxMag,
                 int32_t hi = kMaxMag) {
  std::vector<int32_t> decoded;
  const Status status = DecodeBlock(bytes, count, lo, hi, &decoded);
  EXPECT_EQ(status.code(), code) << status.message();
  EXPECT_NE(status.message().find(message_part), std::string::npos) << status.message();
}

TEST(EntropyTest, TruncatedAtEveryPosition) {
  for (uint32_t count : {50u, 5000u}) {  // Both the search and the table decoder.
    std::vector<int32_t> values = Laplacian(count, 2.0, 40, 19);
    values[7] = 40;  // A zero run in the table.
    values[8] = -40;
    const std::vector<uint8_t> bytes = EncodeBlock(values);
    for (size_t size = 0; size < bytes.size(); ++size) {
      const std::vector<uint8_t> prefix(bytes.begin(), bytes.begin() + size);
      std::vector<int32_t> decoded;
      EXPECT_EQ(DecodeBlock(prefix, count, -kMaxMag, kMaxMag, &decoded).code(), M4D_ERR_BITSTREAM)
          << "size " << size;
    }
  }
}

TEST(EntropyTest, RejectsBadAlphabetSize) {
  ExpectError({0, 0}, 1, M4D_ERR_BITSTREAM, "alphabet_size 0");
  ExpectError({0x81, 0x20, 0}, 1, M4D_ERR_LIMIT, "alphabet_size 4097");  // 4097
  ExpectError({0xff, 0xff, 0xff, 0xff, 0xff, 0x01}, 1, M4D_ERR_BITSTREAM, "alphabet_size");
  ExpectError({}, 1, M4D_ERR_BITSTREAM, "truncated alphabet_size");
}

TEST(EntropyTest, RejectsMinOutOfRange) {
  std::vector<uint8_t> bytes;
  ByteWriter writer(&bytes);
  writer.WriteVarUint(1);
  writer.WriteVarSint(kMaxMag + 1);
  ExpectError(bytes, 1, M4D_ERR_BITSTREAM, "magnitude");
  bytes.clear();
  writer.WriteVarUint(1);
  writer.WriteVarSint(-kMaxMag - 1);
  ExpectError(bytes, 1, M4D_ERR_BITSTREAM, "magnitude");
  // m within range but m + n - 1 above it.
  ExpectError(RawBlock(3, kMaxMag - 1, {16384, 16384, 0, 0}, {0, 0, 0x80, 0}), 1, M4D_ERR_BITSTREAM,
              "magnitude");
}

TEST(EntropyTest, RejectsBadFrequencyTables) {
  const std::vector<uint8_t> state = {0, 0, 0x80, 0};
  ExpectError(RawBlock(2, 0, {16384, 16383}, state), 1, M4D_ERR_BITSTREAM,
              "frequencies sum to 32767, expected 32768");
  ExpectError(RawBlock(2, 0, {16384, 16385}, state), 1, M4D_ERR_BITSTREAM, "sum to 32769");
  ExpectError(RawBlock(2, 0, {32769, 0, 0}, state), 1, M4D_ERR_BITSTREAM, "above 32768");
  // A frequency of 2^32 - 1 must not wrap the sum.
  ExpectError(RawBlock(3, 0, {0xffffffffu, 1, 32768}, state), 1, M4D_ERR_BITSTREAM);
  // Zero run past the end of the alphabet.
  ExpectError(RawBlock(3, 0, {32768, 0, 2}, state), 1, M4D_ERR_BITSTREAM, "zero run");
  ExpectError(RawBlock(3, 0, {0, 5, 32768}, state), 1, M4D_ERR_BITSTREAM, "zero run");
  // All zero.
  ExpectError(RawBlock(4, 0, {0, 3}, state), 1, M4D_ERR_BITSTREAM, "sum to 0");
}

TEST(EntropyTest, RejectsBadPayloadSize) {
  const std::vector<int32_t> values = Uniform(100, 0, 9, 20);
  std::vector<uint8_t> bytes = EncodeBlock(values);
  // Payload size larger than what remains: drop the last byte.
  bytes.pop_back();
  ExpectError(bytes, 100, M4D_ERR_BITSTREAM, "exceeds");
  // Payload sizes below 4.
  for (uint8_t size = 0; size < 4; ++size) {
    std::vector<uint8_t> raw = RawBlock(2, 0, {16384, 16384}, {});
    raw.back() = size;
    raw.insert(raw.end(), size, 0);
    ExpectError(raw, 1, M4D_ERR_BITSTREAM, "below 4");
  }
}

TEST(EntropyTest, RejectsTrailingPayloadBytes) {
  const std::vector<uint32_t> freqs = {10000, 0, 22768};
  std::vector<uint32_t> symbols(3000);
  std::mt19937 rng(21);
  for (auto& s : symbols) s = rng() % 3 == 0 ? 0 : 2;
  for (uint32_t count : {100u, 3000u}) {
    std::vector<uint8_t> payload = RansEncode(symbols.data(), count, freqs);
    std::vector<int32_t> decoded;
    ASSERT_TRUE(
        DecodeBlock(RawBlock(3, 0, {10000, 0, 0, 22768}, payload), count, 0, 2, &decoded).ok());
    for (uint32_t k = 0; k < count; ++k) ASSERT_EQ(decoded[k], static_cast<int32_t>(symbols[k]));
    payload.push_back(0x55);
    ExpectError(RawBlock(3, 0, {10000, 0, 0, 22768}, payload), count, M4D_ERR_BITSTREAM,
                "left over");
  }
}

TEST(EntropyTest, RejectsWrongCount) {
  const std::vector<int32_t> values = Laplacian(4000, 3.0, 100, 22);
  const std::vector<uint8_t> bytes = EncodeBlock(values);
  for (uint32_t count : {1u, 1999u, 3999u, 4001u, 8000u, 100000u}) {
    ExpectError(bytes, count, M4D_ERR_BITSTREAM, "symbol block");
  }
}

TEST(EntropyTest, RejectsWrongFinalState) {
  // Symbol 1 owns the whole range, so the state stays at its initial value.
  ExpectError(RawBlock(2, 0, {0, 0, 32768}, {1, 0, 0x80, 0}), 10, M4D_ERR_BITSTREAM,
              "final rANS state 0 is 8388609");
  // An initial state below L pulls in bytes until it reaches L: legal, and here it works out.
  std::vector<int32_t> decoded;
  EXPECT_TRUE(
      DecodeBlock(RawBlock(2, 0, {0, 0, 32768}, {0, 0x80, 0, 0, 0}), 3, 0, 1, &decoded).ok());
  EXPECT_EQ(decoded, (std::vector<int32_t>{1, 1, 1}));
  ExpectError(RawBlock(2, 0, {0, 0, 32768}, {0, 0, 0, 0}), 3, M4D_ERR_BITSTREAM, "exhausted");
}

// Version 0.4's interleaved states (spec 5.2): blocks of 4096 values or more use four.
TEST(EntropyTest, InterleavedStatesFromTheMinimumCount) {
  EXPECT_EQ(RansStates(RansLayout::kInterleaved, 4095), 1u);
  EXPECT_EQ(RansStates(RansLayout::kInterleaved, 4096), 4u);
  EXPECT_EQ(RansStates(RansLayout::kSingleState, 1u << 20), 1u);
  for (uint32_t count : {4095u, 4096u, 4097u, 4098u, 4099u, 10001u}) {
    const std::vector<int32_t> values = Laplacian(count, 1.5, 300, 40 + count);
    const std::vector<uint8_t> one = EncodeBlock(values, RansLayout::kSingleState);
    const std::vector<uint8_t> four = EncodeBlock(values, RansLayout::kInterleaved);
    for (RansLayout layout : {RansLayout::kSingleState, RansLayout::kInterleaved}) {
      const std::vector<uint8_t>& bytes = layout == RansLayout::kSingleState ? one : four;
      std::vector<int32_t> decoded;
      size_t consumed = 0;
      const Status status = DecodeBlock(bytes, count, -300, 300, &decoded, &consumed, layout);
      ASSERT_TRUE(status.ok()) << count << ": " << status.message();
      EXPECT_EQ(consumed, bytes.size());
      EXPECT_EQ(decoded, values) << count;
    }
    // Three more 4-byte states, and the same bytes below the minimum count.
    if (count < kRansInterleaveMinCount) {
      EXPECT_EQ(four, one);
    } else {
      EXPECT_NEAR(static_cast<double>(four.size()), one.size() + 12.0, 2.0) << count;
      std::vector<int32_t> decoded;
      EXPECT_EQ(DecodeBlock(one, count, -300, 300, &decoded).code(), M4D_ERR_BITSTREAM) << count;
    }
  }
}

TEST(EntropyTest, InterleavedStatesAreEachChecked) {
  // Symbol 1 owns the whole range: every state stays at its initial value.
  const std::vector<uint32_t> table = {0, 0, 32768};
  std::vector<uint8_t> states;
  for (int j = 0; j < 4; ++j) states.insert(states.end(), {0, 0, 0x80, 0});
  std::vector<int32_t> decoded;
  ASSERT_TRUE(DecodeBlock(RawBlock(2, 0, table, states), 4096, 0, 1, &decoded).ok());
  EXPECT_EQ(decoded, std::vector<int32_t>(4096, 1));
  std::vector<uint8_t> bad = states;
  bad[12] = 1;  // the fourth state ends at L + 1
  ExpectError(RawBlock(2, 0, table, bad), 4096, M4D_ERR_BITSTREAM, "final rANS state 3 is 8388609");
  // Each state may start below L and pull in its bytes at its first symbol.
  std::vector<uint8_t> low = states;
  low[8] = 0, low[9] = 0x80, low[10] = 0;  // the third state starts at 2^15
  low.push_back(0);
  ASSERT_TRUE(DecodeBlock(RawBlock(2, 0, table, low), 4097, 0, 1, &decoded).ok());
  EXPECT_EQ(decoded, std::vector<int32_t>(4097, 1));
  // Four states need 16 payload bytes.
  states.resize(15);
  ExpectError(RawBlock(2, 0, table, states), 4096, M4D_ERR_BITSTREAM, "payload_size 15 below 16");
}

TEST(EntropyTest, CorruptedPayloadNeverCrashes) {
  std::mt19937 rng(23);
  int detected = 0, total = 0;
  for (uint32_t count : {60u, 4000u}) {
    const std::vector<int32_t> values = Laplacian(count, 5.0, 200, 24 + count);
    const std::vector<uint8_t> bytes = EncodeBlock(values);
    // Corrupt every byte of the block (table, sizes and payload) in several ways.
    for (size_t pos = 0; pos<bytes.size(); pos += count> 1000 ? 7 : 1) {
      for (uint32_t mask : {0x01u, 0x80u, 0xffu, static_cast<uint32_t>(rng() % 255) | 1u}) {
        std::vector<uint8_t> bad = bytes;
        bad[pos] ^= static_cast<uint8_t>(mask);
        std::vector<int32_t> decoded;
        const Status status = DecodeBlock(bad, count, -200, 200, &decoded);
        ++total;
        if (!status.ok()) {
          EXPECT_TRUE(status.code() == M4D_ERR_BITSTREAM || status.code() == M4D_ERR_LIMIT);
          ++detected;
        } else {
          for (int32_t v : decoded) ASSERT_TRUE(v >= -200 && v <= 200);
        }
      }
    }
  }
  std::printf("[ corrupt  ] %d of %d corrupted blocks rejected\n", detected, total);
  EXPECT_GT(detected, total * 9 / 10);
}

TEST(EntropyTest, RandomGarbageNeverCrashes) {
  std::mt19937 rng(25);
  for (int trial = 0; trial < 20000; ++trial) {
    std::vector<uint8_t> bytes(rng() % 40);
    for (auto& b : bytes) b = static_cast<uint8_t>(rng());
    if (!bytes.empty() && trial % 2) bytes[0] = static_cast<uint8_t>(2 + rng() % 6);  // Small n.
    std::vector<int32_t> decoded;
    DecodeBlock(bytes, rng() % 64, -kMaxMag, kMaxMag, &decoded);
  }
}

TEST(EntropyTest, RejectsValuesOutsideRange) {
  std::vector<int32_t> values = Uniform(3000, -3, 3, 26);
  const std::vector<uint8_t> bytes = EncodeBlock(values);
  std::vector<int32_t> decoded;
  EXPECT_TRUE(DecodeBlock(bytes, 3000, -3, 3, &decoded).ok());
  ExpectError(bytes, 3000, M4D_ERR_BITSTREAM, "outside the allowed range -2..3", -2, 3);
  ExpectError(bytes, 3000, M4D_ERR_BITSTREAM, "outside", -3, 2);
  // Single-value blocks.
  ExpectError(EncodeBlock({5, 5}), 2, M4D_ERR_BITSTREAM, "outside", 0, 4);
  ExpectError(EncodeBlock({-1}), 1, M4D_ERR_BITSTREAM, "outside", 0, 1);
  EXPECT_TRUE(DecodeBlock(EncodeBlock({4, 4}), 2, 0, 4, &decoded).ok());
  // Alphabet symbols of frequency 0 can never be decoded, so they may lie outside.
  std::vector<uint32_t> symbols(10, 1);
  symbols[3] = 2;
  const std::vector<uint8_t> payload = RansEncode(symbols.data(), 10, {0, 30000, 2768, 0});
  const std::vector<uint8_t> edge_zeros = RawBlock(4, -1, {0, 0, 30000, 2768, 0, 0}, payload);
  ASSERT_TRUE(DecodeBlock(edge_zeros, 10, 0, 1, &decoded).ok());
  EXPECT_EQ(decoded[3], 1);
  EXPECT_EQ(decoded[4], 0);
  ExpectError(edge_zeros, 10, M4D_ERR_BITSTREAM, "outside", 0, 0);
}

}  // namespace
}  // namespace m4d
