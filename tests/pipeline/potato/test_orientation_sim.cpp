// Orientation on simulated approaches: the simulator's truth angle of each potato that is
// fully in view, boxes from the labels, each segmentation with PCA on the colour image and on the
// colourised depth (io::colorize_depth over 0.2-1.0 m, as pipeline::potato::Pipeline::orient). The measurement
// behind docs/pipelines/potatoes.md, on held-out seeds 3001..3000+N that no test or tuning used:
//   CROPSIGHT_POTATO_SEEDS=3 build/bin/test_pipeline --gtest_also_run_disabled_tests
//     --gtest_filter='OrientationSim.DISABLED_*'
#include <gtest/gtest.h>

#include <array>
#include <tuple>

#include <cstdio>
#include <cstdlib>
#include <map>
#include <numbers>
#include <string>

#include "cropsight/eval/orientation_eval.hpp"
#include "cropsight/io/depth_colormap.hpp"
#include "cropsight/io/sequence.hpp"
#include "cropsight/measure/orientation.hpp"
#include "cropsight/measure/position.hpp"
#include "cropsight/pipeline/potato/truth.hpp"
#include "cropsight/sim/potato/potato_sim.hpp"
#include "testing/testing.hpp"

namespace cropsight {
namespace {

TEST(OrientationSim, DISABLED_MeasureHeldOutApproaches) {
  const char* env = std::getenv("CROPSIGHT_POTATO_SEEDS");
  const int n = env ? std::atoi(env) : 2;
  cropsight::testing::TempDir dir;
  using M = measure::OrientationSegmentation;
  using I = measure::OrientationInput;
  std::map<std::string, std::pair<double, int>> mae;  // "scene input segmentation" -> (sum, count)
  for (const auto scene : {sim::PotatoScene::sheet, sim::PotatoScene::room, sim::PotatoScene::chamber})
    for (int s = 0; s < n; ++s) {
      sim::PotatoSimConfig cfg;
      cfg.scene = scene;
      const auto seq = dir / (std::string(config_name(scene)) + std::to_string(s));
      sim::simulate_potato_sequence(cfg, 3001 + std::uint64_t(s), 12, seq, false);
      io::SequenceReader reader(seq);
      for (int i = 0; i < reader.size(); i += 2) {
        const RgbdFrame f = reader.read(i);
        const Image<float> depth = measure::depth_in_metres(f.depth, f.camera.depth_scale);
        const ColorImage colour_depth = io::colorize_depth(depth, 0.2f, 1.0f);
        for (const auto& p :
             pipeline::potato::frame_truth(reader.groundtruth(), *f.camera_position, f.camera, f.labels)) {
          // Fully in view, and long enough that the axis is defined (width / length <= 0.85).
          if (p.visible_pixels < 1500 || p.box.x1 < 2 || p.box.y1 < 2 || p.box.x2 > f.color.width - 2 ||
              p.box.y2 > f.color.height - 2 || p.width_m > 0.85 * p.length_m)
            continue;
          // `ours` three times: as configured, with the mask part nearest the box centre alone, and
          // without the no-depth fill.
          const measure::OrientationConfig defaults;
          const std::array<std::tuple<M, double, double, const char*>, 5> variants{
              {{M::canny, 0.0, 0.0, "canny"},
               {M::kmeans, 0.0, 0.0, "kmeans"},
               {M::ours, defaults.ours_part_fraction, defaults.ours_no_depth_fill_fraction, "ours"},
               {M::ours, 0.0, defaults.ours_no_depth_fill_fraction, "ours-nearest-part"},
               {M::ours, defaults.ours_part_fraction, 0.0, "ours-no-depth-fill"}}};
          for (I in : {I::depth, I::rgb})
            for (const auto& [seg, part_fraction, fill, name] : variants) {
              measure::OrientationConfig oc;
              oc.input = in;
              oc.segmentation = seg;
              oc.ours_part_fraction = part_fraction;
              oc.ours_no_depth_fill_fraction = fill;
              const auto r = measure::estimate_orientation(in == I::depth ? colour_depth : f.color, p.box, oc);
              const double e = r.ok ? eval::axis_angle_error_deg(p.angle_rad * 180 / std::numbers::pi,
                                                                 r.angle_rad * 180 / std::numbers::pi)
                                    : 90.0;
              for (const std::string& k : {std::string(config_name(scene)), std::string("all")}) {
                auto& m = mae[k + " " + config_name(in) + " " + std::string(name)];
                m.first += e;
                ++m.second;
              }
            }
        }
      }
    }
  for (const auto& [k, m] : mae) std::printf("%-22s n=%3d MAE %5.1f deg\n", k.c_str(), m.second, m.first / m.second);
}

}  // namespace
}  // namespace cropsight
