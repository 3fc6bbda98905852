// The grape simulator's ray caster: one ray per pixel against the berries and peduncle (spheres),
// the leaves (flat lobed ellipses) and the backdrop (a plane with holes), nearest hit wins.
// Shading is Lambert under a light above and behind the camera, plus a glint on the berries (their
// waxy skin), so that colour varies over a surface as it does in a photograph.
#include <cmath>
#include <limits>

#include "../value_noise.hpp"
#include "grape_scene.hpp"

namespace cropsight::sim::detail {

namespace {

const Eigen::Vector3d kLight = Eigen::Vector3d(-0.3, -0.6, -1.0).normalized();  // toward the light

struct Nearest {
  double t = std::numeric_limits<double>::infinity();
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  int label = kGrapeNoReturn;
  Eigen::Vector3f color{0, 0, 0};
  bool glossy = false;
};

// Ray o = 0, direction d (d.z = 1, so t is the depth).
void hit_spheres(const std::vector<GrapeSphere>& spheres, const Eigen::Vector3d& d, Nearest& best) {
  const double dd = d.squaredNorm();
  for (const GrapeSphere& s : spheres) {
    const double b = d.dot(s.centre), c = s.centre.squaredNorm() - s.radius * s.radius;
    const double disc = b * b - dd * c;
    if (disc < 0) continue;
    const double t = (b - std::sqrt(disc)) / dd;
    if (t <= 0 || t >= best.t) continue;
    best = {t, (t * d - s.centre) / s.radius, s.label, s.color, s.label == kGrapeBerry};
  }
}

void hit_leaves(const std::vector<GrapeLeaf>& leaves, const Eigen::Vector3d& d, Nearest& best) {
  for (const GrapeLeaf& l : leaves) {
    const Eigen::Vector3d n = l.e1.cross(l.e2);
    const double denom = n.dot(d);
    if (std::abs(denom) < 1e-9) continue;
    const double t = n.dot(l.centre) / denom;
    if (t <= 0 || t >= best.t) continue;
    const Eigen::Vector3d q = t * d - l.centre;
    const double x = q.dot(l.e1) / l.a, y = q.dot(l.e2) / l.b;
    const double lobe = 1 + 0.12 * std::cos(5 * std::atan2(y, x));
    if (x * x + y * y >= lobe * lobe) continue;
    best = {t, denom < 0 ? n : -n, kGrapeLeaf, l.color, false};
  }
}

Eigen::Vector3f shade(const Nearest& hit, const Eigen::Vector3d& d) {
  const double lambert = std::max(0.0, hit.normal.dot(kLight));
  Eigen::Vector3f c = hit.color * float(0.55 + 0.45 * lambert);
  if (hit.glossy) {
    const Eigen::Vector3d view = -d.normalized();
    const Eigen::Vector3d half = (view + kLight).normalized();
    c += Eigen::Vector3f::Constant(float(0.35 * std::pow(std::max(0.0, hit.normal.dot(half)), 40)));
  }
  return c.cwiseMin(1.f);
}

}  // namespace

Eigen::Vector3f far_color(std::uint64_t seed, double x, double y) {
  const double sky = 0.5 + 0.5 * fbm(seed + 1, x * 6, y * 6, 3);
  const double tone = 0.5 + 0.5 * fbm(seed + 2, x * 14, y * 14, 2);
  const Eigen::Vector3f blue{0.55f, 0.65f, 0.78f}, green{0.22f, 0.36f, 0.18f}, pale{0.82f, 0.8f, 0.74f};
  const Eigen::Vector3f c = float(sky) * blue + float(1 - sky) * green;
  return float(tone) * c + float(1 - tone) * pale * 0.8f;
}

std::vector<GrapeHit> cast_grape_scene(const GrapeScene& scene, double focal_px, const PixelRect& roi) {
  std::vector<GrapeHit> hits(std::size_t(roi.width) * std::size_t(roi.height));
  for (int j = 0; j < roi.height; ++j) {
    for (int i = 0; i < roi.width; ++i) {
      const Eigen::Vector3d d{(roi.u0 + i + 0.5) / focal_px, (roi.v0 + j + 0.5) / focal_px, 1.0};
      Nearest best;
      hit_spheres(scene.spheres, d, best);
      hit_leaves(scene.leaves, d, best);
      GrapeHit& h = hits[std::size_t(j) * std::size_t(roi.width) + std::size_t(i)];
      if (!std::isfinite(best.t)) {
        // The backdrop, or the world seen through one of its holes.
        const double x = d.x() * scene.backdrop_z, y = d.y() * scene.backdrop_z;
        const double hole = 0.5 + 0.9 * fbm(scene.backdrop_seed, x * 12, y * 12, 3);
        if (hole < scene.backdrop_holes) {
          h.color = far_color(scene.backdrop_seed, x, y);
          continue;
        }
        const float grey = float(0.5 + 0.06 * fbm(scene.backdrop_seed + 7, x * 40, y * 40, 2));
        best = {scene.backdrop_z, {0, 0, -1}, kGrapeBackdrop, Eigen::Vector3f::Constant(grey), false};
        h.color = best.color;
      } else {
        h.color = shade(best, d);
      }
      h.depth = float(best.t);
      h.label = best.label;
      h.position = (best.t * d).cast<float>();
    }
  }
  return hits;
}

}  // namespace cropsight::sim::detail
