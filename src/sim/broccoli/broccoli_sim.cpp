#include "cropsight/sim/broccoli/broccoli_sim.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <locale>
#include <set>
#include <sstream>

#include "core/parallel_for.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/core/timer.hpp"
#include "cropsight/sim/random.hpp"
#include "cropsight/sim/renderer.hpp"
#include "sim/angles.hpp"

namespace cropsight::sim {

namespace {
enum : std::int64_t { kMotionTag = 20, kFrameTag = 30 };
}  // namespace

double HeadVisibility::occlusion() const {
  if (unoccluded_samples <= 0) return std::numeric_limits<double>::quiet_NaN();
  return std::clamp(1.0 - visible_samples / unoccluded_samples, 0.0, 1.0);
}

BroccoliSimulator::~BroccoliSimulator() = default;

BroccoliSimulator::BroccoliSimulator(BroccoliSimConfig config, std::uint64_t seed, int frames)
    : field_(draw_randomized_config(config, seed, &leaf_family_), seed), seed_(seed) {
  const auto& cfg = field_.config();
  if (cfg.randomize.enabled) cfg.validate("sim config (randomized draw of seed " + std::to_string(seed) + ")");
  field_to_camera_ = tilted_camera_rotation(cfg.camera.tilt_deg, cfg.camera.tilt_azimuth_deg);
  if (frames < 1 || frames > 1000000) throw Error("sim config", "frames must be in 1..1000000");
  camera_ = CameraIntrinsics::from_fov(cfg.camera.width, cfg.camera.height, cfg.camera.hfov_deg * kDeg,
                                       cfg.camera.vfov_deg * kDeg);
  camera_.depth_scale = 0.001;
  camera_.sensor = "kinect-v2 (cropsight simulator)";

  // Camera path: constant speed with a jittered advance, a smooth (AR(1)) suspension bounce and sway.
  const auto& M = cfg.motion;
  Rng rng(derive_seed(seed, {kMotionTag}));
  const double step = M.speed_mps / M.fps;
  const double keep = 0.7, fresh = std::sqrt(1 - keep * keep);
  double x = M.start_x_m, dz = 0, dy = 0;
  for (int i = 0; i < frames; ++i) {
    if (i > 0) x += step * (1.0 + M.speed_jitter * rng.normal());
    dz = keep * dz + fresh * M.height_jitter_m * rng.normal();
    dy = keep * dy + fresh * M.lateral_jitter_m * rng.normal();
    poses_.emplace_back(x, cfg.camera.lateral_offset_m + dy, cfg.camera.height_m + dz);
  }

  // The strip the camera can see, with room for leaves reaching in from outside it.
  double zmax = 0, xmin = 1e30, xmax = -1e30, ymax = 0;
  for (const auto& p : poses_) {
    zmax = std::max(zmax, p.z());
    xmin = std::min(xmin, p.x());
    xmax = std::max(xmax, p.x());
    ymax = std::max(ymax, std::abs(p.y()));
  }
  // A tilted camera sees farther to one side (only then the margin grows: nadir strips, and so the
  // head ids, stay as they were).
  const double lean = cfg.camera.tilt_deg > 0 ? zmax * std::tan(cfg.camera.tilt_deg * kDeg) : 0.0;
  const double across = zmax * std::tan(0.5 * cfg.camera.hfov_deg * kDeg) + lean;
  const double along = zmax * std::tan(0.5 * cfg.camera.vfov_deg * kDeg) + lean;
  soil_half_width_ = ymax + across + 0.15;
  rows_ = field_.rows_within(soil_half_width_);
  const double reach = cfg.plant.leaf_length_max_m + 0.15;
  plants_ = field_.plants(rows_, xmin - along - reach, xmax + along + reach);
  int next_id = 1;
  for (auto& p : plants_)
    if (p.has_head) {
      if (next_id > 65535) throw Error("sim config", "more than 65535 heads: simulate fewer frames per sequence");
      p.head.id = next_id++;
    }
}

std::vector<const Mesh*> BroccoliSimulator::scene_for(const Eigen::Vector3d& C) {
  const auto& cfg = field_.config();
  const double lean = cfg.camera.tilt_deg > 0 ? C.z() * std::tan(cfg.camera.tilt_deg * kDeg) : 0.0;
  const double along = C.z() * std::tan(0.5 * cfg.camera.vfov_deg * kDeg) + lean;
  const double reach = cfg.plant.leaf_length_max_m + 0.15;
  // Plants whose leaves can reach into the view.
  std::vector<std::size_t> needed, missing;
  for (std::size_t k = 0; k < plants_.size(); ++k)
    if (std::abs(plants_[k].xy.x() - C.x()) <= along + reach) {
      needed.push_back(k);
      if (!plant_cache_.count(k)) missing.push_back(k);
    }
  std::vector<std::shared_ptr<const Mesh>> built(missing.size());
  cropsight::detail::parallel_for_each_index(
      missing.size(), [&](std::size_t i) { built[i] = field_.build_plant(plants_[missing[i]]); });
  std::map<std::size_t, std::shared_ptr<const Mesh>> plants;
  for (std::size_t i = 0; i < missing.size(); ++i) plants[missing[i]] = built[i];
  for (std::size_t k : needed)
    if (!plants.count(k)) plants[k] = plant_cache_.at(k);
  plant_cache_.swap(plants);

  // Soil tiles under the view.
  const double L = field_.tile_length();
  const int t0 = int(std::floor((C.x() - along - 0.1) / L)), t1 = int(std::floor((C.x() + along + 0.1) / L));
  std::vector<int> tmissing;
  for (int t = t0; t <= t1; ++t)
    if (!tile_cache_.count(t)) tmissing.push_back(t);
  std::vector<std::shared_ptr<const Mesh>> tbuilt(tmissing.size());
  cropsight::detail::parallel_for_each_index(
      tmissing.size(), [&](std::size_t i) { tbuilt[i] = field_.build_tile(tmissing[i], soil_half_width_); });
  std::map<int, std::shared_ptr<const Mesh>> tiles;
  for (std::size_t i = 0; i < tmissing.size(); ++i) tiles[tmissing[i]] = tbuilt[i];
  for (int t = t0; t <= t1; ++t)
    if (!tiles.count(t)) tiles[t] = tile_cache_.at(t);
  tile_cache_.swap(tiles);

  std::vector<const Mesh*> meshes;
  for (const auto& [t, m] : tile_cache_) meshes.push_back(m.get());
  for (const auto& [k, m] : plant_cache_) meshes.push_back(m.get());
  return meshes;
}

RgbdFrame BroccoliSimulator::render(int index) {
  if (index < 0 || index >= frames()) throw Error("sim", "frame index out of range");
  const auto& cfg = field_.config();
  const Eigen::Vector3d C = poses_[std::size_t(index)];
  const std::vector<const Mesh*> meshes = scene_for(C);
  const int f = cfg.camera.supersample;
  const CameraIntrinsics ss = supersampled(camera_, f);
  sim::render(meshes, C, ss, RenderOptions{false, true, field_to_camera_}, samples_);
  sim::render(meshes, C, ss, RenderOptions{true, false, field_to_camera_}, heads_only_);

  RgbdFrame frame;
  frame.index = index;
  frame.timestamp = timestamp(index);
  frame.camera_position = C;
  last_stats_ = apply_tof_sensor(samples_, f, camera_, cfg.sensor, cfg.camera.min_range_m, cfg.camera.max_range_m,
                                 derive_seed(seed_, {kFrameTag, index}), frame);

  // Visibility and occlusion ground truth.
  std::map<int, long> vis, unocc, pixels;
  std::set<int> border;
  const int W = heads_only_.width, H = heads_only_.height;
  for (std::size_t i = 0; i < samples_.label.size(); ++i) {
    if (samples_.label[i]) ++vis[samples_.label[i]];
    if (heads_only_.label[i]) ++unocc[heads_only_.label[i]];
  }
  for (int u = 0; u < W; ++u) {
    border.insert(heads_only_.label[std::size_t(u)]);
    border.insert(heads_only_.label[std::size_t(H - 1) * W + u]);
  }
  for (int v = 0; v < H; ++v) {
    border.insert(heads_only_.label[std::size_t(v) * W]);
    border.insert(heads_only_.label[std::size_t(v) * W + W - 1]);
  }
  for (auto l : frame.labels.data)
    if (l) ++pixels[l];
  for (const auto& [id, n] : pixels) {
    HeadVisibility& h = visibility_[id];
    ++h.frames_visible;
    h.max_visible_pixels = std::max(h.max_visible_pixels, n);
  }
  for (const auto& [id, n] : unocc) {
    if (border.count(id)) continue;
    HeadVisibility& h = visibility_[id];
    ++h.frames_fully_in_view;
    h.unoccluded_samples += double(n);
    h.visible_samples += double(vis.count(id) ? vis.at(id) : 0);
  }
  return frame;
}

// Long on purpose: every ground-truth field of a head and the attributes that document them, in the file's order.
io::GroundTruth BroccoliSimulator::groundtruth() const {
  const auto& cfg = field_.config();
  io::GroundTruth gt;
  auto num = [](double v) {
    std::ostringstream o;
    o.imbue(std::locale::classic());
    o.precision(10);
    o << v;
    return o.str();
  };
  int harvested = 0, heads = 0;
  for (const auto& p : plants_) {
    harvested += p.harvested;
    heads += p.has_head;
    if (!p.has_head) continue;
    auto it = visibility_.find(p.head.id);
    if (it == visibility_.end() || it->second.frames_visible == 0) continue;
    const HeadSpec& h = p.head;
    const HeadVisibility& v = it->second;
    io::InstanceTruth t;
    t.id = h.id;
    t.position = h.apex;
    t.diameter_mm = h.diameter_mm;
    t.extra["caliper_major_mm"] = h.caliper_major_mm;
    t.extra["caliper_minor_mm"] = h.caliper_minor_mm;
    t.extra["mature"] = h.mature ? 1 : 0;
    t.extra["harvested"] = 0;
    t.extra["occlusion"] = std::isnan(v.occlusion()) ? -1.0 : v.occlusion();
    t.extra["frames_visible"] = v.frames_visible;
    t.extra["frames_fully_in_view"] = v.frames_fully_in_view;
    t.extra["max_visible_pixels"] = double(v.max_visible_pixels);
    t.extra["dome_height_m"] = h.dome_height;
    t.extra["tilt_deg"] = h.tilt_deg;
    t.extra["ellipticity"] = (h.semi_a - h.semi_b) / (h.semi_a + h.semi_b);
    t.extra["purple"] = h.purple ? 1 : 0;
    t.extra["row"] = p.row;
    t.extra["base_x"] = h.base.x();
    t.extra["base_y"] = h.base.y();
    t.extra["base_z"] = h.base.z();
    gt.instances.push_back(std::move(t));
  }
  gt.attributes["generator"] = "cropsight simulate broccoli";
  gt.attributes["variety"] = cfg.field.variety;
  gt.attributes["seed"] = std::to_string(seed_);
  gt.attributes["frames"] = std::to_string(frames());
  gt.attributes["fps"] = num(cfg.motion.fps);
  gt.attributes["speed_mps"] = num(cfg.motion.speed_mps);
  gt.attributes["camera_height_m"] = num(cfg.camera.height_m);
  gt.attributes["row_spacing_m"] = num(cfg.field.row_spacing_m);
  gt.attributes["in_row_spacing_m"] = num(cfg.field.in_row_spacing_m);
  gt.attributes["plants"] = std::to_string(plants_.size());
  gt.attributes["harvested_plants"] = std::to_string(harvested);
  gt.attributes["heads_in_strip"] = std::to_string(heads);
  if (cfg.randomize.enabled) {
    // What this sequence drew (docs/simulator.md, "Randomised fields").
    gt.attributes["randomized"] = "1";
    gt.attributes["rows_under_camera"] = std::to_string(cfg.field.rows_under_camera);
    gt.attributes["leaf_family"] = leaf_family_name(leaf_family_);
    gt.attributes["leaf_width_ratio"] = num(cfg.plant.leaf_width_ratio);
    gt.attributes["plant_height_m"] = num(cfg.plant.plant_height_m);
    gt.attributes["head_diameter_range_mm"] = num(cfg.head.diameter_min_mm) + "," + num(cfg.head.diameter_max_mm);
    gt.attributes["floret_ratio"] = num(cfg.head.floret_ratio);
    gt.attributes["floret_height"] = num(cfg.head.floret_height);
    gt.attributes["sensor_model"] = cfg.sensor.model;
    gt.attributes["sunlight"] = cfg.sensor.sunlight ? "1" : "0";
  }
  if (cfg.camera.tilt_deg > 0) {
    gt.attributes["camera_tilt_deg"] = num(cfg.camera.tilt_deg);
    gt.attributes["camera_tilt_azimuth_deg"] = num(cfg.camera.tilt_azimuth_deg);
    gt.attributes["camera_orientation"] =
        "tilted: the optical axis leans camera_tilt_deg from nadir towards camera_tilt_azimuth_deg (from field +x "
        "towards +y); poses.csv holds positions only";
  }
  gt.attributes["field_frame"] = "x along the row (driving direction), y across, z up; z = 0 mean soil; metres";
  gt.attributes["camera_frame"] = "nadir: camera x = field +y, camera y = field +x, camera z = field -z";
  gt.attributes["position"] = "apex of the smooth head dome (top of the head on its axis), field frame";
  gt.attributes["diameter_mm"] = "mean of two perpendicular caliper widths (widest direction and across it)";
  gt.attributes["occlusion"] =
      "fraction of the head's leafless view hidden by leaves, over frames seeing the whole head (-1: never whole)";
  return gt;
}

SimulationSummary simulate_broccoli_sequence(const BroccoliSimConfig& config, std::uint64_t seed, int frames,
                                             const std::filesystem::path& out, bool overwrite,
                                             const std::function<void(int, int)>& progress) {
  return simulate_broccoli_sequence(config, seed, frames, out, io::OutputPolicy{"simulate broccoli", overwrite, {}},
                                    progress);
}

SimulationSummary simulate_broccoli_sequence(const BroccoliSimConfig& config, std::uint64_t seed, int frames,
                                             const std::filesystem::path& out, const io::OutputPolicy& policy,
                                             const std::function<void(int, int)>& progress,
                                             const std::optional<io::GeoOrigin>& geo_origin) {
  const Stopwatch clock;
  if (geo_origin) geo_origin->validate("--geo-origin");  // before any rendering
  io::check_output_folder(out, policy);                  // before the field is grown
  BroccoliSimulator sim(config, seed, frames);
  io::SequenceWriter writer(out, sim.camera(), policy);
  SimulationSummary s;
  double valid = 0;
  for (int i = 0; i < frames; ++i) {
    writer.write(sim.render(i));
    valid += double(sim.last_stats().valid) / double(std::max(1L, sim.last_stats().pixels));
    if (progress) progress(i + 1, frames);
  }
  io::GroundTruth gt = sim.groundtruth();
  s.frames = frames;
  s.instances = int(gt.instances.size());
  s.plants = int(sim.plants().size());
  for (const auto& p : sim.plants()) s.harvested += p.harvested;
  int n = 0;
  for (const auto& t : gt.instances)
    if (t.extra.at("occlusion") >= 0) s.mean_occlusion += t.extra.at("occlusion"), ++n;
  if (n) s.mean_occlusion /= n;
  s.valid_fraction = valid / frames;
  writer.set_groundtruth(std::move(gt));
  if (geo_origin) writer.set_geo_origin(*geo_origin);
  writer.finish();
  s.seconds = clock.seconds();
  return s;
}

}  // namespace cropsight::sim
