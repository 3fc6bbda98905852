// SVM scoring (the broccoli pipelines' "classify" stage): our dense RBF scorer against libsvm's
// svm_predict_values on the same model and vectors in one process. 308 dimensions (VFH),
// Gaussian data as in the unit tests; 64 vectors per iteration.
//   build/bin/bench_learning --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <memory>
#include <random>

#include "cropsight/learning/classifier.hpp"
#include "cropsight/learning/dataset.hpp"
#include "learning/svm_classifier.hpp"

using namespace cropsight;
using namespace cropsight::learning;

namespace {

Dataset gaussians(std::size_t n, int dim, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> g(0.0f, 1.0f);
  Dataset d(dim);
  std::vector<float> row(static_cast<std::size_t>(dim));
  for (std::size_t i = 0; i < n; ++i) {
    const int label = i % 3 == 0;
    for (int j = 0; j < dim; ++j) row[std::size_t(j)] = g(rng) + (label && j % 2 == 0 ? 0.5f : 0.0f);
    d.add(row, label);
  }
  return d;
}

struct Fixture {
  Dataset train = gaussians(1500, 308, 1), test = gaussians(64, 308, 2);
  std::unique_ptr<Classifier> clf;
  Fixture() {
    ClassifierParams p;
    p.type = "svm-rbf";
    p.rbf_gamma = 1.0 / 308;
    clf = train_classifier(train, p);
  }
};
const Fixture& fx() {
  static const Fixture f;
  return f;
}

void BM_SvmScoreOurs(benchmark::State& st) {
  const auto& f = fx();
  for (auto _ : st)
    for (std::size_t i = 0; i < f.test.size(); ++i) benchmark::DoNotOptimize(f.clf->score(f.test.row(i)));
  st.counters["support_vectors"] = double(f.clf->model_size());
}
void BM_SvmScoreLibsvm(benchmark::State& st) {
  const auto& f = fx();
  const auto& svm = dynamic_cast<const detail::SvmClassifier&>(*f.clf);
  for (auto _ : st)
    for (std::size_t i = 0; i < f.test.size(); ++i) benchmark::DoNotOptimize(svm.libsvm_score(f.test.row(i)));
}

}  // namespace

BENCHMARK(BM_SvmScoreOurs)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_SvmScoreLibsvm)->Unit(benchmark::kMicrosecond);

BENCHMARK_MAIN();
