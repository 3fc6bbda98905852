// Seedling scenes: geometry of the seedling and the weeds, camera pose, rendering of the stereo
// pair and its ground truth.
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include "cropsight/core/error.hpp"
#include "cropsight/sim/seedling/seedling_sim.hpp"
#include "seedling_render.hpp"
#include "sim/angles.hpp"

namespace cropsight::sim {

using namespace seedling_detail;

namespace {

// Portable uniform numbers from a fixed generator (std distributions differ between libraries).
struct Uniform {
  std::mt19937_64 g;
  explicit Uniform(std::uint64_t s) : g(s) {}
  double operator()(double a, double b) { return a + (b - a) * double(g() >> 11) * (1.0 / 9007199254740992.0); }
  int integer(int a, int b) { return std::min(b, a + int((*this)(0, 1) * (b - a + 1))); }
  double normal() {  // Box-Muller
    const double u1 = std::max((*this)(0, 1), 1e-300), u2 = (*this)(0, 1);
    return std::sqrt(-2 * std::log(u1)) * std::cos(2 * kPi * u2);
  }
};

/// One leaf (petiole + elliptic blade) as a grid of quads. `base`: attachment point; `azimuth`:
/// direction in the ground plane; `elev`: rise angle; `droop`: m of sag per m^2 of length.
void add_leaf(SMesh& m, const Eigen::Vector3d& base, double azimuth, double elev, double petiole, double length,
              double width, double droop, double cup, std::uint8_t mat, std::uint16_t label,
              const Eigen::Vector3f& color, int ns = 14, int nt = 6) {
  const Eigen::Vector3d dir(std::cos(azimuth), std::sin(azimuth), 0), side(-std::sin(azimuth), std::cos(azimuth), 0);
  auto axis = [&](double r) -> Eigen::Vector3d {  // point on the midrib at distance r from the base
    return base + dir * (r * std::cos(elev)) + Eigen::Vector3d(0, 0, r * std::sin(elev) - droop * r * r);
  };
  // Petiole: a narrow strip (3 mm).
  if (petiole > 0) {
    const std::uint32_t first = std::uint32_t(m.p.size());
    for (int i = 0; i <= 3; ++i) {
      const double r = petiole * i / 3.0;
      for (int j = 0; j < 2; ++j)
        m.add((axis(r) + side * (j ? 0.0015 : -0.0015)).cast<float>(), Eigen::Vector2f(0, j ? 0.1f : -0.1f));
    }
    for (int i = 0; i < 3; ++i) {
      const std::uint32_t a = first + 2 * i;
      m.face(a, a + 1, a + 2, mat, label, color * 1.1f);
      m.face(a + 1, a + 3, a + 2, mat, label, color * 1.1f);
    }
  }
  const std::uint32_t first = std::uint32_t(m.p.size());
  for (int i = 0; i <= ns; ++i) {
    const double s = double(i) / ns;
    const double half = 0.5 * width * std::pow(std::sin(kPi * std::clamp(s, 0.02, 0.98)), 0.7);
    const Eigen::Vector3d c = axis(petiole + s * length);
    for (int j = 0; j <= nt; ++j) {
      const double t = -1.0 + 2.0 * j / nt;
      const Eigen::Vector3d q = c + side * (t * half) + Eigen::Vector3d(0, 0, cup * t * t * half);
      m.add(q.cast<float>(), Eigen::Vector2f(float(s), float(t)));
    }
  }
  for (int i = 0; i < ns; ++i)
    for (int j = 0; j < nt; ++j) {
      const std::uint32_t a = first + i * (nt + 1) + j, b = a + 1, c = a + nt + 1, d = c + 1;
      m.face(a, b, c, mat, label, color);
      m.face(b, d, c, mat, label, color);
    }
}

/// Vertical stem as a 6-sided prism.
void add_stem(SMesh& m, const Eigen::Vector3d& base, double height, double radius, std::uint16_t label,
              const Eigen::Vector3f& color) {
  const std::uint32_t first = std::uint32_t(m.p.size());
  for (int k = 0; k < 6; ++k) {
    const double a = 2 * kPi * k / 6;
    const Eigen::Vector3d o(radius * std::cos(a), radius * std::sin(a), 0);
    m.add((base + o).cast<float>(), Eigen::Vector2f(0, 0));
    m.add((base + o + Eigen::Vector3d(0, 0, height)).cast<float>(), Eigen::Vector2f(1, 0));
  }
  for (int k = 0; k < 6; ++k) {
    const std::uint32_t a = first + 2 * k, b = first + 2 * ((k + 1) % 6);
    m.face(a, b, a + 1, kStem, label, color);
    m.face(b, b + 1, a + 1, kStem, label, color);
  }
}

Eigen::Vector3f jitter_green(Uniform& u, double r, double g, double b) {
  return Eigen::Vector3f(float(r * u(0.85, 1.15)), float(g * u(0.9, 1.1)), float(b * u(0.85, 1.15)));
}

/// The seedling (label 1) at `c`; returns its radius in the ground plane.
double add_seedling(SMesh& m, Uniform& u, const Eigen::Vector3d& c, int leaves) {
  const double stem_h = u(0.02, 0.04);
  const Eigen::Vector3f stem_col = jitter_green(u, 120, 150, 80);
  add_stem(m, c, stem_h, 0.0025, 1, stem_col);
  const Eigen::Vector3f leaf_col = jitter_green(u, 62, 118, 52);
  const double phi0 = u(0, 2 * kPi);
  double radius = 0;
  for (int i = 0; i < leaves; ++i) {
    const double age = double(leaves - i) / leaves;  // older leaves: longer, flatter
    const double length = u(0.035, 0.05) + 0.025 * age;
    const double width = length * u(0.55, 0.75);
    const double petiole = u(0.012, 0.025) * (0.6 + 0.6 * age);
    const double elev = (u(55, 70) - 35 * age) * kPi / 180;
    const double az = phi0 + i * 137.5 * kPi / 180 + u(-0.2, 0.2);
    const Eigen::Vector3d base = c + Eigen::Vector3d(0, 0, stem_h - 0.004 * i);
    add_leaf(m, base, az, elev, petiole, length, width, u(0.5, 2.5), u(0.1, 0.3), kLeaf, 1,
             leaf_col.cwiseProduct(Eigen::Vector3f(float(u(0.93, 1.07)), float(u(0.95, 1.05)), 1.0f)));
    radius = std::max(radius, (petiole + length) * std::cos(elev));
  }
  return radius;
}

/// A weed at `c` (label 0): a flat rosette, or a tuft of narrow upright grass blades.
void add_weed(SMesh& m, Uniform& u, const Eigen::Vector3d& c, bool grass) {
  const Eigen::Vector3f col = jitter_green(u, 70, 126, 56);  // similar to the seedling's green
  if (grass) {
    const int blades = u.integer(4, 9);
    for (int i = 0; i < blades; ++i) {
      const double len = u(0.03, 0.06);
      add_leaf(m, c, u(0, 2 * kPi), u(25, 50) * kPi / 180, 0, len, u(0.003, 0.006), u(4, 10), 0, kWeed, 0, col, 8, 2);
    }
    return;
  }
  const int leaves = u.integer(3, 7);
  const double phi0 = u(0, 2 * kPi);
  for (int i = 0; i < leaves; ++i) {
    const double len = u(0.012, 0.035);
    add_leaf(m, c + Eigen::Vector3d(0, 0, 0.002), phi0 + i * 2 * kPi / leaves + u(-0.3, 0.3), u(5, 25) * kPi / 180,
             u(0, 0.006), len, len * u(0.4, 0.8), u(1, 4), u(0, 0.2), kWeed, 0, col, 8, 4);
  }
}

}  // namespace

StereoRigModel SeedlingSimConfig::rig() const {
  StereoRigModel r;
  r.width = width;
  r.height = height;
  r.f = 0.5 * width / std::tan(0.5 * hfov_deg * kPi / 180);
  r.cx = 0.5 * width - 0.5;
  r.cy = 0.5 * height - 0.5;
  r.T = Eigen::Vector3d(-baseline, 0, 0);
  return r;
}

namespace {

void check_config(const SeedlingSimConfig& cfg) {
  const std::string where = "seedling simulator";
  if (cfg.width < 32 || cfg.height < 32) throw Error(where, "image size too small");
  if (!(cfg.hfov_deg > 10 && cfg.hfov_deg < 170)) throw Error(where, "hfov_deg must be in (10, 170)");
  if (!(cfg.baseline > 0)) throw Error(where, "baseline must be positive");
  if (!(cfg.distance_min > 0.1 && cfg.distance_max >= cfg.distance_min))
    throw Error(where, "need 0.1 < distance_min <= distance_max");
  if (cfg.leaves_min < 1 || cfg.leaves_max < cfg.leaves_min) throw Error(where, "invalid leaf count range");
  if (cfg.weeds_min < 0 || cfg.weeds_max < cfg.weeds_min) throw Error(where, "invalid weed count range");
  if (cfg.supersample < 1 || cfg.supersample > 8) throw Error(where, "supersample must be in 1..8");
}

// One view of the scene: supersampled shading times the exposure gain, plus sensor noise drawn
// from its own generator (seeded by the caller, so the two views' noise is independent).
ColorImage render_view(const SMesh& mesh, const View& v, const SeedlingSimConfig& cfg, double gain,
                       std::uint64_t tex_seed, std::uint64_t noise_seed) {
  const int ss = cfg.supersample;
  Samples s;
  rasterize(mesh, v, ss, s);
  ColorImage img(v.width, v.height);
  Uniform nu(noise_seed);
  for (int y = 0; y < v.height; ++y)
    for (int x = 0; x < v.width; ++x) {
      Eigen::Vector3f acc = Eigen::Vector3f::Zero();
      for (int j = 0; j < ss; ++j)
        for (int i = 0; i < ss; ++i) acc += sample_color(mesh, s, (y * ss + j) * s.w + x * ss + i, tex_seed);
      acc *= float(gain / (ss * ss));
      auto ch = [&](float c) {
        return std::uint8_t(std::clamp(std::lround(c + cfg.noise_sigma * nu.normal()), 0L, 255L));
      };
      img.at(x, y) = Rgb8{ch(acc.x()), ch(acc.y()), ch(acc.z())};
    }
  return img;
}

// Ground truth of the left view (disparity and seedling mask at pixel centres), the soil plane and
// the seedling's envelope box in the left camera frame: x_c = R_cw^T (x_w - C).
void set_ground_truth(SeedlingPair& out, const SMesh& mesh, std::size_t seedling_vertices, const StereoRigModel& rig,
                      const View& vl, const Eigen::Matrix3d& R_cw, const Eigen::Vector3d& C,
                      const Eigen::Vector3d& seedling) {
  Samples g;
  rasterize(mesh, vl, 1, g);
  out.disparity = Image<float>(rig.width, rig.height, std::numeric_limits<float>::quiet_NaN());
  out.mask = GrayImage(rig.width, rig.height, 0);
  for (int i = 0; i < rig.width * rig.height; ++i) {
    if (std::isfinite(g.depth[i])) out.disparity.data[i] = float(rig.f * rig.baseline() / g.depth[i]);
    if (g.tri[i] >= 0 && mesh.label[std::size_t(g.tri[i])] == 1) out.mask.data[i] = 255;
  }
  const Eigen::Matrix3d R_wc = R_cw.transpose();
  out.plane_normal = R_wc * Eigen::Vector3d::UnitZ();
  out.plane_d = C.z();  // n_c . x_c = z_w - C_z
  out.seedling_base = R_wc * (seedling - C);
  std::vector<Eigen::Vector3d> verts;
  for (std::size_t k = 0; k < seedling_vertices; ++k) verts.push_back(R_wc * (mesh.p[k].cast<double>() - C));
  out.envelope = measure::envelope_box(verts, out.plane_normal, out.plane_d);
}

}  // namespace

SeedlingPair simulate_seedling_pair(const SeedlingSimConfig& cfg, std::uint64_t seed, int index) {
  check_config(cfg);

  Uniform u(seed * 0x9E3779B97F4A7C15ull + std::uint64_t(index) * 0xD1B54A32D192ED03ull + 1);
  const StereoRigModel rig = cfg.rig();
  SeedlingPair out;
  out.distance = u(cfg.distance_min, cfg.distance_max);
  out.tilt_deg = u(0, cfg.tilt_max_deg);
  const double roll = u(-5, 5) * kPi / 180, yaw = u(0, 2 * kPi);
  out.exposure = u(0, 1) < cfg.overexposed_fraction ? u(1.8, 2.6) : u(cfg.exposure_min, cfg.exposure_max);
  out.leaves = u.integer(cfg.leaves_min, cfg.leaves_max);
  out.weeds = u.integer(cfg.weeds_min, cfg.weeds_max);

  // Camera: nadir (camera z = world -z, camera x = world x rotated by yaw), then pitched forward
  // by the tilt and rolled; the optical axis hits the soil near the seedling.
  const Eigen::Matrix3d nadir = (Eigen::Matrix3d() << 1, 0, 0, 0, -1, 0, 0, 0, -1).finished();
  const Eigen::Matrix3d R_cw =
      Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix() * nadir *
      Eigen::AngleAxisd(out.tilt_deg * kPi / 180, Eigen::Vector3d::UnitX()).toRotationMatrix() *
      Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Vector3d axis = R_cw.col(2);  // optical axis in the world
  const Eigen::Vector3d seedling(u(-0.04, 0.04), u(-0.04, 0.04), 0);
  const Eigen::Vector3d C = seedling - axis * out.distance;  // camera centre
  // Rectified rig: the right camera is offset along the left camera's x axis.
  const Eigen::Vector3d C_right = C + R_cw * (-rig.R.transpose() * rig.T);

  SMesh mesh;
  const double radius = add_seedling(mesh, u, seedling, out.leaves);
  const std::size_t seedling_vertices = mesh.p.size();
  // Weeds spread over the visible soil (about +-0.6 x distance around the seedling), not on it.
  for (int placed = 0, tries = 0; placed < out.weeds && tries < 1000; ++tries) {
    const double span = 0.6 * out.distance;
    const Eigen::Vector3d c = seedling + Eigen::Vector3d(u(-span, span), u(-span, span), 0);
    if ((c - seedling).norm() < radius + 0.03) continue;
    add_weed(mesh, u, c, u(0, 1) < cfg.grass_fraction);
    ++placed;
  }

  View vl{R_cw, C, rig.f, rig.cx, rig.cy, rig.width, rig.height};
  View vr = vl;
  vr.C = C_right;
  const std::uint64_t tex_seed = seed * 31 + std::uint64_t(index);
  const double gain_right = u(0.97, 1.03);  // the two sensors never match exactly
  std::mt19937_64 noise_rng(tex_seed ^ 0xABCDEFull);
  // Left first: each view draws its noise seed from noise_rng in this order.
  out.left = render_view(mesh, vl, cfg, out.exposure * 1.0, tex_seed, noise_rng());
  out.right = render_view(mesh, vr, cfg, out.exposure * gain_right, tex_seed, noise_rng());

  set_ground_truth(out, mesh, seedling_vertices, rig, vl, R_cw, C, seedling);
  return out;
}

}  // namespace cropsight::sim
