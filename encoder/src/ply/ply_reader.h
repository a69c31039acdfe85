// Reading property values out of a PLY file's data: the chosen scalar properties of one
// element, whatever the format (ASCII, binary of either byte order), the property types and
// order, and whatever other elements and properties (lists included) the file carries.
#ifndef M4D_ENCODER_PLY_PLY_READER_H_
#define M4D_ENCODER_PLY_PLY_READER_H_

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "encoder/src/ply/ply_header.h"
#include "sdk/src/common/status.h"

namespace m4d {

// Reads properties `names` of every row of `element` as floats (doubles and integers are
// converted), row-major: (*values)[row * names.size() + i] is names[i] of that row.
// *rows receives the element's count. M4D_ERR_BITSTREAM for a missing element or property,
// a list property among `names`, or data that ends early or does not parse; the declared
// row count is checked against the bytes left before anything is allocated.
Status ReadPlyProperties(const uint8_t* data, size_t size, const PlyHeader& header,
                         const std::string& element, const std::vector<std::string>& names,
                         std::vector<float>* values, size_t* rows);

}  // namespace m4d

#endif  // M4D_ENCODER_PLY_PLY_READER_H_
