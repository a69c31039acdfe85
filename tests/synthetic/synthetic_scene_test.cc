// The built-in synthetic scene (encoder/src/synthetic): options, the camera rig, the
// rendered content (detail, motion, the emergent object, the background change), the files
// the writer produces, determinism, the initial point cloud, the in-memory capture, and the
// realistic variant's flaws (noise, JPEG, exposure, white balance, a left-handed
// calibration, a sparse rig, background sway, flicker, lens distortion).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "encoder/src/dataset/capture_loader.h"
#include "encoder/src/dataset/undistortion.h"
#include "encoder/src/image_io/byte_samples.h"
#include "encoder/src/image_io/file_bytes.h"
#include "encoder/src/image_io/jpeg_io.h"
#include "encoder/src/image_io/png_io.h"
#include "encoder/src/ply/point_cloud_ply.h"
#include "encoder/src/synthetic/camera_rig.h"
#include "encoder/src/synthetic/lens_resampling.h"
#include "encoder/src/synthetic/scene_animation.h"
#include "encoder/src/synthetic/scene_lighting.h"
#include "encoder/src/synthetic/scene_renderer.h"
#include "encoder/src/synthetic/scene_writer.h"
#include "encoder/src/synthetic/sensor_effects.h"
#include "encoder/src/synthetic/synthetic_capture.h"
#include "encoder/src/synthetic/synthetic_scene.h"

namespace m4d {
namespace {

// A directory of its own per test, removed afterwards.
class TempDir {
 public:
  explicit TempDir(const std::string& tag) {
    const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ =
        ::testing::TempDir() + "m4d_" + info->test_suite_name() + "_" + info->name() + "_" + tag;
    std::filesystem::remove_all(path_);
  }
  ~TempDir() { std::filesystem::remove_all(path_); }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

SyntheticSceneOptions SmallOptions() {
  SyntheticSceneOptions o;
  o.cameras = 3;
  o.width = 96;
  o.height = 72;
  o.frames = 4;
  o.points = 2000;
  return o;
}

std::unique_ptr<SyntheticScene> MakeScene(const SyntheticSceneOptions& options) {
  std::unique_ptr<SyntheticScene> scene;
  const Status status = SyntheticScene::Create(options, &scene);
  EXPECT_TRUE(status.ok()) << status.message();
  return scene;
}

std::vector<uint8_t> Render(SyntheticScene* scene, int frame, int camera) {
  std::vector<uint8_t> rgb;
  const Status status = scene->RenderView(frame, camera, &rgb);
  EXPECT_TRUE(status.ok()) << status.message();
  return rgb;
}

// Projects a world point; false behind the camera.
bool Project(const Camera& c, const glm::vec3& p, float* u, float* v) {
  const float* r = c.rotation;
  const float x = r[0] * p.x + r[1] * p.y + r[2] * p.z + c.translation[0];
  const float y = r[3] * p.x + r[4] * p.y + r[5] * p.z + c.translation[1];
  const float z = r[6] * p.x + r[7] * p.y + r[8] * p.z + c.translation[2];
  if (z <= 0.05f) return false;
  *u = c.fx * x / z + c.cx;
  *v = c.fy * y / z + c.cy;
  return true;
}

// 1 for the pixels covered by the screen boxes (grown by 2 pixels) of the objects that
// `pick` selects, at each of `frames`.
template <typename Pick>
std::vector<char> ObjectMask(const SyntheticScene& scene, int camera, std::vector<int> frames,
                             Pick pick) {
  const Camera& c = scene.cameras()[camera];
  std::vector<char> mask(static_cast<size_t>(c.width) * c.height, 0);
  const SceneContent& content = scene.content();
  for (int frame : frames) {
    const SceneFrameState state = SceneStateAt(content, scene.options(), frame);
    for (size_t o = 0; o < content.objects.size(); ++o) {
      if (!pick(content.objects[o]) || !state.visible[o]) continue;
      float u0 = 1e9f, v0 = 1e9f, u1 = -1e9f, v1 = -1e9f;
      for (const glm::vec3& p : content.objects[o].mesh.positions) {
        float u, v;
        if (!Project(c, glm::vec3(state.model[o] * glm::vec4(p, 1.0f)), &u, &v)) continue;
        u0 = std::min(u0, u), v0 = std::min(v0, v), u1 = std::max(u1, u), v1 = std::max(v1, v);
      }
      for (int y = std::max(0, static_cast<int>(v0) - 2);
           y < std::min(c.height, static_cast<int>(v1) + 3); ++y) {
        for (int x = std::max(0, static_cast<int>(u0) - 2);
             x < std::min(c.width, static_cast<int>(u1) + 3); ++x) {
          mask[static_cast<size_t>(y) * c.width + x] = 1;
        }
      }
    }
  }
  return mask;
}

bool IsMoving(const SceneObject& o) { return o.motion != ObjectMotion::kStatic; }
bool IsEmergent(const SceneObject& o) { return o.motion == ObjectMotion::kEmergent; }
bool MovesOrTurns(const SceneObject& o) {
  return o.motion == ObjectMotion::kFigurePart || o.motion == ObjectMotion::kRotating;
}
bool IsFigure(const SceneObject& o) { return o.motion == ObjectMotion::kFigurePart; }

// Mean absolute difference per sample and count of differing pixels where mask == want.
struct Difference {
  double mean = 0;
  int pixels = 0;
  int compared = 0;
};

Difference Compare(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b,
                   const std::vector<char>& mask, char want) {
  Difference d;
  double sum = 0;
  for (size_t i = 0; i < mask.size(); ++i) {
    if (mask[i] != want) continue;
    ++d.compared;
    int pixel = 0;
    for (int ch = 0; ch < 3; ++ch) pixel += std::abs(a[3 * i + ch] - b[3 * i + ch]);
    sum += pixel / 255.0;
    d.pixels += pixel > 0;
  }
  d.mean = d.compared > 0 ? sum / (3.0 * d.compared) : 0;
  return d;
}

std::vector<uint8_t> FileBytes(const std::string& path) {
  std::vector<uint8_t> bytes;
  EXPECT_TRUE(ReadFileBytes(path, size_t{1} << 26, &bytes).ok()) << path;
  return bytes;
}

TEST(SyntheticScene, BadOptionsAreRejected) {
  const auto code = [](void (*edit)(SyntheticSceneOptions*)) {
    SyntheticSceneOptions o;
    edit(&o);
    return ValidateSyntheticSceneOptions(o).code();
  };
  EXPECT_EQ(code([](SyntheticSceneOptions*) {}), M4D_OK);
  EXPECT_EQ(code([](SyntheticSceneOptions* o) { o->cameras = 0; }), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(code([](SyntheticSceneOptions* o) { o->cameras = 100000; }), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(code([](SyntheticSceneOptions* o) { o->width = 1 << 20; }), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(code([](SyntheticSceneOptions* o) { o->height = -5; }), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(code([](SyntheticSceneOptions* o) { o->frames = 0; }), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(code([](SyntheticSceneOptions* o) { o->points = -1; }), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(code([](SyntheticSceneOptions* o) { o->emergent_frame = 20; }), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(code([](SyntheticSceneOptions* o) { o->background_change_frame = -2; }),
            M4D_ERR_INVALID_ARG);
  EXPECT_EQ(code([](SyntheticSceneOptions* o) { o->horizontal_fov_degrees = NAN; }),
            M4D_ERR_INVALID_ARG);
  EXPECT_EQ(code([](SyntheticSceneOptions* o) {
              o->width = 4096;
              o->supersample = 4;
            }),
            M4D_ERR_LIMIT);

  TempDir dir("out");
  SyntheticSceneOptions bad;
  bad.cameras = 0;
  EXPECT_EQ(WriteSyntheticScene(bad, dir.path()).code(), M4D_ERR_INVALID_ARG);
  EXPECT_FALSE(std::filesystem::exists(dir.path()));
  Capture capture;
  EXPECT_EQ(GenerateSyntheticCapture(bad, &capture).code(), M4D_ERR_INVALID_ARG);
  // Valid, but far too many images to hold in memory: refused before rendering.
  SyntheticSceneOptions huge;
  huge.cameras = 256;
  huge.frames = 10000;
  EXPECT_EQ(GenerateSyntheticCapture(huge, &capture).code(), M4D_ERR_LIMIT);
}

TEST(SyntheticScene, CameraZeroSitsInsideTheRigAndEveryCameraSeesTheRoom) {
  for (int count : {16, 5, 30}) {
    SyntheticSceneOptions o;
    o.cameras = count;
    const std::vector<Camera> rig = MakeCameraRig(o);
    ASSERT_EQ(static_cast<int>(rig.size()), count);
    float x_min = 1e9f, x_max = -1e9f, y_min = 1e9f, y_max = -1e9f, centre0[3];
    CameraCentre(rig[0], centre0);
    for (int c = 0; c < count; ++c) {
      EXPECT_TRUE(ValidateCamera(rig[c]).ok());
      EXPECT_FLOAT_EQ(rig[c].cx, 160.0f);
      // 60 degrees across: fx = 160 / tan(30 degrees).
      EXPECT_NEAR(rig[c].fx, 277.128f, 0.01f);
      float centre[3];
      CameraCentre(rig[c], centre);
      EXPECT_GT(centre[2], 1.0f);  // in front of the room, looking in
      EXPECT_GT(rig[c].rotation[8], -1.0f);
      EXPECT_LT(rig[c].rotation[8], -0.9f);  // optical axis close to -z
      for (int d = 0; d < c; ++d) {
        float other[3];
        CameraCentre(rig[d], other);
        EXPECT_GT(std::hypot(centre[0] - other[0], centre[1] - other[1]), 0.05f);
      }
      if (c == 0) continue;
      x_min = std::min(x_min, centre[0]);
      x_max = std::max(x_max, centre[0]);
      y_min = std::min(y_min, centre[1]);
      y_max = std::max(y_max, centre[1]);
    }
    EXPECT_GT(centre0[0], x_min) << count << " cameras";
    EXPECT_LT(centre0[0], x_max) << count << " cameras";
    if (count >= 16) {  // several rows: camera 0 sits in a middle one
      EXPECT_GT(centre0[1], y_min) << count << " cameras";
      EXPECT_LT(centre0[1], y_max) << count << " cameras";
    }
  }
  const std::vector<std::string> names = CameraNames(120);
  EXPECT_EQ(names[0], "cam000");
  EXPECT_TRUE(std::is_sorted(names.begin(), names.end()));
  EXPECT_EQ(CameraNames(16)[15], "cam15");
}

TEST(SyntheticScene, ImagesHaveFineDetail) {
  SyntheticSceneOptions o = SmallOptions();
  o.width = 160;
  o.height = 120;
  std::unique_ptr<SyntheticScene> scene = MakeScene(o);
  ASSERT_NE(scene, nullptr);
  const std::vector<uint8_t> rgb = Render(scene.get(), 0, 0);
  ASSERT_EQ(rgb.size(), 160u * 120 * 3);
  // Luminance spread, and the energy of the finest scale: mean absolute difference between
  // horizontal and vertical neighbours.
  std::vector<double> luma(160 * 120);
  double mean = 0;
  for (size_t i = 0; i < luma.size(); ++i) {
    luma[i] = (0.299 * rgb[3 * i] + 0.587 * rgb[3 * i + 1] + 0.114 * rgb[3 * i + 2]) / 255.0;
    mean += luma[i] / luma.size();
  }
  double variance = 0, gradient = 0;
  for (int y = 0; y + 1 < 120; ++y) {
    for (int x = 0; x + 1 < 160; ++x) {
      const double l = luma[y * 160 + x];
      variance += (l - mean) * (l - mean);
      gradient += std::fabs(luma[y * 160 + x + 1] - l) + std::fabs(luma[(y + 1) * 160 + x] - l);
    }
  }
  variance /= 159 * 119;
  gradient /= 2 * 159 * 119;
  EXPECT_GT(std::sqrt(variance), 0.1);
  EXPECT_GT(gradient, 0.025);
  EXPECT_GT(mean, 0.2);
  EXPECT_LT(mean, 0.8);
}

TEST(SyntheticScene, FigureMovesWhileTheRoomStaysStill) {
  SyntheticSceneOptions o = SmallOptions();
  o.frames = 6;
  o.emergent_frame = 5;
  std::unique_ptr<SyntheticScene> scene = MakeScene(o);
  ASSERT_NE(scene, nullptr);
  for (int camera = 0; camera < o.cameras; ++camera) {
    // Two frames apart: a frame's motion is a few pixels, like a 30 fps capture's.
    const std::vector<uint8_t> a = Render(scene.get(), 1, camera),
                               b = Render(scene.get(), 3, camera);
    const std::vector<char> moving = ObjectMask(*scene, camera, {1, 3}, MovesOrTurns);
    const Difference room = Compare(a, b, moving, 0);
    EXPECT_GT(room.compared, 96 * 72 / 2);
    EXPECT_EQ(room.pixels, 0) << "camera " << camera;
    const Difference figure = Compare(a, b, ObjectMask(*scene, camera, {1, 3}, IsFigure), 1);
    EXPECT_GT(figure.pixels, figure.compared / 5) << "camera " << camera;
    EXPECT_GT(figure.mean, 0.01) << "camera " << camera;
  }
}

TEST(SyntheticScene, EmergentObjectAppearsAtItsFrame) {
  SyntheticSceneOptions o = SmallOptions();
  o.frames = 6;
  EXPECT_EQ(EmergentFrame(o), 3);
  std::unique_ptr<SyntheticScene> scene = MakeScene(o);
  ASSERT_NE(scene, nullptr);
  const int camera = 0;
  // The ball's box, less whatever else moves there.
  std::vector<char> ball = ObjectMask(*scene, camera, {3}, IsEmergent);
  const std::vector<char> others = ObjectMask(*scene, camera, {1, 2, 3, 4}, MovesOrTurns);
  for (size_t i = 0; i < ball.size(); ++i) ball[i] &= !others[i];
  const std::vector<uint8_t> f1 = Render(scene.get(), 1, camera),
                             f2 = Render(scene.get(), 2, camera);
  const std::vector<uint8_t> f3 = Render(scene.get(), 3, camera),
                             f4 = Render(scene.get(), 4, camera);
  const Difference before = Compare(f1, f2, ball, 1);
  const Difference appears = Compare(f2, f3, ball, 1);
  const Difference after = Compare(f3, f4, ball, 1);
  ASSERT_GT(before.compared, 50);
  EXPECT_EQ(before.pixels, 0);
  EXPECT_GT(appears.pixels, appears.compared / 3);
  EXPECT_GT(appears.mean, 0.05);
  EXPECT_EQ(after.pixels, 0);
  // And it is not drawn at all before: frames 0..2 agree outside the moving objects.
  const SceneFrameState state = SceneStateAt(scene->content(), scene->options(), 2);
  for (size_t i = 0; i < state.visible.size(); ++i) {
    EXPECT_EQ(state.visible[i] != 0, !IsEmergent(scene->content().objects[i]));
  }
}

TEST(SyntheticScene, BackgroundChangesOnlyWhenEnabled) {
  SyntheticSceneOptions o = SmallOptions();
  o.frames = 6;
  o.emergent_frame = 5;
  std::unique_ptr<SyntheticScene> steady = MakeScene(o);
  o.background_change_frame = 3;
  std::unique_ptr<SyntheticScene> changing = MakeScene(o);
  ASSERT_NE(steady, nullptr);
  ASSERT_NE(changing, nullptr);
  const int camera = 1;
  const std::vector<char> moving = ObjectMask(*steady, camera, {0, 2, 3, 4}, IsMoving);
  const Difference steady_diff =
      Compare(Render(steady.get(), 2, camera), Render(steady.get(), 3, camera), moving, 0);
  EXPECT_EQ(steady_diff.pixels, 0);
  const std::vector<uint8_t> c2 = Render(changing.get(), 2, camera);
  const std::vector<uint8_t> c3 = Render(changing.get(), 3, camera);
  const std::vector<uint8_t> c4 = Render(changing.get(), 4, camera);
  EXPECT_EQ(Compare(Render(changing.get(), 0, camera), c2, moving, 0).pixels, 0);
  const Difference change = Compare(c2, c3, moving, 0);
  EXPECT_GT(change.pixels, change.compared / 2);
  EXPECT_GT(change.mean, 0.01);
  EXPECT_EQ(Compare(c3, c4, moving, 0).pixels, 0);
  // Before the change the two scenes are the same.
  EXPECT_EQ(Render(steady.get(), 2, camera), c2);
}

TEST(SyntheticScene, WriterProducesTheDeclaredFiles) {
  SyntheticSceneOptions o = SmallOptions();
  o.background_change_frame = 2;
  TempDir dir("scene");
  int progress_calls = 0, last_done = 0;
  const Status status = WriteSyntheticScene(o, dir.path() + "/nested", [&](int done, int total) {
    ++progress_calls;
    EXPECT_EQ(done, last_done + 1);
    EXPECT_EQ(total, o.frames);
    last_done = done;
  });
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(progress_calls, o.frames);
  const std::string root = dir.path() + "/nested/";

  const std::vector<uint8_t> text = FileBytes(root + "transforms.json");
  const nlohmann::json transforms = nlohmann::json::parse(text.begin(), text.end());
  EXPECT_EQ(transforms["camera_model"], "OPENCV");
  EXPECT_EQ(transforms["w"], o.width);
  EXPECT_EQ(transforms["h"], o.height);
  EXPECT_EQ(transforms["cx"], o.width / 2.0);
  EXPECT_EQ(transforms["ply_file_path"], "points3d.ply");
  const std::vector<Camera> rig = MakeCameraRig(o);
  EXPECT_NEAR(transforms["fl_x"].get<double>(), rig[0].fx, 1e-4);
  const nlohmann::json& frames = transforms["frames"];
  ASSERT_EQ(frames.size(), static_cast<size_t>(o.frames * o.cameras));
  for (const nlohmann::json& entry : frames) {
    const int f = entry["time_index"], c = std::stoi(entry["camera"].get<std::string>().substr(3));
    EXPECT_EQ(entry["file_path"], SyntheticImagePath(CameraNames(o.cameras)[c], f));
    EXPECT_DOUBLE_EQ(entry["time"].get<double>(), f / (o.frames - 1.0));
    Image image;
    ASSERT_TRUE(ReadPng(root + entry["file_path"].get<std::string>(), &image).ok());
    EXPECT_EQ(image.width, o.width);
    EXPECT_EQ(image.height, o.height);
    EXPECT_EQ(image.channels, 3);
    // Camera-to-world in OpenGL axes: the last column is the centre, the third column the
    // backward axis (minus the OpenCV optical axis, the third row of R).
    float centre[3];
    CameraCentre(rig[c], centre);
    for (int a = 0; a < 3; ++a) {
      EXPECT_NEAR(entry["transform_matrix"][a][3].get<double>(), centre[a], 1e-5);
      EXPECT_NEAR(entry["transform_matrix"][a][2].get<double>(), -rig[c].rotation[6 + a], 1e-6);
    }
  }

  PointCloud points;
  ASSERT_TRUE(ReadPointCloudPly(root + "points3d.ply", &points).ok());
  EXPECT_EQ(points.size(), static_cast<size_t>(o.points));

  const std::vector<uint8_t> scene_text = FileBytes(root + "scene.json");
  const nlohmann::json scene = nlohmann::json::parse(scene_text.begin(), scene_text.end());
  EXPECT_EQ(scene["emergent_frame"], 2);
  EXPECT_EQ(scene["background_change_frame"], 2);
  EXPECT_EQ(scene["cameras"], o.cameras);
  EXPECT_EQ(scene["test_camera"], 0);
  EXPECT_EQ(scene["seed"], o.seed);
}

TEST(SyntheticScene, SameOptionsGiveIdenticalFiles) {
  SyntheticSceneOptions o = SmallOptions();
  o.cameras = 2;
  o.frames = 3;
  TempDir first("a"), second("b");
  ASSERT_TRUE(WriteSyntheticScene(o, first.path()).ok());
  ASSERT_TRUE(WriteSyntheticScene(o, second.path()).ok());
  int files = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(first.path())) {
    if (!entry.is_regular_file()) continue;
    const std::string relative = std::filesystem::relative(entry.path(), first.path()).string();
    EXPECT_EQ(FileBytes(entry.path().string()), FileBytes(second.path() + "/" + relative))
        << relative;
    ++files;
  }
  EXPECT_EQ(files, o.cameras * o.frames + 3);
  // Another seed changes the textures.
  o.seed = 2;
  TempDir third("c");
  ASSERT_TRUE(WriteSyntheticScene(o, third.path()).ok());
  EXPECT_NE(FileBytes(first.path() + "/images/cam00/000000.png"),
            FileBytes(third.path() + "/images/cam00/000000.png"));
}

// Mean colour of the points that project into each 8 x 8 block of an image, and of the
// pixels they land on. Block means, because a point takes the texture's finest level while a
// pixel averages the texture over its footprint, and because some points lie on surfaces
// hidden from this camera (the floor under the rug).
struct BlockColours {
  std::vector<glm::vec3> points, pixels;
};

BlockColours BlockMeans(const PointCloud& cloud, const Camera& camera, const Image& image) {
  const int bw = (image.width + 7) / 8, bh = (image.height + 7) / 8;
  std::vector<glm::vec3> point_sum(bw * bh, glm::vec3(0)), pixel_sum(bw * bh, glm::vec3(0));
  std::vector<int> count(bw * bh, 0);
  for (size_t i = 0; i < cloud.size(); ++i) {
    const float* p = &cloud.positions[3 * i];
    float u, v;
    if (!Project(camera, glm::vec3(p[0], p[1], p[2]), &u, &v)) continue;
    if (u < 0 || v < 0 || u >= image.width || v >= image.height) continue;
    const int x = static_cast<int>(u), y = static_cast<int>(v), b = (y / 8) * bw + x / 8;
    ++count[b];
    point_sum[b] +=
        glm::vec3(cloud.colors[3 * i], cloud.colors[3 * i + 1], cloud.colors[3 * i + 2]);
    pixel_sum[b] += glm::vec3(image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2));
  }
  BlockColours blocks;
  for (int b = 0; b < bw * bh; ++b) {
    if (count[b] < 5) continue;
    blocks.points.push_back(point_sum[b] / static_cast<float>(count[b]));
    blocks.pixels.push_back(pixel_sum[b] / static_cast<float>(count[b]));
  }
  return blocks;
}

TEST(SyntheticScene, InitialPointsLieOnTheRenderedSurfaces) {
  SyntheticSceneOptions o = SmallOptions();
  o.width = 160;
  o.height = 120;
  o.frames = 1;
  o.points = 20000;
  TempDir dir("scene");
  ASSERT_TRUE(WriteSyntheticScene(o, dir.path()).ok());
  PointCloud points;
  ASSERT_TRUE(ReadPointCloudPly(dir.path() + "/points3d.ply", &points).ok());
  ASSERT_EQ(points.size(), 20000u);
  const std::vector<Camera> rig = MakeCameraRig(o);
  for (int camera = 0; camera < o.cameras; ++camera) {
    Image image;
    ASSERT_TRUE(
        ReadPng(dir.path() + "/" + SyntheticImagePath(CameraNames(o.cameras)[camera], 0), &image)
            .ok());
    const BlockColours blocks = BlockMeans(points, rig[camera], image);
    // Points cover most of the image...
    ASSERT_GT(blocks.points.size(), 20u * 15 * 8 / 10) << "camera " << camera;
    // ...with the colours of the pixels they fall on, compared with the pixels of another
    // block (what unrelated colours would give).
    const size_t n = blocks.points.size();
    double error = 0, unrelated = 0;
    for (size_t b = 0; b < n; ++b) {
      const glm::vec3 e = glm::abs(blocks.points[b] - blocks.pixels[b]);
      const glm::vec3 f = glm::abs(blocks.points[b] - blocks.pixels[(b + n / 2) % n]);
      error += (e.x + e.y + e.z) / (3.0 * n);
      unrelated += (f.x + f.y + f.z) / (3.0 * n);
    }
    EXPECT_LT(error, 0.05) << "camera " << camera;
    EXPECT_LT(error, 0.3 * unrelated) << "camera " << camera;
  }
}

TEST(SyntheticScene, CaptureInMemoryMatchesTheWrittenImages) {
  SyntheticSceneOptions o = SmallOptions();
  o.frames = 2;
  TempDir dir("scene");
  ASSERT_TRUE(WriteSyntheticScene(o, dir.path()).ok());
  Capture capture;
  const Status status = GenerateSyntheticCapture(o, &capture);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(capture.layout, "synthetic");
  EXPECT_EQ(capture.frame_count, o.frames);
  EXPECT_EQ(capture.camera_count(), o.cameras);
  EXPECT_EQ(capture.test_cameras, (std::vector<int>{0}));
  EXPECT_EQ(capture.TrainCameras(), (std::vector<int>{1, 2}));
  EXPECT_EQ(capture.initial_points.size(), static_cast<size_t>(o.points));
  for (int f = 0; f < o.frames; ++f) {
    for (int c = 0; c < o.cameras; ++c) {
      EXPECT_EQ(capture.camera(f, c).fx, MakeCameraRig(o)[c].fx);
      Image from_memory, from_file;
      ASSERT_TRUE(capture.LoadImage(f, c, &from_memory).ok());
      ASSERT_TRUE(
          ReadPng(dir.path() + "/" + SyntheticImagePath(capture.camera_names[c], f), &from_file)
              .ok());
      EXPECT_EQ(from_memory.pixels, from_file.pixels) << "frame " << f << " camera " << c;
    }
  }
  Image image;
  EXPECT_EQ(capture.LoadImage(o.frames, 0, &image).code(), M4D_ERR_INVALID_ARG);
}

// The realistic variant's tests use tiny views: 64x48, a few cameras and frames.
SyntheticSceneOptions TinyOptions() {
  SyntheticSceneOptions o;
  o.cameras = 3;
  o.width = 64;
  o.height = 48;
  o.frames = 2;
  o.points = 500;
  return o;
}

Image ReadImage(const std::string& path) {
  Image image;
  const bool jpeg = path.size() > 4 && path.compare(path.size() - 4, 4, ".jpg") == 0;
  const Status status = jpeg ? ReadJpeg(path, &image) : ReadPng(path, &image);
  EXPECT_TRUE(status.ok()) << path << ": " << status.message();
  return image;
}

std::vector<uint8_t> ImageBytes(const Image& image) {
  std::vector<uint8_t> bytes(image.pixels.size());
  for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = FloatToByte(image.pixels[i]);
  return bytes;
}

// PSNR of 8-bit RGB views over the pixels at least `margin` from every border.
double Psnr(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b, int width, int height,
            int margin) {
  double sum = 0;
  int count = 0;
  for (int y = margin; y < height - margin; ++y) {
    for (int x = margin; x < width - margin; ++x) {
      for (int ch = 0; ch < 3; ++ch) {
        const size_t i = (static_cast<size_t>(y) * width + x) * 3 + ch;
        sum += (a[i] - b[i]) * (a[i] - b[i]);
        ++count;
      }
    }
  }
  return sum > 0 ? 10.0 * std::log10(255.0 * 255.0 * count / sum) : 99.0;
}

nlohmann::json ReadJson(const std::string& path) {
  const std::vector<uint8_t> text = FileBytes(path);
  return nlohmann::json::parse(text.begin(), text.end());
}

TEST(SyntheticRealism, OptionsAreValidated) {
  const auto code = [](void (*edit)(CaptureRealism*)) {
    SyntheticSceneOptions o;
    edit(&o.realism);
    return ValidateSyntheticSceneOptions(o).code();
  };
  EXPECT_EQ(code([](CaptureRealism* r) { r->noise_sigma = -1; }), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(code([](CaptureRealism* r) { r->noise_sigma = NAN; }), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(code([](CaptureRealism* r) { r->jpeg_quality = 101; }), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(code([](CaptureRealism* r) { r->exposure_spread = 0.6f; }), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(code([](CaptureRealism* r) { r->white_balance_spread = -0.1f; }), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(code([](CaptureRealism* r) { r->p1 = 0.2f; }), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(code([](CaptureRealism* r) { r->sparse_rig_arc_degrees = 0; }), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(code([](CaptureRealism* r) { r->background_sway = 1; }), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(code([](CaptureRealism* r) { r->light_flicker = 0.8f; }), M4D_ERR_INVALID_ARG);
  // Barrel distortion this strong folds the image's corners back inwards.
  EXPECT_EQ(code([](CaptureRealism* r) { r->k1 = -0.9f; }), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(code([](CaptureRealism* r) { r->k1 = -0.2f; }), M4D_OK);
  EXPECT_TRUE(ValidateSyntheticSceneOptions(SyntheticSceneOptions::Realistic()).ok());
}

TEST(SyntheticRealism, DefaultOptionsWriteTheCleanScene) {
  const CaptureRealism off;
  EXPECT_EQ(off.noise_sigma, 0.0f);
  EXPECT_EQ(off.jpeg_quality, 0);
  EXPECT_FALSE(off.left_handed || off.sparse_rig);
  const SyntheticSceneOptions o = TinyOptions();
  TempDir dir("scene");
  ASSERT_TRUE(WriteSyntheticScene(o, dir.path()).ok());
  // No lens model and no mirrored world in the calibration: a pinhole, right-handed rig.
  const nlohmann::json transforms = ReadJson(dir.path() + "/transforms.json");
  for (const char* key : {"k1", "k2", "k3", "p1", "p2"}) {
    EXPECT_FALSE(transforms.contains(key)) << key;
    for (const nlohmann::json& frame : transforms["frames"]) EXPECT_FALSE(frame.contains(key));
  }
  const std::vector<Camera> rig = MakeCameraRig(o);
  for (const nlohmann::json& frame : transforms["frames"]) {
    const nlohmann::json& m = frame["transform_matrix"];
    const double det = m[0][0].get<double>() * (m[1][1].get<double>() * m[2][2].get<double>() -
                                                m[1][2].get<double>() * m[2][1].get<double>()) -
                       m[0][1].get<double>() * (m[1][0].get<double>() * m[2][2].get<double>() -
                                                m[1][2].get<double>() * m[2][0].get<double>()) +
                       m[0][2].get<double>() * (m[1][0].get<double>() * m[2][1].get<double>() -
                                                m[1][1].get<double>() * m[2][0].get<double>());
    EXPECT_NEAR(det, 1.0, 1e-5);
  }
  // The start points are the clean scene's own.
  PointCloud points;
  ASSERT_TRUE(ReadPointCloudPly(dir.path() + "/points3d.ply", &points).ok());
  const std::unique_ptr<SyntheticScene> clean = MakeScene(o);
  ASSERT_NE(clean, nullptr);
  const PointCloud expected = clean->InitialPoints();
  EXPECT_EQ(points.positions, expected.positions);
  ASSERT_EQ(points.colors.size(), expected.colors.size());
  for (size_t i = 0; i < expected.colors.size(); ++i) {
    EXPECT_NEAR(points.colors[i], expected.colors[i], 1.0 / 255) << i;  // stored in 8 bits
  }
  // The images are the renderer's output, untouched.
  std::unique_ptr<SceneRenderer> renderer;
  const SceneContent content = BuildSceneContent(o.seed, false);
  ASSERT_TRUE(SceneRenderer::Create(content, o.width, o.height, o.supersample, 1, &renderer).ok());
  for (int f = 0; f < o.frames; ++f) {
    for (int c = 0; c < o.cameras; ++c) {
      std::vector<uint8_t> rendered;
      ASSERT_TRUE(renderer->Render(SceneStateAt(content, o, f), rig[c], &rendered).ok());
      const std::string path = SyntheticImagePath(CameraNames(o.cameras)[c], f);
      EXPECT_EQ(path.substr(path.size() - 4), ".png");
      EXPECT_EQ(ImageBytes(ReadImage(dir.path() + "/" + path)), rendered) << path;
    }
  }
  const nlohmann::json scene = ReadJson(dir.path() + "/scene.json");
  EXPECT_EQ(scene["realism"]["noise_sigma"], 0.0);
  EXPECT_EQ(scene["realism"]["left_handed"], false);
}

TEST(SyntheticRealism, NoiseIsFreshEveryViewWithTheSigmaAsked) {
  SyntheticSceneOptions o = TinyOptions();
  o.emergent_frame = 1;
  std::unique_ptr<SyntheticScene> clean = MakeScene(o);
  o.realism.noise_sigma = 4.0f;
  std::unique_ptr<SyntheticScene> noisy = MakeScene(o);
  ASSERT_NE(clean, nullptr);
  ASSERT_NE(noisy, nullptr);
  std::vector<double> residual[2];
  for (int c = 0; c < 2; ++c) {
    const std::vector<uint8_t> base = Render(clean.get(), 0, c), n0 = Render(noisy.get(), 0, c);
    // Away from 0 and 255, where clamping would shrink the noise.
    double sum = 0, sum2 = 0;
    for (size_t i = 0; i < base.size(); ++i) {
      const double r = base[i] >= 16 && base[i] <= 239 ? n0[i] - base[i] : 0.0;
      residual[c].push_back(r);
      sum += r;
      sum2 += r * r;
    }
    const double n = static_cast<double>(base.size());
    // Rounding adds 1/12 of a level squared to the variance.
    EXPECT_NEAR(std::sqrt(sum2 / n - (sum / n) * (sum / n)), std::sqrt(16.0 + 1.0 / 12), 0.25)
        << "camera " << c;
    EXPECT_NEAR(sum / n, 0.0, 0.2) << "camera " << c;
    // Static pixels: identical between frames without noise, different with it.
    const std::vector<char> moving = ObjectMask(*clean, c, {0, 1}, IsMoving);
    EXPECT_EQ(Compare(base, Render(clean.get(), 1, c), moving, 0).pixels, 0);
    const Difference frames = Compare(n0, Render(noisy.get(), 1, c), moving, 0);
    EXPECT_GT(frames.pixels, frames.compared * 8 / 10) << "camera " << c;
    EXPECT_EQ(Render(noisy.get(), 0, c), n0);  // deterministic
  }
  // Each camera's noise is its own: the residuals are uncorrelated.
  double cross = 0, norm0 = 0, norm1 = 0;
  for (size_t i = 0; i < residual[0].size(); ++i) {
    cross += residual[0][i] * residual[1][i];
    norm0 += residual[0][i] * residual[0][i];
    norm1 += residual[1][i] * residual[1][i];
  }
  EXPECT_LT(std::fabs(cross) / std::sqrt(norm0 * norm1), 0.1);
}

TEST(SyntheticRealism, JpegFilesAndTheCaptureHoldTheSameLossyPixels) {
  SyntheticSceneOptions o = TinyOptions();
  // Rendered first: a scene renders only while its GL context is the thread's current one.
  std::vector<std::vector<uint8_t>> clean_views;
  {
    std::unique_ptr<SyntheticScene> clean = MakeScene(o);
    ASSERT_NE(clean, nullptr);
    for (int c = 0; c < o.cameras; ++c) clean_views.push_back(Render(clean.get(), 0, c));
  }
  double psnr[2];
  const int qualities[2] = {90, 50};
  for (int q = 0; q < 2; ++q) {
    o.realism.jpeg_quality = qualities[q];
    TempDir dir("q" + std::to_string(qualities[q]));
    ASSERT_TRUE(WriteSyntheticScene(o, dir.path()).ok());
    Capture capture;
    ASSERT_TRUE(GenerateSyntheticCapture(o, &capture).ok());
    const nlohmann::json transforms = ReadJson(dir.path() + "/transforms.json");
    EXPECT_EQ(ReadJson(dir.path() + "/scene.json")["realism"]["jpeg_quality"], qualities[q]);
    double sum = 0;
    for (int c = 0; c < o.cameras; ++c) {
      const std::string path = transforms["frames"][c]["file_path"];
      EXPECT_EQ(path, SyntheticImagePath(capture.camera_names[c], 0, true));
      const Image file = ReadImage(dir.path() + "/" + path);
      Image memory;
      ASSERT_TRUE(capture.LoadImage(0, c, &memory).ok());
      EXPECT_EQ(memory.pixels, file.pixels) << path;
      sum += Psnr(ImageBytes(file), clean_views[c], o.width, o.height, 0);
    }
    psnr[q] = sum / o.cameras;
  }
  // The bounds hold the measured values with room
  // (docs/results/2026-11-30-test-comment-measurements.md).
  EXPECT_GT(psnr[0], 32.0);
  EXPECT_LT(psnr[0], 42.0);
  EXPECT_GT(psnr[1], 25.0);
  EXPECT_LT(psnr[1], psnr[0] - 3.0);
}

TEST(SyntheticRealism, ExposureAndWhiteBalanceScaleEachCamerasColours) {
  SyntheticSceneOptions o = TinyOptions();
  o.cameras = 4;
  o.frames = 1;
  std::unique_ptr<SyntheticScene> clean = MakeScene(o);
  o.realism.exposure_spread = 0.15f;
  o.realism.white_balance_spread = 0.05f;
  std::unique_ptr<SyntheticScene> graded = MakeScene(o);
  ASSERT_NE(clean, nullptr);
  ASSERT_NE(graded, nullptr);
  float lowest = 2.0f, highest = 0.0f;
  for (int c = 0; c < o.cameras; ++c) {
    const glm::vec3 gain = CameraColourGain(o, c);
    const std::vector<uint8_t> a = Render(clean.get(), 0, c), b = Render(graded.get(), 0, c);
    for (int ch = 0; ch < 3; ++ch) {
      EXPECT_GE(gain[ch], 0.85f * 0.95f);
      EXPECT_LE(gain[ch], 1.15f * 1.05f);
      // The mean of each channel over the samples the gain cannot clip.
      double clean_sum = 0, graded_sum = 0;
      for (size_t i = ch; i < a.size(); i += 3) {
        if (a[i] > 200) continue;
        clean_sum += a[i];
        graded_sum += b[i];
      }
      EXPECT_NEAR(graded_sum / clean_sum, gain[ch], 0.005) << "camera " << c << " channel " << ch;
    }
    lowest = std::min(lowest, gain.g);
    highest = std::max(highest, gain.g);
  }
  EXPECT_GT(highest - lowest, 0.05f);  // the cameras do differ
  EXPECT_EQ(CameraColourGain(TinyOptions(), 2), glm::vec3(1.0f));
}

// The 3x3 block of a 4x4 JSON matrix.
double Determinant(const nlohmann::json& m) {
  const auto a = [&m](int i, int j) { return m[i][j].get<double>(); };
  return a(0, 0) * (a(1, 1) * a(2, 2) - a(1, 2) * a(2, 1)) -
         a(0, 1) * (a(1, 0) * a(2, 2) - a(1, 2) * a(2, 0)) +
         a(0, 2) * (a(1, 0) * a(2, 1) - a(1, 1) * a(2, 0));
}

TEST(SyntheticRealism, LeftHandedCalibrationMirrorsTheWorldNotTheImages) {
  SyntheticSceneOptions o = TinyOptions();
  TempDir right("right"), left("left");
  ASSERT_TRUE(WriteSyntheticScene(o, right.path()).ok());
  o.realism.left_handed = true;
  ASSERT_TRUE(WriteSyntheticScene(o, left.path()).ok());
  const nlohmann::json r = ReadJson(right.path() + "/transforms.json");
  const nlohmann::json l = ReadJson(left.path() + "/transforms.json");
  ASSERT_EQ(l["frames"].size(), r["frames"].size());
  for (size_t v = 0; v < l["frames"].size(); ++v) {
    const nlohmann::json& lm = l["frames"][v]["transform_matrix"];
    const nlohmann::json& rm = r["frames"][v]["transform_matrix"];
    EXPECT_NEAR(Determinant(rm), 1.0, 1e-5);
    EXPECT_NEAR(Determinant(lm), -1.0, 1e-5);
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) {
        EXPECT_EQ(lm[i][j].get<double>(), (i == 0 ? -1.0 : 1.0) * rm[i][j].get<double>());
      }
    }
    const std::string image = l["frames"][v]["file_path"];
    EXPECT_EQ(FileBytes(left.path() + "/" + image), FileBytes(right.path() + "/" + image));
  }
  PointCloud lp, rp;
  ASSERT_TRUE(ReadPointCloudPly(left.path() + "/points3d.ply", &lp).ok());
  ASSERT_TRUE(ReadPointCloudPly(right.path() + "/points3d.ply", &rp).ok());
  ASSERT_EQ(lp.size(), rp.size());
  for (size_t i = 0; i < lp.positions.size(); ++i) {
    EXPECT_EQ(lp.positions[i], (i % 3 == 0 ? -1.0f : 1.0f) * rp.positions[i]);
  }
  EXPECT_EQ(lp.colors, rp.colors);
  EXPECT_EQ(ReadJson(left.path() + "/scene.json")["realism"]["left_handed"], true);
}

TEST(SyntheticRealism, SparseRigSpansAWideArcInsideTheRoom) {
  SyntheticSceneOptions o;
  o.cameras = 4;
  o.realism.sparse_rig = true;
  const std::vector<Camera> rig = MakeCameraRig(o);
  ASSERT_EQ(rig.size(), 4u);
  // Bearings of the cameras seen from above the point they aim at (0, 1, -1.8).
  std::vector<double> bearings;
  for (const Camera& camera : rig) {
    EXPECT_TRUE(ValidateCamera(camera).ok());
    float centre[3];
    CameraCentre(camera, centre);
    EXPECT_LT(std::fabs(centre[0]), 2.5f);  // inside the side walls
    EXPECT_NEAR(centre[1], 1.2f, 1e-4f);
    bearings.push_back(std::atan2(centre[0], centre[2] + 1.8) * 180.0 / 3.14159265358979);
    float u, v;
    ASSERT_TRUE(Project(camera, glm::vec3(0.0f, 1.0f, -1.8f), &u, &v));
    EXPECT_NEAR(u, camera.cx, 1e-2f);
  }
  const auto [lowest, highest] = std::minmax_element(bearings.begin(), bearings.end());
  EXPECT_NEAR(*highest - *lowest, 90.0, 1e-3);
  // Neighbours 30 degrees apart, camera 0 (held out) one of the two in the middle.
  std::vector<double> sorted = bearings;
  std::sort(sorted.begin(), sorted.end());
  for (int i = 1; i < 4; ++i) EXPECT_NEAR(sorted[i] - sorted[i - 1], 30.0, 1e-3);
  EXPECT_NEAR(std::fabs(bearings[0]), 15.0, 1e-3);
}

TEST(SyntheticRealism, BackgroundSwayMovesOnlyThePlant) {
  SyntheticSceneOptions o = TinyOptions();
  o.width = 96;
  o.height = 72;
  o.frames = 8;
  o.emergent_frame = 7;
  o.realism.background_sway = 0.05f;
  std::unique_ptr<SyntheticScene> scene = MakeScene(o);
  ASSERT_NE(scene, nullptr);
  const auto is_plant = [](const SceneObject& object) {
    return object.motion == ObjectMotion::kSwaying;
  };
  const int camera = 0;
  // Frames 0 and 6: upright, and near the sway's widest (its period is 27 frames).
  const std::vector<char> others = ObjectMask(*scene, camera, {0, 6}, MovesOrTurns);
  std::vector<char> plant = ObjectMask(*scene, camera, {0, 6}, is_plant);
  int plant_area = 0;
  for (size_t i = 0; i < plant.size(); ++i) {
    plant_area += plant[i];
    if (others[i]) plant[i] = 2;  // where the figure may be, too: not compared
  }
  ASSERT_GT(plant_area, 0);
  EXPECT_LT(plant_area, o.width * o.height / 10);
  const std::vector<uint8_t> a = Render(scene.get(), 0, camera), b = Render(scene.get(), 6, camera);
  const Difference on_plant = Compare(a, b, plant, 1);
  EXPECT_GT(on_plant.pixels, 5);
  EXPECT_LT(on_plant.pixels, on_plant.compared);
  EXPECT_EQ(Compare(a, b, plant, 0).pixels, 0);  // nothing else in the room moves
  // The sway stays within its amplitude: the foliage top (0.95 m up) moves at most that far
  // from where it stands upright, and at least half that far in a cycle.
  float farthest = 0.0f;
  for (int f = 0; f < 40; ++f) {
    const glm::mat4 pose = SceneStateAt(scene->content(), o, f).model.back();
    const glm::vec3 top(0.0f, 0.95f, 0.0f);
    const glm::vec3 upright = glm::vec3(pose[3]) + top;
    farthest = std::max(farthest, glm::length(glm::vec3(pose * glm::vec4(top, 1.0f)) - upright));
  }
  EXPECT_LE(farthest, 0.05f);
  EXPECT_GT(farthest, 0.025f);
}

TEST(SyntheticRealism, FlickerScalesTheLightEveryFrame) {
  SyntheticSceneOptions o = TinyOptions();
  o.frames = 3;
  o.emergent_frame = 2;
  o.realism.light_flicker = 0.05f;
  std::unique_ptr<SyntheticScene> scene = MakeScene(o);
  ASSERT_NE(scene, nullptr);
  const int camera = 1;
  const std::vector<char> moving = ObjectMask(*scene, camera, {0, 1}, IsMoving);
  const std::vector<uint8_t> a = Render(scene.get(), 0, camera), b = Render(scene.get(), 1, camera);
  double sum_a = 0, sum_b = 0;
  for (size_t i = 0; i < moving.size(); ++i) {
    for (int ch = 0; ch < 3; ++ch) {
      // Below the ceiling of 1 that shading clamps to, at either gain.
      if (moving[i] || a[3 * i + ch] > 230 || b[3 * i + ch] > 230) continue;
      sum_a += a[3 * i + ch];
      sum_b += b[3 * i + ch];
    }
  }
  const float g0 = LightFlickerGain(o, 0), g1 = LightFlickerGain(o, 1);
  EXPECT_NEAR(sum_b / sum_a, g1 / g0, 0.004);
  EXPECT_GT(std::fabs(g1 / g0 - 1.0f), 0.01f);  // this seed's two frames do differ
  for (int f = 0; f < 50; ++f) {
    EXPECT_LE(std::fabs(LightFlickerGain(o, f) - 1.0f), 0.05f);
    EXPECT_EQ(LightFlickerGain(TinyOptions(), f), 1.0f);
  }
}

TEST(SyntheticRealism, LensDistortionIsWrittenAndUndistortsToThePinholeRender) {
  SyntheticSceneOptions o = TinyOptions();
  o.width = 96;
  o.height = 72;
  o.frames = 1;
  std::vector<std::vector<uint8_t>> pinhole;  // rendered first: one GL context at a time
  {
    std::unique_ptr<SyntheticScene> clean = MakeScene(o);
    ASSERT_NE(clean, nullptr);
    for (int c = 0; c < o.cameras; ++c) pinhole.push_back(Render(clean.get(), 0, c));
  }
  CaptureRealism& r = o.realism;
  r.k1 = -0.15f;
  r.k2 = 0.04f;
  r.p1 = 0.002f;
  r.p2 = -0.001f;
  TempDir dir("scene");
  ASSERT_TRUE(WriteSyntheticScene(o, dir.path()).ok());
  const nlohmann::json transforms = ReadJson(dir.path() + "/transforms.json");
  EXPECT_EQ(transforms["camera_model"], "OPENCV");
  EXPECT_EQ(transforms["k1"].get<double>(), -0.15);
  EXPECT_EQ(transforms["k2"].get<double>(), 0.04);
  EXPECT_EQ(transforms["p1"].get<double>(), 0.002);
  EXPECT_EQ(transforms["p2"].get<double>(), -0.001);
  EXPECT_FALSE(transforms.contains("k3"));
  EXPECT_EQ(ReadJson(dir.path() + "/scene.json")["realism"]["k1"].get<double>(), -0.15);
  // Undistorting each view back to the rig's pinhole camera: every pinhole pixel takes the
  // distorted image at its distorted position.
  const LensDistortion distortion = SceneLensDistortion(r);
  const std::vector<Camera> rig = MakeCameraRig(o);
  UndistortionMap map;
  ASSERT_TRUE(BuildUndistortionMap(rig[0], distortion, rig[0], "test", &map).ok());
  for (int c = 0; c < o.cameras; ++c) {
    const Image distorted =
        ReadImage(dir.path() + "/" + SyntheticImagePath(CameraNames(o.cameras)[c], 0));
    Image undistorted;
    ASSERT_TRUE(Remap(map, distorted, &undistorted).ok());
    const double recovered = Psnr(ImageBytes(undistorted), pinhole[c], o.width, o.height, 6);
    const double as_is = Psnr(ImageBytes(distorted), pinhole[c], o.width, o.height, 6);
    EXPECT_GT(recovered, 30.0) << "camera " << c;
    EXPECT_LT(as_is, recovered - 5.0) << "camera " << c;  // the lens did bend the view
  }
  // The in-memory capture serves the views as loading the files does: undistorted.
  Capture memory, loaded;
  ASSERT_TRUE(GenerateSyntheticCapture(o, &memory).ok());
  ASSERT_TRUE(LoadCapture(dir.path(), CaptureOptions(), &loaded).ok());
  for (int c = 0; c < o.cameras; ++c) {
    EXPECT_EQ(memory.camera(0, c).fx, loaded.camera(0, c).fx);
    EXPECT_LT(memory.camera(0, c).fx, rig[c].fx);  // barrel: a wider pinhole view
    Image a, b;
    ASSERT_TRUE(memory.LoadImage(0, c, &a).ok());
    ASSERT_TRUE(loaded.LoadImage(0, c, &b).ok());
    EXPECT_EQ(a.pixels, b.pixels) << "camera " << c;
  }
}

}  // namespace
}  // namespace m4d
