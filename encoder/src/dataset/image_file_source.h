// ImageFileSource: a FrameSource over one image file per view (PNG or JPEG), for layouts
// that store frames as images.
#ifndef M4D_ENCODER_DATASET_IMAGE_FILE_SOURCE_H_
#define M4D_ENCODER_DATASET_IMAGE_FILE_SOURCE_H_

#include <string>
#include <vector>

#include "encoder/src/capture/capture.h"
#include "sdk/src/common/status.h"

namespace m4d {

// Reads the image as RGB (grey replicated, alpha composited over black) and checks that it
// is width x height (M4D_ERR_INVALID_ARG naming the file otherwise).
Status ReadViewImage(const std::string& path, int width, int height, Image* rgb);

class ImageFileSource : public FrameSource {
 public:
  // paths[frame][camera]; each image must have the size of cameras[frame][camera].
  ImageFileSource(std::vector<std::vector<std::string>> paths,
                  const std::vector<std::vector<Camera>>& cameras);
  Status Load(int frame, int camera, Image* rgb) override;

 private:
  struct View {
    std::string path;
    int width;
    int height;
  };
  std::vector<std::vector<View>> views_;
};

}  // namespace m4d

#endif  // M4D_ENCODER_DATASET_IMAGE_FILE_SOURCE_H_
