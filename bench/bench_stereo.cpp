// Broccoli seedlings: disparity engines on a 640x480 simulated pair at 128
// disparities, all in one process, with two threads (TBB capped at 2 here; run OpenCV with
// OPENCV_FOR_THREADS_NUM=2 or on a 2-core machine):
//   - ours: census SGM (5 paths, one sweep, LR check from the same costs) + speckle filter + fill,
//   - ours, matcher only (census_sgm core, no speckle filter / filling),
//   - the previous engine: OpenCV SGBM 3-way on rank features, run twice for the explicit
//     left-right check, + fill,
//   - plain OpenCV StereoSGBM (the baseline of eval stereo),
// and our GMM vs cv::ml::EM on the same 4096 points (K = 10, same tolerance and iteration cap):
// first Arg 0 = eight well-separated synthetic blobs (EM converges in a few iterations), 1 = the
// 4096 points the default seedling pipeline hands to its GMM for the simulated pair (28 EM
// iterations, what `eval seedling` reports as ms_gmm); our second Arg 0 = the portable SSE2
// build of the EM, 1 = what fit_gmm() runs (the AVX2 + FMA build where the CPU has it),
// and the whole seedling pipeline (pipeline::seedling::Pipeline::process) with the shipped presets: Arg 0 =
// configs/seedling-paper.yaml (OpenCV engine), Arg 1 = configs/seedling.yaml (the default, census engine).
//   build/bin/bench_stereo --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <random>

#include "cropsight/pipeline/seedling/make_pipeline.hpp"
#include "cropsight/pipeline/seedling/pipeline.hpp"
#include "cropsight/segmentation/gmm.hpp"
#include "cropsight/sim/seedling/seedling_sim.hpp"
#include "cropsight/stereo/disparity.hpp"
#include "segmentation/gmm_kernels.hpp"

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

void BM_DisparityCensus128(benchmark::State& st) {
  stereo::DisparityConfig cfg;
  cfg.num_disparities = 128;
  for (auto _ : st) benchmark::DoNotOptimize(stereo::compute_disparity(pair().left, pair().right, cfg));
}
void BM_CensusSgmMatcherOnly128(benchmark::State& st) {
  // The matcher alone: grey input, no speckle filter, no filling; range(0) = 0 forces SSE2.
  const GrayImage l = stereo::grey_levels(pair().left), r = stereo::grey_levels(pair().right);
  stereo::DisparityConfig cfg;
  cfg.num_disparities = 128;
  cfg.speckle_window = 0;
  cfg.fill_holes = false;
  cfg.allow_avx2 = st.range(0) != 0;
  for (auto _ : st) benchmark::DoNotOptimize(stereo::compute_disparity(l, r, cfg));
}
void BM_DisparityOpenCvEngine128(benchmark::State& st) {
  stereo::DisparityConfig cfg;
  cfg.engine = "opencv";
  cfg.uniqueness_ratio = 10;
  cfg.num_disparities = 128;
  for (auto _ : st) benchmark::DoNotOptimize(stereo::compute_disparity(pair().left, pair().right, cfg));
}
void BM_DisparityOpenCvSgbm128(benchmark::State& st) {
  for (auto _ : st) benchmark::DoNotOptimize(stereo::opencv_sgbm_disparity(pair().left, pair().right, 128));
}
// OpenCV's fastest SGBM variant (3 paths, MODE_SGBM_3WAY), same parameters: the speed baseline.
void BM_DisparityOpenCvSgbm3Way128(benchmark::State& st) {
  for (auto _ : st)
    benchmark::DoNotOptimize(stereo::opencv_sgbm_disparity(pair().left, pair().right, 128, 3, "bench", true));
}
pipeline::seedling::Pipeline preset_pipeline(const std::string& preset) {
  return std::move(*pipeline::seedling::make_pipeline({.preset = preset}));
}

stereo::RectifiedGeometry sim_geometry() { return sim::rectified_geometry(sim::SeedlingSimConfig{}.rig()); }

// The down-sampled candidates the default preset's GMM sees for the simulated pair.
const std::vector<Eigen::Vector3f>& seedling_points() {
  static const std::vector<Eigen::Vector3f> pts =
      preset_pipeline("seedling").process(pair().left, pair().right, sim_geometry()).sampled;
  return pts;
}

const std::vector<Eigen::Vector3f>& gmm_input(std::int64_t which) { return which == 0 ? points() : seedling_points(); }

void BM_GmmOurs(benchmark::State& st) {
  segmentation::GmmConfig cfg;
  const auto& pts = gmm_input(st.range(0));
  const bool portable = st.range(1) == 0;
  if (!portable && !segmentation::em_avx2::available()) st.SetLabel("no AVX2 here: dispatch = portable");
  segmentation::GmmResult r;
  for (auto _ : st) {
    r = portable ? segmentation::em_portable::fit(pts, cfg) : segmentation::fit_gmm(pts, cfg);
    benchmark::DoNotOptimize(r);
  }
  st.counters["iterations"] = r.iterations;
  st.counters["points"] = double(pts.size());
}
void BM_GmmOpenCvEm(benchmark::State& st) {
  segmentation::GmmConfig cfg;
  const auto& pts = gmm_input(st.range(0));
  for (auto _ : st) benchmark::DoNotOptimize(segmentation::fit_gmm_opencv(pts, cfg));
}

void BM_SeedlingPipeline(benchmark::State& st) {
  const std::string preset = st.range(0) == 0 ? "seedling-paper" : "seedling";
  const pipeline::seedling::Pipeline seedlings = preset_pipeline(preset);
  const stereo::RectifiedGeometry g = sim_geometry();
  st.SetLabel(preset);
  for (auto _ : st) benchmark::DoNotOptimize(seedlings.process(pair().left, pair().right, g));
}

}  // namespace

BENCHMARK(BM_DisparityCensus128)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->UseRealTime();
BENCHMARK(BM_CensusSgmMatcherOnly128)
    ->Arg(1)
    ->Arg(0)
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime();
BENCHMARK(BM_DisparityOpenCvEngine128)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->UseRealTime();
BENCHMARK(BM_DisparityOpenCvSgbm128)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->UseRealTime();
BENCHMARK(BM_DisparityOpenCvSgbm3Way128)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->UseRealTime();
BENCHMARK(BM_SeedlingPipeline)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->UseRealTime();
BENCHMARK(BM_GmmOurs)->ArgsProduct({{0, 1}, {0, 1}})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_GmmOpenCvEm)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

int main(int argc, char** argv) {
  // The targets are for two cores: cap both thread pools at 2.
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 2);
  pair(), points(), seedling_points();  // simulate the inputs before timing anything
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
