#pragma once
// Binary classifiers with a continuous score (higher = more likely the positive class):
//
//   svm-rbf     libsvm C-SVC, RBF kernel; score = decision value, sign-corrected so that
//               score > 0 means positive (libsvm's own decision, same threshold)
//   svm-linear  libsvm C-SVC, linear kernel; same score convention
//   knn         k nearest neighbours (Euclidean, nanoflann k-d tree); score = fraction of the
//               k neighbours that are positive, positive when > 0.5 (k odd: no ties)
//
// Classifiers see standardised features (see Standardizer / Model); they do not standardise.
// Scoring is const and thread-safe.
#include <cstddef>
#include <memory>
#include <string>

#include "cropsight/learning/dataset.hpp"

namespace cropsight::learning {

/// Classifier choice and parameters. Defaults: Kusumam et al., "3D-vision based detection,
/// localisation and sizing of broccoli heads in the field" (J. Field Robotics 2017), §4.3.
struct ClassifierParams {
  std::string type = "svm-rbf";  ///< svm-rbf | svm-linear | knn
  double rbf_c = 2.0;            ///< RBF SVM cost C (paper: 2, from their grid search)
  double rbf_gamma = 0.0078125;  ///< RBF kernel γ = 2^-7 (paper: 0.0078125)
  double linear_c = 0.002;       ///< linear SVM cost C (paper: 0.002)
  int knn_k = 11;                ///< KNN neighbours (paper: 11)
  bool balanced_weights = true;  ///< class weight n / (k·n_j) on C (paper: weighted to balance classes)
  double svm_eps = 1e-3;         ///< libsvm stopping tolerance (libsvm default)
  double svm_cache_mb = 200.0;   ///< libsvm kernel cache, MB

  template <class V>
  void visit(V& v) {
    v("type", type, "svm-rbf | svm-linear | knn (paper: svm-rbf best, Kusumam et al. 2017 Table 3)");
    v("rbf_c", rbf_c, "RBF SVM cost C (paper: 2, Kusumam et al. 2017 §4.3)");
    v("rbf_gamma", rbf_gamma, "RBF kernel gamma, 1/feature units^2 after standardisation (paper: 0.0078125)");
    v("linear_c", linear_c, "linear SVM cost C (paper: 0.002, Kusumam et al. 2017 §4.3)");
    v("knn_k", knn_k, "KNN neighbours (paper: 11, Kusumam et al. 2017 §4.3)");
    v("balanced_weights", balanced_weights, "SVM class weights n/(k*n_j) (paper: yes, unbalanced classes)");
    v("svm_eps", svm_eps, "libsvm stopping tolerance (libsvm default 0.001)");
    v("svm_cache_mb", svm_cache_mb, "libsvm kernel cache size, MB");
  }

  /// Throws Error(where, ...) for an unknown type or a non-positive parameter.
  void validate(const std::string& where) const;
};

class Classifier {
 public:
  virtual ~Classifier() = default;
  /// "svm-rbf", "svm-linear" or "knn".
  virtual std::string type() const = 0;
  virtual int dim() const = 0;
  /// Score of one standardised feature vector of dim() values.
  virtual float score(const float* x) const = 0;
  /// score() of `rows` standardised vectors stored one after another in `x` (rows·dim() values),
  /// written to out[0..rows): bit-identical to calling score() per row. The RBF SVM scores them
  /// together (each block of support vectors read once for all rows instead of once per row); the
  /// default loops over score(). Thread-safe (const).
  virtual void score_rows(const float* x, std::size_t rows, float* out) const {
    for (std::size_t r = 0; r < rows; ++r) out[r] = score(x + r * std::size_t(dim()));
  }
  /// Score above which a sample is classified positive (0 for SVMs, 0.5 for KNN).
  virtual float threshold() const = 0;
  bool predict(const float* x) const { return score(x) > threshold(); }
  /// Text payload that, with the params, rebuilds an identical classifier (libsvm model text for
  /// SVMs; the training samples for KNN).
  virtual std::string serialize() const = 0;
  /// Number of support vectors (SVM) or stored samples (KNN).
  virtual std::size_t model_size() const = 0;
};

/// Trains the classifier `params.type` on standardised data with both classes present.
/// Throws Error(where, ...) when a class is missing or the parameters are invalid.
std::unique_ptr<Classifier> train_classifier(const Dataset& data, const ClassifierParams& params,
                                             const std::string& where = "training");
/// Rebuilds a classifier from serialize()'s payload; throws Error(where, ...) when malformed.
std::unique_ptr<Classifier> deserialize_classifier(const ClassifierParams& params, int dim, const std::string& payload,
                                                   const std::string& where);

}  // namespace cropsight::learning
