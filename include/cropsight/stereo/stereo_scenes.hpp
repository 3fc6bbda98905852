#pragma once
// Stereo scenes with ground truth from any folder (eval stereo --scenes). Two layouts:
//   scene folder:      left.png, right.png, gt.png | gt.pgm (8- or 16-bit) | gt.pfm, scene.yaml
//                      (gt_scale: stored value per pixel of disparity; max_disparity: the search
//                      range in pixels); optional right-view truth gt_right.{png,pgm,pfm}.
//   Middlebury 2014:   im0.png, im1.png, disp0GT.pfm (or disp0.pfm), calib.txt (ndisp = search
//                      range); optional disp1GT.pfm / disp1.pfm (right view) or mask0nocc.png
//                      (255 = non-occluded).
// Disparities are in pixels of the images as stored (x_left - x_right); 0, infinity and NaN in a
// ground truth mean "unknown". Where a right-view truth exists, the non-occluded mask is the
// left-right consistency of the two truths (nonoccluded_mask, 1 px).
#include <filesystem>
#include <vector>

#include "cropsight/stereo/middlebury.hpp"

namespace cropsight::stereo {

/// True when `dir` holds one of the two layouts above (the files that must exist).
bool is_stereo_scene(const std::filesystem::path& dir);

/// The scene in `dir` (name = the folder's name). num_disparities = the scene's range rounded up
/// to a multiple of 16, capped at the image width rounded down to 16 and at kMaxDisparities;
/// max_disparity = the largest true disparity. Throws Error(file, ...) naming the file for a
/// missing or unreadable image, ground truth or scene file, a bad or missing gt_scale /
/// max_disparity / ndisp, or a ground truth whose size differs from the images or that has no
/// valid pixel.
MiddleburyPair load_stereo_scene(const std::filesystem::path& dir);

/// Every scene of `dir`: `dir` itself when it is one, else each subfolder that is one, in name
/// order (other subfolders are skipped). Throws Error(dir, ...) when `dir` is missing or holds
/// no scene, and what load_stereo_scene throws.
std::vector<MiddleburyPair> load_stereo_scenes(const std::filesystem::path& dir);

}  // namespace cropsight::stereo
