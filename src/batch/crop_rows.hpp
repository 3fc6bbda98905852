#pragma once
// The CSV rows potato, grape and seedling shards write (crop_shards.hpp): one header line, then
// one line a frame (potato), a bunch (grape) or a pair (seedling), fixed digits so that equal
// results give equal bytes whichever engine ran the shard. Units: metres, radians, seconds.
#include <string>

#include "cropsight/pipeline/grape/frame_result.hpp"
#include "cropsight/pipeline/potato/frame_result.hpp"
#include "cropsight/pipeline/seedling/frame_result.hpp"

namespace cropsight::batch::detail {

std::string potato_header();
std::string potato_row(const pipeline::potato::FrameResult& r);

std::string grape_header();
/// `peduncle_label`: the segmenter label counted as peduncle points (the pipeline's cut_point config).
std::string grape_rows(int frame, const pipeline::grape::FrameResult& r, int peduncle_label);

std::string seedling_header();
std::string seedling_row(int pair_index, const std::string& pair, const pipeline::seedling::FrameResult& r);

}  // namespace cropsight::batch::detail
