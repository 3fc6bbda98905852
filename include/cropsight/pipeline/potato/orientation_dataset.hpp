#pragma once
// The paper's orientation test set (Table 4.3) and its evaluation: folders
// `<rgb dir>/<angle>_<light>_rgb/imageN.png` with their colourised depth in
// `<depth dir>/<angle>_<light>_depth/imageM.png` (M = N or N ± 1: the two cameras' shots are
// numbered in turn). As in the paper, the box comes from a detector run on the RGB image and is
// used for both inputs.
#include <filesystem>
#include <string>
#include <vector>

#include "cropsight/core/detection2d.hpp"
#include "cropsight/eval/orientation_eval.hpp"
#include "cropsight/measure/orientation.hpp"

namespace cropsight::pipeline::potato {

/// One RGB shot and its colourised depth.
struct OrientationShot {
  std::filesystem::path rgb, depth;
  double angle_deg = 0;  ///< true axis angle, trigonometric, degrees (from the folder name)
  std::string light;     ///< from the folder name ("high", "low")
  int number = 0;        ///< N of the RGB file name
  /// Which potato: the shared set's rule (README), numbers up to 13 are potato 1, the rest potato 2.
  int potato = 0;
};

/// Every shot under the two folders, sorted by angle, light, number. Throws Error naming the folder
/// or file when a folder is missing, holds no shot, or an RGB shot has no depth partner.
std::vector<OrientationShot> list_orientation_shots(const std::filesystem::path& rgb_dir,
                                                    const std::filesystem::path& depth_dir);

/// Runs `detector` on each RGB image, keeps its highest-scoring box, and measures the orientation
/// on the RGB or the depth image (cfg.input) inside it. A shot without a box or without a mask is a
/// failure (90° error). Times the orientation step only (ms per potato). Throws Error naming the
/// file for an unreadable image or a depth image of another size than its RGB image.
eval::OrientationEvaluation evaluate_orientation(const std::vector<OrientationShot>& shots, Detector2D& detector,
                                                 const measure::OrientationConfig& cfg);

/// A stand-in box source for these images while the potato detector is being written: the
/// thickest blob of colour on the white board. Chroma distance (Lab a*, b*) from the image's median
/// chroma (the board's, which covers most of the image) above `chroma_threshold`; an elliptic
/// closing of `closing_px` (bridges a string that crosses the potato and cuts its blob in two) and
/// an opening of `opening_px` (removes strings); then the blob holding the largest inscribed disc
/// (radius r; strings and knots are thin), opened once more by a disc of diameter r so that strings
/// still touching it fall off, grown back by r / 4 inside the foreground → one box, score 1. Not a
/// general detector: it assumes one potato on a white or grey background.
class BoardBlobDetector : public Detector2D {
 public:
  explicit BoardBlobDetector(double chroma_threshold = 12, int opening_px = 15, int closing_px = 9)
      : chroma_threshold_(chroma_threshold), opening_px_(opening_px), closing_px_(closing_px) {}
  std::vector<Detection2D> detect(const DetectorInput& in) override;
  std::vector<std::string> class_names() const override { return {"potato"}; }

 private:
  double chroma_threshold_;
  int opening_px_, closing_px_;
};

}  // namespace cropsight::pipeline::potato
