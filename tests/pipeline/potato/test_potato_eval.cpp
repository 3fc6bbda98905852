// The harvest-run evaluator on scripted runs (switches, lost events, angle modulo 180) and end to
// end on a simulated approach: pipeline::potato::Pipeline with a ground-truth-box detector (boxes from the
// simulator's labels) through pipeline::potato::evaluate_potato_sequence, and with the preset's classical detector.
#include <gtest/gtest.h>

#include <cstdlib>
#include <iostream>

#include "cropsight/io/sequence.hpp"
#include "cropsight/pipeline/potato/eval.hpp"
#include "cropsight/sim/potato/potato_sim.hpp"
#include "testing/testing.hpp"

using namespace cropsight;
using namespace cropsight::pipeline::potato;

namespace {

pipeline::potato::FrameTruth potato_truth(int id, float cu, Eigen::Vector3d c) {
  pipeline::potato::FrameTruth t;
  t.id = id;
  t.box = {cu - 20, 100, cu + 20, 140, 0, 1};
  t.visible_pixels = 1600;
  t.centre_camera = c;
  t.length_m = 0.08;
  t.width_m = 0.05;
  t.angle_rad = 0.1;
  return t;
}

// A detector that returns the simulator's visible boxes of each frame in turn (potatoes with at
// least 50 visible pixels), so the loop's position and tracking are measured without detector errors.
class TruthBoxDetector final : public Detector2D {
 public:
  explicit TruthBoxDetector(const std::filesystem::path& seq) {
    const io::SequenceReader reader(seq);
    for (int i = 0; i < reader.size(); ++i) {
      const RgbdFrame f = reader.read(i);
      std::vector<Detection2D> boxes;
      for (const auto& t : pipeline::potato::frame_truth(reader.groundtruth(), *f.camera_position, f.camera, f.labels))
        if (t.visible_pixels >= 50) boxes.push_back(t.box);
      frames_.push_back(boxes);
    }
  }
  std::vector<Detection2D> detect(const DetectorInput&) override {
    return next_ < frames_.size() ? frames_[next_++] : std::vector<Detection2D>{};
  }
  std::vector<std::string> class_names() const override { return {"potato"}; }

 private:
  std::vector<std::vector<Detection2D>> frames_;
  std::size_t next_ = 0;
};

pipeline::potato::FrameResult frame(int id, const Detection2D& box, const Eigen::Vector3d& xyz) {
  pipeline::potato::FrameResult r;
  HarvestTarget& t = r.target;
  t.state = tracking::TargetState::detected;
  t.target_id = id;
  t.detection = true;
  t.box = box;
  t.depth_ok = true;
  t.x = float(xyz.x()) + 0.002f, t.y = float(xyz.y()) - 0.001f, t.z = float(xyz.z()) + 0.003f;
  t.width = 0.081f, t.height = 0.05f;
  t.angle = float(M_PI - 0.1);
  t.angle_ok = true;
  r.timer.add("detect", 2), r.timer.add("locate", 1), r.timer.add("track", 0.5), r.timer.add("orient", 3);
  return r;
}

}  // namespace

TEST(PotatoEval, AngleErrorIsModulo180) {
  EXPECT_NEAR(axis_angle_error(0.05, M_PI - 0.05), 0.1, 1e-12);
  EXPECT_NEAR(axis_angle_error(0.0, M_PI / 2), M_PI / 2, 1e-12);
  EXPECT_NEAR(axis_angle_error(1.0, 1.0 + M_PI), 0.0, 1e-12);
}

TEST(PotatoEval, ScriptedRunCountsSwitchesLossAndErrors) {
  const Eigen::Vector3d a(0, 0, 0.4), b(0.1, 0, 0.45);
  pipeline::potato::FrameTruth target = potato_truth(1, 100, a);
  target.target = true;
  std::vector<std::vector<pipeline::potato::FrameTruth>> truth(4, {target, potato_truth(2, 300, b)});
  std::vector<pipeline::potato::FrameResult> run;
  for (int f = 0; f < 3; ++f) run.push_back(frame(1, truth[0][f == 2 ? 1 : 0].box, f == 2 ? b : a));  // frame 2 jumps
  run[1].target.cut = true;  // the border cuts the box: its error goes to cut_*, not x, y, z
  run[1].target.x += 0.05f;
  run.emplace_back();
  run[3].target.state = tracking::TargetState::lost;
  const pipeline::potato::Figures ev = pipeline::potato::evaluate_potato_run(run, truth);
  EXPECT_EQ(ev.frames, 4);
  EXPECT_EQ(ev.frames_with_target, 3);
  EXPECT_EQ(ev.frames_on_target, 2);
  EXPECT_EQ(ev.target_switches, 1);
  EXPECT_EQ(ev.lost_events, 1);
  EXPECT_EQ(ev.frames_positioned, 2);
  EXPECT_EQ(ev.frames_cut, 1);
  EXPECT_NEAR(ev.cut_x.mean_mm, 52, 1e-3);
  EXPECT_NEAR(ev.x.mean_mm, 2, 1e-3);
  EXPECT_NEAR(ev.y.mae_mm, 1, 1e-3);
  EXPECT_NEAR(ev.z.std_mm, 0, 1e-3);
  EXPECT_NEAR(ev.length_mae_mm, 1, 1e-3);
  EXPECT_NEAR(ev.angle_mae_deg, 0.2 * 180 / M_PI, 1e-4);
  EXPECT_EQ(ev.angles_full_view, ev.angles - 1);  // frame 1's box is cut by the border
  EXPECT_NEAR(ev.angle_mae_full_view_deg, 0.2 * 180 / M_PI, 1e-4);
  const pipeline::potato::StageTimes ms = stage_times(run);
  EXPECT_NEAR(ms.detect, 1.5, 1e-9);  // three frames of 2 ms, one of 0
  EXPECT_NEAR(ms.total, 4.875, 1e-9);
  EXPECT_NEAR(ms.max_total, 6.5, 1e-9);
  run.pop_back();
  EXPECT_THROW(pipeline::potato::evaluate_potato_run(run, truth), Error);
}

TEST(PotatoEval, SimulatedApproachWithGroundTruthBoxes) {
  cropsight::testing::TempDir dir;
  sim::PotatoSimConfig cfg;
  cfg.width = 320;
  cfg.height = 240;
  sim::simulate_potato_sequence(cfg, 11, 10, dir / "seq", false);
  pipeline::potato::Pipeline pipeline(pipeline::potato::load_config("potato"),
                                      std::make_unique<TruthBoxDetector>(dir / "seq"));
  const pipeline::potato::SequenceEvaluation r = pipeline::potato::evaluate_potato_sequence(pipeline, dir / "seq");
  const pipeline::potato::Figures& ev = r.figures;
  ASSERT_EQ(r.run.size(), 10u);
  EXPECT_EQ(ev.target_switches, 0);
  EXPECT_EQ(ev.frames_with_target, 10);
  EXPECT_EQ(ev.targets, 1);  // potato 4 of this seed, nearer than the one the camera approaches
  // Potato 4 is cut by the image border in frames 0-1 (right) and 7-9 (bottom): x, y, z are
  // scored on the frames in full view.
  EXPECT_EQ(ev.frames_positioned + ev.frames_cut, 10);
  EXPECT_GE(ev.frames_positioned, 5);
  EXPECT_LT(ev.x.mae_mm, 5);
  EXPECT_LT(ev.y.mae_mm, 5);
  EXPECT_LT(ev.z.mae_mm, 5);
  EXPECT_GT(r.ms.total, 0);
}

TEST(PotatoEval, SequenceWithoutSimulatorTruthIsAnErrorNamingTheFile) {
  cropsight::testing::TempDir dir;
  sim::PotatoSimConfig cfg;
  cfg.width = 160;
  cfg.height = 120;
  sim::simulate_potato_sequence(cfg, 11, 1, dir / "seq", false);
  std::filesystem::remove(dir / "seq" / "poses.csv");
  pipeline::potato::Pipeline pipeline(pipeline::potato::load_config("potato"));
  try {
    pipeline::potato::evaluate_potato_sequence(pipeline, dir / "seq");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("poses.csv"), std::string::npos) << e.what();
  }
}
