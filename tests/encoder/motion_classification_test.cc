// Static / dynamic classification of a keyframe (paper 3.2, 4.1).

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "encoder/src/decoupling/lookahead_measures.h"
#include "encoder/src/decoupling/motion_classification.h"

namespace m4d {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

TEST(MotionClassificationTest, ThresholdsThenErrorRefinement) {
  LookaheadMeasures m;
  m.displacement = {0.0f, 5.0f, 0.0f, 5.0f, 5.0f};
  m.scale_change = {0.0f, 0.0f, 2.0f, 0.0f, 0.0f};
  m.error = {0.0f, 0.01f, 0.01f, 0.3f, kNaN};
  DecouplingThresholds t;
  std::vector<uint8_t> c = ClassifyDynamic(m, t, {});
  EXPECT_EQ(c, (std::vector<uint8_t>{0, 1, 1, 0, 1}));
}

TEST(MotionClassificationTest, MajorityVoteRemovesIsolatedPointsAndFillsHoles) {
  // Two clusters of 6: 0..5 dynamic except 2; 6..11 static except 9. Neighbours: the cluster.
  LookaheadMeasures m;
  for (int i = 0; i < 12; ++i) {
    bool dynamic = (i < 6 && i != 2) || i == 9;
    m.displacement.push_back(dynamic ? 10.0f : 0.0f);
    m.scale_change.push_back(0.0f);
    m.error.push_back(0.0f);
  }
  DecouplingThresholds t;
  std::vector<uint32_t> neighbours;
  for (uint32_t i = 0; i < 12; ++i) {
    uint32_t base = i < 6 ? 0 : 6;
    for (uint32_t j = base; j < base + 6; ++j) {
      if (j != i) neighbours.push_back(j);
    }
  }
  std::vector<uint8_t> c = ClassifyDynamic(m, t, neighbours);
  for (int i = 0; i < 12; ++i) EXPECT_EQ(c[i], i < 6 ? 1 : 0) << i;
}

TEST(LookaheadMeasuresTest, DisplacementScaleChangeAndError) {
  Camera camera;
  camera.width = 200;
  camera.height = 100;
  camera.fx = camera.fy = 100.0f;
  camera.cx = 100.0f;
  camera.cy = 50.0f;
  // Gaussian 0 at depth 2 moves 0.1 sideways: 5 px, delta = 2.5. Gaussian 1 behind the
  // camera: never seen, delta 0.
  std::vector<float> before = {0, 0, 2, 0, 0, -1};
  std::vector<float> after = {0.1f, 0, 2, 5, 0, -1};
  std::vector<float> ls_before = {0, 0, 0, -1, -1, -1};
  std::vector<float> ls_after = {0.3f, 0, 0.4f, -1, -1, -1};
  std::vector<float> blend = {2.0f, 0.0f}, error = {0.1f, 0.0f};
  LookaheadInput in;
  in.count = 2;
  in.positions_before = before.data();
  in.positions_after = after.data();
  in.log_scales_before = ls_before.data();
  in.log_scales_after = ls_after.data();
  in.blend_weight = blend.data();
  in.error_weight = error.data();
  LookaheadMeasures m = MeasureLookahead({camera, camera}, in);
  EXPECT_NEAR(m.displacement[0], 2.5f, 1e-5f);
  EXPECT_EQ(m.displacement[1], 0.0f);
  EXPECT_NEAR(m.scale_change[0], 0.5f, 1e-6f);
  EXPECT_EQ(m.scale_change[1], 0.0f);
  EXPECT_NEAR(m.error[0], 0.05f, 1e-7f);
  EXPECT_TRUE(std::isnan(m.error[1]));
}

}  // namespace
}  // namespace m4d
