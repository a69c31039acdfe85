// NumPy .npz archives: zip files of .npy arrays, as np.savez and np.savez_compressed write.
#ifndef M4D_ENCODER_DATASET_NPZ_ARCHIVE_H_
#define M4D_ENCODER_DATASET_NPZ_ARCHIVE_H_

#include <cstddef>
#include <cstdint>
#include <string>

#include "encoder/src/dataset/npy_array.h"
#include "sdk/src/common/status.h"

namespace m4d {

// The array saved under `name` (the archive entry "<name>.npy"); see ReadZipEntry and
// ParseNpy for the errors.
Status ParseNpzArray(const uint8_t* data, size_t size, const std::string& name, NpyArray* array);
Status ReadNpzArray(const std::string& path, const std::string& name, NpyArray* array);

}  // namespace m4d

#endif  // M4D_ENCODER_DATASET_NPZ_ARCHIVE_H_
