// The potato harvest loop (target: >= 30 fps single-threaded at 640x480) on a simulated
// approach (sheet, seed 2301, 6 frames: a 2 cm scan, about the per-frame motion of a 40-frame
// approach, then the approach to 0.3 m), and the position step alone
// on the target's box at the end of the approach (the largest box, the worst case for the
// silhouette's moments), with the older half_width rule beside it. Baseline in the same process:
// cv::cvtColor to Lab of the 640x480 frame. OpenCV runs single-threaded (cv::setNumThreads(0)).
#include <benchmark/benchmark.h>

#include <filesystem>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "cropsight/io/sequence.hpp"
#include "cropsight/pipeline/potato/make_pipeline.hpp"
#include "cropsight/pipeline/potato/pipeline.hpp"
#include "cropsight/pipeline/potato/truth.hpp"
#include "cropsight/sim/potato/potato_sim.hpp"

using namespace cropsight;

namespace {

struct Approach {
  std::vector<RgbdFrame> frames;
  Detection2D target_box;  ///< the simulated target's visible box in the last frame
  Image<float> last_depth_m;
};

const Approach& approach() {
  static const Approach a = [] {
    Approach out;
    const auto dir = std::filesystem::temp_directory_path() / "cropsight_bench_potato_loop";
    sim::PotatoSimConfig cfg;
    cfg.scan_sweep_m = 0.02;
    sim::simulate_potato_sequence(cfg, 2301, 6, dir, true);
    const io::SequenceReader reader(dir);
    for (int i = 0; i < reader.size(); ++i) out.frames.push_back(reader.read(i));
    const RgbdFrame& last = out.frames.back();
    for (const auto& t :
         pipeline::potato::frame_truth(reader.groundtruth(), *last.camera_position, last.camera, last.labels))
      if (t.target) out.target_box = t.box;
    out.last_depth_m = measure::depth_in_metres(last.depth, last.camera.depth_scale);
    std::filesystem::remove_all(dir);
    return out;
  }();
  return a;
}

void BM_CvtColorLab640(benchmark::State& state) {
  cv::setNumThreads(0);
  const ColorImage& img = approach().frames.back().color;
  const cv::Mat rgb(img.height, img.width, CV_8UC3, const_cast<Rgb8*>(img.data.data()));
  cv::Mat lab;
  for (auto _ : state) {
    cv::cvtColor(rgb, lab, cv::COLOR_RGB2Lab);
    benchmark::DoNotOptimize(lab.data);
  }
}
BENCHMARK(BM_CvtColorLab640)->Unit(benchmark::kMillisecond);

// The whole loop per frame (detect, locate, ripeness, select / track, orient) with the preset.
void BM_PotatoLoop(benchmark::State& state, const char* preset) {
  cv::setNumThreads(0);
  const Approach& a = approach();
  const auto built = pipeline::potato::make_pipeline({.preset = preset});
  pipeline::potato::Pipeline& pipeline = *built;
  for (auto _ : state) {
    pipeline.reset();
    for (const RgbdFrame& f : a.frames) benchmark::DoNotOptimize(pipeline.process(f).target.z);
  }
  state.SetItemsProcessed(std::int64_t(state.iterations()) * std::int64_t(a.frames.size()));  // items/s = fps
}
BENCHMARK_CAPTURE(BM_PotatoLoop, potato, "potato")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_PotatoLoop, potato_paper, "potato-paper")->Unit(benchmark::kMillisecond);

void BM_Locate(benchmark::State& state, measure::CentreOffset offset) {
  const Approach& a = approach();
  measure::PositionConfig cfg;
  cfg.centre_offset = offset;
  for (auto _ : state)
    benchmark::DoNotOptimize(measure::locate(a.target_box, a.last_depth_m, a.frames.back().camera, cfg).xyz);
}
BENCHMARK_CAPTURE(BM_Locate, profile, measure::CentreOffset::profile)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Locate, silhouette, measure::CentreOffset::silhouette)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Locate, half_width, measure::CentreOffset::half_width)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
