// Capture loaders (dataset/): N3DV, nerfstudio transforms.json, COLMAP and Dynamic 3D
// Gaussians fixtures written here from one synthetic rig, layout detection, the capture
// options (frame window, downscaling, test camera) and malformed layouts.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "encoder/src/dataset/capture_loader.h"
#include "encoder/src/dataset/colmap_model.h"
#include "encoder/src/dataset/lens_distortion.h"
#include "encoder/src/dataset/npy_array.h"
#include "encoder/src/image/area_resize.h"
#include "encoder/src/image_io/file_bytes.h"
#include "encoder/src/image_io/jpeg_io.h"
#include "encoder/src/image_io/png_io.h"
#include "encoder/src/metrics/psnr.h"
#include "encoder/src/ply/point_cloud_ply.h"
#include "encoder/src/video/video_writer.h"
#include "tests/capture_input/dataset_test_util.h"

namespace m4d {
namespace {

using Json = nlohmann::json;
using testing::ExpectSameCamera;
using testing::MakeZip;
using testing::Project;
using testing::Rig;
using testing::TempDir;
using testing::ViewImage;
using testing::ZipMethod;

constexpr int kWidth = 64, kHeight = 48;

void WriteText(const std::string& path, const std::string& text) {
  ASSERT_TRUE(WriteFileBytes(path, std::vector<uint8_t>(text.begin(), text.end())).ok());
}

PointCloud SomePoints() {
  PointCloud points;
  for (int i = 0; i < 10; ++i) {
    points.positions.insert(points.positions.end(), {0.1f * i, -0.2f * i, 0.05f * i - 0.3f});
    points.colors.insert(points.colors.end(), {i / 10.0f, 0.5f, 1.0f - i / 20.0f});
  }
  return points;
}

void ExpectSamePoints(const PointCloud& a, const PointCloud& b, double colour_tolerance) {
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.positions.size(); ++i) {
    EXPECT_NEAR(a.positions[i], b.positions[i], 1e-6) << i;
    EXPECT_NEAR(a.colors[i], b.colors[i], colour_tolerance) << i;
  }
}

// The image loaded for a view equals what the fixture wrote (exactly for PNG).
void ExpectView(const Capture& capture, int frame, int camera, const Image& expected,
                double min_psnr) {
  Image image;
  const Status status = capture.LoadImage(frame, camera, &image);
  ASSERT_TRUE(status.ok()) << status.message();
  ASSERT_EQ(image.width, expected.width);
  ASSERT_EQ(image.height, expected.height);
  ASSERT_EQ(image.channels, 3);
  if (min_psnr == 0) {
    EXPECT_EQ(image.pixels, expected.pixels) << "frame " << frame << " camera " << camera;
  } else {
    double psnr = 0;
    ASSERT_TRUE(Psnr(image, expected, &psnr).ok());
    EXPECT_GT(psnr, min_psnr) << "frame " << frame << " camera " << camera;
  }
}

Status Load(const std::string& path, Capture* capture, CaptureOptions options = {}) {
  return LoadCapture(path, options, capture);
}

// ---- COLMAP fixtures (also N3DV's initial points) ----------------------------------------

// Unit quaternion (w, x, y, z) of a rotation matrix.
void Quaternion(const float* r, double q[4]) {
  const double trace = r[0] + r[4] + r[8];
  if (trace > 0) {
    const double s = 2 * std::sqrt(1 + trace);
    q[0] = s / 4;
    q[1] = (r[7] - r[5]) / s;
    q[2] = (r[2] - r[6]) / s;
    q[3] = (r[3] - r[1]) / s;
  } else if (r[0] > r[4] && r[0] > r[8]) {
    const double s = 2 * std::sqrt(1 + r[0] - r[4] - r[8]);
    q[0] = (r[7] - r[5]) / s;
    q[1] = s / 4;
    q[2] = (r[1] + r[3]) / s;
    q[3] = (r[2] + r[6]) / s;
  } else if (r[4] > r[8]) {
    const double s = 2 * std::sqrt(1 + r[4] - r[0] - r[8]);
    q[0] = (r[2] - r[6]) / s;
    q[1] = (r[1] + r[3]) / s;
    q[2] = s / 4;
    q[3] = (r[5] + r[7]) / s;
  } else {
    const double s = 2 * std::sqrt(1 + r[8] - r[0] - r[4]);
    q[0] = (r[3] - r[1]) / s;
    q[1] = (r[2] + r[6]) / s;
    q[2] = (r[5] + r[7]) / s;
    q[3] = s / 4;
  }
}

struct ColmapCameraSpec {
  int model_id;
  std::vector<double> params;
};

// COLMAP parameters of a rig camera under a model (distortion terms as given).
ColmapCameraSpec Spec(const Camera& c, const char* model, std::vector<double> distortion = {}) {
  const std::string name = model;
  ColmapCameraSpec spec;
  if (name == "SIMPLE_PINHOLE" || name == "SIMPLE_RADIAL" || name == "RADIAL") {
    spec.params = {c.fx, c.cx, c.cy};
  } else {
    spec.params = {c.fx, c.fy, c.cx, c.cy};
  }
  spec.params.insert(spec.params.end(), distortion.begin(), distortion.end());
  spec.model_id = ColmapModelId(name);
  return spec;
}

void Put(const void* p, size_t n, std::vector<uint8_t>* out) {
  const uint8_t* b = static_cast<const uint8_t*>(p);
  out->insert(out->end(), b, b + n);
}
template <typename T>
void Put(T v, std::vector<uint8_t>* out) {
  Put(&v, sizeof(v), out);
}

// Writes the model (camera ids 10 + c, image ids 100 + c, images named "view_c.png" in
// reverse order) as binary or text, and the images.
void WriteColmap(const std::string& dir, const std::vector<Camera>& rig,
                 const std::vector<ColmapCameraSpec>& specs, const PointCloud& points,
                 bool binary) {
  std::filesystem::create_directories(dir + "/sparse/0");
  std::filesystem::create_directories(dir + "/images");
  const std::string model = dir + "/sparse/0/";
  std::vector<uint8_t> cameras, images, points3d;
  std::string cameras_txt = "# Camera list\n", images_txt = "# Image list\n#\n",
              points_txt = "# 3D point list\n";
  Put<uint64_t>(rig.size(), &cameras);
  Put<uint64_t>(rig.size(), &images);
  Put<uint64_t>(points.size(), &points3d);
  char line[512];
  for (int c = static_cast<int>(rig.size()) - 1; c >= 0; --c) {
    const Camera& camera = rig[c];
    Put<int32_t>(10 + c, &cameras);
    Put<int32_t>(specs[c].model_id, &cameras);
    Put<uint64_t>(camera.width, &cameras);
    Put<uint64_t>(camera.height, &cameras);
    std::snprintf(line, sizeof(line), "%d %s %d %d", 10 + c, ColmapModelName(specs[c].model_id),
                  camera.width, camera.height);
    cameras_txt += line;
    for (double p : specs[c].params) {
      Put(p, &cameras);
      std::snprintf(line, sizeof(line), " %.17g", p);
      cameras_txt += line;
    }
    cameras_txt += "\n";

    double q[4];
    Quaternion(camera.rotation, q);
    const std::string name = "view_" + std::to_string(c) + ".png";
    Put<int32_t>(100 + c, &images);
    for (double v : q) Put(v, &images);
    for (float t : camera.translation) Put<double>(t, &images);
    Put<int32_t>(10 + c, &images);
    Put(name.c_str(), name.size() + 1, &images);
    Put<uint64_t>(2, &images);  // two 2D points, unused
    for (int i = 0; i < 2; ++i) {
      Put<double>(1.5 * i, &images);
      Put<double>(2.5, &images);
      Put<int64_t>(i == 0 ? -1 : 7, &images);
    }
    std::snprintf(line, sizeof(line), "%d %.17g %.17g %.17g %.17g %.17g %.17g %.17g %d %s\n",
                  100 + c, q[0], q[1], q[2], q[3], static_cast<double>(camera.translation[0]),
                  static_cast<double>(camera.translation[1]),
                  static_cast<double>(camera.translation[2]), 10 + c, name.c_str());
    images_txt += line;
    images_txt += c % 2 ? "0 2.5 -1 1.5 2.5 7\n" : "\n";  // 2D points (possibly none)
    ASSERT_TRUE(
        WritePng(dir + "/images/" + name, ViewImage(camera.width, camera.height, 0, c)).ok());
  }
  for (size_t i = 0; i < points.size(); ++i) {
    Put<uint64_t>(i + 1, &points3d);
    uint8_t rgb[3];
    for (int a = 0; a < 3; ++a) {
      Put<double>(points.positions[3 * i + a], &points3d);
      rgb[a] = FloatToByte(points.colors[3 * i + a]);
    }
    Put(rgb, 3, &points3d);
    Put<double>(0.5, &points3d);
    Put<uint64_t>(1, &points3d);
    Put<int32_t>(100, &points3d);
    Put<int32_t>(0, &points3d);
    std::snprintf(line, sizeof(line), "%zu %.17g %.17g %.17g %d %d %d 0.5 100 0\n", i + 1,
                  static_cast<double>(points.positions[3 * i]),
                  static_cast<double>(points.positions[3 * i + 1]),
                  static_cast<double>(points.positions[3 * i + 2]), rgb[0], rgb[1], rgb[2]);
    points_txt += line;
  }
  if (binary) {
    ASSERT_TRUE(WriteFileBytes(model + "cameras.bin", cameras).ok());
    ASSERT_TRUE(WriteFileBytes(model + "images.bin", images).ok());
    ASSERT_TRUE(WriteFileBytes(model + "points3D.bin", points3d).ok());
  } else {
    WriteText(model + "cameras.txt", cameras_txt);
    WriteText(model + "images.txt", images_txt);
    WriteText(model + "points3D.txt", points_txt);
  }
}

std::vector<ColmapCameraSpec> MixedSpecs(std::vector<Camera>* rig) {
  (*rig)[1].fy = (*rig)[1].fx;  // the one-focal-length models
  (*rig)[3].fy = (*rig)[3].fx;
  return {Spec((*rig)[0], "PINHOLE"), Spec((*rig)[1], "SIMPLE_PINHOLE"),
          Spec((*rig)[2], "OPENCV", {0.0, 0.0, 0.0, 0.0}), Spec((*rig)[3], "SIMPLE_RADIAL", {0})};
}

// ---- N3DV -----------------------------------------------------------------------------

enum class N3dvFrames { kVideos, kCameraImages, kFramesDir };

// poses_bounds row of a camera, recorded at twice the image size (W = 2 width, f = 2 fx) as
// the original N3DV videos are larger than the training images.
std::vector<double> PosesRow(const Camera& camera) {
  const float* r = camera.rotation;
  float centre[3];
  CameraCentre(camera, centre);
  // LLFF columns (down, right, back) are OpenCV's y, x and -z axes in world coordinates,
  // i.e. rows 1, 0 and -2 of the world-to-camera rotation.
  const double columns[4][3] = {{r[3], r[4], r[5]},
                                {r[0], r[1], r[2]},
                                {-r[6], -r[7], -r[8]},
                                {centre[0], centre[1], centre[2]}};
  const double hwf[3] = {2.0 * camera.height, 2.0 * camera.width, 2.0 * camera.fx};
  std::vector<double> row;
  for (int i = 0; i < 3; ++i) {
    for (int c = 0; c < 4; ++c) row.push_back(columns[c][i]);
    row.push_back(hwf[i]);
  }
  row.insert(row.end(), {0.5, 20.0});
  return row;
}

void WritePoses(const std::string& dir, const std::vector<std::vector<double>>& rows) {
  std::vector<double> values;
  for (const auto& row : rows) values.insert(values.end(), row.begin(), row.end());
  std::vector<uint8_t> bytes;
  ASSERT_TRUE(EncodeNpy({rows.size(), 17}, values, &bytes).ok());
  ASSERT_TRUE(WriteFileBytes(dir + "/poses_bounds.npy", bytes).ok());
}

void WriteN3dv(const TempDir& dir, const std::vector<Camera>& rig, int frames, N3dvFrames mode) {
  std::vector<std::vector<double>> rows;
  for (const Camera& camera : rig) rows.push_back(PosesRow(camera));
  WritePoses(dir.path(), rows);
  for (size_t c = 0; c < rig.size(); ++c) {
    char name[32];
    std::snprintf(name, sizeof(name), "cam%02d", static_cast<int>(c));
    if (mode == N3dvFrames::kVideos) {
      std::unique_ptr<VideoWriter> writer;
      ASSERT_TRUE(VideoWriter::Open(dir.path() + "/" + name + ".mp4", kWidth, kHeight,
                                    VideoWriterOptions(), &writer)
                      .ok());
      for (int f = 0; f < frames; ++f) {
        ASSERT_TRUE(writer->Write(ViewImage(kWidth, kHeight, f, static_cast<int>(c))).ok());
      }
      ASSERT_TRUE(writer->Finish().ok());
      continue;
    }
    const std::string images = mode == N3dvFrames::kCameraImages
                                   ? dir.Subdir(std::string(name) + "/images")
                                   : dir.Subdir(std::string("frames/") + name);
    for (int f = 0; f < frames; ++f) {
      char file[32];
      std::snprintf(file, sizeof(file), "/%04d.png", f);
      ASSERT_TRUE(WritePng(images + file, ViewImage(kWidth, kHeight, f, static_cast<int>(c))).ok());
    }
  }
}

TEST(N3dvLoaderTest, DecodesVideos) {
  TempDir dir;
  const std::vector<Camera> rig = Rig(2, kWidth, kHeight, true);
  WriteN3dv(dir, rig, 5, N3dvFrames::kVideos);
  Capture capture;
  const Status status = Load(dir.path(), &capture);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(capture.layout, "n3dv");
  EXPECT_EQ(capture.frame_count, 5);
  EXPECT_EQ(capture.camera_names, (std::vector<std::string>{"cam00", "cam01"}));
  EXPECT_EQ(capture.test_cameras, (std::vector<int>{0}));
  EXPECT_EQ(capture.fps_num, 30u);
  EXPECT_EQ(capture.TrainCameras(), (std::vector<int>{1}));
  for (int f = 0; f < 5; ++f) {
    for (int c = 0; c < 2; ++c) ExpectSameCamera(capture.camera(f, c), rig[c], 1e-5);
  }
  // Out of order, as training asks: every view decodes to its own frame.
  for (int f : {3, 0, 4, 1}) {
    for (int c : {1, 0}) ExpectView(capture, f, c, ViewImage(kWidth, kHeight, f, c), 30);
  }
  Image image;
  EXPECT_EQ(capture.LoadImage(5, 0, &image).code(), M4D_ERR_INVALID_ARG);

  CaptureOptions window;
  window.first_frame = 2;
  window.max_frames = 2;
  ASSERT_TRUE(Load(dir.path(), &capture, window).ok());
  EXPECT_EQ(capture.frame_count, 2);
  ExpectView(capture, 1, 1, ViewImage(kWidth, kHeight, 3, 1), 30);
}

TEST(N3dvLoaderTest, ReadsExtractedFrames) {
  for (N3dvFrames mode : {N3dvFrames::kCameraImages, N3dvFrames::kFramesDir}) {
    TempDir dir;
    const std::vector<Camera> rig = Rig(3, kWidth, kHeight, true);
    WriteN3dv(dir, rig, 4, mode);
    // COLMAP run on frame 0 in the same world frame gives the initial points.
    WriteColmap(dir.path(), rig,
                {Spec(rig[0], "PINHOLE"), Spec(rig[1], "PINHOLE"), Spec(rig[2], "PINHOLE")},
                SomePoints(), mode == N3dvFrames::kFramesDir);
    CaptureOptions options;
    options.first_frame = 1;
    Capture capture;
    const Status status = Load(dir.path(), &capture, options);
    ASSERT_TRUE(status.ok()) << status.message();
    EXPECT_EQ(capture.frame_count, 3);
    EXPECT_EQ(capture.camera_names, (std::vector<std::string>{"cam00", "cam01", "cam02"}));
    for (int c = 0; c < 3; ++c) ExpectSameCamera(capture.camera(2, c), rig[c], 1e-5);
    ExpectView(capture, 0, 2, ViewImage(kWidth, kHeight, 1, 2), 0);
    ExpectView(capture, 2, 0, ViewImage(kWidth, kHeight, 3, 0), 0);
    ExpectSamePoints(capture.initial_points, SomePoints(), 0.5 / 255 + 1e-6);
  }
}

TEST(N3dvLoaderTest, ProjectsAKnownPointWhereExpected) {
  TempDir dir;
  // A camera at (1, 2, 4) looking down -z with +y up: LLFF down = (0, -1, 0),
  // right = (1, 0, 0), back = (0, 0, 1); recorded at 128 x 96 with f = 100.
  const std::vector<double> row = {0, 1, 0, 1, 96, -1, 0, 0, 2, 128, 0, 0, 1, 4, 100, 0.1, 10};
  WritePoses(dir.path(), {row});
  const std::string images = dir.Subdir("cam00/images");
  ASSERT_TRUE(WritePng(images + "/0000.png", ViewImage(kWidth, kHeight, 0, 0)).ok());
  CaptureOptions options;
  options.test_camera = -1;
  Capture capture;
  ASSERT_TRUE(Load(dir.path(), &capture, options).ok());
  const Camera& camera = capture.camera(0, 0);
  EXPECT_FLOAT_EQ(camera.fx, 50.0f);  // 100 * 64 / 128
  EXPECT_FLOAT_EQ(camera.cx, 32.0f);
  // (1.5, 1, 0) is 0.5 right, 1 below and 4 in front of the camera.
  const double point[3] = {1.5, 1.0, 0.0};
  double u, v;
  Project(camera, point, &u, &v);
  EXPECT_NEAR(u, 50.0 * 0.5 / 4 + 32, 1e-4);
  EXPECT_NEAR(v, 50.0 * 1.0 / 4 + 24, 1e-4);
}

TEST(N3dvLoaderTest, RejectsMismatchedLayouts) {
  TempDir dir;
  const std::vector<Camera> rig = Rig(2, kWidth, kHeight, true);
  WriteN3dv(dir, rig, 2, N3dvFrames::kCameraImages);
  // Three poses for two cameras.
  WritePoses(dir.path(), {PosesRow(rig[0]), PosesRow(rig[1]), PosesRow(rig[1])});
  Capture capture;
  EXPECT_EQ(Load(dir.path(), &capture).code(), M4D_ERR_INVALID_ARG);
  // Cameras with different frame counts: the shortest wins, with a note.
  WritePoses(dir.path(), {PosesRow(rig[0]), PosesRow(rig[1])});
  std::filesystem::remove(dir.path() + "/cam01/images/0001.png");
  ASSERT_TRUE(Load(dir.path(), &capture).ok());
  EXPECT_EQ(capture.frame_count, 1);
  ASSERT_EQ(capture.notes.size(), 1u);
  // Each camera's size is its first image's.
  ASSERT_TRUE(WritePng(dir.path() + "/cam01/images/0000.png", Image(8, 6, 3)).ok());
  ASSERT_TRUE(Load(dir.path(), &capture).ok());
  EXPECT_EQ(capture.camera(0, 1).width, 8);
  EXPECT_FLOAT_EQ(capture.camera(0, 1).fx, rig[1].fx * 8 / kWidth);
  WriteText(dir.path() + "/poses_bounds.npy", "not numpy");
  EXPECT_EQ(Load(dir.path(), &capture).code(), M4D_ERR_UNSUPPORTED);
}

// ---- nerfstudio transforms.json ---------------------------------------------------------

// Camera-to-world with OpenGL axes (x right, y up, z back) as nerfstudio stores it.
Json TransformMatrix(const Camera& camera) {
  const float* r = camera.rotation;
  float centre[3];
  CameraCentre(camera, centre);
  Json matrix = Json::array();
  const double sign[3] = {1, -1, -1};
  for (int i = 0; i < 3; ++i) {
    matrix.push_back({sign[0] * r[0 + i], sign[1] * r[3 + i], sign[2] * r[6 + i], centre[i]});
  }
  matrix.push_back({0, 0, 0, 1});
  return matrix;
}

Json FrameEntry(const Camera& camera, const std::string& file) {
  Json entry = {{"file_path", file}, {"transform_matrix", TransformMatrix(camera)},
                {"fl_x", camera.fx}, {"fl_y", camera.fy},
                {"cx", camera.cx},   {"cy", camera.cy}};
  return entry;
}

// A multi-view video: frames[t][c] with "camera" and "time_index" (or only "time" when
// `by_time`), listed in a shuffled order; images and points written beside it.
Json WriteDynamicTransforms(const TempDir& dir, const std::vector<Camera>& rig, int frames,
                            bool by_time) {
  Json root = {
      {"camera_model", "OPENCV"}, {"w", kWidth}, {"h", kHeight}, {"ply_file_path", "points3d.ply"}};
  std::vector<Json> entries;
  for (int t = 0; t < frames; ++t) {
    for (size_t c = 0; c < rig.size(); ++c) {
      char file[64];
      std::snprintf(file, sizeof(file), "images/cam%02d/%06d.png", static_cast<int>(c), t);
      dir.Subdir("images/cam" + std::string(file + 10, 2));
      EXPECT_TRUE(
          WritePng(dir.path() + "/" + file, ViewImage(kWidth, kHeight, t, static_cast<int>(c)))
              .ok());
      Json entry = FrameEntry(rig[c], std::string("./") + file);
      entry["time"] = frames > 1 ? static_cast<double>(t) / (frames - 1) : 0.0;
      if (!by_time) {
        entry["camera"] = "cam" + std::string(file + 10, 2);
        entry["time_index"] = t;
      }
      entries.push_back(entry);
    }
  }
  std::reverse(entries.begin(), entries.end());
  std::rotate(entries.begin(), entries.begin() + 2, entries.end());
  root["frames"] = entries;
  EXPECT_TRUE(WritePointCloudPly(dir.path() + "/points3d.ply", SomePoints()).ok());
  WriteText(dir.path() + "/transforms.json", root.dump(1));
  return root;
}

TEST(NerfstudioLoaderTest, LoadsMultiViewVideo) {
  for (bool by_time : {false, true}) {
    TempDir dir;
    const std::vector<Camera> rig = Rig(3, kWidth, kHeight, false);
    WriteDynamicTransforms(dir, rig, 3, by_time);
    Capture capture;
    const Status status = Load(dir.path(), &capture);
    ASSERT_TRUE(status.ok()) << status.message();
    EXPECT_EQ(capture.layout, "nerfstudio");
    EXPECT_EQ(capture.frame_count, 3);
    if (by_time) {  // grouped by transform, named after their first view
      EXPECT_EQ(capture.camera_names[1], "images/cam01/000000.png");
    } else {
      EXPECT_EQ(capture.camera_names, (std::vector<std::string>{"cam00", "cam01", "cam02"}));
    }
    for (int f = 0; f < 3; ++f) {
      for (int c = 0; c < 3; ++c) {
        ExpectSameCamera(capture.camera(f, c), rig[c], 1e-5);
        ExpectView(capture, f, c, ViewImage(kWidth, kHeight, f, c), 0);
      }
    }
    ExpectSamePoints(capture.initial_points, SomePoints(), 0.5 / 255 + 1e-6);
    EXPECT_TRUE(capture.notes.empty());
  }
}

TEST(NerfstudioLoaderTest, LoadsStaticCapturesWithIntrinsicsOverride) {
  TempDir dir;
  std::vector<Camera> rig = Rig(3, kWidth, kHeight, false);
  // The second view overrides the shared intrinsics, image size included.
  rig[1].width = 40;
  rig[1].height = 30;
  rig[1].fx = 33;
  rig[1].fy = 34;
  rig[1].cx = 21;
  rig[1].cy = 14;
  Json root = {{"w", kWidth},     {"h", kHeight},    {"fl_x", rig[0].fx}, {"fl_y", rig[0].fy},
               {"cx", rig[0].cx}, {"cy", rig[0].cy}, {"k1", 0.0}};
  dir.Subdir("images");
  for (int c = 0; c < 3; ++c) {
    const std::string file = "images/view_" + std::to_string(c) + ".png";
    ASSERT_TRUE(
        WritePng(dir.path() + "/" + file, ViewImage(rig[c].width, rig[c].height, 0, c)).ok());
    Json entry = {{"file_path", file}, {"transform_matrix", TransformMatrix(rig[c])}};
    if (c == 1) {
      entry.update(FrameEntry(rig[1], file));
      entry["w"] = 40;
      entry["h"] = 30;
    }
    if (c == 2) {  // a camera sharing camera 0's intrinsics would differ here
      rig[2].fx = rig[0].fx;
      rig[2].fy = rig[0].fy;
      rig[2].cx = rig[0].cx;
      rig[2].cy = rig[0].cy;
    }
    root["frames"].push_back(entry);
  }
  WriteText(dir.path() + "/transforms.json", root.dump());
  Capture capture;
  CaptureOptions options;
  options.test_camera = -1;
  const Status status = Load(dir.path() + "/transforms.json", &capture, options);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(capture.frame_count, 1);
  EXPECT_EQ(capture.camera_names[2], "images/view_2.png");
  for (int c = 0; c < 3; ++c) ExpectSameCamera(capture.camera(0, c), rig[c], 1e-5);
  ExpectView(capture, 0, 1, ViewImage(40, 30, 0, 1), 0);
  EXPECT_TRUE(capture.notes.empty());  // k1 = 0: pinhole cameras, nothing undistorted
  EXPECT_TRUE(capture.initial_points.positions.empty());
}

TEST(NerfstudioLoaderTest, RejectsIncompleteAndMalformedFiles) {
  TempDir dir;
  const std::vector<Camera> rig = Rig(2, kWidth, kHeight, false);
  const Json root = WriteDynamicTransforms(dir, rig, 2, false);
  const std::string path = dir.path() + "/transforms.json";
  Capture capture;
  auto load_with = [&](const Json& json) {
    WriteText(path, json.dump());
    return Load(dir.path(), &capture);
  };
  Json missing = root;
  missing["frames"].erase(missing["frames"].begin() + 1);
  Status status = load_with(missing);
  EXPECT_EQ(status.code(), M4D_ERR_INVALID_ARG);
  EXPECT_NE(status.message().find("no view"), std::string::npos) << status.message();
  Json doubled = root;
  doubled["frames"][0]["camera"] = doubled["frames"][1]["camera"];
  doubled["frames"][0]["time_index"] = doubled["frames"][1]["time_index"];
  status = load_with(doubled);
  EXPECT_EQ(status.code(), M4D_ERR_INVALID_ARG);
  EXPECT_NE(status.message().find("two views"), std::string::npos) << status.message();
  Json mixed = root;
  mixed["frames"][0].erase("camera");
  EXPECT_EQ(load_with(mixed).code(), M4D_ERR_INVALID_ARG);
  Json no_pose = root;
  no_pose["frames"][2].erase("transform_matrix");
  EXPECT_EQ(load_with(no_pose).code(), M4D_ERR_INVALID_ARG);
  Json bad_matrix = root;
  bad_matrix["frames"][2]["transform_matrix"][1] = "x";
  EXPECT_EQ(load_with(bad_matrix).code(), M4D_ERR_INVALID_ARG);
  Json not_rigid = root;
  not_rigid["frames"][2]["transform_matrix"][0][0] = 3.0;
  EXPECT_EQ(load_with(not_rigid).code(), M4D_ERR_INVALID_ARG);
  Json equirectangular = root;
  equirectangular["camera_model"] = "EQUIRECTANGULAR";
  EXPECT_EQ(load_with(equirectangular).code(), M4D_ERR_UNSUPPORTED);
  Json no_width = root;
  no_width.erase("w");
  EXPECT_EQ(load_with(no_width).code(), M4D_ERR_INVALID_ARG);
  Json wrong_type = root;
  wrong_type["frames"] = "all of them";
  EXPECT_EQ(load_with(wrong_type).code(), M4D_ERR_INVALID_ARG);
  WriteText(path, "{\"frames\": [");
  EXPECT_EQ(Load(dir.path(), &capture).code(), M4D_ERR_INVALID_ARG);
  // A view whose image is missing loads, then fails on that view only.
  ASSERT_TRUE(load_with(root).ok());
  std::filesystem::remove(dir.path() + "/images/cam01/000001.png");
  Image image;
  EXPECT_EQ(capture.LoadImage(1, 1, &image).code(), M4D_ERR_INVALID_ARG);
  EXPECT_TRUE(capture.LoadImage(1, 0, &image).ok());
}

// ---- COLMAP tests ----------------------------------------------------------------------

TEST(ColmapLoaderTest, BinaryAndTextGiveTheSameCapture) {
  TempDir dir;
  std::vector<Camera> rig = Rig(4, kWidth, kHeight, false);
  const std::vector<ColmapCameraSpec> specs = MixedSpecs(&rig);
  const PointCloud points = SomePoints();
  WriteColmap(dir.Subdir("bin"), rig, specs, points, true);
  WriteColmap(dir.Subdir("txt"), rig, specs, points, false);
  Capture binary, text;
  Status status = Load(dir.path() + "/bin", &binary);
  ASSERT_TRUE(status.ok()) << status.message();
  status = Load(dir.path() + "/txt", &text);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(binary.layout, "colmap");
  EXPECT_EQ(binary.frame_count, 1);
  const std::vector<std::string> names = {"view_0.png", "view_1.png", "view_2.png", "view_3.png"};
  EXPECT_EQ(binary.camera_names, names);
  EXPECT_EQ(text.camera_names, names);
  for (int c = 0; c < 4; ++c) {
    ExpectSameCamera(binary.camera(0, c), text.camera(0, c), 0);
    ExpectSameCamera(binary.camera(0, c), rig[c], 1e-5);
    ExpectView(binary, 0, c, ViewImage(kWidth, kHeight, 0, c), 0);
  }
  EXPECT_EQ(binary.initial_points.positions, text.initial_points.positions);
  EXPECT_EQ(binary.initial_points.colors, text.initial_points.colors);
  ExpectSamePoints(binary.initial_points, points, 0.5 / 255 + 1e-6);
  // OPENCV and SIMPLE_RADIAL with zero coefficients are pinhole cameras: the images above
  // are the files' exactly (no resampling), and there is nothing to note.
  EXPECT_TRUE(binary.notes.empty());
  EXPECT_TRUE(text.notes.empty());
}

TEST(ColmapLoaderTest, RejectsUnsupportedModelsAndBrokenFiles) {
  TempDir dir;
  std::vector<Camera> rig = Rig(2, kWidth, kHeight, false);
  rig[1].fy = rig[1].fx;
  WriteColmap(dir.path(), rig, {Spec(rig[0], "PINHOLE"), Spec(rig[1], "FOV", {0.1})}, SomePoints(),
              true);
  Capture capture;
  Status status = Load(dir.path(), &capture);
  EXPECT_EQ(status.code(), M4D_ERR_UNSUPPORTED);
  EXPECT_NE(status.message().find("FOV"), std::string::npos) << status.message();
  WriteColmap(
      dir.path(), rig,
      {Spec(rig[0], "PINHOLE"), Spec(rig[1], "THIN_PRISM_FISHEYE", std::vector<double>(8, 0.0))},
      SomePoints(), true);
  status = Load(dir.path(), &capture);
  EXPECT_EQ(status.code(), M4D_ERR_UNSUPPORTED);
  EXPECT_NE(status.message().find("THIN_PRISM_FISHEYE"), std::string::npos) << status.message();
  WriteColmap(dir.path(), rig, {Spec(rig[0], "PINHOLE"), Spec(rig[1], "RADIAL", {0, 0})},
              SomePoints(), true);
  ASSERT_TRUE(Load(dir.path(), &capture).ok());
  const std::string model = dir.path() + "/sparse/0/";
  for (const char* file : {"cameras.bin", "images.bin", "points3D.bin"}) {
    std::vector<uint8_t> bytes, cut;
    ASSERT_TRUE(ReadFileBytes(model + file, 1 << 20, &bytes).ok());
    for (size_t size : {size_t{0}, size_t{7}, bytes.size() / 2, bytes.size() - 1}) {
      cut.assign(bytes.begin(), bytes.begin() + size);
      ASSERT_TRUE(WriteFileBytes(model + file, cut).ok());
      EXPECT_EQ(Load(dir.path(), &capture).code(), M4D_ERR_BITSTREAM) << file << " " << size;
    }
    bytes.push_back(0);  // trailing bytes are malformed as well
    ASSERT_TRUE(WriteFileBytes(model + file, bytes).ok());
    EXPECT_EQ(Load(dir.path(), &capture).code(), M4D_ERR_BITSTREAM) << file;
    bytes.pop_back();
    ASSERT_TRUE(WriteFileBytes(model + file, bytes).ok());
  }
  // A huge count is refused from the file size, before allocating.
  std::vector<uint8_t> huge;
  Put<uint64_t>(uint64_t{1} << 60, &huge);
  ASSERT_TRUE(WriteFileBytes(model + "points3D.bin", huge).ok());
  EXPECT_EQ(Load(dir.path(), &capture).code(), M4D_ERR_BITSTREAM);
  std::filesystem::remove(model + "points3D.bin");
  EXPECT_EQ(Load(dir.path(), &capture).code(), M4D_ERR_INVALID_ARG);  // no points3D at all
  // Text: an unknown model, a short line.
  TempDir text;
  WriteColmap(text.path(), rig, {Spec(rig[0], "PINHOLE"), Spec(rig[1], "PINHOLE")}, SomePoints(),
              false);
  const std::string cameras = text.path() + "/sparse/0/cameras.txt";
  WriteText(cameras, "1 PINHOLE 64 48 50 50 32\n");
  EXPECT_EQ(Load(text.path(), &capture).code(), M4D_ERR_BITSTREAM);
  WriteText(cameras, "1 WEIRD 64 48 50 50 32 24\n");
  EXPECT_EQ(Load(text.path(), &capture).code(), M4D_ERR_BITSTREAM);
  // Images whose camera is missing.
  WriteText(cameras, "# nothing\n");
  EXPECT_EQ(Load(text.path(), &capture).code(), M4D_ERR_INVALID_ARG);
}

// ---- Lens distortion ------------------------------------------------------------------

// A smooth colour per ray, given by its normalised pinhole coordinates (x, y) = (X/Z, Y/Z).
void Pattern(double x, double y, float rgb[3]) {
  rgb[0] = static_cast<float>(0.5 + 0.4 * std::sin(9 * x) * std::cos(7 * y));
  rgb[1] = static_cast<float>(0.5 + 0.4 * std::cos(11 * x + 3 * y));
  rgb[2] = static_cast<float>(0.5 + 0.3 * std::sin(5 * x * y + 8 * y));
}

// The pattern as a pinhole camera sees it.
Image PinholePattern(const Camera& c) {
  Image image(c.width, c.height, 3);
  for (int j = 0; j < c.height; ++j) {
    for (int i = 0; i < c.width; ++i)
      Pattern((i + 0.5 - c.cx) / c.fx, (j + 0.5 - c.cy) / c.fy, &image.at(i, j, 0));
  }
  return image;
}

// The pattern through a lens, quantised to 8 bits: each pixel shows the ray whose distorted
// position it is, found by fixed-point iteration on the forward model (not the loaders'
// inverse).
Image DistortedPattern(const Camera& c, const LensDistortion& lens) {
  Image image(c.width, c.height, 3);
  for (int j = 0; j < c.height; ++j) {
    for (int i = 0; i < c.width; ++i) {
      const double xd = (i + 0.5 - c.cx) / c.fx, yd = (j + 0.5 - c.cy) / c.fy;
      double x = xd, y = yd, u = 0, v = 0;
      for (int step = 0; step < 300; ++step) {
        Distort(lens, x, y, &u, &v);
        x += xd - u;
        y += yd - v;
      }
      EXPECT_LT(std::hypot(u - xd, v - yd), 1e-9) << i << " " << j;
      float rgb[3];
      Pattern(x, y, rgb);
      for (int a = 0; a < 3; ++a) image.at(i, j, a) = ByteToFloat(FloatToByte(rgb[a]));
    }
  }
  return image;
}

// PSNR of a loaded view against `expected` over the pixels at least 3 away from the border.
double InnerPsnr(const Image& image, const Image& expected) {
  Image mask(image.width, image.height, 1, 0.0f);
  for (int j = 3; j < image.height - 3; ++j) {
    for (int i = 3; i < image.width - 3; ++i) mask.at(i, j, 0) = 1;
  }
  double psnr = 0;
  EXPECT_TRUE(PsnrMasked(image, expected, mask, &psnr).ok());
  return psnr;
}

constexpr int kLensWidth = 160, kLensHeight = 120;

struct LensCase {
  const char* colmap_model;
  LensDistortion lens;
  std::vector<double> params;  // the COLMAP distortion parameters, in COLMAP's order
};

LensDistortion MakeLens(LensModel model, std::vector<double> k, double p1 = 0, double p2 = 0) {
  LensDistortion lens;
  lens.model = model;
  std::copy(k.begin(), k.end(), lens.k);
  lens.p1 = p1;
  lens.p2 = p2;
  return lens;
}

// One camera per COLMAP model with distortion, then a pinhole one.
std::vector<LensCase> LensCases() {
  return {{"OPENCV",
           MakeLens(LensModel::kOpenCv, {-0.25, 0.06}, 0.001, -0.0015),
           {-0.25, 0.06, 0.001, -0.0015}},
          {"OPENCV_FISHEYE",
           MakeLens(LensModel::kFisheye, {0.06, -0.02, 0.01, -0.004}),
           {0.06, -0.02, 0.01, -0.004}},
          {"FULL_OPENCV",
           MakeLens(LensModel::kFullOpenCv, {-0.2, 0.05, 0, 0.1}, 0.002, 0.001),
           {-0.2, 0.05, 0.002, 0.001, 0, 0.1, 0, 0}},
          {"RADIAL", MakeLens(LensModel::kRadial, {-0.2, 0.03}), {-0.2, 0.03}},
          {"SIMPLE_RADIAL", MakeLens(LensModel::kRadial, {0.22}), {0.22}},
          {"PINHOLE", LensDistortion(), {}}};
}

// A rig of LensCases().size() cameras with lens-like intrinsics (fy = fx for the models with
// one focal length).
std::vector<Camera> LensRig(const std::vector<LensCase>& cases) {
  std::vector<Camera> rig = Rig(static_cast<int>(cases.size()), kLensWidth, kLensHeight, false);
  for (size_t c = 0; c < rig.size(); ++c) {
    rig[c].fx = 100.0f + 4 * c;
    rig[c].fy = cases[c].colmap_model[0] == 'O' || cases[c].colmap_model[0] == 'F' ? rig[c].fx + 2
                                                                                   : rig[c].fx;
    rig[c].cx = 80.5f - c;
    rig[c].cy = 59.25f + 0.5f * c;
  }
  return rig;
}

// The views of `capture` (from LensRig(cases) written with distorted patterns) are the
// pattern as their pinhole cameras see it, the poses are the rig's, the distorted views have
// new intrinsics, and the pinhole view is the file as written.
void ExpectUndistortedViews(const Capture& capture, const std::vector<Camera>& rig,
                            const std::vector<LensCase>& cases, const std::vector<Image>& written,
                            int downscale, double min_psnr) {
  ASSERT_EQ(capture.camera_count(), static_cast<int>(rig.size()));
  for (int c = 0; c < capture.camera_count(); ++c) {
    const Camera& camera = capture.camera(0, c);
    EXPECT_EQ(camera.width, kLensWidth / downscale);
    EXPECT_EQ(camera.height, kLensHeight / downscale);
    for (int i = 0; i < 9; ++i) EXPECT_NEAR(camera.rotation[i], rig[c].rotation[i], 1e-5);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(camera.translation[i], rig[c].translation[i], 1e-5);
    Image image;
    ASSERT_TRUE(capture.LoadImage(0, c, &image).ok());
    ASSERT_EQ(image.width, camera.width);
    ASSERT_EQ(image.height, camera.height);
    if (!HasDistortion(cases[c].lens)) {
      EXPECT_EQ(camera.fx * downscale, rig[c].fx);
      if (downscale == 1) {
        EXPECT_EQ(image.pixels, written[c].pixels);
      }
      continue;
    }
    EXPECT_GT(std::fabs(camera.fx * downscale - rig[c].fx), 0.5) << cases[c].colmap_model;
    const double psnr = InnerPsnr(image, PinholePattern(camera));
    EXPECT_GT(psnr, min_psnr) << cases[c].colmap_model;
    // The files themselves, read as pinhole images, are far from it: the test can fail.
    if (downscale == 1) {
      EXPECT_LT(InnerPsnr(written[c], PinholePattern(rig[c])), 30) << cases[c].colmap_model;
    }
  }
}

TEST(LensUndistortionTest, ColmapCamerasAreUndistortedToPinholes) {
  TempDir dir;
  const std::vector<LensCase> cases = LensCases();
  const std::vector<Camera> rig = LensRig(cases);
  std::vector<ColmapCameraSpec> specs;
  for (size_t c = 0; c < rig.size(); ++c)
    specs.push_back(Spec(rig[c], cases[c].colmap_model, cases[c].params));
  WriteColmap(dir.path(), rig, specs, SomePoints(), false);
  std::vector<Image> written;
  for (size_t c = 0; c < rig.size(); ++c) {
    written.push_back(DistortedPattern(rig[c], cases[c].lens));
    ASSERT_TRUE(
        WritePng(dir.path() + "/images/view_" + std::to_string(c) + ".png", written.back()).ok());
  }
  Capture capture;
  Status status = Load(dir.path(), &capture);
  ASSERT_TRUE(status.ok()) << status.message();
  ExpectUndistortedViews(capture, rig, cases, written, 1, 45);
  ASSERT_EQ(capture.notes.size(), 1u);
  const std::string& note = capture.notes[0];
  EXPECT_EQ(note.find("colmap: 5 of 6 cameras undistorted (FULL_OPENCV, OPENCV, OPENCV_FISHEYE, "
                      "RADIAL) to pinhole"),
            0u)
      << note;
  // Downscaling comes after undistortion: the halved pinhole cameras, area-averaged images.
  Capture half;
  CaptureOptions options;
  options.downscale = 2;
  status = Load(dir.path(), &half, options);
  ASSERT_TRUE(status.ok()) << status.message();
  for (int c = 0; c < capture.camera_count(); ++c) {
    EXPECT_NEAR(half.camera(0, c).fx, capture.camera(0, c).fx / 2, 1e-4);
    EXPECT_NEAR(half.camera(0, c).cx, capture.camera(0, c).cx / 2, 1e-4);
  }
  ExpectUndistortedViews(half, rig, cases, written, 2, 40);
}

TEST(LensUndistortionTest, NerfstudioViewsAreUndistortedToPinholes) {
  TempDir dir;
  // Shared OPENCV k1, k2, k3, p1, p2; view 1 overrides with OPENCV_FISHEYE k1..k4, view 2 is
  // a pinhole.
  const std::vector<LensCase> all = LensCases();
  const std::vector<LensCase> cases = {
      {"OPENCV", MakeLens(LensModel::kOpenCv, {-0.25, 0.06, 0.01}, 0.001, -0.0015), {}},
      all[1],
      all.back()};
  std::vector<Camera> rig = LensRig(cases);
  Json root = {{"camera_model", "OPENCV"},
               {"w", kLensWidth},
               {"h", kLensHeight},
               {"k1", -0.25},
               {"k2", 0.06},
               {"k3", 0.01},
               {"p1", 0.001},
               {"p2", -0.0015}};
  std::vector<Image> written;
  for (int c = 0; c < 3; ++c) {
    const std::string file = "v" + std::to_string(c) + ".png";
    written.push_back(DistortedPattern(rig[c], cases[c].lens));
    ASSERT_TRUE(WritePng(dir.path() + "/" + file, written.back()).ok());
    Json entry = FrameEntry(rig[c], file);
    if (c == 1) {
      entry.update({{"camera_model", "OPENCV_FISHEYE"},
                    {"k1", 0.06},
                    {"k2", -0.02},
                    {"k3", 0.01},
                    {"k4", -0.004},
                    {"p1", 0},
                    {"p2", 0}});
    }
    if (c == 2) {
      entry.update(
          {{"camera_model", "PINHOLE"}, {"k1", 0}, {"k2", 0}, {"k3", 0}, {"p1", 0}, {"p2", 0}});
    }
    root["frames"].push_back(entry);
  }
  WriteText(dir.path() + "/transforms.json", root.dump());
  Capture capture;
  const Status status = Load(dir.path(), &capture);
  ASSERT_TRUE(status.ok()) << status.message();
  ExpectUndistortedViews(capture, rig, cases, written, 1, 45);
  ASSERT_EQ(capture.notes.size(), 1u);
  EXPECT_EQ(capture.notes[0].find(
                "nerfstudio: 2 of 3 cameras undistorted (OPENCV, OPENCV_FISHEYE) to pinhole"),
            0u)
      << capture.notes[0];
}

TEST(LensUndistortionTest, LoadersRefuseDistortionTheyCannotUndistort) {
  TempDir dir;
  std::vector<Camera> rig = LensRig({LensCases()[0], LensCases()[0]});
  Capture capture;
  // Too strong: k1 = -0.9 folds over inside the image.
  WriteColmap(dir.path(), rig, {Spec(rig[0], "PINHOLE"), Spec(rig[1], "OPENCV", {-0.9, 0, 0, 0})},
              SomePoints(), false);
  Status status = Load(dir.path(), &capture);
  EXPECT_EQ(status.code(), M4D_ERR_UNSUPPORTED);
  EXPECT_NE(status.message().find("'view_1.png'"), std::string::npos) << status.message();
  // Not a number: the model parsers refuse it before undistortion.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  WriteColmap(dir.path(), rig, {Spec(rig[0], "PINHOLE"), Spec(rig[1], "OPENCV", {0.1, nan, 0, 0})},
              SomePoints(), true);
  EXPECT_EQ(Load(dir.path(), &capture).code(), M4D_ERR_BITSTREAM);
  // transforms.json: too strong, coefficients of another model, an unknown model.
  TempDir nerfstudio;
  ASSERT_TRUE(
      WritePng(nerfstudio.path() + "/v.png", ViewImage(kLensWidth, kLensHeight, 0, 0)).ok());
  const Json base = {
      {"w", kLensWidth}, {"h", kLensHeight}, {"frames", {FrameEntry(rig[0], "v.png")}}};
  auto load_with = [&](const Json& extra) {
    Json root = base;
    root.update(extra);
    WriteText(nerfstudio.path() + "/transforms.json", root.dump());
    return Load(nerfstudio.path(), &capture);
  };
  ASSERT_TRUE(load_with({{"k1", 0.05}}).ok());
  status = load_with({{"k1", -0.9}});
  EXPECT_EQ(status.code(), M4D_ERR_UNSUPPORTED);
  EXPECT_NE(status.message().find("'v.png'"), std::string::npos) << status.message();
  EXPECT_EQ(load_with({{"k4", 0.01}}).code(), M4D_ERR_UNSUPPORTED);
  EXPECT_EQ(load_with({{"camera_model", "OPENCV_FISHEYE"}, {"p1", 0.01}}).code(),
            M4D_ERR_UNSUPPORTED);
  EXPECT_EQ(load_with({{"camera_model", "FISHEYE624"}}).code(), M4D_ERR_UNSUPPORTED);
}

// ---- Dynamic 3D Gaussians -------------------------------------------------------------------

// cam_id values 4, 0, 2 for the rig's cameras 2, 0, 1 (listed in a different order each
// frame), JPEG images, points in init_pt_cld.npz written with `method`.
void WriteDynamic3dgs(const std::string& dir, const std::vector<Camera>& rig, int frames,
                      ZipMethod method) {
  const int ids[3] = {0, 2, 4};
  Json root = {{"w", kWidth}, {"h", kHeight}};
  for (const char* key : {"k", "w2c", "fn", "cam_id"}) root[key] = Json::array();
  for (int t = 0; t < frames; ++t) {
    Json k = Json::array(), w2c = Json::array(), fn = Json::array(), cam_id = Json::array();
    for (int i = 0; i < 3; ++i) {
      const int c = (i + t + 2) % 3;
      const Camera& camera = rig[c];
      k.push_back(
          Json::array({Json::array({camera.fx, 0.0, camera.cx}),
                       Json::array({0.0, camera.fy, camera.cy}), Json::array({0.0, 0.0, 1.0})}));
      const float* r = camera.rotation;
      const float* tr = camera.translation;
      w2c.push_back(Json::array(
          {Json::array({r[0], r[1], r[2], tr[0]}), Json::array({r[3], r[4], r[5], tr[1]}),
           Json::array({r[6], r[7], r[8], tr[2]}), Json::array({0, 0, 0, 1})}));
      const std::string file = std::to_string(ids[c]) + "/" + std::to_string(t) + ".jpg";
      std::filesystem::create_directories(dir + "/ims/" + std::to_string(ids[c]));
      EXPECT_TRUE(WriteJpeg(dir + "/ims/" + file, ViewImage(kWidth, kHeight, t, c), 95).ok());
      fn.push_back(file);
      cam_id.push_back(ids[c]);
    }
    root["k"].push_back(k);
    root["w2c"].push_back(w2c);
    root["fn"].push_back(fn);
    root["cam_id"].push_back(cam_id);
  }
  WriteText(dir + "/train_meta.json", root.dump());
  const PointCloud points = SomePoints();
  std::vector<double> data;
  for (size_t i = 0; i < points.size(); ++i) {
    for (int a = 0; a < 3; ++a) data.push_back(points.positions[3 * i + a]);
    for (int a = 0; a < 3; ++a) data.push_back(points.colors[3 * i + a]);
    data.push_back(1.0);  // segmentation label
  }
  std::vector<uint8_t> npy;
  ASSERT_TRUE(EncodeNpy({points.size(), 7}, data, &npy).ok());
  ASSERT_TRUE(WriteFileBytes(dir + "/init_pt_cld.npz", MakeZip({{"data.npy", npy}}, method)).ok());
}

TEST(Dynamic3dgsLoaderTest, LoadsMetaImagesAndPoints) {
  for (ZipMethod method : {ZipMethod::kStored, ZipMethod::kDeflated}) {
    TempDir dir;
    const std::vector<Camera> rig = Rig(3, kWidth, kHeight, false);
    WriteDynamic3dgs(dir.path(), rig, 2, method);
    Capture capture;
    const Status status = Load(dir.path(), &capture);
    ASSERT_TRUE(status.ok()) << status.message();
    EXPECT_EQ(capture.layout, "dynamic3dgs");
    EXPECT_EQ(capture.frame_count, 2);
    EXPECT_EQ(capture.camera_names, (std::vector<std::string>{"0", "2", "4"}));
    for (int f = 0; f < 2; ++f) {
      for (int c = 0; c < 3; ++c) {
        ExpectSameCamera(capture.camera(f, c), rig[c], 1e-6);
        ExpectView(capture, f, c, ViewImage(kWidth, kHeight, f, c), 30);
      }
    }
    ExpectSamePoints(capture.initial_points, SomePoints(), 1e-7);
  }
}

// test_meta.json with one held-out camera (id 7, the rig's camera 0 seen again) whose images
// are named per frame in `fn`.
void WriteTestMeta(const std::string& dir, const Camera& camera, int frames, int id = 7) {
  Json root = {{"w", kWidth}, {"h", kHeight}};
  for (const char* key : {"k", "w2c", "fn", "cam_id"}) root[key] = Json::array();
  const std::string folder = "held_out_" + std::to_string(id);
  std::filesystem::create_directories(dir + "/ims/" + folder);
  for (int t = 0; t < frames; ++t) {
    const float* r = camera.rotation;
    const float* tr = camera.translation;
    root["k"].push_back(Json::array(
        {Json::array({Json::array({camera.fx, 0.0, camera.cx}),
                      Json::array({0.0, camera.fy, camera.cy}), Json::array({0.0, 0.0, 1.0})})}));
    root["w2c"].push_back(Json::array({Json::array(
        {Json::array({r[0], r[1], r[2], tr[0]}), Json::array({r[3], r[4], r[5], tr[1]}),
         Json::array({r[6], r[7], r[8], tr[2]}), Json::array({0, 0, 0, 1})})}));
    const std::string file = folder + "/view_" + std::to_string(100 + t) + ".jpg";
    EXPECT_TRUE(WriteJpeg(dir + "/ims/" + file, ViewImage(kWidth, kHeight, t, 5), 95).ok());
    root["fn"].push_back(Json::array({file}));
    root["cam_id"].push_back(Json::array({id}));
  }
  WriteText(dir + "/test_meta.json", root.dump());
}

TEST(Dynamic3dgsLoaderTest, TestMetaCamerasAreHeldOut) {
  TempDir dir;
  const std::vector<Camera> rig = Rig(3, kWidth, kHeight, false);
  WriteDynamic3dgs(dir.path(), rig, 2, ZipMethod::kStored);
  WriteTestMeta(dir.path(), rig[0], 2);
  Capture capture;
  Status status = Load(dir.path(), &capture);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(capture.camera_names, (std::vector<std::string>{"0", "2", "4", "7"}));
  EXPECT_EQ(capture.test_cameras, (std::vector<int>{3}));
  EXPECT_EQ(capture.TrainCameras(), (std::vector<int>{0, 1, 2}));
  for (int f = 0; f < 2; ++f) {
    ExpectSameCamera(capture.camera(f, 3), rig[0], 1e-6);
    ExpectView(capture, f, 3, ViewImage(kWidth, kHeight, f, 5), 30);  // its own `fn` per frame
  }
  // An explicit choice replaces them; the layout's held-out camera then trains.
  CaptureOptions options;
  options.test_camera = 1;
  ASSERT_TRUE(Load(dir.path(), &capture, options).ok());
  EXPECT_EQ(capture.TrainCameras(), (std::vector<int>{0, 2, 3}));
  options.test_camera = -1;
  ASSERT_TRUE(Load(dir.path(), &capture, options).ok());
  EXPECT_TRUE(capture.test_cameras.empty());
  // A frame count or a camera id that contradicts train_meta.json.
  WriteTestMeta(dir.path(), rig[0], 1);
  status = Load(dir.path(), &capture);
  EXPECT_EQ(status.code(), M4D_ERR_INVALID_ARG);
  EXPECT_NE(status.message().find("test_meta.json"), std::string::npos) << status.message();
  WriteTestMeta(dir.path(), rig[0], 2, 2);
  EXPECT_EQ(Load(dir.path(), &capture).code(), M4D_ERR_INVALID_ARG);
}

// A left-handed calibration: the rig and points seen in the world mirrored by x -> -x, which
// makes every world-to-camera rotation's determinant -1. Loading mirrors it back.
TEST(Dynamic3dgsLoaderTest, LeftHandedCalibrationIsMirrored) {
  TempDir dir;
  const std::vector<Camera> rig = Rig(3, kWidth, kHeight, false);
  std::vector<Camera> mirrored = rig;
  for (Camera& camera : mirrored) {
    for (int r = 0; r < 3; ++r) camera.rotation[3 * r] *= -1.0f;
  }
  WriteDynamic3dgs(dir.path(), mirrored, 2, ZipMethod::kStored);
  Capture capture;
  Status status = Load(dir.path(), &capture);
  ASSERT_TRUE(status.ok()) << status.message();
  for (int f = 0; f < 2; ++f) {
    for (int c = 0; c < 3; ++c) ExpectSameCamera(capture.camera(f, c), rig[c], 1e-6);
  }
  PointCloud expected = SomePoints();
  for (size_t i = 0; i < expected.size(); ++i) expected.positions[3 * i] *= -1.0f;
  ExpectSamePoints(capture.initial_points, expected, 1e-7);
  ASSERT_FALSE(capture.notes.empty());
  EXPECT_NE(capture.notes.back().find("left-handed"), std::string::npos);
  // One camera right-handed among left-handed ones: no single world, named in the error.
  mirrored[1] = rig[1];
  WriteDynamic3dgs(dir.path(), mirrored, 2, ZipMethod::kStored);
  status = Load(dir.path(), &capture);
  EXPECT_EQ(status.code(), M4D_ERR_INVALID_ARG);
  EXPECT_NE(status.message().find("left-handed"), std::string::npos) << status.message();
}

TEST(Dynamic3dgsLoaderTest, RejectsInconsistentMeta) {
  TempDir dir;
  const std::vector<Camera> rig = Rig(3, kWidth, kHeight, false);
  WriteDynamic3dgs(dir.path(), rig, 2, ZipMethod::kDeflated);
  std::vector<uint8_t> bytes;
  ASSERT_TRUE(ReadFileBytes(dir.path() + "/train_meta.json", 1 << 24, &bytes).ok());
  const Json root = Json::parse(bytes.begin(), bytes.end());
  Capture capture;
  auto load_with = [&](const Json& json) {
    WriteText(dir.path() + "/train_meta.json", json.dump());
    return Load(dir.path(), &capture).code();
  };
  Json other_cameras = root;
  other_cameras["cam_id"][1][0] = 9;
  EXPECT_EQ(load_with(other_cameras), M4D_ERR_INVALID_ARG);
  Json short_k = root;
  short_k["k"][1].erase(0);
  EXPECT_EQ(load_with(short_k), M4D_ERR_INVALID_ARG);
  Json bad_w2c = root;
  bad_w2c["w2c"][0][0][1] = Json::array({1, 2});
  EXPECT_EQ(load_with(bad_w2c), M4D_ERR_INVALID_ARG);
  Json text_size = root;
  text_size["w"] = "wide";
  EXPECT_EQ(load_with(text_size), M4D_ERR_INVALID_ARG);
  ASSERT_EQ(load_with(root), M4D_OK);
  std::vector<uint8_t> npz;
  ASSERT_TRUE(ReadFileBytes(dir.path() + "/init_pt_cld.npz", 1 << 20, &npz).ok());
  npz.resize(npz.size() / 2);
  ASSERT_TRUE(WriteFileBytes(dir.path() + "/init_pt_cld.npz", npz).ok());
  EXPECT_EQ(Load(dir.path(), &capture).code(), M4D_ERR_BITSTREAM);
}

// ---- Options and detection ------------------------------------------------------------------

TEST(CaptureOptionsTest, DownscaleScalesImagesAndIntrinsicsTogether) {
  TempDir dir;
  const std::vector<Camera> rig = Rig(2, kWidth, kHeight, false);
  WriteDynamicTransforms(dir, rig, 2, false);
  Capture full, half, third;
  ASSERT_TRUE(Load(dir.path(), &full).ok());
  CaptureOptions options;
  options.downscale = 2;
  ASSERT_TRUE(Load(dir.path(), &half, options).ok());
  options.downscale = 3;
  ASSERT_TRUE(Load(dir.path(), &third, options).ok());
  const double point[3] = {0.3, -0.2, 0.4};
  for (int c = 0; c < 2; ++c) {
    const Camera& a = full.camera(1, c);
    const Camera& b = half.camera(1, c);
    EXPECT_EQ(b.width, kWidth / 2);
    EXPECT_EQ(b.height, kHeight / 2);
    EXPECT_FLOAT_EQ(b.fx, a.fx / 2);
    EXPECT_FLOAT_EQ(b.cy, a.cy / 2);
    double u, v, u2, v2, u3, v3;
    Project(a, point, &u, &v);
    Project(b, point, &u2, &v2);
    EXPECT_NEAR(u2, u / 2, 1e-4);
    EXPECT_NEAR(v2, v / 2, 1e-4);
    // 64 x 48 by 3 is 21 x 16: each axis scales by its own ratio, as the image does.
    const Camera& t = third.camera(1, c);
    EXPECT_EQ(t.width, 21);
    EXPECT_EQ(t.height, 16);
    Project(t, point, &u3, &v3);
    EXPECT_NEAR(u3, u * 21 / 64, 1e-4);
    EXPECT_NEAR(v3, v * 16 / 48, 1e-4);

    Image full_image, expected;
    ASSERT_TRUE(full.LoadImage(1, c, &full_image).ok());
    ASSERT_TRUE(ResizeArea(full_image, kWidth / 2, kHeight / 2, &expected).ok());
    ExpectView(half, 1, c, expected, 0);
    ASSERT_TRUE(ResizeArea(full_image, 21, 16, &expected).ok());
    ExpectView(third, 1, c, expected, 0);
  }
}

TEST(CaptureOptionsTest, TestCameraAndFrameWindow) {
  TempDir dir;
  WriteDynamicTransforms(dir, Rig(3, kWidth, kHeight, false), 3, false);
  Capture capture;
  ASSERT_TRUE(Load(dir.path(), &capture).ok());
  EXPECT_EQ(capture.test_cameras, (std::vector<int>{0}));
  EXPECT_EQ(capture.TrainCameras(), (std::vector<int>{1, 2}));
  CaptureOptions options;
  options.test_camera = -1;
  ASSERT_TRUE(Load(dir.path(), &capture, options).ok());
  EXPECT_EQ(capture.TrainCameras(), (std::vector<int>{0, 1, 2}));
  options.test_camera = 2;
  ASSERT_TRUE(Load(dir.path(), &capture, options).ok());
  EXPECT_EQ(capture.TrainCameras(), (std::vector<int>{0, 1}));
  options.test_camera = 3;
  EXPECT_EQ(Load(dir.path(), &capture, options).code(), M4D_ERR_INVALID_ARG);
  options = CaptureOptions();
  options.first_frame = 2;
  options.max_frames = 5;
  ASSERT_TRUE(Load(dir.path(), &capture, options).ok());
  EXPECT_EQ(capture.frame_count, 1);
  ExpectView(capture, 0, 1, ViewImage(kWidth, kHeight, 2, 1), 0);
  options.first_frame = 3;
  EXPECT_EQ(Load(dir.path(), &capture, options).code(), M4D_ERR_INVALID_ARG);
  for (int bad : {0, 65}) {
    options = CaptureOptions();
    options.downscale = bad;
    EXPECT_EQ(Load(dir.path(), &capture, options).code(), M4D_ERR_INVALID_ARG);
  }
  options = CaptureOptions();
  options.downscale = 64;  // 64 x 48 has no rows left
  EXPECT_EQ(Load(dir.path(), &capture, options).code(), M4D_ERR_INVALID_ARG);
  options = CaptureOptions();
  options.max_frames = -1;
  EXPECT_EQ(Load(dir.path(), &capture, options).code(), M4D_ERR_INVALID_ARG);
}

TEST(CaptureOptionsTest, InitialPointsOverride) {
  TempDir dir;
  std::vector<Camera> rig = Rig(4, kWidth, kHeight, false);
  const std::vector<ColmapCameraSpec> specs = MixedSpecs(&rig);
  WriteColmap(dir.Subdir("colmap"), rig, specs, SomePoints(), false);
  WriteDynamicTransforms(dir, Rig(2, kWidth, kHeight, false), 1, false);
  PointCloud other;
  other.positions = {9, 8, 7};
  other.colors = {1, 0, 0};
  ASSERT_TRUE(WritePointCloudPly(dir.path() + "/other.ply", other).ok());
  CaptureOptions options;
  options.initial_points = dir.path() + "/other.ply";
  Capture capture;
  ASSERT_TRUE(Load(dir.path(), &capture, options).ok());
  EXPECT_EQ(capture.initial_points.positions, other.positions);
  options.initial_points = dir.path() + "/colmap/sparse/0";
  ASSERT_TRUE(Load(dir.path(), &capture, options).ok());
  ExpectSamePoints(capture.initial_points, SomePoints(), 0.5 / 255 + 1e-6);
  options.initial_points = dir.path() + "/none.ply";
  EXPECT_EQ(Load(dir.path(), &capture, options).code(), M4D_ERR_INVALID_ARG);
}

TEST(CaptureLoaderTest, DetectsLayouts) {
  TempDir dir;
  std::string layout;
  EXPECT_EQ(DetectCaptureLayout(dir.path(), &layout).code(), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(DetectCaptureLayout(dir.path() + "/missing", &layout).code(), M4D_ERR_INVALID_ARG);
  std::vector<Camera> rig = Rig(4, kWidth, kHeight, false);
  WriteColmap(dir.path(), rig, MixedSpecs(&rig), SomePoints(), true);
  ASSERT_TRUE(DetectCaptureLayout(dir.path(), &layout).ok());
  EXPECT_EQ(layout, "colmap");
  WriteText(dir.path() + "/train_meta.json", "{}");
  ASSERT_TRUE(DetectCaptureLayout(dir.path(), &layout).ok());
  EXPECT_EQ(layout, "dynamic3dgs");
  WriteText(dir.path() + "/poses_bounds.npy", "");
  ASSERT_TRUE(DetectCaptureLayout(dir.path(), &layout).ok());
  EXPECT_EQ(layout, "n3dv");
  WriteText(dir.path() + "/transforms.json", "{}");
  ASSERT_TRUE(DetectCaptureLayout(dir.path(), &layout).ok());
  EXPECT_EQ(layout, "nerfstudio");
  Capture capture;
  EXPECT_EQ(Load(dir.path(), &capture).code(), M4D_ERR_INVALID_ARG);  // no frames
}

// The same rig written in every layout gives the same cameras.
TEST(CaptureLoaderTest, SameRigAcrossLayouts) {
  TempDir dir;
  const std::vector<Camera> rig = Rig(3, kWidth, kHeight, true);  // what N3DV can express
  const std::string nerfstudio = dir.Subdir("nerfstudio"), colmap = dir.Subdir("colmap"),
                    n3dv = dir.Subdir("n3dv"), d3dgs = dir.Subdir("d3dgs");
  Json json = {{"w", kWidth}, {"h", kHeight}};
  for (int c = 0; c < 3; ++c) {
    const std::string file = "v" + std::to_string(c) + ".png";
    ASSERT_TRUE(WritePng(nerfstudio + "/" + file, ViewImage(kWidth, kHeight, 0, c)).ok());
    json["frames"].push_back(FrameEntry(rig[c], file));
  }
  WriteText(nerfstudio + "/transforms.json", json.dump());
  WriteColmap(colmap, rig,
              {Spec(rig[0], "PINHOLE"), Spec(rig[1], "SIMPLE_PINHOLE"), Spec(rig[2], "PINHOLE")},
              SomePoints(), true);
  std::vector<std::vector<double>> rows;
  for (const Camera& camera : rig) rows.push_back(PosesRow(camera));
  WritePoses(n3dv, rows);
  for (int c = 0; c < 3; ++c) {
    const std::string images = n3dv + "/cam0" + std::to_string(c) + "/images";
    std::filesystem::create_directories(images);
    ASSERT_TRUE(WritePng(images + "/0000.png", ViewImage(kWidth, kHeight, 0, c)).ok());
  }
  WriteDynamic3dgs(d3dgs, rig, 1, ZipMethod::kStored);
  std::vector<Capture> captures(4);
  const std::string dirs[4] = {nerfstudio, colmap, n3dv, d3dgs};
  for (int i = 0; i < 4; ++i) {
    const Status status = Load(dirs[i], &captures[i]);
    ASSERT_TRUE(status.ok()) << dirs[i] << ": " << status.message();
    ASSERT_EQ(captures[i].camera_count(), 3) << dirs[i];
    for (int c = 0; c < 3; ++c) {
      ExpectSameCamera(captures[i].camera(0, c), captures[0].camera(0, c), 1e-5);
      ExpectSameCamera(captures[i].camera(0, c), rig[c], 1e-5);
    }
  }
}

}  // namespace
}  // namespace m4d
