// write_grape_sim: the simulated cloud in the dataset's text format and the simulator's truth.
#include <nlohmann/json.hpp>

#include "cropsight/io/files.hpp"
#include "cropsight/io/grape_text.hpp"
#include "cropsight/sim/grape/grape_sim.hpp"

namespace cropsight::sim {

namespace {
nlohmann::json vec(const Eigen::Vector3f& v) { return {v.x(), v.y(), v.z()}; }
}  // namespace

void write_grape_sim(const std::filesystem::path& dir, const GrapeSimCloud& sim) {
  io::write_grape_text(dir / "cloud.txt", sim.cloud);
  const GrapeSimTruth& t = sim.truth;
  nlohmann::json j = {
      {"seed", t.seed},
      {"cloud", "cloud.txt"},
      {"points", sim.cloud.size()},
      // p_camera = R (p * scale_m + centroid_m): the dataset frame's inverse (grape_sim.hpp).
      {"frame", "dataset: camera frame turned 180 degrees about x (x right, y up, z toward the camera)"},
      {"to_camera_rotation", {{1, 0, 0}, {0, -1, 0}, {0, 0, -1}}},
      {"centroid_m", vec(sim.centroid)},
      {"scale_m", sim.scale},
      {"distance_m", t.distance_m},
      {"berries", t.berries},
      {"leaves", t.leaves},
      {"roi_px", {t.roi_width, t.roi_height}},
      {"label_counts", t.label_counts},
      {"cut_point",
       {{"position_m", vec(t.cut_point_m)},
        {"direction", vec(t.peduncle_axis)},
        {"peduncle_points", t.peduncle_points}}},
  };
  io::write_file_atomic(dir / "truth.json", j.dump(2) + "\n");
}

}  // namespace cropsight::sim
