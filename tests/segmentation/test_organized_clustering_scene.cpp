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

TEST(OrganizedClustering, PrecomputedLinksGiveThePredicatesSegments) {
  // segment_oes / segment_org flood-fill over precomputed link bits; the plain predicates
  // (OesPredicate, OrgPredicate evaluated per neighbour pair) must give the same segments.
  auto scene = cropsight::testing::make_synthetic_scene();
  auto& c = scene.cloud;
  geometry::estimate_normals_integral(c);
  const auto edges = geometry::detect_organized_edges(c, {.high_curvature_threshold = 0.02f});
  segmentation::FloodFillWorkspace ws, ref_ws;
  auto same = [](const std::vector<Segment>& a, const std::vector<Segment>& b) {
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t k = 0; k < a.size(); ++k) {
      EXPECT_EQ(a[k].indices, b[k].indices) << k;
      EXPECT_EQ(a[k].centroid, b[k].centroid) << k;
      EXPECT_EQ(a[k].box, b[k].box) << k;
    }
  };
  for (float tol : {0.005f, 0.01f}) {
    const segmentation::OesConfig oes{
        .distance_tolerance = tol, .barrier_labels = 15, .min_size = 50, .max_size = 20000};
    const auto got = segmentation::segment_oes(c, edges, oes, ws);
    const segmentation::OesPredicate pred{c.x.data(), c.y.data(), c.z.data(), edges.data(), 15, tol * tol};
    const auto ref = segmentation::flood_fill_segments(c, pred, oes.min_size, oes.max_size, ref_ws);
    EXPECT_GT(got.size(), 2u);
    same(got, ref);
    EXPECT_EQ(ws.labels, ref_ws.labels);

    const segmentation::OrgConfig org{.angle_threshold = 0.2f,
                                      .curvature_threshold = 0.03f,
                                      .distance_tolerance = tol,
                                      .min_size = 50,
                                      .max_size = 20000};
    const auto got_org = segmentation::segment_org(c, org, ws);
    const segmentation::OrgPredicate org_pred{c.x.data(),  c.y.data(),         c.z.data(),     c.nx.data(), c.ny.data(),
                                              c.nz.data(), c.curvature.data(), std::cos(0.2f), 0.03f,       tol * tol};
    const auto ref_org = segmentation::flood_fill_segments(c, org_pred, org.min_size, org.max_size, ref_ws);
    EXPECT_GT(got_org.size(), 2u);
    same(got_org, ref_org);
    EXPECT_EQ(ws.labels, ref_ws.labels);
  }
}
