// The --overlay pictures of the detect commands (report/frame_overlays.hpp): marks where the
// results are, the scene left readable elsewhere, the right base image.
#include <gtest/gtest.h>

#include "cropsight/report/frame_overlays.hpp"
#include "cropsight/report/render.hpp"

namespace frame_overlays_test {
using namespace cropsight;

RgbdFrame flat_frame(bool with_colour) {
  RgbdFrame f;
  f.depth = DepthImage(40, 30, std::uint16_t(900));
  f.camera.width = 40;
  f.camera.height = 30;
  f.camera.fx = f.camera.fy = 50;
  f.camera.cx = 20;
  f.camera.cy = 15;
  f.camera.depth_scale = 0.001;
  if (with_colour) f.color = ColorImage(40, 30, Rgb8{100, 100, 100});
  return f;
}

TEST(FrameOverlays, BroccoliHeadsAreTintedOnColourOrOnTheDepthMap) {
  pipeline::broccoli::FrameResult r;
  Detection head;
  head.indices = {40 * 10 + 10, 40 * 10 + 11};
  head.box = Box2D{8, 8, 6, 6};
  r.detections = {head};
  tracking::PredictedHead predicted;
  predicted.indices = {40 * 25 + 30};
  r.predicted = {predicted};
  const ColorImage on_colour = report::broccoli_frame_overlay(flat_frame(true), r);
  const Rgb8 h = on_colour.at(10, 10), p = on_colour.at(30, 25), far = on_colour.at(35, 2);
  EXPECT_GT(h.g, h.r + 50);  // green head
  EXPECT_GT(p.r, p.g + 50);  // magenta prediction
  EXPECT_GT(p.b, p.g + 50);
  EXPECT_EQ(far.r, 100);  // untouched elsewhere: the colour image itself
  EXPECT_EQ(far.g, 100);
  // Without colour, the depth colour map of render.hpp is the base.
  const RgbdFrame depth_only = flat_frame(false);
  const ColorImage on_depth = report::broccoli_frame_overlay(depth_only, r);
  const ColorImage map = report::depth_colormap(depth_only.depth, depth_only.camera.depth_scale);
  EXPECT_EQ(on_depth.at(35, 2).r, map.at(35, 2).r);
  EXPECT_EQ(on_depth.at(35, 2).b, map.at(35, 2).b);
  // An index outside the image (a malformed result) is skipped, not written out of bounds.
  r.detections[0].indices.push_back(40 * 30 + 5);
  EXPECT_NO_THROW(report::broccoli_frame_overlay(depth_only, r));
}

TEST(FrameOverlays, GrapePointsLandWhereTheCameraSeesThem) {
  const RgbdFrame f = flat_frame(true);
  pipeline::grape::FrameResult r;
  pipeline::grape::Bunch b;
  b.roi = Box2D{5, 5, 20, 20};
  b.cloud.points = {f.camera.deproject(12.5f, 9.5f, 0.8f)};  // pixel (12, 9)
  b.cloud.labels = {2};                                      // peduncle: orange
  r.bunches = {b};
  const ColorImage img = report::grape_frame_overlay(f.color, f.camera, r);
  const Rgb8 p = img.at(12, 9);
  EXPECT_GT(p.r, p.b + 40);
  EXPECT_EQ(img.at(38, 28).r, 100);  // outside every mark
}

TEST(FrameOverlays, DetectorBoxesAreDrawn) {
  const ColorImage image(60, 40, Rgb8{0, 0, 0});
  Detection2D d;
  d.x1 = 10, d.y1 = 12, d.x2 = 30, d.y2 = 32, d.class_id = 0, d.score = 0.9f;
  const ColorImage img = report::detection_overlay(image, {d}, {"bunch"});
  const Rgb8 edge = img.at(20, 31), inside = img.at(20, 22);
  EXPECT_GT(int(edge.r) + edge.g + edge.b, 100);  // the box's bottom edge
  EXPECT_EQ(int(inside.r) + inside.g + inside.b, 0);
}

}  // namespace frame_overlays_test
