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

// Marks the vertices of the 2D hull of the m points (t[i], w[i]) (t strictly increasing): mark[t[i]]
// = 1 for each. Andrew's monotone chain, lower and upper halves. A middle point is dropped only
// when it lies inside by more than the rounding tolerance `slack_t` (how far a pixel coordinate
// may stand from the exact projective abscissa), so borderline points stay candidates.
// First a branch-free pass over each point and its two list neighbours: a point clearly above the
// chord of its neighbours cannot be a vertex of the lower chain, one clearly below it not of the
// upper chain, so each chain starts from a shorter list (on a head's convex profile the lower
// chain keeps a few points; the monotone chain's data-dependent pops were most of the filter's
// time). `lo`, `up`: scratch of 2m ints each. mark is indexed by t·mark_step.
void mark_chain_vertices(int m, const int* t, const double* w, double slack_t, std::uint8_t* mark,
                         std::ptrdiff_t mark_step, int* lo, int* up) {
  if (m <= 2) {
    for (int i = 0; i < m; ++i) mark[t[i] * mark_step] = 1;
    return;
  }
  // cross(o, a, b) > 0: o -> a -> b turns left (counter-clockwise in (t, w)): a lies below the
  // line o -> b. Also returns the slack below which |cross| is rounding.
  auto turn = [&](int o, int a, int b, double& slack) {
    const double ta = double(t[a] - t[o]), tb = double(t[b] - t[o]);
    const double wa = w[a] - w[o], wb = w[b] - w[o];
    slack = 2.0 * slack_t * (std::abs(wb) + std::abs(wa)) + 1e-300;
    return ta * wb - wa * tb;
  };
  int* lo_in = lo + m;
  int* up_in = up + m;
  int ml = 0, mu = 0;
  lo_in[ml++] = 0, up_in[mu++] = 0;
  for (int i = 1; i < m - 1; ++i) {
    double slack;
    const double c = turn(i - 1, i, i + 1, slack);
    lo_in[ml] = i, up_in[mu] = i;
    ml += c <= -slack ? 0 : 1;
    mu += c >= slack ? 0 : 1;
  }
  lo_in[ml++] = m - 1, up_in[mu++] = m - 1;
  int nl = 0, nu = 0;
  for (int k = 0; k < ml; ++k) {
    const int i = lo_in[k];
    double slack;
    // lower chain: pop a middle point that lies clearly above o -> i (a clear right turn)
    while (nl >= 2 && turn(lo[nl - 2], lo[nl - 1], i, slack) <= -slack) --nl;
    lo[nl++] = i;
  }
  for (int k = 0; k < mu; ++k) {
    const int i = up_in[k];
    double slack;
    // upper chain: pop a clear left turn
    while (nu >= 2 && turn(up[nu - 2], up[nu - 1], i, slack) >= slack) --nu;
    up[nu++] = i;
  }
  for (int k = 0; k < nl; ++k) mark[t[lo[k]] * mark_step] = 1;
  for (int k = 0; k < nu; ++k) mark[t[up[k]] * mark_step] = 1;
}

}  // namespace

// Long on purpose: a hot path of branch-free passes over the same pixel grids (occupancy, 1/z, marks).
std::optional<std::vector<int>> hull_vertex_candidates(const OrganizedCloud& cloud, const std::vector<int>& indices) {
  const std::size_t n = indices.size();
  const int width = cloud.width;
  if (n < 16 || width <= 0) return std::nullopt;
  const float* X = cloud.x.data();
  const float* Y = cloud.y.data();
  const float* Z = cloud.z.data();

  // Pixel coordinates, the bounding box, and the points at the extreme columns and rows for the
  // affine fits. The row comes from the previous point's row when the index stays in it or the
  // next one (segments list their pixels in raster order), from a division otherwise.
  std::vector<int> us(n), vs(n);
  int u_lo = INT_MAX, u_hi = -1, v_lo = INT_MAX, v_hi = -1;
  int at_u_lo = 0, at_u_hi = 0, at_v_lo = 0, at_v_hi = 0;
  int row = 0, row_start = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const int i = indices[k];
    if (i - row_start >= width && i - row_start < 2 * width) {
      ++row, row_start += width;
    } else if (i < row_start || i - row_start >= width) {
      row = i / width, row_start = row * width;
    }
    const int u = i - row_start;
    us[k] = u;
    vs[k] = row;
    if (u < u_lo) u_lo = u, at_u_lo = i;
    if (u > u_hi) u_hi = u, at_u_hi = i;
    if (row < v_lo) v_lo = row, at_v_lo = i;
    if (row > v_hi) v_hi = row, at_v_hi = i;
  }
  if (u_hi == u_lo || v_hi == v_lo) return std::nullopt;

  // Precondition: x/z = a_u + b_u * u and y/z = a_v + b_v * v for every point.
  auto ratio_x = [&](int i) { return double(X[i]) / double(Z[i]); };
  auto ratio_y = [&](int i) { return double(Y[i]) / double(Z[i]); };
  const double slope_u = (ratio_x(at_u_hi) - ratio_x(at_u_lo)) / double(u_hi - u_lo);
  const double slope_v = (ratio_y(at_v_hi) - ratio_y(at_v_lo)) / double(v_hi - v_lo);
  if (!(std::abs(slope_u) > 1e-9) || !(std::abs(slope_v) > 1e-9)) return std::nullopt;  // also NaN
  const double base_u = ratio_x(at_u_lo) - slope_u * u_lo, base_v = ratio_y(at_v_lo) - slope_v * v_lo;
  // Branch-free over the points (one test at the end): |x/z − fit| ≤ tol multiplied through by
  // z > 0 (no division per point); "!(a <= b)" also catches NaN.
  bool pinhole = true;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = std::size_t(indices[k]);
    const double z = double(Z[i]);
    pinhole &= (z > 0.0) & (std::abs(double(X[i]) - (base_u + slope_u * us[k]) * z) <= kPinholeTolerance * z) &
               (std::abs(double(Y[i]) - (base_v + slope_v * vs[k]) * z) <= kPinholeTolerance * z);
  }
  if (!pinhole) return std::nullopt;  // the projective map needs every point in front, and a pinhole
  // How far, in pixels, a point's exact projective abscissa may stand from its integer u / v.
  const double slack_u = kPinholeTolerance / std::abs(slope_u), slack_v = kPinholeTolerance / std::abs(slope_v);

  // Grids over the bounding box (cell r * gw + c = pixel (u_lo + c, v_lo + r)): occupancy, 1/z,
  // and the row / column chain marks. A repeated index fills the same cell twice.
  const int gw = u_hi - u_lo + 1, gh = v_hi - v_lo + 1;
  const std::size_t cells = std::size_t(gw) * std::size_t(gh);
  std::vector<std::uint8_t> occ(cells, 0), row_mark(cells, 0), col_mark(cells, 0);
  std::vector<double> inv_z(cells, 0.0);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t cell = std::size_t(vs[k] - v_lo) * std::size_t(gw) + std::size_t(us[k] - u_lo);
    occ[cell] = 1;
    inv_z[cell] = 1.0 / double(Z[std::size_t(indices[k])]);
  }

  // Each row's chain in (u, 1/z), gathered without branches.
  const int longest = std::max(gw, gh);
  std::vector<int> t(std::size_t(longest) + 1), lo(2 * static_cast<std::size_t>(longest)),
      up(2 * static_cast<std::size_t>(longest));
  std::vector<double> w(std::size_t(longest) + 1);
  for (int r = 0; r < gh; ++r) {
    const std::size_t o = std::size_t(r) * std::size_t(gw);
    int m = 0;
    for (int c = 0; c < gw; ++c) {
      t[std::size_t(m)] = c, w[std::size_t(m)] = inv_z[o + std::size_t(c)];
      m += occ[o + std::size_t(c)];
    }
    mark_chain_vertices(m, t.data(), w.data(), slack_u, row_mark.data() + o, 1, lo.data(), up.data());
  }
  // The first and last rows (columns) of the set lie in a supporting plane of the whole set, so the
  // hull has a face there whose points are coplanar only to float rounding: qhull reports the
  // ones rounding pushes out as vertices. The filter keeps those rows (columns) whole.
  for (int c = 0; c < gw; ++c) {
    row_mark[std::size_t(c)] = 1;
    row_mark[std::size_t(gh - 1) * std::size_t(gw) + std::size_t(c)] = 1;
  }
  // The column pass sees only the row pass's survivors: still a subset that holds every hull
  // vertex, so still exact, at a third of the cost.
  for (int c = 0; c < gw; ++c) {
    int m = 0;
    for (int r = 0; r < gh; ++r) {
      const std::size_t cell = std::size_t(r) * std::size_t(gw) + std::size_t(c);
      t[std::size_t(m)] = r, w[std::size_t(m)] = inv_z[cell];
      m += occ[cell] & row_mark[cell];
    }
    mark_chain_vertices(m, t.data(), w.data(), slack_v, col_mark.data() + c, gw, lo.data(), up.data());
  }
  for (int r = 0; r < gh; ++r) {
    col_mark[std::size_t(r) * std::size_t(gw)] = 1;
    col_mark[std::size_t(r) * std::size_t(gw) + std::size_t(gw - 1)] = 1;
  }

  // Survivors in raster order (ascending pixel index), written without branches.
  std::vector<int> out(cells);
  std::size_t m = 0;
  for (int r = 0; r < gh; ++r) {
    const std::size_t o = std::size_t(r) * std::size_t(gw);
    const int base = (v_lo + r) * width + u_lo;
    for (int c = 0; c < gw; ++c) {
      out[m] = base + c;
      m += occ[o + std::size_t(c)] & row_mark[o + std::size_t(c)] & col_mark[o + std::size_t(c)];
    }
  }
  out.resize(m);
  return out;
}

}  // namespace cropsight::measure
