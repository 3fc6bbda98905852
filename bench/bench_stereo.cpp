// Broccoli seedlings (issue 5): our disparity vs plain OpenCV StereoSGBM on a 640x480 simulated
// pair at 128 disparities, and our GMM vs cv::ml::EM on the same 4096 points (K = 10, same
// tolerance and iteration cap), all in one process. Run with two threads of OpenCV:
//   OPENCV_FOR_THREADS_NUM=2 build/bin/bench_stereo   (or taskset -c 0,1)
#include <benchmark/benchmark.h>

#include <random>

#include "cropsight/segmentation/gmm.hpp"
#include "cropsight/sim/seedling.hpp"
#include "cropsight/stereo/disparity.hpp"

using namespace cropsight;

namespace {

const sim::SeedlingPair& pair() {
  static const sim::SeedlingPair p = [] {
    sim::SeedlingSimConfig cfg;
    cfg.supersample = 1;
    return sim::simulate_seedling_pair(cfg, 2024, 0);
  }();
  return p;
}

// 4096 points of a seedling-like scene: a plane of soil, a blob plant and low weeds.
const std::vector<Eigen::Vector3f>& points() {
  static const std::vector<Eigen::Vector3f> pts = [] {
    std::mt19937 rng(3);
    std::normal_distribution<float> g(0, 1);
    std::vector<Eigen::Vector3f> p;
    for (int i = 0; i < 4096; ++i) {
      const int c = i % 8;
      p.emplace_back(0.05f * c + 0.01f * g(rng), 0.03f * (c % 3) + 0.012f * g(rng),
                     0.6f - 0.02f * (c == 0) + 0.005f * g(rng));
    }
    return p;
  }();
  return pts;
}

void BM_DisparityOurs128(benchmark::State& st) {
  stereo::DisparityConfig cfg;
  cfg.num_disparities = 128;
  for (auto _ : st) benchmark::DoNotOptimize(stereo::compute_disparity(pair().left, pair().right, cfg));
}
void BM_DisparityOursNoLr128(benchmark::State& st) {
  stereo::DisparityConfig cfg;
  cfg.num_disparities = 128;
  cfg.lr_check = -1;
  for (auto _ : st) benchmark::DoNotOptimize(stereo::compute_disparity(pair().left, pair().right, cfg));
}
void BM_DisparityOpenCvSgbm128(benchmark::State& st) {
  for (auto _ : st) benchmark::DoNotOptimize(stereo::opencv_sgbm_disparity(pair().left, pair().right, 128));
}
void BM_GmmOurs(benchmark::State& st) {
  segmentation::GmmConfig cfg;
  for (auto _ : st) benchmark::DoNotOptimize(segmentation::fit_gmm(points(), cfg));
}
void BM_GmmOpenCvEm(benchmark::State& st) {
  segmentation::GmmConfig cfg;
  for (auto _ : st) benchmark::DoNotOptimize(segmentation::fit_gmm_opencv(points(), cfg));
}

}  // namespace

BENCHMARK(BM_DisparityOurs128)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_DisparityOursNoLr128)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_DisparityOpenCvSgbm128)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_GmmOurs)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_GmmOpenCvEm)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);
BENCHMARK_MAIN();
