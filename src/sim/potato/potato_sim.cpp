// The potato sequence: arm trajectory (scan, then approach the target), D415-like sensor model,
// ground truth, writing (see potato_sim.hpp and docs/simulator.md).
#include "cropsight/sim/potato/potato_sim.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "cropsight/core/error.hpp"
#include "cropsight/io/depth_colormap.hpp"
#include "cropsight/io/files.hpp"
#include "cropsight/io/image_io.hpp"
#include "cropsight/sim/random.hpp"
#include "cropsight/sim/renderer.hpp"
#include "sim/potato/potato_scene.hpp"

namespace cropsight::sim {

void PotatoSimConfig::validate(const std::string& where) const {
  check_config(*this, where);
  if (length_max_m < length_min_m) throw Error(where, "length_max_m must be at least length_min_m");
  if (width_ratio_max < width_ratio_min) throw Error(where, "width_ratio_max must be at least width_ratio_min");
  if (max_range_m <= min_range_m) throw Error(where, "max_range_m must be greater than min_range_m");
}

CameraIntrinsics PotatoSimConfig::camera() const {
  const double h = hfov_deg * M_PI / 180.0;
  const double v = 2.0 * std::atan(std::tan(0.5 * h) * double(height) / double(width));
  CameraIntrinsics c = CameraIntrinsics::from_fov(width, height, h, v);
  c.depth_scale = 0.001;
  c.sensor = "realsense-d415 (simulated)";
  return c;
}

namespace {

constexpr int kFactor = 2;  // samples per pixel side: edges see both surfaces

Eigen::Vector3d camera_position(const PotatoSimConfig& cfg, const detail::PotatoSpec& target, int frame, int frames,
                                std::uint64_t seed) {
  const int scan = std::max(1, int(std::lround(cfg.scan_fraction * frames)));
  const double front = target.centre.z();
  Eigen::Vector3d c(target.centre.x(), target.centre.y(), front + cfg.scan_distance_m);
  if (frame < scan) {
    // Scan: sweep sideways across the target at the scan distance, ending in front of it.
    const double s = scan > 1 ? double(frame) / double(scan - 1) : 1.0;
    c.y() = target.centre.y() - cfg.scan_sweep_m * (1.0 - s);
  } else {
    const int n = frames - scan;
    const double s = n > 1 ? double(frame - scan) / double(n - 1) : 1.0;
    c.z() = front + cfg.scan_distance_m + s * (cfg.approach_end_m - cfg.scan_distance_m);
  }
  // Arm vibration: about a millimetre.
  Rng rng(derive_seed(seed, {3, frame}));
  c += Eigen::Vector3d(rng.normal(0, 0.001), rng.normal(0, 0.001), rng.normal(0, 0.001));
  return c;
}

struct SensorOut {
  long valid = 0;
};

// The D415 model: per pixel, the kFactor^2 samples; an edge (depth spread above the threshold)
// loses its depth with edge_hole_prob, else keeps the nearest surface; stereo noise sigma grows
// with z^2; nothing below the minimum range; 1 mm depth units.
SensorOut apply_d415(const SampleBuffers& s, const PotatoSimConfig& cfg, const CameraIntrinsics& cam,
                     std::uint64_t frame_seed, RgbdFrame& f) {
  SensorOut out;
  f.depth = DepthImage(cam.width, cam.height, 0);
  f.color = ColorImage(cam.width, cam.height);
  f.labels = LabelImage(cam.width, cam.height, 0);
  for (int v = 0; v < cam.height; ++v)
    for (int u = 0; u < cam.width; ++u) {
      Rng rng(derive_seed(frame_seed, {std::int64_t(v) * cam.width + u}));
      float zmin = std::numeric_limits<float>::infinity(), zmax = 0;
      Eigen::Vector3f col = Eigen::Vector3f::Zero();
      std::uint16_t label = 0;
      for (int j = 0; j < kFactor; ++j)
        for (int i = 0; i < kFactor; ++i) {
          const std::size_t k = std::size_t(v * kFactor + j) * std::size_t(s.width) + std::size_t(u * kFactor + i);
          const float z = s.depth[k];
          col += std::isfinite(z) ? s.color[k] : Eigen::Vector3f(0, 0, 0);
          if (z < zmin) zmin = z, label = s.label[k];
          zmax = std::max(zmax, std::isfinite(z) ? z : 1e9f);
        }
      col /= float(kFactor * kFactor);
      Rgb8& c = f.color.at(u, v);
      auto byte = [&](float x) {
        return std::uint8_t(std::clamp(x + float(rng.normal(0, cfg.color_noise)), 0.f, 255.f));
      };
      c = {byte(col.x()), byte(col.y()), byte(col.z())};
      f.labels.at(u, v) = label;
      if (!std::isfinite(zmin)) continue;
      if (zmax - zmin > cfg.edge_threshold_m && rng.bernoulli(cfg.edge_hole_prob)) continue;
      if (rng.bernoulli(cfg.dropout_prob)) continue;
      const double sigma = double(zmin) * zmin * cfg.subpixel / (cam.fx * cfg.baseline_m);
      const double z = zmin + rng.normal(0, sigma);
      if (z < cfg.min_range_m || z > cfg.max_range_m) continue;
      f.depth.at(u, v) = std::uint16_t(std::lround(z / cam.depth_scale));
      ++out.valid;
    }
  return out;
}

io::GroundTruth make_truth(const PotatoSimConfig& cfg, const detail::PotatoSceneModel& scene, std::uint64_t seed,
                           int frames) {
  io::GroundTruth gt;
  for (const auto& p : scene.potatoes) {
    io::InstanceTruth t;
    t.id = p.id;
    t.position = p.centre;
    t.diameter_mm = 1000.0 * p.width;
    t.extra["length_m"] = p.length;
    t.extra["width_m"] = p.width;
    t.extra["thickness_m"] = p.thickness;
    t.extra["axis_x"] = p.axes(0, 0);
    t.extra["axis_y"] = p.axes(1, 0);
    t.extra["axis_z"] = p.axes(2, 0);
    t.extra["sprouts"] = p.sprouts;
    t.extra["target"] = p.id == scene.potatoes[0].id ? 1 : 0;
    gt.instances.push_back(t);
  }
  gt.attributes["generator"] = "cropsight simulate potato";
  gt.attributes["scene"] = config_name(cfg.scene);
  gt.attributes["seed"] = std::to_string(seed);
  gt.attributes["frames"] = std::to_string(frames);
  gt.attributes["world_frame"] = "x down (gravity), y right, z from the backdrop (z = 0) toward the camera; metres";
  gt.attributes["camera_frame"] = "camera x = world +y, camera y = world +x, camera z = world -z (poses.csv: position)";
  gt.attributes["position"] = "potato (ellipsoid) centre, world frame";
  gt.attributes["diameter_mm"] = "potato width (second ellipsoid axis), mm";
  gt.attributes["axis"] = "axis_x/y/z: unit length axis, world frame; length_m, width_m, thickness_m: full axes";
  return gt;
}

}  // namespace

PotatoSimSummary simulate_potato_sequence(const PotatoSimConfig& config, std::uint64_t seed, int frames,
                                          const std::filesystem::path& out, bool overwrite,
                                          const std::function<void(int, int)>& progress) {
  return simulate_potato_sequence(config, seed, frames, out, io::OutputPolicy{"simulate potato", overwrite, {}},
                                  progress);
}

PotatoSimSummary simulate_potato_sequence(const PotatoSimConfig& config, std::uint64_t seed, int frames,
                                          const std::filesystem::path& out, const io::OutputPolicy& policy,
                                          const std::function<void(int, int)>& progress) {
  const auto t0 = std::chrono::steady_clock::now();
  // Checked, and its temporary made, before the scene is built.
  io::OutputFolder tmp(out, policy);
  config.validate("sim config");
  if (frames < 1) throw Error("sim config", "frames must be at least 1");
  const CameraIntrinsics cam = config.camera();
  const detail::PotatoSceneModel scene = detail::build_potato_scene(config, seed);
  // The sequence writer fills tmp/sequence; depth_color/ goes beside it; both then move into tmp,
  // which replaces `out` at the end: an interrupted run leaves nothing that looks complete.
  const std::filesystem::path seq = tmp.path() / "sequence", colour_dir = tmp.path() / "depth_color";
  std::filesystem::create_directories(colour_dir);
  PotatoSimSummary summary;
  {
    io::SequenceWriter writer(seq, cam, true);
    const CameraIntrinsics fine = supersampled(cam, kFactor);
    SampleBuffers samples;
    const std::vector<const Mesh*> meshes = {&scene.mesh};
    double valid = 0;
    for (int i = 0; i < frames; ++i) {
      RgbdFrame f;
      f.index = i;
      f.timestamp = i / config.fps;
      f.camera = cam;
      const Eigen::Vector3d c = camera_position(config, scene.potatoes[0], i, frames, seed);
      f.camera_position = c;
      render(meshes, c, fine, RenderOptions{}, samples);
      valid +=
          double(apply_d415(samples, config, cam, derive_seed(seed, {4, i}), f).valid) / double(cam.width * cam.height);
      Image<float> metres(cam.width, cam.height, 0.f);
      for (std::size_t k = 0; k < metres.data.size(); ++k) metres.data[k] = float(f.depth.data[k] * cam.depth_scale);
      io::write_color(colour_dir / io::frame_file_name(i), io::colorize_depth(metres, float(config.min_range_m), 1.0f));
      writer.write(f);
      if (progress) progress(i + 1, frames);
    }
    writer.set_groundtruth(make_truth(config, scene, seed, frames));
    writer.finish();
    summary.valid_fraction = valid / frames;
  }
  for (const auto& entry : std::filesystem::directory_iterator(seq))
    std::filesystem::rename(entry.path(), tmp.path() / entry.path().filename());
  std::filesystem::remove(seq);
  tmp.commit("sequence");
  summary.frames = frames;
  summary.potatoes = int(scene.potatoes.size());
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return summary;
}

}  // namespace cropsight::sim
