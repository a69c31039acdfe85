// Helpers for dataset loader tests: per-test temporary directories, a synthetic camera rig,
// projection, view images and a small zip writer (for .npz fixtures).
#ifndef M4D_TESTS_CAPTURE_INPUT_DATASET_TEST_UTIL_H_
#define M4D_TESTS_CAPTURE_INPUT_DATASET_TEST_UTIL_H_

#include <gtest/gtest.h>
#include <zlib.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "encoder/src/image/image.h"
#include "encoder/src/image_io/byte_samples.h"
#include "sdk/src/render/camera.h"

namespace m4d {
namespace testing {

// A directory in the test temporary directory, unique per test, removed with its contents
// when the object goes.
class TempDir {
 public:
  TempDir() {
    const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = ::testing::TempDir() + "m4d_" + info->test_suite_name() + "_" + info->name();
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code error;
    std::filesystem::remove_all(path_, error);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::string& path() const { return path_; }
  // Creates the subdirectory (and its parents) and returns its path.
  std::string Subdir(const std::string& name) const {
    const std::string dir = path_ + "/" + name;
    std::filesystem::create_directories(dir);
    return dir;
  }

 private:
  std::string path_;
};

// A camera at `eye` looking at `target` with world +y up (OpenCV axes: image y points down).
inline Camera LookAt(const double eye[3], const double target[3], int width, int height, double fx,
                     double fy, double cx, double cy) {
  double z[3] = {target[0] - eye[0], target[1] - eye[1], target[2] - eye[2]};
  const double zn = std::sqrt(z[0] * z[0] + z[1] * z[1] + z[2] * z[2]);
  for (double& v : z) v /= zn;
  double x[3] = {-z[2], 0, z[0]};  // z x (0, 1, 0)
  const double xn = std::sqrt(x[0] * x[0] + x[2] * x[2]);
  for (double& v : x) v /= xn;
  const double y[3] = {z[1] * x[2] - z[2] * x[1], z[2] * x[0] - z[0] * x[2],
                       z[0] * x[1] - z[1] * x[0]};
  const double* rows[3] = {x, y, z};
  Camera camera;
  camera.width = width;
  camera.height = height;
  camera.fx = static_cast<float>(fx);
  camera.fy = static_cast<float>(fy);
  camera.cx = static_cast<float>(cx);
  camera.cy = static_cast<float>(cy);
  for (int r = 0; r < 3; ++r) {
    double t = 0;
    for (int c = 0; c < 3; ++c) {
      camera.rotation[3 * r + c] = static_cast<float>(rows[r][c]);
      t -= rows[r][c] * eye[c];
    }
    camera.translation[r] = static_cast<float>(t);
  }
  return camera;
}

// n cameras around the origin looking at it. With `centred`, fx == fy and the principal
// point is the image centre (all N3DV can express); otherwise intrinsics vary per camera.
inline std::vector<Camera> Rig(int n, int width, int height, bool centred) {
  std::vector<Camera> cameras;
  const double target[3] = {0.1, 0.2, -0.1};
  for (int c = 0; c < n; ++c) {
    const double angle = 0.7 * c + 0.3;
    const double eye[3] = {4 * std::sin(angle), 0.5 + 0.3 * c, 4 * std::cos(angle)};
    const double fx = 50 + 3 * c;
    cameras.push_back(centred
                          ? LookAt(eye, target, width, height, fx, fx, 0.5 * width, 0.5 * height)
                          : LookAt(eye, target, width, height, fx, fx * 1.05, 0.5 * width + 1.5 * c,
                                   0.5 * height - 0.75 * c));
  }
  return cameras;
}

// Pixel coordinates of a world point (the convention of render/camera.h).
inline void Project(const Camera& camera, const double p[3], double* u, double* v) {
  double q[3];
  for (int r = 0; r < 3; ++r) {
    q[r] = camera.translation[r];
    for (int c = 0; c < 3; ++c) q[r] += static_cast<double>(camera.rotation[3 * r + c]) * p[c];
  }
  *u = camera.fx * q[0] / q[2] + camera.cx;
  *v = camera.fy * q[1] / q[2] + camera.cy;
}

inline void ExpectSameCamera(const Camera& a, const Camera& b, double tolerance) {
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  EXPECT_NEAR(a.fx, b.fx, tolerance);
  EXPECT_NEAR(a.fy, b.fy, tolerance);
  EXPECT_NEAR(a.cx, b.cx, tolerance);
  EXPECT_NEAR(a.cy, b.cy, tolerance);
  for (int i = 0; i < 9; ++i) EXPECT_NEAR(a.rotation[i], b.rotation[i], tolerance) << i;
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(a.translation[i], b.translation[i], tolerance) << i;
}

// Smooth content that differs per view, quantised to 8 bits so image files keep it exactly.
inline Image ViewImage(int width, int height, int frame, int camera) {
  Image image(width, height, 3);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const float values[3] = {
          0.1f + 0.8f * x / width, 0.15f + 0.7f * y / height,
          0.3f + 0.05f * camera + 0.04f * frame + 0.1f * std::sin(0.1f * (x + y + 3 * frame))};
      for (int c = 0; c < 3; ++c) image.at(x, y, c) = ByteToFloat(FloatToByte(values[c]));
    }
  }
  return image;
}

// How a zip entry is written.
enum class ZipMethod { kStored, kDeflated, kDeflatedWithDescriptor, kStoredZip64 };

inline void PutLittle(uint64_t v, int bytes, std::vector<uint8_t>* out) {
  for (int i = 0; i < bytes; ++i) out->push_back(static_cast<uint8_t>(v >> (8 * i)));
}

inline std::vector<uint8_t> RawDeflate(const std::vector<uint8_t>& data) {
  z_stream stream = {};
  EXPECT_EQ(deflateInit2(&stream, 9, Z_DEFLATED, -MAX_WBITS, 8, Z_DEFAULT_STRATEGY), Z_OK);
  std::vector<uint8_t> out(deflateBound(&stream, data.size()));
  stream.next_in = const_cast<Bytef*>(data.data());
  stream.avail_in = static_cast<uInt>(data.size());
  stream.next_out = out.data();
  stream.avail_out = static_cast<uInt>(out.size());
  EXPECT_EQ(deflate(&stream, Z_FINISH), Z_STREAM_END);
  out.resize(stream.total_out);
  deflateEnd(&stream);
  return out;
}

struct ZipEntryData {
  std::string name;
  std::vector<uint8_t> contents;
};

// A zip archive of the entries (local headers, data, central directory, end record).
inline std::vector<uint8_t> MakeZip(const std::vector<ZipEntryData>& entries, ZipMethod method) {
  std::vector<uint8_t> zip, central;
  for (const ZipEntryData& entry : entries) {
    const bool deflated =
        method == ZipMethod::kDeflated || method == ZipMethod::kDeflatedWithDescriptor;
    const bool descriptor = method == ZipMethod::kDeflatedWithDescriptor;
    const bool zip64 = method == ZipMethod::kStoredZip64;
    const std::vector<uint8_t> data = deflated ? RawDeflate(entry.contents) : entry.contents;
    const uint32_t crc = static_cast<uint32_t>(crc32(crc32(0, Z_NULL, 0), entry.contents.data(),
                                                     static_cast<uInt>(entry.contents.size())));
    const uint32_t offset = static_cast<uint32_t>(zip.size());
    PutLittle(0x04034b50, 4, &zip);
    PutLittle(zip64 ? 45 : 20, 2, &zip);
    PutLittle(descriptor ? 8 : 0, 2, &zip);
    PutLittle(deflated ? 8 : 0, 2, &zip);
    PutLittle(0, 4, &zip);  // time and date
    PutLittle(descriptor ? 0 : crc, 4, &zip);
    PutLittle(descriptor ? 0 : zip64 ? 0xffffffff : data.size(), 4, &zip);
    PutLittle(descriptor ? 0 : zip64 ? 0xffffffff : entry.contents.size(), 4, &zip);
    PutLittle(entry.name.size(), 2, &zip);
    PutLittle(zip64 ? 20 : 0, 2, &zip);
    zip.insert(zip.end(), entry.name.begin(), entry.name.end());
    if (zip64) {
      PutLittle(0x0001, 2, &zip);
      PutLittle(16, 2, &zip);
      PutLittle(entry.contents.size(), 8, &zip);
      PutLittle(data.size(), 8, &zip);
    }
    zip.insert(zip.end(), data.begin(), data.end());
    if (descriptor) {
      PutLittle(0x08074b50, 4, &zip);
      PutLittle(crc, 4, &zip);
      PutLittle(data.size(), 4, &zip);
      PutLittle(entry.contents.size(), 4, &zip);
    }
    PutLittle(0x02014b50, 4, &central);
    PutLittle(20, 2, &central);
    PutLittle(20, 2, &central);
    PutLittle(descriptor ? 8 : 0, 2, &central);
    PutLittle(deflated ? 8 : 0, 2, &central);
    PutLittle(0, 4, &central);
    PutLittle(crc, 4, &central);
    PutLittle(data.size(), 4, &central);
    PutLittle(entry.contents.size(), 4, &central);
    PutLittle(entry.name.size(), 2, &central);
    central.insert(central.end(), 12, 0);  // extra, comment, disk, attributes
    PutLittle(offset, 4, &central);
    central.insert(central.end(), entry.name.begin(), entry.name.end());
  }
  const uint32_t central_offset = static_cast<uint32_t>(zip.size());
  zip.insert(zip.end(), central.begin(), central.end());
  PutLittle(0x06054b50, 4, &zip);
  PutLittle(0, 4, &zip);
  PutLittle(entries.size(), 2, &zip);
  PutLittle(entries.size(), 2, &zip);
  PutLittle(central.size(), 4, &zip);
  PutLittle(central_offset, 4, &zip);
  PutLittle(0, 2, &zip);
  return zip;
}

}  // namespace testing
}  // namespace m4d

#endif  // M4D_TESTS_CAPTURE_INPUT_DATASET_TEST_UTIL_H_
