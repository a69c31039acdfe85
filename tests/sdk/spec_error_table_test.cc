// The error table of bitstream-spec section 9 is checked against the invalid conformance
// streams: every row names streams whose conformance/invalid/EXPECTED line gives the row's
// code (TRUNCATED, NONE for "none", or an M4D_ERR_* name), or says why it has none; and every
// invalid stream stands in some row. The streams' decoding is checked by InvalidStreams.* and
// the conformance runner.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace {

const std::string kRoot = M4D_SOURCE_DIR;

struct ErrorRow {
  std::string id, code;
  std::vector<std::string> streams;
  bool explains_none = false;  // "none: why"
};

std::string ReadText(const std::string& path) {
  std::ifstream in(path);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// The rows "| E<n> | condition | code | streams |" of section 9.
std::vector<ErrorRow> ErrorTable() {
  const std::string spec = ReadText(kRoot + "/bitstream-spec/README.md");
  const size_t begin = spec.find("## 9. Errors"), end = spec.find("## 10. Versioning");
  EXPECT_NE(begin, std::string::npos);
  std::istringstream section(spec.substr(begin, end - begin));
  const std::regex row(R"(^\| (E\d+) \| .* \| `?([A-Za-z0-9_]+)`? \| (.*) \|$)");
  const std::regex name("`([a-z0-9_]+)`");
  std::vector<ErrorRow> rows;
  for (std::string line; std::getline(section, line);) {
    std::smatch m;
    if (!std::regex_match(line, m, row)) continue;
    ErrorRow r{m[1], m[2], {}, m[3].str().rfind("none:", 0) == 0};
    const std::string streams = m[3];
    for (std::sregex_iterator it(streams.begin(), streams.end(), name), last; it != last; ++it) {
      if (!r.explains_none) r.streams.push_back((*it)[1]);
    }
    rows.push_back(r);
  }
  return rows;
}

// invalid/EXPECTED: stream -> first error.
std::map<std::string, std::string> Expected() {
  std::istringstream in(ReadText(kRoot + "/conformance/invalid/EXPECTED"));
  std::map<std::string, std::string> out;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    std::string stream, error;
    fields >> stream >> error;
    out[stream] = error;
  }
  return out;
}

TEST(SpecErrorTable, EveryRowHasItsStreamsAndEveryInvalidStreamARow) {
  const std::vector<ErrorRow> rows = ErrorTable();
  const std::map<std::string, std::string> expected = Expected();
  ASSERT_GE(rows.size(), 30u) << "section 9's error table not found";
  std::set<std::string> listed;
  for (const ErrorRow& r : rows) {
    EXPECT_TRUE(!r.streams.empty() || r.explains_none) << r.id << " names no stream";
    const std::string want = r.code == "none" ? "NONE" : r.code;
    for (const std::string& stream : r.streams) {
      listed.insert(stream);
      const auto it = expected.find(stream);
      ASSERT_NE(it, expected.end()) << r.id << ": " << stream << " is not in invalid/EXPECTED";
      EXPECT_EQ(it->second, want) << r.id << ": " << stream;
    }
  }
  for (const auto& [stream, error] : expected) {
    EXPECT_TRUE(listed.count(stream)) << stream << " (" << error << ") stands in no row";
  }
}

// Every invalid stream is also expected with one layer alone (spec 6.6, 6.8): a row of
// invalid/EXPECTED_LAYERS with a first error per layer, and the frames of each.
TEST(SpecErrorTable, EveryInvalidStreamHasItsLayerExpectations) {
  const std::map<std::string, std::string> expected = Expected();
  std::istringstream in(ReadText(kRoot + "/conformance/invalid/EXPECTED_LAYERS"));
  const std::set<std::string> codes = {"NONE",          "TRUNCATED",        "M4D_ERR_BITSTREAM",
                                       "M4D_ERR_LIMIT", "M4D_ERR_CHECKSUM", "M4D_ERR_UNSUPPORTED"};
  std::set<std::string> rows;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    std::string stream, by_static, by_dynamic;
    fields >> stream >> by_static >> by_dynamic;
    EXPECT_TRUE(expected.count(stream)) << stream << " is not in invalid/EXPECTED";
    EXPECT_TRUE(codes.count(by_static) && codes.count(by_dynamic)) << line;
    for (const char* layer : {"static", "dynamic"}) {
      EXPECT_TRUE(std::ifstream(kRoot + "/conformance/invalid/" + stream + "." + layer + ".md5"))
          << stream << ": no ." << layer << ".md5";
    }
    rows.insert(stream);
  }
  for (const auto& [stream, error] : expected) {
    EXPECT_TRUE(rows.count(stream)) << stream << " has no row in invalid/EXPECTED_LAYERS";
  }
}

// coverage.md's copy: "| E<n> | code | streams |" -> "code | streams".
std::map<std::string, std::string> CoverageErrorRows() {
  std::istringstream in(ReadText(kRoot + "/bitstream-spec/coverage.md"));
  const std::regex row(R"(^\| (E\d+) \| (.*) \|$)");
  std::map<std::string, std::string> out;
  for (std::string line; std::getline(in, line);) {
    std::smatch m;
    if (std::regex_match(line, m, row)) out[m[1]] = m[2];
  }
  return out;
}

TEST(SpecErrorTable, CoverageListsEveryRow) {
  const std::map<std::string, std::string> listed = CoverageErrorRows();
  const std::string spec = ReadText(kRoot + "/bitstream-spec/README.md");
  std::istringstream section(spec.substr(spec.find("## 9. Errors")));
  const std::regex row(R"(^\| (E\d+) \| .* \| (`?[A-Za-z0-9_]+`? \| .*) \|$)");
  size_t rows = 0;
  for (std::string line; std::getline(section, line) && line.rfind("## 10.", 0) != 0;) {
    std::smatch m;
    if (!std::regex_match(line, m, row)) continue;
    ++rows;
    const auto it = listed.find(m[1]);
    ASSERT_NE(it, listed.end()) << m[1] << " is not in coverage.md";
    EXPECT_EQ(it->second, m[2].str()) << m[1];
  }
  EXPECT_EQ(rows, listed.size());
}

}  // namespace
