#include "cropsight/bridge/seedling_runner.hpp"

#include "cropsight/core/error.hpp"
#include "cropsight/pipeline/seedling/config.hpp"
#include "cropsight/pipeline/seedling/make_pipeline.hpp"
#include "cropsight/pipeline/seedling/pipeline.hpp"
#include "cropsight/stereo/calibration.hpp"
#include "cropsight/stereo/rectification.hpp"
#include "cropsight/stereo/stereo_io.hpp"
#include "frame_conversion.hpp"

namespace cropsight::bridge {

namespace {

ColorImage to_color(const RgbImage& im, const std::string& where) {
  if (im.rgb.size() != 3 * std::size_t(im.width) * std::size_t(im.height))
    throw Error(where, "colour buffer does not hold width x height x 3 bytes");
  return color_from_rgb(im.rgb, im.width, im.height);
}

RgbImage to_rgb(const ColorImage& c) { return {c.width, c.height, rgb_from_color(c)}; }

}  // namespace

struct SeedlingRunner::Impl {
  pipeline::seedling::Pipeline pipe;
};

SeedlingRunner::SeedlingRunner(const std::string& preset, const std::vector<std::string>& sets)
    : impl_(std::make_unique<Impl>(Impl{std::move(*pipeline::seedling::make_pipeline({preset, sets}))})) {}
SeedlingRunner::~SeedlingRunner() = default;

pipeline::seedling::FrameResult SeedlingRunner::process(const RgbImage& left, const RgbImage& right,
                                                        const StereoGeometry& g, const std::string& where) const {
  stereo::RectifiedGeometry geo;
  geo.width = g.width;
  geo.height = g.height;
  geo.f = g.f;
  geo.cx = g.cx;
  geo.cy = g.cy;
  geo.cx_right = g.cx_right;
  geo.baseline = g.baseline;
  if (!(g.f > 0) || !(g.baseline > 0)) throw Error(where, "stereo geometry needs a focal length and a baseline > 0");
  return impl_->pipe.process(to_color(left, where), to_color(right, where), geo, where);
}

RectifiedPairBuffers read_rectified_pair(const std::string& calib_yaml, const std::string& left_png,
                                         const std::string& right_png) {
  const auto calib = stereo::load_calibration(calib_yaml);
  auto [l, r] = stereo::read_color_pair(left_png, right_png);
  if (l.width != calib.width || l.height != calib.height)
    throw Error(left_png, "image size differs from the calibration " + calib_yaml);
  const auto pair = stereo::rectify_pair(calib, std::move(l), std::move(r), left_png);
  RectifiedPairBuffers out;
  out.left = to_rgb(pair.left);
  out.right = to_rgb(pair.right);
  out.geometry = {pair.geometry.width, pair.geometry.height,   pair.geometry.f,       pair.geometry.cx,
                  pair.geometry.cy,    pair.geometry.cx_right, pair.geometry.baseline};
  return out;
}

}  // namespace cropsight::bridge
