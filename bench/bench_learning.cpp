// SVM scoring (the broccoli pipelines' "classify" stage): our dense RBF scorer against libsvm's
// svm_predict_values on the same model and vectors in one process. 308 dimensions (VFH),
// the learning tests' Gaussian data (tests/learning/test_learning_common.hpp); 64 vectors per
// iteration. Argument 1: the training data's columns 154..307 are 0, as the VFH bins no training
// cluster fills (about half of them in the shipped broccoli models); the scorer then skips them
// in its dot products (argument 0: every column is used). BM_SvmScoreRows: the same vectors through
// Classifier::score_rows in one call.
//   build/bin/bench_learning --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <memory>

#include "../tests/learning/test_learning_common.hpp"
#include "cropsight/learning/classifier.hpp"
#include "cropsight/learning/dataset.hpp"
#include "cropsight/learning/standardizer.hpp"
#include "learning/svm_classifier.hpp"

using namespace cropsight;
using namespace cropsight::learning;

namespace {

struct Fixture {
  // The learning tests' two overlapping Gaussian classes, standardised as the pipelines do.
  Dataset raw = testdata::gaussians(1500, 308, 0.5, 1);
  Standardizer s;
  Dataset train, test;
  std::unique_ptr<Classifier> clf;
  explicit Fixture(bool empty_columns) {
    if (empty_columns)
      for (std::size_t i = 0; i < raw.size(); ++i)
        for (std::size_t j = 154; j < 308; ++j) raw.values[i * 308 + j] = 0.0f;
    s = Standardizer::fit(raw);
    train = s.apply(raw);
    test = s.apply(testdata::gaussians(64, 308, 0.5, 2));
    ClassifierParams p;
    p.type = "svm-rbf";
    p.rbf_gamma = 1.0 / 308;
    clf = train_classifier(train, p);
  }
};
const Fixture& fx(bool empty_columns) {
  static const Fixture full(false), half(true);
  return empty_columns ? half : full;
}

void BM_SvmScoreOurs(benchmark::State& st) {
  const auto& f = fx(st.range(0) != 0);
  for (auto _ : st)
    for (std::size_t i = 0; i < f.test.size(); ++i) benchmark::DoNotOptimize(f.clf->score(f.test.row(i)));
  st.counters["support_vectors"] = double(f.clf->model_size());
}
// The same 64 vectors through score_rows (support vectors in L1-sized blocks, read once for all
// of them): the detector's classify stage scores a frame's clusters this way.
void BM_SvmScoreRows(benchmark::State& st) {
  const auto& f = fx(st.range(0) != 0);
  std::vector<float> out(f.test.size());
  for (auto _ : st) {
    f.clf->score_rows(f.test.values.data(), f.test.size(), out.data());
    benchmark::DoNotOptimize(out.data());
  }
  st.counters["support_vectors"] = double(f.clf->model_size());
}
void BM_SvmScoreLibsvm(benchmark::State& st) {
  const auto& f = fx(st.range(0) != 0);
  const auto& svm = dynamic_cast<const detail::SvmClassifier&>(*f.clf);
  for (auto _ : st)
    for (std::size_t i = 0; i < f.test.size(); ++i) benchmark::DoNotOptimize(svm.libsvm_score(f.test.row(i)));
}

}  // namespace

BENCHMARK(BM_SvmScoreOurs)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_SvmScoreRows)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_SvmScoreLibsvm)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

BENCHMARK_MAIN();
