// OES and ORG on the synthetic scene: each dome (a "head") comes out as one segment, the
// ground (too large) does not.
#include <gtest/gtest.h>

#include <iostream>
#include <limits>
#include <map>
#include <random>

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
  segmentation::OrganizedClusteringWorkspace ws;
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
  segmentation::OrganizedClusteringWorkspace ws;
  segmentation::FloodFillWorkspace ref_ws;
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

TEST(OrganizedClustering, OesComponentsMatchTheFloodFillOnRandomGrids) {
  // segment_oes labels the connected components of its link graph by row runs and union-find;
  // the reference is the plain flood fill with OesPredicate. Random grids with depth steps, NaN
  // holes and barrier edges give many runs that merge late (U shapes, spirals of links), and the
  // size range drops both the large and the small components.
  std::mt19937 rng(12345);
  for (int trial = 0; trial < 60; ++trial) {
    const int w = 8 + int(rng() % 90), h = 4 + int(rng() % 70);
    OrganizedCloud c(w, h);
    std::vector<std::uint8_t> edges(c.size(), 0);
    const float nan_rate = 0.02f * float(trial % 7), step_rate = 0.05f * float(trial % 5), edge_rate = 0.03f;
    std::uniform_real_distribution<float> uni(0.0f, 1.0f);
    for (int v = 0; v < h; ++v)
      for (int u = 0; u < w; ++u) {
        const std::size_t i = std::size_t(v) * w + u;
        // Piecewise planes: a random step in depth now and then separates neighbours in 3D.
        const float z = 0.8f + 0.002f * float(u % 17) + (uni(rng) < step_rate ? 0.05f : 0.0f);
        c.z[i] = uni(rng) < nan_rate ? std::numeric_limits<float>::quiet_NaN() : z;
        c.x[i] = 0.002f * float(u) * c.z[i];
        c.y[i] = 0.002f * float(v) * c.z[i];
        if (uni(rng) < edge_rate) edges[i] = std::uint8_t(1u << (rng() % 4));
      }
    const int min_size = 1 + int(rng() % 20);
    const int max_size = min_size + int(rng() % 400);
    const segmentation::OesConfig cfg{
        .distance_tolerance = 0.004f, .barrier_labels = int(rng() % 16), .min_size = min_size, .max_size = max_size};
    segmentation::OrganizedClusteringWorkspace ws;
    segmentation::FloodFillWorkspace ref_ws;
    const auto got = segmentation::segment_oes(c, edges, cfg, ws);
    const segmentation::OesPredicate pred{c.x.data(),
                                          c.y.data(),
                                          c.z.data(),
                                          edges.data(),
                                          std::uint8_t(cfg.barrier_labels),
                                          cfg.distance_tolerance * cfg.distance_tolerance};
    const auto ref = segmentation::flood_fill_segments(c, pred, cfg.min_size, cfg.max_size, ref_ws);
    ASSERT_EQ(got.size(), ref.size()) << "trial " << trial;
    for (std::size_t k = 0; k < got.size(); ++k) {
      EXPECT_EQ(got[k].indices, ref[k].indices) << "trial " << trial << " segment " << k;
      EXPECT_EQ(got[k].centroid, ref[k].centroid) << "trial " << trial << " segment " << k;
      EXPECT_EQ(got[k].box, ref[k].box) << "trial " << trial << " segment " << k;
    }
    EXPECT_EQ(ws.labels, ref_ws.labels) << "trial " << trial;
    // The workspace is reused frame to frame: a second call on the same input gives the same.
    const auto again = segmentation::segment_oes(c, edges, cfg, ws);
    ASSERT_EQ(again.size(), got.size());
    for (std::size_t k = 0; k < got.size(); ++k) EXPECT_EQ(again[k].indices, got[k].indices);
  }
}
