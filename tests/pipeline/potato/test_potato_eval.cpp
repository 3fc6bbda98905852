// The harvest-run evaluator on scripted runs (switches, lost events, angle modulo 180) and end to
// end on simulated approaches with a ground-truth-box detector (boxes from the simulator's labels,
// optionally dropped): measure/position + ripeness + tracking/target_tracker + evaluate_potato_run.
// Not the pipeline (the lead composes it); this drives the parts the same way.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <iostream>

#include "cropsight/io/sequence.hpp"
#include "cropsight/measure/position.hpp"
#include "cropsight/pipeline/potato/potato_eval.hpp"
#include "cropsight/sim/random.hpp"
#include "testing/testing.hpp"

using namespace cropsight;
using namespace cropsight::pipeline;

namespace {

sim::PotatoFrameTruth potato(int id, float cu, Eigen::Vector3d c) {
  sim::PotatoFrameTruth t;
  t.id = id;
  t.box = {cu - 20, 100, cu + 20, 140, 0, 1};
  t.visible_pixels = 1600;
  t.centre_camera = c;
  t.length_m = 0.08;
  t.width_m = 0.05;
  t.angle_rad = 0.1;
  return t;
}

struct RunResult {
  PotatoEvaluation ev;
  double ms_per_frame = 0;
};

// A harvest loop over a simulated sequence with ground-truth boxes; `drop` = probability that the
// target's box is missing in a frame (the visual tracker must carry it).
RunResult harvest(const std::filesystem::path& seq, tracking::VisualTrackerKind kind, double drop, std::uint64_t seed) {
  io::SequenceReader reader(seq);
  tracking::TargetTrackerConfig tcfg;
  tcfg.visual_tracker = kind;
  tracking::TargetTracker tracker(tcfg);
  sim::Rng rng(seed);
  std::vector<PotatoFrameResult> run;
  std::vector<std::vector<sim::PotatoFrameTruth>> truth;
  double ms = 0;
  for (int i = 0; i < reader.size(); ++i) {
    const RgbdFrame f = reader.read(i);
    auto t = sim::potato_frame_truth(reader.groundtruth(), *f.camera_position, f.camera, f.labels);
    const auto t0 = std::chrono::steady_clock::now();
    const Image<float> depth = measure::depth_in_metres(f.depth, f.camera.depth_scale);
    std::vector<tracking::TargetCandidate> cands;
    std::vector<measure::Position3D> pos;
    for (const auto& p : t) {
      if (p.visible_pixels < 50) continue;
      if (p.target && rng.bernoulli(drop)) continue;
      const auto loc = measure::locate(p.box, depth, f.camera);
      cands.push_back({p.box, loc.surface_depth_m, measure::is_ripe(loc, {}), loc.depth_ok});
      pos.push_back(loc);
    }
    const auto u = tracker.update(&f.color, cands);
    PotatoFrameResult r;
    r.state = u.state;
    r.target_id = u.target_id;
    r.box = u.box;
    if (u.box) {
      const auto loc = u.candidate >= 0 ? pos[std::size_t(u.candidate)] : measure::locate(*u.box, depth, f.camera);
      r.depth_ok = loc.depth_ok;
      r.xyz = loc.xyz;
      r.width_m = loc.width_m;
      r.height_m = loc.height_m;
    }
    ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    run.push_back(r);
    truth.push_back(std::move(t));
  }
  return {evaluate_potato_run(run, truth), ms / reader.size()};
}

}  // namespace

TEST(PotatoEval, AngleErrorIsModulo180) {
  EXPECT_NEAR(axis_angle_error(0.05, M_PI - 0.05), 0.1, 1e-12);
  EXPECT_NEAR(axis_angle_error(0.0, M_PI / 2), M_PI / 2, 1e-12);
  EXPECT_NEAR(axis_angle_error(1.0, 1.0 + M_PI), 0.0, 1e-12);
}

TEST(PotatoEval, ScriptedRunCountsSwitchesLossAndErrors) {
  const Eigen::Vector3d a(0, 0, 0.4), b(0.1, 0, 0.45);
  std::vector<std::vector<sim::PotatoFrameTruth>> truth(4, {potato(1, 100, a), potato(2, 300, b)});
  std::vector<PotatoFrameResult> run(4);
  for (int f = 0; f < 3; ++f) {
    run[std::size_t(f)].state = tracking::TargetState::detected;
    run[std::size_t(f)].target_id = 1;
    run[std::size_t(f)].box = truth[0][f == 2 ? 1 : 0].box;  // frame 2: the target jumps to potato 2
    run[std::size_t(f)].depth_ok = true;
    run[std::size_t(f)].xyz = (f == 2 ? b : a).cast<float>() + Eigen::Vector3f(0.002f, -0.001f, 0.003f);
    run[std::size_t(f)].width_m = 0.081f;
    run[std::size_t(f)].height_m = 0.05f;
    run[std::size_t(f)].angle_rad = M_PI - 0.1;
  }
  run[3].state = tracking::TargetState::lost;
  const PotatoEvaluation ev = evaluate_potato_run(run, truth);
  EXPECT_EQ(ev.frames, 4);
  EXPECT_EQ(ev.frames_with_target, 3);
  EXPECT_EQ(ev.target_switches, 1);
  EXPECT_EQ(ev.lost_events, 1);
  EXPECT_NEAR(ev.x.mean_mm, 2, 1e-3);
  EXPECT_NEAR(ev.y.mae_mm, 1, 1e-3);
  EXPECT_NEAR(ev.z.std_mm, 0, 1e-3);
  EXPECT_NEAR(ev.length_mae_mm, 1, 1e-3);
  EXPECT_NEAR(ev.angle_mae_deg, 0.2 * 180 / M_PI, 1e-6);
}

TEST(PotatoEval, SimulatedApproachWithGroundTruthBoxes) {
  cropsight::testing::TempDir dir;
  sim::PotatoSimConfig cfg;
  cfg.width = 320;
  cfg.height = 240;
  sim::simulate_potato_sequence(cfg, 11, 10, dir / "seq", false);
  const RunResult r = harvest(dir / "seq", tracking::VisualTrackerKind::none, 0.0, 1);
  EXPECT_EQ(r.ev.target_switches, 0);
  EXPECT_EQ(r.ev.frames_with_target, 10);
  EXPECT_GT(r.ev.frames_positioned, 8);
  EXPECT_LT(r.ev.x.mae_mm, 5);
  // Known gap (measured on this seed: y MAE 8.9 mm, z mean +9.4 mm): centre_offset half_width takes
  // the axis-aligned box's smaller side, which overestimates the width of a potato lying at an
  // angle, so z is too far; the 5 mm target is not met yet. These bounds only guard the present state.
  EXPECT_LT(r.ev.y.mae_mm, 12);
  EXPECT_LT(r.ev.z.mae_mm, 12);
}

// The measurement behind docs (held-out seeds 1001..1000+N, no test uses them):
//   CROPSIGHT_POTATO_SEEDS=5 build/bin/test_pipeline --gtest_also_run_disabled_tests \
//     --gtest_filter='PotatoEval.DISABLED_Measure*'
TEST(PotatoEval, DISABLED_MeasureHeldOutApproaches) {
  const char* env = std::getenv("CROPSIGHT_POTATO_SEEDS");
  const int n = env ? std::atoi(env) : 3;
  cropsight::testing::TempDir dir;
  for (const auto scene : {sim::PotatoScene::sheet, sim::PotatoScene::room, sim::PotatoScene::chamber})
    for (int s = 0; s < n; ++s) {
      sim::PotatoSimConfig cfg;
      cfg.scene = scene;
      const auto seq = dir / ("seq" + std::to_string(int(scene)) + "_" + std::to_string(s));
      sim::simulate_potato_sequence(cfg, 1001 + std::uint64_t(s), 40, seq, false);
      for (const auto kind :
           {tracking::VisualTrackerKind::csrt, tracking::VisualTrackerKind::kcf, tracking::VisualTrackerKind::mil}) {
        const RunResult r = harvest(seq, kind, 0.3, 77 + std::uint64_t(s));
        std::cout << "scene=" << config_name(scene) << " seed=" << 1001 + s << " tracker=" << config_name(kind)
                  << " mae_mm=" << r.ev.x.mae_mm << "," << r.ev.y.mae_mm << "," << r.ev.z.mae_mm
                  << " mean_mm=" << r.ev.x.mean_mm << "," << r.ev.y.mean_mm << "," << r.ev.z.mean_mm
                  << " switches=" << r.ev.target_switches << " lost=" << r.ev.lost_events
                  << " with_target=" << r.ev.frames_with_target << "/" << r.ev.frames
                  << " matched=" << r.ev.frames_matched << " ms_per_frame=" << r.ms_per_frame << "\n";
      }
    }
}
