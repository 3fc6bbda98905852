// Noise-adaptive depth denoising (depth_denoise.hpp): the noise estimate on surfaces of known noise,
// the bilateral filter's effect (noise down, steps and holes kept), and the detector's use of both.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "broccoli_sim_frames.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/pipeline/broccoli/depth_denoise.hpp"
#include "cropsight/pipeline/broccoli/detector.hpp"
#include "cropsight/pipeline/broccoli/pipeline.hpp"
#include "cropsight/pipeline/broccoli/training.hpp"
#include "cropsight/pipeline/broccoli/truth.hpp"
#include "testing/testing.hpp"

// Inside the namespace rather than `using namespace`: this file shares unity batches with others.
namespace cropsight::pipeline::broccoli {

namespace {
constexpr int kW = 200, kH = 150;
// A slanted plane from 0.7 to 0.9 m across the image, with Gaussian noise `sigma` (m), in units of
// `scale` m; a 5 cm step (nearer) on the right third when `step`; a hole of zeros in the middle.
std::vector<std::uint16_t> plane(float sigma, float scale, bool step, unsigned seed = 3) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> noise(0.0f, sigma);
  std::vector<std::uint16_t> d(std::size_t(kW) * kH);
  for (int v = 0; v < kH; ++v)
    for (int u = 0; u < kW; ++u) {
      float z = 0.7f + 0.2f * float(u) / float(kW) + (step && u >= 2 * kW / 3 ? -0.05f : 0.0f);
      z += sigma > 0.0f ? noise(rng) : 0.0f;
      const bool hole = std::abs(u - kW / 3) < 4 && std::abs(v - kH / 2) < 4;
      d[std::size_t(v) * kW + u] = hole ? 0 : std::uint16_t(std::lround(z / scale));
    }
  return d;
}
// Std (m) of `d` minus the noiseless plane over the pixels at least 4 px from the step and the hole.
double residual(const std::vector<std::uint16_t>& d, const std::vector<std::uint16_t>& clean, float scale) {
  double s2 = 0.0;
  long n = 0;
  for (int v = 0; v < kH; ++v)
    for (int u = 0; u < kW; ++u) {
      if (std::abs(u - 2 * kW / 3) < 4 || (std::abs(u - kW / 3) < 8 && std::abs(v - kH / 2) < 8)) continue;
      const std::size_t i = std::size_t(v) * kW + u;
      const double e = (double(d[i]) - double(clean[i])) * scale;
      s2 += e * e, ++n;
    }
  return std::sqrt(s2 / double(n));
}
}  // namespace

TEST(DepthDenoise, NoiseEstimateFollowsTheNoise) {
  std::vector<std::uint32_t> bins;
  for (float sigma : {0.002f, 0.006f, 0.012f}) {
    const auto d = plane(sigma, 0.0001f, false);  // 0.1 mm units: no quantisation to speak of
    const float est = estimate_depth_noise(d, kW, kH, 0.0001f, 0.5f, 1.0f, bins);
    EXPECT_NEAR(est, sigma, 0.15f * sigma) << "sigma " << sigma;
  }
  // In 1 mm units (Kinect v2's), a 6 mm noise is still told from a 2 mm one.
  const float est1 = estimate_depth_noise(plane(0.006f, 0.001f, false), kW, kH, 0.001f, 0.5f, 1.0f, bins);
  EXPECT_NEAR(est1, 0.006f, 0.0012f);
  EXPECT_LT(estimate_depth_noise(plane(0.002f, 0.001f, false), kW, kH, 0.001f, 0.5f, 1.0f, bins), 0.003f);
  // Only triples inside the window count: none at all gives NaN.
  EXPECT_TRUE(std::isnan(estimate_depth_noise(plane(0.006f, 0.001f, false), kW, kH, 0.001f, 1.2f, 2.0f, bins)));
  // A window beyond the 16-bit range (tiny scale) is clamped, not overflowed: nothing lies in it.
  EXPECT_TRUE(std::isnan(estimate_depth_noise(plane(0.006f, 0.001f, false), kW, kH, 1e-9f, 0.5f, 1.0f, bins)));
  EXPECT_THROW(estimate_depth_noise(plane(0.0f, 0.001f, false), kW, kH + 1, 0.001f, 0.5f, 1.0f, bins), Error);
}

TEST(DepthDenoise, BilateralRemovesNoiseAndKeepsStepsAndHoles) {
  const float sigma = 0.008f, scale = 0.0001f;
  const auto clean = plane(0.0f, scale, true), noisy = plane(sigma, scale, true);
  std::vector<std::uint16_t> out;
  bilateral_depth(noisy, kW, kH, scale, 2.5f * sigma, 5, 2.0f, out);
  ASSERT_EQ(out.size(), noisy.size());
  EXPECT_GT(residual(noisy, clean, scale), 0.9 * sigma);
  EXPECT_LT(residual(out, clean, scale), 0.45 * sigma) << "a 5x5 window averages the noise down";
  // The 5 cm step (6 sigmas) stays a step: the mean depth just either side of it keeps its side.
  double left = 0.0, right = 0.0;
  for (int v = 0; v < kH; ++v) {
    left += double(out[std::size_t(v) * kW + 2 * kW / 3 - 1]) * scale;
    right += double(out[std::size_t(v) * kW + 2 * kW / 3]) * scale;
  }
  EXPECT_GT((left - right) / kH, 0.045);
  // Holes stay holes, and their 0 m pulls no neighbour towards the camera.
  for (int v = 0; v < kH; ++v)
    for (int u = 0; u < kW; ++u) {
      const std::size_t i = std::size_t(v) * kW + u;
      EXPECT_EQ(out[i] == 0, noisy[i] == 0);
      if (noisy[i]) {
        EXPECT_GT(double(out[i]) * scale, 0.6);
      }
    }
  EXPECT_THROW(bilateral_depth(noisy, kW, kH, scale, 0.0f, 5, 2.0f, out), Error);
  EXPECT_THROW(bilateral_depth(noisy, kW + 1, kH, scale, 0.02f, 5, 2.0f, out), Error);
}

// The shipped general model denoises only noisy frames: ToF in sun (5 mm noise at 1 m) makes OES
// shatter the heads without it; a clean uk frame is left as it is.
TEST(DepthDenoise, DetectorFiltersOnlyNoisyFramesAndFindsTheHeadsThere) {
  const auto model_path = cropsight::testing::source_dir() / "models" / "broccoli-oes-general.json";
  const auto model = pipeline::broccoli::load_model(model_path.string());
  const pipeline::broccoli::DetectorConfig on =
      pipeline::broccoli::config_for_model(*model, {}, model_path.string()).detector;
  ASSERT_GT(on.denoise.above, 0.0f) << "the shipped general model denoises";
  pipeline::broccoli::DetectorConfig off = on;
  off.denoise.above = 0.0f;
  pipeline::broccoli::Detector a(off), b(on);
  a.set_model(model);
  b.set_model(model);

  const auto clean = testdata::simulate(testdata::sim_preset("uk"), 31, 1);
  b.process(clean[0]);
  EXPECT_LT(b.noise_sigma(), on.denoise.above);
  EXPECT_FALSE(b.denoised());

  sim::BroccoliSimConfig sun = testdata::sim_preset("uk");
  sun.sensor.sunlight = true;
  sun.sensor.noise_at_1m_m = 0.005;
  const auto frames = testdata::simulate(sun, 31, 3);
  int found_on = 0, found_off = 0, truths = 0;
  for (const auto& f : frames) {
    const auto ca = a.process(f);
    const auto cb = b.process(f);
    EXPECT_GT(b.noise_sigma(), on.denoise.above);
    EXPECT_TRUE(b.denoised());
    EXPECT_FALSE(a.denoised());
    // Truth heads with >= 300 points that some head detection covers with IoU >= 0.5.
    std::vector<TruthInstance> truth;
    truth_instances(b.cloud(), 1, truth);
    for (const auto& t : truth) {
      if (t.indices.size() < 300) continue;
      ++truths;
      auto found = [&](std::span<const pipeline::broccoli::Candidate> cands, const OrganizedCloud& cloud) {
        for (const auto& c : cands) {
          if (!c.head) continue;
          long inter = 0;
          for (int i : c.segment.indices) inter += cloud.labels[std::size_t(i)] == t.id;
          if (double(inter) / double(long(c.segment.indices.size()) + long(t.indices.size()) - inter) >= 0.5)
            return true;
        }
        return false;
      };
      found_on += found(cb, b.cloud());
      found_off += found(ca, a.cloud());
    }
  }
  ASSERT_GT(truths, 0);
  EXPECT_GE(found_on, truths - 2) << "found " << found_on << " of " << truths;
  EXPECT_LT(found_off, found_on) << "without denoising " << found_off;
}

// denoise.in_training false: the training samples come from the raw frames (the same samples as
// with denoising off), while the stored config keeps the setting for detection.
TEST(DepthDenoise, InTrainingFalseBuildsSamplesFromRawFrames) {
  sim::BroccoliSimConfig sun = testdata::sim_preset("uk");
  sun.sensor.sunlight = true;
  sun.sensor.noise_at_1m_m = 0.005;
  const auto frames = testdata::simulate(sun, 32, 1);
  pipeline::broccoli::DetectorConfig raw;
  const auto preset_path = cropsight::testing::source_dir() / "configs" / "broccoli-oes-uk.yaml";
  apply_config(raw, io::load_config_map(preset_path), preset_path.string());
  pipeline::broccoli::DetectorConfig at_detection = raw, always = raw;
  at_detection.denoise.above = always.denoise.above = 0.006f;
  at_detection.denoise.in_training = false;
  pipeline::broccoli::DatasetBuilder r(raw, {}), d(at_detection, {}), w(always, {});
  r.add_frame(frames[0]);
  d.add_frame(frames[0]);
  w.add_frame(frames[0]);
  EXPECT_EQ(d.dataset().size(), r.dataset().size());
  EXPECT_EQ(d.dataset().positives(), r.dataset().positives());
  EXPECT_NE(w.dataset().size(), r.dataset().size()) << "denoised frames give other clusters";
  EXPECT_EQ(config_map(at_detection, {}).at("denoise.above"), config_map(always, {}).at("denoise.above"));
}

}  // namespace cropsight::pipeline::broccoli
