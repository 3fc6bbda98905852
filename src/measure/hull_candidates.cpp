// Row/column hull filter for 3D convex-hull candidates (see hull_candidates.hpp for the proof).
#include "measure/hull_candidates.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>

#include "cropsight/core/organized_cloud.hpp"

namespace cropsight::measure {

namespace {

// Largest deviation of x/z (y/z) from an affine function of u (v) accepted as float rounding of a
// pinhole deprojection. Rounding gives about 1e-7 (|x/z| < 1 for any field of view under 90°);
// lens distortion, even mild, shows up above 1e-5 over a head's extent.
constexpr double kPinholeTolerance = 1e-6;

struct ChainPoint {
  double t;    // pixel coordinate along the row (u) or column (v)
  double w;    // 1 / z
  int member;  // position in the filter's point list
};

// Marks the vertices of the 2D hull of `pts` (sorted by strictly increasing t) in `is_vertex`.
// Andrew's monotone chain, lower and upper halves. A middle point is dropped only when it lies
// inside by more than the rounding tolerance `slack_t` (how far a pixel coordinate may stand from
// the exact projective abscissa), so borderline points stay candidates.
void mark_chain_vertices(const std::vector<ChainPoint>& pts, double slack_t, std::vector<std::uint8_t>& is_vertex,
                         std::vector<int>& stack) {
  const std::size_t m = pts.size();
  if (m <= 2) {
    for (const auto& p : pts) is_vertex[std::size_t(p.member)] = 1;
    return;
  }
  // cross(o, a, b) > 0: o -> a -> b turns left (counter-clockwise in (t, w)).
  auto inside = [&](const ChainPoint& o, const ChainPoint& a, const ChainPoint& b, double sign) {
    const double cross = (a.t - o.t) * (b.w - o.w) - (a.w - o.w) * (b.t - o.t);
    const double slack = 2.0 * slack_t * (std::abs(b.w - o.w) + std::abs(a.w - o.w)) + 1e-300;
    return sign * cross <= -slack;  // a lies clearly on the inner side of o -> b
  };
  for (double sign : {1.0, -1.0}) {  // +1: lower chain (left turns), -1: upper chain
    stack.clear();
    for (std::size_t i = 0; i < m; ++i) {
      while (stack.size() >= 2 &&
             inside(pts[std::size_t(stack[stack.size() - 2])], pts[std::size_t(stack.back())], pts[i], sign))
        stack.pop_back();
      stack.push_back(int(i));
    }
    for (int k : stack) is_vertex[std::size_t(pts[std::size_t(k)].member)] = 1;
  }
}

}  // namespace

std::optional<std::vector<int>> hull_vertex_candidates(const OrganizedCloud& cloud, const std::vector<int>& indices) {
  const std::size_t n = indices.size();
  const int width = cloud.width;
  if (n < 16 || width <= 0) return std::nullopt;

  // Pixel coordinates (one division each), the bounding box, and the points at the extreme
  // columns and rows for the affine fits.
  std::vector<int> us(n), vs(n);
  int u_lo = INT_MAX, u_hi = -1, v_lo = INT_MAX, v_hi = -1;
  int at_u_lo = 0, at_u_hi = 0, at_v_lo = 0, at_v_hi = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const int i = indices[k], v = i / width, u = i - v * width;
    us[k] = u;
    vs[k] = v;
    if (u < u_lo) u_lo = u, at_u_lo = i;
    if (u > u_hi) u_hi = u, at_u_hi = i;
    if (v < v_lo) v_lo = v, at_v_lo = i;
    if (v > v_hi) v_hi = v, at_v_hi = i;
  }
  if (u_hi == u_lo || v_hi == v_lo) return std::nullopt;

  // Precondition: x/z = a_u + b_u * u and y/z = a_v + b_v * v for every point.
  auto ratio_x = [&](int i) { return double(cloud.x[std::size_t(i)]) / double(cloud.z[std::size_t(i)]); };
  auto ratio_y = [&](int i) { return double(cloud.y[std::size_t(i)]) / double(cloud.z[std::size_t(i)]); };
  const double slope_u = (ratio_x(at_u_hi) - ratio_x(at_u_lo)) / double(u_hi - u_lo);
  const double slope_v = (ratio_y(at_v_hi) - ratio_y(at_v_lo)) / double(v_hi - v_lo);
  if (!(std::abs(slope_u) > 1e-9) || !(std::abs(slope_v) > 1e-9)) return std::nullopt;  // also NaN
  const double base_u = ratio_x(at_u_lo) - slope_u * u_lo, base_v = ratio_y(at_v_lo) - slope_v * v_lo;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = std::size_t(indices[k]);
    const double z = double(cloud.z[i]);
    if (!(z > 0.0)) return std::nullopt;  // the projective map needs every point in front
    // |x/z − fit| ≤ tol, multiplied through by z > 0 (no division per point)
    if (std::abs(double(cloud.x[i]) - (base_u + slope_u * us[k]) * z) > kPinholeTolerance * z ||
        std::abs(double(cloud.y[i]) - (base_v + slope_v * vs[k]) * z) > kPinholeTolerance * z)
      return std::nullopt;
  }
  // How far, in pixels, a point's exact projective abscissa may stand from its integer u / v.
  const double slack_u = kPinholeTolerance / std::abs(slope_u), slack_v = kPinholeTolerance / std::abs(slope_v);

  // Grid of the bounding box: member number per pixel, -1 where the set has no point (a repeated
  // index keeps its first entry).
  const int gw = u_hi - u_lo + 1, gh = v_hi - v_lo + 1;
  std::vector<int> grid(std::size_t(gw) * std::size_t(gh), -1);
  std::vector<int> members;
  std::vector<double> inv_z;
  members.reserve(n);
  inv_z.reserve(n);
  for (std::size_t k = 0; k < n; ++k) {
    int& cell = grid[std::size_t(vs[k] - v_lo) * std::size_t(gw) + std::size_t(us[k] - u_lo)];
    if (cell >= 0) continue;
    cell = int(members.size());
    members.push_back(indices[k]);
    inv_z.push_back(1.0 / double(cloud.z[std::size_t(indices[k])]));
  }

  std::vector<std::uint8_t> row_vertex(members.size(), 0), col_vertex(members.size(), 0);
  std::vector<ChainPoint> chain;
  std::vector<int> stack;
  chain.reserve(std::size_t(std::max(gw, gh)));
  for (int r = 0; r < gh; ++r) {
    chain.clear();
    for (int c = 0; c < gw; ++c)
      if (const int k = grid[std::size_t(r) * std::size_t(gw) + std::size_t(c)]; k >= 0)
        chain.push_back({double(c), inv_z[std::size_t(k)], k});
    mark_chain_vertices(chain, slack_u, row_vertex, stack);
  }
  // The column pass sees only the row pass's survivors (and the first and last rows, kept whole
  // below): still a subset that holds every hull vertex, so still exact, at a third of the cost.
  for (int c = 0; c < gw; ++c) {
    chain.clear();
    for (int r = 0; r < gh; ++r)
      if (const int k = grid[std::size_t(r) * std::size_t(gw) + std::size_t(c)];
          k >= 0 && (row_vertex[std::size_t(k)] || r == 0 || r == gh - 1))
        chain.push_back({double(r), inv_z[std::size_t(k)], k});
    mark_chain_vertices(chain, slack_v, col_vertex, stack);
  }

  // The first and last rows (columns) of the set lie in a supporting plane of the whole set, so the
  // hull has a face there whose points are coplanar only to float rounding: qhull reports the
  // ones rounding pushes out as vertices. The filter keeps those rows (columns) whole.
  std::vector<int> out;
  for (int r = 0; r < gh; ++r)  // row-major scan: ascending pixel index
    for (int c = 0; c < gw; ++c) {
      const int k = grid[std::size_t(r) * std::size_t(gw) + std::size_t(c)];
      if (k < 0) continue;
      const bool row_ok = row_vertex[std::size_t(k)] || r == 0 || r == gh - 1;
      const bool col_ok = col_vertex[std::size_t(k)] || c == 0 || c == gw - 1;
      if (row_ok && col_ok) out.push_back(members[std::size_t(k)]);
    }
  return out;
}

}  // namespace cropsight::measure
