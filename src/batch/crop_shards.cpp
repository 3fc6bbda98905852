// Per-crop shards of a batch (batch/crop_shards.hpp).
#include "cropsight/batch/crop_shards.hpp"

#include <map>

#include "crop_rows.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"
#include "cropsight/io/sequence.hpp"
#include "cropsight/pipeline/broccoli/make_pipeline.hpp"
#include "cropsight/pipeline/grape/make_pipeline.hpp"
#include "cropsight/pipeline/grape/roi.hpp"
#include "cropsight/pipeline/potato/make_pipeline.hpp"
#include "cropsight/pipeline/seedling/make_pipeline.hpp"
#include "cropsight/pipeline/seedling/truth.hpp"
#include "cropsight/tracking/field_map_io.hpp"

namespace cropsight::batch {

namespace fs = std::filesystem;

namespace {

bool owned(const Shard& s, int frame) { return frame >= s.own_first && frame < s.own_end; }

// The recording, opened once by the shard, still holds the frames the plan counted.
void check_planned(const Shard& shard, int frames) {
  if (shard.end_frame > frames)
    throw Error(shard.sequence.string(), "has " + std::to_string(frames) + " frames, the plan expected " +
                                             std::to_string(shard.end_frame) + " (re-plan with a new --out)");
}

ShardCounts run_broccoli(const pipeline::PipelineSpec& spec, const Shard& shard, const fs::path& folder) {
  const auto pipe = pipeline::broccoli::make_pipeline(spec);
  const io::SequenceReader reader(shard.sequence);
  check_planned(shard, reader.size());
  ShardCounts c;
  for (int i = shard.first_frame; i < shard.end_frame; ++i, ++c.frames)
    c.detections += long(pipe->process(reader.read(i)).detections.size());
  std::vector<tracking::TrackedHead> kept;
  for (const auto& h : pipe->finish())
    if (owned(shard, h.first_frame)) kept.push_back(h);
  c.items = int(kept.size());
  tracking::write_field_map(folder / shard_output_file("broccoli"), kept);
  return c;
}

ShardCounts run_potato(const pipeline::PipelineSpec& spec, const Shard& shard, const fs::path& folder) {
  const auto pipe = pipeline::potato::make_pipeline(spec);
  const io::SequenceReader reader(shard.sequence);
  check_planned(shard, reader.size());
  ShardCounts c;
  std::string csv = detail::potato_header();
  int last_target = 0;
  for (int i = shard.first_frame; i < shard.end_frame; ++i, ++c.frames) {
    const auto r = pipe->process(reader.read(i));
    if (!owned(shard, i)) continue;  // the leading overlap only warms up the tracker
    c.detections += long(r.detections.size());
    csv += detail::potato_row(r);
    if (r.target.target_id != 0 && r.target.target_id != last_target) ++c.items;
    last_target = r.target.target_id;
  }
  io::write_file_atomic(folder / shard_output_file("potato"), csv);
  return c;
}

// Boxes from the detector, or from the recording's detections.json (read once: image_id = frame).
ShardCounts run_grape(const pipeline::PipelineSpec& spec, const Shard& shard, const fs::path& folder) {
  const auto pipe = pipeline::grape::make_pipeline(spec);
  const io::SequenceReader reader(shard.sequence);
  check_planned(shard, reader.size());
  std::map<long, std::vector<pipeline::grape::Detection>> boxes;
  if (!pipe->has_detector()) boxes = pipeline::grape::read_coco_detections_by_image(shard.sequence / "detections.json");
  ShardCounts c;
  std::string csv = detail::grape_header();
  for (int i = shard.own_first; i < shard.own_end; ++i, ++c.frames) {  // frames are judged alone
    const RgbdFrame frame = reader.read(i);
    const auto r = pipe->has_detector() ? pipe->process(frame) : pipe->process(frame, boxes[i]);
    c.detections += long(r.detections.size());
    c.items += int(r.bunches.size());
    csv += detail::grape_rows(i, r, pipe->config().cut_point.peduncle_label);
  }
  io::write_file_atomic(folder / shard_output_file("grape"), csv);
  return c;
}

ShardCounts run_seedling(const pipeline::PipelineSpec& spec, const Shard& shard, const fs::path& folder) {
  const auto pipe = pipeline::seedling::make_pipeline(spec);
  const auto data = pipeline::seedling::open_dataset(shard.sequence);
  check_planned(shard, int(data.pairs.size()));
  ShardCounts c;
  std::string csv = detail::seedling_header();
  for (int i = shard.own_first; i < shard.own_end; ++i, ++c.frames) {  // pairs are judged alone
    const fs::path& pair = data.pairs.at(std::size_t(i));
    const auto [left, right] = pipeline::seedling::read_pair(pair);
    const auto r = pipe->process(left, right, data.geometry, pair.string());
    c.detections += r.found;
    c.items += r.found;
    csv += detail::seedling_row(i, pair.filename().string(), r);
  }
  io::write_file_atomic(folder / shard_output_file("seedling"), csv);
  return c;
}

}  // namespace

bool batch_supports_crop(const std::string& crop) {
  return crop == "broccoli" || crop == "potato" || crop == "grape" || crop == "seedling";
}

std::string shard_output_file(const std::string& crop) {
  if (crop == "broccoli") return "field-map.csv";
  if (crop == "potato") return "targets.csv";
  if (crop == "grape") return "bunches.csv";
  if (crop == "seedling") return "seedlings.csv";
  throw Error("batch", "unknown crop '" + crop + "' (broccoli, potato, grape or seedling)");
}

int recording_frames(const std::string& crop, const fs::path& recording) {
  if (crop == "seedling") return int(pipeline::seedling::open_dataset(recording).pairs.size());
  return io::SequenceReader(recording).size();
}

void check_crop_pipeline(const std::string& crop, const pipeline::PipelineSpec& spec,
                         const std::vector<fs::path>& recordings) {
  if (crop == "broccoli") pipeline::broccoli::make_pipeline(spec);
  if (crop == "potato") pipeline::potato::make_pipeline(spec);
  if (crop == "seedling") pipeline::seedling::make_pipeline(spec);
  if (crop != "grape") return;
  if (pipeline::grape::make_pipeline(spec)->has_detector()) return;
  for (const fs::path& r : recordings) {
    const fs::path boxes = r / "detections.json";
    std::error_code ec;
    if (!fs::is_regular_file(boxes, ec))
      throw Error(boxes.string(), "missing: a grape batch without pipeline.detector reads each recording's boxes here");
    pipeline::grape::read_coco_detections(boxes);  // parses it whole: a bad file fails before submission
  }
}

ShardCounts run_crop_shard(const std::string& crop, const pipeline::PipelineSpec& spec, const Shard& shard,
                           const fs::path& folder) {
  if (crop == "broccoli") return run_broccoli(spec, shard, folder);
  if (crop == "potato") return run_potato(spec, shard, folder);
  if (crop == "grape") return run_grape(spec, shard, folder);
  if (crop == "seedling") return run_seedling(spec, shard, folder);
  throw Error("batch", "unknown crop '" + crop + "'");
}

}  // namespace cropsight::batch
