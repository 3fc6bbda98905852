// Potato ground truth from a sequence's files (see truth.hpp).
#include "cropsight/pipeline/potato/truth.hpp"

#include <algorithm>
#include <cmath>

#include "cropsight/core/error.hpp"
#include "cropsight/tracking/field_transform.hpp"

namespace cropsight::pipeline::potato {

std::vector<FrameTruth> frame_truth(const io::GroundTruth& truth, const Eigen::Vector3d& camera_position,
                                    const CameraIntrinsics& camera, const LabelImage& labels) {
  // The sequence format's nadir convention, spelled as the temporal filter's camera_to_field.
  const Eigen::Matrix3d R = tracking::FieldTransform::parse("y,x,-z", "potato truth").rotation.transpose();
  std::vector<FrameTruth> out;
  for (const auto& t : truth.instances) {
    FrameTruth p;
    p.id = t.id;
    auto extra = [&](const char* k) {
      const auto it = t.extra.find(k);
      return it == t.extra.end() ? 0.0 : it->second;
    };
    p.target = extra("target") > 0.5;
    p.centre_world = t.position;
    p.centre_camera = R * (t.position - camera_position);
    p.length_m = extra("length_m");
    p.width_m = extra("width_m");
    const Eigen::Vector3d axis = R * Eigen::Vector3d(extra("axis_x"), extra("axis_y"), extra("axis_z"));
    if (p.centre_camera.z() > 0) {
      const Eigen::Vector3d a = p.centre_camera - 0.5 * p.length_m * axis,
                            b = p.centre_camera + 0.5 * p.length_m * axis;
      const Eigen::Vector2f pa = camera.project(a.cast<float>()), pb = camera.project(b.cast<float>());
      // Image y points down: counter-clockwise on screen is -dv.
      double ang = std::atan2(-(pb.y() - pa.y()), pb.x() - pa.x());
      ang = std::fmod(ang + 2 * M_PI, M_PI);
      p.angle_rad = ang >= M_PI ? 0.0 : ang;
    }
    int u0 = labels.width, v0 = labels.height, u1 = -1, v1 = -1;
    for (int v = 0; v < labels.height; ++v)
      for (int u = 0; u < labels.width; ++u)
        if (labels.at(u, v) == t.id) {
          u0 = std::min(u0, u), u1 = std::max(u1, u), v0 = std::min(v0, v), v1 = std::max(v1, v);
          ++p.visible_pixels;
        }
    if (p.visible_pixels > 0) p.box = {float(u0), float(v0), float(u1 + 1), float(v1 + 1), 0, 1.f};
    out.push_back(p);
  }
  return out;
}

void require_truth(const io::SequenceReader& reader, const std::filesystem::path& seq) {
  if (reader.groundtruth().instances.empty())
    throw Error((seq / "groundtruth.json").string(), "missing or without instances (not a simulated potato sequence)");
  if (!reader.info().has_poses) throw Error((seq / "poses.csv").string(), "missing (not a simulated sequence)");
  if (!reader.info().has_labels) throw Error((seq / "labels").string(), "missing (not a simulated sequence)");
}

std::vector<FrameTruth> frame_truth(const io::SequenceReader& reader, const RgbdFrame& f,
                                    const std::filesystem::path& seq) {
  if (!f.camera_position) throw Error((seq / "poses.csv").string(), "no pose for frame " + std::to_string(f.index));
  return frame_truth(reader.groundtruth(), *f.camera_position, f.camera, f.labels);
}

TruthSequence read_truth_sequence(const std::filesystem::path& seq) {
  const io::SequenceReader reader(seq);
  require_truth(reader, seq);
  if (!reader.info().has_color) throw Error((seq / "color").string(), "missing (the trackers follow the colour image)");
  TruthSequence out;
  for (int i = 0; i < reader.size(); ++i) {
    RgbdFrame f = reader.read(i);
    out.truth.push_back(frame_truth(reader, f, seq));
    out.colour.push_back(std::move(f.color));
  }
  return out;
}

}  // namespace cropsight::pipeline::potato
