#include "encoder/src/dataset/capture_check.h"

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "encoder/src/dataset/image_file_source.h"
#include "encoder/src/image_io/file_bytes.h"
#include "encoder/src/image_io/png_io.h"
#include "tests/capture_input/dataset_test_util.h"

namespace m4d {
namespace {

using testing::Rig;
using testing::TempDir;
using testing::ViewImage;

constexpr int kWidth = 24, kHeight = 16;

// Two cameras over three frames from PNG files; the caller spoils some of them.
Capture FileCapture(const TempDir& dir) {
  Capture capture;
  capture.layout = "test";
  capture.camera_names = {"left", "right"};
  capture.frame_count = 3;
  capture.cameras.assign(3, Rig(2, kWidth, kHeight, false));
  std::vector<std::vector<std::string>> paths(3);
  for (int f = 0; f < 3; ++f) {
    for (int c = 0; c < 2; ++c) {
      paths[f].push_back(dir.path() + "/" + std::to_string(c) + "_" + std::to_string(f) + ".png");
      EXPECT_TRUE(WritePng(paths[f].back(), ViewImage(kWidth, kHeight, f, c)).ok());
    }
  }
  capture.frames = std::make_unique<ImageFileSource>(paths, capture.cameras);
  return capture;
}

TEST(CaptureCheckTest, PassesAGoodCapture) {
  TempDir dir;
  const Capture capture = FileCapture(dir);
  int calls = 0;
  EXPECT_TRUE(CheckCaptureViews(capture, 0, 0, [&](int done, int total) {
                EXPECT_EQ(total, 3);
                EXPECT_EQ(done, ++calls);
              }).ok());
  EXPECT_EQ(calls, 3);
}

TEST(CaptureCheckTest, ListsEveryBadViewInOneError) {
  TempDir dir;
  const Capture capture = FileCapture(dir);
  std::filesystem::remove(dir.path() + "/1_0.png");  // missing
  ASSERT_TRUE(WritePng(dir.path() + "/0_1.png", ViewImage(kWidth / 2, kHeight, 1, 0)).ok());
  ASSERT_TRUE(WriteFileBytes(dir.path() + "/1_2.png", {0x89, 'P', 'N', 'G', 1, 2}).ok());  // cut
  const Status status = CheckCaptureViews(capture, 0, 0);
  ASSERT_EQ(status.code(), M4D_ERR_INVALID_ARG);
  const std::string& m = status.message();
  EXPECT_NE(m.find("3 of 6 views"), std::string::npos) << m;
  EXPECT_NE(m.find("camera right, frame 0"), std::string::npos) << m;
  EXPECT_NE(m.find("camera left, frame 1"), std::string::npos) << m;
  EXPECT_NE(m.find("expected 24x16"), std::string::npos) << m;
  EXPECT_NE(m.find("camera right, frame 2"), std::string::npos) << m;
  // Only the frames asked for are checked.
  const Status second = CheckCaptureViews(capture, 1, 1);
  EXPECT_NE(second.message().find("1 of 2 views"), std::string::npos) << second.message();
  EXPECT_EQ(CheckCaptureViews(capture, 3, 1).code(), M4D_ERR_INVALID_ARG);
}

}  // namespace
}  // namespace m4d
