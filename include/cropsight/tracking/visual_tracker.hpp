#pragma once
// A single-object visual tracker that follows a box from frame to frame on the colour image: the
// potato paper's dlib correlation tracker (§3.4) is replaced by one of OpenCV's trackers, chosen
// by a measurement on simulated approaches (docs/pipelines/potatoes.md). The interface lets the
// target tracker's state machine be tested with a scripted tracker.
#include <array>
#include <memory>
#include <optional>

#include "cropsight/core/detection2d.hpp"
#include "cropsight/core/image.hpp"

namespace cropsight::tracking {

/// OpenCV trackers: CSRT (discriminative correlation filter with channel and spatial
/// reliability; the closest relative of dlib's DSST correlation tracker), KCF (kernelised
/// correlation filter), MIL (multiple-instance learning); none = no visual tracking.
enum class VisualTrackerKind { csrt, kcf, mil, none };
constexpr std::array<const char*, 4> config_names(VisualTrackerKind) { return {"csrt", "kcf", "mil", "none"}; }

class VisualTracker {
 public:
  virtual ~VisualTracker() = default;
  /// Starts following `box` (pixels, continuous, see Detection2D) in `image`.
  virtual void init(const ColorImage& image, const Detection2D& box) = 0;
  /// The box in the next frame, clipped to the image; nullopt when the tracker lost it.
  virtual std::optional<Detection2D> update(const ColorImage& image) = 0;
};

/// CSRT's cost per frame is set by its template (the padded box resized to about this many pixels
/// a side) and by the scales its scale filter tries, not by the box's size in the image.
struct CsrtParams {
  int template_size = 200;   ///< px; OpenCV's default
  int scales = 33;           ///< scale-filter scales; OpenCV's default
  bool segmentation = true;  ///< colour-histogram mask of the filter (OpenCV's default: on)
  int admm_iterations = 4;   ///< iterations of the filter's ADMM solve per frame; OpenCV's default
};

/// An OpenCV tracker of `kind`; nullptr for VisualTrackerKind::none. `csrt` applies to CSRT only.
std::unique_ptr<VisualTracker> make_visual_tracker(VisualTrackerKind kind, const CsrtParams& csrt = {});

}  // namespace cropsight::tracking
