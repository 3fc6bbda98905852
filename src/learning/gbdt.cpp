#include "cropsight/learning/gbdt.hpp"

#include <xgboost/c_api.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <deque>
#include <limits>
#include <nlohmann/json.hpp>
#include <tuple>
#include <utility>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/cpu_dispatch.hpp"
#include "core/parallel_for.hpp"
#include "cropsight/core/config.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"

#if CROPSIGHT_X86_DISPATCH
#include <immintrin.h>
#endif

namespace cropsight::learning {
namespace {
// XGBoost's messages start "[time] path/to/source.cc:123: reason" and go on with a multi-line
// stack trace: keep the reason.
std::string xgb_reason() {
  std::string s = XGBGetLastError();
  s = s.substr(0, s.find('\n'));
  if (s.rfind('[', 0) == 0)
    if (const auto at = s.find(": "); at != std::string::npos) s = s.substr(at + 2);
  // Some messages quote the whole offending JSON document.
  constexpr std::size_t kMax = 200;
  if (s.size() > kMax) s = s.substr(0, kMax) + "...";
  return s;
}
void check(int rc, const std::string& where) {
  if (rc != 0) throw Error(where, "XGBoost: " + xgb_reason());
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

// The compiled forest: every tree's nodes in breadth-first order, children adjacent, so that a
// split node sends x to left + !(x < value) (XGBoost's own rule; NaN = missing = default child).
// A leaf steps to itself whatever x (threshold NaN, left = itself - 1, missing goes right), so every row can
// take exactly `depth` steps in a tree: rows walk a tree in lock-step groups, without a branch
// per node, which hides the latency of the dependent loads.
struct Gbdt::Flat {
  struct Node {
    float threshold;
    std::uint32_t feature;  // bit 31: a missing value goes right
    std::int32_t left;      // index (within the tree) of the left child; a leaf: its own index
  };
  std::vector<Node> nodes;
  std::vector<float> leaf;  // leaf value per node (0 for split nodes)
  std::vector<std::uint8_t> is_leaf;
  std::vector<std::uint32_t> root;  // first node of each tree
  std::vector<int> depth;           // steps from the root to the deepest leaf
  std::vector<int> group;           // class of each tree
  float base_score = 0.5f;
};

Gbdt::Gbdt() = default;
Gbdt::~Gbdt() {
  if (booster_) XGBoosterFree(booster_);
}
Gbdt::Gbdt(Gbdt&& o) noexcept
    : booster_(std::exchange(o.booster_, nullptr)),
      num_class_(o.num_class_),
      cols_(o.cols_),
      nthread_(o.nthread_),
      flat_(std::move(o.flat_)) {}
Gbdt& Gbdt::operator=(Gbdt&& o) noexcept {
  if (this != &o) {
    if (booster_) XGBoosterFree(booster_);
    booster_ = std::exchange(o.booster_, nullptr);
    num_class_ = o.num_class_;
    cols_ = o.cols_;
    nthread_ = o.nthread_;
    flat_ = std::move(o.flat_);
  }
  return *this;
}

bool Gbdt::trained() const { return booster_ != nullptr; }

void GbdtParams::validate(const std::string& where, const std::string& prefix) const {
  cropsight::detail::check_range(where, prefix + "num_class", num_class, Range::at_least(2));
  check_config(*this, where, prefix);
}

void Gbdt::train(const std::vector<float>& x, std::size_t rows, std::size_t cols, const std::vector<float>& labels,
                 const std::vector<float>& weights, const GbdtParams& p) {
  if (labels.size() != rows) throw Error("gbdt", "label count differs from row count");
  if (!weights.empty() && weights.size() != rows) throw Error("gbdt", "weight count differs from row count");
  p.validate("gbdt");
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
  nthread_ = std::max(1, p.nthread);
  flat_.reset();
}

std::vector<float> Gbdt::predict_proba(const std::vector<float>& x, std::size_t rows, std::size_t cols) const {
  if (!booster_) throw Error("gbdt", "model is not trained");
  if (flat_) {
    std::vector<float> out(rows * std::size_t(num_class_));
    predict_flat(x, rows, cols, nullptr, out.data());
    return out;
  }
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

void Gbdt::compile() {
  if (!booster_) throw Error("gbdt", "model is not trained");
  bst_ulong len = 0;
  const char* buf = nullptr;
  check(XGBoosterSaveModelToBuffer(booster_, R"({"format": "json"})", &len, &buf), "gbdt");
  const auto j = nlohmann::json::parse(buf, buf + len);
  const auto& learner = j.at("learner");
  auto flat = std::make_shared<Flat>();
  flat->base_score = std::stof(learner.at("learner_model_param").at("base_score").get<std::string>());
  const auto& model = learner.at("gradient_booster").at("model");
  flat->group = model.at("tree_info").get<std::vector<int>>();
  const auto& trees = model.at("trees");
  if (trees.size() != flat->group.size()) throw Error("gbdt", "compile: tree_info and trees differ in length");
  for (const auto& t : trees) {
    const auto left = t.at("left_children").get<std::vector<int>>();
    const auto right = t.at("right_children").get<std::vector<int>>();
    const auto feat = t.at("split_indices").get<std::vector<std::int64_t>>();
    const auto cond = t.at("split_conditions").get<std::vector<float>>();
    const auto dleft = t.at("default_left").get<std::vector<int>>();
    if (t.contains("split_type"))
      for (int st : t.at("split_type").get<std::vector<int>>())
        if (st != 0) throw Error("gbdt", "compile: categorical splits are not supported");
    const std::size_t base = flat->nodes.size();
    flat->root.push_back(std::uint32_t(base));
    // Breadth-first re-layout: (old node, new index relative to the tree's first node, depth).
    std::deque<std::tuple<int, std::size_t, int>> queue{{0, 0, 0}};
    flat->nodes.emplace_back();
    int depth = 0;
    while (!queue.empty()) {
      const auto [old, idx, d] = queue.front();
      queue.pop_front();
      depth = std::max(depth, d);
      const std::size_t o = std::size_t(old);
      if (left.at(o) < 0) {
        // !(x < NaN) holds for every x and a missing x goes right: left + 1 = the leaf itself.
        flat->nodes[base + idx] = {std::numeric_limits<float>::quiet_NaN(), 0x80000000u, std::int32_t(idx) - 1};
        flat->leaf.resize(flat->nodes.size(), 0.f);
        flat->is_leaf.resize(flat->nodes.size(), 0);
        flat->leaf[base + idx] = cond.at(o);
        flat->is_leaf[base + idx] = 1;
        continue;
      }
      const std::size_t l = flat->nodes.size() - base;
      const std::uint32_t f = std::uint32_t(feat.at(o));
      if (f >= cols_) throw Error("gbdt", "compile: split on a feature beyond the model's count");
      flat->nodes[base + idx] = {cond.at(o), f | (dleft.at(o) ? 0u : 0x80000000u), std::int32_t(l)};
      flat->nodes.emplace_back();
      flat->nodes.emplace_back();
      queue.emplace_back(left[o], l, d + 1);
      queue.emplace_back(right.at(o), l + 1, d + 1);
    }
    flat->depth.push_back(depth);
  }
  flat->leaf.resize(flat->nodes.size(), 0.f);
  flat->is_leaf.resize(flat->nodes.size(), 0);
  for (int g : flat->group)
    if (g < 0 || g >= num_class_) throw Error("gbdt", "compile: tree of an unknown class");
  flat_ = std::move(flat);
}

namespace {
#if CROPSIGHT_X86_DISPATCH
// Eight rows down one tree together, `depth` steps: the scalar step (see predict_rows) with the
// nodes' three fields and the rows' feature values gathered eight at a time. Nodes are 12 bytes
// {threshold, feature, left}: field k of node n is the 32-bit word 3n + k. Integer selects and
// one float comparison per lane, so the leaves reached are the scalar loop's.
template <class Node>
CROPSIGHT_TARGET_AVX2 void walk8_avx2(const Node* tree, const float* row, std::size_t cols, int depth,
                                      std::int32_t* out) {
  static_assert(sizeof(Node) == 12, "walk8_avx2 reads nodes as three 32-bit words");
  const auto* words = reinterpret_cast<const int*>(tree);
  const __m256i row_off = _mm256_mullo_epi32(_mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7), _mm256_set1_epi32(int(cols)));
  const __m256i three = _mm256_set1_epi32(3), low31 = _mm256_set1_epi32(0x7fffffff), one = _mm256_set1_epi32(1);
  __m256i n = _mm256_setzero_si256();
  for (int d = 0; d < depth; ++d) {
    const __m256i w = _mm256_mullo_epi32(n, three);
    const __m256 thr = _mm256_i32gather_ps(reinterpret_cast<const float*>(words), w, 4);
    const __m256i feat = _mm256_i32gather_epi32(words + 1, w, 4);
    const __m256i left = _mm256_i32gather_epi32(words + 2, w, 4);
    const __m256 v = _mm256_i32gather_ps(row, _mm256_add_epi32(row_off, _mm256_and_si256(feat, low31)), 4);
    const __m256i lt = _mm256_castps_si256(_mm256_cmp_ps(v, thr, _CMP_LT_OQ));   // false for NaN
    const __m256i nan = _mm256_castps_si256(_mm256_cmp_ps(v, v, _CMP_UNORD_Q));  // missing value
    const __m256i dir = _mm256_andnot_si256(lt, one);                            // !(v < threshold)
    const __m256i missing_dir = _mm256_srli_epi32(feat, 31);                     // bit 31: go right
    n = _mm256_add_epi32(left, _mm256_blendv_epi8(dir, missing_dir, nan));
  }
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(out), n);
}
#endif

// Rows [begin, end) through every tree, a block of rows per tree (the tree stays in cache) in
// lock-step groups of kLanes rows, then XGBoost's softmax (common::Softmax: expf, double sum)
// and the first arg-max. Sums start at base_score and add leaf values in tree order, in float,
// as XGBoost's CPU predictor does.
template <class Flat>
void predict_rows(const Flat& f, const float* x, std::size_t cols, int num_class, std::size_t begin, std::size_t end,
                  int* out, float* proba) {
  constexpr std::size_t kBlock = 256, kLanes = 8;
  const std::size_t C = std::size_t(num_class);
  std::vector<float> margin(kBlock * C);
  std::vector<float> e(C);
#if CROPSIGHT_X86_DISPATCH
  // The feature gather's offsets are 32-bit: 8 rows of cols floats must stay below 2^31.
  const bool avx2 = cropsight::detail::cpu_has_avx2_fma() && cols < (std::size_t(1) << 27);
#endif
  // One step: the child a row goes to (missing: default child; a leaf stays put for finite x).
  auto step = [](const typename Flat::Node& nd, const float* row) {
    const float v = row[nd.feature & 0x7fffffffu];
    return nd.left + (std::isnan(v) ? std::int32_t(nd.feature >> 31) : std::int32_t(!(v < nd.threshold)));
  };
  for (std::size_t b0 = begin; b0 < end; b0 += kBlock) {
    const std::size_t nb = std::min(kBlock, end - b0);
    std::fill(margin.begin(), margin.end(), f.base_score);
    for (std::size_t t = 0; t < f.root.size(); ++t) {
      const auto* tree = f.nodes.data() + f.root[t];
      const float* leaf = f.leaf.data() + f.root[t];
      const std::uint8_t* is_leaf = f.is_leaf.data() + f.root[t];
      const int depth = f.depth[t];
      float* m = margin.data() + std::size_t(f.group[t]);
      std::size_t r = 0;
      for (; r + kLanes <= nb; r += kLanes) {
        std::int32_t n[kLanes] = {};
        const float* row = x + (b0 + r) * cols;
#if CROPSIGHT_X86_DISPATCH
        if (avx2) {
          walk8_avx2(tree, row, cols, depth, n);
        } else
#endif
        {
          for (int d = 0; d < depth; ++d)
            for (std::size_t j = 0; j < kLanes; ++j) n[j] = step(tree[n[j]], row + j * cols);
        }
        for (std::size_t j = 0; j < kLanes; ++j) m[(r + j) * C] += leaf[n[j]];
      }
      for (; r < nb; ++r) {
        const float* row = x + (b0 + r) * cols;
        std::int32_t n = 0;
        while (!is_leaf[n]) n = step(tree[n], row);
        m[r * C] += leaf[n];
      }
    }
    for (std::size_t r = 0; r < nb; ++r) {
      const float* m = margin.data() + r * C;
      const float wmax = *std::max_element(m, m + C);
      double wsum = 0.0;
      for (std::size_t c = 0; c < C; ++c) wsum += (e[c] = std::exp(m[c] - wmax));
      for (std::size_t c = 0; c < C; ++c) e[c] /= float(wsum);
      if (out) out[b0 + r] = int(std::max_element(e.begin(), e.end()) - e.begin());
      if (proba) std::copy(e.begin(), e.end(), proba + (b0 + r) * C);
    }
  }
}
}  // namespace

void Gbdt::predict_flat(const std::vector<float>& x, std::size_t rows, std::size_t cols, int* labels,
                        float* proba) const {
  if (cols != cols_)
    throw Error("gbdt", "model expects " + std::to_string(cols_) + " features, got " + std::to_string(cols));
  if (x.size() != rows * cols) throw Error("gbdt", "feature matrix size differs from rows x cols");
  // Rows are independent: split over nthread threads; small inputs stay on the calling thread.
  cropsight::detail::parallel_for(rows, nthread_, 256, [&](std::size_t b, std::size_t e) {
    predict_rows(*flat_, x.data(), cols, num_class_, b, e, labels, proba);
  });
}

std::vector<int> Gbdt::predict(const std::vector<float>& x, std::size_t rows, std::size_t cols) const {
  if (flat_) {
    std::vector<int> out(rows);
    predict_flat(x, rows, cols, out.data(), nullptr);
    return out;
  }
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
  if (std::filesystem::is_directory(path)) throw Error(path.string(), "is a directory, expected a file name");
  // Atomic, and no temporary left behind on a failure.
  io::write_file_atomic(path, std::string(buf, len));
}

namespace {

// XGBoost's "no parent" (the root's parent index in its JSON).
constexpr std::int64_t kNoParent = 2147483647;

// A decimal count written as a string (XGBoost's parameters); 0 when it is not one.
std::int64_t parse_count(const std::string& text) {
  try {
    std::size_t used = 0;
    const std::int64_t v = std::stoll(text, &used);
    return used == text.size() ? v : 0;
  } catch (const std::exception&) {
    return 0;
  }
}

// The count XGBoost writes as a decimal string under `key` of object `o`: -1 when absent or not a
// string, 0 when the string is not a count.
std::int64_t count_at(const nlohmann::json& o, const char* key) {
  return o.contains(key) && o[key].is_string() ? parse_count(o[key].get<std::string>()) : -1;
}

// One tree's nodes (check_tree_model below says why each rule): num_nodes entries in every per-node
// array, children after their parents, parents that name them, features within the model's, no
// categorical splits.
void check_tree_nodes(const nlohmann::json& t, std::int64_t num_feature, const std::string& where) {
  const auto fail = [&](const std::string& problem) { throw Error(where, "not a valid XGBoost model: " + problem); };
  const auto param = t.find("tree_param");
  if (param == t.end() || !param->is_object() || !param->contains("num_nodes") || !(*param)["num_nodes"].is_string())
    fail("a tree without tree_param.num_nodes");
  const std::int64_t nodes = parse_count((*param)["num_nodes"].get<std::string>());
  if (nodes < 1 || nodes > (std::int64_t(1) << 31)) fail("a tree's num_nodes is not a positive count");
  for (const char* key : {"left_children", "right_children", "parents", "split_indices", "split_conditions",
                          "default_left", "base_weights", "loss_changes", "sum_hessian"}) {
    const auto a = t.find(key);
    if (a == t.end() || !a->is_array() || std::int64_t(a->size()) != nodes)
      fail(std::string("a tree's \"") + key + "\" does not hold num_nodes entries");
  }
  for (const char* key : {"left_children", "right_children"}) {
    const auto& a = t[key];
    for (std::int64_t i = 0; i < nodes; ++i) {
      const auto& c = a[std::size_t(i)];
      if (!c.is_number_integer()) fail(std::string("a tree's \"") + key + "\" holds a non-integer");
      const std::int64_t v = c.get<std::int64_t>();
      if (v != -1 && (v <= i || v >= nodes)) fail("a tree node's child is not a later node of the same tree");
    }
  }
  // XGBoost writes each node's parent index unchecked: a parent far out of range was a SEGV in
  // RegTree::LoadModel (fuzzing finding 23), a near one silent heap corruption.
  const auto& parents = t["parents"];
  for (std::int64_t i = 0; i < nodes; ++i) {
    const auto& p = parents[std::size_t(i)];
    if (!p.is_number_integer()) fail("a tree's \"parents\" holds a non-integer");
    const std::int64_t v = p.get<std::int64_t>();
    const bool ok = i == 0 ? v == kNoParent
                           : v >= 0 && v < i &&
                                 (t["left_children"][std::size_t(v)].get<std::int64_t>() == i ||
                                  t["right_children"][std::size_t(v)].get<std::int64_t>() == i);
    if (!ok) fail("a tree node's parent is not the node whose child it is");
  }
  // A split's feature index reads the feature row: it must be one of the model's features.
  for (const auto& f : t["split_indices"])
    if (!f.is_number_integer() || f.get<std::int64_t>() < 0 || f.get<std::int64_t>() >= num_feature)
      fail("a tree's split feature is not one of the model's " + std::to_string(num_feature) + " features");
  // cropsight trains numerical splits only; XGBoost's categorical ones index further arrays.
  if (const auto st = t.find("split_type"); st != t.end())
    if (!st->is_array() || std::int64_t(st->size()) != nodes ||
        !std::all_of(st->begin(), st->end(), [](const nlohmann::json& v) { return v == 0; }))
      fail("a tree's \"split_type\" is not num_nodes numerical splits (0)");
  for (const char* key : {"categories", "categories_nodes", "categories_segments", "categories_sizes"})
    if (const auto c = t.find(key); c != t.end() && !(c->is_array() && c->empty()))
      fail(std::string("a tree holds categorical splits (\"") + key + "\")");
}

// XGBoost 1.7 trusts a JSON model's tree structure: two trees with the same "id" made its
// parallel loader free one tree twice (fuzz_gbdt_model; fuzz/regressions/gbdt_model/), and a
// child index out of range or pointing back up would send compile() out of bounds or round a
// cycle. So the gbtree model is checked first: tree ids 0..n-1 each once, tree_info of n
// entries, every per-node array of num_nodes entries, every child after its parent and in range,
// every parent the node that names the child, split features within the model's, no categorical
// splits.
void check_tree_model(const nlohmann::json& j, const std::string& where) {
  const auto fail = [&](const std::string& problem) { throw Error(where, "not a valid XGBoost model: " + problem); };
  const auto* learner = j.contains("learner") && j["learner"].is_object() ? &j["learner"] : nullptr;
  if (!learner) fail("no \"learner\" object");
  const auto gb = learner->find("gradient_booster");
  // Every value is type-checked before it is read: nlohmann's value() / get() throw type_error on
  // a mismatch ("name": [..] escaped as an internal error, fuzzing finding 27).
  const auto name = gb != learner->end() && gb->is_object() ? gb->find("name") : learner->end();
  if (gb == learner->end() || !gb->is_object() || name == gb->end() || !name->is_string() || *name != "gbtree")
    fail("the gradient booster is not a gbtree (cropsight trains and reads gbtree models)");
  const auto model = gb->find("model");
  if (model == gb->end() || !model->is_object()) fail("gbtree without its model");
  const auto trees = model->find("trees");
  const auto info = model->find("tree_info");
  if (trees == model->end() || !trees->is_array() || info == model->end() || !info->is_array() ||
      info->size() != trees->size())
    fail("\"trees\" and \"tree_info\" must be arrays of the same length");
  // The learner's feature and class counts (strings, as XGBoost writes its parameters).
  const auto mp = learner->find("learner_model_param");
  const bool has_mp = mp != learner->end() && mp->is_object();
  const std::int64_t num_feature = has_mp ? count_at(*mp, "num_feature") : -1;
  if (num_feature < 1 || num_feature > (std::int64_t(1) << 31))
    fail("learner_model_param.num_feature is not a positive count");
  const std::size_t n = trees->size();
  // XGBoost's loader reads tree_info[i] for every i below gbtree_model_param.num_trees, unchecked:
  // a num_trees above the trees given read past the array (SEGV, fuzzing finding 25). So it must
  // be the number of trees, num_parallel_tree must divide it, and each tree_info entry (the
  // tree's output group) must be one of the learner's num_class groups (1 when num_class is 0).
  const auto gp = model->find("gbtree_model_param");
  if (gp == model->end() || !gp->is_object() || count_at(*gp, "num_trees") != std::int64_t(n))
    fail("gbtree_model_param.num_trees is not the number of trees (" + std::to_string(n) + ")");
  if (gp->contains("num_parallel_tree")) {
    const std::int64_t parallel = count_at(*gp, "num_parallel_tree");
    if (parallel < 1 || (n > 0 && std::int64_t(n) % parallel != 0))
      fail("gbtree_model_param.num_parallel_tree is not a positive divisor of the number of trees");
  }
  const std::int64_t groups = std::max<std::int64_t>(has_mp ? count_at(*mp, "num_class") : 1, 1);
  for (const auto& g : *info)
    if (!g.is_number_integer() || g.get<std::int64_t>() < 0 || g.get<std::int64_t>() >= groups)
      fail("a \"tree_info\" entry is not one of the model's " + std::to_string(groups) + " output groups");
  std::vector<char> seen(n, 0);
  for (const auto& t : *trees) {
    const auto id = t.find("id");
    if (!t.is_object() || id == t.end() || !id->is_number_integer() || id->get<std::int64_t>() < 0 ||
        id->get<std::int64_t>() >= std::int64_t(n) || seen[std::size_t(id->get<std::int64_t>())]++)
      fail("tree ids must be 0.." + std::to_string(n) + "-1, each once");
    check_tree_nodes(t, num_feature, where);
  }
}

}  // namespace

Gbdt Gbdt::load(const std::filesystem::path& path, int nthread) {
  const std::string where = path.string();
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(where, "cannot open model file");
  if (std::filesystem::is_directory(path)) throw Error(where, "not a model file (a directory?)");
  check_thread_count(nthread, "threads");
  std::ostringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  // Only XGBoost's JSON format is a cropsight model (save() writes it). Anything else went to
  // XGBoost's binary loader, which trusts the lengths stored in the file: a corrupt one asked for
  // 4e18 bytes (fuzz_gbdt_model; fuzz/regressions/gbdt_model/), std::bad_alloc at best and an
  // out-of-memory kill for a length of a few GB. XGBoost takes a buffer as JSON when it starts
  // with '{', so the check is that plus well-formed JSON.
  if (text.empty() || text[0] != '{' || !nlohmann::json::accept(text))
    throw Error(where, "not an XGBoost JSON model (cropsight reads the JSON models that train grape writes)");
  // XGBoost's JSON models hold a "learner" object; another JSON file (a broccoli model, say)
  // would only get XGBoost's complaint about its version field.
  if (text.find("\"learner\"") == std::string::npos)
    throw Error(where, "not an XGBoost model (a JSON file without a \"learner\" object)");
  check_tree_model(nlohmann::json::parse(text), where);
  Gbdt g;
  check(XGBoosterCreate(nullptr, 0, &g.booster_), where);
  if (XGBoosterLoadModelFromBuffer(g.booster_, text.data(), bst_ulong(text.size())) != 0)
    throw Error(where, "not an XGBoost model: " + xgb_reason());
  check(XGBoosterSetParam(g.booster_, "nthread", std::to_string(nthread).c_str()), where);
  g.nthread_ = std::max(1, nthread);
  // The whole attribute must be a number ("6abc" is a corrupt file, not 6 classes).
  cropsight::detail::parse_value(where, "cropsight.num_class", g.attribute("cropsight.num_class"), g.num_class_);
  cropsight::detail::parse_value(where, "cropsight.num_features", g.attribute("cropsight.num_features"), g.cols_);
  cropsight::detail::check_range(where, "cropsight.num_class", g.num_class_, Range::at_least(2));
  cropsight::detail::check_range(where, "cropsight.num_features", g.cols_, Range::at_least(1));
  return g;
}

}  // namespace cropsight::learning
