// The row/column hull filter (src/measure/hull_candidates.hpp) against qhull (pcl::ConvexHull):
// every vertex qhull finds on all of a head's points must be among the candidates, and the sizer
// must give the same hull diameter with and without the filter — on ray-cast noisy domes with
// leaves cut out, and on heads of simulated broccoli frames. Lens distortion must switch it off.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>

#include "cropsight/core/organized_cloud.hpp"
#include "cropsight/measure/head_size.hpp"
#include "cropsight/sim/broccoli/broccoli_sim.hpp"
#include "measure/hull_candidates.hpp"
#include "measure/qhull_reference.hpp"

using namespace cropsight;
using namespace cropsight::measure;

namespace {

// Pixel indices of the vertices qhull finds on the points at `indices`.
std::vector<int> qhull_vertices(const OrganizedCloud& c, const std::vector<int>& indices) {
  std::vector<Eigen::Vector3f> pts;
  for (int i : indices) pts.push_back(c.point(std::size_t(i)));
  std::vector<int> v;
  for (int k : reference::qhull_of(pts).vertices) v.push_back(indices[std::size_t(k)]);
  std::sort(v.begin(), v.end());
  return v;
}

// A 320×240 pinhole camera 0.75 m above a hemisphere of radius r (flat side down), depth noise of
// sigma metres along each ray, quantised to millimetres like a depth PNG; pixels for which
// `hidden(u, v)` holds are left out (a leaf). Returns the cloud and the dome's pixel indices.
std::pair<OrganizedCloud, std::vector<int>> pinhole_dome(double r, double sigma, unsigned seed,
                                                         bool (*hidden)(int, int) = nullptr) {
  const CameraIntrinsics cam = CameraIntrinsics::from_fov(320, 240, 70.6 * M_PI / 180, 60.0 * M_PI / 180);
  OrganizedCloud c(cam.width, cam.height);
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  const Eigen::Vector3d centre(0.03, -0.02, 0.75 + r);  // sphere centre; the apex is at z = 0.75
  std::vector<int> idx;
  for (int v = 0; v < cam.height; ++v)
    for (int u = 0; u < cam.width; ++u) {
      if (hidden && hidden(u, v)) continue;
      const Eigen::Vector3d d = Eigen::Vector3d((u - cam.cx) / cam.fx, (v - cam.cy) / cam.fy, 1.0);
      // ray t·d hits |t·d − centre| = r; nearest root
      const double a = d.squaredNorm(), b = -2 * d.dot(centre), q = centre.squaredNorm() - r * r;
      const double disc = b * b - 4 * a * q;
      if (disc < 0) continue;
      const double t = (-b - std::sqrt(disc)) / (2 * a);
      if (t * d.z() > centre.z()) continue;  // below the equator: the flat side
      const double depth_mm = std::round(1000.0 * (t * d.z() + noise(rng)));
      const auto p = cam.deproject(float(u), float(v), float(depth_mm * 0.001));
      const int i = c.index(u, v);
      c.x[std::size_t(i)] = p.x();
      c.y[std::size_t(i)] = p.y();
      c.z[std::size_t(i)] = p.z();
      idx.push_back(i);
    }
  return {std::move(c), std::move(idx)};
}

void expect_filter_is_exact(const OrganizedCloud& c, const std::vector<int>& idx, const std::string& what,
                            double* kept_fraction = nullptr) {
  const auto cand = hull_vertex_candidates(c, idx);
  ASSERT_TRUE(cand.has_value()) << what;
  const auto truth = qhull_vertices(c, idx);
  ASSERT_GE(truth.size(), 4u) << what;
  std::vector<int> missing;
  std::set_difference(truth.begin(), truth.end(), cand->begin(), cand->end(), std::back_inserter(missing));
  EXPECT_TRUE(missing.empty()) << what << ": " << missing.size() << " of " << truth.size()
                               << " qhull vertices dropped by the filter";
  if (kept_fraction) *kept_fraction = double(cand->size()) / double(idx.size());

  HeadSizeConfig on, off;
  off.hull_prefilter = false;
  const HeadSize a = HeadSizer(on).measure(c, idx), b = HeadSizer(off).measure(c, idx);
  EXPECT_EQ(a.hull_vertices, b.hull_vertices) << what;
  EXPECT_NEAR(a.hull_mm, b.hull_mm, 1e-6) << what;
  EXPECT_EQ(a.bbox_mm, b.bbox_mm) << what;
}

}  // namespace

TEST(HullCandidates, NoisyPinholeDomesKeepEveryQhullVertex) {
  for (double r : {0.04, 0.07}) {
    for (double sigma : {0.0, 0.002}) {
      auto [c, idx] = pinhole_dome(r, sigma, 7);
      double kept = 1.0;
      expect_filter_is_exact(c, idx, "dome r=" + std::to_string(r) + " sigma=" + std::to_string(sigma), &kept);
      std::printf("[ info ] dome r=%.2f sigma=%.3f: the filter keeps %.1f %%\n", r, sigma, 100 * kept);
      if (sigma > 0 && r > 0.05) {
        EXPECT_LT(kept, 0.3) << "the filter should drop most points of a noisy head-sized dome";
      }
    }
  }
}

TEST(HullCandidates, DomesWithLeavesCutOutKeepEveryQhullVertex) {
  // Occluders that make the head's image region non-convex and its rows and columns gappy.
  auto diagonal_leaf = +[](int u, int v) { return std::abs((u - 150) - (v - 110)) < 6; };
  auto corner_leaf = +[](int u, int v) { return u > 165 && v > 125; };
  auto holes = +[](int u, int v) { return (u * 7 + v * 13) % 11 == 0; };  // scattered missing returns
  int n = 0;
  for (auto hidden : {diagonal_leaf, corner_leaf, holes}) {
    auto [c, idx] = pinhole_dome(0.07, 0.002, 11 + unsigned(n), hidden);
    expect_filter_is_exact(c, idx, "occluder " + std::to_string(n++));
  }
}

TEST(HullCandidates, SimulatedBroccoliHeadsKeepEveryQhullVertex) {
  // Heads as the pipeline sees them: a uk frame's labelled head pixels within the 0.5–1.0 m range.
  sim::BroccoliSimulator simulator(sim::BroccoliSimConfig{}, 2024, 12);
  int heads = 0;
  double kept_sum = 0.0;
  for (int f = 0; f < 12; f += 4) {
    const OrganizedCloud c = to_organized_cloud(simulator.render(f), 0.5f, 1.0f);
    std::map<int, std::vector<int>> by_head;
    for (std::size_t i = 0; i < c.size(); ++i)
      if (c.labels[i] && c.valid(i)) by_head[c.labels[i]].push_back(int(i));
    for (const auto& [id, idx] : by_head) {
      if (idx.size() < 300) continue;  // the pipeline's smallest segment is 300–500 points
      double kept = 1.0;
      expect_filter_is_exact(c, idx, "frame " + std::to_string(f) + " head " + std::to_string(id), &kept);
      kept_sum += kept;
      ++heads;
    }
  }
  ASSERT_GE(heads, 3) << "the simulated frames should show several heads";
  std::printf("[ info ] %d simulated heads, the filter keeps %.1f %% of their points on average\n", heads,
              100.0 * kept_sum / heads);
}

TEST(HullCandidates, LensDistortionOrTinySetsSwitchItOff) {
  auto [c, idx] = pinhole_dome(0.07, 0.002, 3);
  // Radial distortion (k1 = 0.09, Kinect-like) applied to the deprojected points: rows are no
  // longer planes through the camera centre, so the filter must decline.
  OrganizedCloud d = c;
  for (int i : idx) {
    const double a = c.x[std::size_t(i)] / c.z[std::size_t(i)], b = c.y[std::size_t(i)] / c.z[std::size_t(i)];
    const double k = 1.0 + 0.09 * (a * a + b * b);
    d.x[std::size_t(i)] = float(a * k * c.z[std::size_t(i)]);
    d.y[std::size_t(i)] = float(b * k * c.z[std::size_t(i)]);
  }
  EXPECT_FALSE(hull_vertex_candidates(d, idx).has_value());
  // ...and the sizer then gives qhull every point: same answer as without the filter.
  HeadSizeConfig off;
  off.hull_prefilter = false;
  EXPECT_EQ(HeadSizer().measure(d, idx).hull_mm, HeadSizer(off).measure(d, idx).hull_mm);

  // A single image row or column, or a handful of points: no filter.
  std::vector<int> row, few(idx.begin(), idx.begin() + 10);
  for (int i : idx)
    if (i / c.width == idx[idx.size() / 2] / c.width) row.push_back(i);
  EXPECT_FALSE(hull_vertex_candidates(c, row).has_value());
  EXPECT_FALSE(hull_vertex_candidates(c, few).has_value());
}

TEST(HullCandidates, InputOrderAndRepeatsDoNotMatter) {
  // The filter reads rows incrementally when the indices come in raster order (as segments list
  // them) and by division otherwise; a repeated index is one point. Same candidates either way.
  auto corner_leaf = +[](int u, int v) { return u > 165 && v > 125; };
  auto [c, idx] = pinhole_dome(0.06, 0.002, 21, corner_leaf);
  const auto sorted = hull_vertex_candidates(c, idx);
  ASSERT_TRUE(sorted.has_value());
  std::vector<int> shuffled = idx, repeated = idx, reversed(idx.rbegin(), idx.rend());
  std::shuffle(shuffled.begin(), shuffled.end(), std::mt19937(4));
  repeated.insert(repeated.end(), idx.begin(), idx.begin() + std::ptrdiff_t(idx.size() / 3));
  for (const auto* in : {&shuffled, &repeated, &reversed}) {
    const auto cand = hull_vertex_candidates(c, *in);
    ASSERT_TRUE(cand.has_value());
    EXPECT_EQ(*cand, *sorted);
  }
}
