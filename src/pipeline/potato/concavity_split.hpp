#pragma once
// Splits a blob of touching or overlapping potatoes along cuts between concavities of its outline
// (private to the classical detector; OpenCV types stay in the .cpp).
//
// Why concavities and not the distance transform: two potatoes that touch along a wide edge leave
// no neck in the distance transform (the contact line is as deep as either potato's core), but
// their outline still has a deep notch where the two convex outlines meet. A single potato is
// convex up to small notches (eyes, sprouts, a string's attachment). So: a blob splits only when
// its outline has a notch deeper than `depth_fraction` x its inscribed radius (scale-free); the
// cut runs from that notch to the outline point that leaves the two parts most convex (area-weighted
// solidity), and is kept only when the parts are more convex than the whole, each is nearly convex
// itself (`min_part_solidity`) and holds at least `min_part_fraction` of it. Parts are split
// again, up to `max_depth` levels.
#include <vector>

namespace cv {
class Mat;
}

namespace cropsight::pipeline::potato::detail {

struct SplitRule {
  double depth_fraction = 0.5;      ///< notch depth / inscribed radius that splits; <= 0 = never
  double min_part_fraction = 0.15;  ///< area of the smaller part / the blob's
  double min_part_solidity = 0.9;   ///< area / convex hull area of each part
  int max_depth = 2;                ///< levels of splitting; <= 0 = never
};

/// `blob`: 8-bit mask of one connected component (non-zero inside). Appends to `parts` one mask
/// per part (blob-sized, 255 inside). Returns the number of parts; 1 means no split and `parts`
/// gets nothing (the caller keeps the blob).
int split_at_concavities(const cv::Mat& blob, const SplitRule& rule, std::vector<cv::Mat>& parts);

}  // namespace cropsight::pipeline::potato::detail
