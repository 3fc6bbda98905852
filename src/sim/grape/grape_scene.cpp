// The grape simulator's scene: a conical bunch of berries packed without much overlap, a slightly
// bent peduncle above it, lobed leaves beside or in front of it, a backdrop behind.
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "../angles.hpp"
#include "grape_scene.hpp"

namespace cropsight::sim::detail {

namespace {

// Radius of the bunch's envelope at fraction s of its length from the top: widest at the
// shoulders (s ~ 0.1), tapering to a third at the tip, as a table-grape bunch is.
double envelope_radius(double shoulder, double s) {
  return shoulder * (0.35 + 0.65 * (1 - s)) * std::min(1.0, 0.6 + 4 * s);
}

Eigen::Vector3f jitter(const Eigen::Vector3f& base, double amount, Rng& rng) {
  const float k = float(1.0 + rng.uniform(-amount, amount));
  return (base * k).cwiseMax(0.f).cwiseMin(1.f);
}

// Berries tried one by one inside the envelope, favouring its surface (the inside is never seen);
// one that would overlap a placed berry by more than 15 % of the radii is dropped.
void add_berries(GrapeScene& scene, const GrapeSimConfig& cfg, const Eigen::Vector3d& axis, double length,
                 double shoulder, Rng& rng) {
  const int tries = rng.uniform_int(cfg.berries_min, cfg.berries_max);
  const Eigen::Vector3d side = axis.cross(Eigen::Vector3d::UnitZ()).normalized();
  const Eigen::Vector3d depth = axis.cross(side).normalized();
  const Eigen::Vector3f purple{0.085f, 0.082f, 0.11f};
  for (int i = 0; i < tries * 20 && scene.berries < tries; ++i) {
    const double r = rng.uniform(cfg.berry_radius_min, cfg.berry_radius_max);
    // The shoulders rise above the peduncle's junction (s < 0) on the outside only, so the
    // peduncle shows between them, as in the shared clouds.
    const double s = rng.uniform(-0.12, 1.0);
    const double phi = rng.uniform(0.0, 2 * kPi);
    const double rho = std::max(0.0, envelope_radius(shoulder, std::max(s, 0.0)) - r) *
                       (s < 0 ? rng.uniform(0.75, 1.0) : rng.uniform(0.55, 1.0));
    const Eigen::Vector3d c =
        scene.bunch_top + axis * (r + s * (length - 2 * r)) + rho * (std::cos(phi) * side + std::sin(phi) * depth);
    const bool overlaps = std::any_of(scene.spheres.begin(), scene.spheres.end(), [&](const GrapeSphere& o) {
      return (o.centre - c).norm() < 0.85 * (o.radius + r);
    });
    if (overlaps) continue;
    scene.spheres.push_back({c, r, kGrapeBerry, jitter(purple, 0.3, rng)});
    ++scene.berries;
  }
}

// The peduncle: spheres every half radius along a gentle arc from 1 cm inside the bunch's top up
// to the cane.
void add_peduncle(GrapeScene& scene, const GrapeSimConfig& cfg, const Eigen::Vector3d& bunch_axis, Rng& rng) {
  const double length = rng.uniform(cfg.peduncle_length_min, cfg.peduncle_length_max);
  const Eigen::Vector3d bend{rng.uniform(-0.3, 0.3), 0, rng.uniform(-0.2, 0.2)};
  const Eigen::Vector3f stem = jitter({0.11f, 0.145f, 0.14f}, 0.25, rng);
  const double r = cfg.peduncle_radius, step = r / 2;
  Eigen::Vector3d p = scene.bunch_top + 0.01 * bunch_axis;
  Eigen::Vector3d dir = -bunch_axis;
  for (double run = -0.01; run <= length; run += step) {
    scene.spheres.push_back({p, r, kGrapePeduncle, stem});
    dir = (dir + bend * (step / length)).normalized();
    p += dir * step;
  }
  scene.peduncle_axis = (p - scene.bunch_top).normalized();
}

// Leaves beside the bunch, mostly behind its axis; one in twenty in front of its edge.
void add_leaves(GrapeScene& scene, const GrapeSimConfig& cfg, const Eigen::Vector3d& centre, double length,
                double shoulder, Rng& rng) {
  const int n = rng.uniform_int(cfg.leaves_min, cfg.leaves_max);
  for (int i = 0; i < n; ++i) {
    GrapeLeaf leaf;
    leaf.a = rng.uniform(cfg.leaf_size_min, cfg.leaf_size_max);
    leaf.b = leaf.a * rng.uniform(0.6, 0.9);
    const bool in_front = rng.bernoulli(0.05);
    const double side = rng.bernoulli(0.5) ? 1.0 : -1.0;
    const double out = in_front ? shoulder * rng.uniform(0.9, 1.3) : shoulder * rng.uniform(0.2, 1.2) + leaf.a * 0.5;
    leaf.centre = centre + Eigen::Vector3d{side * out, rng.uniform(-0.45, 0.35) * length,
                                           in_front ? -rng.uniform(0.03, 0.05) : rng.uniform(0.01, 0.06)};
    const Eigen::Vector3d normal =
        (Eigen::AngleAxisd(rng.uniform(-0.8, 0.8), Eigen::Vector3d::UnitY()) *
         Eigen::AngleAxisd(rng.uniform(-0.6, 0.6), Eigen::Vector3d::UnitX()) * Eigen::Vector3d(0, 0, -1));
    leaf.e1 = normal.cross(Eigen::Vector3d::UnitY()).normalized();
    leaf.e2 = normal.cross(leaf.e1).normalized();
    const double spin = rng.uniform(0.0, kPi);
    const Eigen::Vector3d e1 = std::cos(spin) * leaf.e1 + std::sin(spin) * leaf.e2;
    leaf.e2 = normal.cross(e1).normalized();
    leaf.e1 = e1;
    leaf.color = jitter({0.105f, 0.235f, 0.165f}, 0.3, rng);
    scene.leaves.push_back(leaf);
  }
}

}  // namespace

GrapeScene build_grape_scene(const GrapeSimConfig& cfg, std::uint64_t seed) {
  Rng rng(derive_seed(seed, {0x67726170}));
  GrapeScene scene;
  scene.distance = rng.uniform(cfg.distance_min, cfg.distance_max);
  const double length = rng.uniform(cfg.bunch_length_min, cfg.bunch_length_max);
  const double shoulder = rng.uniform(cfg.bunch_radius_min, cfg.bunch_radius_max);
  // The bunch hangs about straight down, leaning a little sideways and toward or away from us.
  const Eigen::Vector3d axis{std::sin(rng.uniform(-0.15, 0.15)), 1.0, std::sin(rng.uniform(-0.15, 0.15))};
  scene.bunch_top = {rng.uniform(-0.03, 0.03), -length / 2 + rng.uniform(-0.02, 0.02), scene.distance};
  add_berries(scene, cfg, axis.normalized(), length, shoulder, rng);
  add_peduncle(scene, cfg, axis.normalized(), rng);
  add_leaves(scene, cfg, scene.bunch_top + axis.normalized() * (length / 2), length, shoulder, rng);
  scene.backdrop_z = scene.distance + rng.uniform(cfg.backdrop_min, cfg.backdrop_max);
  scene.backdrop_holes = cfg.backdrop_holes;
  scene.backdrop_seed = derive_seed(seed, {0x6261636b});
  return scene;
}

PixelRect grape_roi(const GrapeScene& scene, double focal_px) {
  double u_min = 1e9, u_max = -1e9, v_min = 1e9, v_max = -1e9;
  for (const GrapeSphere& s : scene.spheres) {
    const double z = s.centre.z(), r = s.radius * focal_px / z;
    const double u = s.centre.x() / z * focal_px, v = s.centre.y() / z * focal_px;
    v_min = std::min(v_min, v - r);  // the peduncle's top sets the ROI's top (Eq. 1)
    if (s.label != kGrapeBerry) continue;
    u_min = std::min(u_min, u - r);
    u_max = std::max(u_max, u + r);
    v_max = std::max(v_max, v + r);
  }
  const int margin = 3;
  PixelRect roi;
  roi.u0 = int(std::floor(u_min)) - margin;
  roi.v0 = int(std::floor(v_min)) - margin;
  roi.width = int(std::ceil(u_max)) + margin - roi.u0;
  roi.height = int(std::ceil(v_max)) + margin - roi.v0;
  return roi;
}

}  // namespace cropsight::sim::detail
