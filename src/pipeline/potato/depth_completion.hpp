#pragma once
// Completes a colour blob's box over the depth surface it lies on (private to the classical
// detector; OpenCV types stay in the .cpp files).
//
// Why: the colour model finds the lit part of a potato; its shaded underside, a dark end in the
// root chamber, or the part beyond a root's shadow fall outside it, and the box is then half a
// potato (simulated dev approaches: IoU 0.3-0.6 with the potato on some targets), which moves the
// 3D centre and the angle. The depth sees the whole potato as one smooth surface in front of the
// backdrop. So the box grows over the pixels connected to the blob's (8-neighbours, each step at
// most `step_m` in depth, all within `band_m` of the blob's median depth, none in another blob),
// up to `grow` of the box's sides beyond it; an opening as wide as half the region's width (its
// largest inscribed radius; at least the detector's kernel) then removes the strings and roots that
// touch the potato at its depth, which near the camera are wider than the detector's opening. The box only grows, and
// not at all when the surface runs on to the limit on two sides or more (a wall at the potato's depth).
#include "cropsight/core/detection2d.hpp"
#include "cropsight/core/image.hpp"

namespace cv {
class Mat;
}

namespace cropsight::pipeline::potato::detail {

struct DepthCompletionRule {
  double grow = 0;                ///< fraction of the box's width / height it may reach beyond each side; <= 0 = off
  double band_m = 0.05;           ///< m; completed pixels lie within this of the blob's median depth
  double step_m = 0.01;           ///< m; largest depth step between neighbouring completed pixels
  int min_depth_px = 20;          ///< fewer blob pixels with depth: the box stays as it is
  double opening_fraction = 1.0;  ///< opening diameter / the region's largest inscribed radius (roots near the camera)
};

/// `box`: the part's box (image pixels); `part`: its mask (8-bit, non-zero inside) in the ROI at
/// (roi_x, roi_y); `depth_m`: metres, 0 = none, the image's size; `labels`: CV_32S blob labels of
/// the image (0 = background), `own`: the part's blob; `opening`: the detector's opening kernel
/// (may be empty). Returns the completed box (a superset of `box`).
Detection2D complete_by_depth(const Detection2D& box, const cv::Mat& part, int roi_x, int roi_y,
                              const Image<float>& depth_m, const cv::Mat& labels, int own, const cv::Mat& opening,
                              const DepthCompletionRule& rule);

}  // namespace cropsight::pipeline::potato::detail
