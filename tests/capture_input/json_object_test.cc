// A capture's JSON file that is not JSON is refused with its line, column and cause.
#include "encoder/src/dataset/json_object.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace m4d {
namespace {

std::string Error(const std::string& text) {
  nlohmann::json json;
  const Status status =
      ParseJsonObject("transforms.json", std::vector<uint8_t>(text.begin(), text.end()), &json);
  EXPECT_EQ(status.code(), status.ok() ? M4D_OK : M4D_ERR_INVALID_ARG);
  return status.message();
}

TEST(JsonObjectTest, NanNamesItsLineAndColumn) {
  const std::string error = Error("{\n  \"fl_x\": NaN\n}");
  EXPECT_NE(error.find("'transforms.json' line 2, column 11: "), std::string::npos) << error;
  EXPECT_NE(error.find("invalid literal"), std::string::npos) << error;
}

TEST(JsonObjectTest, HugeNumberIsNamedAtItsPlace) {
  const std::string error = Error("{\"w\": 4,\n \"fl_x\": 1e999}");
  EXPECT_NE(error.find("line 2, column 10: a number too large"), std::string::npos) << error;
  EXPECT_NE(error.find("1e999"), std::string::npos) << error;
}

TEST(JsonObjectTest, CutInHalfSaysTheInputEnds) {
  const std::string error = Error("{\"frames\": [\n{\"file_path\": \"a.png\"");
  EXPECT_NE(error.find("line 2, column "), std::string::npos) << error;
  EXPECT_NE(error.find("unexpected end of input"), std::string::npos) << error;
}

TEST(JsonObjectTest, AnArrayIsNotAnObject) {
  EXPECT_EQ(Error("[1, 2]"), "'transforms.json' holds a JSON array, not an object");
  EXPECT_EQ(Error("{\"a\": 1}"), "");
}

TEST(JsonObjectTest, LineAndColumnCountFromOne) {
  const std::string text = "ab\ncd";
  const std::vector<uint8_t> bytes(text.begin(), text.end());
  size_t line = 0, column = 0;
  LineAndColumn(bytes, 0, &line, &column);
  EXPECT_EQ(line, 1u);
  EXPECT_EQ(column, 1u);
  LineAndColumn(bytes, 4, &line, &column);
  EXPECT_EQ(line, 2u);
  EXPECT_EQ(column, 2u);
}

}  // namespace
}  // namespace m4d
