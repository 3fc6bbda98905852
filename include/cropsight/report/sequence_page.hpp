#pragma once
// The sequence part of the demo page: summary table, camera, ground truth, valid depth per
// frame, and depth / colour / label renders of a few evenly spaced frames. These are the page's
// data part (HtmlPage::Part::Data): result sections added to the same HtmlPage (e.g. the
// broccoli detections with --model, broccoli_report.hpp) are shown before them, in whichever
// order the two were added.
#include <vector>

#include "cropsight/io/sequence.hpp"
#include "cropsight/report/html_page.hpp"
#include "cropsight/report/sequence_summary.hpp"

namespace cropsight::report {

struct SequencePageOptions {
  int frames_shown = 4;           ///< evenly spaced frames rendered (first and last included)
  int max_instances_listed = 40;  ///< rows of the ground-truth table
  int min_display_width = 320;    ///< small frames are upscaled (nearest) to at least this width
};

/// `count` frame indices spread evenly over [0, frames-1], first and last included, no repeats.
std::vector<int> evenly_spaced_frames(int frames, int count);

/// Adds the sequence sections to `page`, in its data part.
void add_sequence_sections(HtmlPage& page, const io::SequenceReader& reader, const SequenceSummary& summary,
                           const SequencePageOptions& options = {});

}  // namespace cropsight::report
