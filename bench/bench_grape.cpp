// Grape pipeline timings per cloud: per-point features + GBDT prediction, network
// forward passes, and our KNN-PCA normals against PCL's NormalEstimation on the same cloud.
//
//   build/bin/bench_grape [--benchmark_filter=...]
//
// Uses one shared cloud unpacked by scripts/unpack-grape.sh ($CROPSIGHT_GRAPE_DIR, else
// build-grape/data, else ~/.cache/cropsight/grape) and the shipped models in models/; benchmarks
// whose input is missing report an error instead of a time.
#include <benchmark/benchmark.h>
#include <pcl/features/normal_3d.h>
#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>

#include <cstdlib>
#include <filesystem>
#include <memory>
#include <optional>

#include "cropsight/core/install_paths.hpp"
#include "cropsight/geometry/farthest_point.hpp"
#include "cropsight/geometry/knn_normals.hpp"
#include "cropsight/io/grape_text.hpp"
#include "cropsight/learning/gbdt.hpp"
#include "cropsight/nn/point_segmenter.hpp"
#include "cropsight/pipeline/grape/features.hpp"
#include "cropsight/pipeline/grape/gbdt.hpp"
#include "cropsight/pipeline/grape/model.hpp"

namespace {
namespace fs = std::filesystem;
using namespace cropsight;

const std::optional<Cloud>& grape_cloud() {
  static const std::optional<Cloud> cloud = []() -> std::optional<Cloud> {
    std::vector<fs::path> dirs;
    if (const char* e = std::getenv("CROPSIGHT_GRAPE_DIR")) dirs.emplace_back(e);
    dirs.push_back(fs::path(CROPSIGHT_SOURCE_DIR) / "build-grape" / "data");
    if (const char* h = std::getenv("HOME")) dirs.push_back(fs::path(h) / ".cache" / "cropsight" / "grape");
    for (const auto& d : dirs)
      if (fs::exists(d / "points")) return io::read_grape_text(io::list_grape_clouds(d).front());
    return std::nullopt;
  }();
  return cloud;
}

void BM_GrapeFeatures(benchmark::State& state) {
  if (!grape_cloud()) return state.SkipWithError("grape data not unpacked (scripts/unpack-grape.sh)");
  pipeline::grape::FeatureConfig cfg;
  cfg.fpfh = state.range(0) != 0;
  for (auto _ : state) benchmark::DoNotOptimize(pipeline::grape::grape_point_features(*grape_cloud(), cfg));
  state.counters["points"] = double(grape_cloud()->size());
}
BENCHMARK(BM_GrapeFeatures)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

void BM_GrapeGbdtSegment(benchmark::State& state) {
  const fs::path m = cropsight::data_dir() / "models" / "grape-gbdt.json";
  if (!grape_cloud() || !fs::exists(m)) return state.SkipWithError("needs grape data and models/grape-gbdt.json");
  const auto model = pipeline::grape::Model::load(m, 2);
  for (auto _ : state) benchmark::DoNotOptimize(model.segment(*grape_cloud()));
}
BENCHMARK(BM_GrapeGbdtSegment)->Unit(benchmark::kMillisecond);

// Fast recipe (configs/grape-gbdt-fast.yaml): raw cloud to a label on every point, i.e. the
// pass sample, its features, XGBoost on the sample and the nearest-sample carry-back. Compare
// with BM_GrapeNetworkSegment/1 (paper mode) of the same run. $CROPSIGHT_GRAPE_FAST_MODEL
// overrides the model (e.g. a fold model).
void BM_GrapeGbdtFastSegment(benchmark::State& state) {
  const char* env = std::getenv("CROPSIGHT_GRAPE_FAST_MODEL");
  const fs::path m = env ? fs::path(env) : cropsight::data_dir() / "models" / "grape-gbdt-fast.json";
  if (!grape_cloud() || !fs::exists(m)) return state.SkipWithError("needs grape data and models/grape-gbdt-fast.json");
  const auto model = pipeline::grape::Model::load(m, 2);
  for (auto _ : state) benchmark::DoNotOptimize(model.segment(*grape_cloud()));
}
BENCHMARK(BM_GrapeGbdtFastSegment)->Unit(benchmark::kMillisecond);

// The fast segment's stages: 0 sample + features, 1 trees on the sample (second argument: 0
// XGBoost's predictor, 1 the compiled forest that pipeline::grape::Model uses), 2 carry-back (2 threads).
void BM_GrapeGbdtFastStages(benchmark::State& state) {
  const char* env = std::getenv("CROPSIGHT_GRAPE_FAST_MODEL");
  const fs::path m = env ? fs::path(env) : cropsight::data_dir() / "models" / "grape-gbdt-fast.json";
  if (!grape_cloud() || !fs::exists(m)) return state.SkipWithError("needs grape data and models/grape-gbdt-fast.json");
  const Cloud& c = *grape_cloud();
  auto model = learning::Gbdt::load(m, 2);
  if (state.range(1)) model.compile();
  const auto fc = pipeline::grape::FeatureConfig::from_recipe(model.attribute("cropsight.features"), "bench");
  const auto s = pipeline::grape::grape_sample(c.size(), fc, fc.sample_seed);
  const auto X = pipeline::grape::grape_sample_features(c, fc, s);
  const auto labels = model.predict(X, s.size(), pipeline::grape::grape_feature_count(fc));
  for (auto _ : state) {
    if (state.range(0) == 0)
      benchmark::DoNotOptimize(
          pipeline::grape::grape_sample_features(c, fc, pipeline::grape::grape_sample(c.size(), fc, 1)));
    else if (state.range(0) == 1)
      benchmark::DoNotOptimize(model.predict(X, s.size(), pipeline::grape::grape_feature_count(fc)));
    else
      benchmark::DoNotOptimize(pipeline::grape::grape_carry_back(c, s, labels, fc, model.num_class(), 2));
  }
  state.counters["sample"] = double(s.size());
}
BENCHMARK(BM_GrapeGbdtFastStages)
    ->Args({0, 1})
    ->Args({1, 0})
    ->Args({1, 1})
    ->Args({2, 1})
    ->Unit(benchmark::kMillisecond);

void BM_GrapeNetworkSegment(benchmark::State& state) {
  const fs::path m = cropsight::data_dir() / "models" / "grape-pointresnet.pt";
  if (!grape_cloud() || !fs::exists(m)) return state.SkipWithError("needs grape data and models/grape-pointresnet.pt");
  auto model = pipeline::grape::Model::load(m, 2);
  if (state.range(0) > 0) model.set_sampled(true, false, int(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(model.segment(*grape_cloud()));
}
// 0: every point gets its own pass (eval grape's default); k > 0: the paper's mode, one pass on
// a random sample, carried back by the k-nearest colour-guided vote (1 = nearest neighbour).
BENCHMARK(BM_GrapeNetworkSegment)->Arg(0)->Arg(1)->Arg(4)->Unit(benchmark::kMillisecond);

// Test-time votes and the ensemble (docs/pipelines/grape-bunches.md): the one-pass mode with
// `votes` rotated samples (colour-guided 4-NN carry-back), alone (second argument 0) or mixed
// with models/grape-gbdt-fast4096.json at weight 0.5 (1), the best model within 0.3 s.
void BM_GrapeNetworkVotes(benchmark::State& state) {
  const fs::path root = cropsight::data_dir() / "models";
  const fs::path net = root / "grape-pointresnet.pt", gbdt = root / "grape-gbdt-fast4096.json";
  if (!grape_cloud() || !fs::exists(net) || !fs::exists(gbdt))
    return state.SkipWithError("needs grape data, models/grape-pointresnet.pt and grape-gbdt-fast4096.json");
  auto model = pipeline::grape::Model::load(net, 2);
  model.set_sampled(true, false, 4);
  model.set_votes(int(state.range(0)));
  if (state.range(1))
    model.set_ensemble(std::make_shared<const pipeline::grape::Model>(pipeline::grape::Model::load(gbdt, 2)), 0.5);
  for (auto _ : state) benchmark::DoNotOptimize(model.segment(*grape_cloud()));
  state.SetLabel(state.range(1) ? "network votes + fast4096 GBDT" : "network votes");
}
BENCHMARK(BM_GrapeNetworkVotes)->Args({1, 0})->Args({4, 1})->Args({6, 0})->Args({6, 1})->Unit(benchmark::kMillisecond);

void BM_KnnNormalsOurs(benchmark::State& state) {
  if (!grape_cloud()) return state.SkipWithError("grape data not unpacked");
  for (auto _ : state) benchmark::DoNotOptimize(geometry::knn_normals(grape_cloud()->points));
}
BENCHMARK(BM_KnnNormalsOurs)->Unit(benchmark::kMillisecond);

void BM_KnnNormalsPcl(benchmark::State& state) {
  if (!grape_cloud()) return state.SkipWithError("grape data not unpacked");
  pcl::PointCloud<pcl::PointXYZ>::Ptr pc(new pcl::PointCloud<pcl::PointXYZ>);
  for (const auto& p : grape_cloud()->points) pc->push_back({p.x(), p.y(), p.z()});
  for (auto _ : state) {
    pcl::NormalEstimation<pcl::PointXYZ, pcl::Normal> ne;
    ne.setInputCloud(pc);
    ne.setSearchMethod(pcl::search::KdTree<pcl::PointXYZ>::Ptr(new pcl::search::KdTree<pcl::PointXYZ>));
    ne.setKSearch(30);
    pcl::PointCloud<pcl::Normal> out;
    ne.compute(out);
    benchmark::DoNotOptimize(out);
  }
}
BENCHMARK(BM_KnnNormalsPcl)->Unit(benchmark::kMillisecond);
}  // namespace

BENCHMARK_MAIN();
