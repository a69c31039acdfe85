#include "encoder/src/stream/frame_rate.h"

#include <gtest/gtest.h>

namespace m4d {
namespace {

void ExpectRate(const std::string& text, uint32_t num, uint32_t den) {
  uint32_t n = 0, d = 0;
  const Status status = ParseFrameRate(text, &n, &d);
  ASSERT_TRUE(status.ok()) << text << ": " << status.message();
  EXPECT_EQ(n, num) << text;
  EXPECT_EQ(d, den) << text;
}

TEST(FrameRateTest, ParsesIntegersFractionsAndNtscRates) {
  ExpectRate("30", 30, 1);
  ExpectRate("25", 25, 1);
  ExpectRate("29.97", 30000, 1001);
  ExpectRate("59.94", 60000, 1001);
  ExpectRate("23.976", 24000, 1001);
  ExpectRate("12.5", 12500, 1000);
  ExpectRate("30000/1001", 30000, 1001);
  ExpectRate("2147483648/1", 2147483648u, 1);
}

TEST(FrameRateTest, RefusesWhatTheHeaderCannotHold) {
  for (const char* text : {"", "0", "-30", "abc", "30fps", "30/0", "1/2.5", "nan", "inf", "1e12",
                           "2147483649/1", "/", "30/"}) {
    uint32_t n = 7, d = 7;
    const Status status = ParseFrameRate(text, &n, &d);
    EXPECT_EQ(status.code(), M4D_ERR_INVALID_ARG) << text;
    EXPECT_NE(status.message().find(text), std::string::npos) << text;
    EXPECT_EQ(n, 7u);
  }
}

}  // namespace
}  // namespace m4d
