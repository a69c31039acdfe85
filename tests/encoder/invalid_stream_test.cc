// The invalid conformance streams (conformance/invalid/, written by m4d_make_invalid): read
// as a player reads a file, each must first report the error its EXPECTED line names (NONE:
// none at all), then output exactly the frames of <name>.md5 (what survives: frames before the
// damage and the GOPs after it).
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "tests/encoder/stream_test_util.h"

namespace m4d {
namespace testing {
namespace {

const std::string kDir = std::string(M4D_SOURCE_DIR) + "/conformance/invalid/";

struct Expectation {
  std::string name, error;
};

std::vector<Expectation> Expectations() {
  std::ifstream in(kDir + "EXPECTED");
  std::vector<Expectation> out;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    Expectation e;
    fields >> e.name >> e.error;
    out.push_back(e);
  }
  return out;
}

std::string ErrorName(const PlayResult& r) {
  static const std::map<int, std::string> kNames = {{M4D_ERR_BITSTREAM, "M4D_ERR_BITSTREAM"},
                                                    {M4D_ERR_CHECKSUM, "M4D_ERR_CHECKSUM"},
                                                    {M4D_ERR_UNSUPPORTED, "M4D_ERR_UNSUPPORTED"},
                                                    {M4D_ERR_LIMIT, "M4D_ERR_LIMIT"},
                                                    {M4D_ERR_NOMEM, "M4D_ERR_NOMEM"}};
  if (!r.errors.empty()) {
    const auto it = kNames.find(r.errors.front());
    return it == kNames.end() ? std::to_string(r.errors.front()) : it->second;
  }
  return r.truncated ? "TRUNCATED" : "NONE";
}

TEST(InvalidStreams, EachReportsItsErrorAndKeepsWhatSurvives) {
  const std::vector<Expectation> expectations = Expectations();
  ASSERT_GE(expectations.size(), 20u) << "no EXPECTED in " << kDir;
  for (const Expectation& e : expectations) {
    std::ifstream file(kDir + e.name + ".m4d", std::ios::binary);
    ASSERT_TRUE(file) << e.name;
    const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(file)),
                                     std::istreambuf_iterator<char>());
    const PlayResult r = PlayBytes(DefaultSettings(), bytes);
    EXPECT_EQ(ErrorName(r), e.error) << e.name;
    std::ostringstream got;
    for (const auto& [index, hash] : r.frames) got << index << " " << hash << "\n";
    std::ifstream md5(kDir + e.name + ".md5");
    const std::string expected((std::istreambuf_iterator<char>(md5)),
                               std::istreambuf_iterator<char>());
    EXPECT_EQ(got.str(), expected) << e.name;
  }
}

}  // namespace
}  // namespace testing
}  // namespace m4d
