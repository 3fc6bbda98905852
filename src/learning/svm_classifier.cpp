#include "learning/svm_classifier.hpp"

#include <libsvm/svm.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <mutex>
#include <sstream>
#include <string>
#include <vector>

#include "core/cpu_dispatch.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"
#include "learning/rbf_blocks.hpp"
#include "learning/temp_file.hpp"

namespace cropsight::learning::detail {

namespace {
void silent(const char*) {}  // libsvm prints optimisation progress on stdout otherwise

typedef float v8f __attribute__((vector_size(32)));
typedef float v4f __attribute__((vector_size(16)));

// Σ_i coef_i · exp(−γ · max(0, |sv_i|² + z2 − 2 sv_i·z)) over `n` support vectors stored as rows
// of `stride` floats (a multiple of 16, zero-padded like `z`; only the columns where some support
// vector is non-zero, see SvmClassifier::active_), z2 = |x|² over every column, with L-lane vectors
// and two accumulators per dot product. Same decision value as libsvm's to float rounding (tested).
template <class V, int L>
__attribute__((always_inline)) inline float rbf_sum_impl(int n, int stride, const float* __restrict sv,
                                                         const float* __restrict norm2, const float* __restrict coef,
                                                         const float* __restrict z, float z2, float g) {
  float s = 0.0f;
  for (int i = 0; i < n; ++i) {
    const float* r = sv + std::size_t(i) * std::size_t(stride);
    V d0 = {}, d1 = {};
    for (int j = 0; j < stride; j += 2 * L) {
      V a, b, u, w;
      __builtin_memcpy(&a, z + j, sizeof(V)), __builtin_memcpy(&b, z + j + L, sizeof(V));
      __builtin_memcpy(&u, r + j, sizeof(V)), __builtin_memcpy(&w, r + j + L, sizeof(V));
      d0 += a * u, d1 += b * w;
    }
    const V d = d0 + d1;
    float dot = 0.0f;
    for (int l = 0; l < L; ++l) dot += d[l];
    s += coef[i] * std::exp(-g * std::max(0.0f, norm2[i] + z2 - 2.0f * dot));
  }
  return s;
}
// The baseline build of the kernel (4 lanes); CPUs with AVX2 + FMA run RbfBlocks instead.
float rbf_sum_base(int n, int stride, const float* sv, const float* norm2, const float* coef, const float* z, float z2,
                   float g) {
  return rbf_sum_impl<v4f, 4>(n, stride, sv, norm2, coef, z, z2, g);
}
}  // namespace

SvmClassifier::SvmClassifier(const Dataset& data, const ClassifierParams& params, const std::string& where)
    : type_(params.type), dim_(data.dim) {
  const std::size_t n = data.size();
  const std::size_t npos = data.positives(), nneg = n - npos;
  if (npos == 0 || nneg == 0)
    throw Error(where, "training data needs both classes (positives " + std::to_string(npos) + ", negatives " +
                           std::to_string(nneg) + ")");
  // Dense rows as libsvm node lists: dim entries plus the -1 terminator each.
  std::vector<svm_node> nodes(n * std::size_t(dim_ + 1));
  std::vector<svm_node*> rows(n);
  std::vector<double> y(n);
  for (std::size_t i = 0; i < n; ++i) {
    svm_node* r = nodes.data() + i * std::size_t(dim_ + 1);
    const float* x = data.row(i);
    for (int j = 0; j < dim_; ++j) r[j] = {j + 1, double(x[j])};
    r[dim_] = {-1, 0.0};
    rows[i] = r;
    y[i] = data.labels[i] == 1 ? 1.0 : -1.0;
  }
  svm_problem prob{};
  prob.l = int(n);
  prob.y = y.data();
  prob.x = rows.data();

  rbf_ = params.type == "svm-rbf";
  svm_parameter p{};
  p.svm_type = C_SVC;
  p.kernel_type = rbf_ ? RBF : LINEAR;
  p.gamma = rbf_ ? params.rbf_gamma : 0.0;
  p.C = rbf_ ? params.rbf_c : params.linear_c;
  p.cache_size = params.svm_cache_mb;
  p.eps = params.svm_eps;
  p.shrinking = 1;
  p.probability = 0;
  // Class weights n / (k · n_j) with k = 2 classes: each class contributes equally to the loss.
  int weight_label[2] = {1, -1};
  double weight[2] = {double(n) / (2.0 * double(npos)), double(n) / (2.0 * double(nneg))};
  if (params.balanced_weights) {
    p.nr_weight = 2;
    p.weight_label = weight_label;
    p.weight = weight;
  }
  if (const char* msg = svm_check_parameter(&prob, &p)) throw Error(where, std::string("libsvm: ") + msg);
  svm_set_print_string_function(&silent);
  svm_model* trained = svm_train(&prob, &p);
  // The trained model points into `nodes`; go through libsvm's own text format so that the
  // object holds exactly what a saved file holds (and owns its memory).
  TempFile tmp;
  const int rc = svm_save_model(tmp.path().c_str(), trained);
  svm_free_and_destroy_model(&trained);
  if (rc != 0) throw Error(tmp.path().string(), "libsvm could not write its model");
  load_text(io::read_file(tmp.path()), where);
}

SvmClassifier::SvmClassifier(const ClassifierParams& params, int dim, const std::string& libsvm_text,
                             const std::string& where)
    : type_(params.type), dim_(dim) {
  load_text(libsvm_text, where);
}

SvmClassifier::~SvmClassifier() {
  if (model_) svm_free_and_destroy_model(&model_);
}

// libsvm's svm_load_model trusts its text: it reads `total_sv` lines after "SV" without checking
// that they are there (a model cut in half turned 25 detections into 116: the missing support
// vectors were stale buffer contents), allocates its rho / label / nr_sv arrays from nr_class as
// written (a huge one was a 16-exabyte allocation, fuzzing finding 28), leaves an array null when
// its line is missing (finding 26) and prints to stderr on an unknown line. cropsight's models are
// two-class C-SVCs, so the header is checked line by line before libsvm sees it: known keys only,
// each once, nr_class 2 before the per-class lines, the value counts of a two-class model, nr_sv
// summing to total_sv; then the "SV" line and exactly total_sv non-empty lines.
namespace {
// The whitespace-separated fields of `rest`, each a number (integers where `integers`), exactly
// `count` of them; false otherwise.
bool numbers(const std::string& rest, std::size_t count, bool integers, std::vector<double>* out = nullptr) {
  std::istringstream in(rest);
  std::vector<double> v;
  for (std::string field; in >> field;) {
    char* end = nullptr;
    const double x = integers ? double(std::strtol(field.c_str(), &end, 10)) : std::strtod(field.c_str(), &end);
    if (end == field.c_str() || *end != '\0' || !std::isfinite(x)) return false;
    if (integers && (x < -1e9 || x > 1e9)) return false;
    v.push_back(x);
  }
  if (out) *out = v;
  return v.size() == count;
}

void check_libsvm_text(const std::string& text, const std::string& where) {
  const auto bad = [&](const std::string& problem) { throw Error(where, "embedded SVM model: " + problem); };
  std::istringstream in(text);
  std::string line;
  std::vector<std::string> seen;
  long total = -1;
  std::vector<double> nr_sv;
  bool sv = false;
  while (std::getline(in, line)) {
    if (line == "SV") {
      sv = true;
      break;
    }
    const auto space = line.find(' ');
    const std::string key = line.substr(0, space), rest = space == std::string::npos ? "" : line.substr(space + 1);
    if (std::find(seen.begin(), seen.end(), key) != seen.end()) bad("header line '" + key + "' appears twice");
    seen.push_back(key);
    const bool after_nr_class = std::find(seen.begin(), seen.end(), "nr_class") != seen.end();
    if (key == "svm_type") {
      if (rest != "c_svc") bad("svm_type is not c_svc");
    } else if (key == "kernel_type") {
      if (rest != "linear" && rest != "rbf") bad("kernel_type is not linear or rbf");
    } else if (key == "degree") {
      if (!numbers(rest, 1, true)) bad("bad degree line");
    } else if (key == "gamma" || key == "coef0") {
      if (!numbers(rest, 1, false)) bad("bad " + key + " line");
    } else if (key == "nr_class") {
      if (rest != "2") bad("nr_class is not 2 (cropsight's SVMs are two-class)");
    } else if (key == "total_sv") {
      std::vector<double> v;
      if (!numbers(rest, 1, true, &v) || v[0] < 1) bad("bad total_sv line");
      total = long(v[0]);
    } else if (key == "rho" || key == "probA" || key == "probB") {
      if (!after_nr_class || !numbers(rest, 1, false)) bad("bad " + key + " line (one number, after nr_class)");
    } else if (key == "label") {
      if (!after_nr_class || !numbers(rest, 2, true)) bad("bad label line (two integers, after nr_class)");
    } else if (key == "nr_sv") {
      if (!after_nr_class || !numbers(rest, 2, true, &nr_sv) || nr_sv[0] < 0 || nr_sv[1] < 0)
        bad("bad nr_sv line (two counts, after nr_class)");
    } else {
      bad("unknown header line '" + line.substr(0, 40) + "'");
    }
  }
  if (!sv) bad("no SV section");
  for (const char* key : {"svm_type", "kernel_type", "nr_class", "total_sv", "rho", "label", "nr_sv"})
    if (std::find(seen.begin(), seen.end(), key) == seen.end()) bad(std::string("no ") + key + " line");
  if (long(nr_sv[0] + nr_sv[1]) != total) bad("nr_sv does not sum to total_sv");
  long lines = 0;
  while (std::getline(in, line))
    if (!line.empty()) ++lines;
  if (lines != total)
    throw Error(where, "embedded SVM model is truncated or padded: its header says " + std::to_string(total) +
                           " support vectors, " + std::to_string(lines) + " are present");
  if (text.back() != '\n') throw Error(where, "embedded SVM model is truncated (last line incomplete)");
}
}  // namespace

// A function-try-block: when a check below rejects the model, libsvm's model is freed before the
// error leaves (the constructors call this, and a constructor that throws runs no destructor).
void SvmClassifier::load_text(const std::string& text, const std::string& where) try {
  check_libsvm_text(text, where);
  {
    TempFile tmp;
    tmp.write(text);
    // svm_load_model splits its lines with strtok, whose position is one static pointer for the
    // whole process: two threads loading models at once (a batch's workers) read each other's
    // freed buffers. The lock serialises the loads only; prediction needs none.
    static std::mutex libsvm_load;
    const std::lock_guard lock(libsvm_load);
    model_ = svm_load_model(tmp.path().c_str());
  }
  if (!model_) throw Error(where, "libsvm cannot parse the embedded SVM model");
  text_ = text;
  const svm_parameter& p = model_->param;
  if (p.svm_type != C_SVC || model_->nr_class != 2) throw Error(where, "SVM model is not a two-class C-SVC");
  const bool want_rbf = type_ == "svm-rbf";
  if ((want_rbf && p.kernel_type != RBF) || (!want_rbf && p.kernel_type != LINEAR))
    throw Error(where, "SVM model kernel does not match classifier type '" + type_ + "'");
  rbf_ = want_rbf;
  gamma_ = p.gamma;
  const int l0 = model_->label[0], l1 = model_->label[1];
  if (!((l0 == 1 && l1 == -1) || (l0 == -1 && l1 == 1))) throw Error(where, "SVM model labels must be +1 and -1");
  // libsvm's decision value is positive for label[0]; flip so that positive always means head.
  sign_ = l0 == 1 ? 1.0f : -1.0f;
  rho_ = float(model_->rho[0]);
  const int l = model_->l;
  // Support vectors as dense rows of dim_ floats first.
  using RowMajor = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  RowMajor sv = RowMajor::Zero(l, dim_);
  coef_.resize(l);
  for (int i = 0; i < l; ++i) {
    coef_[i] = float(model_->sv_coef[0][i]);
    for (const svm_node* nd = model_->SV[i]; nd->index != -1; ++nd) {
      if (nd->index < 1 || nd->index > dim_)
        throw Error(where, "SVM support vector has feature index " + std::to_string(nd->index) + " outside 1.." +
                               std::to_string(dim_));
      sv(i, nd->index - 1) = float(nd->value);
    }
  }
  if (!sv.allFinite() || !coef_.allFinite() || !std::isfinite(rho_))
    throw Error(where, "SVM model has non-finite values");
  sv_norm2_ = sv.rowwise().squaredNorm();
  w_ = sv.transpose() * coef_;
  // The RBF kernel's layout: only the columns where some support vector is non-zero take part in
  // the dot products (a column that is 0 in every support vector adds 0 to each sv·z; it still
  // counts in |z|²). VFH bins that no training cluster fills standardise to 0 in every support
  // vector: about half of the 308 (broccoli models), so this halves the kernel's work. Rows are
  // zero-padded to svp_stride_ floats.
  active_.clear();
  for (int j = 0; j < dim_; ++j)
    if ((sv.col(j).array() != 0.0f).any()) active_.push_back(j);
  svp_stride_ = (int(active_.size()) + 15) / 16 * 16;
  svp_.assign(std::size_t(l) * std::size_t(svp_stride_), 0.0f);
  for (int i = 0; i < l; ++i)
    for (std::size_t k = 0; k < active_.size(); ++k)
      svp_[std::size_t(i) * std::size_t(svp_stride_) + k] = sv(i, active_[k]);
  // CPUs with AVX2 + FMA: the same support vectors in RbfBlocks' layout instead (rbf_blocks.hpp).
  // svp_ stays: baseline_score() runs the baseline kernel on this CPU too (tests).
  if (RbfBlocks::available())
    blocks_ = RbfBlocks(svp_.data(), l, svp_stride_, coef_.data(), sv_norm2_.data(), float(gamma_));
} catch (...) {
  if (model_) svm_free_and_destroy_model(&model_);
  throw;
}

float SvmClassifier::gather_active(const float* x, float* zp) const {
  const std::size_t na = active_.size();
  for (std::size_t k = 0; k < na; ++k) zp[k] = x[active_[k]];
  std::fill(zp + na, zp + svp_stride_, 0.0f);
  return Eigen::Map<const Eigen::VectorXf>(x, dim_).squaredNorm();
}

float SvmClassifier::score(const float* x) const { return score_with(x, false); }

float SvmClassifier::baseline_score(const float* x) const { return score_with(x, true); }

float SvmClassifier::score_with(const float* x, bool baseline) const {
  float dec;
  if (rbf_) {
    // K(sv, z) = exp(-γ |sv − z|²) with |sv − z|² = |sv|² + |z|² − 2 sv·z: one vectorised dot
    // product per support vector over the active columns (rows padded to svp_stride_). z's active
    // columns are gathered on the stack (on the heap only past 1024 of them).
    float buf[1024];
    std::vector<float> heap;
    float* zp = svp_stride_ <= 1024 ? buf : (heap.resize(std::size_t(svp_stride_)), heap.data());
    const float z2 = gather_active(x, zp);
    if (!blocks_.empty() && !baseline) {
      float sum = 0.0f;
      blocks_.sums(zp, &z2, 1, &sum);
      dec = sum - rho_;
    } else {
      dec = rbf_sum_base(int(coef_.size()), svp_stride_, svp_.data(), sv_norm2_.data(), coef_.data(), zp, z2,
                         float(gamma_)) -
            rho_;
    }
  } else {
    dec = w_.dot(Eigen::Map<const Eigen::VectorXf>(x, dim_)) - rho_;
  }
  return sign_ * dec;
}

void SvmClassifier::score_rows(const float* x, std::size_t rows, float* out) const {
  if (!rbf_ || blocks_.empty() || rows < 2) {
    Classifier::score_rows(x, rows, out);
    return;
  }
  const std::size_t stride = std::size_t(svp_stride_);
  std::vector<float> zp(rows * stride), z2(rows);
  for (std::size_t r = 0; r < rows; ++r) z2[r] = gather_active(x + r * std::size_t(dim_), zp.data() + r * stride);
  blocks_.sums(zp.data(), z2.data(), rows, out);
  for (std::size_t r = 0; r < rows; ++r) out[r] = sign_ * (out[r] - rho_);
}

double SvmClassifier::libsvm_score(const float* x) const {
  std::vector<svm_node> nodes(std::size_t(dim_) + 1);
  for (int j = 0; j < dim_; ++j) nodes[std::size_t(j)] = {j + 1, double(x[j])};
  nodes[std::size_t(dim_)] = {-1, 0.0};
  double dec = 0.0;
  svm_predict_values(model_, nodes.data(), &dec);
  return double(sign_) * dec;
}

}  // namespace cropsight::learning::detail
