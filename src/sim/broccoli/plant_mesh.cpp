// Geometry of one broccoli plant: stem, outer leaves, inner leaves curling over the head, and the
// head as a dome of florets (or the stump of a harvested plant).
#include <algorithm>
#include <cmath>

#include "cropsight/sim/broccoli/broccoli_field.hpp"
#include "cropsight/sim/random.hpp"
#include "sim/angles.hpp"
#include "sim/leaf_mesh.hpp"
#include "sim/value_noise.hpp"

namespace cropsight::sim {

namespace {
constexpr double kGoldenAngle = 137.50776405 * kDeg;  // phyllotaxis of leaves and florets

Eigen::Vector3f light_direction(const SimLightConfig& L) {
  const double el = L.sun_elevation_deg * kDeg, az = L.sun_azimuth_deg * kDeg;
  return Eigen::Vector3d(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el)).cast<float>();
}

void add_cylinder(Mesh& m, const Eigen::Vector3d& bottom, double z_top, double radius, int sides,
                  const Eigen::Vector3f& color, float refl, SurfaceKind kind) {
  const int rings = 4;
  const auto first = std::uint32_t(m.position.size());
  for (int r = 0; r < rings; ++r) {
    const double z = bottom.z() + (z_top - bottom.z()) * r / (rings - 1);
    for (int k = 0; k < sides; ++k) {
      const double a = 2 * kPi * k / sides;
      m.add_vertex(
          Eigen::Vector3d(bottom.x() + radius * std::cos(a), bottom.y() + radius * std::sin(a), z).cast<float>(), color,
          refl);
    }
  }
  for (int r = 0; r + 1 < rings; ++r)
    for (int k = 0; k < sides; ++k) {
      const auto a = first + std::uint32_t(r * sides + k), b = first + std::uint32_t(r * sides + (k + 1) % sides);
      const auto c = b + std::uint32_t(sides), d = a + std::uint32_t(sides);
      m.add_triangle(a, b, c, 0, kind);
      m.add_triangle(a, c, d, 0, kind);
    }
}

/// The cut face of a harvested stem: a disc, slightly domed.
void add_disc(Mesh& m, const Eigen::Vector3d& center, double radius, const Eigen::Vector3f& color, float refl,
              SurfaceKind kind) {
  const int sides = 12;
  const auto c0 = m.add_vertex(center.cast<float>() + Eigen::Vector3f(0, 0, 0.003f), color, refl);
  for (int k = 0; k < sides; ++k) {
    const double a = 2 * kPi * k / sides;
    m.add_vertex(
        Eigen::Vector3d(center.x() + radius * std::cos(a), center.y() + radius * std::sin(a), center.z()).cast<float>(),
        color * 0.9f, refl);
  }
  for (int k = 0; k < sides; ++k)
    m.add_triangle(c0, c0 + 1 + std::uint32_t(k), c0 + 1 + std::uint32_t((k + 1) % sides), 0, kind);
}

struct Floret {
  Eigen::Vector3d center;
  double radius;
};

/// A head's dome in its own frame (origin = rim centre, z = axis): a half ellipsoid with semi-axes
/// a, b and height H, covered with florets on Vogel's spiral (the phyllotactic packing of real
/// florets) and fine beads (the buds).
struct HeadDome {
  double a, b, H, rf, hf, R;
  std::vector<Floret> florets;
  std::uint64_t bead_seed = 0;

  HeadDome(const HeadSpec& h, Rng& rng)
      : a(h.semi_a), b(h.semi_b), H(h.dome_height), rf(h.floret_radius), hf(h.floret_height * rf), R(0.5 * (a + b)) {
    const int n_florets = std::max(7, int(std::lround(1.3 * (R / rf) * (R / rf))));
    const double psi0 = rng.uniform(0.0, 2 * kPi);
    for (int k = 0; k < n_florets; ++k) {
      const double rho = std::sqrt((k + 0.5) / n_florets) * 1.02;
      florets.push_back({dome(rho, psi0 + k * kGoldenAngle), rf * rng.uniform(0.85, 1.2)});
    }
    bead_seed = rng.next();
  }
  Eigen::Vector3d dome(double rho, double psi) const {
    rho = std::min(rho, 1.0);
    return Eigen::Vector3d(a * rho * std::cos(psi), b * rho * std::sin(psi),
                           H * std::sqrt(std::max(0.0, 1 - rho * rho)));
  }
  // Bump height at a dome point: the highest floret cap over it, plus fine beads (the buds).
  double bump(const Eigen::Vector3d& p) const {
    double best = 0;
    for (const auto& f : florets) {
      const double d2 = (p - f.center).squaredNorm();
      if (d2 < f.radius * f.radius) best = std::max(best, std::sqrt(1 - d2 / (f.radius * f.radius)));
    }
    const double beads = 0.5 + 0.5 * detail::value_noise(bead_seed, p.x() / (0.22 * rf), p.y() / (0.22 * rf));
    return hf * best + 0.12 * hf * beads * best;
  }
  Eigen::Vector3d ellipsoid_normal(const Eigen::Vector3d& p) const {
    return Eigen::Vector3d(p.x() / (a * a), p.y() / (b * b), p.z() / (H * H)).normalized();
  }
};

/// The head's vertices in its own frame: the apex, then rings of constant elevation beta
/// (uniform spacing along the dome's profile, `sectors` vertices each), then `skirt` rings of
/// the underside; `bump_frac` receives each vertex's bump height as a fraction of a floret's.
struct HeadVertices {
  std::vector<Eigen::Vector3d> local;
  std::vector<double> bump_frac;
  int sectors, rings, skirt = 4;
};

HeadVertices head_vertices(const HeadDome& d) {
  const double a = d.a, b = d.b, H = d.H, R = d.R, hf = d.hf;
  HeadVertices v;
  const double spacing = d.rf / 4.0;
  v.sectors = std::max(24, int(std::ceil(2 * kPi * std::max(a, b) / spacing)));
  v.rings = std::max(6, int(std::ceil(0.5 * kPi * 0.5 * (R + H) / spacing)));
  const int sectors = v.sectors, rings = v.rings, skirt = v.skirt;
  auto& local = v.local;
  auto& bump_frac = v.bump_frac;
  local.push_back({0, 0, H + d.bump({0, 0, H})});
  bump_frac.push_back((local[0].z() - H) / hf);
  for (int i = 1; i <= rings + skirt; ++i) {
    for (int k = 0; k < sectors; ++k) {
      const double psi = 2 * kPi * k / sectors;
      if (i <= rings) {
        const double beta = 0.5 * kPi * (1.0 - double(i) / rings);
        const Eigen::Vector3d p(a * std::cos(beta) * std::cos(psi), b * std::cos(beta) * std::sin(psi),
                                H * std::sin(beta));
        const double bh = d.bump(p);
        local.push_back(p + d.ellipsoid_normal(p) * bh);
        bump_frac.push_back(bh / hf);
      } else {
        // Underside: from the rim inward and down to the stalk.
        const double tau = double(i - rings) / skirt;
        const Eigen::Vector3d rim(a * std::cos(psi), b * std::sin(psi), 0.0);
        const double shrink = 1.0 - 0.55 * tau;
        local.push_back(Eigen::Vector3d(rim.x() * shrink, rim.y() * shrink, -0.45 * R * tau) +
                        Eigen::Vector3d(rim.x(), rim.y(), 0).normalized() * (d.bump(rim) * (1 - tau)));
        bump_frac.push_back(0.2);
      }
    }
  }
  return v;
}

/// Scales the head so that the grower's diameter (mean of two perpendicular calipers) equals the
/// drawn one, places it (the apex of the smooth dome where plants() wanted it) and fills the
/// measured fields of `h`; returns the vertices in the field frame.
std::vector<Eigen::Vector3f> size_and_place(HeadSpec& h, std::vector<Eigen::Vector3d>& local) {
  std::vector<Eigen::Vector3f> lf(local.size());
  for (std::size_t i = 0; i < local.size(); ++i) lf[i] = local[i].cast<float>();
  auto [major, minor] = caliper_widths(lf, Eigen::Vector3f::Zero(), Eigen::Matrix3f::Identity());
  const double scale = 1e-3 * h.target_diameter_mm / (0.5 * (major + minor));
  for (auto& p : local) p *= scale;
  h.semi_a *= scale;
  h.semi_b *= scale;
  h.dome_height *= scale;
  h.floret_radius *= scale;
  const Eigen::Vector3d axis = h.orientation.col(2);
  h.base = h.apex - axis * h.dome_height;
  std::vector<Eigen::Vector3f> field(local.size());
  for (std::size_t i = 0; i < local.size(); ++i) field[i] = (h.base + h.orientation * local[i]).cast<float>();
  std::tie(major, minor) = caliper_widths(field, h.base.cast<float>(), h.orientation.cast<float>());
  h.caliper_major_mm = 1e3 * major;
  h.caliper_minor_mm = 1e3 * minor;
  h.diameter_mm = 0.5 * (h.caliper_major_mm + h.caliper_minor_mm);
  return field;
}

/// Builds the head in its own frame (origin = rim centre, z = axis), sizes it so that the mean
/// of the two caliper widths equals the drawn diameter, then places it on the plant.
void add_head(Mesh& m, HeadSpec& h, const SimHeadConfig& cfg, Rng& rng) {
  const HeadDome dome(h, rng);
  HeadVertices v = head_vertices(dome);
  const std::vector<Eigen::Vector3f> field = size_and_place(h, v.local);
  const int sectors = v.sectors, rings = v.rings, skirt = v.skirt;

  const auto first = std::uint32_t(m.position.size());
  const Eigen::Vector3f underside(125, 145, 95);
  for (std::size_t i = 0; i < field.size(); ++i) {
    const bool under = i >= std::size_t(1 + rings * sectors);
    const float f = float(std::clamp(v.bump_frac[i], 0.0, 1.0));
    // Crevices between florets are darker (self-shadowing), floret tops lighter.
    Eigen::Vector3f c = (under ? underside : h.color) * (0.55f + 0.6f * f) * float(rng.uniform(0.9, 1.1));
    m.add_vertex(field[i], c, 0.45f);
  }
  const std::uint16_t id = std::uint16_t(h.id);
  for (int k = 0; k < sectors; ++k)
    m.add_triangle(first, first + 1 + std::uint32_t(k), first + 1 + std::uint32_t((k + 1) % sectors), id,
                   SurfaceKind::head);
  for (int i = 1; i < rings + skirt; ++i)
    for (int k = 0; k < sectors; ++k) {
      const auto r0 = first + 1 + std::uint32_t((i - 1) * sectors), r1 = r0 + std::uint32_t(sectors);
      const auto k1 = std::uint32_t((k + 1) % sectors);
      m.add_triangle(r0 + std::uint32_t(k), r1 + std::uint32_t(k), r1 + k1, id, SurfaceKind::head);
      m.add_triangle(r0 + std::uint32_t(k), r1 + k1, r0 + k1, id, SurfaceKind::head);
    }
  (void)cfg;
}

/// Moves an outer leaf down the stem so that its midrib leaves the head's outline (`radius` from
/// the stem axis `axis`) at or below `z_max`. A leaf too steep to get there while attached above
/// kMinAttachZ leans outward in 5-degree steps: a petiole growing below a head wider than the
/// stem has to go out before it can rise past the head.
void keep_below_rim(detail::LeafShape& L, const Eigen::Vector2d& axis, double radius, double z_max) {
  constexpr double kMinAttachZ = 0.05;  // lowest leaf base above soil, as drawn for the oldest leaves
  for (int tries = 0; tries < 12; ++tries) {
    const double z_out = detail::midrib_z_at_radius(L, axis, radius);
    if (std::isnan(z_out) || z_out <= z_max) return;
    const double z_start = L.start.z() - (z_out - z_max);
    if (z_start >= kMinAttachZ) {
      L.start.z() = z_start;
      return;
    }
    L.elevation0 -= 5 * kDeg;
    L.elevation1 -= 5 * kDeg;
  }
  L.start.z() = kMinAttachZ;
}

Eigen::Vector3f leaf_color(Rng& rng) {
  // Waxy, glaucous blue-green of brassica leaves; some older leaves yellower.
  const float g = float(rng.uniform(0.85, 1.12));
  Eigen::Vector3f c(float(rng.uniform(88, 104)) * g, float(rng.uniform(122, 140)) * g,
                    float(rng.uniform(112, 132)) * g);
  if (rng.bernoulli(0.12)) c = 0.7f * c + 0.3f * Eigen::Vector3f(165, 160, 85);
  return c;
}

// Outer leaf i of n (rank 0 = oldest): older ones low on the stem, long and spreading; younger
// higher and steeper. Draws from `rng` in a fixed order.
detail::LeafShape outer_leaf(const SimPlantConfig& P, Rng& rng, int i, int n, double az0, const Eigen::Vector3d& foot,
                             double attach_top) {
  const double rank = n > 1 ? double(i) / (n - 1) : 0.5;  // 0 = oldest
  detail::LeafShape L;
  L.azimuth = az0 + i * kGoldenAngle + rng.normal(0.0, 10 * kDeg);
  L.yaw_bend = rng.normal(0.0, 12 * kDeg);
  const double z = 0.05 + (attach_top - 0.05) * std::clamp(rank + rng.normal(0.0, 0.08), 0.0, 1.0);
  L.start = foot + Eigen::Vector3d(std::cos(L.azimuth), std::sin(L.azimuth), 0) * P.stem_radius_m +
            Eigen::Vector3d(0, 0, z - foot.z());
  L.length = rng.uniform(P.leaf_length_min_m, P.leaf_length_max_m) * (1.05 - 0.2 * rank);
  L.width = L.length * P.leaf_width_ratio * rng.uniform(0.85, 1.15);
  L.petiole = rng.uniform(0.15, 0.28);
  L.blade_exponent = P.leaf_blade_exponent;
  L.blade_fullness = P.leaf_blade_fullness;
  L.elevation0 = (rng.uniform(P.leaf_elevation_min_deg, P.leaf_elevation_max_deg) + 10 * rank) * kDeg;
  L.elevation1 = L.elevation0 - rng.uniform(P.leaf_droop_min_deg, P.leaf_droop_max_deg) * kDeg;
  L.bend_power = rng.uniform(1.2, 2.2);
  L.cup = P.leaf_cup * rng.uniform(0.5, 1.5);
  L.ruffle = P.leaf_ruffle_m * rng.uniform(0.5, 1.5);
  L.twist = rng.normal(0.0, 15 * kDeg);
  L.color = leaf_color(rng);
  L.reflectivity = float(rng.uniform(0.5, 0.6));
  return L;
}

// An inner leaf: young, hugging the head (outside its outline at `out` from the stem axis),
// rising past it and curling back over its rim. Draws from `rng` in a fixed order.
detail::LeafShape inner_leaf(const SimPlantConfig& P, Rng& rng, const PlantSpec& spec, double stem_top, double head_r,
                             double rim_radius) {
  detail::LeafShape L;
  L.azimuth = rng.uniform(0.0, 2 * kPi);
  L.yaw_bend = rng.normal(0.0, 15 * kDeg);
  // Outside the head's outline (widest semi-axis plus floret bumps): a leaf cannot grow through
  // the head, and one that did would join the head's surface without any depth step.
  const double gap = rng.uniform(0.003, std::max(0.003, P.inner_leaf_gap_max_m));
  const double out = spec.has_head ? rim_radius + spec.head.floret_height * spec.head.floret_radius + gap
                                   : head_r * rng.uniform(0.9, 1.2) + 0.01;
  L.start = Eigen::Vector3d(spec.xy.x(), spec.xy.y(), stem_top - rng.uniform(0.0, 0.06)) +
            Eigen::Vector3d(std::cos(L.azimuth), std::sin(L.azimuth), 0) * out;
  L.length = rng.uniform(P.inner_leaf_length_min_m, P.inner_leaf_length_max_m);
  L.width = L.length * rng.uniform(0.45, 0.6);
  L.petiole = 0.08;
  L.blade_exponent = P.leaf_blade_exponent;
  L.blade_fullness = P.leaf_blade_fullness;
  L.elevation0 = rng.uniform(72, 88) * kDeg;
  L.elevation1 = rng.uniform(P.inner_leaf_curl_min_deg, P.inner_leaf_curl_max_deg) * kDeg;
  L.bend_power = rng.uniform(1.3, 2.0);
  L.cup = P.leaf_cup * rng.uniform(0.8, 1.8);
  L.ruffle = P.leaf_ruffle_m * rng.uniform(0.3, 1.0);
  L.twist = rng.normal(0.0, 20 * kDeg);
  L.color = leaf_color(rng) * 1.05f;
  L.reflectivity = float(rng.uniform(0.5, 0.6));
  return L;
}

}  // namespace

std::shared_ptr<const Mesh> BroccoliField::build_plant(PlantSpec& spec) const {
  const auto& P = cfg_.plant;
  Rng rng(spec.seed);
  auto mesh = std::make_shared<Mesh>();
  Mesh& m = *mesh;
  const Eigen::Vector3d foot(spec.xy.x(), spec.xy.y(), soil_base_height(spec.xy.x(), spec.xy.y()) - 0.02);
  // The head first: its final size and rim height decide where the leaves may pass.
  if (spec.has_head) add_head(m, spec.head, cfg_.head, rng);
  const double head_r = spec.has_head ? 0.5e-3 * spec.head.target_diameter_mm : 0.05;
  const double apex_z = spec.has_head ? spec.head.apex.z() : spec.stump_height + 0.1;
  const double stem_top = spec.has_head ? apex_z - 0.5 * head_r : spec.stump_height;

  // Stem (or stump with its cut face).
  add_cylinder(m, foot, stem_top, P.stem_radius_m * (spec.has_head ? 1.0 : 1.3), 10, {150, 170, 118}, 0.6f,
               spec.has_head ? SurfaceKind::stem : SurfaceKind::stump);
  if (!spec.has_head)
    add_disc(m, {foot.x(), foot.y(), stem_top}, P.stem_radius_m * 1.3, {214, 214, 172}, 0.7f, SurfaceKind::stump);

  // Outer leaves: older ones low on the stem, long and spreading; younger higher and steeper.
  const int n = rng.uniform_int(P.leaf_count_min, P.leaf_count_max);
  const double az0 = rng.uniform(0.0, 2 * kPi);
  const double attach_top = std::max(0.08, stem_top - 0.06);
  // Rim step: where an outer leaf's midrib leaves the head's outline it must lie a drawn step
  // below the lowest point of the (tilted) rim; leaves drawn higher are moved down the stem.
  double rim_low = 0, rim_radius = 0;
  if (spec.has_head) {
    const HeadSpec& h = spec.head;
    rim_radius = std::max(h.semi_a, h.semi_b);
    rim_low = h.base.z() - rim_radius * std::sin(h.tilt_deg * kDeg);
  }
  for (int i = 0; i < n; ++i) {
    detail::LeafShape L = outer_leaf(P, rng, i, n, az0, foot, attach_top);
    const bool touches = rng.bernoulli(P.leaf_rim_touch_prob);
    const double step = touches ? 0.0 : rng.uniform(P.leaf_rim_step_min_m, P.leaf_rim_step_max_m);
    if (spec.has_head) keep_below_rim(L, spec.xy, rim_radius + P.leaf_rim_clearance_m, rim_low - step);
    detail::add_leaf(m, L, SurfaceKind::leaf, rng);
  }

  // Inner leaves: young leaves hugging the head, rising past it and curling back over its rim;
  // their tips are often the highest points of the plant ("some leaf tips above the head").
  const int n_inner = rng.uniform_int(P.inner_leaves_min, P.inner_leaves_max) / (spec.has_head ? 1 : 2);
  for (int i = 0; i < n_inner; ++i) {
    const detail::LeafShape L = inner_leaf(P, rng, spec, stem_top, head_r, rim_radius);
    detail::add_leaf(m, L, SurfaceKind::leaf, rng);
  }

  m.compute_normals();
  m.shade(light_direction(cfg_.light), float(cfg_.light.ambient));
  return mesh;
}

std::pair<double, double> caliper_widths(const std::vector<Eigen::Vector3f>& points, const Eigen::Vector3f& center,
                                         const Eigen::Matrix3f& head_to_field) {
  // Coordinates in the head's own plane (orthogonal to its axis).
  std::vector<Eigen::Vector2f> q(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3f l = head_to_field.transpose() * (points[i] - center);
    q[i] = {l.x(), l.y()};
  }
  auto width = [&](double theta) {
    const float c = float(std::cos(theta)), s = float(std::sin(theta));
    float lo = 1e9f, hi = -1e9f;
    for (const auto& p : q) {
      const float d = c * p.x() + s * p.y();
      lo = std::min(lo, d);
      hi = std::max(hi, d);
    }
    return double(hi - lo);
  };
  double best = -1, best_theta = 0;
  for (int k = 0; k < 360; ++k) {
    const double th = k * 0.5 * kDeg;
    const double w = width(th);
    if (w > best) best = w, best_theta = th;
  }
  return {best, width(best_theta + 0.5 * kPi)};
}

}  // namespace cropsight::sim
