// The L1 loss and its gradient (metrics/l1_loss.h).

#include <gtest/gtest.h>

#include "encoder/src/metrics/l1_loss.h"

namespace m4d {
namespace {

TEST(L1LossTest, MeanAbsoluteErrorAndSignGradient) {
  Image rendered(5, 3, 3), target(5, 3, 3);
  const size_t n = rendered.pixels.size();
  for (size_t i = 0; i < n; ++i) {
    rendered.pixels[i] = 0.5f;
    // Above, below and equal in turn: |d| = 0.25, 0.5, 0.
    target.pixels[i] = i % 3 == 0 ? 0.25f : (i % 3 == 1 ? 1.0f : 0.5f);
  }
  double loss = 0;
  Image grad(1, 1, 1, 7.0f);  // stale shape and content must be replaced
  ASSERT_TRUE(L1Loss(rendered, target, &loss, &grad).ok());
  EXPECT_NEAR(loss, 0.25, 1e-12);  // (0.25 + 0.5 + 0) / 3
  ASSERT_EQ(grad.width, 5);
  ASSERT_EQ(grad.height, 3);
  ASSERT_EQ(grad.channels, 3);
  for (size_t i = 0; i < n; ++i) {
    const float expected = i % 3 == 0 ? 1.0f / n : (i % 3 == 1 ? -1.0f / n : 0.0f);
    EXPECT_FLOAT_EQ(grad.pixels[i], expected) << i;
  }
  double loss_only = 0;
  ASSERT_TRUE(L1Loss(rendered, target, &loss_only).ok());
  EXPECT_EQ(loss_only, loss);
}

TEST(L1LossTest, RejectsMismatchedShapes) {
  double loss = 0;
  EXPECT_EQ(L1Loss(Image(4, 4, 3), Image(4, 4, 4), &loss).code(), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(L1Loss(Image(4, 4, 3), Image(3, 4, 3), &loss).code(), M4D_ERR_INVALID_ARG);
}

}  // namespace
}  // namespace m4d
