#pragma once
// Kinect v2 time-of-flight sensor model: turns ideal sub-pixel samples into what the camera
// returns (docs/simulator.md, "Sensor").
//
// Per pixel, from its factor x factor samples:
//  * Discontinuities: when the samples' depths spread more than edge_threshold_m, the pixel sees
//    two surfaces. ToF mixes their returns: with flying_prob it reports the amplitude-weighted
//    mean depth (a "flying pixel" floating between fore- and background; linearised phasor sum),
//    with edge_dropout_prob it is dropped (the driver's flying-pixel filter), otherwise it keeps
//    the foreground surface.
//  * Amplitude A = (reflectivity x |cos incidence| / reference_reflectivity) / z^2 (1 for the
//    reference surface head-on at 1 m). Axial noise sigma = noise_at_1m * sqrt((A + B) /
//    (1 + B0)) / A (shot noise of signal A plus background B; B0 = indoor background), so noise
//    grows with range, with grazing incidence, on dark surfaces and under sunlight.
//  * Missing returns with probability random_dropout + [sunlight_dropout] + logistic(A below
//    amplitude_min): dark (moist soil) and grazing surfaces lose returns.
//  * Labels: a pixel keeps the instance id of its surface only when it returns a depth of that
//    surface (not dropped, not a mixed flying pixel).
// With cfg.model == "stereo" (a RealSense-like active stereo camera) instead: edge pixels are
// dropped with stereo_edge_dropout_prob or keep the foreground (no flying pixels), returns are lost
// in blob-shaped holes (stereo_hole_fraction of the image) and at random_dropout, and the noise
// std is stereo_noise_at_1m_m x z^2.
// Every pixel draws from its own stream derive_seed(frame_seed, {pixel}), so output is
// deterministic under parallel processing.
#include <cstdint>

#include "cropsight/core/rgbd_frame.hpp"
#include "cropsight/sim/broccoli/broccoli_config.hpp"
#include "cropsight/sim/renderer.hpp"

namespace cropsight::sim {

struct SensorStats {
  long pixels = 0;
  long valid = 0;
  long flying = 0;   ///< mixed-depth pixels returned
  long dropped = 0;  ///< no return (any cause)
};

/// Axial noise std (m) for a surface at depth z (m) with NIR reflectivity x |cos incidence| `nir`.
double tof_noise_sigma(const SimSensorConfig& cfg, double z, double nir);

/// Fills frame.depth / frame.color / frame.labels (size camera.width x camera.height) from
/// `samples` rendered at supersampled(camera, factor). Depths outside [min_range, max_range] (m)
/// are no return.
SensorStats apply_tof_sensor(const SampleBuffers& samples, int factor, const CameraIntrinsics& camera,
                             const SimSensorConfig& cfg, double min_range, double max_range, std::uint64_t frame_seed,
                             RgbdFrame& frame);

}  // namespace cropsight::sim
