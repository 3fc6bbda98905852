#include "cropsight/eval/map_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "cropsight/core/error.hpp"

namespace cropsight::eval {

namespace {

// Hungarian algorithm with potentials (Kuhn–Munkres, O(n²m)) for n ≤ m: every row gets a
// column. a is 1-based internally; returns the column of each row.
std::vector<int> hungarian_rows_le_cols(const std::vector<double>& a, int n, int m) {
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> u(std::size_t(n) + 1, 0.0), v(std::size_t(m) + 1, 0.0);
  std::vector<int> p(std::size_t(m) + 1, 0), way(std::size_t(m) + 1, 0);
  for (int i = 1; i <= n; ++i) {
    p[0] = i;
    int j0 = 0;
    std::vector<double> minv(std::size_t(m) + 1, inf);
    std::vector<char> used(std::size_t(m) + 1, 0);
    do {
      used[std::size_t(j0)] = 1;
      const int i0 = p[std::size_t(j0)];
      double delta = inf;
      int j1 = 0;
      for (int j = 1; j <= m; ++j) {
        if (used[std::size_t(j)]) continue;
        const double cur =
            a[std::size_t(i0 - 1) * std::size_t(m) + std::size_t(j - 1)] - u[std::size_t(i0)] - v[std::size_t(j)];
        if (cur < minv[std::size_t(j)]) minv[std::size_t(j)] = cur, way[std::size_t(j)] = j0;
        if (minv[std::size_t(j)] < delta) delta = minv[std::size_t(j)], j1 = j;
      }
      for (int j = 0; j <= m; ++j) {
        if (used[std::size_t(j)]) {
          u[std::size_t(p[std::size_t(j)])] += delta;
          v[std::size_t(j)] -= delta;
        } else {
          minv[std::size_t(j)] -= delta;
        }
      }
      j0 = j1;
    } while (p[std::size_t(j0)] != 0);
    do {
      const int j1 = way[std::size_t(j0)];
      p[std::size_t(j0)] = p[std::size_t(j1)];
      j0 = j1;
    } while (j0);
  }
  std::vector<int> row_to_col(std::size_t(n), -1);
  for (int j = 1; j <= m; ++j)
    if (p[std::size_t(j)] > 0) row_to_col[std::size_t(p[std::size_t(j)] - 1)] = j - 1;
  return row_to_col;
}

}  // namespace

std::vector<int> hungarian(const std::vector<double>& cost, int rows, int cols) {
  if (rows < 0 || cols < 0 || cost.size() != std::size_t(rows) * std::size_t(cols))
    throw Error("hungarian", "cost matrix size does not match rows × cols");
  for (double c : cost)
    if (!std::isfinite(c)) throw Error("hungarian", "non-finite cost");
  if (rows == 0 || cols == 0) return std::vector<int>(std::size_t(rows), -1);
  if (rows <= cols) return hungarian_rows_le_cols(cost, rows, cols);
  std::vector<double> t(cost.size());
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < cols; ++j)
      t[std::size_t(j) * std::size_t(rows) + std::size_t(i)] =
          cost[std::size_t(i) * std::size_t(cols) + std::size_t(j)];
  const auto col_to_row = hungarian_rows_le_cols(t, cols, rows);
  std::vector<int> out(std::size_t(rows), -1);
  for (int j = 0; j < cols; ++j)
    if (col_to_row[std::size_t(j)] >= 0) out[std::size_t(col_to_row[std::size_t(j)])] = j;
  return out;
}

MapMetrics map_metrics(const std::vector<Eigen::Vector3d>& map, const std::vector<Eigen::Vector3d>& truth,
                       const MapMatchConfig& cfg, const std::vector<Eigen::Vector3d>& ignore) {
  if (!(cfg.radius_m > 0)) throw Error("map metrics", "match radius must be positive");
  const int n = int(map.size()), m = int(truth.size());
  auto dist_to = [&](int i, const Eigen::Vector3d& p) {
    Eigen::Vector3d d = map[std::size_t(i)] - p;
    if (!cfg.use_z) d.z() = 0.0;
    return d.norm();
  };
  auto dist = [&](int i, int j) { return dist_to(i, truth[std::size_t(j)]); };
  // Infeasible pairs cost more than any sum of feasible ones, so the optimum first maximises the
  // number of feasible pairs, then minimises their total distance.
  const double big = cfg.radius_m * double(std::max(n, m) + 1) * 4.0 + 1.0;
  std::vector<double> cost(std::size_t(n) * std::size_t(m));
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      const double d = dist(i, j);
      cost[std::size_t(i) * std::size_t(m) + std::size_t(j)] = d <= cfg.radius_m ? d : big;
    }
  const auto a = hungarian(cost, n, m);

  MapMetrics r;
  r.map_heads = n;
  r.true_heads = m;
  std::vector<char> truth_matched(std::size_t(m), 0), map_matched(std::size_t(n), 0);
  double dsum = 0.0;
  for (int i = 0; i < n; ++i) {
    const int j = a[std::size_t(i)];
    if (j < 0) continue;
    const double d = dist(i, j);
    if (d > cfg.radius_m) continue;
    r.matches.push_back({i, j, d});
    truth_matched[std::size_t(j)] = map_matched[std::size_t(i)] = 1;
    dsum += d;
  }
  r.matched = int(r.matches.size());
  for (int i = 0; i < n; ++i) {
    if (map_matched[std::size_t(i)]) continue;
    bool duplicate = false;
    for (int j = 0; j < m && !duplicate; ++j) duplicate = truth_matched[std::size_t(j)] && dist(i, j) <= cfg.radius_m;
    if (duplicate) {
      ++r.duplicates;
      continue;
    }
    for (const auto& p : ignore)
      if (dist_to(i, p) <= cfg.radius_m) {
        ++r.ignored;
        break;
      }
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  r.precision = n ? double(r.matched) / n : nan;
  r.precision_visible = n > r.ignored ? double(r.matched) / (n - r.ignored) : nan;
  r.recall = m ? double(r.matched) / m : nan;
  r.duplicate_rate = n ? double(r.duplicates) / n : nan;
  r.count_error = n - m;
  r.count_error_rel = m ? double(n - m) / m : nan;
  r.mean_distance_m = r.matched ? dsum / r.matched : nan;
  return r;
}

}  // namespace cropsight::eval
