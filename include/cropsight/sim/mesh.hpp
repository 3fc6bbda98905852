#pragma once
// Triangle meshes of scene objects, in the field frame (metres; x along the row, y across, z up).
// Every vertex carries what the renderer needs: a shaded colour (static sun lighting, baked at
// build time), a near-infrared reflectivity for the ToF amplitude model, and a normal for the
// incidence angle. Every triangle carries an instance label (head id, 0 for everything else).
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

namespace cropsight::sim {

/// What a surface is; used for statistics and the occlusion ground truth.
enum class SurfaceKind : std::uint8_t { soil = 0, leaf = 1, head = 2, stem = 3, weed = 4, stump = 5 };

struct Mesh {
  std::vector<Eigen::Vector3f> position;          ///< field frame, m
  std::vector<Eigen::Vector3f> normal;            ///< unit, field frame
  std::vector<Eigen::Vector3f> color;             ///< linear 0..255 RGB after shading
  std::vector<float> reflectivity;                ///< NIR reflectivity 0..1
  std::vector<std::array<std::uint32_t, 3>> tri;  ///< vertex indices
  std::vector<std::uint16_t> tri_label;           ///< instance id per triangle (0 = none)
  std::vector<SurfaceKind> tri_kind;
  Eigen::Vector3f box_min{1e9f, 1e9f, 1e9f};
  Eigen::Vector3f box_max{-1e9f, -1e9f, -1e9f};

  std::uint32_t add_vertex(const Eigen::Vector3f& p, const Eigen::Vector3f& c, float refl) {
    position.push_back(p);
    normal.emplace_back(0.f, 0.f, 0.f);
    color.push_back(c);
    reflectivity.push_back(refl);
    box_min = box_min.cwiseMin(p);
    box_max = box_max.cwiseMax(p);
    return std::uint32_t(position.size() - 1);
  }
  void add_triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint16_t label, SurfaceKind kind) {
    tri.push_back({a, b, c});
    tri_label.push_back(label);
    tri_kind.push_back(kind);
  }
  /// Appends `other` (indices shifted).
  void append(const Mesh& other);
  /// Area-weighted vertex normals from the triangles. Orientation is not meaningful: thin
  /// surfaces (leaves) are seen from either side, so users take |n . d|.
  void compute_normals();
  /// Multiplies every vertex colour by Lambert shading (ambient + (1-ambient) * |n.l|).
  void shade(const Eigen::Vector3f& light_dir, float ambient);
  std::size_t triangles() const { return tri.size(); }
};

}  // namespace cropsight::sim
