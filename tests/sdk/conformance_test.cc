// Decodes every stream of conformance/streams/ and compares each frame's hash with the
// expected hashes committed beside it (<name>.md5: "<frame_index> <md5>" per line), for
// every layer choice that has an expected file (<name>.<layers>.md5 for static/dynamic).
#include <gtest/gtest.h>

#include <dirent.h>

#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "tests/sdk/packet_test_util.h"

namespace m4d {
namespace testing {
namespace {

const std::string kDir = std::string(M4D_SOURCE_DIR) + "/conformance/streams/";

std::vector<std::string> StreamNames() {
  std::vector<std::string> names;
  if (DIR* dir = opendir(kDir.c_str())) {
    while (dirent* entry = readdir(dir)) {
      const std::string name = entry->d_name;
      if (name.size() > 4 && name.substr(name.size() - 4) == ".m4d") {
        names.push_back(name.substr(0, name.size() - 4));
      }
    }
    closedir(dir);
  }
  return names;
}

std::vector<std::string> ExpectedLines(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) {
    if (!line.empty()) lines.push_back(line);
  }
  return lines;
}

TEST(Conformance, EveryStreamDecodesToItsExpectedHashes) {
  const std::vector<std::string> names = StreamNames();
  ASSERT_GE(names.size(), 12u) << "no conformance streams in " << kDir;
  const std::pair<const char*, uint32_t> choices[] = {
      {"", M4D_LAYER_ALL}, {".static", M4D_LAYER_STATIC}, {".dynamic", M4D_LAYER_DYNAMIC}};
  for (const std::string& name : names) {
    std::ifstream file(kDir + name + ".m4d", std::ios::binary);
    const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(file)),
                                     std::istreambuf_iterator<char>());
    for (const auto& [suffix, layers] : choices) {
      const std::vector<std::string> expected = ExpectedLines(kDir + name + suffix + ".md5");
      if (expected.empty() && *suffix) continue;
      ASSERT_FALSE(expected.empty()) << name << ": no expected hashes";
      M4dSettings s = DefaultSettings();
      s.layers = layers;
      const DecodeResult r = DecodeWith(s, SplitPackets(bytes));
      EXPECT_TRUE(r.errors.empty()) << name;
      std::vector<std::string> got;
      for (size_t i = 0; i < r.hashes.size(); ++i) {
        got.push_back(std::to_string(r.frame_indices[i]) + " " + r.hashes[i]);
      }
      EXPECT_EQ(got, expected) << name << suffix;
    }
  }
}

}  // namespace
}  // namespace testing
}  // namespace m4d
