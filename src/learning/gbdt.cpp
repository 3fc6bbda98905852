#include "cropsight/learning/gbdt.hpp"

#include <xgboost/c_api.h>

#include <algorithm>
#include <limits>
#include <utility>

#include <filesystem>
#include <fstream>
#include <sstream>
#include "cropsight/core/error.hpp"

namespace cropsight::learning {
namespace {
void check(int rc, const std::string& where) {
  if (rc != 0) throw Error(where, std::string("XGBoost: ") + XGBGetLastError());
}
struct DMatrix {
  DMatrixHandle h = nullptr;
  DMatrix(const std::vector<float>& x, std::size_t rows, std::size_t cols) {
    if (x.size() != rows * cols) throw Error("gbdt", "feature matrix size differs from rows x cols");
    check(
        XGDMatrixCreateFromMat(x.data(), bst_ulong(rows), bst_ulong(cols), std::numeric_limits<float>::quiet_NaN(), &h),
        "gbdt");
  }
  ~DMatrix() {
    if (h) XGDMatrixFree(h);
  }
};
}  // namespace

Gbdt::Gbdt() = default;
Gbdt::~Gbdt() {
  if (booster_) XGBoosterFree(booster_);
}
Gbdt::Gbdt(Gbdt&& o) noexcept
    : booster_(std::exchange(o.booster_, nullptr)), num_class_(o.num_class_), cols_(o.cols_) {}
Gbdt& Gbdt::operator=(Gbdt&& o) noexcept {
  if (this != &o) {
    if (booster_) XGBoosterFree(booster_);
    booster_ = std::exchange(o.booster_, nullptr);
    num_class_ = o.num_class_;
    cols_ = o.cols_;
  }
  return *this;
}

bool Gbdt::trained() const { return booster_ != nullptr; }

void Gbdt::train(const std::vector<float>& x, std::size_t rows, std::size_t cols, const std::vector<float>& labels,
                 const std::vector<float>& weights, const GbdtParams& p) {
  if (labels.size() != rows) throw Error("gbdt", "label count differs from row count");
  if (!weights.empty() && weights.size() != rows) throw Error("gbdt", "weight count differs from row count");
  if (p.num_class < 2) throw Error("gbdt", "need at least two classes");
  for (float l : labels)
    if (l < 0 || l >= float(p.num_class)) throw Error("gbdt", "label " + std::to_string(l) + " out of range");
  DMatrix d(x, rows, cols);
  check(XGDMatrixSetFloatInfo(d.h, "label", labels.data(), bst_ulong(rows)), "gbdt");
  if (!weights.empty()) check(XGDMatrixSetFloatInfo(d.h, "weight", weights.data(), bst_ulong(rows)), "gbdt");
  if (booster_) XGBoosterFree(booster_), booster_ = nullptr;
  check(XGBoosterCreate(&d.h, 1, &booster_), "gbdt");
  auto set = [&](const char* k, const std::string& v) { check(XGBoosterSetParam(booster_, k, v.c_str()), "gbdt"); };
  set("objective", "multi:softprob");
  set("num_class", std::to_string(p.num_class));
  set("tree_method", "hist");
  set("max_depth", std::to_string(p.max_depth));
  set("eta", std::to_string(p.eta));
  set("subsample", std::to_string(p.subsample));
  set("colsample_bytree", std::to_string(p.colsample));
  set("min_child_weight", std::to_string(p.min_child_weight));
  set("lambda", std::to_string(p.lambda));
  set("max_bin", std::to_string(p.max_bin));
  set("nthread", std::to_string(p.nthread));
  set("seed", std::to_string(p.seed));
  set("verbosity", "0");
  for (int it = 0; it < p.rounds; ++it) check(XGBoosterUpdateOneIter(booster_, it, d.h), "gbdt");
  num_class_ = p.num_class;
  cols_ = cols;
}

std::vector<float> Gbdt::predict_proba(const std::vector<float>& x, std::size_t rows, std::size_t cols) const {
  if (!booster_) throw Error("gbdt", "model is not trained");
  if (cols != cols_)
    throw Error("gbdt", "model expects " + std::to_string(cols_) + " features, got " + std::to_string(cols));
  if (rows == 0) return {};
  DMatrix d(x, rows, cols);
  bst_ulong len = 0;
  const float* out = nullptr;
  check(XGBoosterPredict(booster_, d.h, 0, 0, 0, &len, &out), "gbdt");
  if (len != bst_ulong(rows) * bst_ulong(num_class_)) throw Error("gbdt", "unexpected prediction size");
  return std::vector<float>(out, out + len);
}

std::vector<int> Gbdt::predict(const std::vector<float>& x, std::size_t rows, std::size_t cols) const {
  const std::vector<float> p = predict_proba(x, rows, cols);
  std::vector<int> out(rows);
  for (std::size_t i = 0; i < rows; ++i) {
    const float* r = p.data() + i * std::size_t(num_class_);
    out[i] = int(std::max_element(r, r + num_class_) - r);
  }
  return out;
}

void Gbdt::set_attribute(const std::string& key, const std::string& value) {
  if (!booster_) throw Error("gbdt", "model is not trained");
  check(XGBoosterSetAttr(booster_, key.c_str(), value.c_str()), "gbdt");
}

std::string Gbdt::attribute(const std::string& key) const {
  if (!booster_) return "";
  const char* out = nullptr;
  int success = 0;
  check(XGBoosterGetAttr(booster_, key.c_str(), &out, &success), "gbdt");
  return success && out ? std::string(out) : std::string();
}

void Gbdt::save(const std::filesystem::path& path) const {
  if (!booster_) throw Error(path.string(), "model is not trained");
  // Store our own bookkeeping as attributes so that one file is the whole model.
  auto* self = const_cast<Gbdt*>(this);
  self->set_attribute("cropsight.num_class", std::to_string(num_class_));
  self->set_attribute("cropsight.num_features", std::to_string(cols_));
  bst_ulong len = 0;
  const char* buf = nullptr;
  check(XGBoosterSaveModelToBuffer(booster_, R"({"format": "json"})", &len, &buf), path.string());
  // Atomic: write a temporary sibling, then rename (learning does not depend on io).
  const std::filesystem::path tmp = path.string() + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary);
    out.write(buf, std::streamsize(len));
    if (!out) throw Error(path.string(), "cannot write model file");
  }
  std::filesystem::rename(tmp, path);
}

Gbdt Gbdt::load(const std::filesystem::path& path, int nthread) {
  const std::string where = path.string();
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(where, "cannot open model file");
  std::ostringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  Gbdt g;
  check(XGBoosterCreate(nullptr, 0, &g.booster_), where);
  if (XGBoosterLoadModelFromBuffer(g.booster_, text.data(), bst_ulong(text.size())) != 0)
    throw Error(where, std::string("not an XGBoost model: ") + XGBGetLastError());
  check(XGBoosterSetParam(g.booster_, "nthread", std::to_string(nthread).c_str()), where);
  try {
    g.num_class_ = std::stoi(g.attribute("cropsight.num_class"));
    g.cols_ = std::stoul(g.attribute("cropsight.num_features"));
  } catch (const std::exception&) {
    throw Error(where, "model lacks cropsight.num_class / cropsight.num_features attributes");
  }
  return g;
}

}  // namespace cropsight::learning
