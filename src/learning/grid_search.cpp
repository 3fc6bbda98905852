#include "cropsight/learning/grid_search.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include "cropsight/core/error.hpp"
#include "cropsight/learning/standardizer.hpp"

namespace cropsight::learning {

namespace {
std::vector<double> expand(const std::vector<double>& range, const std::string& name, const std::string& where) {
  if (range.size() != 3 || range[2] == 0.0 || (range[1] - range[0]) / range[2] < 0.0)
    throw Error(where, name + " must be [begin, end, step] with a step towards end");
  std::vector<double> out;
  const int n = int(std::floor((range[1] - range[0]) / range[2] + 1e-9)) + 1;
  for (int i = 0; i < n; ++i) out.push_back(range[0] + i * range[2]);
  return out;
}

struct Scores {
  double accuracy, kappa;
};
Scores score(const std::vector<int>& truth, const std::vector<int>& pred) {
  double tp = 0, tn = 0, fp = 0, fn = 0;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    if (truth[i] == 1)
      (pred[i] == 1 ? tp : fn) += 1;
    else
      (pred[i] == 1 ? fp : tn) += 1;
  }
  const double n = tp + tn + fp + fn;
  const double po = (tp + tn) / n;
  const double pe = ((tp + fp) * (tp + fn) + (tn + fn) * (tn + fp)) / (n * n);
  return {po, pe < 1.0 ? (po - pe) / (1.0 - pe) : (po == 1.0 ? 1.0 : 0.0)};
}

struct Fold {
  Dataset train, test;
  std::vector<std::size_t> test_idx;
};
}  // namespace

void GridSearchConfig::validate(const std::string& where) const {
  if (folds < 2) throw Error(where, "folds must be at least 2");
  if (metric != "accuracy" && metric != "kappa") throw Error(where, "metric must be accuracy or kappa");
  expand(log2_c, "log2_c", where);
  expand(log2_gamma, "log2_gamma", where);
}

std::vector<int> stratified_folds(const std::vector<int>& labels, int folds, int seed) {
  // Shuffle each class separately, then deal its samples round-robin over the folds, so every
  // fold has the class ratio of the whole set (±1 sample).
  std::vector<int> fold_of(labels.size(), 0);
  std::mt19937 rng{std::uint32_t(seed)};
  for (int cls : {0, 1}) {
    std::vector<std::size_t> idx;
    for (std::size_t i = 0; i < labels.size(); ++i)
      if (labels[i] == cls) idx.push_back(i);
    std::shuffle(idx.begin(), idx.end(), rng);
    for (std::size_t r = 0; r < idx.size(); ++r) fold_of[idx[r]] = int(r % std::size_t(folds));
  }
  return fold_of;
}

static std::vector<Fold> make_folds(const Dataset& data, const std::vector<int>& fold_of, int folds) {
  std::vector<Fold> out{std::size_t(folds)};
  for (int f = 0; f < folds; ++f) {
    std::vector<std::size_t> tr, te;
    for (std::size_t i = 0; i < data.size(); ++i) (fold_of[i] == f ? te : tr).push_back(i);
    Dataset train = data.subset(tr), test = data.subset(te);
    // Standardise with training-fold statistics only.
    const Standardizer s = Standardizer::fit(train);
    out[std::size_t(f)] = {s.apply(train), s.apply(test), std::move(te)};
  }
  return out;
}

static std::vector<int> run_folds(const std::vector<Fold>& folds, std::size_t n, const ClassifierParams& params) {
  std::vector<int> pred(n, 0);
  for (const Fold& f : folds) {
    if (f.test.empty()) continue;
    const auto clf = train_classifier(f.train, params, "cross-validation");
    for (std::size_t i = 0; i < f.test.size(); ++i) pred[f.test_idx[i]] = clf->predict(f.test.row(i)) ? 1 : 0;
  }
  return pred;
}

std::vector<int> cross_validate(const Dataset& data, const ClassifierParams& params, const std::vector<int>& fold_of,
                                int folds) {
  return run_folds(make_folds(data, fold_of, folds), data.size(), params);
}

GridSearchResult grid_search(const Dataset& data, const ClassifierParams& params, const GridSearchConfig& cfg,
                             const std::string& where, const GridProgress& progress) {
  cfg.validate(where);
  params.validate(where);
  if (params.type == "knn") throw Error(where, "grid search tunes SVM C and gamma; it does not apply to knn");
  if (data.positives() < std::size_t(cfg.folds) || data.negatives() < std::size_t(cfg.folds))
    throw Error(where, "each class needs at least " + std::to_string(cfg.folds) + " samples for " +
                           std::to_string(cfg.folds) + "-fold cross-validation");
  const bool rbf = params.type == "svm-rbf";
  const std::vector<double> cs = expand(cfg.log2_c, "log2_c", where);
  const std::vector<double> gs = rbf ? expand(cfg.log2_gamma, "log2_gamma", where) : std::vector<double>{0.0};
  const std::vector<Fold> folds = make_folds(data, stratified_folds(data.labels, cfg.folds, cfg.seed), cfg.folds);

  GridSearchResult result;
  result.params = params;
  double best = -1e300;
  for (double lc : cs) {
    for (double lg : gs) {
      ClassifierParams p = params;
      GridPoint g;
      g.c = std::exp2(lc);
      if (rbf) {
        g.gamma = std::exp2(lg);
        p.rbf_c = g.c;
        p.rbf_gamma = g.gamma;
      } else {
        p.linear_c = g.c;
      }
      const Scores s = score(data.labels, run_folds(folds, data.size(), p));
      g.accuracy = s.accuracy;
      g.kappa = s.kappa;
      result.points.push_back(g);
      const double m = cfg.metric == "kappa" ? g.kappa : g.accuracy;
      if (m > best) {
        best = m;
        result.best = g;
        result.params = p;
      }
      if (progress) progress(result.points.size(), cs.size() * gs.size());
    }
  }
  return result;
}

}  // namespace cropsight::learning
