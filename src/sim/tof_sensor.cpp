#include "cropsight/sim/tof_sensor.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/parallel_for.hpp"
#include "cropsight/sim/random.hpp"
#include "sim/value_noise.hpp"

namespace cropsight::sim {

namespace {
double amplitude(const SimSensorConfig& cfg, double z, double nir) {
  return std::max(1e-4, nir / cfg.reference_reflectivity / (z * z));
}
double background(const SimSensorConfig& cfg) { return cfg.sunlight ? cfg.sunlight_background : cfg.background; }

// Stereo holes: where smooth value noise at the hole scale exceeds its (1 - fraction) quantile
// over the image, so a frame loses about stereo_hole_fraction in blobs (failed matches on
// textureless or specular patches). Empty for the ToF model.
std::vector<std::uint8_t> stereo_holes(const SimSensorConfig& cfg, int W, int H, std::uint64_t frame_seed) {
  if (cfg.model != "stereo" || cfg.stereo_hole_fraction <= 0) return {};
  const std::uint64_t seed = derive_seed(frame_seed, {-1});
  std::vector<float> field(std::size_t(W) * std::size_t(H));
  for (int v = 0; v < H; ++v)
    for (int u = 0; u < W; ++u)
      field[std::size_t(v) * W + u] =
          float(detail::fbm(seed, u / cfg.stereo_hole_scale_px, v / cfg.stereo_hole_scale_px, 2));
  std::vector<float> sorted = field;
  const auto k = std::size_t(double(sorted.size() - 1) * (1.0 - cfg.stereo_hole_fraction));
  std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(k), sorted.end());
  const float cut = sorted[k];
  std::vector<std::uint8_t> hole(field.size());
  for (std::size_t i = 0; i < field.size(); ++i) hole[i] = field[i] > cut;
  return hole;
}
}  // namespace

double tof_noise_sigma(const SimSensorConfig& cfg, double z, double nir) {
  const double A = amplitude(cfg, z, nir);
  return cfg.noise_at_1m_m * std::sqrt((A + background(cfg)) / (1.0 + cfg.background)) / A;
}

// Long on purpose: the sensor model's per-pixel hot loop, one fixed draw order per pixel.
SensorStats apply_tof_sensor(const SampleBuffers& S, int f, const CameraIntrinsics& cam, const SimSensorConfig& cfg,
                             double min_range, double max_range, std::uint64_t frame_seed, RgbdFrame& frame) {
  const int W = cam.width, H = cam.height;
  frame.camera = cam;
  frame.depth = DepthImage(W, H, 0);
  frame.color = ColorImage(W, H);
  frame.labels = LabelImage(W, H, 0);
  std::vector<SensorStats> row_stats(static_cast<std::size_t>(H));
  const int n = f * f;
  const bool stereo = cfg.model == "stereo";
  const std::vector<std::uint8_t> holes = stereo_holes(cfg, W, H, frame_seed);
  cropsight::detail::parallel_for_each_index(std::size_t(H), [&](std::size_t row) {
    const int v = int(row);
    SensorStats& st = row_stats[std::size_t(v)];
    float z[16], a[16];
    std::uint16_t lab[16];
    for (int u = 0; u < W; ++u) {
      const std::size_t pix = std::size_t(v) * W + u;
      Rng rng(derive_seed(frame_seed, {std::int64_t(pix)}));
      // Fixed draw order, whatever branch is taken: stable streams.
      const double r_edge = rng.uniform(), r_drop = rng.uniform(), gauss = rng.normal();
      const double cn[3] = {rng.normal(), rng.normal(), rng.normal()};
      int m = 0;
      Eigen::Vector3f color = Eigen::Vector3f::Zero();
      float zmin = 1e30f, zmax = -1e30f;
      for (int j = 0; j < f; ++j)
        for (int i = 0; i < f; ++i) {
          const std::size_t s = std::size_t(v * f + j) * std::size_t(S.width) + std::size_t(u * f + i);
          color += S.color[s];
          if (!std::isfinite(S.depth[s])) continue;
          z[m] = S.depth[s];
          a[m] = S.nir[s];
          lab[m] = S.label[s];
          zmin = std::min(zmin, z[m]);
          zmax = std::max(zmax, z[m]);
          ++m;
        }
      ++st.pixels;
      // Colour: box-filtered samples + sensor noise (registered to depth, kept where depth is missing).
      color /= float(n);
      Rgb8& c = frame.color.data[pix];
      auto chan = [&](float x, double g) {
        return std::uint8_t(std::clamp(std::lround(x + cfg.color_noise * g), 0L, 255L));
      };
      c = {chan(color.x(), cn[0]), chan(color.y(), cn[1]), chan(color.z(), cn[2])};
      if (m == 0) {
        ++st.dropped;
        continue;
      }
      double depth = 0, nir = 0;
      bool flying = false;
      int used = m;  // samples that make up the return
      if (zmax - zmin > cfg.edge_threshold_m) {
        if (stereo && r_edge < cfg.stereo_edge_dropout_prob) {
          // Stereo: the left-right check (or the occlusion shadow) removes edge pixels; no mixing.
          ++st.dropped;
          continue;
        } else if (!stereo && r_edge < cfg.flying_prob) {
          double wsum = 0;
          for (int k = 0; k < m; ++k) {
            const double w = std::max(1e-6, double(a[k])) / (double(z[k]) * z[k]);
            depth += w * z[k];
            wsum += w;
            nir += a[k];
          }
          depth /= wsum;
          nir /= m;
          flying = true;
        } else if (!stereo && r_edge < cfg.flying_prob + cfg.edge_dropout_prob) {
          ++st.dropped;
          continue;
        } else {
          // Keep the foreground surface: move its samples to the front.
          used = 0;
          for (int k = 0; k < m; ++k)
            if (z[k] <= zmin + cfg.edge_threshold_m) {
              std::swap(z[k], z[used]);
              std::swap(a[k], a[used]);
              std::swap(lab[k], lab[used]);
              ++used;
            }
        }
      }
      std::uint16_t label = 0;
      if (!flying) {
        for (int k = 0; k < used; ++k) {
          depth += z[k];
          nir += a[k];
        }
        depth /= used;
        nir /= used;
        // Majority label among the samples used (ties: the first sample's).
        int best = 0;
        for (int k = 0; k < used; ++k) {
          int cnt = 0;
          for (int q = 0; q < used; ++q) cnt += lab[q] == lab[k];
          if (cnt > best) best = cnt, label = lab[k];
        }
      }
      if (depth < min_range || depth > max_range) {
        ++st.dropped;
        continue;
      }
      double p_drop, sigma;
      if (stereo) {
        p_drop = holes.empty() ? cfg.random_dropout : (holes[pix] ? 1.0 : cfg.random_dropout);
        sigma = cfg.stereo_noise_at_1m_m * depth * depth;  // disparity noise: sigma_z ~ z^2
      } else {
        const double A = amplitude(cfg, depth, nir);
        p_drop = cfg.random_dropout + (cfg.sunlight ? cfg.sunlight_dropout : 0.0) +
                 1.0 / (1.0 + std::exp((A - cfg.amplitude_min) / cfg.amplitude_softness));
        sigma = tof_noise_sigma(cfg, depth, nir);
      }
      if (r_drop < p_drop) {
        ++st.dropped;
        continue;
      }
      const double zn = depth + sigma * gauss;
      if (zn < cam.depth_scale * 0.5 || zn < 0) {
        ++st.dropped;
        continue;
      }
      const long raw = std::lround(zn / cam.depth_scale);
      if (raw <= 0 || raw > 65535) {
        ++st.dropped;
        continue;
      }
      frame.depth.data[pix] = std::uint16_t(raw);
      frame.labels.data[pix] = flying ? 0 : label;
      ++st.valid;
      st.flying += flying;
    }
  });
  SensorStats total;
  for (const auto& s : row_stats) {
    total.pixels += s.pixels;
    total.valid += s.valid;
    total.flying += s.flying;
    total.dropped += s.dropped;
  }
  return total;
}

}  // namespace cropsight::sim
