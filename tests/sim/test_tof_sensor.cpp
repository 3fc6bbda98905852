// Sensor model and renderer on hand-made inputs: measured noise follows the model and grows with
// range; depth steps produce mixed (flying) pixels strictly between the two surfaces, unlabelled;
// the rasteriser's depth is the exact ray-plane intersection.
#include <gtest/gtest.h>

#include <cmath>

#include "cropsight/sim/renderer.hpp"
#include "cropsight/sim/tof_sensor.hpp"

using namespace cropsight;

namespace {
CameraIntrinsics small_camera() {
  CameraIntrinsics c = CameraIntrinsics::from_fov(64, 48, 70.6 * M_PI / 180, 60 * M_PI / 180);
  c.depth_scale = 0.001;
  return c;
}

sim::SampleBuffers plane(int w, int h, float z, float nir, std::uint16_t label) {
  sim::SampleBuffers s;
  s.reset(w, h);
  for (std::size_t i = 0; i < s.depth.size(); ++i) {
    s.depth[i] = z;
    s.nir[i] = nir;
    s.label[i] = label;
    s.color[i] = {100, 120, 90};
  }
  return s;
}

double measured_std(float z, const sim::SimSensorConfig& cfg) {
  const CameraIntrinsics cam = small_camera();
  double sum = 0, sum2 = 0;
  long n = 0;
  for (int frame = 0; frame < 20; ++frame) {
    RgbdFrame f;
    sim::apply_tof_sensor(plane(cam.width, cam.height, z, 0.5f, 0), 1, cam, cfg, 0.5, 4.5, 1000 + frame, f);
    for (auto d : f.depth.data)
      if (d) {
        const double e = d * 0.001 - z;
        sum += e;
        sum2 += e * e;
        ++n;
      }
  }
  const double mean = sum / n;
  return std::sqrt(sum2 / n - mean * mean);
}
}  // namespace

TEST(TofSensor, MeasuredNoiseFollowsModelAndGrowsWithRange) {
  sim::SimSensorConfig cfg;
  const double near = measured_std(0.7f, cfg), far = measured_std(1.3f, cfg);
  EXPECT_LT(near, far);
  // Millimetre quantisation adds 1/12 mm^2 of variance.
  for (auto [z, s] : {std::pair{0.7, near}, std::pair{1.3, far}}) {
    const double model = std::sqrt(std::pow(sim::tof_noise_sigma(cfg, z, 0.5), 2) + 1e-6 / 12);
    EXPECT_NEAR(s, model, 0.15 * model) << "z " << z;
  }
}

TEST(TofSensor, DepthStepGivesUnlabelledFlyingPixelsBetweenSurfaces) {
  const CameraIntrinsics cam = small_camera();
  const int f = 2;
  sim::SampleBuffers s = plane(cam.width * f, cam.height * f, 1.2f, 0.3f, 0);
  // A head-labelled surface at 0.8 m on the left, its edge through the middle of pixel column 20.
  for (int v = 0; v < s.height; ++v)
    for (int u = 0; u < 41; ++u) {
      s.depth[std::size_t(v) * s.width + u] = 0.8f;
      s.label[std::size_t(v) * s.width + u] = 7;
      s.nir[std::size_t(v) * s.width + u] = 0.5f;
    }
  sim::SimSensorConfig cfg;
  cfg.flying_prob = 1.0;
  cfg.edge_dropout_prob = 0.0;
  RgbdFrame out;
  const auto stats = sim::apply_tof_sensor(s, f, cam, cfg, 0.5, 4.5, 3, out);
  EXPECT_GT(stats.flying, 0);
  int flying = 0;
  for (int v = 0; v < cam.height; ++v) {
    const auto d = out.depth.at(20, v);
    if (!d) continue;
    EXPECT_GT(d, 820);
    EXPECT_LT(d, 1180);
    EXPECT_EQ(out.labels.at(20, v), 0) << "a mixed pixel is no head point";
    ++flying;
    const auto inside = out.labels.at(10, v);
    if (out.depth.at(10, v)) {
      EXPECT_EQ(inside, 7);
    }
  }
  EXPECT_GT(flying, cam.height / 2);
}

TEST(Renderer, DepthIsExactRayPlaneIntersection) {
  // A large tilted quad below the camera: z_field = 0.1 * x_field + 0.2.
  sim::Mesh m;
  auto zf = [](float x) { return 0.1f * x + 0.2f; };
  const auto a = m.add_vertex({-2, -2, zf(-2)}, {1, 1, 1}, 0.5f), b = m.add_vertex({2, -2, zf(2)}, {1, 1, 1}, 0.5f);
  const auto c = m.add_vertex({2, 2, zf(2)}, {1, 1, 1}, 0.5f), d = m.add_vertex({-2, 2, zf(-2)}, {1, 1, 1}, 0.5f);
  m.add_triangle(a, b, c, 3, sim::SurfaceKind::head);
  m.add_triangle(a, c, d, 3, sim::SurfaceKind::head);
  m.compute_normals();
  const CameraIntrinsics cam = small_camera();
  const Eigen::Vector3d C(0.3, 0.1, 1.25);
  sim::SampleBuffers out;
  sim::render({&m}, C, cam, {}, out);
  for (int v = 0; v < cam.height; v += 7)
    for (int u = 0; u < cam.width; u += 5) {
      const float z = out.depth[std::size_t(v) * cam.width + u];
      ASSERT_TRUE(std::isfinite(z));
      EXPECT_EQ(out.label[std::size_t(v) * cam.width + u], 3);
      const Eigen::Vector3d p = sim::camera_to_field(cam.deproject(float(u), float(v), z).cast<double>(), C);
      EXPECT_NEAR(p.z(), 0.1 * p.x() + 0.2, 1e-5) << u << "," << v;
    }
}
