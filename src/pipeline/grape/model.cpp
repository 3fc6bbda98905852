#include "cropsight/pipeline/grape/model.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numeric>
#include <random>

#include "cropsight/core/class_scores.hpp"
#include "cropsight/core/config.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/io/grape_text.hpp"
#include "cropsight/learning/gbdt.hpp"
#include "cropsight/nn/point_segmenter.hpp"
#include "cropsight/pipeline/grape/gbdt.hpp"

namespace cropsight::pipeline::grape {

struct Model::Impl {
  std::unique_ptr<learning::Gbdt> gbdt;
  std::unique_ptr<nn::PointSegmenter> net;
  int threads = 2;
  bool sampled = false, farthest = false;
  int carry_k = 1;
  int votes = 1;
  std::shared_ptr<const Model> partner;
  double partner_weight = 0.5;
};

Model::~Model() = default;
Model::Model(Model&&) noexcept = default;
Model& Model::operator=(Model&&) noexcept = default;

Model Model::load(const std::filesystem::path& path, int threads) {
  const std::string where = path.string();
  // The error-code overload: a name the system refuses (a preset names its model) is "no such file".
  if (std::error_code ec; !std::filesystem::is_regular_file(path, ec)) throw Error(where, "no such model file");
  Model m;
  m.impl_ = std::make_unique<Impl>();
  m.impl_->threads = threads;
  // XGBoost JSON models start with '{'; torch archives are zip files ("PK").
  char first = 0;
  std::ifstream(path, std::ios::binary).get(first);
  if (first == '{') {
    m.impl_->gbdt = std::make_unique<learning::Gbdt>(learning::Gbdt::load(path, threads));
    if (m.impl_->gbdt->attribute("cropsight.kind") != "grape-gbdt") throw Error(where, "not a grape GBDT model");
    // Fast-recipe models predict through the compiled forest (same labels as XGBoost, faster on
    // a pass sample); models of the original recipe keep XGBoost's predictor.
    if (FeatureConfig::from_recipe(m.impl_->gbdt->attribute("cropsight.features"), where).sample > 0)
      m.impl_->gbdt->compile();
    m.kind_ = "gbdt";
    m.features_ = "gbdt-features";
  } else {
    m.impl_->net = std::make_unique<nn::PointSegmenter>(nn::PointSegmenter::load(path, threads));
    m.kind_ = m.impl_->net->config().arch;
    m.features_ = m.impl_->net->config().features;
  }
  return m;
}

std::vector<float> Model::scores(const Cloud& cloud) const {
  std::vector<float> s;
  if (cloud.empty()) return s;
  if (impl_->gbdt) {
    segment_grape_gbdt(*impl_->gbdt, cloud, impl_->threads, &s);
    return s;
  }
  if (!impl_->sampled) {
    impl_->net->segment(cloud, nullptr, impl_->votes, &s);
    return s;
  }
  FeatureConfig fc;
  fc.carry_k = impl_->carry_k;
  const int C = impl_->net->config().num_classes, V = impl_->votes;
  // The passes' forward runs first, spread over the threads a pass each; then each pass's
  // carry-back (itself split over the threads), summed in pass order.
  std::vector<std::vector<int>> idx(static_cast<std::size_t>(V));
  std::vector<float> angles(static_cast<std::size_t>(V));
  for (int v = 0; v < V; ++v) {
    idx[std::size_t(v)] = impl_->net->sample_for_pass(cloud, impl_->farthest, v);
    angles[std::size_t(v)] = 2.f * float(M_PI) * float(v) / float(V);
  }
  std::vector<std::vector<float>> proba;
  const auto labels = impl_->net->predict_passes(cloud, idx, angles, impl_->threads, &proba);
  std::vector<float> one;
  for (std::size_t v = 0; v < std::size_t(V); ++v) {
    grape_carry_back(cloud, idx[v], labels[v], fc, C, impl_->threads, &proba[v], &one);
    if (s.empty()) s.assign(one.size(), 0.f);
    for (std::size_t k = 0; k < s.size(); ++k) s[k] += one[k] / float(V);
  }
  return s;
}

void Model::set_ensemble(std::shared_ptr<const Model> partner, double weight) {
  if (!(weight >= 0.0 && weight <= 1.0))
    throw Error("grape model", "'ensemble_weight' must be within [0, 1], got " + std::to_string(weight));
  impl_->partner = std::move(partner);
  impl_->partner_weight = weight;
}

std::vector<int> Model::segment(const Cloud& cloud) const {
  if (impl_->partner) {
    if (cloud.empty()) return {};
    std::vector<float> a = scores(cloud);
    const std::vector<float> b = impl_->partner->scores(cloud);
    if (a.size() != b.size()) throw Error("grape ensemble", "the two models differ in their number of classes");
    const float w = float(impl_->partner_weight);
    for (std::size_t k = 0; k < a.size(); ++k) a[k] = (1.f - w) * a[k] + w * b[k];
    return argmax_rows(a.data(), cloud.size(), a.size() / cloud.size());
  }
  if (impl_->gbdt) return segment_grape_gbdt(*impl_->gbdt, cloud, impl_->threads);
  if (!impl_->sampled) return impl_->net->segment(cloud, nullptr, impl_->votes);
  if (cloud.empty()) return {};
  if (impl_->votes == 1) {
    FeatureConfig fc;
    fc.carry_k = impl_->carry_k;
    const auto idx = impl_->net->sample_for_pass(cloud, impl_->farthest);
    return grape_carry_back(cloud, idx, impl_->net->predict_at(cloud, idx), fc, impl_->net->config().num_classes,
                            impl_->threads);
  }
  // Soft vote of the passes (scores(): each pass's class probabilities carried back to every
  // point, averaged); the largest wins.
  const std::vector<float> s = scores(cloud);
  return argmax_rows(s.data(), cloud.size(), s.size() / cloud.size());
}

void Model::set_sampled(bool sampled, bool farthest, int carry_k) {
  if (carry_k < 1) throw Error("grape model", "'carry_k' must be at least 1, got " + std::to_string(carry_k));
  if (sampled && impl_->gbdt)
    throw Error("grape model", "'sampled' is only for network models (a GBDT recipe fixes its own sampling)");
  impl_->sampled = sampled;
  impl_->farthest = farthest;
  impl_->carry_k = carry_k;
}

void Model::set_votes(int votes) {
  if (votes < 1) throw Error("grape model", "'votes' must be at least 1, got " + std::to_string(votes));
  if (votes > 1 && impl_->gbdt) throw Error("grape model", "'votes' above 1 is only for network models");
  impl_->votes = votes;
}

int Model::votes() const { return impl_->votes; }

bool Model::sampled() const { return impl_->sampled; }

std::vector<int> grape_folds(std::size_t n, int k, std::uint64_t seed) {
  if (k < 2) throw Error("folds", "need at least 2 folds");
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::mt19937_64 rng(seed);
  std::shuffle(order.begin(), order.end(), rng);
  std::vector<int> fold(n);
  for (std::size_t i = 0; i < n; ++i) fold[std::size_t(order[i])] = int(i % std::size_t(k));
  return fold;
}

std::pair<int, int> parse_fold(const std::string& text, const std::string& option) {
  const auto slash = text.find('/');
  try {
    if (slash == std::string::npos) throw Error(option, "no '/'");
    int k = 0, K = 0;  // each side a whole number ("1x/4" is a typo, not fold 1)
    detail::parse_value(option, "k", text.substr(0, slash), k);
    detail::parse_value(option, "K", text.substr(slash + 1), K);
    if (K < 2 || k < 1 || k > K) throw Error(option, "out of range");
    return {k - 1, K};
  } catch (const Error&) {
    throw Error(option, "expected k/K with 1 <= k <= K and K >= 2, got '" + text + "'");
  }
}

}  // namespace cropsight::pipeline::grape
