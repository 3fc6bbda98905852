#pragma once
// Z-buffer rasteriser for the nadir camera of the simulators.
//
// Frames: the camera looks straight down. With field x along the row, y across, z up:
//   camera x (image right, u) = field +y,  camera y (image down, v) = field +x,
//   camera z (depth)          = field -z.
// So p_cam = R (p_field - C) with R = field_to_camera_rotation() and C the camera position.
// Depth is exact per sample (the triangle's plane intersected with the sample's ray, i.e. 1/z
// interpolated linearly in the image), attributes are interpolated perspective-correctly, and the
// nearest surface wins (ties: the earlier triangle), so the result does not depend on threading.
#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <vector>

#include "cropsight/core/camera.hpp"
#include "cropsight/sim/mesh.hpp"

namespace cropsight::sim {

/// Rotation taking field-frame vectors to the nadir camera frame.
Eigen::Matrix3d field_to_camera_rotation();
/// Field-to-camera rotation of a camera whose optical axis leans `tilt_deg` from straight down
/// towards the field direction `azimuth_deg` (from +x towards +y); 0 = field_to_camera_rotation().
Eigen::Matrix3d tilted_camera_rotation(double tilt_deg, double azimuth_deg);
/// Field-frame point of a camera-frame point seen from a camera at `camera_position` (field frame).
Eigen::Vector3d camera_to_field(const Eigen::Vector3d& p_camera, const Eigen::Vector3d& camera_position);

/// Ideal (noise-free) samples: one per (sub-)pixel.
struct SampleBuffers {
  int width = 0, height = 0;
  std::vector<float> depth;            ///< camera z, m; +inf where nothing was hit
  std::vector<std::uint16_t> label;    ///< instance id of the visible surface, 0 = none
  std::vector<SurfaceKind> kind;       ///< what the visible surface is
  std::vector<Eigen::Vector3f> color;  ///< shaded colour 0..255
  std::vector<float> nir;              ///< NIR reflectivity x |cos(incidence)| of the surface
  void reset(int w, int h);
};

struct RenderOptions {
  bool heads_only = false;  ///< render only head triangles (occlusion ground truth)
  bool attributes = true;   ///< fill colour / nir / kind (false: depth and label only)
  /// Field-to-camera rotation: the nadir camera unless the rig is tilted (tilted_camera_rotation).
  Eigen::Matrix3d field_to_camera = field_to_camera_rotation();
};

/// Renders `meshes` seen from `camera_position` with intrinsics `camera` into `out`
/// (resized to camera.width x camera.height). Parallel over image bands (TBB).
void render(const std::vector<const Mesh*>& meshes, const Eigen::Vector3d& camera_position,
            const CameraIntrinsics& camera, const RenderOptions& options, SampleBuffers& out);

/// Intrinsics of a sub-sampled grid: `factor` x `factor` samples per pixel of `camera`, sample
/// (i, j) of pixel (u, v) at sub-pixel centre ((i + 0.5) / factor - 0.5, (j + 0.5) / factor - 0.5).
CameraIntrinsics supersampled(const CameraIntrinsics& camera, int factor);

}  // namespace cropsight::sim
