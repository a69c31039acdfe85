#include "encoder/src/dataset/json_object.h"

#include <algorithm>

namespace m4d {
namespace {

using Json = nlohmann::json;

Status ErrorAt(const std::string& path, const std::vector<uint8_t>& bytes, size_t offset,
               const std::string& cause) {
  size_t line = 0, column = 0;
  LineAndColumn(bytes, offset, &line, &column);
  return Status(M4D_ERR_INVALID_ARG, "'" + path + "' line " + std::to_string(line) + ", column " +
                                         std::to_string(column) + ": " + cause);
}

// nlohmann's message without its "[json.exception...] parse error at line L, column C: "
// prefix (the position is given the same way for every error).
std::string Cause(const std::string& what) {
  const size_t bracket = what.find("] ");
  std::string cause = bracket == std::string::npos ? what : what.substr(bracket + 2);
  const size_t column = cause.find("column ");
  const size_t colon = column == std::string::npos ? column : cause.find(": ", column);
  return colon == std::string::npos ? cause : cause.substr(colon + 2);
}

// A number too large for a double has no position in nlohmann's error: it is its token's
// first occurrence.
size_t TokenOffset(const std::vector<uint8_t>& bytes, const std::string& what) {
  const size_t open = what.find('\'');
  const size_t close = what.rfind('\'');
  if (open == std::string::npos || close <= open + 1) return 0;
  const std::string token = what.substr(open + 1, close - open - 1);
  const auto at = std::search(bytes.begin(), bytes.end(), token.begin(), token.end());
  return at == bytes.end() ? 0 : static_cast<size_t>(at - bytes.begin());
}

}  // namespace

void LineAndColumn(const std::vector<uint8_t>& bytes, size_t offset, size_t* line, size_t* column) {
  offset = std::min(offset, bytes.size());
  *line = 1;
  size_t line_start = 0;
  for (size_t i = 0; i < offset; ++i) {
    if (bytes[i] == '\n') ++*line, line_start = i + 1;
  }
  *column = offset - line_start + 1;
}

Status ParseJsonObject(const std::string& path, const std::vector<uint8_t>& bytes, Json* json) {
  try {
    *json = Json::parse(bytes.begin(), bytes.end());
  } catch (const Json::parse_error& e) {
    // e.byte counts from 1 and points at the last byte read, the one that broke the syntax.
    return ErrorAt(path, bytes, e.byte > 0 ? e.byte - 1 : 0, Cause(e.what()));
  } catch (const Json::out_of_range& e) {
    return ErrorAt(path, bytes, TokenOffset(bytes, e.what()),
                   "a number too large for a double (" + Cause(e.what()) + ")");
  } catch (const Json::exception& e) {
    return Status(M4D_ERR_INVALID_ARG, "'" + path + "': " + Cause(e.what()));
  }
  if (!json->is_object()) {
    return Status(M4D_ERR_INVALID_ARG, "'" + path + "' holds a JSON " +
                                           std::string(json->type_name()) + ", not an object");
  }
  return Status::Ok();
}

}  // namespace m4d
