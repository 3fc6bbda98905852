#include "cropsight/geometry/grid_sampling.hpp"

#include <algorithm>
#include <limits>
#include <numeric>
#include <random>

#include "cropsight/core/error.hpp"

namespace cropsight::geometry {
namespace {

struct Splitter {
  const std::vector<Eigen::Vector3f>& pts;
  int max_per_box;
  float min_size;
  std::vector<int> out;

  void leaf(const int* b, const int* e) {
    Eigen::Vector3f c = Eigen::Vector3f::Zero();
    for (const int* i = b; i != e; ++i) c += pts[*i];
    c /= float(e - b);
    int best = *b;
    float bd = std::numeric_limits<float>::max();
    for (const int* i = b; i != e; ++i) {
      const float d = (pts[*i] - c).squaredNorm();
      if (d < bd) bd = d, best = *i;
    }
    out.push_back(best);
  }

  void split(int* b, int* e, Eigen::Vector3f lo, Eigen::Vector3f hi, int depth) {
    if (b == e) return;
    if (e - b <= max_per_box || (hi - lo).maxCoeff() < min_size || depth >= 24) {
      leaf(b, e);
      return;
    }
    const Eigen::Vector3f mid = 0.5f * (lo + hi);
    // Three nested partitions give the 8 octants as contiguous ranges.
    int* px = std::partition(b, e, [&](int i) { return pts[i].x() < mid.x(); });
    int* cuts[9];
    cuts[0] = b;
    cuts[4] = px;
    cuts[8] = e;
    for (int h = 0; h < 2; ++h) {
      int* s = cuts[4 * h];
      int* t = cuts[4 * h + 4];
      int* py = std::partition(s, t, [&](int i) { return pts[i].y() < mid.y(); });
      cuts[4 * h + 2] = py;
      cuts[4 * h + 1] = std::partition(s, py, [&](int i) { return pts[i].z() < mid.z(); });
      cuts[4 * h + 3] = std::partition(py, t, [&](int i) { return pts[i].z() < mid.z(); });
    }
    for (int o = 0; o < 8; ++o) {
      Eigen::Vector3f l = lo, u = hi;
      ((o & 4) ? l.x() : u.x()) = mid.x();
      ((o & 2) ? l.y() : u.y()) = mid.y();
      ((o & 1) ? l.z() : u.z()) = mid.z();
      split(cuts[o], cuts[o + 1], l, u, depth + 1);
    }
  }
};

}  // namespace

std::vector<int> nonuniform_grid_representatives(const std::vector<Eigen::Vector3f>& points, int max_points_per_box,
                                                 double min_box_size) {
  if (max_points_per_box < 1) throw Error("grid sampling", "max_points_per_box must be >= 1");
  if (!(min_box_size > 0)) throw Error("grid sampling", "min_box_size must be > 0");
  std::vector<int> idx;
  idx.reserve(points.size());
  Eigen::Vector3f lo = Eigen::Vector3f::Constant(std::numeric_limits<float>::max()), hi = -lo;
  for (int i = 0; i < int(points.size()); ++i)
    if (points[i].allFinite()) {
      idx.push_back(i);
      lo = lo.cwiseMin(points[i]);
      hi = hi.cwiseMax(points[i]);
    }
  Splitter s{points, max_points_per_box, float(min_box_size), {}};
  if (idx.empty()) return {};
  s.out.reserve(idx.size() / std::size_t(max_points_per_box) * 2 + 8);
  s.split(idx.data(), idx.data() + idx.size(), lo, hi, 0);
  std::sort(s.out.begin(), s.out.end());
  return s.out;
}

std::vector<int> sample_exact(const std::vector<Eigen::Vector3f>& points, const GridSamplingConfig& cfg) {
  if (cfg.target_points < 1) throw Error("grid sampling", "target_points must be >= 1");
  long finite = 0;
  for (const auto& p : points) finite += p.allFinite();
  if (finite == 0) throw Error("grid sampling", "the cloud has no finite point");
  const int target = cfg.target_points;
  std::vector<int> reps;
  if (finite <= target) {
    for (int i = 0; i < int(points.size()); ++i)
      if (points[i].allFinite()) reps.push_back(i);
    // Too few points for the target: repeat them in order so that the count is exact.
    for (std::size_t i = 0; int(reps.size()) < target; ++i) reps.push_back(reps[i]);
    return reps;
  }
  // With at most floor(N / target) points per box there are at least `target` boxes.
  const int m = cfg.max_points_per_box > 0 ? cfg.max_points_per_box : int(std::max<long>(1, finite / target));
  reps = nonuniform_grid_representatives(points, m, cfg.min_box_size);
  if (int(reps.size()) < target) {  // a user-set threshold too coarse: fall back to a finer one
    reps = nonuniform_grid_representatives(points, int(std::max<long>(1, finite / target)), cfg.min_box_size);
  }
  if (int(reps.size()) > target) {
    std::mt19937 rng(cfg.seed);
    std::vector<int> order(reps.size());
    std::iota(order.begin(), order.end(), 0);
    // Partial Fisher-Yates: the first `target` entries are a uniform random subset.
    for (int i = 0; i < target; ++i) {
      const int j = std::uniform_int_distribution<int>(i, int(order.size()) - 1)(rng);
      std::swap(order[i], order[j]);
    }
    order.resize(target);
    std::sort(order.begin(), order.end());
    std::vector<int> kept;
    kept.reserve(target);
    for (int o : order) kept.push_back(reps[o]);
    reps.swap(kept);
  }
  // Boxes of identical points below min_box_size can leave fewer than target representatives:
  // pad by repetition (rare; only for degenerate clouds).
  for (std::size_t i = 0; int(reps.size()) < target; ++i) reps.push_back(reps[i]);
  return reps;
}

}  // namespace cropsight::geometry
