#include "cropsight/pipeline/seedling/pipeline.hpp"

#include <algorithm>
#include <utility>

#include "cropsight/core/error.hpp"
#include "cropsight/geometry/grid_sampling.hpp"
#include "cropsight/pipeline/seedling/steps.hpp"
#include "cropsight/stereo/disparity.hpp"
#include "cropsight/stereo/reconstruct.hpp"

namespace cropsight::pipeline::seedling {

namespace {

// Fewer reconstructed points than this cannot hold a soil plane and a plant: nothing is found.
constexpr std::size_t kMinReconstructedPoints = 100;

// The right image's size is checked by compute_disparity().
void check_size(const ColorImage& left, const stereo::RectifiedGeometry& geo, const std::string& where) {
  if (left.width != geo.width || left.height != geo.height)
    throw Error(where, "image size " + std::to_string(left.width) + "x" + std::to_string(left.height) +
                           " differs from the calibration's " + std::to_string(geo.width) + "x" +
                           std::to_string(geo.height));
}

template <class T>
std::vector<T> pick(const std::vector<T>& v, const std::vector<int>& idx) {
  std::vector<T> out;
  out.reserve(idx.size());
  for (int i : idx) out.push_back(v[std::size_t(i)]);
  return out;
}

// The detection's outputs from the dense plant: points, pixels, image mask, top view, envelope.
void set_dense_result(FrameResult& r, DensePlant plant, const stereo::StereoPoints& sp, const SoilPlane& pl) {
  std::vector<Eigen::Vector3d> dense;
  dense.reserve(plant.indices.size());
  for (int i : plant.indices) {
    r.points.push_back(sp.points[i]);
    r.pixels.push_back(sp.pixels[i]);
    r.image_mask.data[std::size_t(sp.pixels[i])] = 255;
    dense.push_back(sp.points[i].cast<double>());
  }
  r.top_view = std::move(plant.top_view);
  r.envelope = measure::envelope_box(dense, pl.n, pl.d);
  r.found = !dense.empty();
}

}  // namespace

Pipeline::Pipeline(Config config, const std::string& where) : cfg_(std::move(config)) { cfg_.validate(where); }

Pipeline Pipeline::from_preset(const std::string& preset) { return Pipeline(load_config(preset), preset); }

// The paper's steps, one call each; a step that leaves too little to go on ends the detection
// with found = false and the counts reached so far.
FrameResult Pipeline::process(const ColorImage& left, const ColorImage& right, const stereo::RectifiedGeometry& geo,
                              const std::string& where) const {
  check_size(left, geo, where);
  FrameResult r;
  r.image_mask = GrayImage(left.width, left.height, 0);
  auto stage = [&r](const char* name) { return r.timer.scope(name); };

  stereo::DisparityImage disp;
  stereo::StereoPoints sp;
  {
    auto s = stage("disparity");
    disp = stereo::compute_disparity(left, right, cfg_.disparity, where);
  }
  {
    auto s = stage("reconstruct");
    sp = stereo::reconstruct(disp, geo, cfg_.min_depth, cfg_.max_depth);
  }
  r.points_total = int(sp.points.size());
  if (sp.points.size() < kMinReconstructedPoints) return r;

  SoilPlane plane;
  std::vector<float> height;
  std::vector<int> cand;  // indices into sp
  {
    auto s = stage("plane");
    plane = fit_soil_plane(sp.points, cfg_, where);
    height = heights_above(sp.points, plane);
    cand = select_candidates(sp, height, left, cfg_);
  }
  r.plane_normal = plane.n;
  r.plane_d = plane.d;
  r.points_candidates = int(cand.size());
  if (int(cand.size()) < std::max(cfg_.gmm.components, cfg_.min_component_points)) return r;

  std::vector<int> sampled;  // indices into sp
  {
    auto s = stage("sample");
    sampled = pick(cand, geometry::sample_exact(pick(sp.points, cand), cfg_.sampling));
    r.sampled = pick(sp.points, sampled);
  }
  r.points_sampled = int(r.sampled.size());
  {
    auto s = stage("gmm");
    r.gmm = segmentation::fit_gmm(r.sampled, cfg_.gmm, where);
  }
  std::vector<Eigen::Vector3f> kept;
  {
    auto s = stage("recognise");
    r.chosen_components = select_components(r.sampled, pick(height, sampled), r.gmm, cfg_);
    kept = points_of_components(r.sampled, r.gmm.labels, r.chosen_components);
  }
  if (r.chosen_components.empty()) return r;
  {
    auto s = stage("outlier");
    kept = remove_outliers(kept, cfg_);
  }
  r.points_seedling_sampled = int(kept.size());
  if (kept.empty()) return r;
  {
    auto s = stage("output");
    set_dense_result(r, densify_top_view(kept, sp, cand, plane, cfg_), sp, plane);
  }
  return r;
}

}  // namespace cropsight::pipeline::seedling
