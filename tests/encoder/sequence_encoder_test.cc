// The reference encoder over a short sequence, closed loop: every frame's reconstruction hash
// equals the SDK's decode of the written stream; GOP policies and ablations.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "encoder/src/capture/capture.h"
#include "encoder/src/pipeline/sequence_encoder.h"
#include "encoder/src/raster/splat_renderer.h"
#include "encoder/src/train/keyframe_stage.h"
#include "encoder/src/train/keyframe_trainer.h"
#include "m4d/m4d.h"
#include "sdk/src/decode/decoder.h"
#include "tests/encoder/stream_test_util.h"
#include "tests/raster/splat_test_scenes.h"

namespace m4d {
namespace {

constexpr int kWidth = 48, kHeight = 36, kCameras = 6, kFrames = 5;

class MemoryFrames : public FrameSource {
 public:
  explicit MemoryFrames(std::vector<std::vector<Image>> images) : images_(std::move(images)) {}
  Status Load(int frame, int camera, Image* rgb) override {
    *rgb = images_[frame][camera];
    return Status::Ok();
  }

 private:
  std::vector<std::vector<Image>> images_;
};

// A background and a blob moving right by `speed` per frame; a second blob appears at frame 3.
Capture MakeCapture(float speed = 0.06f) {
  test::SceneOptions bg;
  bg.count = 250;
  bg.sh_degree = 0;
  bg.extent = 1.5f;
  bg.logit_lo = 1.0f;
  bg.logit_hi = 3.0f;
  GaussianSet background = test::RandomGaussians(bg, 61);
  for (size_t i = 0; i < background.size(); ++i) background.positions[3 * i + 2] += 2.0f;
  test::SceneOptions b;
  b.count = 80;
  b.sh_degree = 0;
  b.extent = 0.3f;
  b.logit_lo = 2.0f;
  b.logit_hi = 4.0f;
  b.sh_dc = 1.5f;
  GaussianSet blob = test::RandomGaussians(b, 62);
  GaussianSet newcomer = test::RandomGaussians(b, 63);
  for (size_t i = 0; i < newcomer.size(); ++i) newcomer.positions[3 * i + 1] -= 0.6f;

  Capture capture;
  capture.layout = "memory";
  capture.frame_count = kFrames;
  capture.test_cameras = {0};
  std::vector<std::vector<Image>> images(kFrames);
  std::vector<Camera> rig;
  const float target[3] = {0, 0, 0};
  for (int c = 0; c < kCameras; ++c) {
    const float angle = 1.0f * (static_cast<float>((c + 2) % kCameras) / (kCameras - 1) - 0.5f);
    const float eye[3] = {4.0f * std::sin(angle), -0.4f + 0.4f * (c % 3), -4.0f * std::cos(angle)};
    rig.push_back(test::LookAtCamera(kWidth, kHeight, 55.0f, 0, 0, eye, target));
    capture.camera_names.push_back("cam" + std::to_string(c));
  }
  capture.cameras.assign(kFrames, rig);
  RenderSettings settings;
  RenderContext context;
  for (int f = 0; f < kFrames; ++f) {
    GaussianSet moved = blob;
    for (size_t i = 0; i < moved.size(); ++i) moved.positions[3 * i] += speed * f;
    std::vector<M4dGaussians> layers = {GaussianView(background), GaussianView(moved)};
    if (f >= 3) layers.push_back(GaussianView(newcomer));
    for (int c = 0; c < kCameras; ++c) {
      EXPECT_TRUE(RenderForward(rig[c], layers.data(), static_cast<int>(layers.size()), settings,
                                nullptr, &context)
                      .ok());
      Image image(kWidth, kHeight, 3);
      for (size_t i = 0; i < image.pixels.size(); ++i) {
        image.pixels[i] = std::clamp(context.color[i], 0.0f, 1.0f);
      }
      images[f].push_back(std::move(image));
    }
  }
  // Initial points: the truth's positions of frame 0, jittered.
  for (const GaussianSet* set : {&background, &blob}) {
    for (size_t i = 0; i < set->size(); ++i) {
      for (int a = 0; a < 3; ++a) {
        capture.initial_points.positions.push_back(set->positions[3 * i + a] +
                                                   0.02f * std::sin(float(7 * i + a)));
        capture.initial_points.colors.push_back(0.5f);
      }
    }
  }
  capture.frames = std::make_unique<MemoryFrames>(std::move(images));
  return capture;
}

EncoderOptions SmallOptions() {
  EncoderOptions o;
  o.sh_degree = 0;
  o.grid.num_levels = 2;
  o.grid.channels[0] = 4;
  o.grid.channels[1] = 2;
  o.grid.resolution[0] = 8;
  o.grid.resolution[1] = 16;
  o.mlp.hidden_width = 16;
  o.keyframe.iterations = 400;
  o.keyframe.learning_rates.position.max_steps = 400;
  o.keyframe.densify_from = 100;
  o.keyframe.densify_until = 250;
  o.keyframe.densify_interval = 50;
  o.keyframe.opacity_reset_interval = 0;
  o.keyframe.sh_degree_interval = 0;
  o.retrain_iterations = 150;
  o.lookahead_frames = 2;
  o.decoupling.fine_tune_iterations = 100;
  o.decoupling.thresholds.displacement = 0.2f;
  o.decoupling.thresholds.scale_change = 0.3f;
  o.motion.iterations = 40;
  o.first_motion_iterations = 80;
  o.compensation.iterations = 30;
  o.context.threads = 2;
  return o;
}

std::vector<std::string> DecodedHashes(const std::vector<uint8_t>& stream) {
  return testing::DecodeWith(testing::DefaultSettings(), testing::SplitPackets(stream)).hashes;
}

TEST(SequenceEncoderTest, ClosedLoopHashesMatchTheSdkDecode) {
  Capture capture = MakeCapture();
  SequenceEncoder encoder(capture, SmallOptions());
  SequenceReport report;
  int trained = 0;
  EncoderCallbacks callbacks;
  callbacks.training = [&](const std::string&, int, const TrainingProgress&) { ++trained; };
  ASSERT_TRUE(encoder.Encode(callbacks, &report).ok());
  EXPECT_GT(trained, 0);
  ASSERT_EQ(report.frames.size(), static_cast<size_t>(kFrames));
  EXPECT_EQ(report.stream_bytes, encoder.stream().size());
  const std::vector<std::string> decoded = DecodedHashes(encoder.stream());
  ASSERT_EQ(decoded.size(), static_cast<size_t>(kFrames));
  size_t bytes = 0;
  for (int f = 0; f < kFrames; ++f) {
    const FrameReport& r = report.frames[f];
    EXPECT_EQ(r.frame_index, static_cast<uint32_t>(f));
    EXPECT_EQ(r.hash, decoded[f]) << "frame " << f;
    EXPECT_GT(r.psnr, 18.0) << "frame " << f;
    bytes += r.bytes.total();
  }
  EXPECT_TRUE(report.frames[0].keyframe);
  EXPECT_GT(report.frames[0].dynamic_count, 0u);
  EXPECT_GT(report.frames[0].static_count, 0u);
  EXPECT_EQ(bytes, report.stream_bytes);  // every byte is in some frame's count
}

TEST(SequenceEncoderTest, FixedGopAndAblations) {
  Capture capture = MakeCapture();
  EncoderOptions o = SmallOptions();
  o.gop.adaptive = false;
  o.gop.fixed_length = 2;
  o.ablation.compensation = false;
  o.ablation.decoupling = false;
  SequenceEncoder encoder(capture, o);
  SequenceReport report;
  ASSERT_TRUE(encoder.Encode(EncoderCallbacks(), &report).ok());
  ASSERT_EQ(report.frames.size(), static_cast<size_t>(kFrames));
  const std::vector<std::string> decoded = DecodedHashes(encoder.stream());
  ASSERT_EQ(decoded.size(), static_cast<size_t>(kFrames));
  for (int f = 0; f < kFrames; ++f) {
    const FrameReport& r = report.frames[f];
    EXPECT_EQ(r.keyframe, f % 2 == 0) << f;
    EXPECT_EQ(r.hash, decoded[f]) << f;
    EXPECT_EQ(r.added, 0u);
    if (r.keyframe) {
      EXPECT_EQ(r.static_count, 0u);  // no decoupling: all dynamic
    }
  }
}

// Within the random-access interval a new GOP keeps the static layer bit for bit (a dependent
// keyframe re-sends the dynamic layer and adds what grew in the background); at interval 0
// every GOP re-sends both.
TEST(SequenceEncoderTest, DependentGopsKeepTheStaticLayer) {
  Capture capture = MakeCapture();
  for (double seconds : {10.0, 0.0}) {
    EncoderOptions o = SmallOptions();
    o.gop.adaptive = false;
    o.gop.fixed_length = 2;
    o.gop.random_access_seconds = seconds;
    SequenceEncoder encoder(capture, o);
    SequenceReport report;
    ASSERT_TRUE(encoder.Encode(EncoderCallbacks(), &report).ok());
    ASSERT_EQ(report.frames.size(), static_cast<size_t>(kFrames));
    Decoder decoder{DecoderOptions()};
    std::vector<DecodedFrame> frames;
    for (const testing::Packet& p : testing::SplitPackets(encoder.stream())) {
      ASSERT_TRUE(decoder.SendPacket(p.data(), p.size()).ok());
      if (decoder.HasFrame()) frames.push_back(decoder.TakeFrame());
    }
    ASSERT_EQ(frames.size(), static_cast<size_t>(kFrames));
    const GaussianSet& first = *frames[0].static_layer;
    for (int f = 2; f < kFrames; f += 2) {
      const FrameReport& r = report.frames[f];
      ASSERT_TRUE(r.keyframe) << f;
      EXPECT_EQ(r.random_access, seconds == 0.0) << f;
      EXPECT_EQ(r.bytes.by_type[M4D_PACKET_KEYFRAME_STATIC] > 0, seconds == 0.0) << f;
      EXPECT_EQ(r.bytes.by_type[M4D_PACKET_SEQUENCE_HEADER] > 0, seconds == 0.0) << f;
      if (seconds == 0.0) continue;
      // The kept set comes first, unchanged; a STATIC_UPDATE only appends.
      const GaussianSet& kept = *frames[f].static_layer;
      ASSERT_GE(kept.size(), first.size()) << f;
      EXPECT_TRUE(
          std::equal(first.positions.begin(), first.positions.end(), kept.positions.begin()));
      EXPECT_TRUE(std::equal(first.sh.begin(), first.sh.end(), kept.sh.begin()));
      EXPECT_EQ(kept.size() > frames[f - 1].static_layer->size(),
                r.bytes.by_type[M4D_PACKET_STATIC_UPDATE] > 0)
          << f;
    }
  }
}

// The blob appearing at frame 3 is far from the dynamic blob, so compensation adds little and
// r_t stays small; the quality guard of the adaptive GOP starts a new GOP there instead.
TEST(SequenceEncoderTest, ContentAppearingAwayFromMotionStartsAGop) {
  Capture capture = MakeCapture();
  auto encode = [&](float max_psnr_drop, SequenceReport* report) {
    EncoderOptions o = SmallOptions();
    o.gop.threshold = 1e9f;  // r_t never decides
    o.gop.max_psnr_drop = max_psnr_drop;
    SequenceEncoder encoder(capture, o);
    ASSERT_TRUE(encoder.Encode(EncoderCallbacks(), report).ok());
    ASSERT_EQ(report->frames.size(), static_cast<size_t>(kFrames));
    const std::vector<std::string> decoded = DecodedHashes(encoder.stream());
    ASSERT_EQ(decoded.size(), static_cast<size_t>(kFrames));
    for (int f = 0; f < kFrames; ++f) EXPECT_EQ(report->frames[f].hash, decoded[f]) << f;
  };
  SequenceReport guarded, unguarded;
  encode(2.0f, &guarded);
  encode(0.0f, &unguarded);
  for (int f = 0; f < kFrames; ++f) {
    EXPECT_EQ(guarded.frames[f].keyframe, f == 0 || f == 3) << f;
    EXPECT_EQ(unguarded.frames[f].keyframe, f == 0) << f;
  }
  // Without a new GOP the newcomer stays missing over the training views. The single held-out
  // camera is not asserted: after this short schedule its sign changes between compilers
  // (docs/results/2026-11-30-test-comment-measurements.md).
  EXPECT_LT(unguarded.frames[3].training_psnr, unguarded.frames[0].training_psnr - 2.0);
  EXPECT_GT(guarded.frames[3].training_psnr, unguarded.frames[3].training_psnr + 2.0);
}

// A GOP restarted by the quality guard (the newcomer at frame 3) is retrained from its
// frame's prediction, motion applied, with the newcomer seeded where the prediction does not
// explain the views, so even a short retraining (40 iterations) beats the prediction it
// replaces, and beats a retraining from the last coded frame without seeds (the encoder
// before; docs/results/2026-11-30-test-comment-measurements.md).
TEST(SequenceEncoderTest, ARestartedGopStartsFromItsFramesPrediction) {
  Capture capture = MakeCapture(0.12f);
  EncoderOptions o = SmallOptions();
  o.retrain_iterations = 40;
  o.gop.threshold = 1e9f;  // r_t never decides
  o.gop.max_psnr_drop = 2.0f;
  SequenceEncoder encoder(capture, o);
  SequenceReport report;
  ASSERT_TRUE(encoder.Encode(EncoderCallbacks(), &report).ok());
  ASSERT_EQ(report.frames.size(), static_cast<size_t>(kFrames));
  EXPECT_EQ(report.frames[0].prediction_psnr, 0.0);
  int restarted = 0;
  for (int f = 1; f < kFrames; ++f) {
    const FrameReport& r = report.frames[f];
    if (!r.keyframe) continue;
    ++restarted;
    ASSERT_GT(r.prediction_psnr, 10.0) << f;
    EXPECT_GT(r.seeded, 0u) << f;
    EXPECT_GT(r.training_psnr, r.prediction_psnr + 1.0) << f;
  }
  EXPECT_GE(restarted, 1);
}

// Compensation is a mode decision: coded only where it raises the training views' PSNR by
// compensation_min_gain. Always coded, it adds Gaussians; never coded, nothing is added or
// removed, its measured gain (at the probe) is still reported, and the closed loop holds
// either way.
TEST(SequenceEncoderTest, CompensationIsCodedOnlyWhereItGains) {
  constexpr int kCodedFrames = 3;
  Capture capture = MakeCapture();
  auto encode = [&](double min_gain, SequenceReport* report) {
    EncoderOptions o = SmallOptions();
    o.gop.adaptive = false;  // the same frames are inter frames in both runs
    o.frame_count = kCodedFrames;
    o.compensation_min_gain = min_gain;
    SequenceEncoder encoder(capture, o);
    ASSERT_TRUE(encoder.Encode(EncoderCallbacks(), report).ok());
    ASSERT_EQ(report->frames.size(), static_cast<size_t>(kCodedFrames));
    const std::vector<std::string> decoded = DecodedHashes(encoder.stream());
    ASSERT_EQ(decoded.size(), static_cast<size_t>(kCodedFrames));
    for (int f = 0; f < kCodedFrames; ++f) EXPECT_EQ(report->frames[f].hash, decoded[f]) << f;
  };
  SequenceReport always, never;
  encode(-1e9, &always);
  encode(1e9, &never);
  size_t added = 0;
  for (int f = 1; f < kCodedFrames; ++f) {
    added += always.frames[f].added;
    EXPECT_EQ(never.frames[f].added, 0u) << f;
    EXPECT_EQ(never.frames[f].removed, 0u) << f;
  }
  EXPECT_GT(added, 0u);
  // The first inter frame starts from the same keyframe: its gain was measured, not coded,
  // and never reaching 1e9 dB, its training ended at the probe.
  EXPECT_NE(never.frames[1].compensation_gain, 0.0);
  EXPECT_TRUE(never.frames[1].compensation_abandoned);
  EXPECT_FALSE(always.frames[1].compensation_abandoned);
  EXPECT_NEAR(never.frames[1].training_psnr,
              always.frames[1].training_psnr - always.frames[1].compensation_gain, 0.3);
}

// Motion is a mode decision: coded where it raises the training views' PSNR, else the frame
// shows the previous one again (the grid's box holds no Gaussian).
TEST(SequenceEncoderTest, MotionIsCodedOnlyWhereItGains) {
  constexpr int kCodedFrames = 3;
  Capture capture = MakeCapture();
  for (double min_gain : {0.0, 1e9}) {
    EncoderOptions o = SmallOptions();
    o.motion_min_gain = min_gain;
    o.gop.adaptive = false;
    o.frame_count = kCodedFrames;
    o.compensation_min_gain = 1e9;  // never: frames differ by motion alone
    o.ablation.decoupling = false;  // every Gaussian may move
    SequenceEncoder encoder(capture, o);
    SequenceReport report;
    ASSERT_TRUE(encoder.Encode(EncoderCallbacks(), &report).ok());
    const std::vector<std::string> decoded = DecodedHashes(encoder.stream());
    ASSERT_EQ(decoded.size(), static_cast<size_t>(kCodedFrames));
    for (int f = 1; f < kCodedFrames; ++f) {
      const FrameReport& frame = report.frames[f];
      EXPECT_EQ(frame.hash, decoded[f]) << f;
      EXPECT_EQ(frame.motion_skipped, !(frame.motion_gain > min_gain)) << f;
      EXPECT_NE(frame.motion_gain, 0.0) << f;  // measured either way
      if (frame.motion_skipped) {
        EXPECT_EQ(decoded[f], decoded[f - 1]) << f;
      }
    }
    // The blob moves 0.06 a frame: motion pays; forced off, every frame repeats the keyframe.
    EXPECT_EQ(report.frames[1].motion_skipped, min_gain > 0) << report.frames[1].motion_gain;
    if (min_gain > 0) {
      EXPECT_LT(report.frames[2].training_psnr, report.frames[0].training_psnr - 0.5);
    }
  }
}

// The colour change trained with the motion is a mode decision of its own: coded (an
// APPEARANCE packet) exactly when its measured gain passes the bound, which its bytes raise.
TEST(SequenceEncoderTest, AppearanceIsCodedOnlyWhereItGains) {
  constexpr int kCodedFrames = 3;
  Capture capture = MakeCapture();
  const std::pair<double, double> bounds[] = {{-1.0, 0.5}, {1e9, 0.0}, {0.0, 1e9}};
  for (const auto& [min_gain, per_doubling] : bounds) {
    const bool coded = min_gain < 0;
    EncoderOptions o = SmallOptions();
    o.appearance_min_gain = min_gain;
    o.appearance_gain_per_doubling = per_doubling;
    o.appearance_min_views = 1;           // the capture has 5 training views
    o.motion.appearance_check_every = 2;  // views 1 and 3 judge it, the others train it
    o.gop.adaptive = false;
    o.frame_count = kCodedFrames;
    o.ablation.decoupling = false;
    SequenceEncoder encoder(capture, o);
    SequenceReport report;
    ASSERT_TRUE(encoder.Encode(EncoderCallbacks(), &report).ok());
    const std::vector<std::string> decoded = DecodedHashes(encoder.stream());
    ASSERT_EQ(decoded.size(), static_cast<size_t>(kCodedFrames));
    for (int f = 1; f < kCodedFrames; ++f) {
      const FrameReport& frame = report.frames[f];
      EXPECT_EQ(frame.hash, decoded[f]) << f;
      EXPECT_NE(frame.appearance_gain, 0.0) << f;  // measured either way
      EXPECT_EQ(frame.appearance_skipped, !coded) << f;
      EXPECT_EQ(frame.bytes.by_type[M4D_PACKET_APPEARANCE] > 0, !frame.appearance_skipped) << f;
    }
  }
  // With fewer training views than the default bound none is trained.
  EncoderOptions o = SmallOptions();
  o.gop.adaptive = false;
  o.frame_count = kCodedFrames;
  SequenceEncoder encoder(capture, o);
  SequenceReport report;
  ASSERT_TRUE(encoder.Encode(EncoderCallbacks(), &report).ok());
  for (int f = 1; f < kCodedFrames; ++f) {
    EXPECT_TRUE(report.frames[f].appearance_skipped) << f;
    EXPECT_EQ(report.frames[f].appearance_gain, 0.0) << f;
  }
}

// The per-frame baseline: every frame a static keyframe from its own training (here from the
// caller's source, as `m4d rd` shares one training per frame between rate points).
TEST(SequenceEncoderTest, IndependentFramesAreStaticKeyframesFromTheSource) {
  Capture capture = MakeCapture();
  EncoderOptions o = SmallOptions();
  o.independent_frames = true;
  o.frame_count = 3;
  SequenceEncoder encoder(capture, o);
  std::vector<int> asked;
  encoder.SetKeyframeSource([&](int frame, GaussianModel* model) {
    asked.push_back(frame);
    return TrainKeyframe(capture, frame, o.keyframe, nullptr, model);
  });
  SequenceReport report;
  ASSERT_TRUE(encoder.Encode(EncoderCallbacks(), &report).ok());
  EXPECT_EQ(asked, (std::vector<int>{0, 1, 2}));
  ASSERT_EQ(report.frames.size(), 3u);
  const std::vector<std::string> decoded = DecodedHashes(encoder.stream());
  ASSERT_EQ(decoded.size(), 3u);
  for (int f = 0; f < 3; ++f) {
    const FrameReport& r = report.frames[f];
    EXPECT_TRUE(r.keyframe) << f;
    EXPECT_EQ(r.hash, decoded[f]) << f;
    EXPECT_EQ(r.dynamic_count, 0u) << f;
    EXPECT_GT(r.static_count, 0u) << f;
    EXPECT_GT(r.psnr, 18.0) << f;  // each frame's own training follows the moving blob
  }
  EXPECT_NE(report.frames[1].hash, report.frames[2].hash);
  encoder.SetKeyframeSource(
      [](int, GaussianModel*) { return Status(M4D_ERR_UNSUPPORTED, "gone"); });
  EXPECT_EQ(encoder.Encode(EncoderCallbacks(), &report).code(), M4D_ERR_UNSUPPORTED);
}

TEST(SequenceEncoderTest, RejectsBadOptions) {
  Capture capture = MakeCapture();
  EncoderOptions o = SmallOptions();
  o.sh_degree = 4;
  SequenceEncoder encoder(capture, o);
  SequenceReport report;
  EXPECT_EQ(encoder.Encode(EncoderCallbacks(), &report).code(), M4D_ERR_INVALID_ARG);
  o = SmallOptions();
  o.first_frame = kFrames;
  SequenceEncoder late(capture, o);
  EXPECT_EQ(late.Encode(EncoderCallbacks(), &report).code(), M4D_ERR_INVALID_ARG);
  o = SmallOptions();
  o.compensation_min_gain = std::nan("");
  SequenceEncoder no_gain(capture, o);
  EXPECT_EQ(no_gain.Encode(EncoderCallbacks(), &report).code(), M4D_ERR_INVALID_ARG);
  for (double decay : {-0.1, 1.5, std::nan("")}) {
    o = SmallOptions();
    o.motion_rate_decay = decay;
    SequenceEncoder bad_decay(capture, o);
    EXPECT_EQ(bad_decay.Encode(EncoderCallbacks(), &report).code(), M4D_ERR_INVALID_ARG) << decay;
  }
}

}  // namespace
}  // namespace m4d
