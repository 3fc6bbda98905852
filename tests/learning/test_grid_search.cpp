#include <gtest/gtest.h>

#include <algorithm>

#include "cropsight/core/error.hpp"
#include "cropsight/learning/grid_search.hpp"
#include "test_learning_common.hpp"

using namespace cropsight;
using namespace cropsight::learning;

TEST(GridSearch, StratifiedFoldsKeepClassRatio) {
  std::vector<int> labels(103, 0);
  for (std::size_t i = 0; i < 23; ++i) labels[i * 4] = 1;
  const auto f = stratified_folds(labels, 5, 1);
  for (int k = 0; k < 5; ++k) {
    int pos = 0, all = 0;
    for (std::size_t i = 0; i < labels.size(); ++i)
      if (f[i] == k) ++all, pos += labels[i];
    EXPECT_GE(pos, 4);
    EXPECT_LE(pos, 5);
    EXPECT_GE(all, 20);
    EXPECT_LE(all, 21);
  }
  EXPECT_EQ(f, stratified_folds(labels, 5, 1));  // deterministic per seed
}

TEST(GridSearch, EvaluatesTheWholeGridAndPicksTheBest) {
  const Dataset d = testdata::gaussians(300, 8, 1.0, 21);
  ClassifierParams p;
  GridSearchConfig cfg;
  cfg.log2_c = {-3, 5, 4};        // 3 values
  cfg.log2_gamma = {1, -11, -6};  // 3 values
  const GridSearchResult r = grid_search(d, p, cfg);
  ASSERT_EQ(r.points.size(), 9u);
  for (const auto& g : r.points) EXPECT_LE(g.accuracy, r.best.accuracy);
  EXPECT_DOUBLE_EQ(r.params.rbf_c, r.best.c);
  EXPECT_DOUBLE_EQ(r.params.rbf_gamma, r.best.gamma);
  // Very large γ (2^1) on 8 standardised features overfits; the best must beat it clearly.
  const auto worst = std::min_element(r.points.begin(), r.points.end(),
                                      [](const GridPoint& a, const GridPoint& b) { return a.accuracy < b.accuracy; });
  EXPECT_GT(r.best.accuracy, 0.85);
  EXPECT_GT(r.best.accuracy, worst->accuracy);
}

TEST(GridSearch, LinearSearchesCOnly) {
  const Dataset d = testdata::gaussians(200, 6, 1.5, 22);
  ClassifierParams p;
  p.type = "svm-linear";
  GridSearchConfig cfg;
  cfg.log2_c = {-9, -1, 4};
  cfg.metric = "kappa";
  std::vector<std::pair<std::size_t, std::size_t>> calls;  // the progress callback: once per grid point
  const GridSearchResult r = grid_search(d, p, cfg, "grid search",
                                         [&](std::size_t done, std::size_t total) { calls.emplace_back(done, total); });
  EXPECT_EQ(r.points.size(), 3u);
  EXPECT_EQ(calls, (std::vector<std::pair<std::size_t, std::size_t>>{{1, 3}, {2, 3}, {3, 3}}));
  EXPECT_DOUBLE_EQ(r.params.linear_c, r.best.c);
  EXPECT_GT(r.best.kappa, 0.7);
}

TEST(GridSearch, RejectsBadRequests) {
  const Dataset d = testdata::gaussians(100, 4, 1.0, 23);
  ClassifierParams p;
  GridSearchConfig cfg;
  cfg.log2_c = {1, 5, -1};  // step away from the end
  EXPECT_THROW(grid_search(d, p, cfg), Error);
  cfg = {};
  p.type = "knn";
  EXPECT_THROW(grid_search(d, p, cfg), Error);
  Dataset tiny(4);
  tiny.add(std::vector<float>{1, 2, 3, 4}, 1);
  tiny.add(std::vector<float>{1, 2, 3, 5}, 0);
  p.type = "svm-rbf";
  EXPECT_THROW(grid_search(tiny, p, cfg), Error);
}
