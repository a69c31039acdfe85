// Images side by side in one PNG (ground truth beside renders), for reports.
#ifndef M4D_ENCODER_RUN_VIEW_STRIP_H_
#define M4D_ENCODER_RUN_VIEW_STRIP_H_

#include <string>
#include <vector>

#include "encoder/src/image/image.h"
#include "sdk/src/common/status.h"

namespace m4d {

// RGB images of equal height, left to right, with a 4-pixel white gap; creates the
// directory of path if needed.
Status WriteViewStrip(const std::string& path, const std::vector<const Image*>& images);

// The same strip as an image.
Status ViewStrip(const std::vector<const Image*>& images, Image* strip);

}  // namespace m4d

#endif  // M4D_ENCODER_RUN_VIEW_STRIP_H_
