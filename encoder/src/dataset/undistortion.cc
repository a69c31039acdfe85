#include "encoder/src/dataset/undistortion.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "encoder/src/metrics/parallel_rows.h"

namespace m4d {
namespace {

// The pinhole image border stays this many pixels inside the valid region, so that storing
// the intrinsics as floats cannot push it out.
constexpr double kMargin = 0.01;

// Beyond a tenfold change of focal length the pinhole image would sample the distorted one
// far too coarsely (or finely) to stand for it: the lens is refused instead.
constexpr double kMaxFocalChange = 10;

Status TooStrong(const Camera& distorted, const LensDistortion& distortion, const std::string& what,
                 const char* why) {
  return Status(M4D_ERR_UNSUPPORTED, what + ": " + LensModelName(distortion.model) +
                                         " distortion (" + std::to_string(distorted.width) + "x" +
                                         std::to_string(distorted.height) + ") " + why);
}

Status CheckIntrinsics(const Camera& c, const std::string& what) {
  if (c.width < 2 || c.height < 2 || c.width > kMaxImageSide || c.height > kMaxImageSide) {
    return Status(M4D_ERR_INVALID_ARG, what + ": image too small or too large to undistort");
  }
  if (!(c.fx > 0 && c.fy > 0 && std::isfinite(c.fx) && std::isfinite(c.fy) && std::isfinite(c.cx) &&
        std::isfinite(c.cy))) {
    return Status(M4D_ERR_INVALID_ARG, what + ": intrinsics must be finite, focal lengths > 0");
  }
  return Status::Ok();
}

// The undistorted normalised coordinates of the distorted image's point (u, v).
bool UndistortPixel(const Camera& c, const LensDistortion& d, double u, double v, double* x,
                    double* y) {
  return Undistort(d, (u - c.cx) / c.fx, (v - c.cy) / c.fy, x, y);
}

// OpenCV's inner rectangle: x0 the largest undistorted x of the left edge's pixel centres, x1
// the smallest of the right edge's, y0 and y1 likewise from the top and bottom edges.
// bounds = x0, y0, x1, y1; false when the inverse fails somewhere.
bool InnerRectangle(const Camera& c, const LensDistortion& d, double bounds[4]) {
  const double inf = std::numeric_limits<double>::infinity();
  bounds[0] = bounds[1] = -inf;
  bounds[2] = bounds[3] = inf;
  double x, y;
  for (int i = 0; i < c.width; ++i) {
    if (!UndistortPixel(c, d, i + 0.5, 0.5, &x, &y)) return false;
    bounds[1] = std::max(bounds[1], y);
    if (!UndistortPixel(c, d, i + 0.5, c.height - 0.5, &x, &y)) return false;
    bounds[3] = std::min(bounds[3], y);
  }
  for (int j = 0; j < c.height; ++j) {
    if (!UndistortPixel(c, d, 0.5, j + 0.5, &x, &y)) return false;
    bounds[0] = std::max(bounds[0], x);
    if (!UndistortPixel(c, d, c.width - 0.5, j + 0.5, &x, &y)) return false;
    bounds[2] = std::min(bounds[2], x);
  }
  return true;
}

// The distorted image's column and row (pixel indices) that pinhole pixel (i, j) samples.
void SourcePixel(const Camera& distorted, const LensDistortion& d, const Camera& pinhole, int i,
                 int j, double* column, double* row) {
  double xd, yd;
  Distort(d, (i + 0.5 - pinhole.cx) / pinhole.fx, (j + 0.5 - pinhole.cy) / pinhole.fy, &xd, &yd);
  *column = distorted.fx * xd + distorted.cx - 0.5;
  *row = distorted.fy * yd + distorted.cy - 0.5;
}

bool Inside(const Camera& c, double column, double row) {
  return column >= 0 && column <= c.width - 1 && row >= 0 && row <= c.height - 1;
}

// Whether every pixel on the pinhole image border samples inside the distorted image.
bool BorderInside(const Camera& distorted, const LensDistortion& d, const Camera& pinhole) {
  bool inside = true;
  double column, row;
  for (int i = 0; i < pinhole.width; ++i) {
    for (int j : {0, pinhole.height - 1}) {
      SourcePixel(distorted, d, pinhole, i, j, &column, &row);
      inside &= Inside(distorted, column, row);
    }
  }
  for (int j = 0; j < pinhole.height; ++j) {
    for (int i : {0, pinhole.width - 1}) {
      SourcePixel(distorted, d, pinhole, i, j, &column, &row);
      inside &= Inside(distorted, column, row);
    }
  }
  return inside;
}

}  // namespace

Status UndistortedCamera(const Camera& distorted, const LensDistortion& distortion,
                         const std::string& what, Camera* pinhole) {
  M4D_RETURN_IF_ERROR(CheckLensDistortion(distortion, what));
  *pinhole = distorted;
  if (!HasDistortion(distortion)) return Status::Ok();
  M4D_RETURN_IF_ERROR(CheckIntrinsics(distorted, what));
  double b[4];
  if (!InnerRectangle(distorted, distortion, b)) {
    return TooStrong(distorted, distortion, what, "is too strong to invert at the image border");
  }
  if (!(b[2] > b[0] && b[3] > b[1])) {
    return TooStrong(distorted, distortion, what, "leaves no valid region");
  }
  // Pixel centres 0.5 and width - 0.5 (less the margin) map to x0 and x1.
  const double fx = (distorted.width - 1 + 2 * kMargin) / (b[2] - b[0]);
  const double fy = (distorted.height - 1 + 2 * kMargin) / (b[3] - b[1]);
  if (!(std::max(fx / distorted.fx, distorted.fx / fx) < kMaxFocalChange &&
        std::max(fy / distorted.fy, distorted.fy / fy) < kMaxFocalChange)) {
    return TooStrong(distorted, distortion, what, "would change the focal length tenfold");
  }
  pinhole->fx = static_cast<float>(fx);
  pinhole->fy = static_cast<float>(fy);
  pinhole->cx = static_cast<float>(0.5 - kMargin - fx * b[0]);
  pinhole->cy = static_cast<float>(0.5 - kMargin - fy * b[1]);
  if (!BorderInside(distorted, distortion, *pinhole)) {
    return TooStrong(distorted, distortion, what, "has a valid region no rectangle fits");
  }
  return Status::Ok();
}

Status BuildUndistortionMap(const Camera& distorted, const LensDistortion& distortion,
                            const Camera& pinhole, const std::string& what, UndistortionMap* map) {
  map->width = pinhole.width;
  map->height = pinhole.height;
  map->source_width = distorted.width;
  map->source_height = distorted.height;
  map->source.resize(2 * static_cast<size_t>(pinhole.width) * pinhole.height);
  ParallelForRows(pinhole.height, pinhole.width, [&](int begin, int end) {
    for (int j = begin; j < end; ++j) {
      float* out = map->source.data() + 2 * static_cast<size_t>(j) * pinhole.width;
      for (int i = 0; i < pinhole.width; ++i) {
        double column, row;
        SourcePixel(distorted, distortion, pinhole, i, j, &column, &row);
        out[2 * i] = static_cast<float>(column);
        out[2 * i + 1] = static_cast<float>(row);
      }
    }
  });
  for (size_t p = 0; p < map->source.size(); p += 2) {
    if (!Inside(distorted, map->source[p], map->source[p + 1])) {
      return TooStrong(distorted, distortion, what, "maps a pixel outside the image");
    }
  }
  return Status::Ok();
}

Status Remap(const UndistortionMap& map, const Image& source, Image* out) {
  M4D_RETURN_IF_ERROR(CheckImage(source, "undistortion source"));
  if (source.width != map.source_width || source.height != map.source_height) {
    return Status(M4D_ERR_INVALID_ARG, "undistortion: image size differs from the camera's");
  }
  Reshape(map.width, map.height, source.channels, out);
  const int channels = source.channels;
  ParallelForRows(map.height, static_cast<size_t>(map.width) * channels, [&](int begin, int end) {
    for (int j = begin; j < end; ++j) {
      const float* position = map.source.data() + 2 * static_cast<size_t>(j) * map.width;
      float* pixel = out->row(j);
      for (int i = 0; i < map.width; ++i, position += 2, pixel += channels) {
        // Positions are within the image (checked when the map was built).
        const int x0 = static_cast<int>(position[0]), y0 = static_cast<int>(position[1]);
        const int x1 = std::min(x0 + 1, source.width - 1), y1 = std::min(y0 + 1, source.height - 1);
        const float wx = position[0] - x0, wy = position[1] - y0;
        for (int c = 0; c < channels; ++c) {
          const float top =
              source.at(x0, y0, c) + wx * (source.at(x1, y0, c) - source.at(x0, y0, c));
          const float bottom =
              source.at(x0, y1, c) + wx * (source.at(x1, y1, c) - source.at(x0, y1, c));
          pixel[c] = top + wy * (bottom - top);
        }
      }
    }
  });
  return Status::Ok();
}

}  // namespace m4d
