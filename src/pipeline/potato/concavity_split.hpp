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
// solidity), and is kept only when the parts are more convex than the whole and each holds at
// least `min_part_fraction` of it. Parts are split again, up to `max_depth` levels.
#include <vector>

namespace cv {
class Mat;
}

namespace cropsight::pipeline::potato::detail {

/// `blob`: 8-bit mask of one connected component (non-zero inside). Appends to `parts` one mask
/// per part (blob-sized, 255 inside). Returns the number of parts; 1 means no split and `parts`
/// gets nothing (the caller keeps the blob). depth_fraction <= 0 or max_depth <= 0: never splits.
int split_at_concavities(const cv::Mat& blob, double depth_fraction, double min_part_fraction, int max_depth,
                         std::vector<cv::Mat>& parts);

}  // namespace cropsight::pipeline::potato::detail
