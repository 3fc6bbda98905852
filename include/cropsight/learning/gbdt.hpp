#pragma once
// Gradient-boosted trees for multi-class classification (XGBoost C API, Debian libxgboost-dev),
// behind a pimpl so that no XGBoost header leaks into users. Rows are row-major float features.
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "cropsight/core/config.hpp"
#include "cropsight/core/threads.hpp"

namespace cropsight::learning {

struct GbdtParams {
  int num_class = 6;
  int rounds = 200;  ///< boosting rounds
  int max_depth = 8;
  double eta = 0.15;       ///< learning rate
  double subsample = 0.8;  ///< row subsampling per tree
  double colsample = 0.8;  ///< feature subsampling per tree
  double min_child_weight = 1;
  double lambda = 1;  ///< L2 leaf regularisation
  int max_bin = 256;  ///< histogram bins (tree_method=hist)
  int nthread = 2;    ///< XGBoost threads (set deliberately: the machine has 2 cores)
  int seed = 0;

  template <class V>
  void visit(V& v) {
    v("rounds", rounds, "count; boosting rounds", Range::at_least(1));
    v("max_depth", max_depth, "count; maximum tree depth", Range::at_least(1));
    v("eta", eta, "1; learning rate", Range::above(0));
    v("subsample", subsample, "fraction; rows sampled per tree", Range::within(0, 1).open_below());
    v("colsample", colsample, "fraction; features sampled per tree", Range::within(0, 1).open_below());
    v("min_child_weight", min_child_weight, "1; minimum hessian sum in a leaf", Range::at_least(0));
    v("lambda", lambda, "1; L2 regularisation of leaf weights", Range::at_least(0));
    v("max_bin", max_bin, "count; histogram bins of tree_method=hist", Range::at_least(2));
    v("nthread", nthread, "count; XGBoost threads", Range::within(1, kMaxThreads));
    v("seed", seed, "1; random seed");
  }

  /// Throws Error(where, "'PREFIXrounds' must be at least 1, got 0") for the first field out of
  /// the Range declared in visit(), or num_class below 2 (set by the caller, not a preset key).
  /// `prefix` is the fields' key path in a larger config ("gbdt.").
  void validate(const std::string& where, const std::string& prefix = "") const;
};

class Gbdt {
 public:
  Gbdt();
  ~Gbdt();
  Gbdt(Gbdt&&) noexcept;
  Gbdt& operator=(Gbdt&&) noexcept;

  /// Trains from scratch on `rows` × `cols` features, labels in [0, num_class), optional
  /// per-row weights (empty = 1). Throws Error on inconsistent sizes.
  void train(const std::vector<float>& x, std::size_t rows, std::size_t cols, const std::vector<float>& labels,
             const std::vector<float>& weights, const GbdtParams& params);

  /// Class probabilities, rows × num_class, row-major (through the compiled forest after
  /// compile(): XGBoost's float sums and softmax, so equal to XGBoost's up to rounding).
  std::vector<float> predict_proba(const std::vector<float>& x, std::size_t rows, std::size_t cols) const;
  /// Arg-max class per row (through the compiled forest after compile()).
  std::vector<int> predict(const std::vector<float>& x, std::size_t rows, std::size_t cols) const;

  /// Copies the trees into a compact array (nodes 12 bytes, children adjacent) that predict()
  /// then walks itself, a block of rows per tree, instead of calling XGBoost: the same sums of
  /// leaf values in the same (tree) order and the same softmax, so the same arg-max, several
  /// times faster on a few thousand rows. Numerical features only (no categorical splits).
  void compile();
  bool compiled() const { return flat_ != nullptr; }

  int num_class() const { return num_class_; }
  std::size_t num_features() const { return cols_; }

  /// Free-text metadata stored inside the model file (e.g. the feature recipe).
  void set_attribute(const std::string& key, const std::string& value);
  std::string attribute(const std::string& key) const;  ///< "" when absent

  /// XGBoost's JSON model format (one file). save() is atomic; load() throws Error(path, ...).
  void save(const std::filesystem::path& path) const;
  static Gbdt load(const std::filesystem::path& path, int nthread = 2);

  bool trained() const;

 private:
  struct Flat;
  void predict_flat(const std::vector<float>& x, std::size_t rows, std::size_t cols, int* labels, float* proba) const;
  void* booster_ = nullptr;  // BoosterHandle
  int num_class_ = 0;
  std::size_t cols_ = 0;
  int nthread_ = 1;
  std::shared_ptr<const Flat> flat_;  // set by compile()
};

}  // namespace cropsight::learning
