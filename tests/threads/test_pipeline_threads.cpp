// The thread-safety claims of docs/library.md (deliverable 6): one pipeline object per
// thread, read-only models shared between threads. Broccoli (one shared SVM model), potato and
// seedling pipelines run at once, two threads of each, on the same simulated inputs; every
// thread's results must equal a single-threaded run's. In the ordinary build this checks the
// results; under ThreadSanitizer (make tsan, build-tsan/) it also checks that no two threads
// touch the same memory without synchronisation (tests/threads/tsan.supp says what is suppressed
// in third-party libraries and why).
#include <gtest/gtest.h>

#include <opencv2/core/utility.hpp>

#include <cstdint>
#include <cstring>
#include <functional>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "cropsight/io/sequence.hpp"
#include "cropsight/pipeline/broccoli/pipeline.hpp"
#include "cropsight/pipeline/potato/pipeline.hpp"
#include "cropsight/pipeline/seedling/config.hpp"
#include "cropsight/pipeline/seedling/pipeline.hpp"
#include "cropsight/sim/broccoli/broccoli_sim.hpp"
#include "cropsight/sim/potato/potato_sim.hpp"
#include "cropsight/sim/seedling/seedling_sim.hpp"
#include "testing/testing.hpp"

namespace cropsight {
namespace {

constexpr int kThreadsPerPipeline = 2;

// FNV-1a over the bytes of the values compared: equal results give equal hashes.
struct Hash {
  std::uint64_t h = 1469598103934665603ull;
  template <class T>
  Hash& add(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    unsigned char bytes[sizeof(T)];
    std::memcpy(bytes, &v, sizeof(T));
    for (unsigned char b : bytes) h = (h ^ b) * 1099511628211ull;
    return *this;
  }
  Hash& add(const Eigen::Vector3f& v) { return add(v.x()).add(v.y()).add(v.z()); }
};

std::vector<RgbdFrame> broccoli_frames() {
  sim::BroccoliSimConfig cfg;  // the uk preset's defaults
  sim::BroccoliSimulator s(cfg, 7301, 3);
  std::vector<RgbdFrame> out;
  for (int i = 0; i < 3; ++i) out.push_back(s.render(i));
  return out;
}

// What a run produced: a hash of its results, and how many things it found (so that equal
// hashes of empty results cannot pass for agreement).
struct Outcome {
  std::uint64_t hash = 0;
  int found = 0;
  friend bool operator==(const Outcome&, const Outcome&) = default;
};

// Detections, sizes and track ids of a tracked pass.
Outcome run_broccoli(const pipeline::broccoli::Config& cfg, const std::shared_ptr<const learning::Model>& model,
                     const std::vector<RgbdFrame>& frames) {
  pipeline::broccoli::Pipeline p(cfg, model, "test");
  Hash h;
  int found = 0;
  for (const RgbdFrame& f : frames) {
    const auto& r = p.process(f);
    found += int(r.detections.size());
    h.add(r.detections.size());
    for (const Detection& d : r.detections) h.add(d.score).add(d.centroid).add(d.size_m).add(d.track_id);
  }
  h.add(p.finish().size());
  return {h.h, found};
}

std::vector<RgbdFrame> potato_frames(const std::filesystem::path& dir) {
  sim::PotatoSimConfig cfg;
  sim::simulate_potato_sequence(cfg, 7302, 4, dir, false);
  const io::SequenceReader reader(dir);
  std::vector<RgbdFrame> out;
  for (int i = 0; i < reader.size(); ++i) out.push_back(reader.read(i));
  return out;
}

// Detections and the harvest message of every frame (CSRT tracking included).
Outcome run_potato(const pipeline::potato::Config& cfg, const std::vector<RgbdFrame>& frames) {
  pipeline::potato::Pipeline p(cfg);
  Hash h;
  int found = 0;
  for (const RgbdFrame& f : frames) {
    const auto r = p.process(f);
    found += r.target.detection ? 1 : 0;
    h.add(r.detections.size());
    for (const auto& d : r.detections) h.add(d.x1).add(d.y1).add(d.x2).add(d.y2).add(d.score);
    const auto& t = r.target;
    h.add(t.detection).add(t.depth_ok).add(t.x).add(t.y).add(t.z).add(t.angle).add(t.target_id);
  }
  return {h.h, found};
}

// Found flag, envelope and point count of each pair (census SGM, GMM).
Outcome run_seedling(const pipeline::seedling::Config& cfg, const std::vector<sim::SeedlingPair>& pairs,
                     const stereo::RectifiedGeometry& g) {
  const pipeline::seedling::Pipeline p(cfg);
  Hash h;
  int found = 0;
  for (const auto& pair : pairs) {
    const auto d = p.process(pair.left, pair.right, g);
    found += d.found ? 1 : 0;
    h.add(d.found).add(d.points.size()).add(d.envelope.length).add(d.envelope.width).add(d.envelope.height);
  }
  return {h.h, found};
}

TEST(PipelineThreads, ParallelPipelinesEqualASingleThreadedRun) {
#if defined(__SANITIZE_THREAD__)
  // OpenCV's own thread pool is TBB, which is not instrumented: TSan sees the memory its workers
  // touch but not their synchronisation, so every cv::Mat a worker filled would be reported. Under
  // TSan OpenCV runs its loops on the calling thread (0: no threading optimisations); the
  // pipelines still run in threads of their own, which is what this test checks. Suppressing
  // libopencv_* instead would also hide a race of ours on a cv::Mat two of our threads share.
  cv::setNumThreads(0);
#endif
  testing::TempDir tmp;
  // Inputs and configurations, built before any thread starts.
  const auto model =
      pipeline::broccoli::load_model(testing::source_dir() / "models" / "broccoli-oes-uk.json");  // shared, read-only
  const auto broccoli_cfg = [&] {
    auto c = pipeline::broccoli::config_for_model(*model, {}, "broccoli-oes-uk.json");
    c.track = true;
    return c;
  }();
  const auto broccoli_in = broccoli_frames();
  const auto potato_cfg = pipeline::potato::load_config("potato");
  const auto potato_in = potato_frames(tmp / "potato");
  const auto seedling_cfg = pipeline::seedling::load_config("seedling");
  sim::SeedlingSimConfig sim_cfg;
  sim_cfg.supersample = 1;
  const stereo::RectifiedGeometry geometry = sim::rectified_geometry(sim_cfg.rig());
  const std::vector<sim::SeedlingPair> seedling_in = {sim::simulate_seedling_pair(sim_cfg, 7303, 0),
                                                      sim::simulate_seedling_pair(sim_cfg, 7303, 1)};

  // The reference: each pipeline alone on this thread.
  const Outcome want_broccoli = run_broccoli(broccoli_cfg, model, broccoli_in);
  const Outcome want_potato = run_potato(potato_cfg, potato_in);
  const Outcome want_seedling = run_seedling(seedling_cfg, seedling_in, geometry);
  EXPECT_GE(want_broccoli.found, 3) << "broccoli detections over 3 frames";
  EXPECT_GE(want_potato.found, 3) << "potato frames with a target, of 4";
  EXPECT_EQ(want_seedling.found, 2) << "seedlings found, of 2 pairs";

  // All of them at once: two threads per pipeline, each with its own pipeline object.
  std::vector<Outcome> got(3 * kThreadsPerPipeline);
  std::vector<std::string> errors(got.size());
  std::vector<std::thread> threads;
  for (int k = 0; k < kThreadsPerPipeline; ++k) {
    const std::function<Outcome()> jobs[] = {
        [&] { return run_broccoli(broccoli_cfg, model, broccoli_in); },
        [&] { return run_potato(potato_cfg, potato_in); },
        [&] { return run_seedling(seedling_cfg, seedling_in, geometry); },
    };
    for (int j = 0; j < 3; ++j) {
      const std::size_t slot = std::size_t(3 * k + j);
      threads.emplace_back([&, slot, job = jobs[j]] {
        try {
          got[slot] = job();
        } catch (const std::exception& e) {
          errors[slot] = e.what();
        }
      });
    }
  }
  for (auto& t : threads) t.join();

  const char* names[] = {"broccoli", "potato", "seedling"};
  const Outcome want[] = {want_broccoli, want_potato, want_seedling};
  for (std::size_t slot = 0; slot < got.size(); ++slot) {
    EXPECT_EQ(errors[slot], "") << names[slot % 3] << " thread " << slot;
    EXPECT_TRUE(got[slot] == want[slot % 3]) << names[slot % 3] << " thread " << slot << " differs from the single run";
  }
}

}  // namespace
}  // namespace cropsight
