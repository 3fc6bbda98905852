// OES and ORG on the synthetic scene: each dome (a "head") comes out as one segment, the
// ground (too large) does not.
#include <gtest/gtest.h>

#include <iostream>
#include <map>

#include "cropsight/geometry/integral_normals.hpp"
#include "cropsight/geometry/organized_edges.hpp"
#include "cropsight/segmentation/organized_clustering.hpp"
#include "geometry/synthetic_scene.hpp"

using namespace cropsight;

namespace {
// For each dome, the best segment's precision and recall of that dome's pixels.
void check_domes(const char* name, const OrganizedCloud& c, const std::vector<Segment>& segs, int domes) {
  std::map<int, int> dome_size;
  for (auto l : c.labels)
    if (l >= 1 && l <= domes) ++dome_size[l];
  for (int d = 1; d <= domes; ++d) {
    double best_f = 0, best_p = 0, best_r = 0;
    for (const auto& s : segs) {
      int hit = 0;
      for (int i : s.indices) hit += c.labels[i] == d;
      const double p = double(hit) / double(s.size()), r = double(hit) / double(dome_size[d]);
      const double f = p + r > 0 ? 2 * p * r / (p + r) : 0;
      if (f > best_f) best_f = f, best_p = p, best_r = r;
    }
    std::cout << "[" << name << "] dome " << d << " (" << dome_size[d] << " px): precision " << best_p << ", recall "
              << best_r << "\n";
    EXPECT_GT(best_p, 0.93) << name << " dome " << d;
    EXPECT_GT(best_r, 0.80) << name << " dome " << d;
  }
  // Nothing else but the domes and the leaf (label 100) comes out.
  EXPECT_EQ(segs.size(), std::size_t(domes + 1)) << name;
}
}  // namespace

TEST(OrganizedClustering, OesAndOrgFindTheDomes) {
  auto scene = cropsight::testing::make_synthetic_scene();
  auto& c = scene.cloud;
  geometry::estimate_normals_integral(c);
  segmentation::FloodFillWorkspace ws;
  // Depth edges alone do not separate a dome from the ground it grows out of (a crease, no
  // depth jump): the curvature barrier does.
  const auto plain = geometry::detect_organized_edges(c);
  EXPECT_LE(segmentation::segment_oes(c, plain, {.min_size = 300, .max_size = 20000}, ws).size(), 2u);
  const auto edges = geometry::detect_organized_edges(c, {.high_curvature_threshold = 0.02f});
  const auto oes = segmentation::segment_oes(c, edges, {.min_size = 300, .max_size = 20000}, ws);
  std::cout << "[oes] segments " << oes.size() << "\n";
  check_domes("oes", c, oes, scene.domes);
  const auto org = segmentation::segment_org(c,
                                             {.angle_threshold = 5.0f * float(M_PI) / 180.0f,
                                              .curvature_threshold = 0.02f,
                                              .min_size = 300,
                                              .max_size = 20000},
                                             ws);
  std::cout << "[org] segments " << org.size() << "\n";
  check_domes("org", c, org, scene.domes);
  for (const auto& s : oes) EXPECT_LE(s.size(), 20000u);
}
