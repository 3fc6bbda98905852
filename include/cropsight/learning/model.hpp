#pragma once
// Model: a trained classifier with the standardiser it was trained behind and the metadata
// that says which pipeline produced its features. Saved as one JSON file:
//
//   {
//     "format": "cropsight-model", "version": 1,
//     "task": "broccoli-heads", "pipeline": "oes",          // which detector and clustering
//     "features": ["vfh"], "feature_dim": 308,               // feature blocks, concatenated
//     "config": {"normals.depth_change_factor": "0.02", ...}, // every detector parameter
//     "classifier": {"type": "svm-rbf", "rbf_c": "2", ...},   // ClassifierParams
//     "standardizer": {"mean": [...], "std": [...]},
//     "provenance": {"data": "...", "seeds": "...", ...},     // free text: how it was trained
//     "payload": "svm_type c_svc\nkernel_type rbf\n..."       // libsvm model text / KNN samples
//   }
//
// Loading checks everything it can (format, sizes, finite values, libsvm model parse) and a
// consumer checks compatibility with require_compatible() before using it.
#include <filesystem>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "cropsight/core/config.hpp"
#include "cropsight/learning/classifier.hpp"
#include "cropsight/learning/standardizer.hpp"

namespace cropsight::learning {

struct ModelInfo {
  std::string task;                   ///< e.g. "broccoli-heads"
  std::string pipeline;               ///< e.g. "oes" | "org" | "fec"
  std::vector<std::string> features;  ///< feature blocks in concatenation order, e.g. {"vfh", "va"}
  int feature_dim = 0;
  ConfigMap config;                               ///< every pipeline parameter at training time (dotted key → value)
  std::map<std::string, std::string> provenance;  ///< training data, seeds, command, sample counts
};

class Model {
 public:
  ModelInfo info;
  Standardizer standardizer;
  ClassifierParams params;
  std::unique_ptr<Classifier> classifier;

  /// Score of one raw (unstandardised) feature vector; `scratch` is resized to dim and reused,
  /// so a caller that keeps it allocates nothing per call.
  float score(std::span<const float> x, std::vector<float>& scratch) const;
  /// score() of the x.size() / out.size() raw vectors stored one after another in `x`, into `out`
  /// (bit-identical to score() per vector; the RBF SVM scores them together, see
  /// Classifier::score_rows). Throws std::invalid_argument when x.size() is not out.size() · dim.
  void score_rows(std::span<const float> x, std::span<float> out, std::vector<float>& scratch) const;
  float threshold() const { return classifier->threshold(); }
};

/// Fits the standardiser on `data`, trains `params.type` on the standardised data.
Model train_model(const Dataset& data, const ClassifierParams& params, ModelInfo info);

/// Writes the model atomically. Throws Error(path, ...) on failure.
void save_model(const std::filesystem::path& path, const Model& model);
/// Reads and validates a model file. Throws Error(path, ...) naming what is wrong.
Model load_model(const std::filesystem::path& path);

/// Throws Error(where, ...) when the model was trained for another task, pipeline or feature
/// list (order matters: the feature vector is their concatenation) or another dimension.
void require_compatible(const ModelInfo& info, const std::string& task, const std::string& pipeline,
                        const std::vector<std::string>& features, int feature_dim, const std::string& where);

}  // namespace cropsight::learning
