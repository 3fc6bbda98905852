#pragma once
// What `cropsight info` prints and the report page tabulates about a sequence. Computing it
// reads (and so validates) every frame.
#include <vector>

#include "cropsight/io/sequence.hpp"

namespace cropsight::report {

struct SequenceSummary {
  io::SequenceInfo info;
  int instances = 0;                          ///< ground-truth instances in groundtruth.json (0 when absent)
  double valid_depth_fraction = 0.0;          ///< mean over frames of (pixels with depth != 0) / pixels
  std::vector<double> valid_depth_per_frame;  ///< same fraction, per frame
  double labelled_fraction = 0.0;  ///< mean over frames of (pixels with label != 0) / pixels; 0 without labels
  std::vector<int> visible_instances_per_frame;  ///< distinct label ids per frame; empty without labels
  double depth_min_m = 0.0, depth_max_m = 0.0;   ///< over all valid pixels of all frames (0 when none)
};

/// Reads every frame of `reader` (throwing the reader's Error naming the first bad file).
SequenceSummary summarize_sequence(const io::SequenceReader& reader);

}  // namespace cropsight::report
