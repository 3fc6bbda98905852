#pragma once
// SVM classifier through libsvm (internal header; tests include it to compare the dense scorer
// with libsvm's own svm_predict_values).
//
// Training and the saved model are libsvm's. For scoring, the support vectors are copied once
// into dense rows: libsvm's sparse svm_node lists cost a branch per feature and the feature
// vectors here are dense (VFH: 308 values), so dense dot products over the support vectors give
// the same decision value (to float rounding) several times faster; the RBF dot products skip the
// columns that are 0 in every support vector (empty VFH bins). On CPUs with AVX2 + FMA the RBF
// kernel is RbfBlocks (blocks of 16 support vectors, eight exponentials at a time, several
// vectors per pass: score_rows), else 4-lane rows. Unit tests check both against libsvm.
#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "cropsight/learning/classifier.hpp"
#include "learning/rbf_blocks.hpp"

struct svm_model;

namespace cropsight::learning::detail {

class SvmClassifier final : public Classifier {
 public:
  /// Trains with libsvm on standardised data (labels 1 → +1, 0 → -1).
  SvmClassifier(const Dataset& data, const ClassifierParams& params, const std::string& where);
  /// Loads libsvm model text; throws Error(where, ...) when it is not a 2-class C-SVC with the
  /// kernel `params.type` names or its support vectors exceed `dim`.
  SvmClassifier(const ClassifierParams& params, int dim, const std::string& libsvm_text, const std::string& where);
  ~SvmClassifier() override;

  std::string type() const override { return type_; }
  int dim() const override { return dim_; }
  float score(const float* x) const override;
  void score_rows(const float* x, std::size_t rows, float* out) const override;
  float threshold() const override { return 0.0f; }
  std::string serialize() const override { return text_; }
  std::size_t model_size() const override { return std::size_t(coef_.size()); }

  /// score() through the 4-lane row kernel that CPUs without AVX2 + FMA run (tests compare it
  /// with libsvm on any CPU).
  float baseline_score(const float* x) const;

  /// libsvm's own decision value for x, sign-corrected like score() (reference for tests).
  double libsvm_score(const float* x) const;
  double gamma() const { return gamma_; }

 private:
  void load_text(const std::string& text, const std::string& where);
  /// x's active_ columns, zero-padded to svp_stride_ floats, into zp; returns |x|² over every column.
  float gather_active(const float* x, float* zp) const;
  /// score(), through the baseline row kernel when `baseline` (else RbfBlocks where built).
  float score_with(const float* x, bool baseline) const;

  std::string type_;
  int dim_ = 0;
  bool rbf_ = true;
  double gamma_ = 0.0;
  float sign_ = 1.0f;  ///< +1 when libsvm's first label is the positive class
  float rho_ = 0.0f;
  Eigen::VectorXf coef_;      ///< y_i α_i per support vector
  Eigen::VectorXf sv_norm2_;  ///< |sv_i|² (RBF)
  std::vector<int> active_;   ///< columns where some support vector is non-zero (RBF dot products)
  std::vector<float> svp_;    ///< support vectors × active_ columns, rows zero-padded to svp_stride_ floats
  int svp_stride_ = 0;
  RbfBlocks blocks_;            ///< the support vectors for the AVX2 + FMA kernel; empty without it
  Eigen::VectorXf w_;           ///< Σ coef_i sv_i (linear kernel: the decision is w·x − ρ)
  std::string text_;            ///< libsvm model file text
  svm_model* model_ = nullptr;  ///< loaded from text_ (owns its memory); for libsvm_score()
};

}  // namespace cropsight::learning::detail
