#include "cropsight/report/frame_overlays.hpp"

#include <algorithm>
#include <cstdio>
#include <opencv2/imgproc.hpp>

#include "cropsight/report/render.hpp"
#include "stereo/cv_convert.hpp"

namespace cropsight::report {

namespace {

// Half the picture, half the colour: the scene stays readable under the mark.
void tint(Rgb8& p, Rgb8 c) {
  p = Rgb8{std::uint8_t((p.r + c.r) / 2), std::uint8_t((p.g + c.g) / 2), std::uint8_t((p.b + c.b) / 2)};
}

cv::Scalar scalar(Rgb8 c) { return {double(c.r), double(c.g), double(c.b)}; }

void box(cv::Mat& m, const Box2D& b, Rgb8 c, int thickness = 2) {
  cv::rectangle(m, cv::Point(b.x, b.y), cv::Point(b.x + b.width - 1, b.y + b.height - 1), scalar(c), thickness);
}

// The dataset's labels: 1 grape, 2 peduncle, 3 leaf, 4 background, 5 noise, 0 unlabelled.
Rgb8 grape_label_color(int label) {
  switch (label) {
    case 1:
      return {150, 40, 200};
    case 2:
      return {250, 160, 30};
    case 3:
      return {40, 200, 60};
    default:
      return {150, 150, 150};
  }
}

}  // namespace

ColorImage broccoli_frame_overlay(const RgbdFrame& frame, const pipeline::broccoli::FrameResult& result) {
  const bool colour =
      !frame.color.empty() && frame.color.width == frame.depth.width && frame.color.height == frame.depth.height;
  ColorImage img = colour ? frame.color : depth_colormap(frame.depth, frame.camera.depth_scale);
  const std::size_t n = img.data.size();
  for (const auto& p : result.predicted)
    for (int i : p.indices)
      if (i >= 0 && std::size_t(i) < n) tint(img.data[std::size_t(i)], {255, 0, 255});
  for (const Detection& d : result.detections)
    for (int i : d.indices)
      if (i >= 0 && std::size_t(i) < n) tint(img.data[std::size_t(i)], {0, 255, 0});
  cv::Mat m = stereo::detail::view(img);  // a view: drawing writes into img
  for (const Detection& d : result.detections) box(m, d.box, {0, 255, 0}, 1);
  return img;
}

ColorImage grape_frame_overlay(const ColorImage& color, const CameraIntrinsics& camera,
                               const pipeline::grape::FrameResult& result) {
  ColorImage img = color;
  for (const auto& b : result.bunches)
    for (std::size_t i = 0; i < b.cloud.size(); ++i) {
      const Eigen::Vector2f uv = camera.project(b.cloud.points[i]);
      const int u = int(uv.x()), v = int(uv.y());
      if (u < 0 || v < 0 || u >= img.width || v >= img.height) continue;
      tint(img.data[std::size_t(v) * std::size_t(img.width) + std::size_t(u)],
           grape_label_color(i < b.cloud.labels.size() ? b.cloud.labels[i] : 0));
    }
  cv::Mat m = stereo::detail::view(img);
  for (const auto& d : result.detections) box(m, d.box, d.category == 2 ? Rgb8{250, 160, 30} : Rgb8{220, 40, 220});
  for (const auto& b : result.bunches) {
    box(m, Box2D{b.roi.x - 2, b.roi.y - 2, b.roi.width + 4, b.roi.height + 4}, {40, 220, 40}, 1);
    if (!b.cut_point) continue;
    const Eigen::Vector2f c = camera.project(b.cut_point->position);
    const Eigen::Vector2f tip = camera.project(b.cut_point->position + 0.03f * b.cut_point->direction);
    cv::drawMarker(m, cv::Point(int(c.x()), int(c.y())), cv::Scalar(255, 255, 255), cv::MARKER_CROSS, 14, 2);
    cv::line(m, cv::Point(int(c.x()), int(c.y())), cv::Point(int(tip.x()), int(tip.y())), cv::Scalar(255, 255, 255), 2);
  }
  return img;
}

ColorImage detection_overlay(const ColorImage& image, const std::vector<Detection2D>& detections,
                             const std::vector<std::string>& class_names) {
  ColorImage img = image;
  cv::Mat m = stereo::detail::view(img);
  for (const Detection2D& d : detections) {
    const Rgb8 c = label_color(std::uint32_t(d.class_id + 1));
    const cv::Point a(int(d.x1), int(d.y1)), b(int(d.x2) - 1, int(d.y2) - 1);
    cv::rectangle(m, a, b, scalar(c), 2);
    const std::string name =
        d.class_id >= 0 && std::size_t(d.class_id) < class_names.size() ? class_names[std::size_t(d.class_id)] : "?";
    char text[64];
    std::snprintf(text, sizeof text, "%s %.2f", name.c_str(), double(d.score));
    cv::putText(m, text, {a.x, std::max(12, a.y - 3)}, cv::FONT_HERSHEY_SIMPLEX, 0.45, scalar(c), 1);
  }
  return img;
}

}  // namespace cropsight::report
