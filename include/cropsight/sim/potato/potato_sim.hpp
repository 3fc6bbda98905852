#pragma once
// The potato simulator (docs/simulator.md, "Potatoes"): potatoes hanging on strings
// among roots, seen by a RealSense D415-like camera on the gripper of an arm that scans the scene
// and then approaches one potato (the target).
//
// World frame (the renderer's field frame, so that its camera looks along -z): x down (gravity),
// y right, z from the backdrop toward the camera, metres; the backdrop lies at z = 0. Camera
// frame: camera x = world y, camera y = world x, camera z = -world z (renderer.hpp); the arm only
// translates the camera (poses.csv holds its position in the world frame).
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <vector>

#include "cropsight/core/camera.hpp"
#include "cropsight/core/config.hpp"
#include "cropsight/core/detection2d.hpp"
#include "cropsight/core/image.hpp"
#include "cropsight/io/output.hpp"
#include "cropsight/io/sequence.hpp"

namespace cropsight::sim {

/// sheet: a white sheet behind the potatoes (the paper's set-up); room: a smaller sheet with a
/// room (walls, furniture, dark clothes, a blue object) around and behind it; chamber: a dark root
/// chamber (black walls, dim light).
enum class PotatoScene { sheet, room, chamber };
constexpr std::array<const char*, 3> config_names(PotatoScene) { return {"sheet", "room", "chamber"}; }

struct PotatoSimConfig {
  PotatoScene scene = PotatoScene::sheet;
  int potatoes = 4;  ///< potatoes in the scene; the first is the target
  double length_min_m = 0.06, length_max_m = 0.10;
  double width_ratio_min = 0.6, width_ratio_max = 0.85;  ///< width / length
  int sprouts_max = 3;
  int roots = 10;                    ///< hanging roots (thin tubes) across the scene
  bool root_across_target = true;    ///< one root hangs in front of the target
  bool roots_across_others = false;  ///< one root hangs in front of every other potato too
  double scan_distance_m = 0.5;      ///< camera-to-target distance (z) during the scan
  double approach_end_m = 0.3;       ///< ... at the end of the approach
  double scan_fraction = 0.4;        ///< fraction of the frames spent scanning
  double scan_sweep_m = 0.15;        ///< lateral half-sweep of the scan
  double fps = 15;
  // D415-like sensor.
  int width = 640, height = 480;
  double hfov_deg = 65;       ///< depth field of view (D415: 65 x 40 deg at 16:9; 4:3 crop here)
  double min_range_m = 0.25;  ///< D415 minimum range: no depth nearer
  double max_range_m = 3.0;
  double baseline_m = 0.055;       ///< stereo baseline: depth noise sigma = z^2 * subpixel / (fx * baseline)
  double subpixel = 0.08;          ///< RMS disparity error, pixels
  double edge_threshold_m = 0.02;  ///< a pixel whose samples span more depth than this is an edge
  double edge_hole_prob = 0.6;     ///< probability that an edge pixel has no depth
  double dropout_prob = 0.003;     ///< random missing depth
  double color_noise = 2.0;        ///< colour noise sigma, 0..255

  template <class V>
  void visit(V& v) {
    v("scene", scene, "sheet | room | chamber; backdrop");
    v("potatoes", potatoes, "count; potatoes hanging in the scene, the first is the target", Range::within(1, 8));
    v("length_min_m", length_min_m, "m; shortest potato length", Range::within(0.02, 0.2));
    v("length_max_m", length_max_m, "m; longest potato length", Range::within(0.02, 0.2));
    v("width_ratio_min", width_ratio_min, "1; smallest width / length", Range::within(0.3, 1.0));
    v("width_ratio_max", width_ratio_max, "1; largest width / length", Range::within(0.3, 1.0));
    v("sprouts_max", sprouts_max, "count; most sprouts per potato", Range::within(0, 10));
    v("roots", roots, "count; hanging roots across the scene", Range::within(0, 60));
    v("root_across_target", root_across_target, "bool; one root hangs in front of the target potato");
    v("roots_across_others", roots_across_others,
      "bool; one root hangs in front of every other potato too (the loop's target is the nearest potato, not "
      "always the one the camera approaches; drawn from a stream of its own, so the rest of the scene is unchanged)");
    v("scan_distance_m", scan_distance_m, "m; camera-to-target distance while scanning", Range::within(0.26, 1.5));
    v("approach_end_m", approach_end_m, "m; camera-to-target distance at the end of the approach",
      Range::within(0.26, 1.5));
    v("scan_fraction", scan_fraction, "fraction of the frames spent scanning", Range::within(0.0, 1.0));
    v("scan_sweep_m", scan_sweep_m, "m; lateral half-sweep of the scan", Range::within(0.0, 0.5));
    v("fps", fps, "Hz; frame rate (timestamps)", Range::above(0.0));
    v("width", width, "px; image width", Range::within(64, 4096));
    v("height", height, "px; image height", Range::within(48, 4096));
    v("hfov_deg", hfov_deg, "deg; horizontal field of view", Range::within(20.0, 120.0));
    v("min_range_m", min_range_m, "m; no depth nearer (D415 minimum range ~0.25 m at 640x480)", Range::at_least(0.0));
    v("max_range_m", max_range_m, "m; no depth farther", Range::above(0.0));
    v("baseline_m", baseline_m, "m; stereo baseline (D415: 55 mm)", Range::above(0.0));
    v("subpixel", subpixel, "px; RMS disparity error (D415 datasheet-like 0.08)", Range::at_least(0.0));
    v("edge_threshold_m", edge_threshold_m, "m; depth spread inside a pixel that makes it an edge", Range::above(0.0));
    v("edge_hole_prob", edge_hole_prob, "probability; edge pixels without depth", Range::within(0.0, 1.0));
    v("dropout_prob", dropout_prob, "probability; random pixels without depth", Range::within(0.0, 1.0));
    v("color_noise", color_noise, "0..255; colour noise sigma", Range::within(0.0, 50.0));
  }
  /// Rules between fields; throws Error(where, ...).
  void validate(const std::string& where) const;
  /// The camera: 640 x 480 pinhole, principal point centred, depth_scale 1 mm.
  CameraIntrinsics camera() const;
};

// The truth of each frame is read back from the files by pipeline/potato/truth.hpp.

struct PotatoSimSummary {
  int frames = 0, potatoes = 0;
  double valid_fraction = 0;  ///< mean fraction of pixels with depth
  double seconds = 0;
};

/// Simulates `frames` frames and writes the sequence to `out` (camera.yaml, depth/, color/,
/// labels/, poses.csv, groundtruth.json, depth_color/), atomically. Throws Error(out, ...) before
/// any rendering when `policy` refuses `out` (io/output.hpp).
PotatoSimSummary simulate_potato_sequence(const PotatoSimConfig& config, std::uint64_t seed, int frames,
                                          const std::filesystem::path& out, const io::OutputPolicy& policy,
                                          const std::function<void(int, int)>& progress = {});
/// The same as the command "simulate potato" with `overwrite` as its --force.
PotatoSimSummary simulate_potato_sequence(const PotatoSimConfig& config, std::uint64_t seed, int frames,
                                          const std::filesystem::path& out, bool overwrite,
                                          const std::function<void(int, int)>& progress = {});

}  // namespace cropsight::sim
