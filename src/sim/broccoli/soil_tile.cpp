// Soil tiles: a height field (fractal roughness + planting beds + clods) and the weeds on it.
#include <algorithm>
#include <cmath>

#include "cropsight/sim/broccoli/broccoli_field.hpp"
#include "cropsight/sim/random.hpp"
#include "sim/angles.hpp"
#include "sim/leaf_mesh.hpp"
#include "sim/value_noise.hpp"

namespace cropsight::sim {

namespace {
enum : std::int64_t { kClodTag = 4, kWeedTag = 5, kSoilColorTag = 11, kMoistTag = 12 };
constexpr double kClodCell = 0.1;  // m; clods are drawn per cell of this size

struct Clod {
  double x, y, rx, ry, c, s, height;
};

double smoothstep(double e0, double e1, double x) {
  const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
  return t * t * (3 - 2 * t);
}

// The tile's height-field grid: vertex (i, j) at ((gx0 + i)·g, (gy0 + j)·g). Grid vertices are
// indexed globally (gx, gy) so that neighbouring tiles compute identical positions on their
// shared edge (no cracks).
struct TileGrid {
  double g;
  int gx0, gx1, gy0, gy1, nx, ny;
  std::size_t at(int i, int j) const { return std::size_t(j) * nx + i; }
};

// Height of the clods at every grid vertex. Clods are drawn per global cell (a seed of its own);
// every tile stamps those that can reach it.
std::vector<double> clod_heights(const SimSoilConfig& S, std::uint64_t seed, const TileGrid& t) {
  const double g = t.g;
  const int gx0 = t.gx0, gy0 = t.gy0, nx = t.nx, ny = t.ny;
  std::vector<double> clod(std::size_t(nx) * ny, 0.0);
  const double x_lo = gx0 * g, x_hi = t.gx1 * g;
  const double reach = S.clod_size_max_m * 1.3;
  const int cx0 = int(std::floor((x_lo - reach) / kClodCell)), cx1 = int(std::floor((x_hi + reach) / kClodCell));
  const int cy0 = int(std::floor((gy0 * g - reach) / kClodCell)),
            cy1 = int(std::floor((t.gy1 * g + reach) / kClodCell));
  for (int cy = cy0; cy <= cy1; ++cy)
    for (int cx = cx0; cx <= cx1; ++cx) {
      Rng rng(derive_seed(seed, {kClodTag, cx, cy}));
      const int count = rng.poisson(S.clod_density_m2 * kClodCell * kClodCell);
      for (int k = 0; k < count; ++k) {
        Clod c;
        c.x = (cx + rng.uniform()) * kClodCell;
        c.y = (cy + rng.uniform()) * kClodCell;
        const double r = rng.uniform(S.clod_size_min_m, S.clod_size_max_m);
        const double elong = rng.uniform(0.75, 1.3);
        c.rx = r * elong;
        c.ry = r / elong;
        const double ang = rng.uniform(0.0, kPi);
        c.c = std::cos(ang);
        c.s = std::sin(ang);
        c.height = r * rng.uniform(0.35, 0.75);
        const double rmax = std::max(c.rx, c.ry);
        const int i0 = std::max(0, int(std::floor((c.x - rmax) / g)) - gx0),
                  i1 = std::min(nx - 1, int(std::ceil((c.x + rmax) / g)) - gx0);
        const int j0 = std::max(0, int(std::floor((c.y - rmax) / g)) - gy0),
                  j1 = std::min(ny - 1, int(std::ceil((c.y + rmax) / g)) - gy0);
        for (int j = j0; j <= j1; ++j)
          for (int i = i0; i <= i1; ++i) {
            const double dx = (gx0 + i) * g - c.x, dy = (gy0 + j) * g - c.y;
            const double u = (c.c * dx + c.s * dy) / c.rx, v = (-c.s * dx + c.c * dy) / c.ry;
            const double q = u * u + v * v;
            if (q < 1) {
              double& cl = clod[t.at(i, j)];
              cl = std::max(cl, c.height * std::sqrt(1 - q));
            }
          }
      }
    }
  return clod;
}

// The soil surface: one vertex per grid vertex at base height + clod, two triangles per cell.
// Colour and NIR reflectivity: brown soil, darker moist patches (weak ToF returns), dry clods.
void add_soil(Mesh& m, const SimSoilConfig& S, std::uint64_t seed, const TileGrid& t, const std::vector<double>& height,
              const std::vector<double>& clod) {
  const std::uint64_t color_seed = derive_seed(seed, {kSoilColorTag}), moist_seed = derive_seed(seed, {kMoistTag});
  // fbm is roughly symmetric in about [-0.45, 0.45]: map the wanted moist fraction to a threshold.
  const double threshold = 0.45 - 0.9 * S.moist_fraction;
  const int nx = t.nx, ny = t.ny;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const double x = (t.gx0 + i) * t.g, y = (t.gy0 + j) * t.g;
      const double cl = clod[t.at(i, j)];
      const double z = height[t.at(i, j)] + cl;
      double wet = smoothstep(threshold - 0.04, threshold + 0.04, detail::fbm(moist_seed, x / 0.4, y / 0.4, 3));
      if (cl > 0.002) wet *= 0.3;
      const double tone = 0.85 + 0.3 * (0.5 + 0.5 * detail::fbm(color_seed, x / 0.03, y / 0.03, 2));
      Eigen::Vector3f c = Eigen::Vector3f(124, 97, 72) * float(tone * (1.0 - 0.45 * wet) * (cl > 0.002 ? 1.08 : 1.0));
      const float refl = float(S.reflectivity_dry + (S.reflectivity_moist - S.reflectivity_dry) * wet);
      m.add_vertex(Eigen::Vector3f(float(x), float(y), float(z)), c, refl);
    }
  for (int j = 0; j + 1 < ny; ++j)
    for (int i = 0; i + 1 < nx; ++i) {
      const auto a = std::uint32_t(j * nx + i), b = a + 1, c = a + 1 + std::uint32_t(nx), d = a + std::uint32_t(nx);
      m.add_triangle(a, b, c, 0, SurfaceKind::soil);
      m.add_triangle(a, c, d, 0, SurfaceKind::soil);
    }
}

// Weeds of tile `tile` (x in [x_lo, x_hi]): small rosettes of bright green leaves lying on the soil.
void add_weeds(Mesh& m, const BroccoliField& field, int tile, double x_lo, double x_hi, double half_width) {
  Rng rng(derive_seed(field.seed(), {kWeedTag, tile}));
  const int weeds = rng.poisson(field.config().field.weed_density_m2 * field.tile_length() * 2 * half_width);
  const auto& W = field.config().weed;
  for (int w = 0; w < weeds; ++w) {
    const double x = rng.uniform(x_lo, x_hi), y = rng.uniform(-half_width, half_width);
    const double radius = rng.uniform(W.size_min_m, W.size_max_m);
    const int leaves = rng.uniform_int(3, 7);
    const double az0 = rng.uniform(0.0, 2 * kPi);
    const double rise = std::min(W.height_max_m, radius);
    const Eigen::Vector3f base_color(float(rng.uniform(70, 100)), float(rng.uniform(130, 160)),
                                     float(rng.uniform(40, 65)));
    for (int k = 0; k < leaves; ++k) {
      detail::LeafShape L;
      L.start = {x, y, field.soil_base_height(x, y) + 0.003};
      L.azimuth = az0 + k * 2 * kPi / leaves + rng.normal(0.0, 0.2);
      L.length = radius * rng.uniform(0.7, 1.0);
      L.width = L.length * rng.uniform(0.3, 0.55);
      L.petiole = 0.1;
      // Steep enough to reach `rise` at mid-length, then drooping to the soil.
      L.elevation0 = std::atan2(2.0 * rise, L.length) * rng.uniform(0.6, 1.0);
      L.elevation1 = -rng.uniform(5, 30) * kDeg;
      L.cup = 0.15;
      L.ruffle = 0.002;
      L.segments = 7;
      L.across = 5;
      L.color = base_color * float(rng.uniform(0.9, 1.1));
      L.midrib_color = L.color * 1.2f;
      L.reflectivity = 0.5f;
      detail::add_leaf(m, L, SurfaceKind::weed, rng);
    }
  }
}

}  // namespace

std::shared_ptr<const Mesh> BroccoliField::build_tile(int tile, double half_width) const {
  auto mesh = std::make_shared<Mesh>();
  Mesh& m = *mesh;
  const int per_tile = std::max(1, int(std::lround(tile_length() / cfg_.soil.grid_m)));
  TileGrid t;
  t.g = tile_length() / per_tile;
  t.gx0 = tile * per_tile, t.gx1 = t.gx0 + per_tile;
  t.gy1 = int(std::ceil(half_width / t.g)), t.gy0 = -t.gy1;
  t.nx = t.gx1 - t.gx0 + 1, t.ny = t.gy1 - t.gy0 + 1;
  std::vector<double> height(std::size_t(t.nx) * t.ny);
  for (int j = 0; j < t.ny; ++j)
    for (int i = 0; i < t.nx; ++i) height[t.at(i, j)] = soil_base_height((t.gx0 + i) * t.g, (t.gy0 + j) * t.g);
  add_soil(m, cfg_.soil, seed_, t, height, clod_heights(cfg_.soil, seed_, t));
  add_weeds(m, *this, tile, t.gx0 * t.g, t.gx1 * t.g, half_width);
  m.compute_normals();
  const double el = cfg_.light.sun_elevation_deg * kDeg, az = cfg_.light.sun_azimuth_deg * kDeg;
  m.shade(Eigen::Vector3f(float(std::cos(el) * std::cos(az)), float(std::cos(el) * std::sin(az)), float(std::sin(el))),
          float(cfg_.light.ambient));
  return mesh;
}

}  // namespace cropsight::sim
