// A capture's JSON file (transforms.json, train_meta.json) read as an object, with the error a
// person can act on: where (line and column) and why (NaN is not JSON, a number too large, the
// file cut short), not only "not a JSON object".
#ifndef M4D_ENCODER_DATASET_JSON_OBJECT_H_
#define M4D_ENCODER_DATASET_JSON_OBJECT_H_

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "sdk/src/common/status.h"

namespace m4d {

// Parses `bytes`, the contents of `path`, into *json, which must be an object. Otherwise
// M4D_ERR_INVALID_ARG: "'<path>' line L, column C: <cause>".
Status ParseJsonObject(const std::string& path, const std::vector<uint8_t>& bytes,
                       nlohmann::json* json);

// The 1-based line and column of the byte at `offset` (0-based) of `bytes`.
void LineAndColumn(const std::vector<uint8_t>& bytes, size_t offset, size_t* line, size_t* column);

}  // namespace m4d

#endif  // M4D_ENCODER_DATASET_JSON_OBJECT_H_
