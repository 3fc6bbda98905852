// OpenCV trackers behind VisualTracker (CSRT and KCF from opencv_contrib's tracking module, MIL
// from the video module).
#include "cropsight/tracking/visual_tracker.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/tracking.hpp>
#include <opencv2/video/tracking.hpp>

#include "cropsight/core/error.hpp"

namespace cropsight::tracking {
namespace {

cv::Mat view(const ColorImage& im) { return cv::Mat(im.height, im.width, CV_8UC3, const_cast<Rgb8*>(im.data.data())); }

class OpenCvTracker final : public VisualTracker {
 public:
  OpenCvTracker(VisualTrackerKind kind, const CsrtParams& csrt) : kind_(kind), csrt_(csrt) {}

  void init(const ColorImage& image, const Detection2D& box) override {
    tracker_ = create();
    class_id_ = box.class_id;
    score_ = box.score;
    // Integer rectangle covering the continuous box, at least 2 x 2 and inside the image.
    const int x1 = std::clamp(int(std::floor(box.x1)), 0, image.width - 2);
    const int y1 = std::clamp(int(std::floor(box.y1)), 0, image.height - 2);
    const int x2 = std::clamp(int(std::ceil(box.x2)), x1 + 2, image.width);
    const int y2 = std::clamp(int(std::ceil(box.y2)), y1 + 2, image.height);
    tracker_->init(view(image), cv::Rect(x1, y1, x2 - x1, y2 - y1));
  }

  std::optional<Detection2D> update(const ColorImage& image) override {
    if (!tracker_) return std::nullopt;
    cv::Rect r;
    if (!tracker_->update(view(image), r)) return std::nullopt;
    Detection2D d;
    d.x1 = float(std::max(0, r.x));
    d.y1 = float(std::max(0, r.y));
    d.x2 = float(std::min(image.width, r.x + r.width));
    d.y2 = float(std::min(image.height, r.y + r.height));
    d.class_id = class_id_;
    d.score = score_;
    if (d.area() <= 0) return std::nullopt;
    return d;
  }

 private:
  cv::Ptr<cv::Tracker> create() const {
    switch (kind_) {
      case VisualTrackerKind::kcf:
        return cv::TrackerKCF::create();
      case VisualTrackerKind::mil:
        return cv::TrackerMIL::create();
      default: {
        cv::TrackerCSRT::Params p;
        p.template_size = float(csrt_.template_size);
        p.number_of_scales = csrt_.scales;
        p.use_segmentation = csrt_.segmentation;
        p.admm_iterations = csrt_.admm_iterations;
        return cv::TrackerCSRT::create(p);
      }
    }
  }
  VisualTrackerKind kind_;
  CsrtParams csrt_;
  cv::Ptr<cv::Tracker> tracker_;
  int class_id_ = 0;
  float score_ = 0;
};

}  // namespace

std::unique_ptr<VisualTracker> make_visual_tracker(VisualTrackerKind kind, const CsrtParams& csrt) {
  if (kind == VisualTrackerKind::none) return nullptr;
  if (csrt.template_size < 16 || csrt.scales < 1 || csrt.admm_iterations < 1)
    throw Error("visual tracker", "CSRT needs template_size >= 16, scales >= 1 and admm_iterations >= 1");
  return std::make_unique<OpenCvTracker>(kind, csrt);
}

}  // namespace cropsight::tracking
