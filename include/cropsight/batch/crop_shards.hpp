#pragma once
// What a batch does per crop: how a recording is opened and counted, how the pipeline spec is
// checked before submission, and what one shard writes. Every crop goes through its own
// make_pipeline (pipeline/<crop>/make_pipeline.hpp); nothing here assembles a config.
//
//   crop      recording                          shard output (DIR/shards/NAME/)
//   broccoli  RGB-D sequence folder              field-map.csv  heads kept by the seam rule (plan.hpp)
//   potato    RGB-D sequence folder (colour)     targets.csv    one harvest message a frame
//   grape     RGB-D sequence folder (colour)     bunches.csv    one row a bunch: box, points, cut point
//   seedling  stereo data set folder             seedlings.csv  one row a pair: found, envelope, area
//             (rig.yaml + pair_* folders, as `simulate seedling` writes it)
//
// Potato, grape and seedling shards write the rows of their OWNED frames only; the frames of the
// overlap before a range warm up the potato tracker (grape and seedling judge each frame alone).
// Grape needs boxes: from the pipeline's 2D detector (pipeline.detector in the manifest) or, when
// none is given, from the recording's detections.json (COCO, image_id = frame index, as
// `detect objects --coco` writes it).
#include <filesystem>
#include <string>

#include "cropsight/batch/plan.hpp"
#include "cropsight/pipeline/pipeline_spec.hpp"

namespace cropsight::batch {

/// What a shard counted, for its shard.json.
struct ShardCounts {
  int frames = 0;       ///< frames (pairs) processed, overlaps included
  long detections = 0;  ///< detections over those frames (seedling: pairs with a seedling found)
  int items = 0;        ///< broccoli heads kept, potato targets selected, grape bunches, seedlings found
};

/// The crops a batch can run: broccoli, potato, grape, seedling.
bool batch_supports_crop(const std::string& crop);

/// The file each shard of `crop` writes (the table above).
std::string shard_output_file(const std::string& crop);

/// Frames (pairs) of `recording` as `crop`'s shards read it; opening it checks its layout.
/// Throws Error naming the recording's file that is wrong.
int recording_frames(const std::string& crop, const std::filesystem::path& recording);

/// Builds `crop`'s pipeline once from `spec`, as every shard will: an unknown preset, model or
/// --set key fails here. Grape without a detector needs every recording's detections.json
/// (`recordings` are checked for it). Throws Error.
void check_crop_pipeline(const std::string& crop, const pipeline::PipelineSpec& spec,
                         const std::vector<std::filesystem::path>& recordings);

/// Runs `shard` with `crop`'s pipeline and writes its output file into `folder` (which exists).
/// Throws Error naming the recording's file or the model.
ShardCounts run_crop_shard(const std::string& crop, const pipeline::PipelineSpec& spec, const Shard& shard,
                           const std::filesystem::path& folder);

}  // namespace cropsight::batch
