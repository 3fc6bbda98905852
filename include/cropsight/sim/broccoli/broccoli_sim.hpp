#pragma once
// The broccoli-field simulator: a tractor-mounted, downward-looking Kinect v2 driving along the
// rows of a broccoli field (docs/simulator.md).
//
//   BroccoliSimulator sim(config, seed, frames);
//   for (int i = 0; i < sim.frames(); ++i) frames.push_back(sim.render(i));
//   io::GroundTruth truth = sim.groundtruth();   // after rendering: visibility statistics
//
// Frames (field frame: x along the row = driving direction, y across, z up, z = 0 mean soil;
// camera frame per renderer.hpp: camera x = field y, camera y = field x, camera z = -field z).
// Each RgbdFrame carries timestamp = index / fps and camera_position (field frame).
#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <vector>

#include "cropsight/core/rgbd_frame.hpp"
#include "cropsight/io/geo_origin.hpp"
#include "cropsight/io/output.hpp"
#include "cropsight/io/sequence.hpp"
#include "cropsight/sim/broccoli/broccoli_config.hpp"
#include "cropsight/sim/broccoli/broccoli_field.hpp"
#include "cropsight/sim/broccoli/broccoli_randomize.hpp"
#include "cropsight/sim/tof_sensor.hpp"

namespace cropsight::sim {

/// Per-head visibility, accumulated over rendered frames.
struct HeadVisibility {
  int frames_visible = 0;         ///< frames with at least one labelled pixel
  long max_visible_pixels = 0;    ///< most labelled pixels in one frame
  int frames_fully_in_view = 0;   ///< frames where the whole (leafless) head projects inside the image
  double visible_samples = 0;     ///< sums over fully-in-view frames (sub-pixel samples)
  double unoccluded_samples = 0;  ///< same head with all leaves removed
  /// 1 - visible / unoccluded: the fraction of the camera's view of the head hidden by leaves
  /// (averaged over the frames that see the whole head; NaN when none did).
  double occlusion() const;
};

class BroccoliSimulator {
 public:
  /// Throws Error("sim config", ...) on invalid parameters or frames < 1. With
  /// config.randomize.enabled the field is drawn from its ranges first (config() is the draw).
  BroccoliSimulator(BroccoliSimConfig config, std::uint64_t seed, int frames);
  ~BroccoliSimulator();

  int frames() const { return int(poses_.size()); }
  const BroccoliSimConfig& config() const { return field_.config(); }
  /// Leaf family of a randomised draw (obovate, the presets' outline, when not randomised).
  LeafFamily leaf_family() const { return leaf_family_; }
  const CameraIntrinsics& camera() const { return camera_; }
  Eigen::Vector3d camera_position(int frame) const { return poses_.at(std::size_t(frame)); }
  double timestamp(int frame) const { return frame / config().motion.fps; }

  /// Renders frame `index` (any order; sequential order reuses cached meshes).
  RgbdFrame render(int index);
  /// Sensor statistics of the last rendered frame.
  const SensorStats& last_stats() const { return last_stats_; }

  /// Every plant of the traversed strip (head ids set; measured head fields filled once built).
  const std::vector<PlantSpec>& plants() const { return plants_; }
  const std::map<int, HeadVisibility>& visibility() const { return visibility_; }

  /// Ground truth of the heads seen in at least one rendered frame: id, position = apex of the
  /// smooth dome (field frame), diameter_mm = mean of two perpendicular calipers; extras
  /// (occlusion, mature, caliper_major_mm, ...) and sequence attributes (docs/simulator.md).
  io::GroundTruth groundtruth() const;

 private:
  std::vector<const Mesh*> scene_for(const Eigen::Vector3d& camera_position);

  LeafFamily leaf_family_ = LeafFamily::obovate;  // before field_: its initialiser sets it
  BroccoliField field_;
  std::uint64_t seed_;
  Eigen::Matrix3d field_to_camera_;
  CameraIntrinsics camera_;
  std::vector<Eigen::Vector3d> poses_;
  std::vector<PlantSpec> plants_;
  std::vector<int> rows_;
  double soil_half_width_ = 1.0;
  std::map<std::size_t, std::shared_ptr<const Mesh>> plant_cache_;
  std::map<int, std::shared_ptr<const Mesh>> tile_cache_;
  std::map<int, HeadVisibility> visibility_;
  SampleBuffers samples_, heads_only_;
  SensorStats last_stats_;
};

struct SimulationSummary {
  int frames = 0;
  int instances = 0;  ///< heads in groundtruth.json
  int plants = 0;     ///< plants in the traversed strip
  int harvested = 0;
  double mean_occlusion = 0;
  double valid_fraction = 0;  ///< mean fraction of pixels with a depth return
  double seconds = 0;         ///< wall time, rendering + writing
};

/// Simulates `frames` frames and writes the sequence (io::SequenceWriter: camera.yaml, depth/,
/// color/, labels/, poses.csv, groundtruth.json) to `out`, atomically. Throws Error(out, ...)
/// before any rendering when `policy` refuses `out` (io/output.hpp). `progress(done, total)` is
/// called after each frame. With `geo_origin`, the sequence also gets geo_origin.yaml, which ties
/// the simulator's field frame to WGS84 (io/geo_origin.hpp).
SimulationSummary simulate_broccoli_sequence(const BroccoliSimConfig& config, std::uint64_t seed, int frames,
                                             const std::filesystem::path& out, const io::OutputPolicy& policy,
                                             const std::function<void(int, int)>& progress = {},
                                             const std::optional<io::GeoOrigin>& geo_origin = std::nullopt);
/// The same as the command "simulate broccoli" with `overwrite` as its --force.
SimulationSummary simulate_broccoli_sequence(const BroccoliSimConfig& config, std::uint64_t seed, int frames,
                                             const std::filesystem::path& out, bool overwrite,
                                             const std::function<void(int, int)>& progress = {});

}  // namespace cropsight::sim
