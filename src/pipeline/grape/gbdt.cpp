#include "cropsight/pipeline/grape/gbdt.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <numeric>
#include <random>
#include <unordered_map>

#include "core/parallel_for.hpp"
#include "cropsight/core/class_scores.hpp"
#include "cropsight/core/error.hpp"
#include "geometry/point_kdtree.hpp"

namespace cropsight::pipeline::grape {

namespace {
// Rows used for training from one cloud: every point of a class rarer than rare_class_max,
// plus a uniform draw from the rest up to points_per_cloud (the shared clouds have 14k-40k
// points; all of them would make training slow without adding much information).
std::vector<int> training_rows(const Cloud& c, const GbdtConfig& cfg, std::mt19937_64& rng) {
  std::map<int, std::vector<int>> by_class;
  for (std::size_t i = 0; i < c.size(); ++i) by_class[c.labels[i]].push_back(int(i));
  std::vector<int> rows, rest;
  for (auto& [label, idx] : by_class) {
    if (int(idx.size()) < cfg.rare_class_max)
      rows.insert(rows.end(), idx.begin(), idx.end());
    else
      rest.insert(rest.end(), idx.begin(), idx.end());
  }
  std::shuffle(rest.begin(), rest.end(), rng);
  const std::size_t want = std::size_t(std::max(0, cfg.points_per_cloud - int(rows.size())));
  rows.insert(rows.end(), rest.begin(), rest.begin() + long(std::min(want, rest.size())));
  std::sort(rows.begin(), rows.end());
  return rows;
}
}  // namespace

void GbdtConfig::validate(const std::string& where) const {
  // In the order of visit(): the features, XGBoost's parameters, then this struct's own fields
  // (check_config walks the features again: they hold).
  features.validate(where, "features.");
  gbdt.validate(where, "gbdt.");
  check_config(*this, where);
}

learning::Gbdt train_grape_gbdt(const std::vector<Cloud>& clouds, const GbdtConfig& cfg,
                                const std::function<void(const std::string&)>& log) {
  cfg.validate("grape gbdt config");
  if (clouds.empty()) throw Error("train grape", "no training clouds");
  const std::size_t F = grape_feature_count(cfg.features);
  std::mt19937_64 rng(cfg.seed);
  std::vector<float> X, y;
  for (std::size_t k = 0; k < clouds.size(); ++k) {
    const Cloud& c = clouds[k];
    if (!c.has_labels()) throw Error("train grape", "cloud " + std::to_string(k) + " has no labels");
    if (cfg.features.sample > 0) {
      // Fast recipe: rows are whole pass samples, drawn and featurised exactly as at segment
      // time (only the seed differs), so that training and test features match.
      for (int d = 0; d < std::max(1, cfg.sample_draws); ++d) {
        const std::vector<int> rows = grape_sample(c.size(), cfg.features, rng());
        const std::vector<float> f = grape_sample_features(c, cfg.features, rows);
        X.insert(X.end(), f.begin(), f.end());
        for (int r : rows) y.push_back(float(c.labels[std::size_t(r)]));
        if (rows.size() == c.size()) break;  // the whole cloud: further draws would repeat it
      }
    } else {
      const std::vector<int> rows = training_rows(c, cfg, rng);
      const std::vector<float> f = grape_point_features(c, cfg.features, rows);
      X.insert(X.end(), f.begin(), f.end());
      for (int r : rows) y.push_back(float(c.labels[std::size_t(r)]));
    }
    if (log && (k + 1) % 10 == 0) log("features: " + std::to_string(k + 1) + "/" + std::to_string(clouds.size()));
  }
  const std::size_t n = y.size();
  // Inverse-frequency weights (softened by class_weight_power), normalised so that the median
  // class has weight 1: lifts the tiny peduncle class without drowning the others.
  std::vector<double> count(std::size_t(cfg.gbdt.num_class), 0.0);
  for (float l : y) {
    if (l < 0 || l >= float(cfg.gbdt.num_class)) throw Error("train grape", "label out of range: " + std::to_string(l));
    count[std::size_t(l)] += 1;
  }
  const std::vector<double> class_weight = median_frequency_weights(count, cfg.class_weight_power);
  std::vector<float> w(n);
  for (std::size_t i = 0; i < n; ++i) w[i] = float(class_weight[std::size_t(y[i])]);
  if (log) log("training XGBoost on " + std::to_string(n) + " rows x " + std::to_string(F) + " features");
  learning::Gbdt model;
  model.train(X, n, F, y, w, cfg.gbdt);
  model.set_attribute("cropsight.kind", "grape-gbdt");
  model.set_attribute("cropsight.features", cfg.features.recipe());
  return model;
}

namespace {
// Searches of positions that several points to carry back share exactly (the same three float
// bits): the shared clouds put 15-20 % of their points at one position (label 0), and those
// searches are the slowest (every sample there is at distance 0, so no branch of the tree can
// be skipped). A search is a function of the query's coordinates alone, so one search per such
// position gives every point there exactly the neighbours and distances its own search would.
struct SharedSearches {
  std::vector<int> group;  // per point: its position's row below, or -1 (a position of its own)
  std::vector<std::uint32_t> nb;
  std::vector<float> d2;
  std::vector<std::size_t> found;
};

SharedSearches search_repeated_positions(const Cloud& cloud, const std::vector<int>& out,
                                         const geometry::detail::PointKdTree& tree, std::size_t k, int threads) {
  using Key = std::array<std::uint32_t, 3>;
  struct KeyHash {
    std::size_t operator()(const Key& key) const {
      return std::size_t(key[0]) * 0x9E3779B97F4A7C15ull ^ std::size_t(key[1]) * 0xC2B2AE3D27D4EB4Full ^ key[2];
    }
  };
  SharedSearches s;
  s.group.assign(cloud.size(), -1);
  std::unordered_map<Key, std::pair<std::size_t, int>, KeyHash> first;  // position -> (first point, its row)
  first.reserve(cloud.size());
  std::vector<std::size_t> query;  // one point per shared position
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (out[i] >= 0) continue;
    Key key;
    std::memcpy(key.data(), cloud.points[i].data(), sizeof(key));
    auto [it, inserted] = first.try_emplace(key, i, -1);
    if (inserted) continue;
    if (it->second.second < 0) {
      it->second.second = int(query.size());
      s.group[it->second.first] = int(query.size());
      query.push_back(it->second.first);
    }
    s.group[i] = it->second.second;
  }
  s.nb.resize(query.size() * k);
  s.d2.resize(query.size() * k);
  s.found.resize(query.size());
  cropsight::detail::parallel_for(query.size(), threads, 1, [&](std::size_t b, std::size_t e) {
    for (std::size_t g = b; g < e; ++g)
      s.found[g] = tree.knnSearch(cloud.points[query[g]].data(), k, &s.nb[g * k], &s.d2[g * k]);
  });
  return s;
}
}  // namespace

std::vector<int> grape_carry_back(const Cloud& cloud, const std::vector<int>& sample,
                                  const std::vector<int>& sample_labels, const FeatureConfig& fc, int num_class,
                                  int threads, const std::vector<float>* sample_proba, std::vector<float>* scores_out) {
  if (sample_proba && sample_proba->size() != sample.size() * std::size_t(num_class))
    throw Error("grape carry-back", "probabilities are not sample size x classes");
  if (sample.size() != sample_labels.size()) throw Error("grape carry-back", "sample and labels differ in count");
  if (sample.empty()) throw Error("grape carry-back", "empty sample");
  if (fc.carry_k < 1) throw Error("grape carry-back", "carry_k must be at least 1");
  // Sample points keep their own label; every other point takes the vote of its carry_k nearest
  // sample points, weighted by distance and colour likeness (carry_k = 1: the nearest sample's
  // label, as geometry::carry_labels_back). Rows are split over the threads.
  geometry::detail::PackedPoints packed;
  packed.xyz.reserve(3 * sample.size());
  std::vector<int> out(cloud.size(), -1);
  for (std::size_t s = 0; s < sample.size(); ++s) {
    const std::size_t i = std::size_t(sample[s]);
    if (i >= cloud.size()) throw Error("grape carry-back", "sample index out of range");
    const int l = sample_labels[s];
    if (l < 0 || l >= num_class) throw Error("grape carry-back", "label out of range");
    packed.xyz.insert(packed.xyz.end(), {cloud.points[i].x(), cloud.points[i].y(), cloud.points[i].z()});
    out[i] = l;
  }
  const std::size_t C = std::size_t(num_class);
  // One voter's scores: its probabilities, or its label one-hot.
  auto voter_scores = [&](std::size_t s, float w, float* dst) {
    if (sample_proba) {
      const float* pr = sample_proba->data() + s * C;
      for (std::size_t c = 0; c < C; ++c) dst[c] += w * pr[c];
    } else {
      dst[std::size_t(sample_labels[s])] += w;
    }
  };
  if (scores_out) {
    scores_out->assign(cloud.size() * C, 0.f);
    for (std::size_t s = 0; s < sample.size(); ++s) voter_scores(s, 1.f, &(*scores_out)[std::size_t(sample[s]) * C]);
  }
  geometry::detail::PointKdTree tree(3, packed, geometry::detail::kdtree_params());
  tree.buildIndex();
  const std::size_t k = std::min<std::size_t>(std::size_t(fc.carry_k), sample.size());
  const float wc = float(fc.carry_colour);
  const bool colour = k > 1 && cloud.has_colors();
  const SharedSearches shared = search_repeated_positions(cloud, out, tree, k, threads);
  cropsight::detail::parallel_for(cloud.size(), threads, 2048, [&](std::size_t b, std::size_t e) {
    std::vector<std::uint32_t> own_nb(k);
    std::vector<float> own_d2(k), vote(static_cast<std::size_t>(num_class));
    for (std::size_t i = b; i < e; ++i) {
      if (out[i] >= 0) continue;
      // A shared position's neighbours come from its one search; any other point searches here.
      const int g = shared.group[i];
      const std::size_t row = g >= 0 ? std::size_t(g) * k : 0;
      const std::uint32_t* nb = g >= 0 ? &shared.nb[row] : own_nb.data();
      const float* d2 = g >= 0 ? &shared.d2[row] : own_d2.data();
      const std::size_t found = g >= 0 ? shared.found[std::size_t(g)]
                                       : tree.knnSearch(cloud.points[i].data(), k, own_nb.data(), own_d2.data());
      if (!colour || found == 1) {
        out[i] = sample_labels[nb[0]];
        if (scores_out) voter_scores(nb[0], 1.f, &(*scores_out)[i * C]);
        continue;
      }
      std::fill(vote.begin(), vote.end(), 0.f);
      const float inv_r2 = 1.f / (d2[found - 1] + 1e-12f);
      for (std::size_t q = 0; q < found; ++q) {
        const float dc = (cloud.colors[i] - cloud.colors[std::size_t(sample[nb[q]])]).squaredNorm();
        voter_scores(nb[q], std::exp(-d2[q] * inv_r2 - wc * dc), vote.data());
      }
      float sum = 0.f;
      for (float x : vote) sum += x;
      if (!(sum > 0.f)) {  // every weight underflowed (a colour unlike all k voters): the nearest decides
        std::fill(vote.begin(), vote.end(), 0.f);
        voter_scores(nb[0], 1.f, vote.data());
        sum = 0.f;
        for (float x : vote) sum += x;
      }
      out[i] = int(std::max_element(vote.begin(), vote.end()) - vote.begin());
      if (scores_out)
        for (std::size_t c = 0; c < C; ++c) (*scores_out)[i * C + c] = vote[c] / sum;
    }
  });
  return out;
}

std::vector<int> segment_grape_gbdt(const learning::Gbdt& model, const Cloud& cloud, int threads,
                                    std::vector<float>* scores) {
  if (model.attribute("cropsight.kind") != "grape-gbdt")
    throw Error("grape model", "not a grape GBDT model (cropsight.kind attribute missing)");
  FeatureConfig fc = FeatureConfig::from_recipe(model.attribute("cropsight.features"), "grape model");
  fc.threads = threads;
  if (fc.sample > 0 && std::size_t(fc.sample) < cloud.size()) {
    const std::vector<int> sample = grape_sample(cloud.size(), fc, fc.sample_seed);
    const std::vector<float> X = grape_sample_features(cloud, fc, sample);
    const std::vector<float> proba = model.predict_proba(X, sample.size(), grape_feature_count(fc));
    const std::vector<int> sample_labels = argmax_rows(proba.data(), sample.size(), std::size_t(model.num_class()));
    return grape_carry_back(cloud, sample, sample_labels, fc, model.num_class(), threads,
                            fc.carry_soft ? &proba : nullptr, scores);
  }
  // Every point (also the fast recipe on a cloud no larger than its sample: the same features).
  const std::vector<float> X = fc.sample > 0
                                   ? grape_sample_features(cloud, fc, grape_sample(cloud.size(), fc, fc.sample_seed))
                                   : grape_point_features(cloud, fc);
  if (!scores) return model.predict(X, cloud.size(), grape_feature_count(fc));
  *scores = model.predict_proba(X, cloud.size(), grape_feature_count(fc));
  return argmax_rows(scores->data(), cloud.size(), std::size_t(model.num_class()));
}

}  // namespace cropsight::pipeline::grape
