#pragma once
// KNN classifier (internal): nanoflann k-d tree over the standardised training samples.
#include <memory>
#include <string>

#include "cropsight/learning/classifier.hpp"

namespace cropsight::learning::detail {

class KnnClassifier final : public Classifier {
 public:
  KnnClassifier(Dataset data, int k, const std::string& where);
  ~KnnClassifier() override;
  /// Payload: "knn <n> <dim>\n<base64 float32 values>\n<labels as 0/1 characters>\n".
  static std::unique_ptr<KnnClassifier> from_payload(int k, int dim, const std::string& payload,
                                                     const std::string& where);

  std::string type() const override { return "knn"; }
  int dim() const override { return data_.dim; }
  float score(const float* x) const override;  ///< fraction of the k nearest samples that are positive
  float threshold() const override { return 0.5f; }
  std::string serialize() const override;
  std::size_t model_size() const override { return data_.size(); }

  /// Brute-force reference (tests): the same score from an exhaustive search.
  float brute_force_score(const float* x) const;

 private:
  struct Index;
  Dataset data_;
  int k_ = 11;
  std::unique_ptr<Index> index_;
};

}  // namespace cropsight::learning::detail
