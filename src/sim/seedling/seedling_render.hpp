#pragma once
// Internal to the seedling simulator: triangle meshes with materials, procedural textures and a
// z-buffer rasteriser for an arbitrary pinhole pose, with the soil as an analytic plane (z = 0)
// intersected per sample.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

namespace cropsight::sim::seedling_detail {

enum Material : std::uint8_t { kSoil = 0, kLeaf = 1, kStem = 2, kWeed = 3 };

struct SMesh {
  std::vector<Eigen::Vector3f> p;   ///< world, m
  std::vector<Eigen::Vector2f> uv;  ///< leaf coordinates (s along the midrib 0..1, t across -1..1)
  std::vector<std::array<std::uint32_t, 3>> tri;
  std::vector<std::uint8_t> mat;
  std::vector<std::uint16_t> label;         ///< 1 = the seedling, 0 = other
  std::vector<Eigen::Vector3f> base_color;  ///< per triangle, 0..255 before shading
  std::uint32_t add(const Eigen::Vector3f& q, const Eigen::Vector2f& st) {
    p.push_back(q);
    uv.push_back(st);
    return std::uint32_t(p.size() - 1);
  }
  void face(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint8_t m, std::uint16_t l,
            const Eigen::Vector3f& col) {
    tri.push_back({a, b, c});
    mat.push_back(m);
    label.push_back(l);
    base_color.push_back(col);
  }
};

/// Pinhole view: camera-to-world rotation and centre.
struct View {
  Eigen::Matrix3d R_cw = Eigen::Matrix3d::Identity();
  Eigen::Vector3d C = Eigen::Vector3d::Zero();
  double f = 1, cx = 0, cy = 0;
  int width = 0, height = 0;
};

struct Samples {
  int w = 0, h = 0;          ///< width * factor, height * factor
  std::vector<float> depth;  ///< camera z, m (+inf: nothing)
  std::vector<int> tri;      ///< -1 = soil / nothing
  std::vector<Eigen::Vector3f> world;
  std::vector<Eigen::Vector2f> uv;
};

/// Renders mesh + soil plane; `factor` samples per pixel side at sub-pixel centres.
void rasterize(const SMesh& mesh, const View& view, int factor, Samples& out);

/// Shaded, textured colour (0..255, unclipped) of sample `i`; `seed` varies the soil texture.
Eigen::Vector3f sample_color(const SMesh& mesh, const Samples& s, int i, std::uint64_t seed);

}  // namespace cropsight::sim::seedling_detail
