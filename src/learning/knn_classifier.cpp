#include "learning/knn_classifier.hpp"

#include <algorithm>
#include <array>
#include <cstring>
#include <nanoflann.hpp>
#include <sstream>
#include <utility>
#include <vector>

#include "cropsight/core/error.hpp"
#include "learning/temp_file.hpp"

namespace cropsight::learning::detail {

namespace {
constexpr int kMaxK = 255;  // neighbours per query live on the stack

struct Adaptor {
  const Dataset* d;
  std::size_t kdtree_get_point_count() const { return d->size(); }
  float kdtree_get_pt(std::size_t i, std::size_t j) const { return d->row(i)[j]; }
  template <class BBox>
  bool kdtree_get_bbox(BBox&) const {
    return false;
  }
};
using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, Adaptor>, Adaptor, -1>;
}  // namespace

struct KnnClassifier::Index {
  Adaptor adaptor;
  Tree tree;
  Index(const Dataset& d) : adaptor{&d}, tree(d.dim, adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(16)) {}
};

KnnClassifier::KnnClassifier(Dataset data, int k, const std::string& where) : data_(std::move(data)), k_(k) {
  if (k_ < 1 || k_ > kMaxK) throw Error(where, "knn_k must be in 1.." + std::to_string(kMaxK));
  if (data_.positives() == 0 || data_.negatives() == 0)
    throw Error(where, "training data needs both classes (positives " + std::to_string(data_.positives()) +
                           ", negatives " + std::to_string(data_.negatives()) + ")");
  index_ = std::make_unique<Index>(data_);
}

KnnClassifier::~KnnClassifier() = default;

float KnnClassifier::score(const float* x) const {
  const std::size_t k = std::min<std::size_t>(std::size_t(k_), data_.size());
  std::array<std::uint32_t, kMaxK> idx;
  std::array<float, kMaxK> d2;
  const std::size_t found = index_->tree.knnSearch(x, k, idx.data(), d2.data());
  int pos = 0;
  for (std::size_t i = 0; i < found; ++i) pos += data_.labels[idx[i]];
  return found ? float(pos) / float(found) : 0.0f;
}

float KnnClassifier::brute_force_score(const float* x) const {
  std::vector<std::pair<float, int>> all;
  for (std::size_t i = 0; i < data_.size(); ++i) {
    float s = 0.0f;
    for (int j = 0; j < data_.dim; ++j) {
      const float t = data_.row(i)[j] - x[j];
      s += t * t;
    }
    all.emplace_back(s, data_.labels[i]);
  }
  const std::size_t k = std::min<std::size_t>(std::size_t(k_), all.size());
  std::partial_sort(all.begin(), all.begin() + std::ptrdiff_t(k), all.end());
  int pos = 0;
  for (std::size_t i = 0; i < k; ++i) pos += all[i].second;
  return k ? float(pos) / float(k) : 0.0f;
}

std::string KnnClassifier::serialize() const {
  std::string out = "knn " + std::to_string(data_.size()) + " " + std::to_string(data_.dim) + "\n";
  out += base64_encode(data_.values.data(), data_.values.size() * sizeof(float));
  out += "\n";
  for (int l : data_.labels) out += char('0' + l);
  out += "\n";
  return out;
}

std::unique_ptr<KnnClassifier> KnnClassifier::from_payload(int k, int dim, const std::string& payload,
                                                           const std::string& where) {
  std::istringstream in(payload);
  std::string tag, b64, labels;
  std::size_t n = 0;
  int d = 0;
  if (!(in >> tag >> n >> d) || tag != "knn") throw Error(where, "KNN payload does not start with 'knn <n> <dim>'");
  if (d != dim)
    throw Error(where,
                "KNN payload dimension " + std::to_string(d) + " differs from feature_dim " + std::to_string(dim));
  if (!(in >> b64 >> labels)) throw Error(where, "KNN payload is truncated");
  const std::string bytes = base64_decode(b64, where);
  if (bytes.size() != n * std::size_t(d) * sizeof(float) || labels.size() != n)
    throw Error(where, "KNN payload sizes do not match its header");
  Dataset data(d);
  data.values.resize(n * std::size_t(d));
  std::memcpy(data.values.data(), bytes.data(), bytes.size());
  data.labels.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (labels[i] != '0' && labels[i] != '1') throw Error(where, "KNN payload labels must be 0 or 1");
    data.labels[i] = labels[i] - '0';
  }
  for (float v : data.values)
    if (!std::isfinite(v)) throw Error(where, "KNN payload has a non-finite value");
  return std::make_unique<KnnClassifier>(std::move(data), k, where);
}

}  // namespace cropsight::learning::detail
