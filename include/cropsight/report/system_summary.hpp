#pragma once
// The opening of one system's chapter on the demo page: the result picture first, then the few
// figures the run measured, a note on what they are (and are not), and the commands that
// reproduce them. Every system's chapter opens the same way, so a reader compares like with like.
#include <string>
#include <utility>
#include <vector>

#include "cropsight/report/html_page.hpp"

namespace cropsight::report {

struct SystemSummary {
  std::string picture_svg;           ///< inline SVG markup (svg_overlay.hpp); shown when not empty
  std::vector<Figure> picture_pngs;  ///< else these images, in a row
  std::string caption;               ///< what the picture shows (colours, marks)
  /// The measured figures, 2-4: (what, value with its unit), e.g. ("AP50, visible heads", "0.907").
  std::vector<std::pair<std::string, std::string>> figures;
  std::string note;                   ///< what the figures are measured on; shown when not empty
  std::vector<std::string> commands;  ///< command lines that reproduce the run, in order
};

/// Adds `summary` to the page's current chapter or section: picture, caption, figures, note,
/// commands. Throws Error("system summary", ...) when it has no picture.
void add_system_summary(HtmlPage& page, const SystemSummary& summary);

}  // namespace cropsight::report
