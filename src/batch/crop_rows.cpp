// CSV rows of potato, grape and seedling shards (crop_rows.hpp).
#include "crop_rows.hpp"

#include "cropsight/pipeline/grape/truth.hpp"
#include "cropsight/tracking/target_state.hpp"
#include "fixed_text.hpp"

namespace cropsight::batch::detail {

namespace {

std::string join(std::initializer_list<std::string> fields) {
  std::string out;
  for (const std::string& f : fields) out += (out.empty() ? "" : ",") + f;
  return out + "\n";
}

std::string flag(bool b) { return b ? "1" : "0"; }

}  // namespace

std::string potato_header() {
  return "frame,timestamp_s,detections,detection,depth_ok,x_m,y_m,z_m,height_m,width_m,angle_rad,angle_ok,cut,"
         "target_id,state,score,box_x1,box_y1,box_x2,box_y2\n";
}

std::string potato_row(const pipeline::potato::FrameResult& r) {
  const auto& t = r.target;
  const auto box = [&](float v) { return t.detection ? fixed(v, 1) : std::string(); };
  return join({std::to_string(t.frame),
               fixed(t.timestamp, 6),
               std::to_string(r.detections.size()),
               flag(t.detection),
               flag(t.depth_ok),
               fixed(t.x, 4),
               fixed(t.y, 4),
               fixed(t.z, 4),
               fixed(t.height, 4),
               fixed(t.width, 4),
               fixed(t.angle, 4),
               flag(t.angle_ok),
               flag(t.cut),
               std::to_string(t.target_id),
               config_names(t.state)[std::size_t(t.state)],
               fixed(t.score, 4),
               box(t.box.x1),
               box(t.box.y1),
               box(t.box.x2),
               box(t.box.y2)});
}

std::string grape_header() {
  return "frame,bunch,roi_x,roi_y,roi_width,roi_height,points,peduncle_points,cut,cut_x_m,cut_y_m,cut_z_m,"
         "cut_confidence\n";
}

std::string grape_rows(int frame, const pipeline::grape::FrameResult& r, int peduncle_label) {
  std::string out;
  for (std::size_t i = 0; i < r.bunches.size(); ++i) {
    const auto& b = r.bunches[i];
    const auto counts = pipeline::grape::label_counts(b.cloud);
    const long peduncle =
        peduncle_label >= 0 && std::size_t(peduncle_label) < counts.size() ? counts[std::size_t(peduncle_label)] : 0;
    const auto& c = b.cut_point;
    out += join({std::to_string(frame), std::to_string(i), std::to_string(b.roi.x), std::to_string(b.roi.y),
                 std::to_string(b.roi.width), std::to_string(b.roi.height), std::to_string(b.cloud.size()),
                 std::to_string(peduncle), flag(bool(c)), c ? fixed(c->position.x(), 4) : "",
                 c ? fixed(c->position.y(), 4) : "", c ? fixed(c->position.z(), 4) : "",
                 c ? std::to_string(c->confidence) : ""});
  }
  return out;
}

std::string seedling_header() {
  return "pair_index,pair,found,length_m,width_m,height_m,volume_m3,top_view_area_m2,points\n";
}

std::string seedling_row(int pair_index, const std::string& pair, const pipeline::seedling::FrameResult& r) {
  const auto& e = r.envelope;
  return join({std::to_string(pair_index), pair, flag(r.found), fixed(e.length, 4), fixed(e.width, 4),
               fixed(e.height, 4), fixed(e.volume(), 7), fixed(r.top_view.area(), 6), std::to_string(r.points.size())});
}

}  // namespace cropsight::batch::detail
