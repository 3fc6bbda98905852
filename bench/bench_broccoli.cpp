// End-to-end broccoli head detection on simulated 512x424 frames (rendered in-process by the sim
// module): OES, ORG, FEC (no outlier removal) and the PCL reference pipeline, single-threaded,
// each scoring clusters with the same RBF SVM (trained once at start-up on other frames).
//
//   build/bin/bench_broccoli [--benchmark_filter=Oes]
//
// CROPSIGHT_BENCH_SEQ=DIR times the first (up to) 20 frames of a recorded/simulated sequence
// instead, and CROPSIGHT_BENCH_MODEL=FILE scores with that model (VFH features) instead of the
// one trained at start-up, e.g. the shipped models on the uk test seed:
//   CROPSIGHT_BENCH_SEQ=uk-test CROPSIGHT_BENCH_MODEL=models/broccoli-oes-uk.json
//   build/bin/bench_broccoli --benchmark_filter='Oes|Org'
// Counters: fps and clusters per frame, plus each stage's wall-clock ms per frame.
#include <benchmark/benchmark.h>
#include <oneapi/tbb/global_control.h>

#include <algorithm>
#include <cstdlib>
#include <memory>

#include "cropsight/io/sequence.hpp"
#include "cropsight/pipeline/broccoli/bench.hpp"
#include "cropsight/pipeline/broccoli/pcl_reference.hpp"
#include "cropsight/pipeline/broccoli/timing.hpp"
#include "cropsight/pipeline/broccoli/training.hpp"
#include "cropsight/sim/broccoli/broccoli_sim.hpp"

using namespace cropsight;

namespace {
struct Fixture {
  std::vector<RgbdFrame> frames;                 // timed frames (seed 7)
  std::shared_ptr<const learning::Model> model;  // trained on seed 5 with FEC clusters
  static const Fixture& get() {
    static const Fixture f;
    return f;
  }

 private:
  Fixture() {
    if (const char* seq = std::getenv("CROPSIGHT_BENCH_SEQ")) {
      io::SequenceReader reader(seq);
      for (int i = 0; i < std::min(reader.size(), 20); ++i) frames.push_back(reader.read(i));
    } else {
      sim::BroccoliSimulator test(sim::BroccoliSimConfig{}, 7, 4);
      for (int i = 0; i < test.frames(); ++i) frames.push_back(test.render(i));
    }
    if (const char* file = std::getenv("CROPSIGHT_BENCH_MODEL")) {
      model = std::make_shared<learning::Model>(learning::load_model(file));
      return;
    }
    sim::BroccoliSimulator train(sim::BroccoliSimConfig{}, 5, 6);
    auto cfg = config(pipeline::broccoli::Variant::fec);
    pipeline::broccoli::DatasetBuilder builder(cfg, {});
    for (int i = 0; i < train.frames(); ++i) builder.add_frame(train.render(i));
    model = std::make_shared<learning::Model>(pipeline::broccoli::train_model(builder.dataset(), cfg, {}, {}));
  }

 public:
  // The settings `cropsight bench broccoli` times a variant with (uk presets, no outlier removal:
  // the same work as the PCL reference).
  static pipeline::broccoli::DetectorConfig config(pipeline::broccoli::Variant variant) {
    return pipeline::broccoli::variant_config({}, variant).detector;
  }
};

void run_detector(benchmark::State& state, pipeline::broccoli::Variant variant) {
  tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
  const Fixture& f = Fixture::get();
  pipeline::broccoli::Detector det(Fixture::config(variant));
  det.set_model(pipeline::broccoli::model_for_variant(f.model, variant, "bench"));
  det.process(f.frames.front());  // warm-up: buffers sized
  det.timer().clear();
  std::size_t i = 0, clusters = 0;
  for (auto _ : state) {
    clusters += det.process(f.frames[i++ % f.frames.size()]).size();
  }
  state.counters["fps"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["clusters"] = double(clusters) / double(state.iterations());
  for (const auto& s : det.timer().stages()) state.counters[s.name] = s.total_ms / double(state.iterations());
}

void BM_Oes(benchmark::State& s) { run_detector(s, pipeline::broccoli::Variant::oes); }
void BM_Org(benchmark::State& s) { run_detector(s, pipeline::broccoli::Variant::org); }
void BM_Fec(benchmark::State& s) { run_detector(s, pipeline::broccoli::Variant::fec); }

void BM_PclReference(benchmark::State& state) {
  const Fixture& f = Fixture::get();
  pipeline::broccoli::PclReferencePipeline pcl(Fixture::config(pipeline::broccoli::Variant::fec), f.model);
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(pcl.process(f.frames[i++ % f.frames.size()]));
  state.counters["fps"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
}
}  // namespace

BENCHMARK(BM_Oes)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Org)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Fec)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PclReference)->Unit(benchmark::kMillisecond)->Iterations(4);
BENCHMARK_MAIN();
