// One frame's broccoli detections (and, with --track, its heads' sizes and tracks) as the JSON
// line of `detect broccoli`; nothing is computed here.
#include "broccoli_cli.hpp"

namespace cropsight::cli {

namespace {
nlohmann::json num_or_null(double v, bool valid) { return valid ? json_number(v) : nlohmann::json(nullptr); }
}  // namespace

nlohmann::json detection_json(const Detection& d, int id) {
  return {{"id", id},
          {"score", d.score},
          {"centroid", {d.centroid.x(), d.centroid.y(), d.centroid.z()}},
          {"box", {d.box.x, d.box.y, d.box.width, d.box.height}},
          {"points", d.indices.size()}};
}

// --track: each head's size and track id, the heads the frame missed (tracking.predict_missed:
// where the filter expects them; their tracks may still fail to reach the map, compare track_id
// with --map) and the camera estimate.
void add_tracking_json(const pipeline::broccoli::FrameResult& r, const tracking::HeadMapper& mapper,
                       nlohmann::json& line) {
  nlohmann::json heads = nlohmann::json::array();
  const auto& measured = mapper.detections();
  const std::size_t first = measured.size() - r.detections.size();
  for (std::size_t k = 0; k < r.detections.size(); ++k) {
    const auto& m = measured[first + k];
    heads.push_back({{"id", int(k) + 1},
                     {"track_id", m.track_id},
                     {"diameter_mm", num_or_null(m.size.diameter_mm, m.size.valid)},
                     {"bbox_mm", num_or_null(m.size.bbox_mm, m.size.valid)},
                     {"hull_mm", num_or_null(m.size.hull_mm, m.size.valid)},
                     {"harvestable", m.size.harvestable},
                     {"field", {m.field_position.x(), m.field_position.y(), m.field_position.z()}}});
  }
  line["heads"] = std::move(heads);
  nlohmann::json predicted = nlohmann::json::array();
  for (const auto& p : r.predicted)
    predicted.push_back({{"track_id", p.track_id},
                         {"points", p.indices.size()},
                         {"centroid", {p.centroid.x(), p.centroid.y(), p.centroid.z()}}});
  line["predicted"] = std::move(predicted);
  const auto& c = r.association.camera_position;
  line["camera_estimate"] = {c.x(), c.y(), c.z()};
}

}  // namespace cropsight::cli
