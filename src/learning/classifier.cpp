#include "cropsight/learning/classifier.hpp"

#include <cmath>

#include "cropsight/core/error.hpp"
#include "learning/knn_classifier.hpp"
#include "learning/svm_classifier.hpp"

namespace cropsight::learning {

void ClassifierParams::validate(const std::string& where) const {
  if (type != "svm-rbf" && type != "svm-linear" && type != "knn")
    throw Error(where, "unknown classifier '" + type + "' (expected svm-rbf, svm-linear or knn)");
  auto positive = [&](const char* name, double v) {
    if (!(v > 0.0) || !std::isfinite(v)) throw Error(where, std::string(name) + " must be positive");
  };
  positive("rbf_c", rbf_c);
  positive("rbf_gamma", rbf_gamma);
  positive("linear_c", linear_c);
  positive("svm_eps", svm_eps);
  positive("svm_cache_mb", svm_cache_mb);
  if (knn_k < 1 || knn_k > 255) throw Error(where, "knn_k must be in 1..255");
}

std::unique_ptr<Classifier> train_classifier(const Dataset& data, const ClassifierParams& params,
                                             const std::string& where) {
  params.validate(where);
  if (data.empty() || data.dim <= 0) throw Error(where, "no training samples");
  if (params.type == "knn") return std::make_unique<detail::KnnClassifier>(data, params.knn_k, where);
  return std::make_unique<detail::SvmClassifier>(data, params, where);
}

std::unique_ptr<Classifier> deserialize_classifier(const ClassifierParams& params, int dim, const std::string& payload,
                                                   const std::string& where) {
  params.validate(where);
  if (params.type == "knn") return detail::KnnClassifier::from_payload(params.knn_k, dim, payload, where);
  return std::make_unique<detail::SvmClassifier>(params, dim, payload, where);
}

}  // namespace cropsight::learning
