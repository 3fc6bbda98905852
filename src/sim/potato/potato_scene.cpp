// Potatoes (bumpy, textured ellipsoids with eyes and sprouts) on strings among roots in front of a
// backdrop (sheet, room or root chamber). World frame: x down, y right, z toward the camera.
#include "sim/potato/potato_scene.hpp"

#include <cmath>

#include "cropsight/sim/random.hpp"
#include "sim/value_noise.hpp"

namespace cropsight::sim::detail {
namespace {

using V3 = Eigen::Vector3f;

// An axis-aligned quad (two triangles) with a flat colour.
void add_quad(Mesh& m, const V3& a, const V3& b, const V3& c, const V3& d, const V3& color, SurfaceKind kind) {
  const auto i0 = m.add_vertex(a, color, 0.8f), i1 = m.add_vertex(b, color, 0.8f);
  const auto i2 = m.add_vertex(c, color, 0.8f), i3 = m.add_vertex(d, color, 0.8f);
  m.add_triangle(i0, i1, i2, 0, kind);
  m.add_triangle(i0, i2, i3, 0, kind);
}

// A box [lo, hi] (its six faces).
void add_box(Mesh& m, const V3& lo, const V3& hi, const V3& color) {
  const V3 p[8] = {{lo.x(), lo.y(), lo.z()}, {hi.x(), lo.y(), lo.z()}, {hi.x(), hi.y(), lo.z()},
                   {lo.x(), hi.y(), lo.z()}, {lo.x(), lo.y(), hi.z()}, {hi.x(), lo.y(), hi.z()},
                   {hi.x(), hi.y(), hi.z()}, {lo.x(), hi.y(), hi.z()}};
  const int f[6][4] = {{0, 1, 2, 3}, {4, 5, 6, 7}, {0, 1, 5, 4}, {2, 3, 7, 6}, {1, 2, 6, 5}, {0, 3, 7, 4}};
  for (const auto& q : f) add_quad(m, p[q[0]], p[q[1]], p[q[2]], p[q[3]], color, SurfaceKind::soil);
}

// A thin tube along a polyline: a square prism per segment (strings, roots, sprouts).
void add_tube(Mesh& m, const std::vector<V3>& pts, float radius, const V3& color, std::uint16_t label,
              SurfaceKind kind) {
  for (std::size_t s = 0; s + 1 < pts.size(); ++s) {
    const V3 a = pts[s], b = pts[s + 1], d = (b - a).normalized();
    V3 u = d.cross(V3(0, 0, 1));
    if (u.norm() < 1e-3f) u = d.cross(V3(0, 1, 0));
    u.normalize();
    const V3 w = d.cross(u).normalized();
    std::uint32_t ring[2][4];
    for (int e = 0; e < 2; ++e)
      for (int k = 0; k < 4; ++k) {
        const float an = float(k) * 1.5707963f;
        const V3 off = radius * (std::cos(an) * u + std::sin(an) * w);
        ring[e][k] = m.add_vertex((e ? b : a) + off, color, 0.5f);
      }
    for (int k = 0; k < 4; ++k) {
      const int k1 = (k + 1) % 4;
      m.add_triangle(ring[0][k], ring[1][k], ring[1][k1], label, kind);
      m.add_triangle(ring[0][k], ring[1][k1], ring[0][k1], label, kind);
    }
  }
}

// A potato: a UV ellipsoid with low-frequency bumps (a few % of the radius), a russet texture
// with darker eyes, and sprouts growing from a few eyes.
void add_potato(Mesh& m, const PotatoSpec& p, std::uint64_t seed, float light) {
  Rng rng(seed);
  const int nu = 48, nv = 32;
  const V3 base(float(rng.uniform(165, 200)), float(rng.uniform(125, 155)), float(rng.uniform(80, 105)));
  const std::uint32_t first = std::uint32_t(m.position.size());
  for (int j = 0; j <= nv; ++j) {
    const double th = M_PI * j / nv;
    for (int i = 0; i < nu; ++i) {
      const double ph = 2 * M_PI * i / nu;
      const Eigen::Vector3d unit(std::cos(th), std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph));
      const double bump = 1.0 + 0.03 * fbm(seed, 2.0 * th, 2.0 * ph, 2);
      const Eigen::Vector3d local(0.5 * p.length * unit.x(), 0.5 * p.width * unit.y(), 0.5 * p.thickness * unit.z());
      const Eigen::Vector3d pos = p.centre + p.axes * (bump * local);
      const double tex = fbm(seed + 7, 6.0 * th, 6.0 * ph, 3);
      const double eye = fbm(seed + 11, 9.0 * th, 9.0 * ph, 1) > 0.6 ? 0.6 : 1.0;
      const float shade = float((0.9 + 0.15 * tex) * eye) * light;
      m.add_vertex(pos.cast<float>(), base * shade, 0.6f);
    }
  }
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const std::uint32_t a = first + std::uint32_t(j * nu + i), b = first + std::uint32_t(j * nu + (i + 1) % nu);
      const std::uint32_t c = a + std::uint32_t(nu), d = b + std::uint32_t(nu);
      m.add_triangle(a, c, d, std::uint16_t(p.id), SurfaceKind::head);
      m.add_triangle(a, d, b, std::uint16_t(p.id), SurfaceKind::head);
    }
  // Sprouts: short whitish-purple tubes along the surface normal.
  for (int s = 0; s < p.sprouts; ++s) {
    const double th = rng.uniform(0.3, M_PI - 0.3), ph = rng.uniform(0, 2 * M_PI);
    const Eigen::Vector3d unit(std::cos(th), std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph));
    const Eigen::Vector3d local(0.5 * p.length * unit.x(), 0.5 * p.width * unit.y(), 0.5 * p.thickness * unit.z());
    const Eigen::Vector3d root = p.centre + p.axes * local;
    const Eigen::Vector3d n =
        (p.axes * Eigen::Vector3d(unit.x() / p.length, unit.y() / p.width, unit.z() / p.thickness)).normalized();
    const double len = rng.uniform(0.004, 0.012);
    add_tube(m, {root.cast<float>(), (root + len * n).cast<float>()}, 0.0015f, V3(220, 190, 210) * light,
             std::uint16_t(p.id), SurfaceKind::head);
  }
}

// A root hanging from above with a gentle random sway; white-beige (aeroponic roots) or brown.
std::vector<V3> hanging_polyline(Rng& rng, double y, double z, double x_top, double x_bottom) {
  std::vector<V3> pts;
  double yy = y, zz = z;
  for (double x = x_top; x < x_bottom; x += 0.04) {
    pts.emplace_back(float(x), float(yy), float(zz));
    yy += rng.normal(0, 0.006);
    zz += rng.normal(0, 0.003);
  }
  return pts;
}

}  // namespace

PotatoSceneModel build_potato_scene(const PotatoSimConfig& cfg, std::uint64_t seed) {
  Rng rng(derive_seed(seed, {1}));
  PotatoSceneModel scene;
  const float light = cfg.scene == PotatoScene::chamber ? 0.45f : 1.0f;
  // Potatoes at 0.15-0.3 m in front of the backdrop, spread over the view, at least 0.12 m apart.
  for (int k = 0; k < cfg.potatoes; ++k) {
    PotatoSpec p;
    p.id = k + 1;
    for (int attempt = 0; attempt < 200; ++attempt) {
      p.centre = k == 0 ? Eigen::Vector3d(rng.uniform(-0.05, 0.05), rng.uniform(-0.05, 0.05), rng.uniform(0.2, 0.3))
                        : Eigen::Vector3d(rng.uniform(-0.15, 0.15), rng.uniform(-0.3, 0.3), rng.uniform(0.15, 0.3));
      bool ok = true;
      for (const auto& q : scene.potatoes) ok = ok && (q.centre - p.centre).norm() > 0.13;
      if (ok) break;
    }
    p.length = rng.uniform(cfg.length_min_m, cfg.length_max_m);
    p.width = p.length * rng.uniform(cfg.width_ratio_min, cfg.width_ratio_max);
    p.thickness = p.width * rng.uniform(0.85, 1.0);
    // Length axis: any angle in the image plane, tilted at most 20 deg toward the camera.
    const double a = rng.uniform(0, M_PI), tilt = rng.uniform(-0.35, 0.35), roll = rng.uniform(0, M_PI);
    p.axes = (Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(tilt, Eigen::Vector3d::UnitY()) *
              Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
                 .toRotationMatrix();
    p.sprouts = rng.uniform_int(0, cfg.sprouts_max);
    scene.potatoes.push_back(p);
  }
  Mesh& m = scene.mesh;
  for (const auto& p : scene.potatoes) {
    add_potato(m, p, derive_seed(seed, {2, p.id}), light);
    // The string: from the ceiling to the potato's top.
    const Eigen::Vector3d top = p.centre - Eigen::Vector3d(0.35 * std::max(p.width, p.thickness), 0, 0);
    add_tube(m, {V3(-1.0f, float(top.y()), float(top.z())), top.cast<float>()}, 0.001f, V3(120, 85, 55) * light, 0,
             SurfaceKind::stem);
  }
  // Roots: hanging across the scene between the backdrop and the potatoes' fronts.
  for (int r = 0; r < cfg.roots; ++r) {
    const double y = rng.uniform(-0.5, 0.5), z = rng.uniform(0.05, 0.35);
    const bool brown = rng.bernoulli(0.4);
    const V3 c = (brown ? V3(130, 95, 60) : V3(225, 215, 190)) * light;
    add_tube(m, hanging_polyline(rng, y, z, -1.0, rng.uniform(-0.1, 0.6)), float(rng.uniform(0.0008, 0.002)), c, 0,
             SurfaceKind::stem);
  }
  // A root 2 cm in front of a potato, within 0.3 widths of its centre line.
  const auto root_in_front = [&](Rng& r, const PotatoSpec& t) {
    const double front = t.centre.z() + 0.5 * t.thickness + 0.02;
    add_tube(m, hanging_polyline(r, t.centre.y() + r.uniform(-0.3, 0.3) * t.width, front, -1.0, 0.6), 0.0015f,
             V3(225, 215, 190) * light, 0, SurfaceKind::stem);
  };
  if (cfg.root_across_target && !scene.potatoes.empty()) root_in_front(rng, scene.potatoes[0]);
  if (cfg.roots_across_others) {
    Rng others(derive_seed(seed, {5}));
    for (std::size_t k = 1; k < scene.potatoes.size(); ++k) root_in_front(others, scene.potatoes[k]);
  }
  // Backdrop.
  const V3 white = V3(235, 235, 230) * light;
  if (cfg.scene == PotatoScene::sheet) {
    add_quad(m, V3(-2, -2, 0), V3(2, -2, 0), V3(2, 2, 0), V3(-2, 2, 0), white, SurfaceKind::soil);
  } else if (cfg.scene == PotatoScene::chamber) {
    const V3 black(25, 25, 28);
    add_quad(m, V3(-2, -2, 0), V3(2, -2, 0), V3(2, 2, 0), V3(-2, 2, 0), black, SurfaceKind::soil);
    add_quad(m, V3(-2, -0.7f, 0), V3(2, -0.7f, 0), V3(2, -0.7f, 1), V3(-2, -0.7f, 1), black * 1.3f, SurfaceKind::soil);
    add_quad(m, V3(-2, 0.7f, 0), V3(2, 0.7f, 0), V3(2, 0.7f, 1), V3(-2, 0.7f, 1), black * 1.3f, SurfaceKind::soil);
  } else {
    // Room: a sheet 0.8 m wide; behind it, 2 m back, a wall with furniture, clothes, a blue object.
    add_quad(m, V3(-0.5f, -0.4f, 0), V3(0.45f, -0.4f, 0), V3(0.45f, 0.4f, 0), V3(-0.5f, 0.4f, 0), white,
             SurfaceKind::soil);
    add_quad(m, V3(-3, -4, -2), V3(3, -4, -2), V3(3, 4, -2), V3(-3, 4, -2), V3(190, 180, 160), SurfaceKind::soil);
    add_quad(m, V3(1.2f, -4, -2), V3(1.2f, 4, -2), V3(1.2f, 4, 1), V3(1.2f, -4, 1), V3(120, 100, 80),
             SurfaceKind::soil);                                                      // floor
    add_box(m, V3(0.2f, -1.4f, -1.6f), V3(1.2f, -0.6f, -1.0f), V3(110, 70, 40));      // cupboard
    add_box(m, V3(-0.3f, 0.6f, -1.2f), V3(0.5f, 1.0f, -0.9f), V3(30, 30, 35));        // dark clothes
    add_box(m, V3(0.3f, 0.5f, -0.8f), V3(0.7f, 0.9f, -0.6f), V3(40, 70, 200));        // blue object
    add_box(m, V3(-0.9f, -0.9f, -1.5f), V3(-0.5f, -0.5f, -1.3f), V3(200, 170, 120));  // a brownish box
  }
  m.compute_normals();
  m.shade(Eigen::Vector3f(0.3f, -0.2f, 1.0f).normalized(), cfg.scene == PotatoScene::chamber ? 0.5f : 0.55f);
  return scene;
}

}  // namespace cropsight::sim::detail
