// Reading one entry of a zip archive (as NumPy's .npz files are), found by walking the
// local file headers from the start: stored or deflated entries, ZIP64 sizes, data
// descriptors after deflated entries; the CRC-32 is checked.
#ifndef M4D_ENCODER_DATASET_ZIP_ARCHIVE_H_
#define M4D_ENCODER_DATASET_ZIP_ARCHIVE_H_

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "sdk/src/common/status.h"

namespace m4d {

// The contents of the entry called `name`. M4D_ERR_INVALID_ARG when the archive has no
// such entry, M4D_ERR_LIMIT when it would inflate beyond max_size bytes, M4D_ERR_BITSTREAM
// for malformed or truncated archives and CRC mismatches, M4D_ERR_UNSUPPORTED for
// encryption, other compression methods, or stored entries of unknown size.
Status ReadZipEntry(const uint8_t* data, size_t size, const std::string& name, size_t max_size,
                    std::vector<uint8_t>* contents);

}  // namespace m4d

#endif  // M4D_ENCODER_DATASET_ZIP_ARCHIVE_H_
